//! The kernels' tolerances: how far a port of a kernel (the WGSL twins in the
//! kernel conformance suite, `tests/conformance_kernels.rs`, or an HLSL,
//! GLSL, CUDA, Metal or C++ port checked against the golden vectors of
//! [`crate::vectors`]) may differ from the Rust kernel, each stated once with
//! its reason.
//!
//! [`Tol::Ulps`]`(n)`: at most `n` ulps apart; [`Tol::Abs`]`(a)`: within `a`
//! absolute (or within 4 ulps, which matters near 0); [`Tol::Rel`]`(r)`:
//! within `r · max(1, |a|, |b|)`. For every kind, both NaN agrees, and a Rust
//! subnormal against a port's zero agrees (GPUs may flush subnormals).
//!
//! The `*_NEAR` and `*_PER_*` constants are the conformance suite's rules
//! for decisions that one rounding can flip (a mask cell on its line, a gate
//! on its threshold): they say which differences are counted rather than
//! failed, and how many may be.

/// How two floats may differ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tol {
    /// At most this many ulps apart (or both NaN). `Ulps(0)`: exactly.
    Ulps(u32),
    /// `|a − b| ≤ abs`, or at most 4 ulps apart (or both NaN).
    Abs(f32),
    /// `|a − b| ≤ rel · max(1, |a|, |b|)` (or both NaN).
    Rel(f32),
}

impl Tol {
    /// The error of `b` against `a` in this tolerance's unit (ulps, absolute
    /// or relative): 0 where the rules above say they agree, `+∞` where one
    /// is non-finite and the other differs.
    pub fn error(self, a: f32, b: f32) -> f64 {
        if a != 0.0 && a.abs() < f32::MIN_POSITIVE && b == 0.0 {
            return 0.0;
        }
        match self {
            Tol::Ulps(_) => ulps(a, b) as f64,
            Tol::Rel(_) => {
                if ulps(a, b) == 0 {
                    0.0
                } else if a.is_finite() && b.is_finite() {
                    let scale = 1f64.max(a.abs() as f64).max(b.abs() as f64);
                    (a as f64 - b as f64).abs() / scale
                } else {
                    f64::INFINITY
                }
            }
            Tol::Abs(_) => {
                if ulps(a, b) <= 4 {
                    0.0
                } else if a.is_finite() && b.is_finite() {
                    (a as f64 - b as f64).abs()
                } else {
                    f64::INFINITY
                }
            }
        }
    }

    /// The largest allowed [`Tol::error`].
    pub fn limit(self) -> f64 {
        match self {
            Tol::Ulps(u) => u as f64,
            Tol::Abs(a) | Tol::Rel(a) => a as f64,
        }
    }

    /// Whether `b` agrees with `a` within this tolerance.
    pub fn accepts(self, a: f32, b: f32) -> bool {
        self.error(a, b) <= self.limit()
    }

    /// The kind's name in the golden vector files: `ulps`, `abs` or `rel`.
    pub fn kind(self) -> &'static str {
        match self {
            Tol::Ulps(_) => "ulps",
            Tol::Abs(_) => "abs",
            Tol::Rel(_) => "rel",
        }
    }
}

/// Distance of two floats in ulps: 0 when equal (`0 == −0`) or both NaN,
/// `u32::MAX` when only one is NaN or either is infinite (and they differ).
pub fn ulps(a: f32, b: f32) -> u32 {
    if a == b || (a.is_nan() && b.is_nan()) {
        return 0;
    }
    if a.is_nan() || b.is_nan() || a.is_infinite() || b.is_infinite() {
        return u32::MAX;
    }
    // Ordered integer representation: adjacent floats differ by one.
    let key = |x: f32| {
        let i = x.to_bits() as i32;
        if i < 0 {
            i32::MIN.wrapping_sub(i) as i64
        } else {
            i as i64
        }
    };
    (key(a) - key(b)).unsigned_abs().min(u32::MAX as u64) as u32
}

