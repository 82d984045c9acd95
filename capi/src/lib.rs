//! A C ABI for subcone's kernels, for C and C++ engines: the SRAA weights
//! (SRAA for ray tracing, eq. 1 and 2) and per-pixel resolve, the CTSS cone
//! kernels (CTSS eq. 3–8) and one whole CTSS trace over a distance callback.
//! The header, `include/subcone.h`, is generated from this file by cbindgen
//! and checked in (`tests/header.rs` keeps it current).
//!
//! # Contract
//!
//! - Every fallible function returns a [`SubconeStatus`] and writes its result
//!   through an out-pointer only on [`SubconeStatus::Ok`].
//! - Null pointers, zero sizes, mismatched lengths and non-finite parameters
//!   (the fields of the parameter structs, camera and cone settings, a ray's
//!   origin and direction) are refused with an error code, never undefined
//!   behaviour. Per-sample data (depths, normals, colours, distances) may be
//!   anything: the kernels' documented domains say what they return outside
//!   them (see each function).
//! - Nothing panics across the boundary: every body runs under
//!   `catch_unwind`, and an unexpected panic becomes
//!   [`SubconeStatus::Panic`].
//! - Thread safety: every function is reentrant and thread-safe; there is no
//!   global state. [`subcone_ctss_trace`] calls its callbacks synchronously on
//!   the calling thread; they must not unwind (a C callback cannot).
//!
//! ```
//! use subcone_capi::*;
//!
//! let mut params = SubconeSraaParams::default();
//! assert_eq!(unsafe { subcone_sraa_params_paper(&mut params) }, SubconeStatus::Ok);
//! let g = SubconeGeometry { normal: SubconeVec3 { x: 0.0, y: 0.0, z: 1.0 }, depth: 2.0 };
//! let mut w = 0.0;
//! assert_eq!(unsafe { subcone_bilateral_weight(&params, &g, &g, &mut w) }, SubconeStatus::Ok);
//! assert_eq!(w, 1.0);
//! // A null pointer is an error, not a crash.
//! let e = unsafe { subcone_bilateral_weight(&params, &g, std::ptr::null(), &mut w) };
//! assert_eq!(e, SubconeStatus::NullPointer);
//! ```
#![deny(unsafe_op_in_unsafe_fn)]
#![deny(missing_docs)]

use std::ffi::c_void;
use std::panic::{catch_unwind, AssertUnwindSafe};

use glam::{Vec2, Vec3, Vec4};
use subcone_kernels::aggregate::{sample_weight, Weighting};
use subcone_kernels::camera::{in_normal_range, look_frame, PinholeCamera};
use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, cone_tan_theta,
    PixelFootprint,
};
use subcone_kernels::ctss::{
    cross_section_frame, trace_field, ConeField, CtssParams, FieldSample, SplitRay, StopReason,
};
use subcone_kernels::fxaa::{edge_clamped, fxaa_decode, fxaa_encode, fxaa_pixel, FxaaParams};
use subcone_kernels::mask::{project_normal, visibility_mask, MaskPlacement};
use subcone_kernels::sraa::{
    albedo_difference, bilateral_weight, reconstruction_weight, resolve_pixel, shadow_gated_weight,
    Geometry, Resolver, ShadedFrame, ShadedGroup, SraaParams, Subsamples, ALBEDO_TOLERANCE,
    MAX_LAYERS,
};
use subcone_kernels::taa::{jitter, resolve_pixel as taa_resolve_pixel, ResolveSpace, TaaParams};
use subcone_kernels::uniforms::{CtssUniform, SraaFrame};

/// Major version of this library (the crate's; see [`subcone_version`]).
pub const SUBCONE_VERSION_MAJOR: u32 = 0;
/// Minor version.
pub const SUBCONE_VERSION_MINOR: u32 = 2;
/// Patch version.
pub const SUBCONE_VERSION_PATCH: u32 = 0;

/// What a call did.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SubconeStatus {
    /// Success: the out-pointers were written.
    Ok = 0,
    /// A required pointer was null.
    NullPointer = 1,
    /// A parameter was not finite or out of its range (named in the function's
    /// documentation).
    InvalidArgument = 2,
    /// A size was zero, or a buffer's length does not match the sizes given.
    SizeMismatch = 3,
    /// An internal error was caught before it crossed the boundary (a bug:
    /// please report it).
    Panic = 4,
}

/// `From` both ways between a C struct and the kernels' struct it mirrors,
/// from one list of `c_field: kernels_field` pairs: both directions convert
/// the same fields, and a field added to either struct and not listed is a
/// compile error (a struct literal must name every field).
macro_rules! mirror_conversions {
    ($c:ident <=> $k:ident { $($cf:ident: $kf:ident),+ $(,)? }) => {
        impl From<$c> for $k {
            fn from(p: $c) -> $k {
                $k { $($kf: p.$cf),+ }
            }
        }

        impl From<$k> for $c {
            fn from(p: $k) -> $c {
                $c { $($cf: p.$kf),+ }
            }
        }
    };
}

/// A 3-vector: a point, a direction or a linear RGB colour.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeVec3 {
    /// x (red).
    pub x: f32,
    /// y (green).
    pub y: f32,
    /// z (blue).
    pub z: f32,
}

impl From<SubconeVec3> for Vec3 {
    fn from(v: SubconeVec3) -> Vec3 {
        Vec3::new(v.x, v.y, v.z)
    }
}

