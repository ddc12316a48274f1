//! The 3-D view on the page's canvas, drawn with wgpu: the surface as a lit, colour-mapped
//! triangle mesh ([`crate::colormap`], Lambert + ambient shading with a light fixed to the
//! camera) and the tool path as line segments on top, under an orbit camera ([`camera`]); or,
//! while a verified program is shown, the surface grey and the program's path as a line strip
//! coloured by its deviation from the design on the same colour scale. Optical
//! surfaces are nearly flat, so heights are exaggerated until their range is about 15 % of the
//! part diameter. The skeleton follows wgpu's examples (`examples/features/src/framework.rs`):
//! WebGPU when `navigator.gpu` yields an adapter, else WebGL2; the surface is created from the
//! canvas before the adapter is requested; `downlevel_webgl2_defaults()` limits; drawing buffer
//! = CSS size × devicePixelRatio, at least 1; reconfigure on Lost/Outdated. The device and the
//! pipelines are the page's, shared by its viewers on WebGPU ([`gpu`]).

use std::rc::Rc;

use glam::Vec3;
use wasm_bindgen::prelude::*;
use wgpu::util::DeviceExt;

use crate::camera::OrbitCamera;

mod gpu;
use gpu::Gpu;

/// Height range shown, as a fraction of the part diameter, once exaggerated.
const HEIGHT_FRACTION: f32 = 0.15;
/// How far the path is moved towards the eye, as a fraction of the scene radius.
const PATH_LIFT: f32 = 0.004;
/// Background, #1e1f24 (the framebuffer is not sRGB, so these are the sRGB values).
const CLEAR: wgpu::Color = wgpu::Color {
    r: 30.0 / 255.0,
    g: 31.0 / 255.0,
    b: 36.0 / 255.0,
    a: 1.0,
};
/// The path's colour: a warm red, apart from every colour of the viridis scale.
const PATH_COLOR: [f32; 4] = [1.0, 0.25, 0.3, 1.0];
/// Depth buffer format (renderable and multisampled on WebGPU and WebGL2).
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Size of the `Uniforms` struct in shader.wgsl: a mat4 and six vec4 (bytes).
const UNIFORM_SIZE: u64 = 64 + 6 * 16;

/// Little-endian bytes of a float slice, the layout GPU buffers expect.
fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Where the model sits in the world: the part centre goes to the origin and heights are
/// multiplied by `exaggeration`; the result lies within ±`extent`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Placement {
    centre: Vec3,
    exaggeration: f32,
    extent: Vec3,
    z_min: f32,
    inv_range: f32,
}

impl Placement {
    /// The placement for points `xyz` whose colour scale spans `z_min..z_max`; `None` when
    /// there is no finite point.
    fn new(xyz: &[f32], z_min: f32, z_max: f32) -> Option<Self> {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for p in xyz.chunks_exact(3) {
            let p = Vec3::new(p[0], p[1], p[2]);
            if p.is_finite() {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        if !lo.is_finite() {
            return None;
        }
        let range = z_max - z_min;
        let range_ok = range.is_finite() && range > 0.0;
        let (z_lo, z_hi) = if range_ok {
            (z_min, z_max)
        } else {
            (lo.z, hi.z)
        };
        let diameter = (hi.x - lo.x).max(hi.y - lo.y);
        let height = z_hi - z_lo;
        let exaggeration = if height > 0.0 && diameter > 0.0 {
            (HEIGHT_FRACTION * diameter / height).max(1.0)
        } else {
            1.0
        };
        let centre = Vec3::new(
            0.5 * (lo.x + hi.x),
            0.5 * (lo.y + hi.y),
            0.5 * (z_lo + z_hi),
        );
        let z_extent = (hi.z - centre.z).abs().max((lo.z - centre.z).abs()) * exaggeration;
        let extent = Vec3::new(0.5 * (hi.x - lo.x), 0.5 * (hi.y - lo.y), z_extent);
        Some(Self {
            centre,
            exaggeration,
            // A single point still gets a small box to look at.
            extent: extent.max(Vec3::splat(1e-3 * extent.max_element().max(1.0))),
            z_min: z_lo,
            inv_range: if height > 0.0 { 1.0 / height } else { 0.0 },
        })
    }
}

/// A GPU buffer destroyed when dropped. On the web, wgpu's handles give their GPU memory back
/// only when the garbage collector collects them; a re-planned part gives it back at once.
struct OwnedBuffer(wgpu::Buffer);

impl OwnedBuffer {
    /// A vertex or index buffer holding `contents`.
    fn new(device: &wgpu::Device, label: &str, contents: &[u8], usage: wgpu::BufferUsages) -> Self {
        OwnedBuffer(
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            }),
        )
    }
}