/// `bilateral_weight`, `shadow_gated_weight`, `material_gated_weight` (eq. 1,
/// 2): weights in [0, 1] built from `exp`; the Rust kernel is within 2e-6 of
/// f64 (kernels/tests/f64_reference.rs), and WGSL's `exp` may be off by
/// 3 + 2|x| ulps, below 1e-6 on a result ≤ 1: 2e-6, the tighter of the two
/// bounds earlier tests used (4e-6, and 2e-6 + 1e-5·w). Lavapipe's worst is
/// ~1e-8.
pub const TOL_WEIGHT: Tol = Tol::Abs(2e-6);
/// `albedo_difference` on its domain (components in [0, 4]): a difference
/// of square roots, a few ulps of WGSL `sqrt` each.
pub const TOL_ALBEDO_DIFFERENCE: Tol = Tol::Abs(1e-6);
/// `resolve_pixel`: one rounding per add and the scale.
pub const TOL_RESOLVE: Tol = Tol::Abs(1e-6);
/// `resolve_pixel_tone_mapped` on its domain (colours in [0, 400], exposure
/// in [0.01, 100]): a weighted mean of four colours with weights
/// `1 / (1 + luma·e)`, summed in f32 on the GPU and in f64 in Rust. A few
/// ulps in each weight and each sum move the mean by a few ulps of the
/// largest colour: 1e-5 relative to the larger of 1 and the values.
pub const TOL_RESOLVE_TONE_MAPPED: Tol = Tol::Rel(1e-5);
/// `sraa::RECONSTRUCT_WGSL`'s loop (`reconstruct_layers` of a subsample,
/// its layers summed) and the pixel's box resolve of four such sums
/// (`sraa::Resolver`): weighted means of non-negative colours, relative to
/// the larger of 1 and the values. A relative error `ε` in the weights moves
/// such a mean by at most `2ε` of it. A weight is `exp(−s)` with `s < 105`:
/// WGSL's `exp` may be off by `3 + 2|s|` ulps (up to 1.3e-5 relative), and
/// `s`, a sum of squares, may round (or fuse) one ulp apart (up to 1.3e-5
/// more), so `2ε` stays below 6e-5; the compensated f32 sums add about one
/// f32 ulp against Rust's f64: 1e-4. A subnormal weight that a GPU flushes
/// to zero moves the mean by less than `2⁻⁶²·C` (`2⁻¹²⁶` over the least
/// total weight that does not fall back, `NEGLIGIBLE_WEIGHT = 2⁻⁶⁴`):
/// nothing for colours `C` of ordinary range (the suite draws them up to
/// 65504). Lavapipe's worst is 3e-6.
pub const TOL_RECONSTRUCT: Tol = Tol::Rel(1e-4);
/// `cone_radius`, `min_step`, `advance`, `backtrace_cone_entry`,
/// `backtrace_hard_hit`: a multiply, an add or a division each. 2 ulps, the
/// tighter of the two bounds earlier tests used (2 and 4 ulps). WGSL allows a
/// division 2.5 ulps, so a GPU using all of that latitude could exceed it;
/// then widen to 3 ulps (2.5 + Rust's 0.5), no further. Lavapipe agrees
/// bit for bit.
pub const TOL_CONE: Tol = Tol::Ulps(2);
/// `cone_tan_theta` (eq. 3): not run by the GPU suite (a renderer computes
/// it once per frame on the host), but a port computes it too: one `tan`, one
/// multiply, one divide, 4 ulps, the bound the Rust kernel meets against
/// f64 (kernels/tests/f64_reference.rs).
pub const TOL_CONE_TAN_THETA: Tol = Tol::Ulps(4);
/// `cone_occlusion` (eq. 5): `(1 − d/R_c)/2`. 2 ulps, the tighter of the
/// two bounds earlier tests used (2 ulps, and 2e-6 absolute). Near ω = 0 the
/// subtraction cancels and one ulp of the quotient is many ulps of the
/// result: a GPU whose division differs from Rust's there would need the
/// 2e-6 absolute bound back (twice the f64 bound). Lavapipe agrees bit for
/// bit.
pub const TOL_OCCLUSION: Tol = Tol::Ulps(2);
/// `project_normal`: a normalisation and two dot products.
pub const TOL_PROJECT_NORMAL: Tol = Tol::Abs(1e-6);
/// `sample_weight`: a count over 32, exact.
pub const TOL_SAMPLE_WEIGHT: Tol = Tol::Ulps(0);
/// Integer and boolean results (the shadow gate's decision, `visibility_mask`,
/// `needs_normal`, the K masks of `TransparencyAccumulator`,
/// `remaining_after`, `is_opaque`): exactly, up to the rounding-decided
/// decisions that [`MASK_NEAR`], [`NEEDS_NORMAL_NEAR`] and
/// [`TRANSPARENCY_NEAR`] describe.
pub const TOL_EXACT: Tol = Tol::Ulps(0);
/// `Aggregate` (eq. 6): a weighted mean of at most five colours, summed in
/// f64 by Rust and in f32 by WGSL (no f64): relative to the larger of 1 and
/// the values.
pub const TOL_AGGREGATE: Tol = Tol::Rel(1e-6);
/// `fxaa_encode`: 8-bit levels; one level apart where the sRGB value lies
/// within an ulp of a rounding boundary (WGSL `pow` is not correctly rounded).
pub const TOL_FXAA_ENCODE: Tol = Tol::Abs(1.0 / 255.0 + 1e-6);
/// `fxaa_pixel`: sRGB units; the encoding's `pow` error moves the luma by
/// ~1e-6 and FXAA blends it.
pub const TOL_FXAA_PIXEL: Tol = Tol::Abs(1e-4);
/// The generated SDF field (`WgslField::compile` against `eval` and
/// `eval_split`), relative to `max(1, |d|, |p|/100)`: GPU `sqrt` and fused
/// multiply-adds differ in the last bits; the `|p|` term covers the far
/// scene, whose coordinates reach 10⁷ (the distance is a difference of such).
pub const TOL_SDF_FIELD: f32 = 2e-6;
/// The SDF field's material: where two objects are nearest within rounding,
/// either may win; at most 1 in 200 points.
pub const SDF_MATERIAL_TIES_PER_200: usize = 1;
/// `visibility_mask`: a cell may differ only where the mask's line passes
/// within this distance (in units of the unit disk, computed in f64 from the
/// inputs) of its centre: one rounding of `h` and of the two products, a few
/// 1e-7, with margin. The cell pitch is `2s/6 ≈ 0.31`.
pub const MASK_NEAR: f64 = 1e-5;
/// Masks with such a near-line difference, at most 1 % of cases.
pub const MASK_NEAR_ROWS_PER_100: usize = 1;
/// `material_gated_weight`'s gate decision: exact, except where the albedo
/// difference lies within this of the tolerance, where a few ulps of WGSL
/// `sqrt` decide (skipped and counted).
pub const MATERIAL_GATE_NEAR: f32 = 1e-5;
/// `needs_normal`: exact, except where `|d/R_c|` lies within this of the
/// farthest cell centre, where one rounding decides it.
pub const NEEDS_NORMAL_NEAR: f32 = 1e-5;
/// `ao_direction` (with `tangent_frame` and `ao_direction_local`): WGSL
/// bounds `sin` and `cos` only to 2^-11 absolute on [−π, π], the azimuth's
/// range, and the frame adds the two components' errors: √2·2^-11 ≈ 6.9e-4,
/// plus a few roundings of the normalisation and the frame: 1e-3. Every
/// other step (the stratum's division, square roots) is a few ulps.
/// Lavapipe's worst is 9e-8.
pub const TOL_AO_DIRECTION: Tol = Tol::Abs(1e-3);
/// `TransparencyAccumulator` (CTSS §5.3's K masks: `add`'s visible cells and
/// gained levels, the planes, `level`, `level_set`, `is_binary`, `opaque`,
/// `total_levels`), `remaining_after` and `is_opaque`: integer results,
/// compared exactly. The one float step, `⌊r·(1 − α) + ½⌋`, may be fused on
/// a GPU: where `r·(1 − α) + ½` lies within this of an integer (in f64, and
/// not exactly on it in f32) a level may differ, so such records are skipped
/// and counted (at most 1 %): a few roundings of `r·(1 − α)`, with margin.
pub const TRANSPARENCY_NEAR: f64 = 1e-6;
/// `level_weight`, `uncovered_weight` and `clamp_alpha`: small integers
/// times a power of two, or a clamp: exact.
pub const TOL_TRANSPARENCY_WEIGHT: Tol = Tol::Ulps(0);
/// The stepper's translucent parts (`ConeStepper::advance_object` passing
/// through a semi-transparent object, `record_alpha_mask`, `split_group`,
/// `end_pass`, `background_weight`): events, stop reasons, masks, counters
/// exactly, and every depth and weight within 2 ulps (the cone kernels'
/// [`TOL_CONE`]: a multiply, an add or a division each; the weights are
/// exact). One ulp of a depth can flip a later threshold decision, so a
/// record whose two traces part ways is counted, not failed, while fewer
/// than 1 % do. Lavapipe agrees on every record.
pub const TOL_STEPPER: Tol = Tol::Ulps(2);
/// `ao_fraction`: a quotient of two exactly converted integers (≤ 2^24);
/// WGSL allows the division 2.5 ulps, Rust's is correctly rounded: 3 ulps.
pub const TOL_AO_FRACTION: Tol = Tol::Ulps(3);
/// `subcone_ctss_trace` (the whole CTSS trace, `ctss::trace_field`) on
/// analytic fields: the colour of a ray whose decisions agree (the same
/// samples, SDF evaluations, coverage mask and stop). Its error is the
/// shading normals' (tetrahedral differences of step ≈ R_c/4 over distances
/// that GPU `sqrt` rounds differently: ~ulp(d)/h ≈ 1e-5 at the steps used),
/// carried through the shade hook and eq. 6 (f32 sums on the GPU, f64 in
/// Rust): 1e-4 absolute.
pub const TOL_CTSS_TRACE: Tol = Tol::Abs(1e-4);
/// `subcone_ctss_trace`'s decisions: a ray's counts (samples, evaluations),
/// coverage mask and stop reason are compared exactly, except that a
/// distance one rounding apart can flip one of the stepper's threshold tests
/// (or a split test) where its value lies on the threshold, and then the
/// rest of the trace differs: at most 1 ray in 200 may differ so (counted and
/// reported; its colour is not compared). Lavapipe differs on none.
pub const CTSS_TRACE_FLIPS_PER_200: usize = 1;
