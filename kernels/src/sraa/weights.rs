//! The bilateral weights: eq. 1, its spatial term, and eq. 2's shadow gate.

use super::{DepthMetric, Geometry, SraaParams, WeightForm};

/// Cosines within this of 1 count as equal normals in [`bilateral_weight`]
/// (`2⁻²¹ ≈ 4.8·10⁻⁷`, eight ulps of 1): rounding noise of f32 normalisation.
pub const NORMAL_COS_SNAP: f32 = 1.0 / 2_097_152.0;

/// Weight sums below this (`2⁻⁶⁴ ≈ 5.4·10⁻²⁰`) count as underflowed: products
/// `w·C` of such weights with ordinary colours approach f32's subnormal range,
/// where the normalised result would lose its precision.
pub const NEGLIGIBLE_WEIGHT: f32 = 5.421_011e-20;

/// `G(x) = exp(−x²)`, the Gaussian of eq. 1. `G(±∞) = 0`, `G(NaN) = 0`.
#[inline]
pub fn gaussian(x: f32) -> f32 {
    let e = libm::expf(-(x * x));
    // NaN must exclude, never propagate.
    if !e.is_nan() {
        e
    } else {
        0.0
    }
}

/// Beyond this `s`, `exp(−s) < 2⁻¹⁵¹` rounds to 0 in f32 (`e⁻¹⁰⁵ ≈ 2.5·10⁻⁴⁶`).
const EXP_UNDERFLOW: f32 = 105.0;

/// `exp(−s)` for `s = a² + b² ≥ 0`; 0 for `s = ∞` or NaN.
///
/// The two ends skip the exponential and return what it would: `s = 0`
/// (same depth, same normal: the common case inside a surface, and `w_ii`)
/// gives exactly 1, and `s ≥ 105`, ∞ or NaN gives 0.
#[inline]
fn gaussian_sum(s: f32) -> f32 {
    if s == 0.0 {
        1.0
    } else if s < EXP_UNDERFLOW {
        libm::expf(-s)
    } else {
        0.0
    }
}

/// `sat(x) = max(0, min(1, x))` (§3.1). `sat(NaN) = 0`.
#[inline]
pub fn saturate(x: f32) -> f32 {
    if x > 0.0 {
        if x < 1.0 {
            x
        } else {
            1.0
        }
    } else {
        0.0
    }
}

/// The depth dissimilarity `Δz` of eq. 1 under `metric`, always `≥ 0`.
///
/// Domain: depths `≥ 0`, finite or `+∞` (a miss). Equal depths (including two
/// misses) give 0. A miss against a hit, or a NaN, gives `+∞`, so the weight is 0.
/// Under the relative metric a step away from depth 0 is total (`2`), and
/// subnormal depths are compared like any others.
#[inline]
pub fn depth_difference(zi: f32, zj: f32, metric: DepthMetric) -> f32 {
    if zi == zj {
        return 0.0;
    }
    let diff = libm::fabsf(zj - zi);
    let r = match metric {
        DepthMetric::Absolute => diff,
        DepthMetric::Relative => {
            // Halve before adding so two depths near f32::MAX do not overflow.
            // Subnormal means divide fine; a mean that underflows to 0 gives ∞.
            let mean = 0.5 * libm::fabsf(zi) + 0.5 * libm::fabsf(zj);
            diff / mean
        }
    };
    // ∞/∞ and anything involving NaN: the samples cannot be matched.
    if !r.is_nan() {
        r
    } else {
        f32::INFINITY
    }
}

/// Bilateral weight `w_ij` of sample `j` when reconstructing sample `i` (eq. 1).
///
/// `w_ij = G(σz·Δz) · G(σn·(1 − sat(nj·ni)))` for [`WeightForm::Product`] (the
/// paper), or `exp(−s·max(1 − sat(nj·ni), σz·Δz))` for [`WeightForm::ChajdasMax`].
///
/// Domain: unit normals, depths in `[0, ∞]`, finite non-negative parameters.
/// Returns a value in `[0, 1]`; `w_ii = 1`; symmetric in `i` and `j`;
/// non-increasing in `|Δz|` and in the angle between the normals.
/// Outside the domain: a NaN anywhere gives 0 (the neighbour is excluded, never
/// blended); two misses (`depth = +∞`) give 1 whatever their normals; non-unit normals are accepted (the cosine is saturated to `[0, 1]`);
/// weights that underflow are 0, and [`reconstruct`](super::reconstruct) falls back.
#[inline]
pub fn bilateral_weight(params: &SraaParams, gi: &Geometry, gj: &Geometry) -> f32 {
    reconstruction_weight(params, gi, gj, 0.0)
}

