//! The hit-group logic of CTSS (Algorithm 1, §3.3, §3.6) as a pure stepper, plus
//! [`trace`], which drives it with closures, and [`sphere_trace`], the NoAA
//! baseline with the same cone-based hit threshold.
//!
//! The caller owns the SDF and the shading. It asks the [`ConeStepper`] where to
//! evaluate ([`ConeStepper::t`]), feeds the distance back ([`ConeStepper::advance`])
//! and gets an [`Event`]: march on, sample a hit group, or stop. For a sample it
//! computes the normal at the sample point and hands the projected normal to
//! [`ConeStepper::record`], which makes the visibility mask, correlates it with
//! the pixel's global mask `M` and returns the sample's weight.
//! For semi-transparent surfaces, [`ConeStepper::record_alpha`] takes the
//! surface's opacity and composites into the `K` masks of §5.3
//! ([`crate::transparency`]) instead; [`trace_translucent`] drives it.
//!
//! ```
//! use glam::Vec3;
//! use subcone_kernels::ctss::{trace, CtssParams};
//!
//! // A unit sphere 5 units in front of the camera, seen by a pixel whose ray
//! // grazes its silhouette.
//! let sphere = |p: Vec3| (p - Vec3::new(0.0, 0.0, 5.0)).length() - 1.0;
//! let normal = |p: Vec3| (p - Vec3::new(0.0, 0.0, 5.0)).normalize();
//! let params = CtssParams::new(0.02);
//! let dir = Vec3::new(0.2, 0.0, 1.0).normalize();
//! let r = trace(&params, Vec3::ZERO, dir, Vec3::X, Vec3::Y, sphere, normal, |_, _| Vec3::ONE, Vec3::ZERO);
//! // The pixel is partly sphere (white), partly background (black).
//! assert!(r.color.x > 0.0 && r.color.x < 1.0, "{:?}", r);
//! ```

/// The WGSL mirror of this module (ConeStepper, with the translucent parts of
/// CTSS §5.3, and sphere_trace_split): same names, the parameter structs of
/// [`crate::wgsl::PARAMS`]; concatenate after `PARAMS`, [`crate::cone::WGSL`],
/// [`crate::mask::WGSL`], [`crate::aggregate::WGSL`] and
/// [`crate::transparency::WGSL`] (see [`crate::wgsl`]).
pub const WGSL: &str = include_str!("ctss.wgsl");

/// The WGSL mirror of [`trace_field`] (with [`march`], [`group_mask`],
/// [`shade_split`] and the §5.3 split kernels [`group_needs_split`],
/// [`split_weights`], [`split_direction`], [`split_trace_params`],
/// [`split_group`], [`coarse_normal_step`], [`normal_step`],
/// [`tetra_normal`]): `subcone_ctss_trace(params, origin, dir, right, up,
/// background) -> subcone_CtssTraceResult` (colour, samples, steps, coverage,
/// stop code). Concatenate after [`WGSL`] (which needs `PARAMS`, `cone`,
/// `mask` and `aggregate`).
///
/// The scene is the including shader's, through hooks it defines (the
/// [`ConeField`] trait and `trace_field`'s `shade` closure):
///
/// - `fn subcone_field(p: vec3<f32>) -> vec3<f32>`: [`ConeField::sample`] as
///   (signed distance, safe step `≤` distance, object id). The id is an exact
///   integer held in an `f32` (every integer below 2²⁴ is exact; a material
///   index, say); a negative or NaN id is [`NO_OBJECT`].
/// - `fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32>`:
///   [`ConeField::normal`] with difference step `h`; `return
///   subcone_tetra_normal(p, h);` is the trait's default ([`tetra_normal`] of
///   `subcone_field`'s distance). It is also the coarse normal of
///   `ctss+edges` ([`ConeField::coarse_normal`]'s default).
/// - `fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32>`:
///   the colour of a surface point seen along `dir`. Work the host counts
///   while shading (shadow rays) goes into a `var<private>` of its own.
/// - `const subcone_CTSS_BATCH: u32` (≥ 1): the hit groups the trace marches
///   ahead of shading them. The groups wait in order and are shaded together,
///   so the lanes of a SIMD group march together and shade together: the
///   GPU's bounded form of delayed shading (§5.1). Eq. 6 adds the same terms
///   in the same order whatever the batch, so the result does not depend on
///   it.
///
/// [`WGSL`]'s own hook `ctss_field` (for `subcone_sphere_trace_split`, the
/// NoAA trace) is independent of these: the sub-traces of a split group run
/// on `subcone_field`.
pub const TRACE_WGSL: &str = include_str!("ctss/trace.wgsl");

use crate::math::Euclidean;
use glam::{Vec2, Vec3};

mod trace;
pub use trace::{
    close_group, group_mask, group_normal_depths, march, march_step, normal_step, shade_split,
    split_samples, trace_field, ClosureField, ConeField, FieldSample, GroupHit, PartSample,
    SHEET_PROBE, SHELL_LENGTH,
};

use crate::aggregate::{sample_weight, Aggregate, Weighting};
use crate::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius,
    OcclusionThresholds, OCCLUSION_EPS,
};
use crate::mask::{visibility_mask, MaskPlacement, VisibilityAccumulator};
use crate::transparency::{is_opaque, level_weight, TransparencyAccumulator};

/// `flags` bit: CTSS-R, stop at the first hard hit instead of full occlusion (§4).
pub const FLAG_RELAXED: u32 = 1;
/// `flags` bit: subdivide hit groups whose normal varies across the cone or
/// that are long for their depth, and shade them with extra samples (§5.3,
/// [`group_needs_split`], [`split_group`]). Off by default; both backends
/// (the WGSL twin is [`TRACE_WGSL`]).
pub const FLAG_SPLIT_GROUPS: u32 = 1 << 1;
/// `flags` bit: the paper's hit groups and masks (the `-paper` methods). A
/// group then runs as long as the cone touches any surface, and its mask is
/// the half-plane of its peak occlusion alone. Without it (the default) a
/// group also ends where the nearest object changes
/// ([`ConeStepper::advance_object`]) or where the occlusion rises again after
/// a dip of [`GROUP_DIP`] (a second surface within the cone), and a group
/// whose surface the cone passes through is masked from both of its sides
/// ([`group_mask`]).
pub const FLAG_PAPER: u32 = 1 << 2;

/// Cone coverage (§5.1's multiplier of the pixel's cone, eq. 3) of the CTSS
/// methods by default: a cone of radius `0.6·√2/2 ≈ 0.42` pixels instead of
/// the paper's `0.71` (the circle through the pixel's corners, coverage 1,
/// kept by the `-paper` methods). The half-plane mask overestimates how much
/// of the cross-section a curved or small object covers, and a wide cone
/// blurs each edge over more than its pixel; both cost more than the
/// narrower cone loses at the pixel's corners. Swept over 0.5–1 on the
/// `primitives` and `random-box` scenes at 96×64 and 320×180, against
/// `ssaa64`/`ssaa256`: 0.6 gave the least silhouette error on both scenes at
/// both sizes.
pub const CONE_COVERAGE: f32 = 0.6;

/// Fall and rise of the cone occlusion inside a hit group, below its peak
/// and then above the lowest value since, that ends the group and opens a
/// new one (beyond the paper, off with [`FLAG_PAPER`]): the cone has passed
/// one surface and met another one behind it.
pub const GROUP_DIP: f32 = 0.1;

