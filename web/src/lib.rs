//! spiralcam in the browser: the wasm-bindgen API the page's worker calls to plan a job
//! (`api`), correct a job from a measured part and turn a test cut into set-up offsets
//! (`correct`), and the wgpu renderer that draws the surface and the path on the page's canvas
//! (`viewer`, WebGPU first, WebGL2 as the fallback) with its orbit [`camera`]. [`colormap`] is
//! the one height colour scale shared by the shader and the page's legend; [`bundle`] zips a
//! program and its child programs into one download; [`design`] is the page's import of a
//! designer's file; `verify` is the page's Open NC… (a program verified against the job).
//! `api`, `correct`, `verify` and `viewer` exist only in the wasm32 build.

pub mod bundle;
pub mod camera;
pub mod colormap;
pub mod design;

#[cfg(target_arch = "wasm32")]
pub mod api;
#[cfg(target_arch = "wasm32")]
pub mod correct;
#[cfg(target_arch = "wasm32")]
pub mod verify;
#[cfg(target_arch = "wasm32")]
pub mod viewer;
