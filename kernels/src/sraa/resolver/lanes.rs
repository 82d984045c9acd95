//! The product-form weights (§3.1, eq. 1 times the spatial term) in lanes:
//! one (subsample, neighbour) pair per lane, in branch-free loops that
//! vectorise 4, 8 or 16 wide, to the bits of the scalar
//! [`reconstruction_weight`](crate::sraa::reconstruction_weight) (with
//! libm's `expf` written out lane by lane).

use glam::Vec4;

use super::super::{DepthMetric, Geometry, SraaParams, NORMAL_COS_SNAP};

/// The four subsamples' geometry, one subsample per lane.
#[derive(Clone, Copy, Debug)]
pub struct GeometryLanes {
    nx: Vec4,
    ny: Vec4,
    nz: Vec4,
    depth: Vec4,
}

impl GeometryLanes {
    /// Lanes from four geometries.
    pub fn new(g: &[Geometry; 4]) -> Self {
        Self {
            nx: Vec4::new(g[0].normal.x, g[1].normal.x, g[2].normal.x, g[3].normal.x),
            ny: Vec4::new(g[0].normal.y, g[1].normal.y, g[2].normal.y, g[3].normal.y),
            nz: Vec4::new(g[0].normal.z, g[1].normal.z, g[2].normal.z, g[3].normal.z),
            depth: Vec4::new(g[0].depth, g[1].depth, g[2].depth, g[3].depth),
        }
    }
}

/// [`reconstruction_weight`](crate::sraa::reconstruction_weight) of the product form (§3.1, eq. 1 times the
/// spatial term) for four targets `gi` (lanes) against one neighbour `gj`,
/// with `spatial` the lanes' `d²/σs²` (0 for none): [`weights_product_wide`]
/// in four lanes, so each lane equals the scalar weight bit for bit.
/// Domain and out-of-domain behaviour are the scalar function's.
#[inline]
pub fn weights_product_lanes(
    p: &SraaParams,
    gi: &GeometryLanes,
    gj: &Geometry,
    spatial: Vec4,
) -> Vec4 {
    let gi = GeometryWide {
        nx: gi.nx.to_array(),
        ny: gi.ny.to_array(),
        nz: gi.nz.to_array(),
        depth: gi.depth.to_array(),
    };
    let gj = GeometryWide::from_fn(|_| *gj);
    Vec4::from_array(weights_product_wide(p, &gi, &gj, &spatial.to_array()))
}

// libm's expf (FreeBSD's e_expf.c), constants and thresholds, by their
// bits: a shortest decimal can name the neighbouring f32 (1.442_695_1 is
// 0x3fb8aa3c, one ulp above libm's 1/ln 2).
const LN2_HI: f32 = f32::from_bits(0x3f31_7200); // 6.9314575195e-01
const LN2_LO: f32 = f32::from_bits(0x35bf_be8e); // 1.4286067653e-06
const INV_LN2: f32 = f32::from_bits(0x3fb8_aa3b); // 1.4426950216e+00
const P1: f32 = f32::from_bits(0x3e2a_aa8f); // 0xaaaa8f.0p-26
const P2: f32 = f32::from_bits(0xbb35_5215); // -0xb55215.0p-32
/// `1.5·2²³`: `(t + ROUND_MAGIC) − ROUND_MAGIC` is `t` rounded to the
/// nearest integer (ties to even), exactly, for `|t| < 2²²`.
const ROUND_MAGIC: f32 = 12_582_912.0;

/// `exp(−s)` of `gaussian_sum` in four lanes: exactly 1 for `s = 0`,
/// 0 for `s ≥ 105`, `+∞` or NaN, and `libm::expf(−s)` in between:
/// [`gaussian_sum_wide`] in four lanes.
///
/// Error against libm's `expf`: none (see [`gaussian_sum_wide`]). Its
/// error against the true `e^−s` is libm's, under 1 ulp. The WGSL twin
/// (`subcone_gaussian_sum`) keeps the GPU's `exp`, whose tolerance in the
/// kernel conformance table is unchanged.
///
/// Domain: `s ≥ 0` or NaN, as `gaussian_sum` is called (a sum of squares).
/// A negative `s` is outside it: its lane returns `1 − s`, not `expf(−s)`
/// (never NaN, never a panic).
#[inline]
pub fn gaussian_sum_lanes(s: Vec4) -> Vec4 {
    Vec4::from_array(gaussian_sum_wide(&s.to_array()))
}