impl From<Vec3> for SubconeVec3 {
    fn from(v: Vec3) -> SubconeVec3 {
        SubconeVec3 {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

/// A sample's geometry for the SRAA weights: unit normal and view depth (the
/// distance along the view axis). 16 bytes; a NaN depth marks a miss.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeGeometry {
    /// Unit surface normal.
    pub normal: SubconeVec3,
    /// View depth; NaN for a miss.
    pub depth: f32,
}

impl From<SubconeGeometry> for Geometry {
    fn from(g: SubconeGeometry) -> Geometry {
        Geometry {
            normal: g.normal.into(),
            depth: g.depth,
        }
    }
}

/// The SRAA weight parameters, the layout of the kernels' `SraaParams`
/// (32 bytes). Fill it with [`subcone_sraa_params_default`] or
/// [`subcone_sraa_params_paper`] and adjust the σs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeSraaParams {
    /// σz of eq. 1 (relative depth difference by default).
    pub sigma_z: f32,
    /// σn of eq. 1.
    pub sigma_n: f32,
    /// The Chajdas form's scale (unused by eq. 1's product form).
    pub scale: f32,
    /// Bits 0..8: weight form (0 eq. 1's product, 1 the Chajdas form);
    /// 8..16: depth metric (0 relative, 1 absolute); 16..32: radius in
    /// pixels. Other codes read as 0, as the kernels (and their WGSL twins)
    /// read them.
    pub packed: u32,
    /// σs, the spatial falloff in pixels (0: off, as in eq. 1).
    pub sigma_s: f32,
    /// Where the shaded sample lies: 0 on subsample 0 (the paper), 1 at the
    /// pixel centre; other codes read as 0.
    pub shading: u32,
    /// Padding; write 0.
    pub pad: [u32; 2],
}

mirror_conversions!(SubconeSraaParams <=> SraaParams {
    sigma_z: sigma_z,
    sigma_n: sigma_n,
    scale: scale,
    packed: packed,
    sigma_s: sigma_s,
    shading: shading,
    pad: _pad,
});

/// The CTSS trace parameters, the layout of the kernels' `CtssParams`
/// (48 bytes). Fill it with [`subcone_ctss_params_default`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeCtssParams {
    /// `tan θ` of the pixel's cone (eq. 3, [`subcone_cone_tan_theta`]).
    pub tan_theta: f32,
    /// Minimum step factor α (§3.1).
    pub alpha: f32,
    /// ε of the occlusion thresholds (§3.2).
    pub eps: f32,
    /// First depth evaluated.
    pub t_min: f32,
    /// Depth at which the ray leaves the scene.
    pub t_max: f32,
    /// Minimum sample weight (0 by default).
    pub min_sample_weight: f32,
    /// Step budget.
    pub max_steps: u32,
    /// Sample cap.
    pub max_samples: u32,
    /// Visibility threshold k (§5.1), 1..=32; 32 is off.
    pub visibility_k: u32,
    /// Bit 0: CTSS-R (stop at the first hard hit). Bit 1: split groups at
    /// internal edges (§5.3). Bit 2: the paper's groups and masks. Bits
    /// 8..16: mask placement (as [`subcone_visibility_mask`]'s; codes above
    /// 2 read as 0). Bits 16..24: sample weighting (as
    /// [`subcone_sample_weight`]'s; codes above 1 read as 0). Other bits are
    /// ignored.
    pub flags: u32,
    /// Padding; write 0.
    pub pad: [u32; 2],
}

mirror_conversions!(SubconeCtssParams <=> CtssParams {
    tan_theta: tan_theta,
    alpha: alpha,
    eps: eps,
    t_min: t_min,
    t_max: t_max,
    min_sample_weight: min_sample_weight,
    max_steps: max_steps,
    max_samples: max_samples,
    visibility_k: visibility_k,
    flags: flags,
    pad: _pad,
});

// The mirrored structs have the kernels' layouts (a host may hand the same
// bytes to the WGSL kernels).
const _: () = {
    use std::mem::{offset_of, size_of};
    assert!(size_of::<SubconeGeometry>() == size_of::<Geometry>());
    assert!(offset_of!(SubconeGeometry, depth) == offset_of!(Geometry, depth));
    assert!(size_of::<SubconeSraaParams>() == size_of::<SraaParams>());
    assert!(offset_of!(SubconeSraaParams, sigma_s) == offset_of!(SraaParams, sigma_s));
    assert!(offset_of!(SubconeSraaParams, shading) == offset_of!(SraaParams, shading));
    assert!(size_of::<SubconeCtssParams>() == size_of::<CtssParams>());
    assert!(offset_of!(SubconeCtssParams, flags) == offset_of!(CtssParams, flags));
};

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

fn guard(f: impl FnOnce() -> SubconeStatus) -> SubconeStatus {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or(SubconeStatus::Panic)
}

/// `*p` when `p` is not null.
///
/// # Safety
/// `p` is null or points to a valid `T`.
unsafe fn read<T: Copy>(p: *const T) -> Result<T, SubconeStatus> {
    // SAFETY: the caller's contract; null was checked.
    unsafe { p.as_ref() }
        .copied()
        .ok_or(SubconeStatus::NullPointer)
}

/// Write `v` through `p` when `p` is not null.
///
/// # Safety
/// `p` is null or points to writable memory for a `T`.
unsafe fn write<T>(p: *mut T, v: T) -> SubconeStatus {
    // SAFETY: the caller's contract; null was checked.
    match unsafe { p.as_mut() } {
        Some(out) => {
            *out = v;
            SubconeStatus::Ok
        }
        None => SubconeStatus::NullPointer,
    }
}

/// Whether `len` elements at `p` can be a slice: `Ok` for `len == 0`, an
/// error for a null `p` with `len > 0` or a length that overflows the
/// address space.
fn extent<T>(p: *const T, len: usize) -> Result<(), SubconeStatus> {
    if len == 0 {
        return Ok(());
    }
    if p.is_null() {
        return Err(SubconeStatus::NullPointer);
    }
    if len
        .checked_mul(size_of::<T>())
        .is_none_or(|b| b > isize::MAX as usize)
    {
        return Err(SubconeStatus::SizeMismatch);
    }
    Ok(())
}

/// `len` elements at `p`: empty for `len == 0`, else checked by [`extent`].
///
/// # Safety
/// `p` is null or points to `len` valid, initialised `T`.
unsafe fn slice<'a, T>(p: *const T, len: usize) -> Result<&'a [T], SubconeStatus> {
    extent(p, len)?;
    if len == 0 {
        return Ok(&[]);
    }
    // SAFETY: non-null, a length that fits (checked), the caller's contract
    // on validity.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// `len` writable elements at `p`, checked as [`slice`] checks.
///
/// # Safety
/// `p` is null or points to `len` writable `T`, not otherwise borrowed.
unsafe fn slice_mut<'a, T>(p: *mut T, len: usize) -> Result<&'a mut [T], SubconeStatus> {
    extent(p.cast_const(), len)?;
    if len == 0 {
        return Ok(&mut []);
    }
    // SAFETY: as `slice`.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, len) })
}

fn finite(values: &[f32]) -> Result<(), SubconeStatus> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SubconeStatus::InvalidArgument)
    }
}

