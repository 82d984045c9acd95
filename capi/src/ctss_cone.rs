//! CTSS's cone kernels: the cone's angle, radius and occlusion (eq. 3–5),
//! the march's step (§3.1), the backtraced depths (eq. 9–10, §3.6), the
//! visibility mask (eq. 7–8) and the sample weight of eq. 6.

use glam::Vec2;
use subcone_kernels::aggregate::{sample_weight, Weighting};
use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, cone_tan_theta,
    PixelFootprint,
};
use subcone_kernels::mask::{project_normal, visibility_mask, MaskPlacement};

use crate::checks::{finite, write};
use crate::geometry::SubconeVec3;
use crate::status::{call, Refusal, SubconeStatus};

/// CTSS eq. 3: `tan θ` of a pixel's cone for a vertical field of view `fov_y`
/// (radians, in `(0, π)`), an image `height` in pixels (> 0), a `coverage`
/// in pixels (> 0, finite) and a footprint (0 circumscribed, the default; 1
/// the authors' balanced; 2 inscribed).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_cone_tan_theta(
    fov_y: f32,
    height: u32,
    coverage: f32,
    footprint: u32,
    out: *mut f32,
) -> SubconeStatus {
    call("subcone_cone_tan_theta", || {
        let fp = match footprint {
            0 => PixelFootprint::Circumscribed,
            1 => PixelFootprint::Balanced,
            2 => PixelFootprint::Inscribed,
            _ => {
                return Err(Refusal::invalid(format!(
                    "footprint is {footprint}; it must be 0 (circumscribed), 1 (balanced) or 2 \
                     (inscribed)"
                )))
            }
        };
        if !(fov_y > 0.0 && fov_y < std::f32::consts::PI) {
            return Err(Refusal::invalid(format!(
                "fov_y is {fov_y}; it must be in (0, π) radians"
            )));
        }
        if height == 0 {
            return Err(Refusal::invalid("height is 0; it must be at least 1 pixel"));
        }
        if !(coverage.is_finite() && coverage > 0.0) {
            return Err(Refusal::invalid(format!(
                "coverage is {coverage}; it must be finite and positive"
            )));
        }
        // SAFETY: forwarded contract.
        unsafe { write(out, cone_tan_theta(fov_y, height, coverage, fp), "out") }
    })
}

/// CTSS eq. 4: the cone radius `t·tan θ` at depth `t`.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_cone_radius(
    t: f32,
    tan_theta: f32,
    out: *mut f32,
) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_cone_radius", || unsafe {
        write(out, cone_radius(t, tan_theta), "out")
    })
}

/// CTSS eq. 5: the cone occlusion `ω = (1 − d/rc)/2` of a surface at
/// distance `d` from the axis for a cone of radius `rc`, clamped to
/// `[−1, 2]` (below 0 the cone misses, above 1 the whole cross-section is
/// inside); never NaN or infinite: a NaN `d` gives −1, and outside the
/// domain (`d` finite, `rc > 0` finite) the limits of the Rust
/// `cone_occlusion`.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_cone_occlusion(d: f32, rc: f32, out: *mut f32) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_cone_occlusion", || unsafe {
        write(out, cone_occlusion(d, rc), "out")
    })
}

/// The next depth of the cone march from `t`: `t + max(d, α·R_c)` (§3.1).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_advance(
    t: f32,
    d: f32,
    alpha: f32,
    rc: f32,
    out: *mut f32,
) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_advance", || unsafe {
        write(out, advance(t, d, alpha, rc), "out")
    })
}

/// CTSS eq. 9–10: the depth where the cone first met the surface, backtraced
/// from `t_i`.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_backtrace_cone_entry(
    t_i: f32,
    tan_theta: f32,
    out: *mut f32,
) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_backtrace_cone_entry", || unsafe {
        write(out, backtrace_cone_entry(t_i, tan_theta), "out")
    })
}

/// CTSS §3.6: the depth of the first hard hit, between `t_prev` and `t_i`.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_backtrace_hard_hit(
    t_prev: f32,
    d_prev: f32,
    t_i: f32,
    out: *mut f32,
) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_backtrace_hard_hit", || unsafe {
        write(out, backtrace_hard_hit(t_prev, d_prev, t_i), "out")
    })
}

/// The surface normal projected on the cone's cross-section, `(n̂·r, n̂·u)`:
/// `out` receives 2 floats.
///
/// # Safety
/// `out` is null or points to 2 writable floats.
#[no_mangle]
pub unsafe extern "C" fn subcone_project_normal(
    normal: SubconeVec3,
    right: SubconeVec3,
    up: SubconeVec3,
    out: *mut f32,
) -> SubconeStatus {
    call("subcone_project_normal", || {
        let n = project_normal(normal.into(), right.into(), up.into());
        // SAFETY: forwarded contract (2 floats).
        unsafe { write(out.cast::<[f32; 2]>(), n.to_array(), "out") }
    })
}

/// CTSS eq. 7–8: the 32-bit visibility mask of a surface of cone occlusion
/// `occlusion` whose projected normal is `(nx, ny)`; `placement` 0 derived
/// (default), 1 the authors' code, 2 the paper's eq. 8.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_visibility_mask(
    occlusion: f32,
    nx: f32,
    ny: f32,
    placement: u32,
    out: *mut u32,
) -> SubconeStatus {
    call("subcone_visibility_mask", || {
        if placement > 2 {
            return Err(Refusal::invalid(format!(
                "placement is {placement}; it must be 0 (derived), 1 (the authors' code) or 2 \
                 (the paper's eq. 8)"
            )));
        }
        let m = visibility_mask(
            occlusion,
            Vec2::new(nx, ny),
            MaskPlacement::from_u32(placement),
        );
        // SAFETY: forwarded contract.
        unsafe { write(out, m, "out") }
    })
}

/// CTSS eq. 6's weight of a sample whose correlated mask is `visible`;
/// `weighting` 0 visibility (default), 1 uniform; `min_weight` finite.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_sample_weight(
    visible: u32,
    weighting: u32,
    min_weight: f32,
    out: *mut f32,
) -> SubconeStatus {
    call("subcone_sample_weight", || {
        if weighting > 1 {
            return Err(Refusal::invalid(format!(
                "weighting is {weighting}; it must be 0 (visibility) or 1 (uniform)"
            )));
        }
        finite(&[("min_weight", min_weight)])?;
        let w = sample_weight(visible, Weighting::from_u32(weighting), min_weight);
        // SAFETY: forwarded contract.
        unsafe { write(out, w, "out") }
    })
}
