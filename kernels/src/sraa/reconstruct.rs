//! The reconstruction of a geometric subsample from its shaded neighbours
//! (§3.1–3.3), for one colour or several layers at once.

use glam::Vec3;

use super::{material_gate, reconstruction_weight, Geometry, SraaParams};
use crate::sum::WeightedSum;

/// One shaded sample offered to [`reconstruct`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadedSample {
    /// Geometry at the shaded sample.
    pub geometry: Geometry,
    /// Its shaded colour (linear RGB). Non-finite colours are excluded.
    pub color: Vec3,
    /// Its shadow state for the light being reconstructed (ignored when the
    /// target has no gate).
    pub shadowed: bool,
    /// Squared screen distance, in pixels², from the target subsample: the
    /// spatial term's `d²` ([`reconstruction_weight`]) and what chooses the
    /// fallback sample.
    pub distance2: f32,
}

/// Result of reconstructing one geometric subsample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reconstruction {
    /// The reconstructed colour.
    pub color: Vec3,
    /// Sum of the weights used (0 when the fallback applied).
    pub weight_sum: f32,
    /// `true` when every weight was 0 or underflowed and the nearest shaded
    /// sample was taken instead.
    pub fell_back: bool,
}

/// Reconstruct the colour of a geometric subsample from shaded neighbours (§3.1–3.3).
///
/// `C_i = Σ_j w_ij C_j / Σ_j w_ij`, with `w_ij` from [`reconstruction_weight`]
/// (eq. 1 times the spatial term), gated as [`shadow_gated_weight`](super::shadow_gated_weight) gates when
/// `target_shadow` is `Some` (eq. 2).
/// The caller chooses the neighbourhood (by default the shaded samples of the
/// 3×3 pixels around, [`SraaParams::radius`]).
///
/// When every weight is 0 or their sum is negligible, below
/// [`NEGLIGIBLE_WEIGHT`](super::NEGLIGIBLE_WEIGHT) (e.g. `σz·Δz = 1e20` for every neighbour), returns the nearest shaded sample with a finite colour (smallest
/// `distance2`, first on ties) with `fell_back = true`; with no usable neighbour
/// at all, returns black. Never NaN: non-finite neighbour colours are excluded.
/// The result lies in the convex hull of the neighbours' colours, up to f32 rounding.
pub fn reconstruct<I>(
    params: &SraaParams,
    target: &Geometry,
    target_shadow: Option<bool>,
    neighbours: I,
) -> Reconstruction
where
    I: IntoIterator<Item = ShadedSample>,
{
    let mut acc = WeightedSum::ZERO;
    let mut nearest = Vec3::ZERO;
    let mut nearest_d2 = f32::INFINITY;
    let mut any = false;
    for s in neighbours {
        if !s.color.is_finite() {
            continue;
        }
        let d2 = if !s.distance2.is_nan() {
            s.distance2
        } else {
            f32::INFINITY
        };
        if !any || d2 < nearest_d2 {
            nearest = s.color;
            nearest_d2 = d2;
            any = true;
        }
        let w = match target_shadow {
            Some(si) if si != s.shadowed => 0.0,
            _ => reconstruction_weight(params, target, &s.geometry, d2),
        };
        acc.add(w, s.color);
    }
    if let Some(c) = acc.mean() {
        return Reconstruction {
            color: c,
            weight_sum: acc.weight(),
            fell_back: false,
        };
    }
    Reconstruction {
        color: nearest,
        weight_sum: 0.0,
        fell_back: true,
    }
}

/// Most layers [`reconstruct_layers`] handles at once.
pub const MAX_LAYERS: usize = 16;

/// One shaded neighbour offered to [`reconstruct_layers`]: its geometry, its
/// shadow states (bit `b` = in light `b`'s shadow) and one colour per layer.
#[derive(Clone, Copy, Debug)]
pub struct LayeredSample<'a> {
    /// Geometry at the shaded sample.
    pub geometry: Geometry,
    /// Shadow states, one bit per light.
    pub shadow: u32,
    /// Squared screen distance to the target subsample (for the fallback).
    pub distance2: f32,
    /// One colour per layer.
    pub colors: &'a [Vec3],
}

