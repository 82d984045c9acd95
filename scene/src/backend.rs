//! The interface every backend implements.

use subcone_kernels::passes::Passes;

use crate::camera::Camera;
use crate::error::RenderError;
use crate::frame::Frame;
use crate::method::Method;
use crate::scene::Scene;

/// Largest accepted image side.
pub const MAX_SIDE: u32 = 16_384;
/// Largest accepted pixel count (a 16k × 16k frame is 3 GiB of f32 RGB alone).
pub const MAX_PIXELS: u64 = 1 << 26;

/// Settings of one render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Mirror bounces (Whitted); 1 by default.
    pub reflection_depth: u32,
    /// Passes to run even where the scene does not need them (for tests that
    /// check that leaving a pass out changes nothing).
    pub force_passes: Passes,
    /// Record depth, normal and samples-per-pixel AOVs.
    pub aovs: bool,
    /// SDF scenes: step budget per ray, overriding the scene's.
    pub max_steps: Option<u32>,
    /// SDF scenes: maximum ray distance, overriding the scene's.
    pub max_distance: Option<f32>,
}

impl RenderSettings {
    /// Settings for a `width × height` image.
    pub fn new(width: u32, height: u32) -> Self {
        RenderSettings {
            width,
            height,
            reflection_depth: 1,
            force_passes: Passes::empty(),
            aovs: false,
            max_steps: None,
            max_distance: None,
        }
    }

    /// Check the resolution: non-zero, at most [`MAX_SIDE`] per side and
    /// [`MAX_PIXELS`] in all.
    pub fn validate(&self) -> Result<(), RenderError> {
        let err = |reason: String| RenderError::Resolution {
            width: self.width,
            height: self.height,
            reason,
        };
        if self.width == 0 || self.height == 0 {
            return Err(err("width and height must be at least 1".into()));
        }
        if self.width > MAX_SIDE || self.height > MAX_SIDE {
            return Err(err(format!("each side must be at most {MAX_SIDE}")));
        }
        if self.width as u64 * self.height as u64 > MAX_PIXELS {
            return Err(err(format!("at most {MAX_PIXELS} pixels")));
        }
        if self.max_steps == Some(0) {
            return Err(RenderError::Method("max steps must be at least 1".into()));
        }
        if let Some(d) = self.max_distance {
            if !(d > 0.0 && d.is_finite()) {
                return Err(RenderError::Method(format!(
                    "max distance {d} must be positive and finite"
                )));
            }
        }
        Ok(())
    }
}

/// A renderer: the CPU reference, the wgpu backend, or your own.
pub trait Backend {
    /// Short name (`"cpu"`, `"wgpu"`).
    fn name(&self) -> &'static str;

    /// What the backend runs on, for reports (e.g. the GPU adapter and driver).
    fn describe(&self) -> String {
        self.name().to_string()
    }

    /// Render `scene` through `camera` with `method`.
    fn render(
        &self,
        scene: &Scene,
        camera: &Camera,
        method: &Method,
        settings: &RenderSettings,
    ) -> Result<Frame, RenderError>;
}
