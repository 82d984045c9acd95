//! Edge classes: which pixels need antialiasing, and why.
//!
//! A pixel is classified from its own **sub-samples**: the AOVs (view depth,
//! normal, albedo, per-light visibility, mirror reflectance) of a NoAA frame
//! rendered by the CPU reference at [`SUBSAMPLES`]× the quality size on each
//! side, so sub-sample `(i, j)` of pixel `(x, y)` is pixel
//! `(SUBSAMPLES·x + i, SUBSAMPLES·y + j)` of that frame: the centre of cell
//! `(i, j)` of a regular `SUBSAMPLES × SUBSAMPLES` grid over the pixel. A
//! feature that the one NoAA sample through the pixel centre misses (a thin
//! pole, a shadow corner) is still seen by some sub-sample, so the pixel is
//! not called flat.
//!
//! The classes may overlap; *flat* is a pixel in none of the others.
//!
//! | class | a pixel is in it when |
//! |---|---|
//! | silhouette | two 4-neighbouring sub-samples of the pixel see a surface and the background, or view depths that differ by more than [`SILHOUETTE_DEPTH`] relatively, unless the inverse depth continues linearly from either side (as across one plane, however grazing) |
//! | crease | two 4-neighbouring sub-samples on one continuous surface (no silhouette between them) have normals whose cosine is below [`CREASE_COS`] |
//! | shadow | no silhouette or crease in the pixel, and the per-light visibility of its surface sub-samples differs (some see a light that others do not) |
//! | texture | no silhouette or crease in the pixel, and the albedo of its surface sub-samples differs by more than [`TEXTURE_ALBEDO`] in some channel of `√albedo` |
//! | reflection | a sub-sample sees a mirror (reflectance above 0) |
//! | flat | none of the above, and no pixel of the above within [`near_edge_radius`] pixels of the metric (Chebyshev distance: 10 under FLIP, the 21×21 square around it; 5 under SSIM) |
//!
//! A pixel in none of the five classes but within [`near_edge_radius`] of
//! one is in the metric's *near edge* band ([`ClassMasks::near`]), not
//! flat: an error metric with a spatial filter (FLIP's filters, SSIM's
//! window) spreads an edge's error onto its neighbours as far as the
//! filter reaches, so a method that changes the edge changes the error
//! there too. The band is measured and reported but not judged; flat is
//! judged on what remains beyond it.

mod masks;
#[cfg(test)]
mod tests;
mod verdict;

pub use masks::{classify, ClassMasks};
pub use verdict::{
    loss_text, outcome_word, ratio_text, ClassError, Judged, Metric, Outcome, Verdict, BEAT_FACTOR,
    DSSIM_FLOOR, FLAT_FACTOR, LOSE_FACTOR,
};

/// Sub-samples per pixel side: the classes see a 4×4 grid in each pixel.
pub const SUBSAMPLES: u32 = 4;
/// Relative view-depth difference between neighbouring sub-samples above
/// which they see different surfaces (the edge mask's threshold, 2 %).
pub const SILHOUETTE_DEPTH: f32 = 0.02;
/// Cosine between neighbouring sub-samples' normals below which one surface
/// folds inside the pixel (about 26°; the edge mask's threshold).
pub const CREASE_COS: f32 = 0.9;
/// Difference of `√albedo` in one channel above which the albedo changes
/// inside the pixel: about 13 sRGB codes at mid-grey, so a printed pattern or
/// a texture step counts and texture noise of a few codes does not.
pub const TEXTURE_ALBEDO: f32 = 0.05;
/// Pixels in none of the classes within this Chebyshev distance of a
/// classed pixel (silhouette, crease, shadow, texture or reflection) are in
/// `metric`'s near-edge band, not flat: as far as the metric carries an
/// edge's error onto its neighbours. Under FLIP, its filters' reach at the
/// pixels per degree it is computed at
/// ([`flip_filter_radius`](subcone_metrics::flip_filter_radius), 10 px at
/// 67 ppd); under SSIM, its window's half-width
/// ([`ssim::RADIUS`](subcone_metrics::ssim::RADIUS), 5 px).
pub fn near_edge_radius(metric: Metric) -> u32 {
    match metric {
        Metric::Flip => flip_near_edge_radius(),
        Metric::Ssim => SSIM_NEAR_EDGE_RADIUS,
    }
}

/// [`near_edge_radius`] under FLIP: its filters' reach at the pixels per
/// degree it is computed at (10 px at 67 ppd).
pub fn flip_near_edge_radius() -> u32 {
    subcone_metrics::flip_filter_radius(subcone_metrics::FLIP_PIXELS_PER_DEGREE)
}

/// [`near_edge_radius`] under SSIM: its window's half-width (5 px).
pub const SSIM_NEAR_EDGE_RADIUS: u32 = subcone_metrics::ssim::RADIUS as u32;
/// A class with fewer pixels than this (at some camera offset) gets no
/// verdict: a mean over a handful of pixels moves with a sub-pixel shift of
/// the camera by more than the thresholds the verdicts use.
pub const MIN_VERDICT_PIXELS: u64 = 64;

/// A class mean as the verdict lines print it: 4 decimals, or 3 significant
/// digits below 0.001, so that two small errors a verdict tells apart do
/// not both read 0.0000.
pub fn figure(v: f64) -> String {
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.2e}")
    } else {
        format!("{v:.4}")
    }
}

/// An edge class: the registry's ([`subcone_scene::EdgeClass`]), which
/// also says which classes each method claims.
pub use subcone_scene::registry::EdgeClass as Class;
/// Every class, in column order.
pub use subcone_scene::registry::EDGE_CLASSES as CLASSES;