fn sraa_params(p: *const SubconeSraaParams) -> Result<SraaParams, SubconeStatus> {
    // SAFETY: `p` comes from the caller's contract on the exported function.
    let p = unsafe { read(p) }?;
    finite(&[p.sigma_z, p.sigma_n, p.scale, p.sigma_s])?;
    Ok(p.into())
}

fn status(r: Result<SubconeStatus, SubconeStatus>) -> SubconeStatus {
    r.unwrap_or_else(|e| e)
}

/// The library's version: `major << 16 | minor << 8 | patch`; compare it
/// with the header's `SUBCONE_VERSION_*` to catch a mismatched library.
#[no_mangle]
pub extern "C" fn subcone_version() -> u32 {
    SUBCONE_VERSION_MAJOR << 16 | SUBCONE_VERSION_MINOR << 8 | SUBCONE_VERSION_PATCH
}

/// The default SRAA parameters (σz 10, σn 1, σs 0.4 px, shaded sample at the
/// pixel centre; the Rust `SraaParams::TUNED`).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_params_default(out: *mut SubconeSraaParams) -> SubconeStatus {
    // SAFETY: forwarded contract.
    guard(|| unsafe { write(out, SraaParams::TUNED.into()) })
}

/// The SRAA paper's parameters (§3.1: σz 10, σn 0.25, eq. 1 as published,
/// the shaded sample on subsample 0).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_params_paper(out: *mut SubconeSraaParams) -> SubconeStatus {
    // SAFETY: forwarded contract.
    guard(|| unsafe { write(out, SraaParams::PAPER.into()) })
}

