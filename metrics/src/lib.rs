//! Image metrics of subcone on tone-mapped 8-bit sRGB images: LDR-FLIP
//! (Andersson et al., "FLIP: A Difference Evaluator for Alternating
//! Images", HPG 2020, through `nv-flip`), SSIM ([`ssim`]) and PSNR.
//!
//! The report and the conformance suite measure with these functions, so a
//! report's FLIP and a conformance bound are the same number. Every function
//! checks its sizes and returns a [`MetricError`] instead of panicking
//! (nv-flip asserts equal sizes; we check first).
//!
//! ```
//! use subcone_metrics::{flip, psnr, ssim::ssim, Rgb8};
//!
//! // A 16×8 grey ramp and the same ramp a little brighter.
//! let ramp = |lift: u8| Rgb8 {
//!     width: 16,
//!     height: 8,
//!     data: (0..16 * 8).flat_map(|i| [(i % 16) as u8 * 10 + lift; 3]).collect(),
//! };
//! let (reference, test) = (ramp(0), ramp(8));
//!
//! let f = flip(&reference, &test)?;
//! assert!(f.mean > 0.0 && f.mean < 1.0);
//! assert_eq!(f.map.len(), 16 * 8);
//! assert!(psnr(&reference, &test)? < psnr(&reference, &reference)?);
//! assert!(ssim(&reference, &test)?.mean < 1.0);
//!
//! // Images of different sizes are an error, not a panic.
//! let small = Rgb8 { width: 4, height: 4, data: vec![0; 48] };
//! assert!(flip(&reference, &small).is_err());
//! # Ok::<(), subcone_metrics::MetricError>(())
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod ssim;

use std::fmt;

use subcone_scene::Frame;

/// Why two images cannot be compared.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MetricError {
    /// The images differ in size.
    SizeMismatch {
        /// The reference's `(width, height)`.
        reference: (u32, u32),
        /// The test image's `(width, height)`.
        test: (u32, u32),
    },
    /// An image's data is not `3 · width · height` bytes (or a frame's
    /// colour is not `width · height` pixels).
    DataLength {
        /// The image's `(width, height)`.
        size: (u32, u32),
        /// The values expected for that size.
        expected: usize,
        /// The values found.
        found: usize,
    },
    /// The images have no pixels.
    Empty,
}

impl fmt::Display for MetricError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MetricError::SizeMismatch { reference, test } => write!(
                f,
                "images differ in size: {}x{} against {}x{}",
                reference.0, reference.1, test.0, test.1
            ),
            MetricError::DataLength {
                size,
                expected,
                found,
            } => write!(
                f,
                "image of {}x{} has {found} values, expected {expected}",
                size.0, size.1
            ),
            MetricError::Empty => f.write_str("empty image"),
        }
    }
}

impl std::error::Error for MetricError {}

/// An 8-bit sRGB RGB image, row-major from the top-left pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb8 {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `3 · width · height` bytes.
    pub data: Vec<u8>,
}

impl Rgb8 {
    /// A grey image whose pixel `(x, y)` is `value(x, y)` in all three
    /// channels: synthetic inputs (steps, ramps) for checking a metric.
    ///
    /// ```
    /// let step = subcone_metrics::Rgb8::grey(4, 2, |x, _| if x < 2 { 0 } else { 255 });
    /// assert_eq!(&step.data[..6], &[0, 0, 0, 0, 0, 0]);
    /// assert_eq!(&step.data[6..9], &[255, 255, 255]);
    /// ```
    pub fn grey(width: u32, height: u32, value: impl Fn(u32, u32) -> u8) -> Self {
        let data = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .flat_map(|(x, y)| [value(x, y); 3])
            .collect();
        Rgb8 {
            width,
            height,
            data,
        }
    }

    /// The image a user sees of `frame` ([`Frame::to_srgb8`]); fails when the
    /// frame's pixels do not match its size.
    pub fn from_frame(frame: &Frame) -> Result<Self, MetricError> {
        let n = frame.width as usize * frame.height as usize;
        if frame.color.len() != n {
            return Err(MetricError::DataLength {
                size: (frame.width, frame.height),
                expected: n,
                found: frame.color.len(),
            });
        }
        Ok(Rgb8 {
            width: frame.width,
            height: frame.height,
            data: frame.to_srgb8(),
        })
    }

