//! `subcone-wgpu`: the GPU backend, through wgpu (Vulkan, Metal or DX12; in
//! CI, Mesa's software Vulkan driver, lavapipe).
//!
//! Triangle scenes: the BVH is flattened into storage buffers and traversed in
//! WGSL compute shaders (closest and any hit; no hardware ray queries, which
//! lavapipe lacks). SRAA's geometric subsamples come from rasterisation with a
//! jittered projection (the paper's hybrid pipeline, §3.1); SRAA-RT traces
//! them. SDF scenes are compiled to WGSL from the scene tree and cone traced.
//! Every antialiasing formula is a WGSL mirror of a `subcone-kernels`
//! function, shipped by that crate. FXAA, the post-process baseline, filters
//! the NoAA frame on the GPU before it is read back.
//!
//! ```no_run
//! use subcone_scene::{builtin::builtin, Backend, RenderSettings};
//! use subcone_wgpu::WgpuBackend;
//!
//! let scene = builtin("cornell").unwrap();
//! let gpu = WgpuBackend::new().expect("a GPU adapter");
//! let frame = gpu
//!     .render(&scene, &scene.camera, &"sraa".parse().unwrap(), &RenderSettings::new(64, 64))
//!     .unwrap();
//! assert_eq!(frame.color.len(), 64 * 64);
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod compute;
pub mod context;
#[cfg(test)]
mod layout_tests;
mod post;
pub mod sdf;
#[cfg(feature = "test-util")]
pub mod test_util;
pub(crate) mod triangles;

use std::sync::Arc;

use subcone_kernels::passes::{Passes, MAX_LIGHTS};
use subcone_scene::backend::{plan, render_passes, Capabilities};
use subcone_scene::{
    Backend, Camera, Frame, Method, RenderError, RenderSettings, Scene, Unsupported,
};

pub use context::GpuContext;

/// The wgpu backend. Cheap to clone; all clones share one device.
#[derive(Clone, Debug)]
pub struct WgpuBackend {
    ctx: Arc<GpuContext>,
}

impl WgpuBackend {
    /// A backend on the process-wide shared device (see [`GpuContext::shared`]).
    pub fn new() -> Result<Self, RenderError> {
        Ok(WgpuBackend {
            ctx: GpuContext::shared()?,
        })
    }

    /// A backend on a device of your own.
    pub fn with_context(ctx: Arc<GpuContext>) -> Self {
        WgpuBackend { ctx }
    }

    /// The device.
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }
}

/// Whether a GPU is required (`SUBCONE_REQUIRE_GPU` set to anything but `0`
/// or empty): tests then fail instead of skipping when no adapter exists
/// ([`subcone_scene::conformance::gpu_required`], the one reading of it).
pub use subcone_scene::conformance::gpu_required;

/// One frame as [`Backend::render`] was asked for it, with the passes
/// [`render_passes`] planned for it: what every render path takes.
pub(crate) struct Job<'a> {
    pub(crate) scene: &'a Scene,
    pub(crate) camera: &'a Camera,
    pub(crate) method: &'a Method,
    pub(crate) settings: &'a RenderSettings,
    pub(crate) passes: Passes,
}

/// What the wgpu backend renders: the kernels' techniques (SRAA-RT on SDF
/// scenes included), up to [`MAX_LIGHTS`] lights on
/// triangle scenes, up to [`sdf::MAX_SIDE_SAMPLES`] samples per pixel side on
/// SDF scenes; the refusals are the one plan's
/// ([`subcone_scene::backend::plan`]).
pub const CAPABILITIES: Capabilities = Capabilities {
    backend: "wgpu",
    max_lights_triangles: Some(MAX_LIGHTS),
    max_lights_sdf: None,
    sdf_subpixel_geometry: Ok(()),
    max_sdf_side_samples: Some(sdf::MAX_SIDE_SAMPLES),
    raster_primary: Err(
        "its sraa already rasterises the subsample G-buffers (the MSAA prepass); -hybrid names the CPU backend's rasteriser",
    ),
    diagonal_ssaa: Ok(()),
};

impl Backend for WgpuBackend {
    fn name(&self) -> &'static str {
        CAPABILITIES.backend
    }

    /// Refuses what the kernels refuse (`required_passes`) and
    /// semi-transparent materials; on triangle scenes more than
    /// [`MAX_LIGHTS`] lights; on SDF scenes mirror reflections, the material
    /// gate and more than
    /// [`sdf::MAX_SIDE_SAMPLES`] samples per pixel side.
    fn supports(&self, scene: &Scene, method: &Method) -> Result<(), Unsupported> {
        plan(scene, method, &CAPABILITIES).map(|_| ())
    }

    fn describe(&self) -> String {
        format!("wgpu on {}", self.ctx.describe())
    }

    /// The resolve on the GPU, through [`subcone_passes::TaaPass`].
    fn resolve_taa(
        &self,
        input: &subcone_scene::history::TaaInput<'_>,
    ) -> Result<(Vec<glam::Vec3>, subcone_scene::PassTiming), RenderError> {
        post::taa::resolve(&self.ctx, input)
    }

    fn render(
        &self,
        scene: &Scene,
        camera: &Camera,
        method: &Method,
        settings: &RenderSettings,
    ) -> Result<Frame, RenderError> {
        let job = Job {
            scene,
            camera,
            method,
            settings,
            passes: render_passes(scene, camera, method, settings, &CAPABILITIES)?,
        };
        if scene.sdf_geometry().is_some() {
            sdf::render(&self.ctx, &job)
        } else {
            triangles::render(&self.ctx, &job)
        }
    }
}