/// The default CTSS parameters for a cone of `tan_theta` (α 0.5, ε 0.01, up
/// to 8 samples, subcone's default groups and masks). `tan_theta` must be
/// finite and not negative.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_ctss_params_default(
    tan_theta: f32,
    out: *mut SubconeCtssParams,
) -> SubconeStatus {
    guard(|| {
        if !(tan_theta.is_finite() && tan_theta >= 0.0) {
            return SubconeStatus::InvalidArgument;
        }
        // SAFETY: forwarded contract.
        unsafe { write(out, CtssParams::new(tan_theta).into()) }
    })
}

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
    guard(|| {
        status((|| {
            let p = sraa_params(params)?;
            // SAFETY: forwarded contract.
            let (gi, gj) = unsafe { (read(gi)?, read(gj)?) };
            // SAFETY: forwarded contract.
            Ok(unsafe { write(out, bilateral_weight(&p, &gi.into(), &gj.into())) })
        })())
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
    guard(|| {
        status((|| {
            let p = sraa_params(params)?;
            // SAFETY: forwarded contract.
            let (gi, gj) = unsafe { (read(gi)?, read(gj)?) };
            let w = shadow_gated_weight(&p, &gi.into(), &gj.into(), si != 0, sj != 0);
            // SAFETY: forwarded contract.
            Ok(unsafe { write(out, w) })
        })())
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
    guard(|| {
        status((|| {
            let p = sraa_params(params)?;
            // SAFETY: forwarded contract.
            let (gi, gj) = unsafe { (read(gi)?, read(gj)?) };
            let w = reconstruction_weight(&p, &gi.into(), &gj.into(), distance2);
            // SAFETY: forwarded contract.
            Ok(unsafe { write(out, w) })
        })())
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
    guard(|| unsafe { write(out, albedo_difference(a.into(), b.into())) })
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
    guard(|| {
        status((|| {
            // SAFETY: forwarded contract (4 values).
            let s = unsafe { slice(subsamples, 4) }?;
            let c = resolve_pixel(&[s[0].into(), s[1].into(), s[2].into(), s[3].into()]);
            // SAFETY: forwarded contract.
            Ok(unsafe { write(out, c.into()) })
        })())
    })
}

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
    guard(|| {
        let fp = match footprint {
            0 => PixelFootprint::Circumscribed,
            1 => PixelFootprint::Balanced,
            2 => PixelFootprint::Inscribed,
            _ => return SubconeStatus::InvalidArgument,
        };
        let fov_ok = fov_y > 0.0 && fov_y < std::f32::consts::PI;
        if !fov_ok || height == 0 || !(coverage.is_finite() && coverage > 0.0) {
            return SubconeStatus::InvalidArgument;
        }
        // SAFETY: forwarded contract.
        unsafe { write(out, cone_tan_theta(fov_y, height, coverage, fp)) }
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
    guard(|| unsafe { write(out, cone_radius(t, tan_theta)) })
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
    guard(|| unsafe { write(out, cone_occlusion(d, rc)) })
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
    guard(|| unsafe { write(out, advance(t, d, alpha, rc)) })
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
    guard(|| unsafe { write(out, backtrace_cone_entry(t_i, tan_theta)) })
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
    guard(|| unsafe { write(out, backtrace_hard_hit(t_prev, d_prev, t_i)) })
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
    guard(|| {
        let n = project_normal(normal.into(), right.into(), up.into());
        // SAFETY: forwarded contract (2 floats).
        unsafe { write(out.cast::<[f32; 2]>(), n.to_array()) }
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
    guard(|| {
        if placement > 2 {
            return SubconeStatus::InvalidArgument;
        }
        let m = visibility_mask(
            occlusion,
            Vec2::new(nx, ny),
            MaskPlacement::from_u32(placement),
        );
        // SAFETY: forwarded contract.
        unsafe { write(out, m) }
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
    guard(|| {
        if weighting > 1 || !min_weight.is_finite() {
            return SubconeStatus::InvalidArgument;
        }
        let w = sample_weight(visible, Weighting::from_u32(weighting), min_weight);
        // SAFETY: forwarded contract.
        unsafe { write(out, w) }
    })
}

/// A frame's worth of SRAA input for [`subcone_sraa_resolve`], in
/// caller-owned CPU buffers (row-major, `width × height` pixels).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct SubconeSraaFrame {
    /// Image width in pixels (> 0).
    pub width: u32,
    /// Image height in pixels (> 0).
    pub height: u32,
    /// Shaded layers per pixel, 1..=16 (`layer_lights` gives each its gate).
    pub layers: u32,
    /// `width·height·layers` linear RGB colours: every pixel's shaded sample,
    /// one colour per layer (e.g. layer 0 ambient and indirect, layer `1 + l`
    /// light `l`'s direct light).
    pub colors: *const SubconeVec3,
    /// Length of `colors`.
    pub colors_len: usize,
    /// `layers` entries: the light whose shadow gates each layer (eq. 2), or
    /// −1 for an ungated layer (eq. 1). Null: every layer ungated.
    pub layer_lights: *const i8,
    /// `width·height` geometries of the shaded samples.
    pub shaded_geometry: *const SubconeGeometry,
    /// Length of `shaded_geometry`.
    pub shaded_geometry_len: usize,
    /// `width·height` shadow bit sets of the shaded samples (bit `l`: in light
    /// `l`'s shadow), or null for none.
    pub shaded_shadow: *const u32,
    /// Length of `shaded_shadow` (0 when null).
    pub shaded_shadow_len: usize,
    /// `4·width·height` geometries of the four subsamples of every pixel, at
    /// `SUBPIXEL_OFFSETS` (the 4× MSAA pattern: (−⅛,−⅜), (⅜,−⅛), (−⅜,⅛),
    /// (⅛,⅜)), pixel by pixel.
    pub subsample_geometry: *const SubconeGeometry,
    /// Length of `subsample_geometry`.
    pub subsample_geometry_len: usize,
    /// `4·width·height` shadow bit sets of the subsamples, or null for none.
    pub subsample_shadow: *const u32,
    /// Length of `subsample_shadow` (0 when null).
    pub subsample_shadow_len: usize,
}

/// SRAA's antialiasing pass (§3, pass 2) over a whole frame: every layer of
/// every subsample reconstructed from the 3×3 neighbourhood's shaded samples
/// (eq. 1, gated by eq. 2 per light), then the box resolve, written to `out`
/// (`width·height` colours). The same loop, to the bit, as the CPU backend's
/// (the kernels' `sraa::Resolver`). Primary hits only: reconstruct the
/// reflections on their own geometry with a second call and add.
///
/// Errors: null pointers where data is required, a zero size or more than 16
/// layers, lengths that do not match the sizes, a gate naming a light above
/// 31, non-finite parameters.
///
/// # Safety
/// Every pointer is null or points to as many valid values as its length says.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_resolve(
    params: *const SubconeSraaParams,
    frame: *const SubconeSraaFrame,
    out: *mut SubconeVec3,
    out_len: usize,
) -> SubconeStatus {
    // SAFETY: forwarded contract.
    guard(|| status(unsafe { sraa_resolve(params, frame, out, out_len) }))
}

/// # Safety
/// As [`subcone_sraa_resolve`].
unsafe fn sraa_resolve(
    params: *const SubconeSraaParams,
    frame: *const SubconeSraaFrame,
    out: *mut SubconeVec3,
    out_len: usize,
) -> Result<SubconeStatus, SubconeStatus> {
    let p = sraa_params(params)?;
    // SAFETY: forwarded contract.
    let f = unsafe { read(frame) }?;
    let (w, h, layers) = (f.width as usize, f.height as usize, f.layers as usize);
    if w == 0 || h == 0 || layers == 0 || layers > MAX_LAYERS {
        return Err(SubconeStatus::SizeMismatch);
    }
    let n = w.checked_mul(h).ok_or(SubconeStatus::SizeMismatch)?;
    let exact = |len: usize, want: Option<usize>| match want {
        Some(want) if len == want => Ok(()),
        _ => Err(SubconeStatus::SizeMismatch),
    };
    exact(f.colors_len, n.checked_mul(layers))?;
    exact(f.shaded_geometry_len, Some(n))?;
    exact(f.subsample_geometry_len, n.checked_mul(4))?;
    exact(out_len, Some(n))?;
    let optional = |len: usize, want: usize| {
        if len == 0 || len == want {
            Ok(())
        } else {
            Err(SubconeStatus::SizeMismatch)
        }
    };
    optional(f.shaded_shadow_len, n)?;
    optional(f.subsample_shadow_len, 4 * n)?;
    // SAFETY: lengths checked above against the sizes; pointers per contract.
    let (colors, geometry, shadow, sub_geometry, sub_shadow, gates) = unsafe {
        (
            slice(f.colors, f.colors_len)?,
            slice(f.shaded_geometry, f.shaded_geometry_len)?,
            slice(f.shaded_shadow, f.shaded_shadow_len)?,
            slice(f.subsample_geometry, f.subsample_geometry_len)?,
            slice(f.subsample_shadow, f.subsample_shadow_len)?,
            if f.layer_lights.is_null() {
                &[][..]
            } else {
                slice(f.layer_lights, layers)?
            },
        )
    };
    // SAFETY: `out` is null or holds `out_len` values (the caller's
    // contract), and `out_len` is `n` (checked above).
    let out = unsafe { slice_mut(out, out_len) }?;
    let mut layer_gates = [None; MAX_LAYERS];
    for (g, &l) in layer_gates.iter_mut().zip(gates) {
        *g = match l {
            l if l < 0 => None,
            l if l < 32 => Some(l as u8),
            _ => return Err(SubconeStatus::InvalidArgument),
        };
    }
    // The kernels take glam types: the same layouts (checked above), copied
    // rather than reinterpreted.
    let colors: Vec<Vec3> = colors.iter().map(|&c| c.into()).collect();
    let geometry: Vec<Geometry> = geometry.iter().map(|&g| g.into()).collect();
    let resolver = Resolver::new(&p, &layer_gates[..layers], ALBEDO_TOLERANCE);
    let shaded = ShadedFrame {
        width: f.width,
        height: f.height,
        colors: &colors,
        layers,
        albedo: &[],
        primary: ShadedGroup {
            geometry: &geometry,
            shadow,
            first_layer: 0,
        },
        secondary: None,
    };
    for (j, o) in out.iter_mut().enumerate() {
        let g = &sub_geometry[4 * j..4 * j + 4];
        let subsamples = Subsamples {
            geometry: [g[0].into(), g[1].into(), g[2].into(), g[3].into()],
            shadow: match sub_shadow.get(4 * j..4 * j + 4) {
                Some(s) => [s[0], s[1], s[2], s[3]],
                None => [0; 4],
            },
            albedo: None,
        };
        let (x, y) = ((j % w) as u32, (j / w) as u32);
        *o = resolver.resolve(&shaded, x, y, &subsamples, None).into();
    }
    Ok(SubconeStatus::Ok)
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
    guard(|| {
        status((|| {
            // SAFETY: forwarded contract.
            let p: CtssParams = unsafe { read(params) }?.into();
            let (Some(distance), Some(shade)) = (distance, shade) else {
                return Err(SubconeStatus::NullPointer);
            };
            if out.is_null() {
                return Err(SubconeStatus::NullPointer);
            }
            finite(&[
                p.tan_theta,
                p.alpha,
                p.eps,
                p.t_min,
                p.t_max,
                p.min_sample_weight,
            ])?;
            let (origin, dir, up_hint) = (Vec3::from(origin), Vec3::from(dir), Vec3::from(up_hint));
            if !(origin.is_finite() && dir.is_finite() && up_hint.is_finite())
                || dir == Vec3::ZERO
                || p.tan_theta < 0.0
                || !(1..=32).contains(&p.visibility_k)
            {
                return Err(SubconeStatus::InvalidArgument);
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
            Ok(unsafe { write(out, result) })
        })())
    })
}

/// The uniform of the SRAA pass's shaders (`SraaFrame`, binding `frame` of
/// every `shaders/sraa/*` variant; the kernels' `uniforms::SraaFrame`, 80
/// bytes, its layout checked against naga's). Fill it with
/// [`subcone_sraa_pass_uniform`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeSraaPassUniform {
    /// The weights' parameters.
    pub sraa: SubconeSraaParams,
    /// Column-major `m[2][2], m[3][2], m[2][3], m[3][3]` of the projection
    /// that wrote hardware depth (zero for linear view depth).
    pub projection: [f32; 4],
    /// The image's (or rect's) width in pixels.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// The hardware depth of a miss (0 for reversed Z).
    pub depth_miss: f32,
    /// The material gate's tolerance (the kernels' `ALBEDO_TOLERANCE`).
    pub albedo_tolerance: f32,
    /// The rect's first pixel (0 for a whole image and for buffers).
    pub origin_x: u32,
    /// The rect's first row.
    pub origin_y: u32,
    /// The tone-mapped resolve's exposure (read only by a tone-mapped
    /// variant).
    pub exposure: f32,
    /// Padding; write 0.
    pub pad: u32,
}

impl From<SraaFrame> for SubconeSraaPassUniform {
    fn from(f: SraaFrame) -> Self {
        SubconeSraaPassUniform {
            sraa: f.sraa.into(),
            projection: f.projection,
            width: f.width,
            height: f.height,
            depth_miss: f.depth_miss,
            albedo_tolerance: f.albedo_tolerance,
            origin_x: f.origin_x,
            origin_y: f.origin_y,
            exposure: f.exposure,
            pad: f._pad,
        }
    }
}

/// The pinhole camera every CTSS shader traces through, the layout of the
/// kernels' `PinholeCamera` (80 bytes, `subcone_PinholeCamera` in WGSL):
/// pixel `(x, y)` of a `width × height` image is the ray through image
/// point `(x + ½, y + ½) + jitter` ([`subcone_pinhole_ray`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconePinholeCamera {
    /// The eye.
    pub position: [f32; 3],
    /// The image's width in pixels.
    pub width: u32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// The image's height in pixels.
    pub height: u32,
    /// Unit right vector (forward × up).
    pub right: [f32; 3],
    /// `tan(fov_y / 2)`.
    pub tan_half_fov: f32,
    /// Unit up vector.
    pub up: [f32; 3],
    /// Padding; write 0.
    pub pad0: u32,
    /// Sub-pixel offset of every ray, in pixels (a temporal method's
    /// jitter; 0 otherwise).
    pub jitter: [f32; 2],
    /// Padding; write 0.
    pub pad1: [u32; 2],
}

mirror_conversions!(SubconePinholeCamera <=> PinholeCamera {
    position: position,
    width: width,
    forward: forward,
    height: height,
    right: right,
    tan_half_fov: tan_half_fov,
    up: up,
    pad0: _pad,
    jitter: jitter,
    pad1: _pad2,
});

/// The uniform of the CTSS pass's shaders (`CtssUniform`, binding
/// `subcone_pass_frame` of every `shaders/ctss/*` variant; the kernels'
/// `uniforms::CtssUniform`, 192 bytes, its layout checked against naga's).
/// Fill it with [`subcone_ctss_pass_uniform`]; the trace's parameters are a
/// [`SubconeCtssParams`] at `subcone_pass_params`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeCtssPassUniform {
    /// The camera.
    pub camera: SubconePinholeCamera,
    /// The colour of what no surface covers (linear RGB).
    pub background: [f32; 3],
    /// 0: the pinhole `camera`; 1 and 2: a projection matrix (written by
    /// the Rust pass's `CtssProjection`).
    pub projection: u32,
    /// NDC to world, column-major (zero for the pinhole).
    pub inverse_view_projection: [[f32; 4]; 4],
    /// The unit axis of view depth (`forward·x + depth_offset`).
    pub forward: [f32; 3],
    /// View depth's offset (the eye at depth 0).
    pub depth_offset: f32,
    /// The first pixel written.
    pub origin: [u32; 2],
    /// The output's width: a buffer row's length.
    pub row_length: u32,
    /// Padding; write 0.
    pub pad: u32,
}

impl From<CtssUniform> for SubconeCtssPassUniform {
    fn from(u: CtssUniform) -> Self {
        SubconeCtssPassUniform {
            camera: u.camera.into(),
            background: u.background,
            projection: u.projection,
            inverse_view_projection: u.inverse_view_projection,
            forward: u.forward,
            depth_offset: u.depth_offset,
            origin: u.origin,
            row_length: u.row_length,
            pad: u._pad,
        }
    }
}

/// The SRAA pass's uniform for a `width × height` image resolved with
/// `params`: geometry of linear view depth (`shaders/sraa/packed`,
/// `buffers*`) when `projection` is null, else hardware depth written by
/// `projection` (16 floats, column-major, the host's projection matrix;
/// `shaders/sraa/msaa*`) with `depth_miss` the depth of a miss. `exposure`
/// is the tone-mapped resolve's (0 for the linear one). The values the
/// Rust `SraaPass` writes (the kernels' `SraaFrame::new`).
///
/// Errors: null `params` or `out`; a zero size; non-finite parameters,
/// projection or `depth_miss`; a negative or non-finite `exposure`.
///
/// # Safety
/// `params` and `out` are null or valid; `projection` is null or points to
/// 16 floats.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_pass_uniform(
    params: *const SubconeSraaParams,
    width: u32,
    height: u32,
    projection: *const f32,
    depth_miss: f32,
    exposure: f32,
    out: *mut SubconeSraaPassUniform,
) -> SubconeStatus {
    guard(|| {
        status((|| {
            let p = sraa_params(params)?;
            if width == 0 || height == 0 {
                return Err(SubconeStatus::SizeMismatch);
            }
            finite(&[depth_miss, exposure])?;
            if exposure < 0.0 {
                return Err(SubconeStatus::InvalidArgument);
            }
            // SAFETY: forwarded contract (null: linear depth).
            let m = unsafe { slice(projection, if projection.is_null() { 0 } else { 16 }) }?;
            finite(m)?;
            // Column c of the column-major matrix is m[4c..4c + 4].
            let hardware_depth = (!m.is_empty()).then(|| {
                let column = |c: usize| [m[4 * c], m[4 * c + 1], m[4 * c + 2], m[4 * c + 3]];
                ([column(0), column(1), column(2), column(3)], depth_miss)
            });
            let resolve = if exposure > 0.0 {
                ResolveSpace::ToneMapped { exposure }
            } else {
                ResolveSpace::Linear
            };
            let frame = SraaFrame::new(p, (0, 0), (width, height), hardware_depth, resolve);
            // SAFETY: forwarded contract.
            Ok(unsafe { write(out, frame.into()) })
        })())
    })
}

/// The CTSS pass's uniform for a pinhole camera at `eye` looking along
/// `forward` (`up_hint` roughly up, not parallel to it), vertical field of
/// view `fov_y` radians, a `width × height` image and `background`: pixel
/// `(x, y)` is the cone around the ray through `(x + ½, y + ½)`, exactly the
/// rays of the Rust `CtssCamera` (the kernels' `PinholeCamera`), which
/// [`subcone_ctss_trace`] takes as `origin`, `dir` and `up_hint`. The values
/// the Rust `CtssPass` writes (the kernels' `CtssUniform::pinhole`).
///
/// Errors: null `out`; a zero size; non-finite or degenerate camera
/// vectors (zero, or `forward` within a sine of 10⁻⁴ of parallel to
/// `up_hint`, the kernels' `LOOK_FRAME_MIN_SINE`, where the cross product
/// cancels too much to give a frame); `fov_y` outside `(0, π)`; a
/// non-finite background.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_ctss_pass_uniform(
    eye: SubconeVec3,
    forward: SubconeVec3,
    up_hint: SubconeVec3,
    fov_y: f32,
    width: u32,
    height: u32,
    background: SubconeVec3,
    out: *mut SubconeCtssPassUniform,
) -> SubconeStatus {
    guard(|| {
        status((|| {
            if width == 0 || height == 0 {
                return Err(SubconeStatus::SizeMismatch);
            }
            let (eye, forward, up_hint, background) = (
                Vec3::from(eye),
                Vec3::from(forward),
                Vec3::from(up_hint),
                Vec3::from(background),
            );
            finite(&[fov_y])?;
            for v in [eye, forward, up_hint, background] {
                finite(&v.to_array())?;
            }
            if !(fov_y > 0.0 && fov_y < std::f32::consts::PI) {
                return Err(SubconeStatus::InvalidArgument);
            }
            // The Rust `CtssCamera::new`'s frame: right = forward × up.
            let (forward, right, up) = look_frame(forward, up_hint);
            if forward == Vec3::ZERO || right == Vec3::ZERO {
                return Err(SubconeStatus::InvalidArgument);
            }
            let camera = PinholeCamera::new(
                eye,
                (forward, right, up),
                (0.5 * fov_y).tan(),
                (width, height),
            );
            let uniform = CtssUniform::pinhole(camera, background, [0, 0], width);
            // SAFETY: forwarded contract.
            Ok(unsafe { write(out, uniform.into()) })
        })())
    })
}

/// The unit direction of the ray through image point `(x, y)` (pixels, y
/// down; a pixel's centre is `(x + ½, y + ½)`) of the pinhole camera of
/// `uniform`: the direction the CTSS shaders trace (`subcone_pinhole_dir`),
/// to the bit on the CPU, for a host that traces the same pixel with
/// [`subcone_ctss_trace`] (`origin` the camera's `position`, `up_hint` its
/// `up`).
///
/// Errors: null pointers; a uniform that is not a pinhole (`projection`
/// not 0); non-finite `x`, `y` or camera.
///
/// # Safety
/// `uniform` and `out` are null or valid.
#[no_mangle]
pub unsafe extern "C" fn subcone_pinhole_ray(
    uniform: *const SubconeCtssPassUniform,
    x: f32,
    y: f32,
    out: *mut SubconeVec3,
) -> SubconeStatus {
    guard(|| {
        status((|| {
            // SAFETY: forwarded contract.
            let u = unsafe { read(uniform) }?;
            if u.projection != 0 {
                return Err(SubconeStatus::InvalidArgument);
            }
            let camera = PinholeCamera::from(u.camera);
            finite(&[x, y, camera.tan_half_fov])?;
            for v in [camera.forward, camera.right, camera.up] {
                finite(&v)?;
            }
            finite(&camera.jitter)?;
            // SAFETY: forwarded contract.
            Ok(unsafe { write(out, camera.ray_dir(Vec2::new(x, y)).into()) })
        })())
    })
}

/// FXAA 3.11's parameters, the layout of the kernels' `FxaaParams` (16
/// bytes; `fxaa_params` of `shaders/fxaa/*`). Fill it with
/// [`subcone_fxaa_params_quality`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeFxaaParams {
    /// `fxaaQualitySubpix`, in `[0, 1]`.
    pub subpix: f32,
    /// `fxaaQualityEdgeThreshold`.
    pub edge_threshold: f32,
    /// `fxaaQualityEdgeThresholdMin`.
    pub edge_threshold_min: f32,
    /// Padding; write 0.
    pub pad: f32,
}

mirror_conversions!(SubconeFxaaParams <=> FxaaParams {
    subpix: subpix,
    edge_threshold: edge_threshold,
    edge_threshold_min: edge_threshold_min,
    pad: _pad,
});

/// The FXAA pass's frame (`FxaaFrame`, binding `fxaa_frame` of
/// `shaders/fxaa/*`; 16 bytes). Fill it with [`subcone_fxaa_pass_frame`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeFxaaPassFrame {
    /// The image's width in pixels.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// Padding; write 0.
    pub pad: [u32; 2],
}

/// One TAA resolve's parameters, the layout of the kernels' `TaaParams`
/// (32 bytes; `taa_params` of `shaders/taa/*`). Fill it with
/// [`subcone_taa_params`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeTaaParams {
    /// The tone-mapped resolve's exposure.
    pub exposure: f32,
    /// The smallest weight of the current frame, in `(0, 1]`.
    pub min_current_weight: f32,
    /// Variance clipping's `γ`.
    pub clip_gamma: f32,
    /// Frames the history holds: 0 after a reset (a camera cut).
    pub history_frames: u32,
    /// The image's width in pixels.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// 1: clip and blend in Karis' tone-mapped space; 0: linear.
    pub tone_mapped: u32,
    /// Padding; write 0.
    pub pad: u32,
}

mirror_conversions!(SubconeTaaParams <=> TaaParams {
    exposure: exposure,
    min_current_weight: min_current_weight,
    clip_gamma: clip_gamma,
    history_frames: history_frames,
    width: width,
    height: height,
    tone_mapped: tone_mapped,
    pad: _pad,
});

/// The TAA pass's origin (`TaaOrigin`, binding `taa_origin` of
/// `shaders/taa/*`; 16 bytes): the first pixel of the rect resolved, zero
/// for whole textures.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeTaaPassOrigin {
    /// The rect's first column.
    pub x: u32,
    /// Its first row.
    pub y: u32,
    /// Padding; write 0.
    pub pad: [u32; 2],
}