/// Parameters of a CTSS trace.
///
/// `#[repr(C)]`, 48 bytes, only `f32`/`u32` fields (explicit padding): uploaded
/// unchanged as a uniform by GPU backends.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct CtssParams {
    /// `tan θ` of the pixel's cone (eq. 3, [`cone_tan_theta`](crate::cone::cone_tan_theta)).
    pub tan_theta: f32,
    /// Minimum step factor α of `s_min = α·R_c` (§3.1; paper: 0.5).
    pub alpha: f32,
    /// ε of the occlusion thresholds (§3.2; authors: 0.01).
    pub eps: f32,
    /// First depth evaluated.
    pub t_min: f32,
    /// Depth at which the ray leaves the scene.
    pub t_max: f32,
    /// The authors' minimum sample weight (0.01); ours is 0, see
    /// [`sample_weight`].
    pub min_sample_weight: f32,
    /// Step budget: no trace takes more SDF evaluations than this.
    pub max_steps: u32,
    /// Sample cap (the authors use 8, `CTSS_NUM_SAMPLES`).
    pub max_samples: u32,
    /// Visibility threshold k (§5.1): stop once `bitCount(M) ≥ k`. 32 = off.
    pub visibility_k: u32,
    /// Bit 0: [`FLAG_RELAXED`]. Bit 1: [`FLAG_SPLIT_GROUPS`]. Bit 2: [`FLAG_PAPER`]. Bits 8..16: [`MaskPlacement`]. Bits 16..24: [`Weighting`].
    pub flags: u32,
    /// Padding to a multiple of 16 bytes (WGSL uniform layout).
    pub _pad: [u32; 2],
}

impl CtssParams {
    /// The paper's configuration for a cone of `tan_theta`: α = 0.5, ε = 0.01, up
    /// to 8 samples, k = 32, visibility weights, the derived mask placement, no
    /// minimum sample weight, `t` in `[0, 10⁴]`, 1024 steps.
    pub const fn new(tan_theta: f32) -> Self {
        Self {
            tan_theta,
            alpha: 0.5,
            eps: OCCLUSION_EPS,
            t_min: 0.0,
            t_max: 1.0e4,
            min_sample_weight: 0.0,
            max_steps: 1024,
            max_samples: 8,
            visibility_k: 32,
            flags: 0,
            _pad: [0; 2],
        }
    }

    /// CTSS-R (§4): terminate at the first hard hit (half cone occlusion).
    pub const fn relaxed(self, on: bool) -> Self {
        self.with_flag(FLAG_RELAXED, on)
    }

    /// Subdivide hit groups at internal edges (§5.3, [`FLAG_SPLIT_GROUPS`]).
    pub const fn with_split_groups(self, on: bool) -> Self {
        self.with_flag(FLAG_SPLIT_GROUPS, on)
    }

    /// The paper's hit groups and masks ([`FLAG_PAPER`]).
    pub const fn paper(self, on: bool) -> Self {
        self.with_flag(FLAG_PAPER, on)
    }

    /// `flag` (one of the `FLAG_*` bits) set or cleared, the other bits kept.
    const fn with_flag(mut self, flag: u32, on: bool) -> Self {
        self.flags = if on {
            self.flags | flag
        } else {
            self.flags & !flag
        };
        self
    }

    /// Whether the paper's hit groups and masks are on ([`FLAG_PAPER`]).
    pub const fn is_paper(&self) -> bool {
        self.flags & FLAG_PAPER != 0
    }

    /// Whether hit groups are subdivided ([`FLAG_SPLIT_GROUPS`]).
    pub const fn splits_groups(&self) -> bool {
        self.flags & FLAG_SPLIT_GROUPS != 0
    }

    /// Choose the mask placement.
    pub const fn with_placement(mut self, p: MaskPlacement) -> Self {
        self.flags = (self.flags & !0xff00) | ((p as u32) << 8);
        self
    }

    /// Choose the sample weighting.
    pub const fn with_weighting(mut self, w: Weighting) -> Self {
        self.flags = (self.flags & !0xff0000) | ((w as u32) << 16);
        self
    }

    /// Set the visibility threshold k (clamped to 1..=32).
    pub const fn with_visibility_k(mut self, k: u32) -> Self {
        self.visibility_k = if k == 0 {
            1
        } else if k > 32 {
            32
        } else {
            k
        };
        self
    }

    /// Set the depth range.
    pub const fn with_range(mut self, t_min: f32, t_max: f32) -> Self {
        self.t_min = t_min;
        self.t_max = t_max;
        self
    }

    /// Set the step budget.
    pub const fn with_max_steps(mut self, n: u32) -> Self {
        self.max_steps = n;
        self
    }

    /// The authors' code's choices where they differ from the paper: the 0.01
    /// minimum sample weight and their mask placement. (Their narrower cone is a
    /// [`PixelFootprint`](crate::cone::PixelFootprint) of the tangent.)
    pub const fn authors_code(self) -> Self {
        let mut s = self.with_placement(MaskPlacement::AuthorsCode);
        s.min_sample_weight = 0.01;
        s
    }

    /// Whether CTSS-R is on.
    pub const fn is_relaxed(&self) -> bool {
        self.flags & FLAG_RELAXED != 0
    }

    /// The mask placement.
    pub const fn placement(&self) -> MaskPlacement {
        MaskPlacement::from_u32((self.flags >> 8) & 0xff)
    }

    /// The weighting.
    pub const fn weighting(&self) -> Weighting {
        Weighting::from_u32((self.flags >> 16) & 0xff)
    }

    /// The thresholds for this ε.
    pub const fn thresholds(&self) -> OcclusionThresholds {
        OcclusionThresholds::with_eps(self.eps)
    }
}

/// Why a trace ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum StopReason {
    /// `ω > 1 − ε`: the cone is fully inside a surface.
    FullOcclusion,
    /// CTSS-R or NoAA: `ω > 0.5 − ε`.
    HardHit,
    /// `bitCount(M) ≥ k`.
    VisibilityThreshold,
    /// The sample cap was reached.
    SampleCap,
    /// `t ≥ t_max`: the ray left the scene.
    MaxDistance,
    /// The step budget ran out.
    StepBudget,
    /// The SDF returned NaN.
    InvalidDistance,
}

impl StopReason {
    /// Whether the pixel is covered by hits alone, so the background gets no
    /// weight: the trace ended on its occlusion rule, or on the visibility
    /// threshold (whose uncovered remainder is unknown, so eq. 6 renormalises
    /// over the hits instead of guessing sky).
    pub const fn covers_pixel(self) -> bool {
        matches!(
            self,
            StopReason::FullOcclusion | StopReason::HardHit | StopReason::VisibilityThreshold
        )
    }
}

/// A hit group to sample (Algorithm 1, lines 15–22).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroupSample {
    /// Where to shade: the backtraced entry (eq. 10) of a soft-only group, or the
    /// backtraced first hard hit (§3.6).
    pub t: f32,
    /// Backtraced entry depth (eq. 10).
    pub t_entry: f32,
    /// Backtraced exit depth (eq. 10 applied to the exit, §3.6), or the depth at
    /// which the group was cut short.
    pub t_exit: f32,
    /// The group's maximum cone occlusion `ω_max` (Algorithm 1, line 12): the
    /// input of the visibility mask.
    pub occlusion: f32,
    /// Depth at which the group's occlusion peaked (where `occlusion` was
    /// measured): where the planar-surface model of the mask holds.
    pub t_occlusion: f32,
    /// Depth of the group's first step in contact with a surface.
    pub t_first: f32,
    /// Depth of the group's last step in contact with a surface: where the
    /// cone leaves it. A surface thinner than the cone shows its far side
    /// here ([`group_mask`]).
    pub t_last: f32,
    /// Whether the group contains a hard hit.
    pub hard: bool,
}

/// What the caller does next.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Event {
    /// Evaluate the SDF at the new [`ConeStepper::t`] and call `advance` again.
    March,
    /// Shade this group at `sample.t`, call [`ConeStepper::record`], then call
    /// `advance` again (it may answer [`Event::Stop`]).
    Sample(GroupSample),
    /// The trace is over.
    Stop(StopReason),
}

#[derive(Clone, Copy, Debug)]
struct Group {
    t_entry: f32,
    t_sample: f32,
    occlusion: f32,
    t_occlusion: f32,
    t_first: f32,
    t_last: f32,
    hard: bool,
    /// Nearest object where the group opened ([`NO_OBJECT`]: not known).
    object: u32,
    /// Lowest occlusion since the peak.
    dip: f32,
}

