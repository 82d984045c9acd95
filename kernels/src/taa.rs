//! Temporal antialiasing (TAA): the baseline engines ship, against which the
//! single-frame methods of both papers are measured in motion.
//!
//! Neither paper is temporal. This module follows the published design most
//! engines derive from, Brian Karis, "High Quality Temporal Supersampling"
//! (SIGGRAPH 2014, Advances in Real-Time Rendering; Unreal Engine 4's TAA),
//! with Marco Salvi's variance clipping ("An Excursion in Temporal
//! Supersampling", GDC 2016):
//!
//! - **Jitter.** Frame `t` moves the projection by a sub-pixel offset, the
//!   Halton (2, 3) point of index `t mod phases + 1`, centred on the pixel
//!   ([`jitter`]; Karis uses 8 phases, 16 resolves a still image as finely as
//!   a 4×4 grid). Each frame traces one sample per pixel at a new place.
//! - **Reprojection.** Each pixel centre `p` finds where its surface was in the
//!   previous frame, `p − velocity` (`velocity` in pixels, current minus
//!   previous), and samples the history there with a 4×4 Catmull-Rom filter
//!   ([`catmull_rom_weights`]; Karis: bilinear blurs the history a little
//!   more every frame). A point outside the previous image has no history.
//!   An engine's motion vectors come in its own units and sign: `velocity`
//!   is the host's vector times [`TaaParams::motion_scale`] (see
//!   [Engine conventions](#engine-conventions)).
//! - **Closest-depth motion** (optional, [`TaaParams::depth_dilation`]). A
//!   pixel on the silhouette of a moving object may show the background
//!   while its neighbour shows the object; its own vector then says "still"
//!   and the history it fetches holds the object that just left (the trail
//!   Karis shows). With a depth buffer, the vector used at a pixel is the
//!   one of the nearest surface in its 3×3 neighbourhood ([`dilated_motion`]:
//!   Karis 2014 takes the velocity of the closest depth of the 3×3
//!   neighbourhood; AMD FSR2's "Reconstruct & dilate" stage "looks at the
//!   depth values for a 3x3 neighbourhood for each pixel and then selects
//!   the depth values and motion vectors in that neighbourhood where the
//!   depth value is nearest to the camera"), so the edge moves with the
//!   object.
//! - **Neighbourhood clipping.** The history is clipped, in YCoCg
//!   ([`rgb_to_ycocg`]; Karis: the box is tighter along luma), toward the
//!   centre of the box `mean ± γ·σ` of the current 3×3 neighbourhood's
//!   colours (Salvi's variance clipping, [`clip_towards`]), stretched to hold
//!   the pixel's own current colour (else a one-pixel feature, an outlier
//!   of its neighbourhood, would lose its history every frame), so a history
//!   that the current frame contradicts (a disocclusion, a moving shadow) is
//!   pulled back to what the current neighbourhood can hold instead of
//!   ghosting.
//! - **Resolve space.** Karis clips and blends on
//!   `T(c) = c / (1 + luma(c))` of the exposed colour ([`tonemap`], his
//!   reversible tone map), mapping the result back ([`tonemap_inverse`]):
//!   a sample beside an HDR highlight weighs what it weighs on screen, so the
//!   edge is as smooth after tone mapping as a box filter of the displayed
//!   samples would make it ([`TaaParams::tone_mapped`]). It is also biased:
//!   a mean of `T` is darker than the mean of the radiances (the average of
//!   0.2 and 0.6 resolves to 0.37, not 0.4), so a still camera does not
//!   converge to the box filter a supersampled reference computes. The
//!   default is therefore the linear resolve, and the tone-mapped one is a
//!   choice (with an exposure) for HDR content; the report measures both.
//! - **Blend.** `out = lerp(history, current, α)` with
//!   `α = max(1 / (n + 1), α_min)`, `n` the frames in the history
//!   ([`TaaParams::history_frames`]): a running mean right after a reset (so a
//!   still camera converges to the mean of the jittered samples, the box
//!   filter supersampling computes) that becomes an exponential average of
//!   weight `α_min` (Karis' 0.04–0.1; here `1/16` by default).
//!
//! A reset (a camera cut) is `history_frames = 0`: the pixel is the current
//! sample.
//!
//! # Engine conventions
//!
//! [`TaaParams::motion_scale`] multiplies the host's vectors, component by
//! component, into pixels, current minus previous, `+y` down (the default
//! `(1, 1)` is that convention itself):
//!
//! - **Bevy** (`MotionVectorPrepass`): "stored in the range -1,1, with +x
//!   right and +y down. A value of (1.0,1.0) indicates a pixel moved from the
//!   top left corner to the bottom right corner of the screen", i.e. UV units
//!   (the whole image is 1), current minus previous (Bevy's prepass writes
//!   `(clip − previous_clip) · (0.5, −0.5)`, and its TAA reads the history at
//!   `uv − motion_vector`): `motion_scale = (width, height)`. Bevy's depth
//!   prepass is reversed Z (1 at the near plane, 0 at infinity):
//!   [`DepthDilation::NearestLargest`].
//! - **AMD FSR2**: motion vectors "encode the motion from a pixel in the
//!   current frame to the position of that same pixel in the previous
//!   frame", in pixels (`<-width, -height>..<width, height>`), after its
//!   `motionVectorScale`: previous minus current, so
//!   `motion_scale = −motionVectorScale`, `(−1, −1)` for a buffer FSR2 reads
//!   with scale 1. Its depth is reversed Z with `FFX_FSR2_ENABLE_DEPTH_INVERTED`
//!   ([`DepthDilation::NearestLargest`]), standard Z otherwise
//!   ([`DepthDilation::NearestSmallest`]).
//!
//! ```
//! use glam::{Vec2, Vec3};
//! use subcone_kernels::taa::{jitter, resolve_pixel, TaaParams};
//!
//! // Halton (2, 3): the first phase is (1/2, 1/3) − 1/2.
//! assert_eq!(jitter(0, 16), Vec2::new(0.0, 1.0 / 3.0 - 0.5));
//! // A grey image and a history of the same grey resolve to that grey.
//! let grey = |_: i32, _: i32| Vec3::splat(0.5);
//! let p = TaaParams::new((8, 8)).with_history_frames(3);
//! let out = resolve_pixel(&grey, &grey, (4, 4), Vec2::ZERO, &p);
//! assert!((out - Vec3::splat(0.5)).abs().max_element() < 1e-6);
//! ```