impl std::ops::Deref for OwnedBuffer {
    type Target = wgpu::Buffer;
    fn deref(&self) -> &wgpu::Buffer {
        &self.0
    }
}

impl Drop for OwnedBuffer {
    fn drop(&mut self) {
        self.0.destroy();
    }
}

/// Vertex and index buffers of the surface mesh.
struct Mesh {
    positions: OwnedBuffer,
    normals: OwnedBuffer,
    indices: OwnedBuffer,
    index_count: u32,
}

/// A verified program's path: positions and each point's deviation, and the colour scale's
/// range.
struct DeviationPath {
    positions: OwnedBuffer,
    deviations: OwnedBuffer,
    count: u32,
    lo_nm: f32,
    hi_nm: f32,
}

/// The drawing-buffer-sized attachments: depth and, with MSAA, the multisampled colour.
struct Targets {
    depth: OwnedTexture,
    msaa: Option<OwnedTexture>,
}

/// A texture and its view, the texture destroyed when dropped (see [`OwnedBuffer`]).
struct OwnedTexture {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

impl Drop for OwnedTexture {
    fn drop(&mut self) {
        self.texture.destroy();
    }
}

/// The 3-D view of a surface and its tool path on a canvas. A viewer freed (its element
/// removed from the page) gives its buffers and textures back at once, and with the last
/// viewer the page's WebGPU device ([`gpu`]).
#[wasm_bindgen]
pub struct Viewer {
    gpu: Rc<Gpu>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    targets: Targets,
    uniforms: OwnedBuffer,
    bind_group: wgpu::BindGroup,
    mesh: Option<Mesh>,
    path: Option<(OwnedBuffer, u32)>,
    /// A verified program's path, drawn instead of `path` while present.
    deviation_path: Option<DeviationPath>,
    /// Placement from the surface, else from the path.
    placement: Option<Placement>,
    path_placement: Option<Placement>,
    camera: OrbitCamera,
    css_height: f32,
    /// Whether the user moved the camera since the last reset (a resize then keeps the view).
    moved: bool,
}

#[wasm_bindgen]
impl Viewer {
    /// Creates a viewer on the canvas: WebGPU if the browser offers an adapter, else WebGL2;
    /// on WebGPU with the page's device where another viewer holds one.
    /// Errors (no backend at all) become a JS exception with a clear message.
    pub async fn create(canvas: web_sys::HtmlCanvasElement) -> Result<Viewer, JsError> {
        let (width, height) = (canvas.width().max(1), canvas.height().max(1));
        let (gpu, surface) = Gpu::for_canvas(canvas).await?;
        let config = gpu.configuration(&surface, width, height)?;
        surface.configure(&gpu.device, &config);
        let uniforms = OwnedBuffer(gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("viewer uniforms"),
            size: UNIFORM_SIZE,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        }));
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("viewer uniforms"),
            layout: &gpu.uniforms_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniforms.as_entire_binding(),
            }],
        });
        let targets = make_targets(&gpu.device, &config, gpu.sample_count);
        let mut viewer = Viewer {
            gpu,
            surface,
            config,
            targets,
            uniforms,
            bind_group,
            mesh: None,
            path: None,
            deviation_path: None,
            placement: None,
            path_placement: None,
            camera: OrbitCamera::default(),
            css_height: height as f32,
            moved: false,
        };
        viewer.camera.aspect = width as f32 / height as f32;
        viewer.reset_view();
        Ok(viewer)
    }

    /// How many GPU devices the page's viewers have opened: on WebGPU one serves them all.
    pub fn devices_opened() -> u32 {
        gpu::devices_opened()
    }

    /// "WebGPU" or "WebGL2": the backend actually in use.
    pub fn backend(&self) -> String {
        self.gpu.backend.to_string()
    }

    /// The surface mesh: positions xyz (mm), unit normals xyz, triangle indices; z_min/z_max
    /// (mm) the height range used for the colour scale (0 → bottom of the colormap, 1 → top).
    /// Inconsistent input (lengths, indices out of range) is reported on the console and
    /// clears the surface. A new part (other extent) resets the view.
    pub fn set_surface(
        &mut self,
        positions: &[f32],
        normals: &[f32],
        indices: &[u32],
        z_min: f64,
        z_max: f64,
    ) {
        self.mesh = None;
        let vertex_count = positions.len() / 3;
        let problem = if !positions.len().is_multiple_of(3) || normals.len() != positions.len() {
            Some(format!(
                "{} position and {} normal values (both must be the same multiple of 3)",
                positions.len(),
                normals.len()
            ))
        } else if !indices.len().is_multiple_of(3) {
            Some(format!(
                "{} indices (must be a multiple of 3)",
                indices.len()
            ))
        } else {
            indices
                .iter()
                .find(|&&i| i as usize >= vertex_count)
                .map(|i| format!("index {i} with only {vertex_count} vertices"))
        };
        if let Some(problem) = problem {
            web_sys::console::error_1(&format!("spiralcam viewer: set_surface: {problem}").into());
        } else if !indices.is_empty() {
            let buffer = |label, contents: &[u8], usage| {
                OwnedBuffer::new(&self.gpu.device, label, contents, usage)
            };
            let index_bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
            self.mesh = Some(Mesh {
                positions: buffer(
                    "surface positions",
                    &f32_bytes(positions),
                    wgpu::BufferUsages::VERTEX,
                ),
                normals: buffer(
                    "surface normals",
                    &f32_bytes(normals),
                    wgpu::BufferUsages::VERTEX,
                ),
                indices: buffer("surface indices", &index_bytes, wgpu::BufferUsages::INDEX),
                index_count: indices.len() as u32,
            });
        }
        let placement = match self.mesh {
            Some(_) => Placement::new(positions, z_min as f32, z_max as f32),
            None => None,
        };
        self.place(placement.or(self.path_placement));
    }

    /// The tool path as line segments, two xyz points (mm) each, lying on the surface; drawn
    /// on top in a contrasting colour.
    pub fn set_path(&mut self, xyz: &[f32]) {
        let count = xyz.len() / 6 * 2;
        self.path = (count >= 2).then(|| {
            let buffer = OwnedBuffer::new(
                &self.gpu.device,
                "path",
                &f32_bytes(&xyz[..3 * count]),
                wgpu::BufferUsages::VERTEX,
            );
            (buffer, count as u32)
        });
        // The path places the scene only while there is no surface.
        self.path_placement = Placement::new(&xyz[..3 * count], f32::NAN, f32::NAN);
        if self.mesh.is_none() {
            self.place(self.path_placement);
        }
    }

    /// A verified program's path, drawn instead of the planned path until cleared: `xyz` its
    /// points in order (mm, a line strip), `deviation_nm` each point's deviation from the
    /// design (nm), coloured on the height scale's colours from `lo_nm` (bottom) to `hi_nm`
    /// (top) while the surface is drawn grey. Fewer than two points, or lengths that disagree
    /// (reported on the console), go back to the planned path and the height colours. The
    /// placement stays the surface's.
    pub fn set_deviation_path(
        &mut self,
        xyz: &[f32],
        deviation_nm: &[f32],
        lo_nm: f64,
        hi_nm: f64,
    ) {
        self.deviation_path = None;
        let count = xyz.len() / 3;
        if xyz.len() != 3 * deviation_nm.len() {
            web_sys::console::error_1(
                &format!(
                    "spiralcam viewer: set_deviation_path: {} position values for {} deviations \
                     (three a point)",
                    xyz.len(),
                    deviation_nm.len()
                )
                .into(),
            );
            return;
        }
        if count < 2 {
            return;
        }
        let buffer = |label, values: &[f32]| {
            OwnedBuffer::new(
                &self.gpu.device,
                label,
                &f32_bytes(values),
                wgpu::BufferUsages::VERTEX,
            )
        };
        self.deviation_path = Some(DeviationPath {
            positions: buffer("program path", xyz),
            deviations: buffer("program deviation", deviation_nm),
            count: count as u32,
            lo_nm: lo_nm as f32,
            hi_nm: hi_nm as f32,
        });
    }

    /// Whether a verified program's path is shown (see [`Viewer::set_deviation_path`]).
    pub fn shows_deviation(&self) -> bool {
        self.deviation_path.is_some()
    }

    /// Orbits about the part centre by a drag of `dx`, `dy` CSS pixels.
    pub fn orbit(&mut self, dx: f32, dy: f32) {
        self.camera.orbit(dx, dy);
        self.moved = true;
    }

    /// Pans the view by a drag of `dx`, `dy` CSS pixels.
    pub fn pan(&mut self, dx: f32, dy: f32) {
        self.camera.pan(dx, dy, self.css_height);
        self.moved = true;
    }

    /// Zooms by `factor` (> 1 zooms in).
    pub fn zoom(&mut self, factor: f32) {
        self.camera.zoom(factor);
        self.moved = true;
    }

    /// Back to the default view (part seen from above at 35° elevation, fitted to the canvas).
    pub fn reset_view(&mut self) {
        self.camera.extent = self.placement.map_or(Vec3::ONE, |p| p.extent);
        self.camera.reset();
        self.moved = false;
    }

    /// New canvas size in CSS pixels and the devicePixelRatio; the drawing buffer is
    /// size × dpr, each at least 1 (and at most the device's texture limit).
    pub fn resize(&mut self, css_width: f32, css_height: f32, device_pixel_ratio: f32) {
        let max = self.gpu.device.limits().max_texture_dimension_2d;
        let dpr = if device_pixel_ratio.is_finite() && device_pixel_ratio > 0.0 {
            device_pixel_ratio
        } else {
            1.0
        };
        // `as u32` saturates: NaN and negatives become 0, hence the clamp to ≥ 1.
        let pixels = |css: f32| ((css * dpr).round() as u32).clamp(1, max);
        let (width, height) = (pixels(css_width), pixels(css_height));
        self.css_height = if css_height.is_finite() {
            css_height.max(1.0)
        } else {
            1.0
        };
        self.camera.aspect = width as f32 / height as f32;
        if !self.moved {
            self.reset_view();
        }
        if (width, height) != (self.config.width, self.config.height) {
            self.config.width = width;
            self.config.height = height;
            self.surface.configure(&self.gpu.device, &self.config);
            self.targets = make_targets(&self.gpu.device, &self.config, self.gpu.sample_count);
        }
    }

    /// Vertical exaggeration in use: heights are drawn this many times their true size.
    pub fn z_exaggeration(&self) -> f32 {
        self.placement.map_or(1.0, |p| p.exaggeration)
    }

    /// Draws one frame. Reconfigures the surface and retries on Lost/Outdated.
    pub fn render(&mut self) -> Result<(), JsError> {
        use wgpu::CurrentSurfaceTexture as Current;
        let frame = match self.surface.get_current_texture() {
            Current::Success(frame) | Current::Suboptimal(frame) => frame,
            Current::Timeout | Current::Occluded => return Ok(()),
            Current::Outdated | Current::Lost => {
                self.surface.configure(&self.gpu.device, &self.config);
                match self.surface.get_current_texture() {
                    Current::Success(frame) | Current::Suboptimal(frame) => frame,
                    Current::Timeout | Current::Occluded => return Ok(()),
                    other => {
                        return Err(JsError::new(&format!(
                            "3-D view: no canvas texture after reconfiguring ({other:?})"
                        )));
                    }
                }
            }
            Current::Validation => {
                return Err(JsError::new(
                    "3-D view: invalid canvas texture (validation error)",
                ));
            }
        };
        self.write_uniforms();
        let view = frame
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        let (target, resolve) = match &self.targets.msaa {
            Some(msaa) => (&msaa.view, Some(&view)),
            None => (&view, None),
        };
        let mut encoder = self
            .gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("scene"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: resolve,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(CLEAR),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.targets.depth.view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.bind_group, &[]);
            if let Some(mesh) = &self.mesh {
                pass.set_pipeline(&self.gpu.surface_pipeline);
                pass.set_vertex_buffer(0, mesh.positions.slice(..));
                pass.set_vertex_buffer(1, mesh.normals.slice(..));
                pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            }
            if let Some(program) = &self.deviation_path {
                pass.set_pipeline(&self.gpu.deviation_pipeline);
                pass.set_vertex_buffer(0, program.positions.slice(..));
                pass.set_vertex_buffer(1, program.deviations.slice(..));
                pass.draw(0..program.count, 0..1);
            } else if let Some((buffer, count)) = &self.path {
                pass.set_pipeline(&self.gpu.path_pipeline);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.draw(0..*count, 0..1);
            }
        }
        self.gpu.queue.submit([encoder.finish()]);
        self.gpu.queue.present(frame);
        Ok(())
    }
}