impl Group {
    /// The group as a sample to shade, its exit at `t_exit` (Algorithm 1,
    /// lines 15–17).
    #[inline(always)]
    fn sample(&self, t_exit: f32) -> GroupSample {
        GroupSample {
            t: self.t_sample,
            t_entry: self.t_entry,
            t_exit,
            occlusion: self.occlusion,
            t_occlusion: self.t_occlusion,
            t_first: self.t_first,
            t_last: self.t_last,
            hard: self.hard,
        }
    }
}

/// One step's cone against the field ([`ConeStepper::advance_object`]).
#[derive(Clone, Copy, Debug)]
struct Contact {
    /// The cone's radius `R_c` at the step (eq. 4).
    rc: f32,
    /// Its occlusion `ω` (eq. 5).
    omega: f32,
    /// A soft hit: `ω > 0 − ε`.
    soft: bool,
    /// A hard hit: `ω > 0.5 − ε`.
    hard: bool,
    /// The occlusion rule ends the trace here: full occlusion, or CTSS-R's
    /// hard hit.
    stop: bool,
}

/// The object id that means no object (not known, never a reason to end a
/// group): the id of [`ConeStepper::advance_split`], and the one "none" of
/// every object id. Rust's [`FieldSample::object`] and the C ABI's
/// `SubconeFieldSample::object` are this `u32`; the WGSL twins declare it
/// as `subcone_NO_OBJECT` (`ctss.wgsl`, checked equal by
/// `subcone-passes`' layout tests); the WGSL field hook `subcone_field`
/// returns the id in an `f32` (its third component), where a negative or
/// NaN value reads as `NO_OBJECT` (`subcone_field_sample` in
/// `ctss/trace.wgsl`).
pub const NO_OBJECT: u32 = u32::MAX;

/// Algorithm 1 as a state machine, generic over nobody's SDF.
///
/// Every trace ends: `t` strictly increases each step ([`advance`]), and after
/// `max_steps` evaluations the stepper stops with [`StopReason::StepBudget`].
#[derive(Clone, Debug)]
pub struct ConeStepper {
    params: CtssParams,
    thresholds: OcclusionThresholds,
    t: f32,
    t_prev: f32,
    d_prev: f32,
    have_prev: bool,
    prev_soft: bool,
    prev_hard: bool,
    group: Option<Group>,
    steps: u32,
    samples: u32,
    mask: VisibilityAccumulator,
    stop: Option<StopReason>,
    /// The `K` masks of §5.3, used instead of `mask` once
    /// [`record_alpha`](ConeStepper::record_alpha) is called.
    layers: TransparencyAccumulator,
    translucent: bool,
    /// Marching through a semi-transparent object after its full occlusion.
    passing: bool,
    /// The step that closed a group on an object change also met the
    /// occlusion rule: the next call samples the new group and stops.
    pending_stop: bool,
}

impl ConeStepper {
    /// Start a trace at `params.t_min`.
    pub fn new(params: &CtssParams) -> Self {
        let t0 = if params.t_min > 0.0 {
            params.t_min
        } else {
            0.0
        };
        Self {
            params: *params,
            thresholds: params.thresholds(),
            t: t0,
            t_prev: t0,
            d_prev: 0.0,
            have_prev: false,
            prev_soft: false,
            prev_hard: false,
            group: None,
            steps: 0,
            samples: 0,
            mask: VisibilityAccumulator::new(),
            stop: None,
            layers: TransparencyAccumulator::new(),
            translucent: false,
            passing: false,
            pending_stop: false,
        }
    }

    /// The depth at which to evaluate the SDF next.
    #[inline]
    pub fn t(&self) -> f32 {
        self.t
    }

    /// SDF evaluations so far.
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Groups sampled so far.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// The pixel's global visibility mask `M`.
    pub fn coverage(&self) -> u32 {
        if self.translucent {
            self.layers.opaque()
        } else {
            self.mask.covered()
        }
    }

    /// The `K` transparency masks (§5.3) of a trace driven through
    /// [`record_alpha`](Self::record_alpha).
    pub fn layers(&self) -> &TransparencyAccumulator {
        &self.layers
    }

    /// The stop reason, once the trace is over (or decided to end).
    ///
    /// A step that closed a group where the object changed and also met the
    /// occlusion rule has decided to end: the next call samples the group it
    /// opened and stops, and `t` no longer moves.
    pub fn stop_reason(&self) -> Option<StopReason> {
        match self.stop {
            None if self.pending_stop => Some(self.occlusion_stop()),
            s => s,
        }
    }

    /// The stop of the occlusion rule: CTSS-R's hard hit or full occlusion.
    fn occlusion_stop(&self) -> StopReason {
        if self.params.is_relaxed() {
            StopReason::HardHit
        } else {
            StopReason::FullOcclusion
        }
    }

    fn end(&mut self, reason: StopReason, t_exit: f32) -> Event {
        self.stop = Some(reason);
        // A group still open when the ray leaves (or the budget runs out) is a
        // surface seen, exit unknown: sample it rather than drop it as the
        // authors' loop does.
        match self.group.take() {
            Some(g) => {
                self.samples += 1;
                Event::Sample(g.sample(t_exit))
            }
            None => Event::Stop(reason),
        }
    }

    /// Feed `d = SDF(o + t·dir)` at `t = self.t()` (Algorithm 1, lines 7–26).
    pub fn advance(&mut self, d: f32) -> Event {
        self.advance_split(d, d)
    }

    /// [`advance`](Self::advance) for fields whose surface distance and safe step
    /// differ: `d` decides occlusion and hit groups, `step` (a bound `≤ d`, e.g.
    /// capped at a repetition cell's walls, the authors' `GRID_TRACE`) decides
    /// how far to march: `t ← t + max(step, α·R_c)`. Guarded fields used for
    /// occlusion make fake soft hits near cell walls; this keeps them out.
    pub fn advance_split(&mut self, d: f32, step: f32) -> Event {
        self.advance_object(d, step, NO_OBJECT)
    }

    /// [`advance_split`](Self::advance_split) with the id of the object
    /// nearest to the evaluated point (e.g. its material). Unless
    /// [`FLAG_PAPER`] is set, a hit group ends where that id changes while the
    /// cone is in contact, and the new object opens a group of its own: one
    /// group, one surface, so a front object's sample never takes the
    /// occlusion of the object behind it (which would extrude the front
    /// object over the pixel). [`NO_OBJECT`] never changes groups.
    #[inline]
    pub fn advance_object(&mut self, d: f32, step: f32, object: u32) -> Event {
        if let Some(event) = self.loop_ends(d) {
            return event;
        }
        self.steps += 1;
        let t = self.t;
        // Lines 9–10: the cone and its occlusion.
        let contact = self.contact(t, d);
        // Lines 11–14: the hit groups.
        let closed = self.close_on_new_surface(t, &contact, object);
        if contact.soft && (!self.prev_soft || closed.is_some()) {
            self.open_group(t, &contact, object, closed.is_some());
        }
        if contact.soft {
            self.extend_group(t, &contact);
        }
        let exit = !contact.soft && self.prev_soft;
        if exit {
            self.passing = false;
        }
        self.prev_soft = contact.soft;
        self.prev_hard = contact.hard;

        // Lines 15–24: sample a group that ended, stop on the rule.
        if let Some(c) = closed {
            return self.sample_closed(c, t, d, step, &contact);
        }
        let event = if exit || contact.stop {
            self.sample_at_exit(t, contact.stop)
        } else {
            Event::March
        };
        self.remember(t, d);
        // Line 26: advance by at least α·R_c.
        if self.stop.is_none() {
            // Through a semi-transparent object's inside, `−d` is a safe step.
            let s = if self.passing && d < 0.0 {
                -d
            } else {
                step.min(d)
            };
            self.t = advance(t, s, self.params.alpha, contact.rc);
        }
        event
    }