use glam::{Vec2, Vec3};

/// The WGSL mirror of this module (same names with a `subcone_` prefix;
/// the pixel reads the current frame and the history through hooks
/// `taa_current(x: i32, y: i32) -> vec3<f32>` and
/// `taa_history(x: i32, y: i32) -> vec3<f32>` the including shader defines,
/// as [`resolve_pixel`]'s `current` and `history`). Needs
/// [`crate::wgsl::PARAMS`].
pub const WGSL: &str = include_str!("taa.wgsl");

/// The WGSL mirror of [`dilated_motion`] (`subcone_taa_dilated_motion`),
/// for a shader that has a depth buffer: it reads the motion vectors and
/// depths through hooks `taa_motion(x: i32, y: i32) -> vec2<f32>` and
/// `taa_depth(x: i32, y: i32) -> f32` the including shader defines (as
/// [`dilated_motion`]'s `motion` and `depth`). Needs
/// [`crate::wgsl::PARAMS`].
pub const DILATION_WGSL: &str = include_str!("taa_dilation.wgsl");

/// Jitter phases Karis' design uses.
pub const PHASES_KARIS: u32 = 8;
/// Jitter phases that resolve a still image on as many positions as ssaa16.
pub const PHASES_FINE: u32 = 16;

/// The Rec. 709 luma weights of [`tonemap`] (linear RGB): the SRAA
/// tone-mapped resolve's.
pub const LUMA: Vec3 = crate::sraa::RESOLVE_LUMA;

/// Variance clipping's `γ` (Salvi 2016: 1 is tight, and less ghosting; more
/// lets the history keep more of the sub-pixel detail it gathered).
pub const CLIP_GAMMA: f32 = 1.25;

