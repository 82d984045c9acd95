//! The material gate: eq. 2's gate applied to albedo (§4.1, Fig. 6).

use glam::Vec3;

use super::{bilateral_weight, Geometry, SraaParams};

/// Default tolerance of the albedo gate ([`material_gated_weight`]), in the
/// square-root encoding of [`albedo_difference`].
///
/// `0.1` is a tenth of the encoded range, about 25 of 255 sRGB codes: slow
/// texture variation and noise below it is blended by eq. 1 as before (gating
/// it would turn the reconstruction into nearest-sample lookup on every
/// textured surface), while the edges between differently coloured patches or
/// texels that SRAA cannot see (§4.1, Fig. 6) lie far above it: the closest
/// two colours of the `checker` palette differ by 0.42.
pub const ALBEDO_TOLERANCE: f32 = 0.1;

/// Dissimilarity of two diffuse albedos for the material gate: the largest
/// per-channel difference of their square roots, `max_c |√a_c − √b_c|`.
///
/// The square root is a cheap perceptual encoding (gamma 2, close to sRGB's
/// transfer curve), so one tolerance means about the same visible step on
/// dark and on bright albedos; the maximum over channels sees a hue change at
/// constant luminance (red against green) that a luminance difference would
/// miss.
///
/// Domain: albedos with finite components, nominally in `[0, 1]`. Negative
/// components count as 0; components above 1 are compared as they are.
/// Outside the domain: a NaN or infinite component in either albedo gives
/// `+∞` (the samples never match). Symmetric; 0 for equal albedos.
#[inline]
pub fn albedo_difference(a: Vec3, b: Vec3) -> f32 {
    if !(a.is_finite() && b.is_finite()) {
        return f32::INFINITY;
    }
    root_difference(albedo_root(a), albedo_root(b))
}

/// `√max(a, 0)` per channel: the space [`albedo_difference`] compares in.
/// Kept apart so the resolver can take each albedo's roots once per pixel
/// instead of once per (subsample, neighbour) pair, to the same bits.
#[inline(always)]
pub(crate) fn albedo_root(a: Vec3) -> Vec3 {
    let e = |x: f32| crate::math::sqrt(if x > 0.0 { x } else { 0.0 });
    Vec3::new(e(a.x), e(a.y), e(a.z))
}

/// The largest channel difference of two [`albedo_root`]s.
#[inline(always)]
pub(crate) fn root_difference(ra: Vec3, rb: Vec3) -> f32 {
    let d = |x: f32, y: f32| libm::fabsf(x - y);
    d(ra.x, rb.x).max(d(ra.y, rb.y)).max(d(ra.z, rb.z))
}

/// Material-gated weight: eq. 2's gate applied to albedo instead of shadow
/// state. 0 when the albedos of `i` (the geometric subsample) and `j` (the
/// shaded sample) differ by more than `tolerance` ([`albedo_difference`]),
/// eq. 1 ([`bilateral_weight`]) when they match.
///
/// This is the fix for the failure case of §4.1 (Fig. 6): edges between
/// patches of different colour on one flat surface are invisible to depth and
/// normal, so eq. 1 blends the colours of both patches into every subsample
/// near the edge and the edge stays as jagged as the shaded samples. With the
/// albedo of each geometric subsample (a texture lookup at its hit; the
/// material's constant albedo elsewhere), a subsample only takes colour from
/// shaded samples of its own patch. As with eq. 2, when the gate removes every
/// neighbour the reconstruction falls back to the nearest shaded sample
/// ([`reconstruct`](super::reconstruct)).
///
/// Domain: that of [`bilateral_weight`] for the geometry, finite albedos, a
/// tolerance `≥ 0`. Outside it: a non-finite albedo, or a NaN or negative
/// tolerance, gates (weight 0); the result is always in `[0, 1]`, never NaN.
#[inline]
pub fn material_gated_weight(
    params: &SraaParams,
    gi: &Geometry,
    gj: &Geometry,
    ai: Vec3,
    aj: Vec3,
    tolerance: f32,
) -> f32 {
    if material_gate(ai, aj, tolerance) {
        bilateral_weight(params, gi, gj)
    } else {
        0.0
    }
}

/// The gate of [`material_gated_weight`]: whether albedos `ai` and `aj` match
/// within `tolerance` ([`albedo_difference`]). A non-finite albedo, or a NaN
/// or negative tolerance, never matches.
#[inline]
pub fn material_gate(ai: Vec3, aj: Vec3, tolerance: f32) -> bool {
    let d = albedo_difference(ai, aj);
    // d = ∞ (a non-finite albedo) gates even under an infinite tolerance.
    d <= tolerance && d < f32::INFINITY
}
