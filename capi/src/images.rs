//! Whole images on the CPU: FXAA and the TAA resolve over caller-owned
//! buffers, and the checks of their sizes.

use glam::{Vec2, Vec3, Vec4};
use subcone_kernels::fxaa::{edge_clamped, fxaa_decode, fxaa_encode, fxaa_pixel, FxaaParams};
use subcone_kernels::taa::{resolve_pixel as taa_resolve_pixel, DepthDilation, TaaParams};

use crate::checks::{finite, read, slice, slice_mut};
use crate::post::{SubconeFxaaParams, SubconeTaaParams};
use crate::status::{call, Checked, Refusal, SubconeStatus};

/// The pixel count of a `width × height` image and the length of a buffer
/// of `per_pixel` floats per pixel: errors on a zero size or an overflow.
/// `size` names the size in messages (`width × height`, say).
fn image_len(width: u32, height: u32, per_pixel: usize, size: &str) -> Checked<(usize, usize)> {
    if width == 0 || height == 0 {
        return Err(Refusal::size(format!(
            "{size} is {width} × {height}; both must be at least 1"
        )));
    }
    let overflow = || Refusal::size(format!("{size} ({width} × {height}) overflows size_t"));
    let n = (width as usize)
        .checked_mul(height as usize)
        .ok_or_else(overflow)?;
    let len = n.checked_mul(per_pixel).ok_or_else(overflow)?;
    Ok((n, len))
}

/// `len`, the length of `name`, must be `want` (`what` says what that is).
fn exact_len(name: &str, len: usize, want: usize, what: &str) -> Checked<()> {
    if len == want {
        Ok(())
    } else {
        Err(Refusal::size(format!(
            "{name} is {len}; it must be {what} = {want}"
        )))
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
    call("subcone_fxaa_image", || {
        // SAFETY: forwarded contract.
        let p = unsafe { read(params, "params") }?;
        finite(&[
            ("params->subpix", p.subpix),
            ("params->edge_threshold", p.edge_threshold),
            ("params->edge_threshold_min", p.edge_threshold_min),
        ])?;
        let p = FxaaParams::from(p);
        let (_, len) = image_len(width, height, 4, "width × height")?;
        exact_len("src_len", src_len, len, "4·width·height")?;
        exact_len("dst_len", dst_len, len, "4·width·height")?;
        // SAFETY: lengths checked against the size; pointers per contract.
        let (src, dst) = unsafe { (slice(src, src_len, "src")?, slice_mut(dst, dst_len, "dst")?) };
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
        Ok(())
    })
}

/// One TAA resolve (`subcone_kernels::taa::resolve_pixel`: Karis 2014 with
/// Salvi's variance clipping) of every pixel of a `params.width ×
/// params.height` image on the CPU: what `shaders/taa/*` computes for a
/// whole texture. `current` and `history` are `4·width·height` floats (RGBA
/// row by row, linear radiance, alpha ignored), `velocity` `2·width·height`
/// (each pixel's motion vector, which times `params.motion_scale` is its
/// motion in pixels, current minus previous); `out` receives
/// `4·width·height` floats, alpha 1. With `params.history_frames == 0` the
/// history is not read and may be null with length 0. Every output is
/// finite and non-negative, whatever the colours and velocities hold.
///
/// Errors: null pointers where data is required; a zero size or lengths
/// that do not match it; non-finite parameters; a `depth_dilation` that
/// asks for a depth (1 or 2: this resolve takes none).
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
    call("subcone_taa_resolve", || {
        // SAFETY: forwarded contract.
        let p = unsafe { read(params, "params") }?;
        finite(&[
            ("params->exposure", p.exposure),
            ("params->min_current_weight", p.min_current_weight),
            ("params->clip_gamma", p.clip_gamma),
            ("params->motion_scale[0]", p.motion_scale[0]),
            ("params->motion_scale[1]", p.motion_scale[1]),
        ])?;
        if DepthDilation::from_code(p.depth_dilation).is_on() {
            return Err(Refusal::invalid(format!(
                "params->depth_dilation is {}; subcone_taa_resolve has no depth input, so it \
                 must be 0",
                p.depth_dilation
            )));
        }
        let p = TaaParams::from(p);
        let (n, len) = image_len(p.width, p.height, 4, "params->width × params->height")?;
        exact_len("current_len", current_len, len, "4·width·height")?;
        exact_len("velocity_len", velocity_len, 2 * n, "2·width·height")?;
        exact_len("out_len", out_len, len, "4·width·height")?;
        // The history may be empty only when it is not read.
        if p.history_frames != 0 || history_len != 0 {
            let what = if p.history_frames != 0 {
                "4·width·height (params->history_frames is not 0)"
            } else {
                "0 or 4·width·height"
            };
            exact_len("history_len", history_len, len, what)?;
        }
        // SAFETY: lengths checked against the size; pointers per contract.
        let (current, velocity, history, out) = unsafe {
            (
                slice(current, current_len, "current")?,
                slice(velocity, velocity_len, "velocity")?,
                slice(history, history_len, "history")?,
                slice_mut(out, out_len, "out")?,
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
        Ok(())
    })
}