/// The smallest weight of the current frame (`α_min`): the history's
/// exponential average after its first `1/α_min − 1` frames.
pub const MIN_CURRENT_WEIGHT: f32 = 1.0 / 16.0;

/// Where a TAA resolve clips and blends ([`TaaParams::tone_mapped`]): the
/// SRAA resolve's choice, one type for both (linear radiance by default, or
/// Karis' tone-mapped space with the display's exposure).
pub use crate::sraa::ResolveSpace;

/// A TAA sequence's settings, checked in one place for every form that
/// runs one (`subcone_scene::temporal::TaaConfig`,
/// `subcone_passes::TaaPassDesc`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaaSettings {
    /// Jitter phases of [`jitter`]: 8 ([`PHASES_KARIS`]) or 16
    /// ([`PHASES_FINE`], the default); at least 1.
    pub phases: u32,
    /// Where the resolve clips and blends ([`ResolveSpace::Linear`] by
    /// default).
    pub space: ResolveSpace,
    /// The smallest weight of the current frame, in `(0, 1]`
    /// ([`MIN_CURRENT_WEIGHT`]).
    pub min_current_weight: f32,
    /// Variance clipping's `γ`, non-negative and finite ([`CLIP_GAMMA`]).
    pub clip_gamma: f32,
    /// Closest-depth motion dilation ([`dilated_motion`]):
    /// [`DepthDilation::Off`] by default (no depth is read, and the result
    /// is the resolve without it, bit for bit).
    pub depth_dilation: DepthDilation,
}

impl Default for TaaSettings {
    fn default() -> Self {
        TaaSettings {
            phases: PHASES_FINE,
            space: ResolveSpace::Linear,
            min_current_weight: MIN_CURRENT_WEIGHT,
            clip_gamma: CLIP_GAMMA,
            depth_dilation: DepthDilation::Off,
        }
    }
}

/// Whether a TAA resolve dilates its motion vectors to the closest depth
/// of each pixel's 3×3 neighbourhood ([`dilated_motion`]), and which depth
/// is nearer: the order of the host's depth buffer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthDilation {
    /// Each pixel's own vector; no depth is read.
    #[default]
    Off,
    /// A smaller depth is nearer: view depth (a subcone `Frame::depth`),
    /// linear distances, or standard `[0, 1]` device depth (0 at the near
    /// plane).
    NearestSmallest,
    /// A larger depth is nearer: reversed-Z device depth (1 at the near
    /// plane, 0 at infinity), as Bevy's depth prepass and FSR2 with
    /// `FFX_FSR2_ENABLE_DEPTH_INVERTED` have it.
    NearestLargest,
}

impl DepthDilation {
    /// The code [`TaaParams::depth_dilation`] holds: 0 off, 1
    /// [`Self::NearestSmallest`], 2 [`Self::NearestLargest`].
    pub const fn code(self) -> u32 {
        match self {
            DepthDilation::Off => 0,
            DepthDilation::NearestSmallest => 1,
            DepthDilation::NearestLargest => 2,
        }
    }

    /// The mode of a [`TaaParams::depth_dilation`] code; any code but 1 and
    /// 2 is off.
    pub const fn from_code(code: u32) -> Self {
        match code {
            1 => DepthDilation::NearestSmallest,
            2 => DepthDilation::NearestLargest,
            _ => DepthDilation::Off,
        }
    }

    /// Whether a depth buffer is read.
    pub const fn is_on(self) -> bool {
        !matches!(self, DepthDilation::Off)
    }
}

/// Why [`TaaSettings`] are refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TaaSettingsError {
    /// No jitter phase.
    NoPhases,
    /// A tone-mapped resolve's exposure that is not positive and finite.
    Exposure(f32),
    /// A smallest current weight outside `(0, 1]`.
    MinCurrentWeight(f32),
    /// A clip `γ` that is negative or not finite.
    ClipGamma(f32),
}

