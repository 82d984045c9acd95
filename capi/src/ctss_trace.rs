//! One whole CTSS trace through the caller's field: its callbacks, what
//! they return, and the trace's result.

use std::ffi::c_void;

use glam::Vec3;
use subcone_kernels::camera::in_normal_range;
use subcone_kernels::ctss::{
    cross_section_frame, trace_field, ConeField, CtssParams, FieldSample, SplitRay, StopReason,
};

use crate::checks::{finite, finite_vec, read, write};
use crate::geometry::SubconeVec3;
use crate::params::SubconeCtssParams;
use crate::status::{call, Refusal, SubconeStatus};

/// What a field callback says about a point (see [`SubconeDistanceFn`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeFieldSample {
    /// Signed distance to the nearest surface.
    pub distance: f32,
    /// A safe step, at most `distance` (return the distance when in doubt).
    pub step: f32,
    /// Id of the nearest object (a material, say); `0xFFFFFFFF` for none (the
    /// kernels' `ctss::NO_OBJECT`). A hit group ends where it changes.
    pub object: u32,
}

/// The signed distance field at `p`, for [`subcone_ctss_trace`] (a nullable
/// function pointer; null is refused).
pub type SubconeDistanceFn =
    Option<extern "C" fn(user: *mut c_void, p: SubconeVec3) -> SubconeFieldSample>;

/// The unit surface normal at `p` from differences of step `h`, for
/// [`subcone_ctss_trace`] (optional: by default a tetrahedron of distance
/// differences: pass null).
pub type SubconeNormalFn =
    Option<extern "C" fn(user: *mut c_void, p: SubconeVec3, h: f32) -> SubconeVec3>;

/// The colour of the surface point `p` with normal `n`, seen along `dir` (a
/// nullable function pointer; null is refused).
pub type SubconeShadeFn = Option<
    extern "C" fn(
        user: *mut c_void,
        p: SubconeVec3,
        n: SubconeVec3,
        dir: SubconeVec3,
    ) -> SubconeVec3,
>;

/// What a CTSS trace returns.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeCtssResult {
    /// The antialiased pixel colour (eq. 6, the background as a sample).
    pub color: SubconeVec3,
    /// Shaded samples taken.
    pub samples: u32,
    /// Distance evaluations.
    pub steps: u32,
    /// The final 32-bit visibility mask `M`.
    pub coverage: u32,
    /// Why it ended: 0 full occlusion, 1 hard hit, 2 visibility threshold, 3
    /// sample cap, 4 left the scene, 5 step budget, 6 NaN distance, 7 a
    /// reason this version does not name.
    pub stop: u32,
}

/// The caller's field, through its callbacks.
struct Callbacks {
    distance: extern "C" fn(*mut c_void, SubconeVec3) -> SubconeFieldSample,
    normal: SubconeNormalFn,
    user: *mut c_void,
}

impl ConeField for Callbacks {
    fn sample(&mut self, p: Vec3) -> FieldSample {
        let s = (self.distance)(self.user, p.into());
        FieldSample {
            distance: s.distance,
            step: s.step,
            object: s.object,
        }
    }

    fn normal(&mut self, p: Vec3, h: f32) -> Vec3 {
        match self.normal {
            Some(f) => f(self.user, p.into(), h).into(),
            None => subcone_kernels::ctss::tetra_normal(|q| self.sample(q).distance, p, h),
        }
    }
}

/// One pixel's CTSS trace (Algorithm 1 with subcone's default groups, or the
/// paper's with bit 2 of `flags`): the cone from `origin` along `dir`
/// (normalised unless unit; any finite non-zero length), its cross-section
/// oriented by `up_hint`, through the caller's
/// field `distance` (and `normal`, or NULL for differences of `distance`),
/// each hit group shaded by `shade` as it closes (ASAP, §5.1), resolved by
/// eq. 6 against `background`. The same loop, to the bit, as the CPU
/// renderer's (the kernels' `ctss::trace_field`).
///
/// Errors: null `params`, `distance`, `shade` or `out`; non-finite
/// parameters, `origin` or `dir`, a zero `dir`, a `visibility_k` outside
/// 1..=32. A callback's NaN distance ends the trace
/// (`stop` 6); its colour is then that of the groups before.
///
/// # Safety
/// `params` and `out` are null or valid; the callbacks are valid functions
/// that accept `user` and do not unwind.
#[no_mangle]
pub unsafe extern "C" fn subcone_ctss_trace(
    params: *const SubconeCtssParams,
    origin: SubconeVec3,
    dir: SubconeVec3,
    up_hint: SubconeVec3,
    distance: SubconeDistanceFn,
    normal: SubconeNormalFn,
    shade: SubconeShadeFn,
    user: *mut c_void,
    background: SubconeVec3,
    out: *mut SubconeCtssResult,
) -> SubconeStatus {
    call("subcone_ctss_trace", || {
        // SAFETY: forwarded contract.
        let p: CtssParams = unsafe { read(params, "params") }?.into();
        let Some(distance) = distance else {
            return Err(Refusal::null("distance"));
        };
        let Some(shade) = shade else {
            return Err(Refusal::null("shade"));
        };
        if out.is_null() {
            return Err(Refusal::null("out"));
        }
        finite(&[
            ("params->tan_theta", p.tan_theta),
            ("params->alpha", p.alpha),
            ("params->eps", p.eps),
            ("params->t_min", p.t_min),
            ("params->t_max", p.t_max),
            ("params->min_sample_weight", p.min_sample_weight),
        ])?;
        let (origin, dir, up_hint) = (Vec3::from(origin), Vec3::from(dir), Vec3::from(up_hint));
        finite_vec("origin", origin)?;
        finite_vec("dir", dir)?;
        finite_vec("up_hint", up_hint)?;
        if dir == Vec3::ZERO {
            return Err(Refusal::invalid("dir is (0, 0, 0); it must not be zero"));
        }
        if p.tan_theta < 0.0 {
            return Err(Refusal::invalid(format!(
                "params->tan_theta is {}; it must not be negative",
                p.tan_theta
            )));
        }
        if !(1..=32).contains(&p.visibility_k) {
            return Err(Refusal::invalid(format!(
                "params->visibility_k is {}; it must be in 1..=32",
                p.visibility_k
            )));
        }
        // A unit direction is used as given (as the renderers pass it).
        let dir = if (dir.length_squared() - 1.0).abs() > 4.0 * f32::EPSILON {
            in_normal_range(dir).normalize()
        } else {
            dir
        };
        let up_hint = in_normal_range(up_hint);
        let (right, up) = cross_section_frame(dir, up_hint);
        let ray = SplitRay {
            origin,
            dir,
            right,
            up,
        };
        let mut field = Callbacks {
            distance,
            normal,
            user,
        };
        let r = trace_field(
            &p,
            &ray,
            &mut field,
            |q, n, d| shade(user, q.into(), n.into(), d.into()).into(),
            background.into(),
        );
        let stop = match r.stop {
            StopReason::FullOcclusion => 0,
            StopReason::HardHit => 1,
            StopReason::VisibilityThreshold => 2,
            StopReason::SampleCap => 3,
            StopReason::MaxDistance => 4,
            StopReason::StepBudget => 5,
            StopReason::InvalidDistance => 6,
            _ => 7,
        };
        let result = SubconeCtssResult {
            color: r.color.into(),
            samples: r.samples,
            steps: r.steps,
            coverage: r.coverage,
            stop,
        };
        // SAFETY: checked non-null; forwarded contract.
        unsafe { write(out, result, "out") }
    })
}