/// Lanes of a full chunk of [`weights_product_wide`] in
/// [`Resolver::weights_product`](crate::sraa::Resolver::weights_product): 16 f32 lanes, one AVX-512 register (two
/// AVX2 registers, four SSE ones). A pixel's 36 (slot, subsample) pairs are
/// two such chunks and one of 4 lanes.
pub const WIDE_LANES: usize = 16;

/// `N` geometries in lanes, one array per component (structure of arrays),
/// for [`weights_product_wide`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeometryWide<const N: usize> {
    /// The normals' x components.
    pub nx: [f32; N],
    /// The normals' y components.
    pub ny: [f32; N],
    /// The normals' z components.
    pub nz: [f32; N],
    /// The depths.
    pub depth: [f32; N],
}

impl<const N: usize> GeometryWide<N> {
    /// Lane `l` is `f(l)`.
    #[inline(always)]
    pub fn from_fn(mut f: impl FnMut(usize) -> Geometry) -> Self {
        let mut g = Self {
            nx: [0.0; N],
            ny: [0.0; N],
            nz: [0.0; N],
            depth: [0.0; N],
        };
        for l in 0..N {
            let s = f(l);
            g.nx[l] = s.normal.x;
            g.ny[l] = s.normal.y;
            g.nz[l] = s.normal.z;
            g.depth[l] = s.depth;
        }
        g
    }
}

/// `|x|`, by clearing the sign bit (no call: it stays in the vector loop).
#[inline(always)]
fn abs_lane(x: f32) -> f32 {
    f32::from_bits(x.to_bits() & 0x7fff_ffff)
}

/// [`super::saturate`], as the same comparisons written as selects.
#[inline(always)]
fn saturate_lane(x: f32) -> f32 {
    let below_one = if x < 1.0 { x } else { 1.0 };
    if x > 0.0 {
        below_one
    } else {
        0.0
    }
}

/// `gaussian_sum` for one lane, branch-free: every branch of libm's `expf`
/// is computed and the lane's result selected, so that a loop of it over an
/// array vectorises at the width of the target (see [`gaussian_sum_wide`]).
/// The same f32 operations in the same order as libm's `expf` for
/// `x = −s ≤ 0`; only `trunc` and `scalbnf` are written differently, to the
/// same values.
#[inline(always)]
fn gaussian_sum_lane(s: f32) -> f32 {
    // s ≥ 103.972084 (libm's underflow: x ≤ −103.972084 gives 0), ∞ and
    // NaN give 0. Those lanes are computed on s = 0 instead and selected
    // out at the end: their garbage would otherwise hold subnormals (and
    // NaNs), which cost microcode assists on some cores even when unused.
    let live = s < f32::from_bits(0x42cf_f1b5);
    let s = if live { s } else { 0.0 };
    let x = -s;
    // k = (int)(x/ln 2 − 0.5) where |x| > 1.5 ln 2: there (−104 < x) the
    // argument t lies in (−151, −1.5). Adding and subtracting 1.5·2²³
    // rounds |t| < 2²² to the nearest integer, exactly; a negative t
    // rounded down is then moved up by 1: truncation, in float operations
    // only (a saturating f32 → i32 conversion does not vectorise).
    // Elsewhere (|x| ≤ 1.5 ln 2, negative s) the value is not used.
    let t = INV_LN2 * x + -0.5;
    let nearest = (t + ROUND_MAGIC) - ROUND_MAGIC;
    let k_big = if nearest < t { nearest + 1.0 } else { nearest };
    let k = if s > f32::from_bits(0x3f85_1592) {
        k_big
    } else {
        -1.0
    };
    let k = if s > f32::from_bits(0x3eb1_7218) {
        k
    } else {
        0.0
    };
    let hi = x - k * LN2_HI;
    let lo = k * LN2_LO;
    let r = hi - lo;
    let rr = r * r;
    let c = r - rr * (P1 + rr * P2);
    let y = 1.0 + (r * c / (2.0 - c) - lo + hi);
    // scalbnf(y, k): pre-scale by 2⁻¹⁰² below k = −126 (exact).
    let deep = k < -126.0;
    let y = if deep {
        y * f32::from_bits(0x0c80_0000)
    } else {
        y
    };
    let k = if deep { k + 102.0 } else { k };
    // 2^k from the bits of k + 127 + 2²³ (exact: an integer below 2²⁴, so
    // its low mantissa bits are k + 127, in [1, 127] here), moved into the
    // exponent field: a bit cast, a subtraction and a shift per lane, no
    // float-to-int conversion. Wrapping, so that no lane can panic.
    let m = (k + (127.0 + 8_388_608.0)).to_bits();
    let y = y * f32::from_bits(m.wrapping_sub(0x4b00_0000) << 23);
    // |x| ≤ 2⁻¹⁴ (and s = 0): 1 + x.
    let y = if s > f32::from_bits(0x3900_0000) {
        y
    } else {
        1.0 + x
    };
    // s ≥ 103.972084, ∞ and NaN: 0 (see above).
    if live {
        y
    } else {
        0.0
    }
}

