// The viewer's shaders: a colour-mapped, Lambert + ambient lit surface and the tool path on top;
// or, while a verified program is shown, a grey surface and the program's path coloured by its
// deviation from the design.
// `fn colormap` is prepended at run time from colormap::wgsl(), so the legend and the shader
// share one colour scale. Model coordinates are mm with Z the optical axis; the world is the
// model moved to the part centre with Z scaled by the vertical exaggeration.

struct Uniforms {
    view_proj: mat4x4<f32>,
    // xyz: eye position (world); w: how far path points move towards the eye (world units).
    eye: vec4<f32>,
    // xyz: unit vector towards the light (world).
    light: vec4<f32>,
    // xyz: part centre (model, mm); w: vertical exaggeration.
    centre: vec4<f32>,
    // x: z_min (mm); y: 1 / (z_max - z_min), 0 for a flat range.
    range: vec4<f32>,
    // The path's colour.
    path_color: vec4<f32>,
    // x: the deviation at the bottom of the colour scale (nm); y: 1 / (top - bottom), 0 for a
    // flat range; z: 1 while a program's deviation is shown (the surface grey), else 0.
    deviation: vec4<f32>,
};

@group(0) @binding(0) var<uniform> u: Uniforms;

fn to_world(p: vec3<f32>) -> vec3<f32> {
    let d = p - u.centre.xyz;
    return vec3<f32>(d.x, d.y, d.z * u.centre.w);
}

struct SurfaceOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) t: f32,
};

@vertex
fn vs_surface(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> SurfaceOut {
    var out: SurfaceOut;
    out.clip = u.view_proj * vec4<f32>(to_world(position), 1.0);
    // Normals transform with the inverse transpose of diag(1, 1, e).
    out.normal = vec3<f32>(normal.xy, normal.z / u.centre.w);
    out.t = (position.z - u.range.x) * u.range.y;
    return out;
}

@fragment
fn fs_surface(in: SurfaceOut) -> @location(0) vec4<f32> {
    // Two-sided Lambert, so the part seen from below is lit too.
    let lambert = abs(dot(normalize(in.normal), u.light.xyz));
    let base = mix(colormap(in.t), vec3<f32>(0.6, 0.6, 0.6), u.deviation.z);
    return vec4<f32>(base * (0.35 + 0.65 * lambert), 1.0);
}

// A path point moved a little towards the eye, which keeps it in front of the surface it lies on.
fn path_clip(position: vec3<f32>) -> vec4<f32> {
    let w = to_world(position);
    let lifted = w + normalize(u.eye.xyz - w) * u.eye.w;
    return u.view_proj * vec4<f32>(lifted, 1.0);
}

@vertex
fn vs_path(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return path_clip(position);
}

@fragment
fn fs_path() -> @location(0) vec4<f32> {
    return u.path_color;
}

struct DeviationOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) t: f32,
};

@vertex
fn vs_deviation(@location(0) position: vec3<f32>, @location(1) deviation_nm: f32) -> DeviationOut {
    var out: DeviationOut;
    out.clip = path_clip(position);
    out.t = (deviation_nm - u.deviation.x) * u.deviation.y;
    return out;
}

@fragment
fn fs_deviation(in: DeviationOut) -> @location(0) vec4<f32> {
    return vec4<f32>(colormap(in.t), 1.0);
}
