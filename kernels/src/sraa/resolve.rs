//! The pixel resolve: the four reconstructed subsamples filtered into the
//! pixel, in linear or tone-mapped space.

use glam::Vec3;

/// The pixel resolve (§3, "the subpixel shading values are filtered into an
/// antialiased screen-resolution image"): a box filter over the four
/// reconstructed subsamples, each of which covers a quarter of the pixel.
///
/// Domain: finite colours. A non-finite subsample is dropped and the others are
/// averaged; with none finite, returns black.
#[inline(always)]
pub fn resolve_pixel(subsamples: &[Vec3; 4]) -> Vec3 {
    let n = subsamples.iter().filter(|c| c.is_finite()).count();
    if n == 0 {
        return Vec3::ZERO;
    }
    // Scale before summing, so four colours near f32::MAX do not overflow.
    let inv = 1.0 / n as f32;
    subsamples
        .iter()
        .filter(|c| c.is_finite())
        .fold(Vec3::ZERO, |s, c| s + *c * inv)
}

/// Luma weights of linear RGB (ITU-R BT.709, the sRGB primaries) for the
/// tone-mapped resolve's weights ([`tone_map_weight`]).
pub const RESOLVE_LUMA: Vec3 = Vec3::new(0.2126, 0.7152, 0.0722);

/// The weight of one subsample in the tone-mapped resolve (Karis 2014,
/// *High Quality Temporal Supersampling*, the resolve of UE4's TAA):
/// `1 / (1 + exposure · luma(c))`, [`RESOLVE_LUMA`]. It is the derivative
/// factor of the reversible tone map `T(c) = c / (1 + luma(c))`, whose
/// inverse is `T⁻¹(c) = c / (1 − luma(c))`: `Σ wᵢ cᵢ / Σ wᵢ` with these
/// weights equals `T⁻¹(mean T(cᵢ))` exactly in exact arithmetic (with the
/// exposure folded into both), so a pixel is averaged as it will be seen
/// after tone mapping, not as linear radiance, and one HDR subsample no
/// longer takes over the pixel.
///
/// Computed in f64 (so the exposed luma of any finite colour at any finite
/// exposure is finite) and rounded to f32.
///
/// Domain: finite colours, `exposure > 0` and finite. Negative luma counts
/// as 0 (weight 1); an exposed luma above about `10⁴⁵` gives a weight that
/// rounds to 0 in f32. Outside the domain: a non-finite colour or exposure
/// gives 0 (the subsample is excluded, as [`resolve_pixel`] drops it); the
/// result is always in `[0, 1]`, never NaN.
#[inline]
pub fn tone_map_weight(c: Vec3, exposure: f32) -> f32 {
    tone_map_weight_f64(c, exposure) as f32
}

/// [`tone_map_weight`] before its rounding to f32.
#[inline]
fn tone_map_weight_f64(c: Vec3, exposure: f32) -> f64 {
    if !(c.is_finite() && exposure.is_finite()) {
        return 0.0;
    }
    let luma = (f64::from(c.x) * f64::from(RESOLVE_LUMA.x)
        + f64::from(c.y) * f64::from(RESOLVE_LUMA.y)
        + f64::from(c.z) * f64::from(RESOLVE_LUMA.z))
        * f64::from(exposure);
    // Negative luma (and a negative exposure's) reads as 0.
    let luma = if luma > 0.0 { luma } else { 0.0 };
    1.0 / (1.0 + luma)
}

/// The pixel resolve in tone-mapped space: the four reconstructed
/// subsamples averaged with [`tone_map_weight`]s, `Σ wₖ cₖ / Σ wₖ`, the
/// weighting TAA resolves with (Karis 2014, *High Quality Temporal
/// Supersampling*) so that an edge beside an HDR highlight is antialiased
/// as it is displayed. The result is linear radiance, like
/// [`resolve_pixel`]'s (the exposure only shapes the weights); tone mapped
/// with the same exposure, `T(exposure · result)` is the mean of the
/// subsamples' `T(exposure · cₖ)`, up to rounding. Subsamples of one luma
/// get equal weights, so the result is [`resolve_pixel`]'s box (up to the
/// box's f32 rounding), a pixel of one colour is returned unchanged (bit
/// for bit), and `exposure → 0` tends to the box.
///
/// Weights and sums in f64 (every weight of a finite colour is then
/// positive, at least about `10⁻⁷⁷`, so the mean never underflows), the
/// mean rounded to f32 once.
///
/// Domain: finite colours, `exposure > 0` and finite. Outside it: a
/// non-finite subsample is dropped (none finite gives black, as
/// [`resolve_pixel`]); an exposure that is not positive and finite gives
/// [`resolve_pixel`]'s box. Never NaN: the result is a convex combination
/// of finite f32 colours, so finite.
#[inline]
pub fn resolve_pixel_tone_mapped(subsamples: &[Vec3; 4], exposure: f32) -> Vec3 {
    if !(exposure > 0.0 && exposure.is_finite()) {
        return resolve_pixel(subsamples);
    }
    let mut sum = [0.0f64; 3];
    let mut weight = 0.0f64;
    for c in subsamples.iter().filter(|c| c.is_finite()) {
        let w = tone_map_weight_f64(*c, exposure);
        for (s, x) in sum.iter_mut().zip(c.to_array()) {
            *s += w * f64::from(x);
        }
        weight += w;
    }
    if !(weight > 0.0) {
        return Vec3::ZERO;
    }
    Vec3::from_array(sum.map(|s| (s / weight) as f32))
}

/// The space a pixel's four reconstructed subsamples are averaged in, the
/// last step of the SRAA resolve (§3: "the subpixel shading values are
/// filtered into an antialiased screen-resolution image").
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum ResolveSpace {
    /// The box filter over linear radiance ([`resolve_pixel`]), the paper's
    /// resolve and the default.
    #[default]
    Linear,
    /// Weighted by [`tone_map_weight`] ([`resolve_pixel_tone_mapped`],
    /// Karis 2014): for HDR radiance that is tone mapped after the resolve.
    ToneMapped {
        /// The exposure the frame is tone mapped with (the factor on
        /// radiance before the tone curve), `> 0` and finite.
        exposure: f32,
    },
}

impl ResolveSpace {
    /// Resolve a pixel's four subsamples in this space.
    #[inline(always)]
    pub fn resolve(&self, subsamples: &[Vec3; 4]) -> Vec3 {
        match *self {
            ResolveSpace::Linear => resolve_pixel(subsamples),
            ResolveSpace::ToneMapped { exposure } => {
                resolve_pixel_tone_mapped(subsamples, exposure)
            }
        }
    }

    /// Whether the space is in its domain: always for
    /// [`ResolveSpace::Linear`], an exposure `> 0` and finite for
    /// [`ResolveSpace::ToneMapped`].
    pub fn is_valid(&self) -> bool {
        match *self {
            ResolveSpace::Linear => true,
            ResolveSpace::ToneMapped { exposure } => exposure > 0.0 && exposure.is_finite(),
        }
    }
}
