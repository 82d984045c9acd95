//! The report's masks and means over metric maps: the edge mask that edge
//! FLIP is averaged over and the class means. The metrics themselves (FLIP,
//! SSIM, PSNR) are [`subcone_metrics`]'s.

use anyhow::{bail, Result};
use subcone_metrics::{same_size, Rgb8};
use subcone_scene::Frame;

/// Mean of `values` where `mask` is set; `None` when the mask is empty or the
/// lengths differ.
pub fn masked_mean(values: &[f32], mask: &[bool]) -> Option<f64> {
    if values.len() != mask.len() {
        return None;
    }
    let (sum, n) = values
        .iter()
        .zip(mask)
        .filter(|(_, &m)| m)
        .fold((0.0f64, 0usize), |(s, n), (&v, _)| (s + v as f64, n + 1));
    (n > 0).then(|| sum / n as f64)
}

/// Relative depth difference above which two neighbouring pixels straddle a
/// depth discontinuity.
pub const DEPTH_EDGE: f32 = 0.02;
/// Normal cosine below which two neighbouring pixels straddle a crease.
pub const NORMAL_EDGE: f32 = 0.9;
/// Sobel magnitude of the sRGB luminance (normalised so that a step of height
/// `h` gives `h`) above which a pixel is on a strong image gradient.
pub const GRADIENT_EDGE: f32 = 0.1;

/// Pixels on a geometric discontinuity of a frame with depth and normal AOVs:
/// a 4-neighbour whose view depth differs by more than [`DEPTH_EDGE`]
/// relatively (unless the inverse depth continues linearly from one side, as
/// it does across a plane, however grazing), or whose normal's cosine is
/// below [`NORMAL_EDGE`], or where one of the two is a miss (∞ depth) and the
/// other is not. Both pixels of such a pair are marked.
pub fn geometric_edges(aov: &Frame) -> Result<Vec<bool>> {
    let (w, h) = (aov.width as usize, aov.height as usize);
    let (Some(depth), Some(normal)) = (&aov.depth, &aov.normal) else {
        bail!("the frame has no depth and normal AOVs (render with aovs = true)");
    };
    if depth.len() != w * h || normal.len() != w * h {
        bail!("AOVs do not match the frame size {w}x{h}");
    }
    let mut mask = vec![false; w * h];
    let differs = |a: usize, b: usize, oa: Option<usize>, ob: Option<usize>| -> bool {
        if depth_discontinuity(depth, a, b, oa, ob, DEPTH_EDGE) {
            return true;
        }
        if !(depth[a].is_finite() && depth[b].is_finite()) {
            return false;
        }
        let (na, nb) = (normal[a], normal[b]);
        na.is_finite()
            && nb.is_finite()
            && na.length_squared() > 0.25
            && nb.length_squared() > 0.25
            && na.normalize().dot(nb.normalize()) < NORMAL_EDGE
    };
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if x + 1 < w {
                let oa = (x > 0).then(|| i - 1);
                let ob = (x + 2 < w).then(|| i + 2);
                if differs(i, i + 1, oa, ob) {
                    mask[i] = true;
                    mask[i + 1] = true;
                }
            }
            if y + 1 < h {
                let oa = (y > 0).then(|| i - w);
                let ob = (y + 2 < h).then(|| i + 2 * w);
                if differs(i, i + w, oa, ob) {
                    mask[i] = true;
                    mask[i + w] = true;
                }
            }
        }
    }
    Ok(mask)
}

/// Whether neighbouring samples `a` and `b` of a view-depth image see
/// different surfaces: one is a miss (non-finite depth) and the other is not,
/// or their depths differ by more than `threshold` relatively and the inverse
/// depth does not continue linearly from either side. `oa` is `a`'s other
/// neighbour on the same line (away from `b`), `ob` is `b`'s: inverse view
/// depth is affine in screen space on a plane, so a plane seen at a grazing
/// angle (whose depth may change by far more than `threshold` per sample)
/// extrapolates exactly from either side; a true discontinuity from neither.
/// Indices must be in `depth`.
pub fn depth_discontinuity(
    depth: &[f32],
    a: usize,
    b: usize,
    oa: Option<usize>,
    ob: Option<usize>,
    threshold: f32,
) -> bool {
    let (da, db) = (depth[a], depth[b]);
    let (fa, fb) = (da.is_finite(), db.is_finite());
    if fa != fb {
        return true;
    }
    if !fa {
        return false;
    }
    let scale = da.abs().min(db.abs()).max(1e-6);
    if (da - db).abs() / scale <= threshold {
        return false;
    }
    let planar = |p: usize, o: Option<usize>, q: usize| -> bool {
        let Some(o) = o else { return false };
        if !depth[o].is_finite() {
            return false;
        }
        let (ip, io, iq) = (1.0 / depth[p], 1.0 / depth[o], 1.0 / depth[q]);
        ((2.0 * ip - io) - iq).abs() <= threshold * ip.max(iq)
    };
    !planar(a, oa, b) && !planar(b, ob, a)
}

