//! SRAA's per-sample kernels: the weights of eq. 1 and 2, the material
//! gate's albedo difference and the box resolve of a pixel.

use subcone_kernels::sraa::{
    albedo_difference, bilateral_weight, reconstruction_weight, resolve_pixel, shadow_gated_weight,
};

use crate::checks::{read, slice, write};
use crate::geometry::{SubconeGeometry, SubconeVec3};
use crate::params::{sraa_params, SubconeSraaParams};
use crate::status::{call, SubconeStatus};

/// SRAA eq. 1: the bilateral weight of sample `gj` for target `gi`, in
/// `[0, 1]`. Geometry outside the domain (a NaN depth, a zero normal) gives
/// 0; see the Rust `bilateral_weight`.
///
/// # Safety
/// Each pointer is null or valid.
#[no_mangle]
pub unsafe extern "C" fn subcone_bilateral_weight(
    params: *const SubconeSraaParams,
    gi: *const SubconeGeometry,
    gj: *const SubconeGeometry,
    out: *mut f32,
) -> SubconeStatus {
    call("subcone_bilateral_weight", || {
        let p = sraa_params(params)?;
        // SAFETY: forwarded contract.
        let (gi, gj) = unsafe { (read(gi, "gi")?, read(gj, "gj")?) };
        // SAFETY: forwarded contract.
        unsafe { write(out, bilateral_weight(&p, &gi.into(), &gj.into()), "out") }
    })
}

/// SRAA eq. 2: 0 when the shadow states `si` and `sj` (non-zero: in shadow)
/// differ, eq. 1 otherwise.
///
/// # Safety
/// Each pointer is null or valid.
#[no_mangle]
pub unsafe extern "C" fn subcone_shadow_gated_weight(
    params: *const SubconeSraaParams,
    gi: *const SubconeGeometry,
    gj: *const SubconeGeometry,
    si: u32,
    sj: u32,
    out: *mut f32,
) -> SubconeStatus {
    call("subcone_shadow_gated_weight", || {
        let p = sraa_params(params)?;
        // SAFETY: forwarded contract.
        let (gi, gj) = unsafe { (read(gi, "gi")?, read(gj, "gj")?) };
        let w = shadow_gated_weight(&p, &gi.into(), &gj.into(), si != 0, sj != 0);
        // SAFETY: forwarded contract.
        unsafe { write(out, w, "out") }
    })
}

/// Eq. 1 times the spatial term `exp(−d²/σs²)` for a neighbour at squared
/// screen distance `distance2` (pixels²); a NaN or infinite `distance2`
/// gives 0 when σs is on.
///
/// # Safety
/// Each pointer is null or valid.
#[no_mangle]
pub unsafe extern "C" fn subcone_reconstruction_weight(
    params: *const SubconeSraaParams,
    gi: *const SubconeGeometry,
    gj: *const SubconeGeometry,
    distance2: f32,
    out: *mut f32,
) -> SubconeStatus {
    call("subcone_reconstruction_weight", || {
        let p = sraa_params(params)?;
        // SAFETY: forwarded contract.
        let (gi, gj) = unsafe { (read(gi, "gi")?, read(gj, "gj")?) };
        let w = reconstruction_weight(&p, &gi.into(), &gj.into(), distance2);
        // SAFETY: forwarded contract.
        unsafe { write(out, w, "out") }
    })
}

/// The material gate's dissimilarity of two albedos, `max |√a − √b|` per
/// channel; `+∞` when either is not finite.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_albedo_difference(
    a: SubconeVec3,
    b: SubconeVec3,
    out: *mut f32,
) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_albedo_difference", || unsafe {
        write(out, albedo_difference(a.into(), b.into()), "out")
    })
}

/// The box resolve of a pixel's four reconstructed subsamples (a plain mean;
/// non-finite ones are dropped, none finite gives black).
///
/// # Safety
/// `subsamples` is null or points to 4 values; `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_resolve_pixel(
    subsamples: *const SubconeVec3,
    out: *mut SubconeVec3,
) -> SubconeStatus {
    call("subcone_resolve_pixel", || {
        // SAFETY: forwarded contract (4 values).
        let s = unsafe { slice(subsamples, 4, "subsamples") }?;
        let c = resolve_pixel(&[s[0].into(), s[1].into(), s[2].into(), s[3].into()]);
        // SAFETY: forwarded contract.
        unsafe { write(out, c.into(), "out") }
    })
}
