//! Non-binary visibility for semi-transparent surfaces: the `K` bitmasks of
//! CTSS §5.3 ("we can extend this to accumulate non-binary visibility thus
//! considering transparent objects … by using K bitmasks to encode K levels of
//! transparency").
//!
//! # Model
//! Each of the 32 cells of the pixel's mask (§3.5, [`crate::mask`]) carries an
//! opacity level `l ∈ {0, …, K}` (accumulated opacity `l/K`, transmittance
//! `(K − l)/K`), stored as `K` nested bitmasks `M_k = {cells with l ≥ k}`,
//! `M_K ⊆ … ⊆ M_1`. With only opaque surfaces every level is 0 or `K`, all `K`
//! masks equal the single global mask `M` of §3.4, and everything below reduces
//! to it exactly.
//!
//! A hit group with visibility mask `m_i` (eq. 7–8) and opacity `α` composites
//! over the cells of `m_i` front to back: a cell with `r = K − l` levels of
//! transmittance left keeps [`remaining_after`]`(r, α) = ⌊r·(1 − α) + ½⌋` of
//! them (never more than `r`; 0 when `α = 1`). The sample's weight in eq. 6 is
//! the transmittance it took, summed over its cells:
//!
//! ```text
//! w_i = Σ_{cells of m_i} (l' − l) / (32·K)
//! ```
//!
//! which for `α = 1` is `bitCount(m_i & !M)/32`, the paper's weight. Levels
//! only grow, so the weights of one pixel telescope: `Σ w_i ≤ 1`, and the
//! background's share is the transmittance left, `1 − Σ_cells l/(32·K)`
//! ([`TransparencyAccumulator::uncovered_weight`]). A cell is fully covered
//! only at `l = K`; the trace may stop at full occlusion only when the
//! occluding surface is opaque (see [`ConeStepper::record_alpha`](crate::ctss::ConeStepper::record_alpha)).
//!
//! # Quantisation
//! [`LEVELS`]` = K = 4`: opacity is resolved to quarters per cell. A single
//! surface's `α` is rounded to the nearest quarter (`α > 0.875` is opaque,
//! `α < 0.125` invisible); a stack of surfaces rounds at each layer (two
//! `α = 0.5` layers give 2 + 1 levels, 0.75, exact; a third adds nothing, as
//! `⌊1·0.5 + ½⌋ = 1`). The error of one layer is at most `1/(2K)` of a cell.

use crate::mask::FULL_MASK;

/// The WGSL mirror of this module (`subcone_remaining_after`,
/// `subcone_level_weight`, `subcone_TransparencyAccumulator` and its methods
/// as `subcone_transparency_accumulator_*`): same names, the parameter structs
/// of [`crate::wgsl::PARAMS`]; concatenate after `PARAMS` and
/// [`crate::mask::WGSL`] (see [`crate::wgsl`]).
pub const WGSL: &str = include_str!("transparency.wgsl");

/// `K`, the number of bitmasks (transparency levels) per pixel.
pub const LEVELS: u32 = 4;

/// `α` clamped to `[0, 1]`; NaN reads as 1 (opaque), so a broken opacity never
/// lets hidden surfaces show through.
#[inline]
pub fn clamp_alpha(alpha: f32) -> f32 {
    if alpha.is_nan() {
        1.0
    } else {
        alpha.clamp(0.0, 1.0)
    }
}

/// Levels of transmittance a cell keeps when a surface of opacity `alpha`
/// covers it with `r` levels left: `⌊r·(1 − α) + ½⌋`, in `[0, r]`.
///
/// Domain: `r ≤ K`, any `alpha` ([`clamp_alpha`] first: NaN is opaque). Monotone
/// non-increasing in `alpha`, non-decreasing in `r`; 0 for `α = 1`, `r` for
/// `α = 0`.
#[inline]
pub fn remaining_after(r: u32, alpha: f32) -> u32 {
    let r = r.min(LEVELS);
    let a = clamp_alpha(alpha);
    let keep = libm::floorf(r as f32 * (1.0 - a) + 0.5) as u32;
    keep.min(r)
}

/// Whether `alpha` is opaque at this quantisation: a surface of this opacity
/// leaves no transmittance in a clear cell (`α > 0.875` for `K = 4`, and NaN).
#[inline]
pub fn is_opaque(alpha: f32) -> bool {
    remaining_after(LEVELS, alpha) == 0
}