/// FXAA 3.11's quality defaults (subpix 0.75, edge threshold 0.166, edge
/// threshold min 0.0833; the Rust `FxaaParams::QUALITY`).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_fxaa_params_quality(out: *mut SubconeFxaaParams) -> SubconeStatus {
    // SAFETY: forwarded contract.
    guard(|| unsafe { write(out, FxaaParams::QUALITY.into()) })
}

/// The FXAA pass's frame for a `width × height` image.
///
/// Errors: a zero size; null `out`.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_fxaa_pass_frame(
    width: u32,
    height: u32,
    out: *mut SubconeFxaaPassFrame,
) -> SubconeStatus {
    guard(|| {
        if width == 0 || height == 0 {
            return SubconeStatus::SizeMismatch;
        }
        let frame = SubconeFxaaPassFrame {
            width,
            height,
            pad: [0; 2],
        };
        // SAFETY: forwarded contract.
        unsafe { write(out, frame) }
    })
}

/// The TAA resolve's parameters for a `width × height` image whose history
/// holds `history_frames` frames (0 after a reset), with the kernels'
/// defaults (`MIN_CURRENT_WEIGHT`, `CLIP_GAMMA`), resolved in linear
/// radiance when `exposure` is 0 and in Karis' tone-mapped space at
/// `exposure` otherwise: the Rust `TaaParams::new(size).with_space(..)
/// .with_history_frames(..)`, what the Rust `TaaPass` writes.
///
/// Errors: a zero size; a negative or non-finite `exposure`; null `out`.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_taa_params(
    width: u32,
    height: u32,
    history_frames: u32,
    exposure: f32,
    out: *mut SubconeTaaParams,
) -> SubconeStatus {
    guard(|| {
        if width == 0 || height == 0 {
            return SubconeStatus::SizeMismatch;
        }
        if !(exposure.is_finite() && exposure >= 0.0) {
            return SubconeStatus::InvalidArgument;
        }
        let space = if exposure > 0.0 {
            ResolveSpace::ToneMapped { exposure }
        } else {
            ResolveSpace::Linear
        };
        let p = TaaParams::new((width, height))
            .with_space(space)
            .with_history_frames(history_frames);
        // SAFETY: forwarded contract.
        unsafe { write(out, p.into()) }
    })
}