/// Sobel gradient magnitude of a `w × h` scalar image, normalised so that a
/// step of height `s` gives `s` next to the step (borders clamp).
pub fn sobel(values: &[f32], w: usize, h: usize) -> Vec<f32> {
    if values.len() != w * h || w == 0 || h == 0 {
        return vec![0.0; values.len()];
    }
    let at = |x: isize, y: isize| {
        let x = x.clamp(0, w as isize - 1) as usize;
        let y = y.clamp(0, h as isize - 1) as usize;
        values[y * w + x]
    };
    let mut out = vec![0.0; w * h];
    for y in 0..h as isize {
        for x in 0..w as isize {
            let gx = (at(x + 1, y - 1) + 2.0 * at(x + 1, y) + at(x + 1, y + 1))
                - (at(x - 1, y - 1) + 2.0 * at(x - 1, y) + at(x - 1, y + 1));
            let gy = (at(x - 1, y + 1) + 2.0 * at(x, y + 1) + at(x + 1, y + 1))
                - (at(x - 1, y - 1) + 2.0 * at(x, y - 1) + at(x + 1, y - 1));
            out[y as usize * w + x as usize] = (gx * gx + gy * gy).sqrt() / 4.0;
        }
    }
    out
}

/// Pixels on a strong gradient of `image`'s luminance ([`GRADIENT_EDGE`]).
pub fn gradient_edges(image: &Rgb8) -> Vec<bool> {
    sobel(&image.luma(), image.width as usize, image.height as usize)
        .into_iter()
        .map(|g| g > GRADIENT_EDGE)
        .collect()
}

/// The edge mask: geometric edges of the NoAA AOV frame or strong gradients
/// of the reference image.
pub fn edge_mask(aov: &Frame, reference: &Rgb8) -> Result<Vec<bool>> {
    if aov.width != reference.width || aov.height != reference.height {
        bail!(
            "AOV frame {}x{} and reference {}x{} differ in size",
            aov.width,
            aov.height,
            reference.width,
            reference.height
        );
    }
    let geo = geometric_edges(aov)?;
    Ok(geo
        .iter()
        .zip(gradient_edges(reference))
        .map(|(&a, b)| a || b)
        .collect())
}

/// Per-pixel absolute luminance difference of two images of the same size.
pub fn luma_difference(a: &Rgb8, b: &Rgb8) -> Result<Vec<f32>> {
    same_size(a, b)?;
    Ok(a.luma()
        .iter()
        .zip(b.luma())
        .map(|(x, y)| (x - y).abs())
        .collect())
}

/// Pixels where two images differ by more than `tolerance` (0–255) in any channel.
pub fn differing_pixels(a: &Rgb8, b: &Rgb8, tolerance: u8) -> Result<Vec<bool>> {
    same_size(a, b)?;
    Ok(a.data
        .chunks_exact(3)
        .zip(b.data.chunks_exact(3))
        .map(|(p, q)| p.iter().zip(q).any(|(&u, &v)| u.abs_diff(v) > tolerance))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn step_is_a_gradient_edge_and_flat_is_not() {
        let a = Rgb8::grey(8, 8, |x, _| if x < 4 { 0 } else { 255 });
        let m = gradient_edges(&a);
        assert!(m[3] && m[4]);
        assert!(!m[0] && !m[7]);
    }

    #[test]
    fn depth_and_miss_discontinuities() {
        let mut f = Frame::new(4, 1);
        f.depth = Some(vec![1.0, 1.001, 2.0, f32::INFINITY]);
        f.normal = Some(vec![Vec3::Y; 4]);
        let m = geometric_edges(&f).unwrap();
        assert_eq!(m, vec![false, true, true, true]);
        f.depth = None;
        assert!(geometric_edges(&f).is_err());
    }

    #[test]
    fn a_grazing_plane_is_not_an_edge() {
        // Inverse depth affine along the row: a plane receding to the horizon,
        // depth growing by far more than 2 % per pixel.
        let mut f = Frame::new(6, 1);
        f.depth = Some((0..6).map(|x| 1.0 / (1.0 - 0.15 * x as f32)).collect());
        f.normal = Some(vec![Vec3::Y; 6]);
        assert_eq!(geometric_edges(&f).unwrap(), vec![false; 6]);
        // A step in the middle of it is.
        let mut d = f.depth.clone().unwrap();
        for v in &mut d[3..] {
            *v *= 1.5;
        }
        f.depth = Some(d);
        let m = geometric_edges(&f).unwrap();
        assert!(m[2] && m[3]);
    }

    #[test]
    fn masked_mean_of_empty_mask_is_none() {
        assert_eq!(masked_mean(&[1.0, 2.0], &[false, false]), None);
        assert_eq!(masked_mean(&[1.0, 3.0], &[true, true]), Some(2.0));
        assert_eq!(masked_mean(&[1.0], &[true, true]), None);
    }
}