/// The weight of `gained` opacity levels (summed over cells): `gained/(32·K)`.
/// For an opaque surface `gained = K·bitCount(visible)`, and the result is
/// exactly [`mask_weight`](crate::mask::mask_weight)`(visible)` (both are
/// products of small integers and powers of two).
#[inline]
pub fn level_weight(gained: u32) -> f32 {
    gained.min(32 * LEVELS) as f32 * (1.0 / (32 * LEVELS) as f32)
}

/// The pixel's `K` nested bitmasks `M_1 ⊇ … ⊇ M_K` (§5.3), the non-binary
/// generalisation of [`VisibilityAccumulator`](crate::mask::VisibilityAccumulator).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TransparencyAccumulator {
    /// `planes[k − 1] = M_k`, the cells whose opacity level is at least `k`.
    planes: [u32; LEVELS as usize],
}

impl TransparencyAccumulator {
    /// Nothing covered: every cell at level 0.
    pub const fn new() -> Self {
        Self {
            planes: [0; LEVELS as usize],
        }
    }

    /// `M_k` for `k` in `1..=K` (`M_0` is every cell, `M_{K+1}` none).
    #[inline]
    pub fn plane(&self, k: u32) -> u32 {
        if k == 0 {
            FULL_MASK
        } else if k > LEVELS {
            0
        } else {
            self.planes[(k - 1) as usize]
        }
    }

    /// The cells at exactly level `l`: `M_l & !M_{l+1}`.
    #[inline]
    pub fn level_set(&self, l: u32) -> u32 {
        self.plane(l) & !self.plane(l + 1)
    }

    /// The opacity level of cell `bit` (0..32), in `0..=K`.
    pub fn level(&self, bit: u32) -> u32 {
        let b = 1u32 << bit.min(31);
        self.planes.iter().filter(|p| *p & b != 0).count() as u32
    }

    /// Composite a surface of opacity `alpha` over the cells of `mask`
    /// (front to back, see the module docs) and return
    /// `(visible, gained)`: the cells whose level rose, and the levels gained
    /// summed over cells (the sample weight is [`level_weight`]`(gained)`).
    ///
    /// With `alpha = 1` this is [`VisibilityAccumulator::add`](crate::mask::VisibilityAccumulator::add):
    /// `visible = mask & !M_K`, `gained = K·bitCount(visible)`. NaN `alpha` is
    /// opaque, values outside `[0, 1]` are clamped.
    pub fn add(&mut self, mask: u32, alpha: f32) -> (u32, u32) {
        let mut next = [0u32; LEVELS as usize];
        for (k, n) in next.iter_mut().enumerate() {
            *n = self.planes[k] & !mask;
        }
        let (mut visible, mut gained) = (0u32, 0u32);
        for l in 0..=LEVELS {
            let cells = self.level_set(l) & mask;
            if cells == 0 {
                continue;
            }
            let to = LEVELS - remaining_after(LEVELS - l, alpha);
            if to > l {
                visible |= cells;
                gained += (to - l) * cells.count_ones();
            }
            for n in next.iter_mut().take(to as usize) {
                *n |= cells;
            }
        }
        self.planes = next;
        (visible, gained)
    }

    /// Whether every cell is clear or opaque (level 0 or `K`, all masks
    /// equal): what only opaque surfaces leave, the single mask of §3.4.
    #[inline]
    pub fn is_binary(&self) -> bool {
        self.plane(1) == self.opaque()
    }

    /// The cells that are fully opaque, `M_K`.
    #[inline]
    pub fn opaque(&self) -> u32 {
        self.planes[(LEVELS - 1) as usize]
    }

    /// Sum of the cells' levels, `Σ l` (at most `32·K`).
    #[inline]
    pub fn total_levels(&self) -> u32 {
        self.planes.iter().map(|p| p.count_ones()).sum()
    }

    /// The background's share, the transmittance left: `1 − Σ l/(32·K)`.
    /// With opaque surfaces only, exactly
    /// [`VisibilityAccumulator::uncovered_weight`](crate::mask::VisibilityAccumulator::uncovered_weight).
    #[inline]
    pub fn uncovered_weight(&self) -> f32 {
        1.0 - level_weight(self.total_levels())
    }
}
