//! Temporal methods: `taa`, `sraa-rt+taa` and `ctss+taa` render a sequence,
//! each frame jittered and resolved into a history
//! ([`subcone_kernels::taa`]: Karis 2014 with Salvi 2016's variance
//! clipping).
//!
//! [`Taa`] is the sequence: give it each frame's camera and it renders the
//! method's single frame ([`Method::single_frame`]) through the camera moved
//! by the frame's jitter, finds each pixel's velocity from the frame's depth
//! and the previous camera ([`velocities`]), and asks the backend to resolve
//! it against the history ([`Backend::resolve_taa`]: the CPU kernel by
//! default, `TaaPass` on the wgpu backend). [`Taa::reset`] is a camera cut.
//!
//! The jitter of frame `t` after a reset:
//! - `taa` and `ctss+taa`: the Halton (2, 3) point of phase `t mod phases`
//!   ([`subcone_kernels::taa::jitter`]); for CTSS this moves each cone's
//!   axis, so sixteen frames trace sixteen cones across the pixel;
//! - `sraa-rt+taa`: [`subcone_kernels::taa::subsample_rotation`], which
//!   puts the shaded sample on geometric subsample `t mod 4` of SRAA's
//!   rotated grid, as SMAA T2x rotates its subsample indices.
//!
//! ```
//! use subcone_kernels::passes::Technique;
//! use subcone_scene::temporal::{Taa, TaaConfig};
//! use subcone_scene::Method;
//!
//! let mut taa = Taa::new(Method::temporal(Technique::NoAa), TaaConfig::default())?;
//! assert_eq!(taa.frames(), 0);
//! // Frame 0 of a sequence is jittered by Halton (2, 3)'s first point.
//! assert_eq!(taa.jitter().x, 0.0);
//! taa.reset();
//! # Ok::<(), subcone_scene::RenderError>(())
//! ```

use crate::registry::TaaJitter;
use glam::{Vec2, Vec3};
use subcone_kernels::taa::{self, TaaSettings};

use crate::backend::{Backend, RenderSettings};
use crate::camera::Camera;
use crate::error::RenderError;
use crate::frame::Frame;
use crate::history::TaaInput;
use crate::method::Method;
use crate::scene::Scene;

/// The settings of a TAA sequence: the kernels' [`TaaSettings`] (jitter
/// phases, resolve space, smallest current weight, clip `γ`), the same
/// struct `subcone_passes::TaaPassDesc` holds.
pub type TaaConfig = TaaSettings;

/// A temporal method's sequence: its history, the previous camera and the
/// frame count since the last reset.
#[derive(Clone, Debug)]
pub struct Taa {
    method: Method,
    config: TaaConfig,
    /// Frames since the last reset.
    frame: u32,
    history: Vec<Vec3>,
    /// The previous frame's camera (without jitter) and size.
    previous: Option<(Camera, (u32, u32))>,
}

impl Taa {
    /// The sequence of `method`, which must be temporal
    /// ([`Method::is_temporal`]), with `config`.
    pub fn new(method: Method, config: TaaConfig) -> Result<Self, RenderError> {
        if !method.is_temporal() {
            return Err(RenderError::Method(format!(
                "{method} is not a temporal method: name one with +taa (or taa)"
            )));
        }
        config
            .validate()
            .map_err(|e| RenderError::Method(format!("TAA: {e}")))?;
        Ok(Taa {
            method,
            config,
            frame: 0,
            history: Vec::new(),
            previous: None,
        })
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.method
    }

    /// Frames rendered since the last reset.
    pub fn frames(&self) -> u32 {
        self.frame
    }

    /// A camera cut: the next frame starts a new history.
    pub fn reset(&mut self) {
        self.frame = 0;
        self.history.clear();
        self.previous = None;
    }

    /// The next frame's sub-pixel jitter, in pixels (see the module docs).
    pub fn jitter(&self) -> Vec2 {
        match crate::registry::info(self.method.technique()).taa_jitter {
            TaaJitter::SubsampleRotation => {
                taa::subsample_rotation(self.frame, self.method.sraa().shaded_offset())
            }
            TaaJitter::Halton => self.config.jitter(self.frame),
        }
    }

    /// Render the next frame of the sequence through `camera` (its own
    /// jitter, if any, is replaced by the sequence's) on `backend`, and
    /// resolve it into the history. A change of size resets the history.
    /// The frame's `stats.timings` gain the resolve (`"taa"`); its colour is
    /// the resolved image, its AOVs the jittered frame's (depth is always
    /// recorded: the velocities need it).
    pub fn render(
        &mut self,
        backend: &dyn Backend,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
    ) -> Result<Frame, RenderError> {
        let size = (settings.width, settings.height);
        let still = camera.with_jitter(Vec2::ZERO);
        if self.previous.is_some_and(|(_, s)| s != size) {
            self.reset();
        }
        let mut with_depth = *settings;
        with_depth.aovs = true;
        let mut frame = backend.render(
            scene,
            &still.with_jitter(self.jitter()),
            &self.method.single_frame(),
            &with_depth,
        )?;
        if !settings.aovs {
            frame.normal = None;
            frame.samples_per_pixel = None;
            frame.albedo = None;
            frame.light_visibility = None;
            frame.mirror = None;
        }
        let velocity = match self.previous {
            Some((previous, _)) => velocities(
                frame.depth.as_deref().unwrap_or(&[]),
                &still,
                &previous,
                size,
            ),
            None => vec![Vec2::ZERO; frame.color.len()],
        };
        let params = self.config.params(size, self.frame);
        let input = TaaInput {
            params,
            current: &frame.color,
            velocity: &velocity,
            history: &self.history,
        };
        let (resolved, timing) = backend.resolve_taa(&input)?;
        frame.stats.timings.push(timing);
        frame.color = resolved;
        self.history.clone_from(&frame.color);
        self.previous = Some((still, size));
        self.frame = self.frame.saturating_add(1);
        Ok(frame)
    }
}

/// Each pixel's velocity in pixels (current minus previous position) for a
/// `width × height` frame seen through `camera` with view depths `depth`
/// (`Frame::depth`; non-finite or non-positive where nothing is hit), the
/// previous frame seen through `previous` (neither jittered: the history is
/// kept at pixel centres). A pixel's surface point is its depth along the
/// ray through its centre; a pixel that hits nothing moves as the direction
/// does (a point at infinity). A point behind the previous camera gets a
/// non-finite velocity: no history. A `depth` of the wrong length reads as
/// all background.
pub fn velocities(
    depth: &[f32],
    camera: &Camera,
    previous: &Camera,
    (w, h): (u32, u32),
) -> Vec<Vec2> {
    let n = w as usize * h as usize;
    let rays = camera.with_jitter(Vec2::ZERO).rays(w, h);
    let before = previous.with_jitter(Vec2::ZERO);
    let mut out = Vec::with_capacity(n);
    for y in 0..h {
        for x in 0..w {
            let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let (_, dir) = rays.ray(p);
            let d = depth
                .get((y * w + x) as usize)
                .copied()
                .filter(|_| depth.len() == n)
                .filter(|d| d.is_finite() && *d > 0.0);
            let then = match d {
                Some(d) => {
                    let point = camera.position + dir * (d / dir.dot(camera.forward));
                    before.project(point, w, h)
                }
                None => before.project_direction(dir, w, h),
            };
            out.push(then.map_or(Vec2::splat(f32::INFINITY), |q| p - q));
        }
    }
    out
}
