//! The 32-bit visibility mask of a hit group (§3.4–3.5, Fig. 6, eq. 7–8) and the
//! correlation of masks along a ray.
//!
//! # Geometry
//! The surface near a sample is modelled as a plane (Heitz and Neyret's
//! macroscopic model, Fig. 4). Let `n` be its unit normal and `d` the signed
//! distance from the point `c` on the cone axis to the plane (`d > 0` outside).
//! The cone's cross-section at `c` is a disk of radius `R_c` perpendicular to the
//! ray, spanned by the screen axes `r` (right) and `u` (up). A point
//! `p = c + R_c(x·r + y·u)` of the disk is inside the solid when
//! `n·(p − c) + d < 0`, i.e. when `x·n_x + y·n_y < −d/R_c` with the *projected*
//! normal `n_p = (n·r, n·u)`. Dividing by `|n_p|`:
//!
//! ```text
//! covered  ⇔  q · n̂_p < h,   h = −(d/R_c) / |n_p|,   q = (x, y) in the unit disk
//! ```
//!
//! The covered side is the one the projected normal points away from, at signed
//! distance `h` from the centre. This is [`MaskPlacement::Derived`], the default.
//!
//! The paper's eq. 7–8 (`a = −n_x/n_y`, `b = d(n_x²+n_y²)/n_y`) put the same
//! line at `q·n̂_p = +(d/R_c)·|n_p|`: the sign is flipped (a soft hit with `d > 0`
//! would cover *more* than half the pixel) and `|n_p|` multiplies instead of
//! divides. The authors' code (`getVisibilityMask`) fixes the sign and
//! normalises `n_p`: `q·n̂_p = −d/R_c`, exact only where the surface is seen edge
//! on (`|n_p| = 1`); towards fronto-parallel surfaces it keeps the line inside
//! the disk where the true plane already covers (or misses) all of it. Both are
//! kept as variants; the `mask_accuracy` test measures all three against the 3D
//! truth, and the SDF renderer's edge error against supersampling is the final
//! arbiter.
//!
//! # Layout (Fig. 6b)
//! A 6×6 grid without its four corners: 4 + 6 + 6 + 6 + 6 + 4 = 32 cells. Row
//! `r` is at `y = s·((2r+1)/6 − 1)` (row 0 at the bottom), column `c` at
//! `x = s·((2c+1)/6 − 1)`, with `s = √(9π/32) ≈ 0.940` ([`GRID_SCALE`]).
//! The paper spans the grid over the full `2R_c` square (`s = 1`); its 32 cells
//! then have area `32/9 ≈ 3.56` against the disk's `π`, so rim cells that are
//! mostly outside the disk count as much as inner ones. Scaling the grid so that
//! the 32 cells have exactly the disk's area cuts the rasterisation error
//! against the exact disk-area fraction from 0.59/32 to 0.46/32 (mean) and from
//! 3.74/32 to 3.14/32 (max) in the `mask_accuracy` test. (No 6-row point-sampled
//! grid can reach a max below 3/32: where a line runs along a column of six
//! centres, six cells flip at once.)
//! Bits 0–3 hold row 0 (columns 1–4), bits 4–9 row 1,
//! …, bits 22–27 row 4, bits 28–31 row 5 (columns 1–4). A cell is covered when
//! its centre is: rows are sampled at cell centres, not at the authors'
//! `y = −1 + 2i/5` (which puts the outer rows on the disk's rim, where a row's
//! chord is degenerate), and a row's crossing is rounded to the nearest cell
//! centre, not truncated, so the rasterisation is unbiased.
//!
//! The mask's orientation (which bit is where) only has to be the same for all
//! masks of one pixel: correlation and weights use `&`, `!` and popcount.

/// The WGSL mirror of this module (project_normal, visibility_mask, needs_normal, …): same names, the parameter structs of
/// [`crate::wgsl::PARAMS`]; concatenate after `PARAMS` (see [`crate::wgsl`]).
pub const WGSL: &str = include_str!("mask.wgsl");

use crate::math::Euclidean;
use glam::{Vec2, Vec3, Vec4};

/// All 32 cells covered.
pub const FULL_MASK: u32 = u32::MAX;

