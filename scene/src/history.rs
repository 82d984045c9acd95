//! One TAA resolve's inputs ([`TaaInput`]) and its CPU implementation
//! ([`resolve`]): what [`Backend::resolve_taa`](crate::Backend::resolve_taa)
//! runs by default, and the reference a backend's own resolve is checked
//! against. The sequence around it (jitter, velocity, history, reset) is
//! [`crate::temporal`].

use glam::{Vec2, Vec3};
use subcone_kernels::taa::{resolve_pixel, TaaParams};

use crate::error::RenderError;

/// One frame's TAA resolve: this frame's jittered colours, each pixel's
/// velocity and the previous output, all `params.width × params.height`,
/// row-major, in linear radiance.
#[derive(Clone, Copy, Debug)]
pub struct TaaInput<'a> {
    /// The kernel's parameters (size, exposure, frames in the history).
    pub params: TaaParams,
    /// This frame's colour of each pixel (its jittered sample).
    pub current: &'a [Vec3],
    /// Each pixel's motion in pixels, current minus previous
    /// (`subcone_kernels::taa::resolve_pixel`).
    pub velocity: &'a [Vec2],
    /// The previous output (ignored when `params.history_frames == 0`).
    pub history: &'a [Vec3],
}

impl TaaInput<'_> {
    /// Pixels of the frame.
    pub fn pixels(&self) -> usize {
        self.params.width as usize * self.params.height as usize
    }

    /// Check that every buffer holds one value per pixel (the history only
    /// when it is read).
    pub fn validate(&self) -> Result<(), RenderError> {
        let n = self.pixels();
        let history = if self.params.history_frames == 0 {
            None
        } else {
            Some(self.history.len())
        };
        for (what, len) in [
            ("colours", Some(self.current.len())),
            ("velocities", Some(self.velocity.len())),
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
/// [`resolve_pixel`], row by row. Errors when a buffer does not hold one
/// value per pixel.
pub fn resolve(input: &TaaInput<'_>) -> Result<Vec<Vec3>, RenderError> {
    input.validate()?;
    let w = input.params.width as i32;
    let at = |buf: &[Vec3], x: i32, y: i32| buf[(y * w + x) as usize];
    let current = |x: i32, y: i32| at(input.current, x, y);
    let history = |x: i32, y: i32| at(input.history, x, y);
    let mut out = Vec::with_capacity(input.pixels());
    for y in 0..input.params.height as i32 {
        for x in 0..w {
            let v = input.velocity[(y * w + x) as usize];
            out.push(resolve_pixel(&current, &history, (x, y), v, &input.params));
        }
    }
    Ok(out)
}
