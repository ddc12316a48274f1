//! The GPU a viewer draws with: adapter, device, queue, the uniforms' layout and the three
//! render pipelines for one canvas format and sample count. On WebGPU one [`Gpu`] serves every
//! viewer of the page (a canvas context may be configured with any device of the page, per
//! the WebGPU specification's `GPUCanvasContext.configure`), so a page of many viewers opens
//! one device and compiles its shaders once. Headless Chromium's SwiftShader made a Vulkan
//! device, with its own worker threads, for every viewer, and twice stalled its GPU process
//! among 40 viewers made and removed in a row. The shared device is destroyed with its last
//! viewer, and a lost one is replaced at the next viewer. On WebGL2 each canvas has its own
//! context, hence its own `Gpu`.

use std::cell::{Cell, RefCell};
use std::rc::{Rc, Weak};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use wasm_bindgen::prelude::*;

use super::{DEPTH_FORMAT, UNIFORM_SIZE};

thread_local! {
    /// The page's WebGPU device and pipelines while a viewer holds them.
    static SHARED: RefCell<Weak<Gpu>> = const { RefCell::new(Weak::new()) };
    /// Devices opened on this page so far (see [`devices_opened`]).
    static OPENED: Cell<u32> = const { Cell::new(0) };
}

/// How many GPU devices the page's viewers have opened: one for all of them on WebGPU (again
/// only after the last viewer went or the device was lost), one a viewer on WebGL2.
pub(super) fn devices_opened() -> u32 {
    OPENED.with(Cell::get)
}

/// A device and what every viewer on it draws with.
pub(super) struct Gpu {
    instance: wgpu::Instance,
    adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    /// "WebGPU" or "WebGL2".
    pub backend: &'static str,
    /// The canvas format the pipelines write.
    format: wgpu::TextureFormat,
    pub sample_count: u32,
    pub uniforms_layout: wgpu::BindGroupLayout,
    pub surface_pipeline: wgpu::RenderPipeline,
    pub path_pipeline: wgpu::RenderPipeline,
    pub deviation_pipeline: wgpu::RenderPipeline,
    /// Set when the browser reports the device lost (or destroyed).
    lost: Arc<AtomicBool>,
}