/// Frame `frame`'s sub-pixel jitter of a TAA sequence of `phases` phases
/// (Halton (2, 3), in `[-½, ½)` pixels; 8 is Karis', 16 the Rust default):
/// the offset a host adds to every pixel's sample position of that frame,
/// `(*x, *y)`.
///
/// Errors: `phases` 0; null `x` or `y`.
///
/// # Safety
/// `x` and `y` are null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_taa_jitter(
    frame: u32,
    phases: u32,
    x: *mut f32,
    y: *mut f32,
) -> SubconeStatus {
    guard(|| {
        if x.is_null() || y.is_null() {
            return SubconeStatus::NullPointer;
        }
        if phases == 0 {
            return SubconeStatus::InvalidArgument;
        }
        let j = jitter(frame, phases);
        // SAFETY: forwarded contract; both checked non-null.
        unsafe {
            write(x, j.x);
            write(y, j.y)
        }
    })
}

/// The pixel count of a `width × height` image and the length of a buffer
/// of `per_pixel` floats per pixel: errors on a zero size or an overflow.
fn image_len(width: u32, height: u32, per_pixel: usize) -> Result<(usize, usize), SubconeStatus> {
    if width == 0 || height == 0 {
        return Err(SubconeStatus::SizeMismatch);
    }
    let n = (width as usize)
        .checked_mul(height as usize)
        .ok_or(SubconeStatus::SizeMismatch)?;
    let len = n
        .checked_mul(per_pixel)
        .ok_or(SubconeStatus::SizeMismatch)?;
    Ok((n, len))
}

