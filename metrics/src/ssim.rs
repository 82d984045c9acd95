//! SSIM (Wang, Bovik, Sheikh and Simoncelli, "Image Quality Assessment:
//! From Error Visibility to Structural Similarity", IEEE TIP 13(4), 2004),
//! the second metric beside FLIP.
//!
//! As in the paper's §III-C and its reference implementation: an 11×11
//! circular-symmetric Gaussian window of σ = 1.5 (normalised to unit sum),
//! `K1 = 0.01`, `K2 = 0.03` and a dynamic range `L = 1`, so
//!
//! ```text
//! SSIM(x, y) = (2 μx μy + C1)(2 σxy + C2) / ((μx² + μy² + C1)(σx² + σy² + C2)),
//! C1 = (K1 L)², C2 = (K2 L)²
//! ```
//!
//! with the window's weighted means, variances and covariance (the paper's
//! eqs. 14–16: population, not sample, statistics). It is computed on the
//! **luminance** of the tone-mapped 8-bit sRGB images FLIP compares
//! ([`Rgb8::luma`]: Rec. 709 weights on the encoded values, in `[0, 1]`), as
//! the paper does for colour images (it converts them to greyscale).
//!
//! The map has one value per pixel: the window is centred on every pixel,
//! and near the border the Gaussian's weights are renormalised over the
//! taps inside the image (the paper's code computes only the interior,
//! "valid", part, which would leave the border pixels without a value and
//! so without a class mean). In the interior both agree exactly; the test
//! `interior_mean_matches_scikit_image` checks that against scikit-image's
//! `structural_similarity` with the paper's settings.
//!
//! The report averages `1 − SSIM` (0 for identical images; larger is
//! worse, like FLIP) over each edge class.

use crate::{same_size, MetricError, Rgb8};

/// Standard deviation of the Gaussian window, pixels (the paper's 1.5).
pub const SIGMA: f64 = 1.5;
/// Window radius: 11×11 taps.
pub const RADIUS: usize = 5;
/// `K1` of the luminance term.
pub const K1: f64 = 0.01;
/// `K2` of the contrast-structure term.
pub const K2: f64 = 0.03;

/// An SSIM comparison: the per-pixel map and its mean.
pub struct Ssim {
    /// Per-pixel SSIM in `[-1, 1]` (1 where the windows agree), row-major.
    pub map: Vec<f32>,
    /// Mean SSIM over every pixel.
    pub mean: f64,
}

impl Ssim {
    /// `1 − SSIM` per pixel: an error map (0 is no error) that the class
    /// means and verdicts use, as they use FLIP's.
    pub fn dissimilarity(&self) -> Vec<f32> {
        self.map.iter().map(|s| 1.0 - s).collect()
    }

    /// The error map as an 8-bit grey image, `1 − SSIM` of 0 black and
    /// 0.5 or more white (a window that differs that much is no longer
    /// similar at all), for looking at beside FLIP's map.
    pub fn image(&self, width: u32, height: u32) -> Rgb8 {
        let data = self
            .map
            .iter()
            .flat_map(|s| {
                let v = ((1.0 - s) * 2.0).clamp(0.0, 1.0);
                [(v * 255.0).round() as u8; 3]
            })
            .collect();
        Rgb8 {
            width,
            height,
            data,
        }
    }
}

/// The window's 1-D weights, `exp(−k² / 2σ²)` for `k` in `−RADIUS..=RADIUS`
/// (normalised where applied).
fn weights() -> [f64; 2 * RADIUS + 1] {
    std::array::from_fn(|i| {
        let k = i as f64 - RADIUS as f64;
        (-k * k / (2.0 * SIGMA * SIGMA)).exp()
    })
}

/// Gaussian-weighted local means of each of `planes` (all `w × h`),
/// separably, with the weights renormalised over the taps inside the image.
/// The clipped window is a rectangle, so renormalising each pass renormalises
/// the 2-D product window.
fn blur<const N: usize>(planes: [&[f64]; N], w: usize, h: usize) -> [Vec<f64>; N] {
    let g = weights();
    let pass = |src: &[f64], along_x: bool| -> Vec<f64> {
        let mut out = vec![0.0; w * h];
        let (len, stride) = if along_x { (w, 1) } else { (h, w) };
        for (i, o) in out.iter_mut().enumerate() {
            let at = if along_x { i % w } else { i / w };
            let lo = at.saturating_sub(RADIUS);
            let hi = (at + RADIUS).min(len - 1);
            let (mut sum, mut norm) = (0.0, 0.0);
            for t in lo..=hi {
                let wt = g[t + RADIUS - at];
                sum += wt * src[i - at * stride + t * stride];
                norm += wt;
            }
            *o = sum / norm;
        }
        out
    };
    planes.map(|p| pass(&pass(p, true), false))
}

