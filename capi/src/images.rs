//! Whole images on the CPU: FXAA and the TAA resolve over caller-owned
//! buffers, and the checks of their sizes.

use glam::{Vec2, Vec3, Vec4};
use subcone_kernels::fxaa::{edge_clamped, fxaa_decode, fxaa_encode, fxaa_pixel, FxaaParams};
use subcone_kernels::taa::{resolve_pixel as taa_resolve_pixel, TaaParams};

use crate::checks::{finite, read, slice, slice_mut};
use crate::post::{SubconeFxaaParams, SubconeTaaParams};
use crate::status::{guard, status, SubconeStatus};

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