/// `len` must be `want`.
fn exact_len(len: usize, want: usize) -> Result<(), SubconeStatus> {
    if len == want {
        Ok(())
    } else {
        Err(SubconeStatus::SizeMismatch)
    }
}

/// FXAA 3.11 (quality preset 12, `subcone_kernels::fxaa`) over a whole
/// `width × height` image on the CPU: what `shaders/fxaa/*` computes, and
/// the same loop as the Rust CPU backend's post-process. `src` and `dst` are
/// `4·width·height` floats, RGBA row by row, linear colour (alpha ignored
/// on input, written as 1). Each texel is clamped to `[0, 1]` (NaN reads as
/// 0) and sRGB-encoded with its luma before it is filtered, as the shader
/// does through its fetch; reads outside the image clamp to its edge. Every
/// output is finite and in `[0, 1]`.
///
/// Errors: null pointers; a zero size or lengths that do not match it;
/// non-finite parameters.
///
/// # Safety
/// `params` is null or valid; `src` is null or holds `src_len` floats;
/// `dst` is null or holds `dst_len` writable floats that do not overlap
/// `src`.
#[no_mangle]
pub unsafe extern "C" fn subcone_fxaa_image(
    params: *const SubconeFxaaParams,
    width: u32,
    height: u32,
    src: *const f32,
    src_len: usize,
    dst: *mut f32,
    dst_len: usize,
) -> SubconeStatus {
    guard(|| {
        status((|| {
            // SAFETY: forwarded contract.
            let p = unsafe { read(params) }?;
            finite(&[p.subpix, p.edge_threshold, p.edge_threshold_min])?;
            let p = FxaaParams::from(p);
            let (_, len) = image_len(width, height, 4)?;
            exact_len(src_len, len)?;
            exact_len(dst_len, len)?;
            // SAFETY: lengths checked against the size; pointers per contract.
            let (src, dst) = unsafe { (slice(src, src_len)?, slice_mut(dst, dst_len)?) };
            let encoded: Vec<Vec4> = src
                .chunks_exact(4)
                .map(|t| fxaa_encode(Vec3::new(t[0], t[1], t[2])))
                .collect();
            let fetch = edge_clamped(&encoded, width, height);
            let w = width as usize;
            for (i, out) in dst.chunks_exact_mut(4).enumerate() {
                let (x, y) = ((i % w) as i32, (i / w) as i32);
                let c = fxaa_decode(fxaa_pixel(&fetch, x, y, &p));
                out.copy_from_slice(&[c.x, c.y, c.z, 1.0]);
            }
            Ok(SubconeStatus::Ok)
        })())
    })
}