/// Cells per row (Fig. 6b).
const ROW_WIDTH: [u32; 6] = [4, 6, 6, 6, 6, 4];
/// First bit of each row.
const ROW_SHIFT: [u32; 6] = [0, 4, 10, 16, 22, 28];
/// Scale of the cell grid: `√(9π/32)`, so the 32 cells of side `2s/6` have the
/// unit disk's area `π`.
pub const GRID_SCALE: f32 = 0.939_985_6;
/// Row centres `y = s·((2r+1)/6 − 1)`.
const ROW_Y: [f32; 6] = [
    -5.0 / 6.0 * GRID_SCALE,
    -0.5 * GRID_SCALE,
    -1.0 / 6.0 * GRID_SCALE,
    1.0 / 6.0 * GRID_SCALE,
    0.5 * GRID_SCALE,
    5.0 / 6.0 * GRID_SCALE,
];

/// Where the mask's half-plane boundary lies.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MaskPlacement {
    /// Derived from the 3D plane: `q·n̂_p < −(d/R_c)/|n_p|`. The default, because
    /// it is the cross-section of the plane the mask is meant to model (see the
    /// module docs); it is also the only placement whose empty/full limits are
    /// right for fronto-parallel surfaces.
    Derived = 0,
    /// The authors' code: `q·n̂_p < −d/R_c` with `n_p` normalised.
    AuthorsCode = 1,
    /// The paper's eq. 7–8 taken literally: `q·n̂_p < +(d/R_c)·|n_p|`.
    PaperEq8 = 2,
}

impl MaskPlacement {
    /// Decode a `u32` (as stored in GPU parameter blocks). Unknown codes read as
    /// [`MaskPlacement::Derived`].
    pub const fn from_u32(v: u32) -> Self {
        match v {
            1 => MaskPlacement::AuthorsCode,
            2 => MaskPlacement::PaperEq8,
            _ => MaskPlacement::Derived,
        }
    }
}

/// Project a surface normal onto the cone's cross-section: `n_p = (n̂·r, n̂·u)`
/// with `n̂ = n/|n|`.
///
/// Domain: any finite non-zero `normal`, however long or short; `right`, `up`
/// orthonormal and perpendicular to the ray. The 3D normal is normalised first
/// (after scaling by its largest component, so no square overflows), so
/// `|n_p| ≤ 1` up to rounding.
/// A zero, NaN or infinite normal returns `(0, 0)`, which [`visibility_mask`]
/// treats as a fronto-parallel surface.
#[inline]
pub fn project_normal(normal: Vec3, right: Vec3, up: Vec3) -> Vec2 {
    // Scale by the largest component first: squaring 1e20 or 1e-23 directly
    // would overflow or underflow f32.
    let m = normal.abs().max_element();
    if !(m > 0.0) || !m.is_finite() {
        return Vec2::ZERO;
    }
    let n = normal / m;
    let n = n.unit();
    let p = Vec2::new(n.dot(right), n.dot(up));
    if p.is_finite() {
        p
    } else {
        Vec2::ZERO
    }
}

/// `d/R_c` from a cone occlusion: `1 − 2ω` (inverse of eq. 5).
#[inline]
pub fn occlusion_to_distance(omega: f32) -> f32 {
    1.0 - 2.0 * omega
}

/// The covered half-plane `{q : q·dir < h}` in the unit disk, for `placement`.
///
/// Returns `None` when the projected normal is `(0, 0)` or not finite (the
/// surface faces the ray: no direction exists). `dir` is a unit vector, `h` is
/// clamped to `[−2, 2]` (beyond `±√2` the whole grid lies on one side).
#[inline]
pub fn half_plane(
    occlusion: f32,
    projected_normal: Vec2,
    placement: MaskPlacement,
) -> Option<(Vec2, f32)> {
    let len = projected_normal.norm();
    if !(len > 0.0) || !len.is_finite() {
        return None;
    }
    let dir = projected_normal / len;
    let delta = occlusion_to_distance(occlusion);
    let h = match placement {
        MaskPlacement::Derived => -delta / len.min(1.0),
        MaskPlacement::AuthorsCode => -delta,
        MaskPlacement::PaperEq8 => delta * len.min(1.0),
    };
    let h = if !h.is_nan() {
        h.clamp(-2.0, 2.0)
    } else {
        -2.0
    };
    Some((dir, h))
}

