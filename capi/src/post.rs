//! FXAA and TAA: their parameters and pass uniforms, as C structs, and
//! TAA's jitter.

use subcone_kernels::fxaa::FxaaParams;
use subcone_kernels::taa::{jitter, ResolveSpace, TaaParams};

use crate::checks::write;
use crate::status::{call, Refusal, SubconeStatus};

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
/// (48 bytes; `taa_params` of `shaders/taa/*`). Fill it with
/// [`subcone_taa_params`], then set `motion_scale` for motion vectors that
/// are not pixels (current minus previous).
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
    /// Closest-depth motion dilation: 0 off, 1 a smaller depth is nearer,
    /// 2 a larger one is (reversed Z), read by `shaders/taa/depth-dilation`.
    /// `subcone_taa_resolve` and `shaders/taa/default` have no depth input:
    /// the first refuses 1 and 2, the second ignores the field.
    pub depth_dilation: u32,
    /// What each motion vector is multiplied by to be pixels, current minus
    /// previous, `+y` down: `{1, 1}` for such vectors (what
    /// [`subcone_taa_params`] writes), `{width, height}` for Bevy's (UV
    /// units, current minus previous), `{-1, -1}` for FSR2's pixel vectors
    /// (previous minus current). A component that is 0 reads as 1.
    pub motion_scale: [f32; 2],
    /// Padding; write 0.
    pub pad: [u32; 2],
}

mirror_conversions!(SubconeTaaParams <=> TaaParams {
    exposure: exposure,
    min_current_weight: min_current_weight,
    clip_gamma: clip_gamma,
    history_frames: history_frames,
    width: width,
    height: height,
    tone_mapped: tone_mapped,
    depth_dilation: depth_dilation,
    motion_scale: motion_scale,
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
    call("subcone_fxaa_params_quality", || unsafe {
        write(out, FxaaParams::QUALITY.into(), "out")
    })
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
    call("subcone_fxaa_pass_frame", || {
        if width == 0 || height == 0 {
            return Err(Refusal::size(format!(
                "width × height is {width} × {height}; both must be at least 1"
            )));
        }
        let frame = SubconeFxaaPassFrame {
            width,
            height,
            pad: [0; 2],
        };
        // SAFETY: forwarded contract.
        unsafe { write(out, frame, "out") }
    })
}

/// The TAA resolve's parameters for a `width × height` image whose history
/// holds `history_frames` frames (0 after a reset), with the kernels'
/// defaults (`MIN_CURRENT_WEIGHT`, `CLIP_GAMMA`), resolved in linear
/// radiance when `exposure` is 0 and in Karis' tone-mapped space at
/// `exposure` otherwise, motion vectors in pixels (`motion_scale` `{1, 1}`)
/// and no depth dilation: the Rust `TaaParams::new(size).with_space(..)
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
    call("subcone_taa_params", || {
        if width == 0 || height == 0 {
            return Err(Refusal::size(format!(
                "width × height is {width} × {height}; both must be at least 1"
            )));
        }
        if !(exposure.is_finite() && exposure >= 0.0) {
            return Err(Refusal::invalid(format!(
                "exposure is {exposure}; it must be finite and not negative (0 for the linear \
                 resolve)"
            )));
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
        unsafe { write(out, p.into(), "out") }
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
    call("subcone_taa_jitter", || {
        if x.is_null() {
            return Err(Refusal::null("x"));
        }
        if y.is_null() {
            return Err(Refusal::null("y"));
        }
        if phases == 0 {
            return Err(Refusal::invalid("phases is 0; it must be at least 1"));
        }
        let j = jitter(frame, phases);
        // SAFETY: forwarded contract; both checked non-null.
        unsafe {
            write(x, j.x, "x")?;
            write(y, j.y, "y")
        }
    })
}

// The pass uniforms have the layouts of the shaders' (the test
// `pass_uniforms` compares every member with naga's layout of the WGSL).
const _: () = {
    use std::mem::size_of;
    assert!(size_of::<SubconeFxaaParams>() == size_of::<FxaaParams>());
    assert!(size_of::<SubconeFxaaPassFrame>() == 16);
    assert!(size_of::<SubconeTaaParams>() == size_of::<TaaParams>());
    assert!(size_of::<SubconeTaaPassOrigin>() == 16);
};