impl Gpu {
    /// The GPU for a viewer on `canvas`, with the canvas's surface: the page's shared WebGPU
    /// device where it can draw on the canvas, else a new device (shared from then on if it
    /// is WebGPU's). Errors (no backend at all) become a JS exception with a clear message.
    pub async fn for_canvas(
        canvas: web_sys::HtmlCanvasElement,
    ) -> Result<(Rc<Gpu>, wgpu::Surface<'static>), JsError> {
        let shared = page_gpu();
        let instance = match &shared {
            Some(gpu) => gpu.instance.clone(),
            None => {
                let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
                desc.backends = wgpu::Backends::BROWSER_WEBGPU | wgpu::Backends::GL;
                wgpu::util::new_instance_with_webgpu_detection(desc).await
            }
        };
        // The surface comes first: the WebGL2 adapter is made from the canvas's context.
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Canvas(canvas))
            .map_err(|e| {
                JsError::new(&format!(
                    "3-D view unavailable: no WebGPU or WebGL2 context on the canvas \
                     (the browser offers neither, or the canvas is in use): {e}"
                ))
            })?;
        if let Some(gpu) = shared.filter(|gpu| gpu.draws_on(&surface)) {
            return Ok((gpu, surface));
        }
        let gpu = Rc::new(Gpu::open(instance, &surface).await?);
        if gpu.backend != "WebGPU" {
            return Ok((gpu, surface));
        }
        // Another viewer may have opened the page's device while this one waited: draw with
        // that one (this device is destroyed as `gpu` drops).
        if let Some(other) = page_gpu().filter(|other| other.draws_on(&surface)) {
            return Ok((other, surface));
        }
        SHARED.with(|s| *s.borrow_mut() = Rc::downgrade(&gpu));
        Ok((gpu, surface))
    }

    /// Opens a device for `surface` and builds the pipelines for its format.
    async fn open(
        instance: wgpu::Instance,
        surface: &wgpu::Surface<'static>,
    ) -> Result<Gpu, JsError> {
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                compatible_surface: Some(surface),
                ..Default::default()
            })
            .await
            .map_err(|e| {
                JsError::new(&format!(
                    "3-D view unavailable: no WebGPU or WebGL2 adapter for the canvas ({e})"
                ))
            })?;
        let backend = match adapter.get_info().backend {
            wgpu::Backend::BrowserWebGpu => "WebGPU",
            _ => "WebGL2",
        };
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("spiralcam viewer"),
                required_limits: wgpu::Limits::downlevel_webgl2_defaults()
                    .using_resolution(adapter.limits()),
                ..Default::default()
            })
            .await
            .map_err(|e| {
                JsError::new(&format!(
                    "3-D view: could not open the {backend} device ({e})"
                ))
            })?;
        OPENED.with(|n| n.set(n.get() + 1));
        device.on_uncaptured_error(Arc::new(|e| {
            web_sys::console::error_1(&format!("spiralcam viewer: {e}").into());
        }));
        let lost = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            flag.store(true, Ordering::Relaxed);
            if reason != wgpu::DeviceLostReason::Destroyed {
                let text = format!("spiralcam viewer: the GPU device was lost ({message})");
                web_sys::console::warn_1(&text.into());
            }
        });

        let format = canvas_format(surface, &adapter)?;
        let msaa = |f| {
            adapter
                .get_texture_format_features(f)
                .flags
                .sample_count_supported(4)
        };
        let sample_count = if msaa(format) && msaa(DEPTH_FORMAT) {
            4
        } else {
            1
        };
        let source = format!(
            "{}\n{}",
            crate::colormap::wgsl(),
            include_str!("shader.wgsl")
        );
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("viewer shader"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let uniforms_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("viewer uniforms"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(UNIFORM_SIZE),
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("viewer"),
            bind_group_layouts: &[Some(&uniforms_layout)],
            immediate_size: 0,
        });
        let pipelines = PipelineSetup {
            device: &device,
            layout: &pipeline_layout,
            shader: &shader,
            format,
            sample_count,
        };
        Ok(Gpu {
            surface_pipeline: pipelines.surface(),
            path_pipeline: pipelines.path(),
            deviation_pipeline: pipelines.deviation(),
            instance,
            adapter,
            device,
            queue,
            backend,
            format,
            sample_count,
            uniforms_layout,
            lost,
        })
    }

    /// Whether the pipelines can draw on `surface` (its canvas offers their format).
    fn draws_on(&self, surface: &wgpu::Surface<'static>) -> bool {
        canvas_format(surface, &self.adapter).ok() == Some(self.format)
    }

    /// The configuration for `surface`, `width` × `height` pixels, in the pipelines' format.
    pub fn configuration(
        &self,
        surface: &wgpu::Surface<'static>,
        width: u32,
        height: u32,
    ) -> Result<wgpu::SurfaceConfiguration, JsError> {
        let mut config = default_config(surface, &self.adapter, width, height)?;
        config.format = self.format;
        Ok(config)
    }
}

/// The device is given back with its last viewer on WebGPU (wgpu's handles on the web would
/// wait for the garbage collector); on WebGL2 the page loses the canvas's context itself
/// (`spiralcam-viewer.js`).
impl Drop for Gpu {
    fn drop(&mut self) {
        if self.backend == "WebGPU" {
            self.device.destroy();
        }
    }
}

/// The page's shared WebGPU device, unless none is held or it was lost.
fn page_gpu() -> Option<Rc<Gpu>> {
    SHARED
        .with(|s| s.borrow().upgrade())
        .filter(|gpu| !gpu.lost.load(Ordering::Relaxed))
}

