//! The hit-group logic of CTSS (Algorithm 1, §3.3, §3.6) as a pure stepper,
//! [`ConeStepper`]: where to evaluate, the hit groups and their backtraced
//! depths (eq. 9–10), the stop rules (CTSS-R, §4), and the visibility masks
//! correlated with the pixel's global mask `M` (or the `K` masks of §5.3).

use glam::Vec2;

use super::params::{CtssParams, GROUP_DIP};
use crate::aggregate::{sample_weight, Weighting};
use crate::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius,
    OcclusionThresholds,
};
use crate::mask::{visibility_mask, VisibilityAccumulator};
use crate::transparency::{is_opaque, level_weight, TransparencyAccumulator};

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
    ///
    /// [`group_mask`]: super::group_mask
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
///
/// [`FieldSample::object`]: super::FieldSample::object
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
    ///
    /// [`FLAG_PAPER`]: super::FLAG_PAPER
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
    ///
    /// [`group_mask`]: super::group_mask
    /// [`FLAG_PAPER`]: super::FLAG_PAPER
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
    ///
    /// [`FLAG_PAPER`]: super::FLAG_PAPER
    /// [`close_group`]: super::close_group
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
    ///
    /// [`group_mask`]: super::group_mask
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