/// Cell centres in units of `s/3`, in bit order: `(c − 2.5, r − 2.5)` for the
/// cell of column `c`, row `r` (exact halves). Built from [`ROW_WIDTH`] and
/// [`ROW_SHIFT`].
const CELL_XY: ([f32; 32], [f32; 32]) = {
    let (mut xs, mut ys) = ([0.0f32; 32], [0.0f32; 32]);
    let mut r = 0;
    while r < 6 {
        let first = if ROW_WIDTH[r as usize] == 4 { 1 } else { 0 };
        let mut i = 0;
        while i < ROW_WIDTH[r as usize] {
            let bit = (ROW_SHIFT[r as usize] + i) as usize;
            xs[bit] = (first + i) as f32 - 2.5;
            ys[bit] = r as f32 - 2.5;
            i += 1;
        }
        r += 1;
    }
    (xs, ys)
};

/// Rasterise the half-plane `{q : q·dir < h}` (unit `dir`) into the 32-bit mask.
///
/// A cell is set when its centre is strictly inside. For `|dir.x| < 10⁻⁶` (a
/// horizontal boundary) `dir.x` is taken as 0, so rows are all-or-nothing,
/// which is the clamp of near-zero normal components that §3.5 asks for.
///
/// # Arithmetic
/// With centres `(x_c, y_r) = (s/3)·(c − 2.5, r − 2.5)`, cell `(r, c)` is
/// covered when `(c − 2.5)·dx + (r − 2.5)·dy < (3/s)·h`: one multiply-add and
/// one compare per cell, no division and no rounding to integers, so the 32
/// cells go four at a time through SIMD lanes (a compare's lane mask is four
/// bits of the result). A NaN anywhere fails every compare: the mask is empty.
/// Infinite inputs give the compare's IEEE result. The test is the `f64`
/// reference's up to the rounding of `(3/s)·h` and of the two products, i.e.
/// only centres within rounding of the line can differ (bounded in the
/// `f64_reference` test).
#[inline]
pub fn half_plane_mask(dir: Vec2, h: f32) -> u32 {
    let dx = if libm::fabsf(dir.x) < 1e-6 {
        0.0
    } else {
        dir.x
    };
    let dx4 = Vec4::splat(dx);
    let dy4 = Vec4::splat(dir.y);
    let h4 = Vec4::splat((3.0 / GRID_SCALE) * h);
    let (xs, ys) = (&CELL_XY.0, &CELL_XY.1);
    let mut mask = 0u32;
    let mut g = 0;
    while g < 8 {
        let x = Vec4::from_slice(&xs[4 * g..4 * g + 4]);
        let y = Vec4::from_slice(&ys[4 * g..4 * g + 4]);
        let inside = (x * dx4 + y * dy4).cmplt(h4);
        mask |= inside.bitmask() << (4 * g);
        g += 1;
    }
    mask
}

/// The visibility mask of a hit group (§3.4–3.5, eq. 7–8).
///
/// `occlusion` is the group's **maximum** cone occlusion `ω_max` (Algorithm 1,
/// lines 3 and 12; the authors' code does the same), `projected_normal` the
/// [projected](project_normal) unit normal at the group's sample point. The
/// distance at the backtraced sample point must not be used instead: eq. 9–10
/// make `d(t_s) ≥ R_s`, so every mask would come out empty.
///
/// Domain: `ω` in `[−1, 2]` (what [`cone_occlusion`](crate::cone::cone_occlusion)
/// returns), `|n_p| ≤ 1`. Outside it:
/// - a fronto-parallel surface (`n_p = (0,0)`, including from a NaN or zero
///   normal) gives [`FULL_MASK`] when `d ≤ 0` (`ω ≥ 0.5`) and 0 otherwise, the
///   limit of the derived placement;
/// - a NaN `ω` gives 0 (no evidence of coverage);
/// - `|n_p| > 1` is treated as 1.
///
/// Extremes, for every placement: the farthest cell centres lie
/// `s·√34/6 ≈ 0.9135` from the middle, so the mask is empty whenever
/// `h ≤ −0.9135` and full whenever `h > 0.9135`. With [`MaskPlacement::Derived`]
/// (`|h| ≥ |d/R_c|`) that means, for **every** normal: `ω ≤ 0.0432` gives an
/// empty mask and `ω > 0.9568` a full one, so a full-occlusion sample
/// (`ω > 1 − ε`) is always fully covered. Both limits are property-tested.
#[inline]
pub fn visibility_mask(occlusion: f32, projected_normal: Vec2, placement: MaskPlacement) -> u32 {
    if occlusion.is_nan() {
        return 0;
    }
    match half_plane(occlusion, projected_normal, placement) {
        Some((dir, h)) => half_plane_mask(dir, h),
        None => {
            if occlusion >= 0.5 {
                FULL_MASK
            } else {
                0
            }
        }
    }
}

