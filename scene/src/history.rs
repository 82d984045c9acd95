//! One TAA resolve's inputs ([`TaaInput`]) and its CPU implementation
//! ([`resolve`]): what [`Backend::resolve_taa`](crate::Backend::resolve_taa)
//! runs by default, and the reference a backend's own resolve is checked
//! against. The sequence around it (jitter, velocity, history, reset) is
//! [`crate::temporal`].

use glam::{Vec2, Vec3};
use subcone_kernels::taa::{dilated_motion, resolve_pixel, DepthDilation, TaaParams};

use crate::error::RenderError;

/// One frame's TAA resolve: this frame's jittered colours, each pixel's
/// velocity, its depth when the motion is dilated, and the previous output,
/// all `params.width × params.height`, row-major, in linear radiance.
#[derive(Clone, Copy, Debug)]
pub struct TaaInput<'a> {
    /// The kernel's parameters (size, exposure, frames in the history, the
    /// motion vectors' scale, closest-depth dilation).
    pub params: TaaParams,
    /// This frame's colour of each pixel (its jittered sample).
    pub current: &'a [Vec3],
    /// Each pixel's motion vector: times `params.motion_scale`, its motion
    /// in pixels, current minus previous
    /// (`subcone_kernels::taa::resolve_pixel`).
    pub velocity: &'a [Vec2],
    /// Each pixel's depth, in the order `params.depth_dilation` says
    /// (`subcone_kernels::taa::dilated_motion`): given exactly when that
    /// dilation is on.
    pub depth: Option<&'a [f32]>,
    /// The previous output (ignored when `params.history_frames == 0`).
    pub history: &'a [Vec3],
}

impl TaaInput<'_> {
    /// Pixels of the frame.
    pub fn pixels(&self) -> usize {
        self.params.width as usize * self.params.height as usize
    }

    /// The closest-depth dilation the parameters ask for.
    pub fn dilation(&self) -> DepthDilation {
        DepthDilation::from_code(self.params.depth_dilation)
    }

    /// Check that every buffer holds one value per pixel (the history only
    /// when it is read), and that a depth is given exactly when the
    /// parameters dilate the motion.
    pub fn validate(&self) -> Result<(), RenderError> {
        let n = self.pixels();
        let history = if self.params.history_frames == 0 {
            None
        } else {
            Some(self.history.len())
        };
        match (self.dilation().is_on(), self.depth) {
            (true, None) => {
                return Err(RenderError::Method(format!(
                    "TAA resolve with depth dilation {:?} given no depth",
                    self.dilation()
                )))
            }
            (false, Some(_)) => {
                return Err(RenderError::Method(
                    "TAA resolve given a depth with depth dilation off: set \
                     params.depth_dilation, or give no depth"
                        .into(),
                ))
            }
            _ => {}
        }
        for (what, len) in [
            ("colours", Some(self.current.len())),
            ("velocities", Some(self.velocity.len())),
            ("depths", self.depth.map(<[f32]>::len)),
            ("history pixels", history),
        ] {
            if let Some(len) = len.filter(|&len| len != n) {
                return Err(RenderError::Method(format!(
                    "TAA resolve of a {}x{} frame given {len} {what}, expected {n}",
                    self.params.width, self.params.height
                )));
            }
        }
        Ok(())
    }
}

/// The TAA resolve of every pixel on the CPU: `subcone_kernels::taa`'s
/// [`resolve_pixel`], row by row, each with its own motion vector or, with
/// depth dilation on, the one [`dilated_motion`] picks. Errors when a
/// buffer does not hold one value per pixel, or a depth is missing or
/// given when it should not be ([`TaaInput::validate`]).
pub fn resolve(input: &TaaInput<'_>) -> Result<Vec<Vec3>, RenderError> {
    input.validate()?;
    let w = input.params.width as i32;
    let at = |buf: &[Vec3], x: i32, y: i32| buf[(y * w + x) as usize];
    let current = |x: i32, y: i32| at(input.current, x, y);
    let history = |x: i32, y: i32| at(input.history, x, y);
    let motion = |x: i32, y: i32| input.velocity[(y * w + x) as usize];
    let mut out = Vec::with_capacity(input.pixels());
    for y in 0..input.params.height as i32 {
        for x in 0..w {
            let v = match input.depth {
                Some(depth) => {
                    let depth = |x: i32, y: i32| depth[(y * w + x) as usize];
                    dilated_motion(&motion, &depth, (x, y), &input.params)
                }
                None => motion(x, y),
            };
            out.push(resolve_pixel(&current, &history, (x, y), v, &input.params));
        }
    }
    Ok(out)
}