    /// The loop's conditions before an evaluation is counted (Algorithm 1,
    /// line 6: `while t < D`, with the step budget, a NaN distance, and the
    /// decisions of earlier steps): the event that ends this call, or `None`
    /// to go on with `d` at `t`.
    #[inline(always)]
    fn loop_ends(&mut self, d: f32) -> Option<Event> {
        if let Some(r) = self.stop {
            return Some(Event::Stop(r));
        }
        if self.pending_stop {
            self.pending_stop = false;
            let reason = self.occlusion_stop();
            let t_exit = backtrace_cone_entry(self.t, self.params.tan_theta);
            return Some(self.end(reason, t_exit));
        }
        let t = self.t;
        if self.steps >= self.params.max_steps {
            return Some(self.end(StopReason::StepBudget, t));
        }
        if !(t < self.params.t_max) {
            return Some(self.end(StopReason::MaxDistance, t));
        }
        if d.is_nan() {
            return Some(self.end(StopReason::InvalidDistance, t));
        }
        None
    }

    /// The cone at `t` against the field's `d` (Algorithm 1, lines 9–11 and
    /// 15's full occlusion): its radius `R_c` (eq. 4), its occlusion `ω`
    /// (eq. 5), and which of the soft-hit, hard-hit and stop thresholds `ω`
    /// exceeds (CTSS-R stops at the hard hit, §4). Passing through a
    /// semi-transparent object (§5.3) holds the stop back, until the distance
    /// outside it shrinks again.
    #[inline(always)]
    fn contact(&mut self, t: f32, d: f32) -> Contact {
        let tan = self.params.tan_theta;
        let rc = cone_radius(t, tan);
        let omega = cone_occlusion(d, rc);
        let th = self.thresholds;
        let soft = omega > th.soft;
        let hard = omega > th.hard;
        let stop_at = if self.params.is_relaxed() {
            th.hard
        } else {
            th.full
        };
        let mut stop = omega > stop_at;
        if self.passing {
            // Inside (or just behind) a semi-transparent object whose full
            // occlusion did not end the trace (`record_alpha`): no stop and no
            // new group until the cone leaves it, or until the distance, outside
            // the object, shrinks again: another surface lies within the cone,
            // and it starts a group of its own here.
            if d > 0.0 && self.have_prev && d < self.d_prev {
                self.passing = false;
                self.prev_soft = false;
                self.prev_hard = false;
            } else {
                stop = false;
            }
        }
        Contact {
            rc,
            omega,
            soft,
            hard,
            stop,
        }
    }

    /// Beyond the paper: one surface per group. A group ends (and a new one
    /// opens here) where the nearest object changes, or where the occlusion
    /// rises by [`GROUP_DIP`] after falling by as much below the group's
    /// peak: the cone has passed one surface and meets another. Returns the
    /// group so closed, exit at `t`, counted as a sample.
    #[inline(always)]
    fn close_on_new_surface(
        &mut self,
        t: f32,
        contact: &Contact,
        object: u32,
    ) -> Option<GroupSample> {
        let omega = contact.omega;
        if !contact.soft || !self.prev_soft || self.params.is_paper() || self.passing {
            return None;
        }
        let g = self.group.as_mut()?;
        g.dip = g.dip.min(omega);
        let other = object != g.object && object != NO_OBJECT && g.object != NO_OBJECT;
        let rises = g.dip < g.occlusion - GROUP_DIP && omega > g.dip + GROUP_DIP;
        if !(other || rises) {
            return None;
        }
        let g = *g;
        self.group = None;
        self.samples += 1;
        self.prev_hard = false;
        self.have_prev = false;
        Some(g.sample(t))
    }

    /// A soft hit's entry opens a hit group (Algorithm 1, lines 13–14), its
    /// sample at the entry backtraced by eq. 10, or, where
    /// [`close_on_new_surface`](Self::close_on_new_surface) just closed the
    /// group before it (`after_close`), at `t`.
    #[inline(always)]
    fn open_group(&mut self, t: f32, contact: &Contact, object: u32, after_close: bool) {
        let te = if after_close {
            t
        } else {
            backtrace_cone_entry(t, self.params.tan_theta)
        };
        self.group = Some(Group {
            t_entry: te,
            t_sample: te,
            occlusion: contact.omega,
            t_occlusion: t,
            t_first: t,
            t_last: t,
            hard: false,
            object,
            dip: contact.omega,
        });
    }

    /// A soft hit inside the open group: its maximum occlusion `ω_max`
    /// (Algorithm 1, line 12) and where it was measured, and at the group's
    /// first hard hit its sample moves there (line 13), backtraced between
    /// the two steps around it (§3.6).
    #[inline(always)]
    fn extend_group(&mut self, t: f32, contact: &Contact) {
        if let Some(g) = self.group.as_mut() {
            g.t_last = t;
            if contact.omega > g.occlusion {
                g.occlusion = contact.omega;
                g.t_occlusion = t;
                g.dip = contact.omega;
            }
            if contact.hard && !self.prev_hard && !g.hard {
                g.hard = true;
                g.t_sample = if self.have_prev {
                    backtrace_hard_hit(self.t_prev, self.d_prev, t)
                } else {
                    t
                };
            }
        }
    }

    /// The step that closed group `closed` on a new surface: the closed group
    /// is sampled now; the one opened at this step is sampled when it ends
    /// (its stop, if this step stops, waits for the next call: `end` samples
    /// an open group).
    #[inline(always)]
    fn sample_closed(
        &mut self,
        closed: GroupSample,
        t: f32,
        d: f32,
        step: f32,
        contact: &Contact,
    ) -> Event {
        self.remember(t, d);
        if self.samples >= self.params.max_samples {
            // The cap holds even when this step also met the occlusion
            // rule: the group opened here is dropped unsampled.
            self.group = None;
            self.stop = Some(StopReason::SampleCap);
        } else if contact.stop {
            self.pending_stop = true;
        }
        if self.stop.is_none() && !self.pending_stop {
            self.t = advance(t, step.min(d), self.params.alpha, contact.rc);
        }
        Event::Sample(closed)
    }

    /// A soft hit's exit or the occlusion rule (Algorithm 1, lines 15–16 and
    /// 23–24): the open group is sampled, its exit backtraced by eq. 10
    /// (§3.6), and the trace stops on the rule (`stop`) or the sample cap.
    #[inline(always)]
    fn sample_at_exit(&mut self, t: f32, stop: bool) -> Event {
        let mut event = Event::March;
        if let Some(g) = self.group.take() {
            self.samples += 1;
            event = Event::Sample(g.sample(backtrace_cone_entry(t, self.params.tan_theta)));
        }
        if stop {
            self.stop = Some(self.occlusion_stop());
        } else if self.samples >= self.params.max_samples {
            self.stop = Some(StopReason::SampleCap);
        }
        event
    }

    /// The step just taken, for the next one's backtrace (§3.6) and its
    /// test of a shrinking distance.
    #[inline(always)]
    fn remember(&mut self, t: f32, d: f32) {
        self.t_prev = t;
        self.d_prev = d;
        self.have_prev = true;
    }