/// `exp(−s)` of `gaussian_sum` in `N` lanes: lane `l` is
/// [`gaussian_sum_lanes`]' result for `s[l]`, bit for bit, so exactly 1 for
/// `s = 0`, 0 for `s ≥ 105`, `+∞` or NaN, and `libm::expf(−s)` in between
/// (the exponential of eq. 1's product form, §3.1, eq. 1).
///
/// One straight-line, branch-free loop over the lanes (every branch of
/// libm's `expf` computed and selected per lane, no call inside), so that
/// inside code compiled for AVX2 or AVX-512 (`#[target_feature]`, with this
/// function inlined: it is `#[inline(always)]`) LLVM vectorises it 8 or 16
/// lanes wide. It never contracts `a·b + c` into an FMA (Rust does not), so
/// the results are the same bits on every target.
///
/// Error against libm's `expf`: none. This is libm 0.2's `expf` (FreeBSD's
/// `e_expf.c`: reduction by `k·ln 2` in two parts, a degree-2 rational
/// approximation, `scalbnf`) with its branches turned into lane selects; for
/// `x = −s ≤ 0` every branch is the same f32 operations in the same order,
/// `k = (int)(x/ln 2 − 0.5)` is truncated exactly (by rounding with
/// `1.5·2²³`, on the range `(−152, −1.5)` where it is used), and `scalbnf(y, k)` is
/// `y·2⁻¹⁰²·2^(k+102)` below `k = −126` and `y·2^k` above, as libm computes
/// it, so each lane equals `libm::expf(−s)` bit for bit
/// (`kernels/tests/lanes.rs` compares the f32s of `[0, ∞]` at a stride and
/// densely around every branch threshold and the subnormal range, and all
/// of them with `--ignored`). Its error against the true `e^−s` is libm's,
/// under 1 ulp.
///
/// Domain: `s ≥ 0` or NaN (a sum of squares). A negative `s` is outside it:
/// its lane returns `1 − s` (`−0` gives 1), not `expf(−s)`; never NaN,
/// never a panic.
#[inline(always)]
pub fn gaussian_sum_wide<const N: usize>(s: &[f32; N]) -> [f32; N] {
    let mut out = [0.0; N];
    for (o, &s) in out.iter_mut().zip(s) {
        *o = gaussian_sum_lane(s);
    }
    out
}