impl Viewer {
    /// Adopts a new placement; a different part (centre or size) resets the view.
    fn place(&mut self, placement: Option<Placement>) {
        let old = self.placement;
        self.placement = placement;
        let same_part = match (old, placement) {
            (Some(a), Some(b)) => {
                let tolerance = 0.01 * a.extent.length();
                a.extent.distance(b.extent) <= tolerance && a.centre.distance(b.centre) <= tolerance
            }
            (None, None) => true,
            _ => false,
        };
        if !same_part || !self.moved {
            self.reset_view();
        }
    }

    /// Uploads the camera, light and placement for this frame.
    fn write_uniforms(&self) {
        let p = self.placement.unwrap_or(Placement {
            centre: Vec3::ZERO,
            exaggeration: 1.0,
            extent: Vec3::ONE,
            z_min: 0.0,
            inv_range: 0.0,
        });
        let eye = self.camera.eye();
        let (right, up) = self.camera.right_up();
        // A light behind the viewer, a little above and to the left.
        let light = ((eye - self.camera.target).normalize() + 0.5 * up - 0.3 * right).normalize();
        let mut data = self.camera.view_proj().to_cols_array().to_vec();
        data.extend_from_slice(&[eye.x, eye.y, eye.z, PATH_LIFT * p.extent.length()]);
        data.extend_from_slice(&[light.x, light.y, light.z, 0.0]);
        data.extend_from_slice(&[p.centre.x, p.centre.y, p.centre.z, p.exaggeration]);
        data.extend_from_slice(&[p.z_min, p.inv_range, 0.0, 0.0]);
        data.extend_from_slice(&PATH_COLOR);
        data.extend_from_slice(&match &self.deviation_path {
            Some(d) => {
                let range = d.hi_nm - d.lo_nm;
                let inv = if range.is_finite() && range > 0.0 {
                    1.0 / range
                } else {
                    0.0
                };
                [d.lo_nm, inv, 1.0, 0.0]
            }
            None => [0.0; 4],
        });
        self.gpu
            .queue
            .write_buffer(&self.uniforms, 0, &f32_bytes(&data));
    }
}

/// Depth (and multisampled colour) attachments the size of the drawing buffer.
fn make_targets(
    device: &wgpu::Device,
    config: &wgpu::SurfaceConfiguration,
    samples: u32,
) -> Targets {
    let texture = |label, format| {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: config.width,
                height: config.height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        OwnedTexture { texture, view }
    };
    Targets {
        depth: texture("depth", DEPTH_FORMAT),
        msaa: (samples > 1).then(|| texture("msaa colour", config.format)),
    }
}