    /// The free-space step of [`advance_object`](Self::advance_object) alone
    /// (Algorithm 1, lines 7–9 and 26), for a packet of up to 32 cones
    /// (bit `k` of `active`: `steppers[k]`, fed `d[k]` and `step[k]`).
    ///
    /// A lane is free where the trace goes on, the step budget and `t_max`
    /// allow the step, `d` is a number, and the cone touches nothing now or
    /// at the step before (`ω ≤ 0 − ε` both times, eq. 5) while not passing
    /// through a semi-transparent object. There `advance_object` only counts
    /// the step, remembers it and steps by `max(min(step, d), α·R_c)`; this
    /// does the same, bit for bit. Every lane's occlusion and next depth are
    /// computed side by side first, branch-free (SIMD lanes where the
    /// compiler can), then the free lanes are stepped. A cone spends most of
    /// its steps in free space, and this path builds no [`Event`].
    ///
    /// Returns the lanes of `active` that were not free, their steppers
    /// untouched: the caller feeds them to `advance_object`. Lanes outside
    /// `active` (and bits 32 and up) are never touched.
    ///
    /// Domain: any `d` and `step` (a NaN `d` is never free).
    #[inline(always)]
    pub fn advance_free_lanes<const N: usize>(
        steppers: &mut [ConeStepper; N],
        d: &[f32; N],
        step: &[f32; N],
        active: u32,
    ) -> u32 {
        let mut next = [0.0f32; N];
        let mut free = [false; N];
        for k in 0..N {
            let s = &steppers[k];
            let tk = s.t;
            let rc = cone_radius(tk, s.params.tan_theta);
            let omega = cone_occlusion(d[k], rc);
            next[k] = advance(tk, step[k].min(d[k]), s.params.alpha, rc);
            // `!(ω > soft)` implies no hard hit and no stop: `soft ≤ hard
            // ≤ full` for every ε (each is a constant minus the same ε).
            free[k] = s.stop.is_none()
                & !s.pending_stop
                & !s.prev_soft
                & !s.passing
                & (s.steps < s.params.max_steps)
                & (tk < s.params.t_max)
                & !d[k].is_nan()
                & !(omega > s.thresholds.soft);
        }
        let mut left = active;
        for k in 0..N.min(32) {
            if active & (1 << k) != 0 && free[k] {
                let s = &mut steppers[k];
                s.steps += 1;
                s.prev_hard = false;
                s.t_prev = s.t;
                s.d_prev = d[k];
                s.have_prev = true;
                s.t = next[k];
                left &= !(1 << k);
            }
        }
        left
    }

    /// Make the sample's visibility mask from its projected normal, correlate it
    /// with `M` (`m_i & !M`, `M |= m_i`) and return `(visible mask, weight)`.
    ///
    /// Trips the visibility threshold k when `bitCount(M) ≥ k`.
    pub fn record(&mut self, sample: &GroupSample, projected_normal: Vec2) -> (u32, f32) {
        let m = visibility_mask(sample.occlusion, projected_normal, self.params.placement());
        self.record_mask(m)
    }

    /// [`record`](Self::record) for a mask the caller made (e.g.
    /// [`group_mask`]).
    ///
    /// CTSS-R (unless [`FLAG_PAPER`]): the group that ended the trace on its
    /// hard hit takes the whole rest of the pixel (its mask is made full).
    /// The central ray hit it, so the cells no group covered are hidden
    /// behind it or are more of it; the paper instead leaves them out and
    /// eq. 6 renormalises over the groups, which stretches every earlier
    /// group's partial mask (a glancing object in front grows by the share of
    /// the pixel the trace never saw).
    pub fn record_mask(&mut self, m: u32) -> (u32, f32) {
        let m = if self.takes_rest_of_pixel() {
            crate::mask::FULL_MASK
        } else {
            m
        };
        let visible = self.mask.add(m);
        if self.stop.is_none() && self.mask.covered_bits() >= self.params.visibility_k {
            self.stop = Some(StopReason::VisibilityThreshold);
        }
        let w = sample_weight(
            visible,
            self.params.weighting(),
            self.params.min_sample_weight,
        );
        (visible, w)
    }

    /// Whether [`record_mask`](Self::record_mask) now ignores the mask it is
    /// given and records a full one: CTSS-R's hard hit (unless
    /// [`FLAG_PAPER`]) takes the rest of the pixel. A caller can then skip
    /// making the mask ([`close_group`] does), and its normals.
    #[inline]
    pub fn takes_rest_of_pixel(&self) -> bool {
        !self.params.is_paper() && self.stop == Some(StopReason::HardHit)
    }

    /// Forget the previous step for grouping: the next step that touches a
    /// surface opens a new group, whose hard hit (if that step is one) is
    /// sampled at the step itself, not backtraced into the previous object.
    fn restart_grouping(&mut self) {
        self.prev_soft = false;
        self.prev_hard = false;
        self.have_prev = false;
        self.passing = false;
    }

    /// Whether the trace is passing through a semi-transparent object
    /// ([`record_alpha`](Self::record_alpha)).
    pub fn is_passing(&self) -> bool {
        self.passing
    }

    /// End a pass through a semi-transparent object here: the caller saw the
    /// nearest object change (e.g. the glass touches the floor, whose inside
    /// the ray has entered). The next step opens a group on that object.
    pub fn end_pass(&mut self) {
        if self.passing {
            self.restart_grouping();
        }
    }

    /// Whether a hit group is open: entered, not yet sampled.
    pub fn in_group(&self) -> bool {
        self.group.is_some()
    }

    /// Close the open hit group at the current depth and return its sample,
    /// so that the next [`advance`](Self::advance_split) starts a new group if
    /// the cone still touches a surface there. `None` when no group is open or
    /// the trace is over.
    ///
    /// For semi-transparent scenes (§5.3): a group must hold one surface. When
    /// the nearest object changes inside a group (e.g. a thin pane, then the
    /// floor behind it within the cone), the caller splits it there; otherwise
    /// the first surface's sample would take the weight of the whole group,
    /// and the occlusion that ends the trace would belong to the second.
    pub fn split_group(&mut self) -> Option<GroupSample> {
        if self.stop.is_some() {
            return None;
        }
        let g = self.group.take()?;
        self.samples += 1;
        self.restart_grouping();
        if self.samples >= self.params.max_samples {
            self.stop = Some(StopReason::SampleCap);
        }
        Some(GroupSample {
            t: g.t_sample,
            t_entry: g.t_entry,
            t_exit: backtrace_cone_entry(self.t, self.params.tan_theta),
            occlusion: g.occlusion,
            t_occlusion: g.t_occlusion,
            t_first: g.t_first,
            t_last: g.t_last,
            hard: g.hard,
        })
    }

    /// [`record`](Self::record) for a surface of opacity `alpha` (CTSS §5.3,
    /// [`crate::transparency`]): the mask is composited over the pixel's `K`
    /// masks instead of the single `M`, and the weight is the transmittance
    /// the sample took, [`level_weight`]. `alpha` is clamped to `[0, 1]`, NaN
    /// is opaque.
    ///
    /// When the sample ended the trace on its occlusion rule (full occlusion,
    /// or the hard hit of CTSS-R) but the surface is not opaque
    /// ([`is_opaque`]), or semi-transparent cells lie in front of it, its mask
    /// is taken as full (the rule says it covers the pixel) and, if the surface
    /// is not opaque, the trace goes on: it marches through the object (steps of `max(−d, α·R_c)`) without
    /// starting a group or stopping until the cone leaves it, so a ray takes
    /// `alpha` of an object's entry surface and sees what lies behind with the
    /// rest. (The exit surface is not sampled again: `alpha` is the object's
    /// opacity along the ray.) With `alpha = 1` the weights, `M`
    /// (= `M_K`, [`coverage`](Self::coverage)), the background weight and the
    /// stop are exactly those of [`record`](Self::record). Use one of the two
    /// for all samples of a trace.
    pub fn record_alpha(
        &mut self,
        sample: &GroupSample,
        projected_normal: Vec2,
        alpha: f32,
    ) -> (u32, f32) {
        let m = visibility_mask(sample.occlusion, projected_normal, self.params.placement());
        self.record_alpha_mask(m, alpha)
    }

    /// [`record_alpha`](Self::record_alpha) for a mask the caller made (e.g.
    /// [`group_mask`]).
    pub fn record_alpha_mask(&mut self, mut m: u32, alpha: f32) -> (u32, f32) {
        self.translucent = true;
        let ended = matches!(
            self.stop,
            Some(StopReason::FullOcclusion | StopReason::HardHit)
        );
        // CTSS-R's hard hit takes the rest of the pixel by default
        // (`record_mask`), opaque or not.
        let relaxed_full = !self.params.is_paper() && self.stop == Some(StopReason::HardHit);
        if ended && (!is_opaque(alpha) || !self.layers.is_binary() || relaxed_full) {
            // The occlusion rule says this surface covers the pixel. CTSS-R's
            // hard hit has a partial mask, which eq. 6's renormalisation
            // stretches over the pixel when only opaque surfaces were seen; a
            // trace that goes on, or one behind semi-transparent cells, cannot
            // renormalise (it would scale the glass in front too), so the mask
            // is made full instead.
            m = crate::mask::FULL_MASK;
        }
        let (visible, gained) = self.layers.add(m, alpha);
        if ended && !is_opaque(alpha) && self.layers.opaque() != crate::mask::FULL_MASK {
            self.stop = None;
            self.passing = true;
        }
        if self.stop.is_none() && self.layers.opaque().count_ones() >= self.params.visibility_k {
            self.stop = Some(StopReason::VisibilityThreshold);
        }
        let w = match self.params.weighting() {
            Weighting::Uniform => 1.0,
            Weighting::Visibility => {
                let floor = self.params.min_sample_weight;
                let floor = if floor > 0.0 { floor.min(1.0) } else { 0.0 };
                level_weight(gained).max(floor)
            }
        };
        (visible, w)
    }

