// The viewer's shaders: a colour-mapped, Lambert + ambient lit surface and the tool path on top.
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
    return vec4<f32>(colormap(in.t) * (0.35 + 0.65 * lambert), 1.0);
}

@vertex
fn vs_path(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    let w = to_world(position);
    // A small lift towards the eye keeps the path in front of the surface it lies on.
    let lifted = w + normalize(u.eye.xyz - w) * u.eye.w;
    return u.view_proj * vec4<f32>(lifted, 1.0);
}

@fragment
fn fs_path() -> @location(0) vec4<f32> {
    return u.path_color;
}
