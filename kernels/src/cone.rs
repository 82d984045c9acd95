//! Cones of cone-traced supersampling (Chubarau et al., §3.1, §3.2, §3.6).
//!
//! The cone of a pixel, its radius at depth `t`, the cone occlusion `ω` of an SDF
//! value, the minimum step, and the backtracing of hit positions.

/// The WGSL mirror of this module (cone_radius, cone_occlusion, advance, backtrace_cone_entry, …): same names, the parameter structs of
/// [`crate::wgsl::PARAMS`]; concatenate after `PARAMS` (see [`crate::wgsl`]).
pub const WGSL: &str = include_str!("cone.wgsl");

/// Paper's ε for the occlusion thresholds (the authors use 0.01, `render_defs.cginc`).
pub const OCCLUSION_EPS: f32 = 0.01;

/// Lower saturation bound of [`cone_occlusion`]: "nothing in the cone".
pub const OCCLUSION_MIN: f32 = -1.0;
/// Upper saturation bound of [`cone_occlusion`]: "deep inside a surface".
pub const OCCLUSION_MAX: f32 = 2.0;

/// How wide a pixel's cone is relative to the pixel square (§3.1).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PixelFootprint {
    /// The cone's base passes through the pixel's four corners (§3.1: "its circular
    /// base passes through the four corners of a given pixel to ensure full pixel
    /// coverage"). Radius = half the pixel diagonal. The default.
    Circumscribed = 0,
    /// The authors' code (`PIXEL_SIZE_MULT_BALANCED`): radius = pixel size ·
    /// `2/(2+√2) ≈ 0.586`, "half way between inscribed and circumscribed", about
    /// 17 % narrower than eq. 3 (`2·0.586/(I_y·F)` against `√2/(I_y·F)`). Kept for
    /// comparison.
    Balanced = 1,
    /// The cone's base is inscribed in the pixel: radius = half the pixel size.
    Inscribed = 2,
}

impl PixelFootprint {
    /// Cone radius at the image plane in units of the pixel's side.
    pub fn radius_in_pixels(self) -> f32 {
        match self {
            PixelFootprint::Circumscribed => core::f32::consts::FRAC_1_SQRT_2,
            PixelFootprint::Balanced => 2.0 / (2.0 + core::f32::consts::SQRT_2),
            PixelFootprint::Inscribed => 0.5,
        }
    }
}

/// `tan θ` of a pixel's cone (eq. 3), from the vertical field of view and resolution.
///
/// Eq. 3 reads `tan θ = √2 / (F·I_y)` "assuming that the vertical number of pixels
/// corresponds to unit distance", which is off by a factor of 2 against the
/// authors' own camera (a screen 2 units tall, `p = (2·pixel − res)/res.y`). We
/// resolve it from §3.1's geometry instead: a pixel is `h = 2·tan(fov_y/2)/I_y`
/// tall on the plane at unit distance, and the circumscribed cone's base radius is
/// half its diagonal, so `tan θ = coverage · √2 · tan(fov_y/2) / I_y`, which equals
/// eq. 3 with `F = 1/tan(fov_y/2)` on the 2-unit screen.
///
/// `coverage` multiplies the cone (§5.1 "cone coverage"; 1 = one pixel).
///
/// Domain: `fov_y` in `(0, π)`, `height ≥ 1`, `coverage > 0`, all finite.
/// Outside it returns 0: an infinitely thin cone, for which every CTSS kernel
/// degrades to plain sphere tracing.
pub fn cone_tan_theta(fov_y: f32, height: u32, coverage: f32, footprint: PixelFootprint) -> f32 {
    let valid = fov_y > 0.0
        && fov_y < core::f32::consts::PI
        && height > 0
        && coverage > 0.0
        && coverage.is_finite();
    if !valid {
        return 0.0;
    }
    let pixel = 2.0 * libm::tanf(0.5 * fov_y) / height as f32;
    let t = coverage * footprint.radius_in_pixels() * pixel;
    if t.is_finite() {
        t
    } else {
        0.0
    }
}

/// Cone radius at depth `t` (eq. 4): `R_c = t · tan θ`.
///
/// Domain: `t ≥ 0`, `tan θ ≥ 0`. Negative or NaN inputs give 0 (a point); `+∞`
/// propagates (`∞ · tan θ`, or 0 when `tan θ = 0`).
#[inline]
pub fn cone_radius(t: f32, tan_theta: f32) -> f32 {
    if t > 0.0 && tan_theta > 0.0 {
        t * tan_theta
    } else {
        0.0
    }
}

