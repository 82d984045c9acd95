//! sdf scenes on the GPU.

use subcone_kernels::passes::Passes;
use subcone_scene::{Camera, Frame, Method, RenderError, RenderSettings, Scene};

use crate::context::{err, GpuContext};

pub(crate) fn render(
    ctx: &GpuContext,
    scene: &Scene,
    camera: &Camera,
    method: &Method,
    settings: &RenderSettings,
    passes: Passes,
) -> Result<Frame, RenderError> {
    let _ = (ctx, scene, camera, method, settings, passes);
    Err(err("sdf scenes are not implemented yet"))
}
