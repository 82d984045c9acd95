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
//! A scene whose objects move gives each frame's scene and where each
//! visible point was a frame earlier ([`Taa::render_moving`],
//! [`velocities_moving`]: the motion vectors of the object and the camera
//! together, as an engine's motion-vector pass writes them). With
//! [`TaaConfig::depth_dilation`] the resolve takes each pixel's motion from
//! the nearest depth of its 3×3 neighbourhood (Karis 2014; the frame's view
//! depth, so [`DepthDilation::NearestSmallest`]).
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
use subcone_kernels::taa::{self, DepthDilation, TaaSettings};

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
    /// ([`Method::is_temporal`]), with `config`. Its depth dilation is off
    /// or [`DepthDilation::NearestSmallest`] (the frames' depth is view
    /// depth: nearer is smaller); [`DepthDilation::NearestLargest`] is
    /// refused.
    pub fn new(method: Method, config: TaaConfig) -> Result<Self, RenderError> {
        if !method.is_temporal() {
            return Err(RenderError::Method(format!(
                "{method} is not a temporal method: name one with +taa (or taa)"
            )));
        }
        config
            .validate()
            .map_err(|e| RenderError::Method(format!("TAA: {e}")))?;
        if config.depth_dilation == DepthDilation::NearestLargest {
            return Err(RenderError::Method(
                "TAA: the sequence dilates by its frames' view depth, where nearer is smaller: \
                 depth dilation NearestLargest (reversed Z) does not apply"
                    .into(),
            ));
        }
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
        self.render_moving(backend, scene, camera, settings, &|p| p)
    }

    /// [`Self::render`] of a frame whose scene moved since the previous one:
    /// `scene` is this frame's, and `previous_point(p)` is where the surface
    /// point `p` of this frame (world space) was in the previous frame (`p`
    /// itself where nothing moved). The velocities are those of the object
    /// and the camera together ([`velocities_moving`]). `render` is this
    /// with every point still.
    pub fn render_moving(
        &mut self,
        backend: &dyn Backend,
        scene: &Scene,
        camera: &Camera,
        settings: &RenderSettings,
        previous_point: &dyn Fn(Vec3) -> Vec3,
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
            Some((previous, _)) => velocities_moving(
                frame.depth.as_deref().unwrap_or(&[]),
                &still,
                &previous,
                size,
                previous_point,
            ),
            None => vec![Vec2::ZERO; frame.color.len()],
        };
        let params = self.config.params(size, self.frame);
        let depth = self
            .config
            .depth_dilation
            .is_on()
            .then(|| frame.depth.as_deref().unwrap_or(&[]));
        let input = TaaInput {
            params,
            current: &frame.color,
            velocity: &velocity,
            depth,
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
    size: (u32, u32),
) -> Vec<Vec2> {
    velocities_moving(depth, camera, previous, size, &|p| p)
}

/// [`velocities`] of a scene that moved: each pixel's surface point `p`
/// (from its depth, as there) was at `previous_point(p)` in the previous
/// frame, which the previous camera projects. A pixel that hits nothing
/// moves with the camera alone (nothing moves at infinity). With
/// `previous_point` the identity, the result is [`velocities`]' bit for
/// bit.
pub fn velocities_moving(
    depth: &[f32],
    camera: &Camera,
    previous: &Camera,
    (w, h): (u32, u32),
    previous_point: &dyn Fn(Vec3) -> Vec3,
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
                    before.project(previous_point(point), w, h)
                }
                None => before.project_direction(dir, w, h),
            };
            out.push(then.map_or(Vec2::splat(f32::INFINITY), |q| p - q));
        }
    }
    out
}