/// The weight a reconstruction gives shaded sample `j` for subsample `i`:
/// eq. 1 ([`bilateral_weight`]) times the spatial term `exp(−d²/σs²)`,
/// `d² = distance2` the squared screen distance in pixels² from the
/// subsample to the shaded sample, when [`SraaParams::sigma_s`] is positive.
///
/// The paper's Fig. 2 weighs neighbours "by their distance and the normal
/// change"; eq. 1 itself has no distance, and without one a 3×3
/// neighbourhood of like geometry is a box filter. For the product form the
/// three Gaussians are one exponential, `exp(−(a² + b² + d²/σs²))`.
///
/// Domain: that of [`bilateral_weight`], and `distance2 ≥ 0`. With the term
/// on, a NaN or infinite `distance2` gives 0; with it off (`σs ≤ 0` or NaN),
/// `distance2` is ignored and the result is eq. 1's, bit for bit.
#[inline]
pub fn reconstruction_weight(
    params: &SraaParams,
    gi: &Geometry,
    gj: &Geometry,
    distance2: f32,
) -> f32 {
    // At distance 0 the term is 1 whatever σs (an underflowing σs² must
    // not turn eq. 1 into 0/0).
    let spatial = if params.sigma_s > 0.0 && distance2 != 0.0 {
        distance2 / (params.sigma_s * params.sigma_s)
    } else {
        0.0
    };
    let dz = depth_difference(gi.depth, gj.depth, params.depth_metric());
    // A unit vector normalised in f32 has |n|² within a few ulps of 1, so its
    // cosine with itself may be 1 − 2⁻²³·k; count cosines that close to 1 as 1,
    // or w_ii = 1 fails for the (linear) Chajdas form.
    let cos = saturate(gj.normal.dot(gi.normal));
    let dn = if cos >= 1.0 - NORMAL_COS_SNAP {
        0.0
    } else {
        1.0 - cos
    };
    if gi.depth == f32::INFINITY && gj.depth == f32::INFINITY {
        // Two misses: both are background, whatever their (meaningless) normals.
        return 1.0;
    }
    if gi.normal.is_nan() || gj.normal.is_nan() {
        return 0.0;
    }
    let w = match params.form() {
        // G(a)·G(b) = exp(−(a² + b²)): one exponential instead of two, the
        // same value up to rounding (bounded against f64 in the tests).
        WeightForm::Product => {
            let (a, b) = (params.sigma_z * dz, params.sigma_n * dn);
            gaussian_sum(a * a + b * b + spatial)
        }
        WeightForm::ChajdasMax => {
            let x = params.scale * dn.max(params.sigma_z * dz);
            let e = libm::expf(-x);
            let e = if !e.is_nan() { e } else { 0.0 };
            if spatial == 0.0 {
                e
            } else {
                e * gaussian_sum(spatial)
            }
        }
    };
    saturate(w)
}

/// Shadow-gated weight (eq. 2): 0 when the shadow states of `i` and `j` differ,
/// eq. 1 ([`bilateral_weight`]) when they agree.
///
/// `si`/`sj` are one light's states (`true` = in shadow). With several lights the
/// faithful extension reconstructs each light's direct contribution with its own
/// gate; which combination a backend uses is its choice.
///
/// Domain and out-of-domain behaviour are those of [`bilateral_weight`].
#[inline]
pub fn shadow_gated_weight(
    params: &SraaParams,
    gi: &Geometry,
    gj: &Geometry,
    si: bool,
    sj: bool,
) -> f32 {
    if si != sj {
        0.0
    } else {
        bilateral_weight(params, gi, gj)
    }
}