/// [`reconstruction_weight`](crate::sraa::reconstruction_weight) of the product form (§3.1, eq. 1 times the
/// spatial term) for one lane: target `(zi, ni)` against neighbour
/// `(zj, nj)`, `spatial` the pair's `d²/σs²`. The same f32 operations in the
/// same order as the scalar function and as [`weights_product_lanes`],
/// every branch a select.
#[inline(always)]
fn weight_product_lane<const RELATIVE: bool>(
    sigma_z: f32,
    sigma_n: f32,
    (zi, nix, niy, niz): (f32, f32, f32, f32),
    (zj, njx, njy, njz): (f32, f32, f32, f32),
    spatial: f32,
) -> f32 {
    // depth_difference(zi, zj, metric)
    let diff = abs_lane(zj - zi);
    let r = if RELATIVE {
        diff / (0.5 * abs_lane(zi) + 0.5 * abs_lane(zj))
    } else {
        diff
    };
    let r = if r.is_nan() { f32::INFINITY } else { r };
    let dz = if zi == zj { 0.0 } else { r };
    // The normal term: nj·ni, saturated and snapped.
    let cos = saturate_lane(njx * nix + njy * niy + njz * niz);
    let dn = if cos >= 1.0 - NORMAL_COS_SNAP {
        0.0
    } else {
        1.0 - cos
    };
    let a = sigma_z * dz;
    let b = sigma_n * dn;
    let w = saturate_lane(gaussian_sum_lane(a * a + b * b + spatial));
    let nan_normal = nix.is_nan() | niy.is_nan() | niz.is_nan();
    let nan_normal = nan_normal | njx.is_nan() | njy.is_nan() | njz.is_nan();
    let w = if nan_normal { 0.0 } else { w };
    // Two misses weigh 1 whatever their normals.
    if (zi == f32::INFINITY) & (zj == f32::INFINITY) {
        1.0
    } else {
        w
    }
}

/// [`reconstruction_weight`](crate::sraa::reconstruction_weight) of the product form (§3.1, eq. 1 times the
/// spatial term `exp(−d²/σs²)`) in `N` lanes: lane `l` weighs neighbour
/// `gj` lane `l` for target `gi` lane `l`, with `spatial[l]` the pair's
/// `d²/σs²` (0 for none, as [`reconstruction_weight`](crate::sraa::reconstruction_weight) computes it from
/// `distance2` and `σs`). `p`'s form is not read: this is the product form
/// whatever [`SraaParams::form`] says.
///
/// Each lane is the scalar weight bit for bit: the same f32 operations in
/// the same order (depth difference by the metric, NaN → `+∞`, equal depths
/// → 0; the cosine saturated and snapped by [`NORMAL_COS_SNAP`]; the sigma
/// products; one exponential of the sum, [`gaussian_sum_wide`]; saturated;
/// 0 for a NaN normal on either side; 1 for two misses), each branch a
/// select, so that the loop vectorises at the target's width like
/// [`gaussian_sum_wide`] (it is `#[inline(always)]`).
///
/// Domain and out-of-domain behaviour are [`reconstruction_weight`](crate::sraa::reconstruction_weight)'s, lane
/// by lane: unit normals, depths in `[0, ∞]`, finite non-negative
/// parameters, `spatial ≥ 0` (NaN or `+∞` gives 0). A NaN anywhere gives 0
/// (two misses excepted: 1); never a panic.
#[inline(always)]
pub fn weights_product_wide<const N: usize>(
    p: &SraaParams,
    gi: &GeometryWide<N>,
    gj: &GeometryWide<N>,
    spatial: &[f32; N],
) -> [f32; N] {
    // The metric chosen outside the loop: one branch-free loop each.
    match p.depth_metric() {
        DepthMetric::Absolute => weights_product_loop::<N, false>(p, gi, gj, spatial),
        DepthMetric::Relative => weights_product_loop::<N, true>(p, gi, gj, spatial),
    }
}

/// The lane loop of [`weights_product_wide`] for one depth metric.
// Lane `l` indexes the five input arrays and the output alike.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn weights_product_loop<const N: usize, const RELATIVE: bool>(
    p: &SraaParams,
    gi: &GeometryWide<N>,
    gj: &GeometryWide<N>,
    spatial: &[f32; N],
) -> [f32; N] {
    let (sigma_z, sigma_n) = (p.sigma_z, p.sigma_n);
    let mut out = [0.0; N];
    for l in 0..N {
        out[l] = weight_product_lane::<RELATIVE>(
            sigma_z,
            sigma_n,
            (gi.depth[l], gi.nx[l], gi.ny[l], gi.nz[l]),
            (gj.depth[l], gj.nx[l], gj.ny[l], gj.nz[l]),
            spatial[l],
        );
    }
    out
}
