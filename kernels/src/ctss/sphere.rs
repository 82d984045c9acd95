//! Plain sphere tracing with the cone-based hit threshold of §4: the NoAA
//! baseline ([`sphere_trace`]), and the sub-traces of a split group
//! ([`sphere_trace_split`]).

use glam::Vec3;

use super::params::CtssParams;
use super::stepper::StopReason;
use crate::cone::{advance, cone_occlusion, cone_radius};

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
///
/// [`ConeStepper::advance_split`]: super::ConeStepper::advance_split
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