    /// The background's weight once the trace is over: 0 when the hits cover the
    /// pixel ([`StopReason::covers_pixel`]), else `1 − bitCount(M)/32` (or 1 with
    /// uniform weights), as in the authors' code.
    pub fn background_weight(&self) -> f32 {
        match self.stop {
            Some(r) if r.covers_pixel() => 0.0,
            _ => match self.params.weighting() {
                Weighting::Uniform => 1.0,
                Weighting::Visibility if self.translucent => self.layers.uncovered_weight(),
                Weighting::Visibility => self.mask.uncovered_weight(),
            },
        }
    }
}

/// Orthonormal axes `(right, up)` of the cone's cross-section for a ray `dir`,
/// from the camera's up vector (the authors take `cross(rd, world_up)`).
///
/// Falls back to another axis when `dir ∥ up_hint`; returns `(X, Y)` for a zero
/// or non-finite `dir`.
pub fn cross_section_frame(dir: Vec3, up_hint: Vec3) -> (Vec3, Vec3) {
    let d = dir.unit_or_zero();
    if d == Vec3::ZERO {
        return (Vec3::X, Vec3::Y);
    }
    let mut right = d.cross(up_hint).unit_or_zero();
    if right == Vec3::ZERO {
        right = d.any_orthonormal_vector();
    }
    // For a camera looking down −z with +y up this gives right = +x, up = +y.
    (right, right.cross(d))
}

/// Result of [`trace`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceResult {
    /// The antialiased pixel colour (eq. 6 with the background as a sample).
    pub color: Vec3,
    /// Shaded samples taken.
    pub samples: u32,
    /// SDF evaluations.
    pub steps: u32,
    /// The final global mask `M`.
    pub coverage: u32,
    /// Why the trace ended.
    pub stop: StopReason,
    /// Depth along the ray (from its origin, in units of its direction) of
    /// the nearest hit group that adds to eq. 6 (weight above 0): that
    /// group's sample depth `t` (the backtraced entry, eq. 10, or the
    /// backtraced first hard hit, §3.6); `+∞` when no group does. A group the
    /// cone grazed without covering a cell of the mask is not the pixel's
    /// surface, so it gives no depth.
    pub depth: f32,
}

impl TraceResult {
    /// The pixel's coverage as an alpha ([`coverage_alpha`] of
    /// [`Self::coverage`] and [`Self::stop`]).
    pub fn alpha(&self) -> f32 {
        coverage_alpha(self.coverage, self.stop)
    }
}

/// The part of a pixel its hit groups cover, from the global mask `M`
/// (§3.4–3.5): `bitCount(M)/32`, or 1 when the trace ended on a rule that
/// gives the background no weight ([`StopReason::covers_pixel`]). With
/// visibility weights and no minimum weight (the defaults), it is
/// `1 − ConeStepper::background_weight()` and the hit weights of eq. 6 sum
/// to it, so the colour resolved against a black background is the pixel's
/// premultiplied colour and `premultiplied + (1 − alpha)·background` is the
/// colour resolved against `background` (the `over` operator, Porter and
/// Duff 1984), up to rounding.
pub fn coverage_alpha(coverage: u32, stop: StopReason) -> f32 {
    if stop.covers_pixel() {
        1.0
    } else {
        crate::mask::mask_weight(coverage)
    }
}

/// Trace one pixel's cone with CTSS (Algorithm 1) through closures.
///
/// `sdf(p)` is the signed distance, `normal(p)` the surface normal, `shade(p, n)`
/// the colour of a surface point, `background` the colour of a miss. `right`/`up`
/// span the cone's cross-section ([`cross_section_frame`]). Shading is ASAP (§5.1).
///
/// With [`FLAG_SPLIT_GROUPS`] every group's coarse normal is taken from `sdf`
/// ([`tetra_normal`], step [`coarse_normal_step`]) and a group that
/// [`group_needs_split`] is shaded at its [`split_group`] parts instead of
/// once; `steps` and `samples` then include the extra evaluations (coarse
/// normals and sub-traces) and shaded parts.
#[allow(clippy::too_many_arguments)]
pub fn trace<S, N, C>(
    params: &CtssParams,
    origin: Vec3,
    dir: Vec3,
    right: Vec3,
    up: Vec3,
    sdf: S,
    normal: N,
    mut shade: C,
    background: Vec3,
) -> TraceResult
where
    S: FnMut(Vec3) -> f32,
    N: FnMut(Vec3) -> Vec3,
    C: FnMut(Vec3, Vec3) -> Vec3,
{
    let ray = SplitRay {
        origin,
        dir,
        right,
        up,
    };
    trace_field(
        params,
        &ray,
        &mut ClosureField { sdf, normal },
        |p, n, _| shade(p, n),
        background,
    )
}

/// [`trace`] for scenes with semi-transparent surfaces (CTSS §5.3): `shade(p, n)`
/// returns the colour and the opacity of the surface, and every sample goes
/// through [`ConeStepper::record_alpha`]. With every opacity 1 the result is
/// [`trace`]'s.
#[allow(clippy::too_many_arguments)]
pub fn trace_translucent<S, N, C>(
    params: &CtssParams,
    origin: Vec3,
    dir: Vec3,
    right: Vec3,
    up: Vec3,
    sdf: S,
    normal: N,
    mut shade: C,
    background: Vec3,
) -> TraceResult
where
    S: FnMut(Vec3) -> f32,
    N: FnMut(Vec3) -> Vec3,
    C: FnMut(Vec3, Vec3) -> (Vec3, f32),
{
    let ray = SplitRay {
        origin,
        dir,
        right,
        up,
    };
    let mut field = ClosureField { sdf, normal };
    let mut stepper = ConeStepper::new(params);
    let mut agg = Aggregate::new();
    let mut depth = f32::INFINITY;
    let stop = loop {
        let t = stepper.t();
        let d = field.sample(origin + t * dir).distance;
        match stepper.advance(d) {
            Event::March => {}
            Event::Sample(s) => {
                let p = origin + s.t * dir;
                let n = field.normal(p, normal_step(s.t, params.tan_theta));
                let (c, a) = shade(p, n);
                let mask = group_mask(params, &ray, &s, n, &mut field);
                let (_, w) = stepper.record_alpha_mask(mask, a);
                if depth == f32::INFINITY && w > 0.0 {
                    depth = s.t;
                }
                agg.add(w, c);
            }
            Event::Stop(r) => break r,
        }
    };
    TraceResult {
        color: agg.resolve(background, stepper.background_weight()),
        samples: stepper.samples(),
        steps: stepper.steps(),
        coverage: stepper.coverage(),
        stop,
        depth,
    }
}

/// Result of [`sphere_trace`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereHit {
    /// Depth of the hit, if any.
    pub t: Option<f32>,
    /// SDF evaluations.
    pub steps: u32,
    /// Why the trace ended ([`StopReason::HardHit`] on a hit).
    pub stop: StopReason,
}