/// Cone occlusion `ω = (1 − d/R_c)/2` (eq. 5).
///
/// `ω < 0`: the cone misses; `ω > 0`: a soft hit; `ω > 0.5`: a hard hit (the ray
/// itself is inside); `ω > 1`: full occlusion (the whole cross-section is inside).
///
/// Domain: `d` finite, `R_c > 0` finite. Saturation policy outside it, chosen so
/// that no NaN and no ∞ ever leaves and every threshold decision (all in `(−1, 1)`)
/// is the one the limit would make:
/// - the result is clamped to `[OCCLUSION_MIN, OCCLUSION_MAX] = [−1, 2]`;
/// - `R_c → 0` (including `R_c = 0`, negative or NaN): the limit, −1 for `d > 0`,
///   2 for `d < 0`, and 0.5 for `d = 0` (a thin ray exactly on the surface);
/// - `d = +∞` → −1, `d = −∞` → 2, `d = NaN` → −1 (no evidence of a surface; the
///   [stepper](crate::ctss::ConeStepper) stops on NaN separately);
/// - `R_c = +∞` with finite `d` → 0.5.
///
/// Monotone non-increasing in `d` for any fixed `R_c`.
#[inline]
pub fn cone_occlusion(d: f32, rc: f32) -> f32 {
    if d.is_nan() {
        return OCCLUSION_MIN;
    }
    let thin = !(rc > 0.0);
    let omega = if thin || d.is_infinite() {
        if d > 0.0 {
            OCCLUSION_MIN
        } else if d < 0.0 {
            OCCLUSION_MAX
        } else {
            0.5
        }
    } else if rc.is_infinite() {
        0.5
    } else {
        (1.0 - d / rc) * 0.5
    };
    omega.clamp(OCCLUSION_MIN, OCCLUSION_MAX)
}

/// The three occlusion thresholds of §3.2, each ε below its paper value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OcclusionThresholds {
    /// Soft hit: `ω > 0 − ε`.
    pub soft: f32,
    /// Hard hit: `ω > 0.5 − ε` (plain sphere tracing's termination, "adaptive
    /// cone-based threshold", §4).
    pub hard: f32,
    /// Full occlusion: `ω > 1 − ε`.
    pub full: f32,
}

impl OcclusionThresholds {
    /// Thresholds with a given ε.
    pub const fn with_eps(eps: f32) -> Self {
        Self {
            soft: 0.0 - eps,
            hard: 0.5 - eps,
            full: 1.0 - eps,
        }
    }
    /// The authors' ε = 0.01.
    pub const PAPER: Self = Self::with_eps(OCCLUSION_EPS);
}

impl Default for OcclusionThresholds {
    fn default() -> Self {
        Self::PAPER
    }
}

/// Minimum step `s_min = α·R_c` (§3.1; the paper's α = 0.5, "at most R_c").
///
/// Domain: `α` in `(0, 1]`, `R_c ≥ 0`. NaN or negative products give 0.
#[inline]
pub fn min_step(alpha: f32, rc: f32) -> f32 {
    let s = alpha * rc;
    if s > 0.0 {
        s
    } else {
        0.0
    }
}

/// The CTSS step rule `t ← t + max(d, α·R_c)` (Algorithm 1, line 26), made to
/// always progress.
///
/// Where `α·R_c < ulp(t)/2` (an extreme telephoto at `t = 10⁷`, say) the sum
/// rounds back to `t`; the step is then promoted to the next representable
/// float, so the trace advances by at least one ulp per iteration and every
/// trace ends within its step budget.
///
/// Domain: finite `t ≥ 0`. A NaN `d` steps by `α·R_c` (then by one ulp); the
/// result is `> t` for every finite `t`, and `+∞` only when the step is.
#[inline]
pub fn advance(t: f32, d: f32, alpha: f32, rc: f32) -> f32 {
    let step = d.max(min_step(alpha, rc)); // f32::max ignores a NaN `d`
    let next = t + step;
    if next > t {
        next
    } else if t.is_finite() {
        t.next_up()
    } else {
        // t = +∞ (already done) or NaN: nothing further to trace.
        f32::INFINITY
    }
}

/// Backtraced entry (or exit) of a cone intersection: `t_s = t_i / (1 + tan θ)`
/// (eq. 9–10), the depth whose *safe* cone of radius `R_s = t_i − t_s = t_s·tan θ`
/// does not reach the surface the cone at `t_i` touched.
///
/// The division form is exact enough to be strict: whenever `t_i·tan θ > ulp(t_i)`,
/// `fl(1 + tan θ) ≥ 1 + 2⁻²³` and the quotient lands at least one ulp below `t_i`.
/// (The authors write `t·(1 − tanθ/(1 + tanθ))`, the same value.)
///
/// Domain: `t_i ≥ 0`, `tan θ ≥ 0`, finite. Returns a value in `[0, t_i]`; a NaN or
/// negative `tan θ` returns `t_i`, a NaN `t_i` returns 0.
#[inline]
pub fn backtrace_cone_entry(t_i: f32, tan_theta: f32) -> f32 {
    if !(t_i > 0.0) {
        return if !t_i.is_nan() { t_i.max(0.0) } else { 0.0 };
    }
    if !(tan_theta > 0.0) {
        return t_i;
    }
    let ts = t_i / (1.0 + tan_theta);
    ts.min(t_i)
}

/// Backtraced first hard hit: `t_s = t_{i−1} + d_{i−1}` (§3.6), the last depth that
/// plain sphere tracing proved safe before the minimum step overshot.
///
/// Algorithm 1 (line 14) samples the hard hit at `t` itself; we follow §3.6, as
/// the authors' code does (`t_s = tP + hP.x`), because `t` may lie inside the
/// surface after a minimum step and would shade the interior.
///
/// Domain: `t_prev ≤ t_i`, `d_prev ≥ 0`. The result is clamped to
/// `[t_prev, t_i]` (a non-Eikonal or negative `d_prev` cannot push it past the
/// hit or behind the previous step); a NaN `d_prev` returns `t_prev`.
#[inline]
pub fn backtrace_hard_hit(t_prev: f32, d_prev: f32, t_i: f32) -> f32 {
    let ts = t_prev + d_prev;
    if ts.is_nan() {
        return t_prev;
    }
    ts.max(t_prev).min(t_i)
}