impl core::fmt::Display for TaaSettingsError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TaaSettingsError::NoPhases => f.write_str("at least one jitter phase"),
            TaaSettingsError::Exposure(e) => write!(f, "exposure {e} must be positive and finite"),
            TaaSettingsError::MinCurrentWeight(w) => {
                write!(
                    f,
                    "the current frame's smallest weight {w} must be in (0, 1]"
                )
            }
            TaaSettingsError::ClipGamma(g) => {
                write!(f, "clip gamma {g} must be non-negative and finite")
            }
        }
    }
}

impl TaaSettings {
    /// Check every setting against its domain.
    pub fn validate(&self) -> Result<(), TaaSettingsError> {
        if self.phases == 0 {
            return Err(TaaSettingsError::NoPhases);
        }
        if let ResolveSpace::ToneMapped { exposure } = self.space {
            if !self.space.is_valid() {
                return Err(TaaSettingsError::Exposure(exposure));
            }
        }
        if !(self.min_current_weight > 0.0 && self.min_current_weight <= 1.0) {
            return Err(TaaSettingsError::MinCurrentWeight(self.min_current_weight));
        }
        if !(self.clip_gamma >= 0.0 && self.clip_gamma.is_finite()) {
            return Err(TaaSettingsError::ClipGamma(self.clip_gamma));
        }
        Ok(())
    }

    /// The resolve's parameters for a `size` frame with `history_frames`
    /// frames in its history.
    pub const fn params(&self, size: (u32, u32), history_frames: u32) -> TaaParams {
        let mut p = TaaParams::new(size)
            .with_history_frames(history_frames)
            .with_space(self.space);
        p.min_current_weight = self.min_current_weight;
        p.clip_gamma = self.clip_gamma;
        p.with_depth_dilation(self.depth_dilation)
    }

    /// Frame `frame`'s jitter over these phases ([`jitter`]).
    pub fn jitter(&self, frame: u32) -> Vec2 {
        jitter(frame, self.phases)
    }
}

/// What one TAA resolve runs with; `#[repr(C)]`, 48 bytes, uploaded
/// unchanged (`subcone_TaaParams` in WGSL).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct TaaParams {
    /// Exposure the tone map of the resolve applies (a colour `c` is seen
    /// as `c · exposure`); positive and finite, anything else reads as 1.
    pub exposure: f32,
    /// `α_min`, the smallest weight of the current frame, in `(0, 1]`;
    /// values outside are clamped into it (NaN reads as 1).
    pub min_current_weight: f32,
    /// Variance clipping's `γ`, non-negative (NaN or negative reads as 0:
    /// the box is the neighbourhood's mean and the current colour; values
    /// above 10⁶ read as 10⁶).
    pub clip_gamma: f32,
    /// Frames the history holds: 0 after a reset (the output is the
    /// current frame).
    pub history_frames: u32,
    /// Image width in pixels (0 reads as 1).
    pub width: u32,
    /// Image height in pixels (0 reads as 1).
    pub height: u32,
    /// 1: clip and blend in Karis' tone-mapped space ([`tonemap`] at
    /// [`Self::exposure`]); 0 (any other value): in linear radiance, where
    /// a still camera's running mean is the box filter supersampling
    /// computes.
    pub tone_mapped: u32,
    /// Closest-depth motion dilation ([`DepthDilation::code`]): 0 off (the
    /// zero a host wrote here when this was padding), 1 a smaller depth is
    /// nearer, 2 a larger one is; any other value is off. Read only where
    /// a depth buffer is ([`dilated_motion`]).
    pub depth_dilation: u32,
    /// What each motion vector is multiplied by, component by component, to
    /// be pixels, current minus previous, `+y` down: `(1, 1)` for such
    /// vectors, `(width, height)` for Bevy's, `(−1, −1)` for FSR2's pixel
    /// vectors (see the [module docs](self#engine-conventions)). A
    /// component that is 0 or not finite reads as 1 (so a zero-filled
    /// struct reads vectors in pixels).
    pub motion_scale: [f32; 2],
    /// Padding to 16 bytes; zero.
    pub _pad: [u32; 2],
}