/// Plain sphere tracing (eq. 1–2) with the adaptive cone-based hit threshold of
/// §4: stop at `ω > 0.5 − ε`, i.e. `d < 2ε·R_c`, with the same ε, cone, range and
/// step budget as CTSS, so that NoAA-vs-CTSS ratios compare like with like. The
/// authors' NoAA (`sphereTrace`) does the same.
///
/// Steps are `t += d` with no minimum step (a step that would not change `t`
/// advances one ulp instead), so every trace ends within `max_steps`.
pub fn sphere_trace<S>(params: &CtssParams, origin: Vec3, dir: Vec3, mut sdf: S) -> SphereHit
where
    S: FnMut(Vec3) -> f32,
{
    sphere_trace_split(params, origin, dir, |p| {
        let d = sdf(p);
        (d, d)
    })
}

/// [`sphere_trace`] for fields whose surface distance (first value, decides the
/// hit) and safe step (second value, `≤` the first) differ, as in
/// [`ConeStepper::advance_split`].
pub fn sphere_trace_split<S>(params: &CtssParams, origin: Vec3, dir: Vec3, mut sdf: S) -> SphereHit
where
    S: FnMut(Vec3) -> (f32, f32),
{
    let mut march = SphereMarch::new(params);
    loop {
        if let Some(hit) = march.before_step(params) {
            return hit;
        }
        let (d, step) = sdf(origin + march.t() * dir);
        if let Some(hit) = march.after_step(params, d, step) {
            return hit;
        }
    }
}

/// [`sphere_trace_split`] one step at a time, for a caller that evaluates the
/// field for several rays together (a packet of rays in SIMD lanes): the
/// same state and the same tests, so every ray ends exactly where
/// [`sphere_trace_split`] ends it.
///
/// ```
/// use glam::Vec3;
/// use subcone_kernels::ctss::{sphere_trace_split, CtssParams, SphereMarch};
///
/// let params = CtssParams::new(0.01);
/// let field = |p: Vec3| (p - Vec3::Z * 4.0).length() - 1.0;
/// let mut m = SphereMarch::new(&params);
/// let hit = loop {
///     if let Some(h) = m.before_step(&params) {
///         break h;
///     }
///     let d = field(Vec3::Z * m.t());
///     if let Some(h) = m.after_step(&params, d, d) {
///         break h;
///     }
/// };
/// let whole = sphere_trace_split(&params, Vec3::ZERO, Vec3::Z, |p| (field(p), field(p)));
/// assert_eq!(hit, whole);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereMarch {
    t: f32,
    steps: u32,
}

impl SphereMarch {
    /// A march from `params.t_min` (or 0).
    #[inline]
    pub fn new(params: &CtssParams) -> SphereMarch {
        SphereMarch {
            t: if params.t_min > 0.0 {
                params.t_min
            } else {
                0.0
            },
            steps: 0,
        }
    }

    /// Depth of the next evaluation.
    #[inline]
    pub fn t(&self) -> f32 {
        self.t
    }

    /// Evaluations so far.
    #[inline]
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// The end of the march before the next evaluation (step budget spent,
    /// or past `t_max`), if it ends.
    #[inline]
    pub fn before_step(&self, params: &CtssParams) -> Option<SphereHit> {
        let miss = |stop| SphereHit {
            t: None,
            steps: self.steps,
            stop,
        };
        if self.steps >= params.max_steps {
            return Some(miss(StopReason::StepBudget));
        }
        if !(self.t < params.t_max) {
            return Some(miss(StopReason::MaxDistance));
        }
        None
    }

    /// Takes the field at [`t`](Self::t): surface distance `d` and safe step
    /// `step`. Returns the end of the march (a hit, or a NaN distance), or
    /// `None` and advances.
    #[inline]
    pub fn after_step(&mut self, params: &CtssParams, d: f32, step: f32) -> Option<SphereHit> {
        self.steps += 1;
        if d.is_nan() {
            return Some(SphereHit {
                t: None,
                steps: self.steps,
                stop: StopReason::InvalidDistance,
            });
        }
        let rc = cone_radius(self.t, params.tan_theta);
        if cone_occlusion(d, rc) > params.thresholds().hard {
            return Some(SphereHit {
                t: Some(self.t),
                steps: self.steps,
                stop: StopReason::HardHit,
            });
        }
        self.t = advance(self.t, step.min(d), 0.0, rc);
        None
    }
}

// ---------------------------------------------------------------------------
// Hit group subdivision (§5.2–5.3)
// ---------------------------------------------------------------------------
//
// One hit group gets one shaded sample (§3.3), so an *internal* edge, where the
// cone never leaves the surface (two faces of one box seen across the pixel),
// is one group, one normal, one colour for the whole pixel (§5.2, Fig. 9–10).
// §5.3 proposes to subdivide a group when its normals at different scales
// disagree, or when its length-to-depth ratio is large. We do both
// ([`group_needs_split`]) and shade a split group at four points spread across
// the cone's cross-section ([`split_group`]), each with its own normal and
// shading and the quarter of the group's mask nearest to it.

/// Smallest cosine between a group's fine and coarse normal that keeps the
/// group whole: `cos 20°`. Two faces of a box meet at 90°; a coarse normal
/// whose taps straddle the edge is bent towards the other face by a share of
/// that, the larger the nearer the edge is to the sample point (the kernel
/// test `split_on_a_box_edge` pins a point a fifth of a cone radius away).
/// On a sphere of radius `ρ` the tetrahedral differences' second-order error
/// bends the coarse normal by at most about `0.6·R_c/ρ` radians, so only
/// surfaces curved within about two cone radii split for their curvature,
/// where one normal per pixel is wrong as well.
pub const SPLIT_MIN_COS: f32 = 0.939_692_6;

/// Largest group length, in cone radii at the sample depth, that keeps the
/// group whole (§5.3's length-to-depth ratio, normalised by `tan θ` so it does
/// not depend on the resolution). A plane seen at angle `φ` from its normal
/// makes a group about `2/cos φ` cone radii long (from `ω = ε` to `ω = 1 − ε`),
/// so 8 splits surfaces seen beyond ~75°, whose pixel footprint is at least
/// four times longer than wide: grazing floors and walls, where shading and
/// texture vary across the pixel.
pub const SPLIT_LENGTH_RATIO: f32 = 8.0;

/// SDF evaluations each sub-sample's sphere trace may take.
pub const SPLIT_MAX_STEPS: u32 = 32;

/// The visibility mask's cells split into the four quadrants of the cone's
/// cross-section, in the order of [`SPLIT_OFFSETS`]: (−x, −y), (+x, −y),
/// (−x, +y), (+x, +y). No cell centre lies on an axis, so the four masks are
/// disjoint, 8 cells each, and their union is the full mask (unit-tested
/// against [`cell_centre`](crate::mask::cell_centre)).
pub const SPLIT_QUADRANTS: [u32; 4] = [0x0000_1C73, 0x0000_E38C, 0x31C7_0000, 0xCE38_0000];

/// Mean cell centre of each quadrant of [`SPLIT_QUADRANTS`], in cone radii:
/// `±(11/8)·s/3` with `s` = [`GRID_SCALE`](crate::mask::GRID_SCALE), ≈ 0.431
/// (the quarter disk's centroid is at 0.424).
pub const SPLIT_OFFSETS: [Vec2; 4] = {
    const A: f32 = 11.0 / 8.0 * crate::mask::GRID_SCALE / 3.0;
    [
        Vec2::new(-A, -A),
        Vec2::new(A, -A),
        Vec2::new(-A, A),
        Vec2::new(A, A),
    ]
};

/// Step `h` of the coarse normal of a group sampled at depth `t`: four times
/// the fine step [`normal_step`], i.e. the cone radius `R_c = t·tan θ` (never
/// below `4·10⁻⁵·max(t, 1)`), so that the coarse differences' taps reach
/// across the pixel's footprint.
#[inline]
pub fn coarse_normal_step(t: f32, params: &CtssParams) -> f32 {
    4.0 * normal_step(t, params.tan_theta)
}

