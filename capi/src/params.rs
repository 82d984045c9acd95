//! The parameter structs of the SRAA weights and the CTSS trace, and their
//! defaults.

use subcone_kernels::ctss::CtssParams;
use subcone_kernels::sraa::SraaParams;

use crate::checks::{finite, read, write};
use crate::status::{call, Checked, Refusal, SubconeStatus};
// The functions the structs' documentation names.
#[cfg(doc)]
use crate::ctss_cone::{subcone_cone_tan_theta, subcone_sample_weight, subcone_visibility_mask};

/// The SRAA weight parameters, the layout of the kernels' `SraaParams`
/// (32 bytes; no leading `size`, as the shaders read these bytes as they
/// are). Fill it with [`subcone_sraa_params_default`] or
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
/// (48 bytes; no leading `size`, as the shaders read these bytes as they
/// are). Fill it with [`subcone_ctss_params_default`].
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
    assert!(size_of::<SubconeSraaParams>() == size_of::<SraaParams>());
    assert!(offset_of!(SubconeSraaParams, sigma_s) == offset_of!(SraaParams, sigma_s));
    assert!(offset_of!(SubconeSraaParams, shading) == offset_of!(SraaParams, shading));
    assert!(size_of::<SubconeCtssParams>() == size_of::<CtssParams>());
    assert!(offset_of!(SubconeCtssParams, flags) == offset_of!(CtssParams, flags));
};

/// The SRAA parameters at `p` (the argument `params`), every σ and the
/// scale finite.
pub(crate) fn sraa_params(p: *const SubconeSraaParams) -> Checked<SraaParams> {
    // SAFETY: `p` comes from the caller's contract on the exported function.
    let p = unsafe { read(p, "params") }?;
    finite(&[
        ("params->sigma_z", p.sigma_z),
        ("params->sigma_n", p.sigma_n),
        ("params->scale", p.scale),
        ("params->sigma_s", p.sigma_s),
    ])?;
    Ok(p.into())
}

/// The default SRAA parameters (σz 10, σn 1, σs 0.4 px, shaded sample at the
/// pixel centre; the Rust `SraaParams::TUNED`).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_params_default(out: *mut SubconeSraaParams) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_sraa_params_default", || unsafe {
        write(out, SraaParams::TUNED.into(), "out")
    })
}

/// The SRAA paper's parameters (§3.1: σz 10, σn 0.25, eq. 1 as published,
/// the shaded sample on subsample 0).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_params_paper(out: *mut SubconeSraaParams) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_sraa_params_paper", || unsafe {
        write(out, SraaParams::PAPER.into(), "out")
    })
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
    call("subcone_ctss_params_default", || {
        if !(tan_theta.is_finite() && tan_theta >= 0.0) {
            return Err(Refusal::invalid(format!(
                "tan_theta is {tan_theta}; it must be finite and not negative"
            )));
        }
        // SAFETY: forwarded contract.
        unsafe { write(out, CtssParams::new(tan_theta).into(), "out") }
    })
}