/// SSIM of `test` against `reference` (the paper's settings above), on
/// luminance; errors when the images differ in size or are empty.
///
/// Inputs are 8-bit, so every value is finite and the map lies in
/// `[-1, 1]`: the constants keep both denominators at least `C1` and `C2`.
pub fn ssim(reference: &Rgb8, test: &Rgb8) -> Result<Ssim, MetricError> {
    same_size(reference, test)?;
    let (w, h) = (reference.width as usize, reference.height as usize);
    let x: Vec<f64> = reference.luma().into_iter().map(f64::from).collect();
    let y: Vec<f64> = test.luma().into_iter().map(f64::from).collect();
    let xx: Vec<f64> = x.iter().map(|v| v * v).collect();
    let yy: Vec<f64> = y.iter().map(|v| v * v).collect();
    let xy: Vec<f64> = x.iter().zip(&y).map(|(a, b)| a * b).collect();
    let [mx, my, mxx, myy, mxy] = blur([&x, &y, &xx, &yy, &xy], w, h);
    let (c1, c2) = (K1 * K1, K2 * K2);
    let map: Vec<f32> = (0..w * h)
        .map(|i| {
            let (ux, uy) = (mx[i], my[i]);
            // E[x²] − μ² can round a hair below zero on a flat window.
            let vx = (mxx[i] - ux * ux).max(0.0);
            let vy = (myy[i] - uy * uy).max(0.0);
            let cov = mxy[i] - ux * uy;
            let s = ((2.0 * ux * uy + c1) * (2.0 * cov + c2))
                / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
            s as f32
        })
        .collect();
    let mean = map.iter().map(|&s| f64::from(s)).sum::<f64>() / map.len() as f64;
    Ok(Ssim { map, mean })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(w: u32, h: u32, f: impl Fn(usize, usize) -> u8) -> Rgb8 {
        let data = (0..(w * h) as usize)
            .flat_map(|i| [f(i % w as usize, i / w as usize); 3])
            .collect();
        Rgb8 {
            width: w,
            height: h,
            data,
        }
    }

    /// A checkerboard with a ramp, and the same blurred with a ±4 pattern:
    /// integer formulas, so that the Python check computes the same pixels.
    fn pair() -> (Rgb8, Rgb8) {
        let (w, h) = (48usize, 40usize);
        let a = |x: usize, y: usize| -> i64 {
            if (x / 8 + y / 8) % 2 == 0 {
                200
            } else {
                40 + ((x * 3 + y * 5) % 16) as i64
            }
        };
        let b = |x: usize, y: usize| -> u8 {
            let (l, r) = (a(x.saturating_sub(1), y), a((x + 1).min(w - 1), y));
            let v = (l + 2 * a(x, y) + r) / 4 + ((x * 7 + y * 11) % 9) as i64 - 4;
            v.clamp(0, 255) as u8
        };
        (
            grey(w as u32, h as u32, |x, y| a(x, y) as u8),
            grey(w as u32, h as u32, b),
        )
    }

    /// scikit-image 0.26's `structural_similarity(x, y, gaussian_weights=True,
    /// sigma=1.5, use_sample_covariance=False, data_range=1.0)`, the
    /// settings its documentation gives to match Wang et al.'s code, on the
    /// luminance of [`pair`]: it averages the map without the 5-pixel
    /// border, where the window leaves the image.
    ///
    /// ```python
    /// import numpy as np
    /// from skimage.metrics import structural_similarity
    /// W, H = 48, 40
    /// a = np.array([[200 if (x // 8 + y // 8) % 2 == 0 else 40 + (x * 3 + y * 5) % 16
    ///                for x in range(W)] for y in range(H)])
    /// b = np.array([[min(max((a[y, max(x - 1, 0)] + 2 * a[y, x] + a[y, min(x + 1, W - 1)]) // 4
    ///                        + (x * 7 + y * 11) % 9 - 4, 0), 255)
    ///                for x in range(W)] for y in range(H)])
    /// def luma(v):
    ///     v = v.astype(np.float32)
    ///     return ((np.float32(0.2126) * v + np.float32(0.7152) * v)
    ///             + np.float32(0.0722) * v) / np.float32(255.0)
    /// print(structural_similarity(luma(a).astype(np.float64), luma(b).astype(np.float64),
    ///       gaussian_weights=True, sigma=1.5, use_sample_covariance=False, data_range=1.0))
    /// ```
    const SCIKIT_IMAGE_MSSIM: f64 = 0.9400919550166451;

    #[test]
    fn interior_mean_matches_scikit_image() {
        let (a, b) = pair();
        let s = ssim(&a, &b).unwrap();
        let (w, h) = (a.width as usize, a.height as usize);
        let interior: Vec<f64> = (RADIUS..h - RADIUS)
            .flat_map(|y| (RADIUS..w - RADIUS).map(move |x| (x, y)))
            .map(|(x, y)| f64::from(s.map[y * w + x]))
            .collect();
        let mean = interior.iter().sum::<f64>() / interior.len() as f64;
        // The map is stored as f32: agreement to about 1e-7 is all f32 holds.
        assert!(
            (mean - SCIKIT_IMAGE_MSSIM).abs() < 1e-6,
            "{mean} against scikit-image's {SCIKIT_IMAGE_MSSIM}"
        );
        // The border pixels count in the report's mean: it differs.
        assert!((s.mean - mean).abs() > 1e-4);
    }

    #[test]
    fn identical_images_score_one_everywhere() {
        let (a, _) = pair();
        let s = ssim(&a, &a).unwrap();
        assert!(s.map.iter().all(|&v| (v - 1.0).abs() < 1e-6));
        assert!(s.dissimilarity().iter().all(|&d| d.abs() < 1e-6));
    }

    #[test]
    fn flat_images_reduce_to_the_luminance_term() {
        // Two constant images: σ = 0, so SSIM = (2ab + C1) / (a² + b² + C1).
        let (a, b) = (grey(16, 12, |_, _| 100), grey(16, 12, |_, _| 140));
        let s = ssim(&a, &b).unwrap();
        let (la, lb) = (a.luma()[0] as f64, b.luma()[0] as f64);
        let c1 = K1 * K1;
        let want = (2.0 * la * lb + c1) / (la * la + lb * lb + c1);
        assert!(s.map.iter().all(|&v| (f64::from(v) - want).abs() < 1e-6));
        // Symmetric, as the formula is.
        let t = ssim(&b, &a).unwrap();
        assert_eq!(s.map, t.map);
    }

    #[test]
    fn an_inverted_pattern_scores_below_zero_and_worse_than_noise() {
        let (a, b) = pair();
        let inverted = Rgb8 {
            data: a.data.iter().map(|v| 255 - v).collect(),
            ..a.clone()
        };
        let noisy = ssim(&a, &b).unwrap().mean;
        let inv = ssim(&a, &inverted).unwrap();
        assert!(inv.mean < 0.0 && inv.mean < noisy, "{} {noisy}", inv.mean);
        assert!(inv.map.iter().all(|v| (-1.0..=1.0).contains(v)));
    }

    #[test]
    fn mismatched_or_empty_images_are_errors() {
        let (a, _) = pair();
        assert!(ssim(&a, &grey(8, 8, |_, _| 0)).is_err());
        let empty = grey(0, 0, |_, _| 0);
        assert!(ssim(&empty, &empty).is_err());
        // A window larger than the image still has a value at every pixel.
        let tiny = ssim(&grey(1, 1, |_, _| 10), &grey(1, 1, |_, _| 30)).unwrap();
        assert_eq!(tiny.map.len(), 1);
        assert!(tiny.mean.is_finite());
    }

    #[test]
    fn the_grey_image_saturates_at_half() {
        let s = Ssim {
            map: vec![1.0, 0.75, 0.5, -1.0],
            mean: 0.0,
        };
        assert_eq!(
            s.image(4, 1).data,
            [0, 0, 0, 128, 128, 128, 255, 255, 255, 255, 255, 255]
        );
    }
}