impl TaaParams {
    /// The defaults for a `width × height` image, right after a reset: a
    /// linear resolve, [`MIN_CURRENT_WEIGHT`], [`CLIP_GAMMA`] (exposure 1,
    /// read only by a tone-mapped resolve).
    pub const fn new((width, height): (u32, u32)) -> Self {
        TaaParams {
            exposure: 1.0,
            min_current_weight: MIN_CURRENT_WEIGHT,
            clip_gamma: CLIP_GAMMA,
            history_frames: 0,
            width,
            height,
            tone_mapped: 0,
            depth_dilation: 0,
            motion_scale: [1.0, 1.0],
            _pad: [0; 2],
        }
    }

    /// The same parameters with motion vectors multiplied by `scale`
    /// ([`Self::motion_scale`]).
    pub const fn with_motion_scale(mut self, scale: [f32; 2]) -> Self {
        self.motion_scale = scale;
        self
    }

    /// The same parameters dilating motion as `dilation` says
    /// ([`Self::depth_dilation`]).
    pub const fn with_depth_dilation(mut self, dilation: DepthDilation) -> Self {
        self.depth_dilation = dilation.code();
        self
    }

    /// The motion scale in effect: [`Self::motion_scale`], each component
    /// that is 0 or not finite read as 1.
    pub fn motion_scale(&self) -> Vec2 {
        let f = |s: f32| if s != 0.0 && s.is_finite() { s } else { 1.0 };
        Vec2::new(f(self.motion_scale[0]), f(self.motion_scale[1]))
    }

    /// The same parameters resolving in `space`.
    pub const fn with_space(mut self, space: ResolveSpace) -> Self {
        match space {
            ResolveSpace::Linear => {
                self.tone_mapped = 0;
                self.exposure = 1.0;
            }
            ResolveSpace::ToneMapped { exposure } => {
                self.tone_mapped = 1;
                self.exposure = exposure;
            }
        }
        self
    }

    /// The same parameters with `n` frames in the history.
    pub const fn with_history_frames(mut self, n: u32) -> Self {
        self.history_frames = n;
        self
    }

    /// The exposure in effect: [`Self::exposure`], or 1 outside its domain.
    pub fn exposure(&self) -> f32 {
        if self.exposure > 0.0 && self.exposure.is_finite() {
            self.exposure
        } else {
            1.0
        }
    }

    /// The current frame's weight `α = max(1 / (n + 1), α_min)`, in
    /// `(0, 1]`: 1 right after a reset.
    pub fn current_weight(&self) -> f32 {
        let min = if self.min_current_weight > 0.0 {
            self.min_current_weight.min(1.0)
        } else if self.min_current_weight.is_nan() {
            1.0
        } else {
            // Zero or negative: the weight a never-ending mean would reach.
            f32::MIN_POSITIVE
        };
        let mean = 1.0 / (self.history_frames as f32 + 1.0);
        mean.max(min)
    }
}

/// The radical inverse of `index` in `base` (the Halton sequence's
/// coordinate), in `[0, 1)`; a base below 2 gives 0.
pub fn halton(mut index: u32, base: u32) -> f32 {
    if base < 2 {
        return 0.0;
    }
    let inv = 1.0 / base as f32;
    let (mut f, mut r) = (1.0f32, 0.0f32);
    while index > 0 {
        f *= inv;
        r += f * (index % base) as f32;
        index /= base;
    }
    r
}

/// Frame `frame`'s sub-pixel jitter in pixels, in `(−½, ½)²`: the Halton
/// (2, 3) point of index `frame mod phases + 1` minus `½` (Karis 2014; index
/// 0 of the sequence is the origin, which would put every cycle's first
/// sample on a pixel corner). `phases` 0 reads as 1.
pub fn jitter(frame: u32, phases: u32) -> Vec2 {
    let i = frame % phases.max(1) + 1;
    Vec2::new(halton(i, 2), halton(i, 3)) - Vec2::splat(0.5)
}