/// Distance of the farthest cell centre from the middle of the grid,
/// `s·√34/6`: beyond it a half-plane covers all cells or none.
pub const FARTHEST_CENTRE: f32 = GRID_SCALE * 0.971_825_3;

/// Whether [`visibility_mask`] depends on the projected normal at this
/// occlusion. For [`MaskPlacement::Derived`] and [`MaskPlacement::AuthorsCode`]
/// it does not when `|d/R_c| ≥` [`FARTHEST_CENTRE`] (the mask is then empty or
/// full for every normal), which lets a renderer skip a normal evaluation for
/// most samples (every full-occlusion one). Always `true` for
/// [`MaskPlacement::PaperEq8`]; `false` for NaN.
#[inline]
pub fn needs_normal(occlusion: f32, placement: MaskPlacement) -> bool {
    if occlusion.is_nan() {
        return false;
    }
    let delta = occlusion_to_distance(occlusion);
    match placement {
        MaskPlacement::PaperEq8 => true,
        _ => delta.abs() < FARTHEST_CENTRE,
    }
}

/// Centre of the cell held by `bit` (0..32), in the unit square `[−1, 1]²`.
/// For tests and visualisation.
pub fn cell_centre(bit: u32) -> Vec2 {
    let bit = bit.min(31);
    let mut r = 5;
    while r > 0 && ROW_SHIFT[r] > bit {
        r -= 1;
    }
    let col = bit - ROW_SHIFT[r] + if ROW_WIDTH[r] == 4 { 1 } else { 0 };
    Vec2::new(((2 * col + 1) as f32 / 6.0 - 1.0) * GRID_SCALE, ROW_Y[r])
}

/// Sample weight of a mask: `bitCount(m)/32` (§3.4).
#[inline]
pub fn mask_weight(mask: u32) -> f32 {
    mask.count_ones() as f32 * (1.0 / 32.0)
}

/// The global visibility mask `M` of one pixel and its correlation rule (§3.4,
/// Algorithm 1 lines 17–22): each new mask loses the bits already covered,
/// `m_i ← m_i & !M`, then `M ← M | m_i`.
///
/// The masks it returns are pairwise disjoint and `M` only grows, so the visible
/// weights of one pixel sum to at most 1.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VisibilityAccumulator {
    covered: u32,
}

impl VisibilityAccumulator {
    /// `M = 0`: nothing covered yet.
    pub const fn new() -> Self {
        Self { covered: 0 }
    }

    /// Correlate `mask` with what is already covered, record it, and return the
    /// newly visible bits `m_i & !M`.
    #[inline]
    pub fn add(&mut self, mask: u32) -> u32 {
        let visible = mask & !self.covered;
        self.covered |= visible;
        visible
    }

    /// The global mask `M`.
    #[inline]
    pub const fn covered(&self) -> u32 {
        self.covered
    }

    /// Number of covered cells, `bitCount(M)`.
    #[inline]
    pub const fn covered_bits(&self) -> u32 {
        self.covered.count_ones()
    }

    /// The background's share, `1 − bitCount(M)/32` (what the authors' code gives
    /// the sky when the trace ends without full occlusion).
    #[inline]
    pub fn uncovered_weight(&self) -> f32 {
        1.0 - mask_weight(self.covered)
    }
}