/// One TAA resolve (`subcone_kernels::taa::resolve_pixel`: Karis 2014 with
/// Salvi's variance clipping) of every pixel of a `params.width ×
/// params.height` image on the CPU: what `shaders/taa/*` computes for a
/// whole texture. `current` and `history` are `4·width·height` floats (RGBA
/// row by row, linear radiance, alpha ignored), `velocity` `2·width·height`
/// (each pixel's motion in pixels, current minus previous); `out` receives
/// `4·width·height` floats, alpha 1. With `params.history_frames == 0` the
/// history is not read and may be null with length 0. Every output is
/// finite and non-negative, whatever the colours and velocities hold.
///
/// Errors: null pointers where data is required; a zero size or lengths
/// that do not match it; non-finite parameters.
///
/// # Safety
/// Every pointer is null or points to as many valid floats as its length
/// says; `out` does not overlap the inputs.
#[no_mangle]
pub unsafe extern "C" fn subcone_taa_resolve(
    params: *const SubconeTaaParams,
    current: *const f32,
    current_len: usize,
    velocity: *const f32,
    velocity_len: usize,
    history: *const f32,
    history_len: usize,
    out: *mut f32,
    out_len: usize,
) -> SubconeStatus {
    guard(|| {
        status((|| {
            // SAFETY: forwarded contract.
            let p = unsafe { read(params) }?;
            finite(&[p.exposure, p.min_current_weight, p.clip_gamma])?;
            let p = TaaParams::from(p);
            let (n, len) = image_len(p.width, p.height, 4)?;
            exact_len(current_len, len)?;
            exact_len(velocity_len, 2 * n)?;
            exact_len(out_len, len)?;
            // The history may be empty only when it is not read.
            if p.history_frames != 0 || history_len != 0 {
                exact_len(history_len, len)?;
            }
            // SAFETY: lengths checked against the size; pointers per contract.
            let (current, velocity, history, out) = unsafe {
                (
                    slice(current, current_len)?,
                    slice(velocity, velocity_len)?,
                    slice(history, history_len)?,
                    slice_mut(out, out_len)?,
                )
            };
            let w = p.width as usize;
            let rgb = |b: &[f32], x: i32, y: i32| {
                let i = 4 * (y as usize * w + x as usize);
                Vec3::new(b[i], b[i + 1], b[i + 2])
            };
            let current_at = |x: i32, y: i32| rgb(current, x, y);
            // Never called when the history is empty: the kernel reads it
            // only when `history_frames > 0`, and then its length is checked.
            let history_at = |x: i32, y: i32| rgb(history, x, y);
            for (i, o) in out.chunks_exact_mut(4).enumerate() {
                let (x, y) = ((i % w) as i32, (i / w) as i32);
                let v = Vec2::new(velocity[2 * i], velocity[2 * i + 1]);
                let c = taa_resolve_pixel(&current_at, &history_at, (x, y), v, &p);
                o.copy_from_slice(&[c.x, c.y, c.z, 1.0]);
            }
            Ok(SubconeStatus::Ok)
        })())
    })
}

// The pass uniforms have the layouts of the shaders' (the test
// `pass_uniforms` compares every member with naga's layout of the WGSL).
const _: () = {
    use std::mem::size_of;
    assert!(size_of::<SubconeSraaPassUniform>() == 80);
    assert!(size_of::<SubconeCtssPassUniform>() == 192);
    assert!(size_of::<SubconeFxaaParams>() == size_of::<FxaaParams>());
    assert!(size_of::<SubconeFxaaPassFrame>() == 16);
    assert!(size_of::<SubconeTaaParams>() == size_of::<TaaParams>());
    assert!(size_of::<SubconeTaaPassOrigin>() == 16);
};