/// SRAA under TAA (`sraa-rt+taa`): frame `frame`'s jitter, which moves
/// SRAA's whole pattern (the shaded sample at `shaded_offset` from the pixel
/// centre, [`crate::sraa::SraaParams::shaded_offset`], and the four geometric
/// subsamples) so that the shaded sample lands where geometric subsample
/// `frame mod 4` ([`crate::sraa::SUBPIXEL_OFFSETS`]) of the still pattern
/// lies. Over four frames every subsample position of the rotated grid is
/// shaded once, as SMAA T2x alternates its subsample indices from frame to
/// frame; the geometric subsamples move with it, so four frames trace sixteen
/// geometric positions.
pub fn subsample_rotation(frame: u32, shaded_offset: Vec2) -> Vec2 {
    crate::sraa::SUBPIXEL_OFFSETS[(frame % 4) as usize] - shaded_offset
}

/// Luma of a linear colour ([`LUMA`]).
#[inline]
pub fn luma(c: Vec3) -> f32 {
    c.dot(LUMA)
}

/// A colour made safe for the resolve: each non-finite or negative channel
/// becomes 0 (radiance is never negative; a NaN must not spread through the
/// history).
#[inline]
pub fn sanitize(c: Vec3) -> Vec3 {
    let f = |x: f32| if x > 0.0 && x.is_finite() { x } else { 0.0 };
    Vec3::new(f(c.x), f(c.y), f(c.z))
}

/// Karis' reversible tone map of the exposed colour,
/// `T(c) = c·e / (1 + luma(c·e))`, for a [`sanitize`]d `c`: every channel of
/// the result has luma below 1, so [`tonemap_inverse`] undoes it.
#[inline]
pub fn tonemap(c: Vec3, exposure: f32) -> Vec3 {
    let c = c * exposure;
    c / (1.0 + luma(c))
}

/// The inverse of [`tonemap`]: `t / (1 − luma(t)) / e`. A `t` of luma 1 or
/// more (never a tone-mapped colour, but a clipped or filtered one may get
/// near) is read at luma `1 − 2⁻¹⁶`, so the result stays finite.
#[inline]
pub fn tonemap_inverse(t: Vec3, exposure: f32) -> Vec3 {
    let d = (1.0 - luma(t)).max(1.0 / 65536.0);
    t / d / exposure
}

/// A colour in the resolve's space: [`tonemap`] at the exposure in effect
/// when `params.tone_mapped == 1`, itself otherwise.
#[inline]
pub fn to_resolve_space(c: Vec3, params: &TaaParams) -> Vec3 {
    if params.tone_mapped == 1 {
        tonemap(c, params.exposure())
    } else {
        c
    }
}

/// The inverse of [`to_resolve_space`].
#[inline]
pub fn from_resolve_space(t: Vec3, params: &TaaParams) -> Vec3 {
    if params.tone_mapped == 1 {
        tonemap_inverse(t, params.exposure())
    } else {
        t
    }
}

/// RGB to YCoCg (Malvar and Sullivan's transform, the one Karis clips in):
/// `Y = R/4 + G/2 + B/4`, `Co = R/2 − B/2`, `Cg = −R/4 + G/2 − B/4`.
#[inline]
pub fn rgb_to_ycocg(c: Vec3) -> Vec3 {
    Vec3::new(
        0.25 * c.x + 0.5 * c.y + 0.25 * c.z,
        0.5 * c.x - 0.5 * c.z,
        -0.25 * c.x + 0.5 * c.y - 0.25 * c.z,
    )
}

/// YCoCg to RGB, the inverse of [`rgb_to_ycocg`].
#[inline]
pub fn ycocg_to_rgb(c: Vec3) -> Vec3 {
    Vec3::new(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z)
}

/// The history `h` clipped toward the box centre `centre` against the box
/// `centre ± extent` (Salvi 2016; the clip of Playdead's INSIDE TAA): where
/// the segment from the centre to `h` leaves the box, the point where it
/// leaves; `h` itself inside. An extent component of 0 (or NaN) clips that
/// axis to the centre.
#[inline]
pub fn clip_towards(h: Vec3, centre: Vec3, extent: Vec3) -> Vec3 {
    let v = h - centre;
    let axis = |v: f32, e: f32| {
        if e > 0.0 {
            (v / e).abs()
        } else if v == 0.0 {
            0.0
        } else {
            f32::INFINITY
        }
    };
    let m = axis(v.x, extent.x)
        .max(axis(v.y, extent.y))
        .max(axis(v.z, extent.z));
    if m > 1.0 {
        centre + v / m
    } else {
        h
    }
}