    /// Number of pixels.
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Relative luminance in `[0, 1]` of the sRGB-encoded values (Rec. 709
    /// weights on the encoded values: a perceptual, not a physical, luminance).
    pub fn luma(&self) -> Vec<f32> {
        self.data
            .chunks_exact(3)
            .map(|p| (0.2126 * p[0] as f32 + 0.7152 * p[1] as f32 + 0.0722 * p[2] as f32) / 255.0)
            .collect()
    }
}

/// Errors unless `a` and `b` are non-empty images of one size whose data
/// matches it.
pub fn same_size(a: &Rgb8, b: &Rgb8) -> Result<(), MetricError> {
    if a.width != b.width || a.height != b.height {
        return Err(MetricError::SizeMismatch {
            reference: (a.width, a.height),
            test: (b.width, b.height),
        });
    }
    for i in [a, b] {
        if i.data.len() != i.pixels() * 3 {
            return Err(MetricError::DataLength {
                size: (i.width, i.height),
                expected: i.pixels() * 3,
                found: i.data.len(),
            });
        }
    }
    if a.pixels() == 0 {
        return Err(MetricError::Empty);
    }
    Ok(())
}

/// A FLIP comparison: the per-pixel error map in `[0, 1]` and its mean.
pub struct Flip {
    /// Per-pixel FLIP error, row-major.
    pub map: Vec<f32>,
    /// Mean FLIP over all pixels (the number the FLIP authors recommend).
    pub mean: f64,
    /// The error map through FLIP's magma colour map, 8-bit RGB.
    pub magma: Rgb8,
}

impl Flip {
    /// The 99th percentile of [`map`](Self::map) (nearest rank), the
    /// conformance suite's second bound beside the mean.
    pub fn p99(&self) -> f32 {
        percentile(&self.map, 0.99)
    }
}

/// The pixels per degree every FLIP of the workspace is computed at: the
/// FLIP paper's default viewing condition (Andersson et al. 2020, §5: a
/// 0.7 m wide 4K monitor seen from 0.7 m).
pub const FLIP_PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// How far, in pixels, FLIP's filters reach at `ppd` pixels per degree:
/// the larger of the colour pipeline's spatial filter radius,
/// `⌈3 √(b_max / (2π²)) · ppd⌉` with the largest of its Gaussians' scale
/// parameters `b_max = 0.04` (the blue–yellow channel's `b1`), and the
/// feature filter's, `⌈3 σ⌉` with `σ = ½ · 0.082 · ppd` (the constants
/// and formulas of FLIP's reference code, `calculateSpatialFilterRadius`
/// and the feature filter; Andersson et al. 2020, §4.1 and §4.2). An
/// edge's error spreads this far onto its neighbours. 10 at 67 ppd (the
/// feature filter alone reaches 9). `ppd` not finite or not positive: 0.
pub fn flip_filter_radius(ppd: f32) -> u32 {
    let (colour, feature) = flip_filter_radii(ppd);
    colour.max(feature)
}

/// The radii behind [`flip_filter_radius`], `(colour, feature)`: 10 and 9
/// at 67 ppd; both 0 for a `ppd` not finite or not positive.
pub fn flip_filter_radii(ppd: f32) -> (u32, u32) {
    if !(ppd.is_finite() && ppd > 0.0) {
        return (0, 0);
    }
    let pi_sq = core::f64::consts::PI * core::f64::consts::PI;
    let ppd = f64::from(ppd);
    let colour = (3.0 * (0.04 / (2.0 * pi_sq)).sqrt() * ppd).ceil();
    let feature = (3.0 * 0.5 * 0.082 * ppd).ceil();
    let radius = |r: f64| r.min(f64::from(u32::MAX)) as u32;
    (radius(colour), radius(feature))
}

/// LDR-FLIP of `test` against `reference` at the default 67 pixels per
/// degree: the one call of `nv-flip` in the workspace.
pub fn flip(reference: &Rgb8, test: &Rgb8) -> Result<Flip, MetricError> {
    same_size(reference, test)?;
    let (w, h) = (reference.width, reference.height);
    let r = nv_flip::FlipImageRgb8::with_data(w, h, &reference.data);
    let t = nv_flip::FlipImageRgb8::with_data(w, h, &test.data);
    let error = nv_flip::flip(r, t, FLIP_PIXELS_PER_DEGREE);
    let map = error.to_vec();
    let mean = map.iter().map(|&v| v as f64).sum::<f64>() / map.len() as f64;
    let magma = Rgb8 {
        width: w,
        height: h,
        data: error.apply_color_lut(&nv_flip::magma_lut()).to_vec(),
    };
    Ok(Flip { map, mean, magma })
}

/// FLIP's magma colour map, 256 RGB entries from error 0 to 1: what
/// [`Flip::magma`] is coloured with, for readers that invert it.
pub fn magma_lut() -> Vec<[u8; 3]> {
    nv_flip::magma_lut()
        .to_vec()
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

fn percentile(values: &[f32], q: f64) -> f32 {
    let mut v = values.to_vec();
    v.sort_by(f32::total_cmp);
    let i = ((v.len() as f64 - 1.0) * q).round() as usize;
    v[i.min(v.len() - 1)]
}

/// PSNR in dB over the three 8-bit channels; `+∞` for identical images.
pub fn psnr(reference: &Rgb8, test: &Rgb8) -> Result<f64, MetricError> {
    same_size(reference, test)?;
    let se: f64 = reference
        .data
        .iter()
        .zip(&test.data)
        .map(|(&a, &b)| {
            let d = a as f64 - b as f64;
            d * d
        })
        .sum();
    let mse = se / reference.data.len() as f64;
    Ok(if mse == 0.0 {
        f64::INFINITY
    } else {
        10.0 * (255.0f64 * 255.0 / mse).log10()
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn flip_reaches_ten_pixels_at_its_default_viewing_condition() {
        // Colour filter ⌈9.05⌉, feature filter ⌈8.24⌉.
        assert_eq!(super::flip_filter_radius(super::FLIP_PIXELS_PER_DEGREE), 10);
        assert_eq!(
            super::flip_filter_radii(super::FLIP_PIXELS_PER_DEGREE),
            (10, 9)
        );
        assert_eq!(super::flip_filter_radius(30.0), 5);
        for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert_eq!(super::flip_filter_radius(bad), 0);
        }
    }

    use super::*;

    #[test]
    fn identical_images_have_zero_flip_and_infinite_psnr() {
        let a = Rgb8::grey(16, 8, |x, _| (x * 10) as u8);
        let f = flip(&a, &a).unwrap();
        assert!(f.mean < 1e-6);
        assert_eq!(f.p99(), 0.0);
        assert_eq!(f.magma.data.len(), 16 * 8 * 3);
        assert_eq!(psnr(&a, &a).unwrap(), f64::INFINITY);
    }

    #[test]
    fn mismatched_or_empty_images_are_typed_errors() {
        let a = Rgb8::grey(4, 4, |_, _| 0);
        let b = Rgb8::grey(4, 5, |_, _| 0);
        let size = MetricError::SizeMismatch {
            reference: (4, 4),
            test: (4, 5),
        };
        assert_eq!(flip(&a, &b).err(), Some(size.clone()));
        assert_eq!(psnr(&a, &b).err(), Some(size));
        let short = Rgb8 {
            data: vec![0; 5],
            ..a.clone()
        };
        assert!(matches!(
            flip(&a, &short),
            Err(MetricError::DataLength { found: 5, .. })
        ));
        let empty = Rgb8::grey(0, 3, |_, _| 0);
        assert_eq!(flip(&empty, &empty).err(), Some(MetricError::Empty));
    }

    #[test]
    fn psnr_of_a_known_error() {
        let a = Rgb8::grey(4, 4, |_, _| 100);
        let b = Rgb8::grey(4, 4, |_, _| 110);
        let p = psnr(&a, &b).unwrap();
        assert!((p - 10.0 * (255.0f64 * 255.0 / 100.0).log10()).abs() < 1e-9);
    }

    #[test]
    fn p99_is_the_nearest_rank() {
        let f = Flip {
            map: (0..=100).rev().map(|i| i as f32 / 100.0).collect(),
            mean: 0.5,
            magma: Rgb8::grey(1, 1, |_, _| 0),
        };
        assert_eq!(f.p99(), 0.99);
    }

    #[test]
    fn the_magma_map_runs_from_dark_to_bright() {
        let lut = magma_lut();
        assert_eq!(lut.len(), 256);
        let sum = |c: [u8; 3]| c.iter().map(|&v| v as u32).sum::<u32>();
        assert!(sum(lut[0]) < sum(lut[255]));
    }

    #[test]
    fn a_frame_with_too_few_pixels_is_an_error() {
        let mut f = Frame::new(2, 2);
        f.color.pop();
        assert!(matches!(
            Rgb8::from_frame(&f),
            Err(MetricError::DataLength { found: 3, .. })
        ));
    }
}