/// Unit normal of `sdf` at `p` from tetrahedral differences of step `h` (4
/// evaluations, Quilez); the CPU renderer's `SdfField::normal` is the same
/// formula. Zero when the differences are zero or not finite.
pub fn tetra_normal<S: FnMut(Vec3) -> f32>(mut sdf: S, p: Vec3, h: f32) -> Vec3 {
    const K: [Vec3; 4] = [
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(1.0, 1.0, 1.0),
    ];
    K.iter()
        .fold(Vec3::ZERO, |a, k| a + *k * sdf(p + *k * h))
        .unit_or_zero()
}

/// Whether a hit group hides an internal edge and needs extra samples (§5.3).
///
/// `n_fine` is the normal at the sample point from small differences (the one
/// shading uses), `n_coarse` the normal at the same point from differences of
/// step [`coarse_normal_step`] (about the cone radius): "surface normals at
/// different scales". Where a box edge or a crease crosses the pixel's
/// footprint, the coarse taps straddle it and the two disagree; on a plane
/// they are equal. `group_length = t_exit − t_entry` and `depth` the sample's
/// depth give §5.3's length-to-depth ratio, measured in cone radii
/// (`group_length / (depth·tan θ)`).
///
/// Splits when the normals differ by more than 20° ([`SPLIT_MIN_COS`]) or the
/// group is longer than [`SPLIT_LENGTH_RATIO`] cone radii.
///
/// Domain: any. A zero or non-finite normal does not take part in the angle
/// test; a NaN or infinite length, a non-positive or non-finite cone radius
/// does not take part in the length test: a test whose inputs are not finite
/// never votes for a split (and nothing panics).
#[inline]
pub fn group_needs_split(
    n_fine: Vec3,
    n_coarse: Vec3,
    group_length: f32,
    depth: f32,
    params: &CtssParams,
) -> bool {
    let rc = cone_radius(depth, params.tan_theta);
    let long = rc.is_finite()
        && rc > 0.0
        && group_length.is_finite()
        && group_length > SPLIT_LENGTH_RATIO * rc;
    let (a, b) = (n_fine.unit_or_zero(), n_coarse.unit_or_zero());
    let bent = a != Vec3::ZERO && b != Vec3::ZERO && a.dot(b) < SPLIT_MIN_COS;
    long || bent
}

/// The group's weight `w` shared between its four sub-samples in proportion to
/// the visible cells of each quadrant: `w_j = w · bitCount(v & Q_j) / bitCount(v)`
/// for the correlated mask `v` and the quadrant masks `Q_j`
/// ([`SPLIT_QUADRANTS`]).
///
/// The `Q_j` partition the grid, so `Σ_j w_j = w` (up to rounding) and eq. 6's
/// weights, the global mask `M` and the background weight are exactly those of
/// the unsplit group: splitting moves colour within the group's share of the
/// pixel, never weight between groups. With visibility weights (the default,
/// no floor) this is `w_j = bitCount(v & Q_j)/32`, the sub-sample's own share
/// of the pixel, i.e. a 2×2 supersampling of the group's coverage.
///
/// `None` (do not split) when `v` is empty (the group is hidden; with a
/// minimum weight or uniform weights it keeps its single sample) or `w` is not
/// finite.
#[inline]
pub fn split_weights(visible: u32, weight: f32) -> Option<[f32; 4]> {
    let n = visible.count_ones();
    if n == 0 || !weight.is_finite() {
        return None;
    }
    let per_cell = weight / n as f32;
    Some(SPLIT_QUADRANTS.map(|q| (visible & q).count_ones() as f32 * per_cell))
}

/// Direction of the sub-ray through offset `offset` (in cone radii) of the
/// cross-section: `normalize(dir + tan θ·(offset.x·right + offset.y·up))`,
/// which passes through `o + t·dir + R_c(t)·(offset.x·right + offset.y·up)` at
/// every depth `t` (up to the normalisation, `1 + O(tan²θ)`). Returns `dir`
/// when the result is zero or not finite.
#[inline]
pub fn split_direction(dir: Vec3, right: Vec3, up: Vec3, tan_theta: f32, offset: Vec2) -> Vec3 {
    let d = dir + (tan_theta * offset.x) * right + (tan_theta * offset.y) * up;
    let n = d.unit_or_zero();
    if n == Vec3::ZERO {
        dir
    } else {
        n
    }
}

/// Parameters of a sub-sample's sphere trace: the same cone and thresholds,
/// depths from the group's backtraced entry (eq. 10: the cone there does not
/// reach the surface, so every sub-ray starts outside it) to two cone radii
/// past the group's last depth, at most [`SPLIT_MAX_STEPS`] evaluations.
pub fn split_trace_params(params: &CtssParams, sample: &GroupSample) -> CtssParams {
    let last = sample.t_exit.max(sample.t_occlusion).max(sample.t);
    let hi = last + 2.0 * cone_radius(last, params.tan_theta);
    params
        .with_range(sample.t_entry, hi.min(params.t_max))
        .with_max_steps(SPLIT_MAX_STEPS)
}

/// The pixel's ray and its cross-section axes ([`cross_section_frame`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitRay {
    /// Ray origin.
    pub origin: Vec3,
    /// Unit ray direction.
    pub dir: Vec3,
    /// Cross-section axis `x` of the mask.
    pub right: Vec3,
    /// Cross-section axis `y` of the mask.
    pub up: Vec3,
}

impl SplitRay {
    /// The ray from `origin` along the unit `dir`, its cross-section axes
    /// taken from the camera's `up_hint` by [`cross_section_frame`].
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3, up_hint: Vec3) -> Self {
        let (right, up) = cross_section_frame(dir, up_hint);
        Self {
            origin,
            dir,
            right,
            up,
        }
    }
}

/// One sub-sample of a split group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitPart {
    /// Its share of the group's weight ([`split_weights`]); 0: not traced.
    pub weight: f32,
    /// Direction of its sub-ray ([`split_direction`]).
    pub dir: Vec3,
    /// Depth of its hit along `dir`, or `None` when the sub-ray found no
    /// surface in range: the caller shades the group's own sample for it, as
    /// unsplit CTSS would.
    pub t: Option<f32>,
}

/// A split hit group: four parts and the SDF evaluations their traces took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitGroup {
    /// The sub-samples, in the order of [`SPLIT_QUADRANTS`].
    pub parts: [SplitPart; 4],
    /// SDF evaluations of the sub-traces.
    pub steps: u32,
}

/// Subdivide a hit group (§5.3): for every quadrant of the cross-section with
/// visible cells, sphere-trace the sub-ray through the quadrant's mean cell
/// centre ([`SPLIT_OFFSETS`], [`split_direction`]) over the group's depths
/// ([`split_trace_params`]) with `sdf` (`(surface distance, safe step)` as in
/// [`sphere_trace_split`]). `visible` and `weight` are what
/// [`ConeStepper::record`] returned for the group. The caller shades each
/// part with a positive weight at its hit (own normal, own shading) and adds
/// it to eq. 6 with its weight, instead of the group's single sample.
///
/// `None` when [`split_weights`] declines (nothing visible). Every sub-trace
/// ends within [`SPLIT_MAX_STEPS`]; NaN distances end it without a hit.
pub fn split_group<S>(
    params: &CtssParams,
    sample: &GroupSample,
    ray: &SplitRay,
    visible: u32,
    weight: f32,
    mut sdf: S,
) -> Option<SplitGroup>
where
    S: FnMut(Vec3) -> (f32, f32),
{
    let weights = split_weights(visible, weight)?;
    let sub = split_trace_params(params, sample);
    let mut steps = 0u32;
    let mut parts = [SplitPart {
        weight: 0.0,
        dir: ray.dir,
        t: None,
    }; 4];
    for (j, part) in parts.iter_mut().enumerate() {
        if !(weights[j] > 0.0) {
            continue;
        }
        let dir = split_direction(
            ray.dir,
            ray.right,
            ray.up,
            params.tan_theta,
            SPLIT_OFFSETS[j],
        );
        let hit = sphere_trace_split(&sub, ray.origin, dir, &mut sdf);
        steps = steps.saturating_add(hit.steps);
        *part = SplitPart {
            weight: weights[j],
            dir,
            t: hit.t,
        };
    }
    Some(SplitGroup { parts, steps })
}