/// The 1D Catmull-Rom weights of the four taps at `−1, 0, 1, 2` around a
/// sample at fraction `t ∈ [0, 1)` past tap 0 (they sum to 1).
#[inline]
pub fn catmull_rom_weights(t: f32) -> [f32; 4] {
    let t2 = t * t;
    let t3 = t2 * t;
    [
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    ]
}

/// The history at image point `p` (pixels; pixel `(i, j)`'s centre is
/// `(i + ½, j + ½)`), Catmull-Rom filtered over 4×4 pixels, taps clamped to
/// the image, [`sanitize`]d (the filter's negative lobes can ring below 0);
/// `None` when `p` is outside the image or not finite (the surface was not
/// on screen: no history).
pub fn sample_history<F: Fn(i32, i32) -> Vec3>(
    history: &F,
    p: Vec2,
    (w, h): (u32, u32),
) -> Option<Vec3> {
    let (w, h) = (w.max(1) as i32, h.max(1) as i32);
    if !(p.x >= 0.0 && p.y >= 0.0 && p.x <= w as f32 && p.y <= h as f32) {
        return None;
    }
    let q = p - Vec2::splat(0.5);
    let (fx, fy) = (libm::floorf(q.x), libm::floorf(q.y));
    let (wx, wy) = (catmull_rom_weights(q.x - fx), catmull_rom_weights(q.y - fy));
    let (x0, y0) = (fx as i32 - 1, fy as i32 - 1);
    let mut sum = Vec3::ZERO;
    for (j, wy) in wy.iter().enumerate() {
        let y = (y0 + j as i32).clamp(0, h - 1);
        let mut row = Vec3::ZERO;
        for (i, wx) in wx.iter().enumerate() {
            let x = (x0 + i as i32).clamp(0, w - 1);
            row += *wx * sanitize(history(x, y));
        }
        sum += *wy * row;
    }
    Some(sanitize(sum))
}

/// One pixel of the TAA resolve (Karis 2014 with Salvi's variance clipping;
/// see the module docs), in linear radiance.
///
/// `current(x, y)` is this frame's (jittered) colour of a pixel and
/// `history(x, y)` the previous output's; both are called only with
/// coordinates inside the image, and every colour they return is
/// [`sanitize`]d. `(x, y)` is the pixel (clamped into the image),
/// `velocity` its motion vector as the host gives it (its own, or the one
/// [`dilated_motion`] picks), which times [`TaaParams::motion_scale`] is
/// its motion in pixels, current minus previous (a non-finite product
/// means no history). With `history_frames == 0`, or when the
/// reprojected point is off the previous image, the result is the
/// sanitised current colour. The result is finite and non-negative for any
/// input.
pub fn resolve_pixel<C: Fn(i32, i32) -> Vec3, H: Fn(i32, i32) -> Vec3>(
    current: &C,
    history: &H,
    (x, y): (i32, i32),
    velocity: Vec2,
    params: &TaaParams,
) -> Vec3 {
    let (w, h) = (params.width.max(1) as i32, params.height.max(1) as i32);
    let (x, y) = (x.clamp(0, w - 1), y.clamp(0, h - 1));
    let centre = sanitize(current(x, y));
    if params.history_frames == 0 {
        return centre;
    }
    // A scale of exactly 1 (the default) leaves the vector's bits as they
    // are: the resolve of pixel vectors is what it was before the scale.
    let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) - velocity * params.motion_scale();
    let Some(past) = sample_history(history, p, (w as u32, h as u32)) else {
        return centre;
    };
    // The 3×3 neighbourhood's mean and standard deviation, in tone-mapped
    // YCoCg.
    let (mut m1, mut m2) = (Vec3::ZERO, Vec3::ZERO);
    for dy in -1..=1 {
        for dx in -1..=1 {
            let c = if (dx, dy) == (0, 0) {
                centre
            } else {
                sanitize(current((x + dx).clamp(0, w - 1), (y + dy).clamp(0, h - 1)))
            };
            let t = rgb_to_ycocg(to_resolve_space(c, params));
            m1 += t;
            m2 += t * t;
        }
    }
    let mean = m1 / 9.0;
    let var = (m2 / 9.0 - mean * mean).max(Vec3::ZERO);
    let sigma = Vec3::new(
        crate::math::sqrt(var.x),
        crate::math::sqrt(var.y),
        crate::math::sqrt(var.z),
    );
    // NaN or negative reads as 0; +inf as a box wider than any colour.
    let gamma = if params.clip_gamma > 0.0 {
        params.clip_gamma.min(1e6)
    } else {
        0.0
    };
    let now = rgb_to_ycocg(to_resolve_space(centre, params));
    // Salvi's box, stretched to hold the current colour: a pixel that is an
    // outlier of its own neighbourhood (a thin feature) keeps a history of
    // its own colour instead of losing it every frame.
    let lo = (mean - gamma * sigma).min(now);
    let hi = (mean + gamma * sigma).max(now);
    let past = rgb_to_ycocg(to_resolve_space(past, params));
    let clipped = clip_towards(past, 0.5 * (lo + hi), 0.5 * (hi - lo));
    let a = params.current_weight();
    let out = clipped + (now - clipped) * a;
    sanitize(from_resolve_space(ycocg_to_rgb(out), params))
}