/// The format a viewer writes on `surface`: the canvas's preferred one, without its sRGB
/// suffix where the canvas offers that (colours are sRGB values already, like the CSS legend).
fn canvas_format(
    surface: &wgpu::Surface<'static>,
    adapter: &wgpu::Adapter,
) -> Result<wgpu::TextureFormat, JsError> {
    let preferred = default_config(surface, adapter, 1, 1)?.format;
    let plain = preferred.remove_srgb_suffix();
    Ok(
        if surface.get_capabilities(adapter).formats.contains(&plain) {
            plain
        } else {
            preferred
        },
    )
}

/// wgpu's default configuration of `surface` on `adapter`, `width` × `height` pixels.
fn default_config(
    surface: &wgpu::Surface<'static>,
    adapter: &wgpu::Adapter,
    width: u32,
    height: u32,
) -> Result<wgpu::SurfaceConfiguration, JsError> {
    surface
        .get_default_config(adapter, width, height)
        .ok_or_else(|| JsError::new("3-D view: the canvas is not supported by the adapter"))
}

/// What the render pipelines share.
struct PipelineSetup<'a> {
    device: &'a wgpu::Device,
    layout: &'a wgpu::PipelineLayout,
    shader: &'a wgpu::ShaderModule,
    format: wgpu::TextureFormat,
    sample_count: u32,
}

impl PipelineSetup<'_> {
    /// A pipeline drawing `topology` from `buffers` with the shader's `vs_<name>`/`fs_<name>`.
    fn pipeline(
        &self,
        name: &str,
        topology: wgpu::PrimitiveTopology,
        buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
    ) -> wgpu::RenderPipeline {
        let (vs, fs) = (format!("vs_{name}"), format!("fs_{name}"));
        self.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(name),
                layout: Some(self.layout),
                vertex: wgpu::VertexState {
                    module: self.shader,
                    entry_point: Some(&vs),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::LessEqual),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: self.sample_count,
                    ..Default::default()
                },
                fragment: Some(wgpu::FragmentState {
                    module: self.shader,
                    entry_point: Some(&fs),
                    compilation_options: Default::default(),
                    targets: &[Some(self.format.into())],
                }),
                multiview_mask: None,
                cache: None,
            })
    }

    /// The surface: triangles from a position and a normal buffer.
    fn surface(&self) -> wgpu::RenderPipeline {
        let position = wgpu::vertex_attr_array![0 => Float32x3];
        let normal = wgpu::vertex_attr_array![1 => Float32x3];
        let layout = |attributes| wgpu::VertexBufferLayout {
            array_stride: 12,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes,
        };
        self.pipeline(
            "surface",
            wgpu::PrimitiveTopology::TriangleList,
            &[Some(layout(&position)), Some(layout(&normal))],
        )
    }

    /// A verified program's path: a line strip from a position and a deviation buffer.
    fn deviation(&self) -> wgpu::RenderPipeline {
        let position = wgpu::vertex_attr_array![0 => Float32x3];
        let deviation = wgpu::vertex_attr_array![1 => Float32];
        self.pipeline(
            "deviation",
            wgpu::PrimitiveTopology::LineStrip,
            &[
                Some(wgpu::VertexBufferLayout {
                    array_stride: 12,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &position,
                }),
                Some(wgpu::VertexBufferLayout {
                    array_stride: 4,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &deviation,
                }),
            ],
        )
    }

    /// The path: a line list (segments) from a position buffer.
    fn path(&self) -> wgpu::RenderPipeline {
        let position = wgpu::vertex_attr_array![0 => Float32x3];
        self.pipeline(
            "path",
            wgpu::PrimitiveTopology::LineList,
            &[Some(wgpu::VertexBufferLayout {
                array_stride: 12,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &position,
            })],
        )
    }
}