/// [`reconstruct`] for several layers that share the target's geometry, in one
/// pass over the neighbours: the weight ([`reconstruction_weight`]: eq. 1 and
/// the spatial term) is computed once per neighbour, and layer `i` applies eq. 2's gate on shadow bit `gates[i]` (or no
/// gate for `None`). This is how SRAA-RT reconstructs a subsample's
/// shadow-independent part and each light's direct part (§3.1–3.2).
///
/// Writes `min(gates.len(), out.len(), MAX_LAYERS)` layers to `out`; each equals,
/// bit for bit, what [`reconstruct`] returns for that layer alone (same
/// weights, same order of summation, same fallback). A neighbour with fewer
/// colours than layers contributes black to the missing ones.
pub fn reconstruct_layers<'a, I>(
    params: &SraaParams,
    target: &Geometry,
    target_shadow: u32,
    gates: &[Option<u8>],
    neighbours: I,
    out: &mut [Vec3],
) where
    I: IntoIterator<Item = LayeredSample<'a>>,
{
    // A NaN distance needs no sanitising here: reconstruction_weight gives
    // it weight 0 with the spatial term on, and ignores it with the term off.
    let weighted = neighbours.into_iter().map(|s| {
        (
            reconstruction_weight(params, target, &s.geometry, s.distance2),
            s,
        )
    });
    reconstruct_weighted_layers(target_shadow, gates, weighted, out);
}

/// [`reconstruct_layers`] with the material gate: each neighbour's weight is
/// [`material_gated_weight`](super::material_gated_weight) of the target's albedo and the neighbour's (the
/// second item of each pair) instead of [`bilateral_weight`](super::bilateral_weight), so every layer
/// is gated by albedo (§4.1, Fig. 6) and, where `gates` says so, by shadow
/// state (eq. 2). Same order of summation and fallback as
/// [`reconstruct_layers`]; with all albedos equal, the same bits.
#[allow(clippy::too_many_arguments)]
pub fn reconstruct_layers_material<'a, I>(
    params: &SraaParams,
    target: &Geometry,
    target_shadow: u32,
    target_albedo: Vec3,
    tolerance: f32,
    gates: &[Option<u8>],
    neighbours: I,
    out: &mut [Vec3],
) where
    I: IntoIterator<Item = (LayeredSample<'a>, Vec3)>,
{
    let weighted = neighbours.into_iter().map(|(s, albedo)| {
        // As material_gated_weight gates, with the spatial term.
        let w = if material_gate(target_albedo, albedo, tolerance) {
            reconstruction_weight(params, target, &s.geometry, s.distance2)
        } else {
            0.0
        };
        (w, s)
    });
    reconstruct_weighted_layers(target_shadow, gates, weighted, out);
}

/// The loop of [`reconstruct_layers`] over neighbours whose ungated weight
/// is already known.
fn reconstruct_weighted_layers<'a, I>(
    target_shadow: u32,
    gates: &[Option<u8>],
    neighbours: I,
    out: &mut [Vec3],
) where
    I: Iterator<Item = (f32, LayeredSample<'a>)>,
{
    let n = gates.len().min(out.len()).min(MAX_LAYERS);
    let mut acc = [WeightedSum::ZERO; MAX_LAYERS];
    let mut nearest = [Vec3::ZERO; MAX_LAYERS];
    let mut nearest_d2 = [f32::INFINITY; MAX_LAYERS];
    let mut any = [false; MAX_LAYERS];
    for (w, s) in neighbours {
        let d2 = if !s.distance2.is_nan() {
            s.distance2
        } else {
            f32::INFINITY
        };
        for i in 0..n {
            let c = s.colors.get(i).copied().unwrap_or(Vec3::ZERO);
            if !c.is_finite() {
                continue;
            }
            if !any[i] || d2 < nearest_d2[i] {
                nearest[i] = c;
                nearest_d2[i] = d2;
                any[i] = true;
            }
            let wi = match gates[i] {
                Some(bit) if bit < 32 && ((target_shadow ^ s.shadow) >> bit) & 1 != 0 => 0.0,
                _ => w,
            };
            acc[i].add(wi, c);
        }
    }
    for i in 0..n {
        out[i] = acc[i].mean().unwrap_or(nearest[i]);
    }
}