/// How near a depth is under dilation `code` ([`TaaParams::depth_dilation`]):
/// larger is nearer. A depth that is not finite (nothing hit: a view depth
/// of `+∞`; or a broken buffer) is never nearer than any other.
#[inline]
fn nearness(depth: f32, code: u32) -> f32 {
    if !depth.is_finite() {
        f32::NEG_INFINITY
    } else if code == DepthDilation::NearestLargest.code() {
        depth
    } else {
        -depth
    }
}

/// The motion vector the resolve uses at pixel `(x, y)` (clamped into the
/// image): with [`TaaParams::depth_dilation`] on, the vector of the pixel
/// whose depth is nearest in the 3×3 neighbourhood (taps clamped to the
/// image), the pixel's own on a tie (the neighbours are visited row by row
/// and only a strictly nearer one wins); with it off, the pixel's own
/// vector, and `depth` is not called.
///
/// Why: Karis 2014 takes the velocity of the closest depth in the 3×3
/// neighbourhood so that the silhouette of a moving object moves with it (a
/// background pixel next to it would otherwise keep the history the object
/// left there), and FSR2's "Reconstruct & dilate" stage dilates its motion
/// vectors to the nearest depth of the same neighbourhood before it
/// reprojects anything.
///
/// `motion(x, y)` and `depth(x, y)` are the host's buffers, called only
/// with coordinates inside the image. Any depth is accepted: a depth that
/// is not finite is never the nearest (all of them not finite: the pixel's
/// own vector). The vector is returned as the host gave it (the resolve
/// scales it, [`resolve_pixel`]).
pub fn dilated_motion<M: Fn(i32, i32) -> Vec2, D: Fn(i32, i32) -> f32>(
    motion: &M,
    depth: &D,
    (x, y): (i32, i32),
    params: &TaaParams,
) -> Vec2 {
    let (w, h) = (params.width.max(1) as i32, params.height.max(1) as i32);
    let (x, y) = (x.clamp(0, w - 1), y.clamp(0, h - 1));
    let code = params.depth_dilation;
    if !DepthDilation::from_code(code).is_on() {
        return motion(x, y);
    }
    let mut best = (x, y);
    let mut near = nearness(depth(x, y), code);
    for dy in -1..=1 {
        for dx in -1..=1 {
            if (dx, dy) == (0, 0) {
                continue;
            }
            let (nx, ny) = ((x + dx).clamp(0, w - 1), (y + dy).clamp(0, h - 1));
            let n = nearness(depth(nx, ny), code);
            if n > near {
                near = n;
                best = (nx, ny);
            }
        }
    }
    motion(best.0, best.1)
}
