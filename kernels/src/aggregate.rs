//! Weighted aggregation of a pixel's CTSS samples (§3.4, eq. 6), with the
//! background as a sample of its own.

/// The WGSL mirror of this module (sample_weight and Aggregate (f32 sums, see the file)): same names, the parameter structs of
/// [`crate::wgsl::PARAMS`]; concatenate after `PARAMS` (see [`crate::wgsl`]).
pub const WGSL: &str = include_str!("aggregate.wgsl");

use glam::Vec3;

use crate::mask::mask_weight;
use crate::sum::WeightedSum;

/// How a hit group's sample is weighted.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Weighting {
    /// `w_i = bitCount(m_i)/32` of the correlated mask (eq. 6). The default.
    Visibility = 0,
    /// `w_i = 1` for every sample (Fig. 5 b, d): kept for comparison; it extrudes
    /// edges instead of smoothing them.
    Uniform = 1,
}

impl Weighting {
    /// Decode a `u32`; unknown codes read as [`Weighting::Visibility`].
    pub const fn from_u32(v: u32) -> Self {
        match v {
            1 => Weighting::Uniform,
            _ => Weighting::Visibility,
        }
    }
}

/// The weight of a sample whose correlated (already `& !M`) mask is `visible`.
///
/// `min_weight` is the authors' `MIN_SAMPLE_WEIGHT` (0.01 in their code; it is
/// not in the paper). Our default is 0: eq. 6 as published, so the hit weights
/// plus the background weight sum to exactly 1 and a surface hidden behind an
/// earlier group contributes nothing. The authors need the floor because their
/// division is by `max(0.01, Σw)`; we guard the division in
/// [`Aggregate::resolve`] instead. With a floor, the hit weights sum to at most
/// `1 + min_weight·samples` (`≤ 1.08` with the 8-sample cap).
///
/// Domain: `min_weight` in `[0, 1]`; NaN reads as 0.
#[inline]
pub fn sample_weight(visible: u32, weighting: Weighting, min_weight: f32) -> f32 {
    match weighting {
        Weighting::Uniform => 1.0,
        Weighting::Visibility => {
            let floor = if min_weight > 0.0 {
                min_weight.min(1.0)
            } else {
                0.0
            };
            mask_weight(visible).max(floor)
        }
    }
}

/// Running sums of eq. 6: `C = Σ w_i C_i / Σ w_i`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Aggregate {
    acc: WeightedSum,
    last: Option<Vec3>,
    samples: u32,
}

impl Aggregate {
    /// An empty aggregate.
    pub const fn new() -> Self {
        Self {
            acc: WeightedSum::ZERO,
            last: None,
            samples: 0,
        }
    }

    /// Add a shaded sample with weight `w`.
    ///
    /// Domain: `w` in `[0, 1]` (mask weights and uniform weights are). A negative
    /// or NaN weight counts as 0, a weight above 1 as 1 (so the sum of a pixel's
    /// weights cannot overflow). A non-finite colour is not added (shading
    /// failed; it must not poison the pixel), but the sample still counts.
    #[inline]
    pub fn add(&mut self, w: f32, color: Vec3) {
        self.samples += 1;
        if !color.is_finite() {
            return;
        }
        let w = if w > 0.0 { w.min(1.0) } else { 0.0 };
        self.acc.add(w, color);
        self.last = Some(color);
    }

    /// Number of samples added.
    pub const fn samples(&self) -> u32 {
        self.samples
    }

    /// Sum of the weights added so far.
    pub fn weight(&self) -> f32 {
        self.acc.weight()
    }

    /// The pixel colour (eq. 6), with `background` given weight `bg_weight` when
    /// the trace ended without full occlusion (the authors' code: `1 − bitCount(M)/32`,
    /// or 1 for uniform weights). Pass `bg_weight = 0` after a full occlusion.
    ///
    /// Eq. 6 and Algorithm 1 average over hits only: an edge pixel against the sky
    /// would take all of the object's colour, and a pixel with no hit would
    /// compute 0/0. Here a pixel with no hit is pure background, and when every
    /// weight is 0 or the total is negligible (below
    /// [`NEGLIGIBLE_WEIGHT`](crate::sraa::NEGLIGIBLE_WEIGHT), e.g. a full-occlusion
    /// surface whose mask was entirely hidden) the last surface's colour is
    /// returned, or the background, or black. If the weighted sum overflows
    /// (colours near `f32::MAX`), the last surface's colour is returned too.
    /// The result lies in the convex hull of the added colours and the background.
    pub fn resolve(&self, background: Vec3, bg_weight: f32) -> Vec3 {
        let bgw = if bg_weight > 0.0 && background.is_finite() {
            bg_weight.min(1.0)
        } else {
            0.0
        };
        let mut all = self.acc;
        if bgw > 0.0 {
            all.add(bgw, background);
        }
        if let Some(c) = all.mean() {
            return c;
        }
        match self.last {
            Some(c) => c,
            None if background.is_finite() => background,
            None => Vec3::ZERO,
        }
    }
}
