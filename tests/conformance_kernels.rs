//! Kernel-level conformance: every WGSL kernel the kernels crate ships (and
//! the SDF code generator's WGSL), run through the one kernel harness,
//! `subcone_wgpu::test_util::run_wgsl`, over thousands of generated inputs
//! (the stiff and extreme domain included: zeros, subnormals, 1e±30,
//! `f32::MAX`, ±∞, NaN) and fixed grids of extremes, against the Rust code it
//! mirrors.
//!
//! Every tolerance is stated once, with its reason, in the `TOL_*` and
//! `*_NEAR` constants of `subcone::vectors::tolerance`, which the golden
//! vectors (`subcone vectors`) state too. How outputs are compared, per kind:
//! - **gates and codes** (the shadow gate of eq. 2, `needs_normal`): exactly;
//! - **masks** (`visibility_mask`): bit for bit, except that a cell may differ
//!   where the mask's line (computed in f64 from the inputs) passes within
//!   `MASK_NEAR` of its centre (WGSL allows inexact division and fused
//!   multiply-adds, so a 1-ulp difference can flip that cell); such masks are
//!   counted, reported and capped;
//! - **floats**: within the kernel's tolerance, in ulps, absolute or relative;
//! - **non-finite inputs**: through the kernels' documented clamps: both
//!   outputs must satisfy the documented contract and agree on its class
//!   (NaN against NaN, or values within the tolerance), never raw bits, since
//!   WGSL leaves NaN and infinity results indeterminate.
//!
//! Each kernel prints its worst case: the input, both outputs and the error.
//! `perturbed_kernels_are_caught` checks that the suite fails when a WGSL
//! kernel is deliberately broken (the mask intercept's sign flipped, a weight's
//! exponent changed).

use std::fmt::Write as _;

use glam::{Vec2, Vec3};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, TestRunner};
use subcone::vectors::tolerance::{
    Tol, CTSS_TRACE_FLIPS_PER_200, MASK_NEAR, MASK_NEAR_ROWS_PER_100, MATERIAL_GATE_NEAR,
    NEEDS_NORMAL_NEAR, SDF_MATERIAL_TIES_PER_200, TOL_AGGREGATE, TOL_ALBEDO_DIFFERENCE,
    TOL_AO_DIRECTION, TOL_AO_FRACTION, TOL_CONE, TOL_CTSS_TRACE, TOL_FXAA_ENCODE, TOL_FXAA_PIXEL,
    TOL_OCCLUSION, TOL_PROJECT_NORMAL, TOL_RECONSTRUCT, TOL_RESOLVE, TOL_RESOLVE_TONE_MAPPED,
    TOL_SAMPLE_WEIGHT, TOL_SDF_FIELD, TOL_STEPPER, TOL_TRANSPARENCY_WEIGHT, TOL_WEIGHT,
    TRANSPARENCY_NEAR,
};
use subcone::vectors::{ao_grid_normals, AO_GRID_INDICES, AWKWARD_DEPTHS, AWKWARD_WEIGHT_PARAMS};
use subcone_kernels::aggregate::{sample_weight, Aggregate, Weighting};
use subcone_kernels::ao::{ao_direction, ao_fraction};
use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, min_step,
};
use subcone_kernels::mask::{
    needs_normal, project_normal, visibility_mask, MaskPlacement, FARTHEST_CENTRE,
};
use subcone_kernels::sraa::{
    albedo_difference, bilateral_weight, material_gated_weight, neighbourhood, reconstruct_layers,
    reconstruct_layers_material, reconstruction_weight, resolve_pixel, resolve_pixel_tone_mapped,
    shadow_gated_weight, DepthMetric, Geometry, LayeredSample, Resolver, ShadedFrame, ShadedGroup,
    SraaParams, Subsamples, WeightForm, ALBEDO_TOLERANCE,
};
use subcone_wgpu::test_util::{gpu_or_skip, run_wgsl, Kernel, Table};
use subcone_wgpu::GpuContext;

/// Inputs per kernel (generated; each check adds its fixed grids of extremes).
const CASES: usize = 4096;

/// The GPU, or `None`: skipped without an adapter unless `SUBCONE_REQUIRE_GPU`.
fn gpu() -> Option<subcone_wgpu::WgpuBackend> {
    gpu_or_skip("kernel conformance")
}

/// Run `body` once per record of `input` (`in_words` each) through the
/// harness, with the kernel sources `library`; `out_words` per record back.
fn run(
    ctx: &GpuContext,
    library: &str,
    body: &str,
    in_words: usize,
    out_words: usize,
    input: &[u32],
) -> Result<Vec<u32>, String> {
    run_wgsl(
        ctx,
        &Kernel {
            library,
            body,
            in_words,
            out_words,
            tables: &[],
        },
        input,
    )
    .map_err(|e| e.to_string())
}

/// Values from every part of f32: mostly the kernels' domain, a third of the
/// time anything at all (subnormals, infinities and NaN included).
fn any_f32(lo: f32, hi: f32) -> BoxedStrategy<f32> {
    prop_oneof![
        6 => lo..hi,
        1 => prop::sample::select(vec![
            0.0f32, -0.0, 1e-30, -1e-30, 1e-38, 1e30, -1e30, f32::MAX, f32::MIN,
            f32::MIN_POSITIVE, 1.4e-45, f32::INFINITY, f32::NEG_INFINITY, f32::NAN,
        ]),
        2 => any::<f32>(),
    ]
    .boxed()
}

fn unit_vec() -> BoxedStrategy<Vec3> {
    prop_oneof![
        8 => (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
            .prop_map(|(x, y, z)| Vec3::new(x, y, z).try_normalize().unwrap_or(Vec3::Z)),
        1 => (any_f32(-2.0, 2.0), any_f32(-2.0, 2.0), any_f32(-2.0, 2.0))
            .prop_map(|(x, y, z)| Vec3::new(x, y, z)),
    ]
    .boxed()
}

/// Awkward f32s, every fifth a special (signed zeros, infinities, NaN, tiny
/// and huge values), else signed and log-uniform over 1e-3..1e3.
fn awkward(i: usize, unit: &mut impl FnMut() -> f32) -> f32 {
    const SPECIAL: [f32; 10] = [
        0.0,
        -0.0,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        1e-30,
        -1e30,
        1.0,
        0.5,
        f32::MAX,
    ];
    if i % 5 == 0 {
        SPECIAL[(unit() * 10.0) as usize % 10]
    } else {
        (unit() * 2.0 - 1.0) * 10f32.powf(unit() * 6.0 - 3.0)
    }
}

fn generate<T: std::fmt::Debug>(strategy: impl Strategy<Value = T>, seed: u8) -> Vec<T> {
    let mut runner = TestRunner::new_with_rng(
        Config::default(),
        proptest::test_runner::TestRng::from_seed(
            proptest::test_runner::RngAlgorithm::ChaCha,
            &[seed; 32],
        ),
    );
    (0..CASES)
        .map(|_| strategy.new_tree(&mut runner).expect("value").current())
        .collect()
}

/// One kernel's comparison: the worst case, and the failures.
struct Report {
    kernel: &'static str,
    worst: f64,
    worst_case: String,
    failures: Vec<String>,
    failed: usize,
    /// Inputs compared.
    inputs: usize,
    near_boundary_rows: usize,
}

impl Report {
    fn new(kernel: &'static str) -> Self {
        Report {
            kernel,
            worst: 0.0,
            worst_case: "all equal".into(),
            failures: Vec::new(),
            failed: 0,
            inputs: 0,
            near_boundary_rows: 0,
        }
    }

    fn floats(&mut self, tol: Tol, input: &dyn std::fmt::Debug, rust: &[f32], gpu: &[f32]) {
        self.inputs += 1;
        let e = rust
            .iter()
            .zip(gpu)
            .map(|(&a, &b)| tol.error(a, b))
            .fold(0.0, f64::max);
        if e > self.worst || (self.worst == 0.0 && e > 0.0) {
            self.worst = e;
            self.worst_case = format!("input {input:?}: rust {rust:?}, wgsl {gpu:?}");
        }
        if e > tol.limit() {
            self.failed += 1;
        }
        if e > tol.limit() && self.failures.len() < 5 {
            self.failures.push(format!(
                "input {input:?}: rust {rust:?}, wgsl {gpu:?} (error {e:e}, limit {tol:?})"
            ));
        }
    }

    fn exact(&mut self, input: &dyn std::fmt::Debug, rust: u32, gpu: u32) {
        self.inputs += 1;
        if rust != gpu {
            self.worst = 1.0;
            self.failed += 1;
            if self.failures.len() < 5 {
                self.failures
                    .push(format!("input {input:?}: rust {rust}, wgsl {gpu}"));
            }
        }
    }

    /// Masks: every differing cell must have the mask's line within
    /// [`MASK_NEAR`] of its centre (see [`line_distance`]); masks with such
    /// cells are counted. Any other difference fails.
    fn mask(
        &mut self,
        input: &dyn std::fmt::Debug,
        line: Option<(f64, f64, f64)>,
        rust: u32,
        gpu: u32,
    ) {
        self.inputs += 1;
        let diff = rust ^ gpu;
        if diff == 0 {
            return;
        }
        let worst = (0..32)
            .filter(|b| diff >> b & 1 == 1)
            .map(|b| line.map_or(f64::INFINITY, |l| line_distance(l, b)))
            .fold(0.0, f64::max);
        if worst > self.worst || self.worst == 0.0 {
            self.worst = worst;
            self.worst_case = format!(
                "input {input:?}: rust {rust:#010x}, wgsl {gpu:#010x} (line {worst:e} from a differing centre)"
            );
        }
        if worst <= MASK_NEAR {
            self.near_boundary_rows += 1;
            return;
        }
        self.failed += 1;
        if self.failures.len() < 5 {
            self.failures.push(format!(
                "input {input:?}: rust {rust:#010x}, wgsl {gpu:#010x} (a differing cell {worst:e} from the line)"
            ));
        }
    }

    fn finish(self) -> Result<String, String> {
        let mut line = format!(
            "{:<24} worst {:<10.3e} {}",
            self.kernel, self.worst, self.worst_case
        );
        if self.near_boundary_rows > 0 {
            let _ = write!(
                line,
                " | masks differing only at cells within {MASK_NEAR:e} of the line: {}",
                self.near_boundary_rows,
            );
        }
        if self.failures.is_empty() {
            Ok(line)
        } else {
            Err(format!(
                "{line}\n  {}: {} of {} comparisons fail, e.g.:\n  {}",
                self.kernel,
                self.failed,
                self.inputs,
                self.failures.join("\n  ")
            ))
        }
    }
}

fn words(v: &[f32]) -> impl Iterator<Item = u32> + '_ {
    v.iter().map(|x| x.to_bits())
}

fn floats(w: &[u32]) -> Vec<f32> {
    w.iter().map(|&x| f32::from_bits(x)).collect()
}

/// The WGSL library under test: kernel sources (the harness puts the
/// prelude, `wgsl::PARAMS`, first).
struct Library {
    sraa: String,
    /// `sraa::RECONSTRUCT_WGSL` with the test's hooks ([`RECONSTRUCT_HOOKS`]);
    /// run after `sraa`.
    reconstruct: String,
    ctss: String,
    /// `transparency::WGSL` (the stepper carries the K masks), `ctss::WGSL` and `ctss::TRACE_WGSL` with the test's hooks
    /// ([`TRACE_HOOKS`]); run after `ctss`.
    trace: String,
    fxaa: String,
    ao: String,
    transparency: String,
    stepper: String,
}

impl Library {
    fn shipped() -> Self {
        use subcone_kernels::*;
        Library {
            sraa: [sraa::WGSL, SRAA_PARAMS_AT].concat(),
            reconstruct: [RECONSTRUCT_HOOKS, sraa::RECONSTRUCT_WGSL].concat(),
            ctss: [cone::WGSL, mask::WGSL, aggregate::WGSL].concat(),
            trace: [
                transparency::WGSL,
                ctss::WGSL,
                TRACE_HOOKS,
                ctss::TRACE_WGSL,
            ]
            .concat(),
            fxaa: [FXAA_FETCH, fxaa::WGSL].concat(),
            ao: ao::WGSL.to_string(),
            transparency: [cone::WGSL, mask::WGSL, transparency::WGSL].concat(),
            stepper: [
                cone::WGSL,
                mask::WGSL,
                aggregate::WGSL,
                transparency::WGSL,
                CTSS_FIELD,
                ctss::WGSL,
            ]
            .concat(),
        }
    }
}

/// The field `ctss.wgsl`'s sphere tracer expects from its including shader
/// (the stepper check does not trace, it feeds the distances).
const CTSS_FIELD: &str = "
fn ctss_field(p: vec3<f32>) -> vec2<f32> { let d = length(p) - 1.0; return vec2<f32>(d, d); }
";

/// The pixel fetch `fxaa.wgsl` expects from its including shader: a 7×7
/// patch of linear colours (the record's first 147 words, row-major),
/// clamped to its edge and encoded as the backends encode frames.
const FXAA_FETCH: &str = "
fn fxaa_fetch(x: i32, y: i32) -> vec4<f32> {
    let cx = u32(clamp(x, 0, 6));
    let cy = u32(clamp(y, 0, 6));
    return subcone_fxaa_encode(v3(3u * (cy * 7u + cx)));
}
";

type Check = fn(&GpuContext, &Library) -> Result<String, String>;

fn sraa_params() -> BoxedStrategy<SraaParams> {
    prop_oneof![
        3 => Just(SraaParams::PAPER),
        3 => Just(SraaParams::TUNED),
        2 => Just(SraaParams::CHAJDAS),
        2 => (any_f32(0.0, 2.0), 0u32..3).prop_map(|(s, shading)| SraaParams {
            sigma_s: s,
            shading,
            ..SraaParams::TUNED
        }),
        1 => any_f32(0.0, 2.0).prop_map(|s| SraaParams::CHAJDAS.with_spatial(s)),
        2 => (any_f32(0.0, 40.0), any_f32(0.0, 2.0), 0u32..2, 0u32..2).prop_map(|(z, n, form, metric)| {
            SraaParams::new(
                z,
                n,
                10.0,
                if form == 0 { WeightForm::Product } else { WeightForm::ChajdasMax },
                if metric == 0 { DepthMetric::Relative } else { DepthMetric::Absolute },
                1,
            )
        }),
    ]
    .boxed()
}

fn geometry() -> BoxedStrategy<Geometry> {
    (unit_vec(), any_f32(0.0, 100.0))
        .prop_map(|(n, z)| Geometry::new(n, z))
        .boxed()
}

/// `SraaParams` as the 8 words `sraa_params_at` reads back in WGSL.
fn params_words(p: &SraaParams) -> [u32; 8] {
    [
        p.sigma_z.to_bits(),
        p.sigma_n.to_bits(),
        p.scale.to_bits(),
        p.packed,
        p.sigma_s.to_bits(),
        p.shading,
        0,
        0,
    ]
}

/// The WGSL of `params_words`: `subcone_SraaParams` from record words
/// `k..k + 8`.
const SRAA_PARAMS_AT: &str = "
fn sraa_params_at(k: u32) -> subcone_SraaParams {
    return subcone_SraaParams(f(k), f(k + 1u), f(k + 2u), u(k + 3u), f(k + 4u), u(k + 5u), 0u, 0u);
}
";

fn geometry_words(g: &Geometry) -> [u32; 4] {
    [
        g.normal.x.to_bits(),
        g.normal.y.to_bits(),
        g.normal.z.to_bits(),
        g.depth.to_bits(),
    ]
}

/// Every pairing of awkward normals (NaN, zero, opposite) and depths (0,
/// subnormal, 3e38, ∞, NaN, a miss-like 1e6) under four parameter sets
/// (both weight forms, both depth metrics, huge sigmas), both shadow states.
fn weight_grid() -> Vec<(SraaParams, Geometry, Geometry, bool, bool)> {
    let nan = f32::NAN;
    let normals = [
        Vec3::Z,
        Vec3::new(0.0, 0.6, 0.8),
        Vec3::X,
        -Vec3::Z,
        Vec3::new(nan, 0.0, 1.0),
        Vec3::ZERO,
    ];
    let (depths, params) = (AWKWARD_DEPTHS, AWKWARD_WEIGHT_PARAMS);
    let mut cases = Vec::new();
    for (a, na) in normals.iter().enumerate() {
        for nb in &normals {
            for (i, za) in depths.iter().enumerate() {
                for zb in &depths {
                    for (k, p) in params.iter().enumerate() {
                        cases.push((
                            *p,
                            Geometry::new(*na, *za),
                            Geometry::new(*nb, *zb),
                            (a + i) % 2 == 1,
                            k % 2 == 1,
                        ));
                    }
                }
            }
        }
    }
    cases
}

/// Eq. 1 and eq. 2, on generated inputs and [`weight_grid`]. Weights are in [0, 1]: the Rust kernel is within 2e-6 of
/// an f64 evaluation (kernels/tests/f64_reference.rs); WGSL's `exp` may be off
/// by 3 + 2|x| ulps, which on a result ≤ 1 is below 1e-6, so the two must agree
/// within twice the f64 bound. The gate itself (neighbours in different shadow
/// states) must be exactly 0 on both.
fn check_weights(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let cases = generate(
        (
            sraa_params(),
            geometry(),
            geometry(),
            any::<bool>(),
            any::<bool>(),
        ),
        1,
    )
    .into_iter()
    .chain(weight_grid())
    .collect::<Vec<_>>();
    // A distance² per case for the spatial term: 0, the subsample offsets'
    // range, far, and the extremes.
    let d2s = [0.0f32, 0.156_25, 0.39, 1.2, 4.5, 1e-30, 3e38, f32::INFINITY];
    let mut input = Vec::new();
    for (i, (p, gi, gj, si, sj)) in cases.iter().enumerate() {
        input.extend(params_words(p));
        input.extend(geometry_words(gi));
        input.extend(geometry_words(gj));
        input.extend([*si as u32, *sj as u32, d2s[i % d2s.len()].to_bits()]);
    }
    let out = run(
        ctx,
        &lib.sraa,
        "let p = sraa_params_at(0u);
         let gi = subcone_Geometry(v3(8u), f(11u));
         let gj = subcone_Geometry(v3(12u), f(15u));
         out[o] = bitcast<u32>(subcone_bilateral_weight(p, gi, gj));
         out[o + 1u] = bitcast<u32>(subcone_shadow_gated_weight(p, gi, gj, u(16u) != 0u, u(17u) != 0u));
         out[o + 2u] = bitcast<u32>(subcone_reconstruction_weight(p, gi, gj, f(18u)));",
        19,
        3,
        &input,
    )?;
    let mut bilateral = Report::new("subcone_bilateral_weight");
    let mut gated = Report::new("subcone_shadow_gated_weight");
    let mut spatial = Report::new("subcone_reconstruction_weight");
    for (i, c) in cases.iter().enumerate() {
        let (p, gi, gj, si, sj) = c;
        let g = floats(&out[3 * i..3 * i + 3]);
        let d2 = d2s[i % d2s.len()];
        spatial.floats(
            TOL_WEIGHT,
            &(c, d2),
            &[reconstruction_weight(p, gi, gj, d2)],
            &g[2..],
        );
        bilateral.floats(TOL_WEIGHT, c, &[bilateral_weight(p, gi, gj)], &g[..1]);
        let r = shadow_gated_weight(p, gi, gj, *si, *sj);
        if si != sj {
            gated.exact(c, r.to_bits(), g[1].to_bits());
        } else {
            gated.floats(TOL_WEIGHT, c, &[r], &g[1..]);
        }
    }
    let a = bilateral.finish();
    let b = gated.finish();
    join(join(a, b), spatial.finish())
}

/// An albedo: mostly in `[0, 1]` (the domain), sometimes anything
/// (`any_f32`'s extremes: huge, negative, infinite, NaN).
fn albedo() -> BoxedStrategy<Vec3> {
    prop_oneof![
        4 => (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0).prop_map(|(r, g, b)| Vec3::new(r, g, b)),
        1 => (any_f32(0.0, 1.0), any_f32(0.0, 1.0), any_f32(0.0, 1.0))
            .prop_map(|(r, g, b)| Vec3::new(r, g, b)),
    ]
    .boxed()
}

/// The material gate (§4.1, Fig. 6; eq. 2's gate on albedo). The pair of
/// albedos is equal, close (a step of up to 0.2 per channel, so the sum
/// straddles the tolerance) or independent. `albedo_difference` is a
/// difference of square roots: WGSL's `sqrt` is within a few ulps, so on the
/// domain (components in `[0, 4]`, differences ≤ 2) the two agree within
/// 1e-6; outside it (huge components, where the difference cancels) only its
/// class is compared: infinite (a non-finite component) or not. The gate's
/// decision must agree exactly (weight exactly 0 on both when gated) except
/// where the difference lies within 1e-5 of the tolerance, where a few ulps
/// of `sqrt` may decide; those cases are skipped and counted. Ungated, the
/// weight is eq. 1's: within 4e-6, as in `check_weights`.
fn check_material(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let pair = prop_oneof![
        2 => albedo().prop_map(|a| (a, a)),
        3 => (albedo(), (-0.2f32..0.2, -0.2f32..0.2, -0.2f32..0.2))
            .prop_map(|(a, (x, y, z))| (a, a + Vec3::new(x, y, z))),
        2 => (albedo(), albedo()),
    ];
    let tolerance = prop_oneof![6 => Just(ALBEDO_TOLERANCE), 2 => any_f32(0.0, 1.0)];
    let cases = generate((sraa_params(), geometry(), geometry(), pair, tolerance), 9);
    let mut input = Vec::new();
    for (p, gi, gj, (ai, aj), tol) in &cases {
        input.extend(params_words(p));
        input.extend(geometry_words(gi));
        input.extend(geometry_words(gj));
        input.extend(words(&ai.to_array()));
        input.extend(words(&aj.to_array()));
        input.push(tol.to_bits());
    }
    let out = run(
        ctx,
        &lib.sraa,
        "let p = sraa_params_at(0u);
         let gi = subcone_Geometry(v3(8u), f(11u));
         let gj = subcone_Geometry(v3(12u), f(15u));
         out[o] = bitcast<u32>(subcone_albedo_difference(v3(16u), v3(19u)));
         out[o + 1u] = bitcast<u32>(subcone_material_gated_weight(p, gi, gj, v3(16u), v3(19u), f(22u)));",
        23,
        2,
        &input,
    )?;
    let mut diff = Report::new("subcone_albedo_difference");
    let mut gated = Report::new("subcone_material_gated_weight");
    let mut near = 0;
    for (i, c) in cases.iter().enumerate() {
        let (p, gi, gj, (ai, aj), tol) = c;
        let g = floats(&out[2 * i..2 * i + 2]);
        let d = albedo_difference(*ai, *aj);
        let domain = |a: &Vec3| a.is_finite() && a.max_element() <= 4.0;
        if domain(ai) && domain(aj) {
            diff.floats(TOL_ALBEDO_DIFFERENCE, c, &[d], &g[..1]);
        } else {
            diff.exact(c, d.is_infinite() as u32, g[0].is_infinite() as u32);
        }
        if d.is_finite() && tol.is_finite() && (d - tol).abs() <= MATERIAL_GATE_NEAR {
            near += 1;
            continue;
        }
        let r = material_gated_weight(p, gi, gj, *ai, *aj, *tol);
        if !(d <= *tol && d.is_finite()) {
            gated.exact(c, r.to_bits(), g[1].to_bits());
        } else {
            gated.floats(TOL_WEIGHT, c, &[r], &g[1..]);
        }
    }
    let b = gated.finish().map(|s| {
        format!("{s} ({near} cases within {MATERIAL_GATE_NEAR:e} of the tolerance skipped)")
    });
    join(diff.finish(), b)
}

fn join(a: Result<String, String>, b: Result<String, String>) -> Result<String, String> {
    match (a, b) {
        (Ok(a), Ok(b)) => Ok(format!("{a}\n{b}")),
        (a, b) => Err(format!(
            "{}\n{}",
            a.unwrap_or_else(|e| e),
            b.unwrap_or_else(|e| e)
        )),
    }
}

/// `r` with the verdict on the `skipped` of `total` records a check could not
/// compare (an ulp away from a decision, where the two sides may
/// legitimately differ): more than 1 % is a failure of its own, since the
/// check would then pass over too much; fewer are noted after `r`.
fn within_skip_budget(
    r: Result<String, String>,
    (skipped, total): (usize, usize),
    check: &str,
    what: &str,
    note: &str,
) -> Result<String, String> {
    if skipped * 100 > total {
        join(
            r,
            Err(format!(
                "{check}: {skipped} of {total} {what} (more than 1 %)"
            )),
        )
    } else {
        r.map(|s| format!("{s} | {note}: {skipped}"))
    }
}

/// The pixel resolve: a mean of four colours, non-finite ones dropped. One
/// rounding per add and the scale: within 4 ulps or 1e-6 of each other.
fn check_resolve(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let colour = (any_f32(0.0, 4.0), any_f32(0.0, 4.0), any_f32(0.0, 4.0))
        .prop_map(|(r, g, b)| Vec3::new(r, g, b));
    let cases = generate([colour.clone(), colour.clone(), colour.clone(), colour], 2);
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|s| {
            s.iter()
                .flat_map(|c| words(&c.to_array()).collect::<Vec<_>>())
        })
        .collect();
    let out = run(
        ctx,
        &lib.sraa,
        "let c = subcone_resolve_pixel(v3(0u), v3(3u), v3(6u), v3(9u));
         out[o] = bitcast<u32>(c.x); out[o + 1u] = bitcast<u32>(c.y); out[o + 2u] = bitcast<u32>(c.z);",
        12,
        3,
        &input,
    )?;
    let mut r = Report::new("subcone_resolve_pixel");
    for (i, c) in cases.iter().enumerate() {
        let rust = resolve_pixel(c).to_array();
        // Colours this large overflow the sum on one side and not the other;
        // the documented contract (finite colours) excludes them.
        let huge = c.iter().any(|v| v.is_finite() && v.max_element() > 1e37);
        if !huge {
            r.floats(TOL_RESOLVE, c, &rust, &floats(&out[3 * i..3 * i + 3]));
        }
    }
    r.finish()
}

/// The tone-mapped pixel resolve (Karis 2014's weights): HDR colours in
/// [0, 400] and exposures in [0.01, 100], extremes and non-finite values
/// included in both; within [`TOL_RESOLVE_TONE_MAPPED`] on the domain, and
/// never NaN where the Rust is finite.
fn check_resolve_tone_mapped(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let colour = (any_f32(0.0, 400.0), any_f32(0.0, 4.0), any_f32(0.0, 400.0))
        .prop_map(|(r, g, b)| Vec3::new(r, g, b));
    let cases = generate(
        (
            [colour.clone(), colour.clone(), colour.clone(), colour],
            any_f32(0.01, 100.0),
        ),
        3,
    );
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|(s, e)| {
            s.iter()
                .flat_map(|c| words(&c.to_array()).collect::<Vec<_>>())
                .chain(words(&[*e]))
                .collect::<Vec<_>>()
        })
        .collect();
    let out = run(
        ctx,
        &lib.sraa,
        "let c = subcone_resolve_pixel_tone_mapped(v3(0u), v3(3u), v3(6u), v3(9u), f(12u));
         out[o] = bitcast<u32>(c.x); out[o + 1u] = bitcast<u32>(c.y); out[o + 2u] = bitcast<u32>(c.z);",
        13,
        3,
        &input,
    )?;
    let mut r = Report::new("subcone_resolve_pixel_tone_mapped");
    for (i, (c, e)) in cases.iter().enumerate() {
        let rust = resolve_pixel_tone_mapped(c, *e).to_array();
        let gpu = floats(&out[3 * i..3 * i + 3]);
        // The contract's domain: radiance (finite, non-negative colours)
        // within the generator's range and a positive, finite exposure
        // within its range. Outside it, f32 and f64 sums may overflow or
        // underflow apart; only "never NaN" is checked there.
        let in_domain = c
            .iter()
            .all(|v| v.is_finite() && v.min_element() >= 0.0 && v.max_element() <= 400.0)
            && (0.01..=100.0).contains(e);
        let nan_out_of_finite =
            rust.iter().all(|v| v.is_finite()) && gpu.iter().any(|v| v.is_nan());
        if in_domain || nan_out_of_finite {
            r.floats(TOL_RESOLVE_TONE_MAPPED, &(c, e), &rust, &gpu);
        }
    }
    r.finish()
}

/// The image of a [`check_reconstruct`] record: `RECON_W × RECON_H` pixels.
const RECON_W: u32 = 4;
const RECON_H: u32 = 3;
/// Layers per group in [`check_reconstruct`]: layer 0 ungated, layer `1 + l`
/// gated by light `l`'s shadow bit (eq. 2), as `SRAA_GATES` says.
const RECON_GATES: [Option<u8>; 3] = [None, Some(0), Some(1)];
/// Words of a [`check_reconstruct`] record before its pixels, and per pixel.
const RECON_HEADER: usize = 44;
const RECON_PIXEL: usize = 17;

/// The hooks `sraa::RECONSTRUCT_WGSL` expects from its including shader,
/// over a [`check_reconstruct`] record: words 0..8 the parameters, 11 the
/// albedo tolerance, then from word 44 the 4×3 image's shaded samples, 17
/// words each (normal, depth, shadow bits, albedo, three colour layers).
/// The secondary group reads the same samples: the record says which group
/// runs, so the loop's one difference between them, the material gate, is
/// what it exercises.
const RECONSTRUCT_HOOKS: &str = "
const SRAA_GATES: u32 = 3u;
const SRAA_MATERIAL: bool = true;
fn sraa_params() -> subcone_SraaParams { return sraa_params_at(0u); }
fn sraa_size() -> vec2<u32> { return vec2<u32>(4u, 3u); }
fn sraa_albedo_tolerance() -> f32 { return f(11u); }
fn recon_pixel(x: u32, y: u32) -> u32 { return 44u + (y * 4u + x) * 17u; }
fn sraa_shaded_geometry(x: u32, y: u32, secondary: bool) -> subcone_Geometry {
    let b = recon_pixel(x, y);
    return subcone_Geometry(v3(b), f(b + 3u));
}
fn sraa_shaded_shadow(x: u32, y: u32, secondary: bool) -> u32 { return u(recon_pixel(x, y) + 4u); }
fn sraa_shaded_albedo(x: u32, y: u32) -> vec3<f32> { return v3(recon_pixel(x, y) + 5u); }
fn sraa_shaded_value(x: u32, y: u32, layer: u32) -> vec3<f32> { return v3(recon_pixel(x, y) + 8u + 3u * layer); }
";

/// One shaded sample of a [`check_reconstruct`] image.
#[derive(Clone, Debug)]
struct ReconPixel {
    geometry: Geometry,
    shadow: u32,
    albedo: Vec3,
    colors: [Vec3; 3],
}

/// One [`check_reconstruct`] record: a pixel `(x, y)` of a 4×3 image, its
/// four subsamples and the image's shaded samples.
#[derive(Clone, Debug)]
struct ReconCase {
    params: SraaParams,
    x: u32,
    y: u32,
    /// The material gate (the primary group with `SRAA_MATERIAL`), or none
    /// (the secondary group).
    gate: bool,
    tolerance: f32,
    targets: Subsamples,
    pixels: Vec<ReconPixel>,
}

/// Geometry that mostly lies on one of three surfaces (so that neighbours
/// weigh something and a few weigh nearly nothing), sometimes a miss, and
/// sometimes anything ([`geometry`]'s extremes: NaN normals, `∞` and NaN
/// depths).
fn surface() -> BoxedStrategy<Geometry> {
    let normals = [Vec3::Z, Vec3::new(0.6, 0.0, 0.8), Vec3::new(0.0, -0.8, 0.6)];
    prop_oneof![
        6 => (0usize..3, prop::sample::select(vec![1.0f32, 1.05, 2.0]), -0.01f32..0.01)
            .prop_map(move |(n, z, dz)| Geometry::new(normals[n], z + dz)),
        1 => Just(Geometry::MISS),
        2 => geometry(),
    ]
    .boxed()
}

/// An albedo of one of three materials (two within the default tolerance of
/// each other, one far), or anything ([`albedo`]).
fn material() -> BoxedStrategy<Vec3> {
    prop_oneof![
        4 => prop::sample::select(vec![
            Vec3::new(0.8, 0.2, 0.2),
            Vec3::new(0.8, 0.25, 0.2),
            Vec3::new(0.1, 0.5, 0.9),
        ]),
        1 => albedo(),
    ]
    .boxed()
}

/// A shaded colour: radiance, so not negative; mostly in `[0, 4]`, exactly
/// black, tiny, as bright as half floats go (65504), or not finite (excluded
/// by both sides). Not brighter: a GPU may flush a subnormal weight (below
/// 2⁻¹²⁶, which eq. 1 reaches on far neighbours) to zero, and times a colour
/// of 1e30 such a weight still moves the mean (see `TOL_RECONSTRUCT`).
fn radiance() -> BoxedStrategy<Vec3> {
    let channel = prop_oneof![
        6 => 0.0f32..4.0,
        1 => Just(0.0f32),
        1 => prop::sample::select(vec![
            1e-30f32, 1e-38, 1.4e-45, 65504.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY,
        ]),
    ];
    (channel.clone(), channel.clone(), channel)
        .prop_map(|(r, g, b)| Vec3::new(r, g, b))
        .boxed()
}

fn shadow_bits() -> BoxedStrategy<u32> {
    prop_oneof![6 => 0u32..4, 1 => any::<u32>()].boxed()
}

fn recon_case() -> BoxedStrategy<ReconCase> {
    let pixel = (
        surface(),
        shadow_bits(),
        material(),
        [radiance(), radiance(), radiance()],
    )
        .prop_map(|(geometry, shadow, albedo, colors)| ReconPixel {
            geometry,
            shadow,
            albedo,
            colors,
        });
    let radius = prop_oneof![8 => Just(1u16), 1 => Just(0u16), 1 => Just(2u16)];
    let tolerance = prop_oneof![6 => Just(ALBEDO_TOLERANCE), 2 => any_f32(0.0, 1.0)];
    (
        (
            sraa_params(),
            radius,
            0..RECON_W,
            0..RECON_H,
            any::<bool>(),
            tolerance,
        ),
        [surface(), surface(), surface(), surface()],
        [shadow_bits(), shadow_bits(), shadow_bits(), shadow_bits()],
        [material(), material(), material(), material()],
        prop::collection::vec(pixel, (RECON_W * RECON_H) as usize),
    )
        .prop_map(
            |((params, radius, x, y, gate, tolerance), geometry, shadow, albedo, pixels)| {
                ReconCase {
                    params: params.with_radius(radius),
                    x,
                    y,
                    gate,
                    tolerance,
                    targets: Subsamples {
                        geometry,
                        shadow,
                        albedo: Some(albedo),
                    },
                    pixels,
                }
            },
        )
        .boxed()
}

impl ReconCase {
    fn words(&self) -> Vec<u32> {
        let mut w = Vec::with_capacity(RECON_HEADER + RECON_PIXEL * self.pixels.len());
        w.extend(params_words(&self.params));
        w.extend([self.x, self.y, self.gate as u32, self.tolerance.to_bits()]);
        for g in &self.targets.geometry {
            w.extend(geometry_words(g));
        }
        w.extend(self.targets.shadow);
        for a in self.targets.albedo.unwrap() {
            w.extend(words(&a.to_array()));
        }
        assert_eq!(w.len(), RECON_HEADER);
        for p in &self.pixels {
            w.extend(geometry_words(&p.geometry));
            w.push(p.shadow);
            w.extend(words(&p.albedo.to_array()));
            for c in &p.colors {
                w.extend(words(&c.to_array()));
            }
        }
        w
    }

    /// The neighbourhood of subsample `k`, as `Resolver` reads it.
    fn hood(&self, k: usize) -> subcone_kernels::sraa::Neighbourhood {
        let p = &self.params;
        neighbourhood(
            self.x,
            self.y,
            k,
            p.shaded_offset(),
            p.radius(),
            RECON_W,
            RECON_H,
        )
    }

    /// Whether the material gate's decision for some subsample and
    /// neighbour lies within [`MATERIAL_GATE_NEAR`] of the tolerance, where
    /// a few ulps of WGSL `sqrt` decide it.
    fn gate_near_tolerance(&self) -> bool {
        let tol = self.tolerance;
        self.gate
            && tol.is_finite()
            && (0..4).any(|k| {
                let ai = self.targets.albedo.unwrap()[k];
                self.hood(k).any(|np| {
                    let aj = self.pixels[(np.y * RECON_W + np.x) as usize].albedo;
                    let d = albedo_difference(ai, aj);
                    // Equal albedos differ by exactly 0 on both sides.
                    ai != aj && d.is_finite() && (d - tol).abs() <= MATERIAL_GATE_NEAR
                })
            })
    }

    /// Subsample `k`'s layers, reconstructed and summed: what
    /// `subcone_sraa_reconstruct_run` returns.
    fn subsample(&self, k: usize) -> Vec3 {
        let samples = self.hood(k).map(|np| {
            let px = &self.pixels[(np.y * RECON_W + np.x) as usize];
            let s = LayeredSample {
                geometry: px.geometry,
                shadow: px.shadow,
                distance2: np.distance2,
                colors: &px.colors,
            };
            (s, px.albedo)
        });
        let (p, t) = (&self.params, &self.targets);
        let mut out = [Vec3::ZERO; 3];
        if self.gate {
            reconstruct_layers_material(
                p,
                &t.geometry[k],
                t.shadow[k],
                t.albedo.unwrap()[k],
                self.tolerance,
                &RECON_GATES,
                samples,
                &mut out,
            );
        } else {
            reconstruct_layers(
                p,
                &t.geometry[k],
                t.shadow[k],
                &RECON_GATES,
                samples.map(|(s, _)| s),
                &mut out,
            );
        }
        out.iter().fold(Vec3::ZERO, |a, c| a + *c)
    }

    /// The pixel through the kernels' `Resolver`, as the CPU backend runs it.
    fn resolve(&self) -> Vec3 {
        let geometry: Vec<Geometry> = self.pixels.iter().map(|p| p.geometry).collect();
        let shadow: Vec<u32> = self.pixels.iter().map(|p| p.shadow).collect();
        let albedo: Vec<Vec3> = if self.gate {
            self.pixels.iter().map(|p| p.albedo).collect()
        } else {
            Vec::new()
        };
        let colors: Vec<Vec3> = self.pixels.iter().flat_map(|p| p.colors).collect();
        let frame = ShadedFrame {
            width: RECON_W,
            height: RECON_H,
            colors: &colors,
            layers: RECON_GATES.len(),
            albedo: &albedo,
            primary: ShadedGroup {
                geometry: &geometry,
                shadow: &shadow,
                first_layer: 0,
            },
            secondary: None,
        };
        Resolver::new(&self.params, &RECON_GATES, self.tolerance).resolve(
            &frame,
            self.x,
            self.y,
            &self.targets,
            None,
        )
    }
}

/// The reconstruction loop every GPU resolve runs (`sraa::RECONSTRUCT_WGSL`,
/// `subcone_sraa_reconstruct_run`) against its Rust twin, on generated
/// pixels of a 4×3 image: each of the four subsamples' sum of layers
/// against [`reconstruct_layers`] (with the material gate,
/// [`reconstruct_layers_material`]) over [`neighbourhood`], within
/// [`TOL_RECONSTRUCT`], and their box resolve (`subcone_resolve_pixel`)
/// against the kernels' `Resolver`, the CPU backend's pass, within the same.
/// Eq. 1 with the spatial term, eq. 2's gate on two lights, the material
/// gate, misses, NaN geometry, non-finite colours, the fallback to the
/// nearest sample, radii 0 to 2 and pixels at the image's edges are all
/// drawn. Records where a material gate decision lies within
/// [`MATERIAL_GATE_NEAR`] of the tolerance are skipped and counted.
fn check_reconstruct(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let cases = generate(recon_case(), 12);
    let input: Vec<u32> = cases.iter().flat_map(|c| c.words()).collect();
    let in_words = RECON_HEADER + RECON_PIXEL * (RECON_W * RECON_H) as usize;
    let library = [lib.sraa.as_str(), &lib.reconstruct].concat();
    let out = run(
        ctx,
        &library,
        "let x = u(8u);
         let y = u(9u);
         let secondary = u(10u) == 0u;
         var s: array<vec3<f32>, 4>;
         for (var k = 0u; k < 4u; k++) {
             let tgt = subcone_Geometry(v3(12u + 4u * k), f(15u + 4u * k));
             s[k] = subcone_sraa_reconstruct_run(tgt, u(28u + k), v3(32u + 3u * k), secondary, 0u, x, y, k);
             out[o + 3u * k] = bitcast<u32>(s[k].x);
             out[o + 3u * k + 1u] = bitcast<u32>(s[k].y);
             out[o + 3u * k + 2u] = bitcast<u32>(s[k].z);
         }
         let c = subcone_resolve_pixel(s[0], s[1], s[2], s[3]);
         out[o + 12u] = bitcast<u32>(c.x); out[o + 13u] = bitcast<u32>(c.y); out[o + 14u] = bitcast<u32>(c.z);",
        in_words,
        15,
        &input,
    )?;
    let mut subsamples = Report::new("subcone_sraa_reconstruct_run");
    let mut pixels = Report::new("reconstruct_run + resolve_pixel (Resolver)");
    let (mut near, mut gated, mut fell_back) = (0usize, 0usize, 0usize);
    for (i, c) in cases.iter().enumerate() {
        if c.gate_near_tolerance() {
            near += 1;
            continue;
        }
        gated += c.gate as usize;
        let g = floats(&out[15 * i..15 * i + 15]);
        let case = (c.params, c.x, c.y, c.gate, c.tolerance);
        for k in 0..4 {
            let rust = c.subsample(k).to_array();
            subsamples.floats(TOL_RECONSTRUCT, &(case, k), &rust, &g[3 * k..3 * k + 3]);
        }
        pixels.floats(TOL_RECONSTRUCT, &case, &c.resolve().to_array(), &g[12..15]);
        // How often the weights underflow everywhere (the fallback).
        let t = &c.targets.geometry[0];
        if c.hood(0).all(|np| {
            let px = &c.pixels[(np.y * RECON_W + np.x) as usize];
            reconstruction_weight(&c.params, t, &px.geometry, np.distance2) == 0.0
        }) {
            fell_back += 1;
        }
    }
    let p = pixels.finish().map(|s| {
        format!(
            "{s} | {gated} records material-gated, {fell_back} whose subsample 0 has \
             no weight (the fallback); {near} within {MATERIAL_GATE_NEAR:e} of the tolerance \
             skipped"
        )
    });
    if fell_back * 100 < cases.len() || gated * 4 < cases.len() {
        return join(
            join(subsamples.finish(), p),
            Err(format!(
                "reconstruction: too few fallbacks ({fell_back}) or gated records ({gated})"
            )),
        );
    }
    join(subsamples.finish(), p)
}

/// CTSS eq. 4, 5, the minimum step, the advance, eq. 9–10 and §3.6's hard
/// hit, within [`TOL_CONE`] and [`TOL_OCCLUSION`], on generated inputs
/// and 20 000 awkward ones ([`awkward`]).
fn check_cone(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    // (t, d, tan θ, α, R_c, t_i): generated, t_i = t + R_c ...
    let mut cases: Vec<(f32, f32, f32, f32, f32, f32)> = generate(
        (
            any_f32(0.0, 1e3),
            any_f32(-1.0, 1.0),
            any_f32(0.0, 0.01),
            any_f32(0.0, 1.0),
            any_f32(0.0, 10.0),
        ),
        3,
    )
    .into_iter()
    .map(|(t, d, tan, alpha, rc)| (t, d, tan, alpha, rc, t + rc))
    .collect();
    // ... and awkward ones, signed and independent, over 1e-3..1e3 and the
    // specials (±0, ±∞, NaN, 1e-30, −1e30, f32::MAX), R_c = tan θ ≥ 0.
    let mut unit = unit_stream(0x9e37_79b9u32);
    for i in 0..20_000 {
        let t = awkward(i, &mut unit);
        let d = awkward(i + 1, &mut unit);
        let rc = awkward(i + 2, &mut unit).abs();
        let ti = awkward(i + 3, &mut unit);
        cases.push((t, d, rc, 0.5, rc, ti));
    }
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|&(t, d, tan, alpha, rc, ti)| {
            words(&[t, d, tan, alpha, rc, ti]).collect::<Vec<_>>()
        })
        .collect();
    let out = run(
        ctx,
        &lib.ctss,
        "let t = f(0u); let d = f(1u); let tan_theta = f(2u); let alpha = f(3u); let rc = f(4u);
         out[o] = bitcast<u32>(subcone_cone_radius(t, tan_theta));
         out[o + 1u] = bitcast<u32>(subcone_cone_occlusion(d, rc));
         out[o + 2u] = bitcast<u32>(subcone_min_step(alpha, rc));
         out[o + 3u] = bitcast<u32>(subcone_advance(t, d, alpha, rc));
         out[o + 4u] = bitcast<u32>(subcone_backtrace_cone_entry(t, tan_theta));
         out[o + 5u] = bitcast<u32>(subcone_backtrace_hard_hit(t, d, f(5u)));",
        6,
        6,
        &input,
    )?;
    let mut reports = [
        Report::new("subcone_cone_radius"),
        Report::new("subcone_cone_occlusion"),
        Report::new("subcone_min_step"),
        Report::new("subcone_advance"),
        Report::new("subcone_backtrace_cone_entry"),
        Report::new("subcone_backtrace_hard_hit"),
    ];
    for (i, c) in cases.iter().enumerate() {
        let &(t, d, tan, alpha, rc, ti) = c;
        let g = floats(&out[6 * i..6 * i + 6]);
        let rust = [
            cone_radius(t, tan),
            cone_occlusion(d, rc),
            min_step(alpha, rc),
            advance(t, d, alpha, rc),
            backtrace_cone_entry(t, tan),
            backtrace_hard_hit(t, d, ti),
        ];
        for (k, rep) in reports.iter_mut().enumerate() {
            let tol = if k == 1 { TOL_OCCLUSION } else { TOL_CONE };
            rep.floats(tol, c, &rust[k..k + 1], &g[k..k + 1]);
        }
    }
    reports
        .into_iter()
        .map(Report::finish)
        .reduce(join)
        .expect("reports")
}

/// The mask's line in f64 from a mask's inputs: `(dx, dy, h)` with the
/// covered side `q·(dx, dy) < h`, following `visibility_mask`'s steps
/// (`half_plane` and `half_plane_mask`'s clamp of `|dx| < 1e-6` to 0), or
/// `None` where no line exists (NaN occlusion, a zero or non-finite normal:
/// the mask is then all or nothing and must agree exactly).
fn mask_line(omega: f32, np: Vec2, placement: MaskPlacement) -> Option<(f64, f64, f64)> {
    let (x, y) = (np.x as f64, np.y as f64);
    let len = (x * x + y * y).sqrt();
    if omega.is_nan() || !len.is_finite() || len <= 0.0 {
        return None;
    }
    let (dx, dy) = (x / len, y / len);
    let delta = 1.0 - 2.0 * omega as f64;
    let h = match placement {
        MaskPlacement::Derived => -delta / len.min(1.0),
        MaskPlacement::AuthorsCode => -delta,
        MaskPlacement::PaperEq8 => delta * len.min(1.0),
    };
    let h = if h.is_nan() { -2.0 } else { h.clamp(-2.0, 2.0) };
    let dx = if dx.abs() < 1e-6 { 0.0 } else { dx };
    Some((dx, dy, h))
}

/// Distance from the centre of mask cell `bit` (mask.rs's layout: rows of
/// 4, 6, 6, 6, 6, 4 cells, centres `s·((2c+1)/6 − 1)`, `s = √(9π/32)`) to
/// the line, in units of the unit disk. With `dx` clamped the direction is
/// not unit: the distance is measured along it, as the kernel compares.
fn line_distance((dx, dy, h): (f64, f64, f64), bit: u32) -> f64 {
    let (row, col) = match bit {
        0..=3 => (0, bit + 1),
        4..=27 => (1 + (bit - 4) / 6, (bit - 4) % 6),
        _ => (5, bit - 28 + 1),
    };
    let s = (9.0 * std::f64::consts::PI / 32.0).sqrt();
    let x = s * ((2 * col + 1) as f64 / 6.0 - 1.0);
    let y = s * ((2 * row + 1) as f64 / 6.0 - 1.0);
    (x * dx + y * dy - h).abs()
}

/// A deterministic stream of uniform values in `[0, 1)` (xorshift32 from
/// `seed`), for hand-made inputs beside the generated ones.
fn unit_stream(seed: u32) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        (state >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// Eq. 7–8: the visibility mask, for all three line placements, with the
/// normal projected on the GPU (`project_normal`, [`TOL_PROJECT_NORMAL`]) on
/// generated 3D normals, and given directly on 20 000 random half-planes
/// (unit and shorter projected normals, 2 % awkward occlusions).
/// `needs_normal` is exact except within [`NEEDS_NORMAL_NEAR`] of its
/// threshold; `sample_weight` of each mask is exact. The mask follows the
/// rule of [`MASK_NEAR`], with at most [`MASK_NEAR_ROWS_PER_100`] % of masks
/// differing at all.
fn check_mask(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    // (ω, n, r, up, placement, direct n_p?, n_p)
    type Case = (f32, Vec3, Vec3, u32, Option<Vec2>);
    let mut cases: Vec<Case> = generate((any_f32(-0.2, 1.2), unit_vec(), unit_vec(), 0u32..3), 4)
        .into_iter()
        .map(|(omega, n, r, p)| (omega, n, r, p, None))
        .collect();
    let mut unit = unit_stream(0x2545_f491u32);
    for i in 0..20_000 {
        let omega = if i % 50 == 0 {
            awkward(i, &mut unit)
        } else {
            unit() * 1.4 - 0.2
        };
        let a = unit() * std::f32::consts::TAU;
        let len = if i % 3 == 0 { unit() } else { 1.0 };
        let np = Vec2::new(a.cos() * len, a.sin() * len);
        cases.push((omega, Vec3::Z, Vec3::X, (i % 3) as u32, Some(np)));
    }
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|&(omega, n, r, placement, direct)| {
            let up = r.cross(n).try_normalize().unwrap_or(Vec3::Y);
            let mut w: Vec<u32> = vec![omega.to_bits()];
            w.extend(words(&n.to_array()));
            w.extend(words(&r.to_array()));
            w.extend(words(&up.to_array()));
            w.push(placement);
            w.push(direct.is_some() as u32);
            w.extend(words(&direct.unwrap_or_default().to_array()));
            w
        })
        .collect();
    let out = run(
        ctx,
        &lib.ctss,
        "var np = subcone_project_normal(v3(1u), v3(4u), v3(7u));
         if u(11u) != 0u { np = vec2<f32>(f(12u), f(13u)); }
         let m = subcone_visibility_mask(f(0u), np, u(10u));
         out[o] = bitcast<u32>(np.x);
         out[o + 1u] = bitcast<u32>(np.y);
         out[o + 2u] = m;
         out[o + 3u] = select(0u, 1u, subcone_needs_normal(f(0u), u(10u)));
         out[o + 4u] = bitcast<u32>(subcone_sample_weight(countOneBits(m), subcone_WEIGHTING_VISIBILITY, 0.0));
         out[o + 5u] = bitcast<u32>(subcone_sample_weight(countOneBits(m), subcone_WEIGHTING_VISIBILITY, 0.01));",
        14,
        6,
        &input,
    )?;
    let mut proj = Report::new("subcone_project_normal");
    let mut mask = Report::new("subcone_visibility_mask");
    let mut needs = Report::new("subcone_needs_normal");
    let mut weight = Report::new("subcone_sample_weight (masks)");
    for (i, c) in cases.iter().enumerate() {
        let &(omega, n, r, code, direct) = c;
        let up = r.cross(n).try_normalize().unwrap_or(Vec3::Y);
        let placement = MaskPlacement::from_u32(code);
        let g = &out[6 * i..6 * i + 6];
        let np_gpu = Vec2::new(f32::from_bits(g[0]), f32::from_bits(g[1]));
        match direct {
            Some(np) => proj.exact(
                c,
                1,
                (np_gpu.to_array().map(f32::to_bits) == np.to_array().map(f32::to_bits)) as u32,
            ),
            None => {
                let np_rust = project_normal(n, r, up);
                proj.floats(
                    TOL_PROJECT_NORMAL,
                    c,
                    &np_rust.to_array(),
                    &np_gpu.to_array(),
                );
            }
        }
        // The mask is compared on the same projected normal (the GPU's), so
        // that a 1-ulp difference in the projection is not counted twice.
        let m = visibility_mask(omega, np_gpu, placement);
        mask.mask(c, mask_line(omega, np_gpu, placement), m, g[2]);
        let near = ((1.0 - 2.0 * omega).abs() - FARTHEST_CENTRE).abs() < NEEDS_NORMAL_NEAR;
        if !near {
            needs.exact(c, needs_normal(omega, placement) as u32, g[3]);
        }
        if m == g[2] {
            for (k, min_w) in [0.0, 0.01].into_iter().enumerate() {
                let w = sample_weight(m.count_ones(), Weighting::Visibility, min_w);
                weight.floats(TOL_SAMPLE_WEIGHT, c, &[w], &[f32::from_bits(g[4 + k])]);
            }
        }
    }
    let cap = cases.len() * MASK_NEAR_ROWS_PER_100 / 100;
    let near_rows = mask.near_boundary_rows;
    println!(
        "subcone_visibility_mask: {near_rows} of {} masks differ, each only at cells within {MASK_NEAR:e} of the line (at most {cap})",
        cases.len()
    );
    let cap_check = if near_rows <= cap {
        Ok(format!(
            "mask near-line differences: {near_rows} (cap {cap})"
        ))
    } else {
        Err(format!(
            "mask near-line differences: {near_rows} of {} inputs fail the cap of {cap}",
            cases.len()
        ))
    };
    [
        proj.finish(),
        mask.finish(),
        needs.finish(),
        weight.finish(),
        cap_check,
    ]
    .into_iter()
    .reduce(join)
    .expect("reports")
}

/// Eq. 6: sample weights and the weighted aggregation with the background as
/// a sample. Weights are exact (a count over 32). The aggregate is a weighted
/// mean of at most five colours, which the Rust kernel sums in f64 and WGSL
/// (without f64) in f32: within 1e-6 relative to the larger of 1 and the
/// values, over its domain of radiances (finite, non-negative colours below
/// 1e30, so no f32 sum can overflow). Outside that domain, both must return a
/// finite colour.
fn check_aggregate(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let colour = (any_f32(0.0, 4.0), any_f32(0.0, 4.0), any_f32(0.0, 4.0))
        .prop_map(|(r, g, b)| Vec3::new(r, g, b));
    let cases = generate(
        (
            prop::array::uniform4((any::<u32>(), colour.clone())),
            colour,
            any_f32(0.0, 1.0),
            0u32..2,
            prop_oneof![Just(0.0f32), Just(0.01f32)],
        ),
        5,
    );
    let mut input = Vec::new();
    for (samples, bg, bgw, weighting, min_w) in &cases {
        for (m, c) in samples {
            input.push(*m);
            input.extend(words(&c.to_array()));
        }
        input.extend(words(&bg.to_array()));
        input.extend([bgw.to_bits(), *weighting, min_w.to_bits()]);
    }
    let out = run(
        ctx,
        &lib.ctss,
        "var agg = subcone_aggregate_new();
         for (var k = 0u; k < 4u; k++) {
             let w = subcone_sample_weight(countOneBits(u(4u * k)), u(20u), f(21u));
             out[o + 3u + k] = bitcast<u32>(w);
             subcone_aggregate_add(&agg, w, v3(4u * k + 1u));
         }
         let c = subcone_aggregate_resolve(agg, v3(16u), f(19u));
         out[o] = bitcast<u32>(c.x); out[o + 1u] = bitcast<u32>(c.y); out[o + 2u] = bitcast<u32>(c.z);",
        22,
        7,
        &input,
    )?;
    let mut weights = Report::new("subcone_sample_weight");
    let mut agg_r = Report::new("subcone_aggregate_add (eq. 6)");
    for (i, c) in cases.iter().enumerate() {
        let (samples, bg, bgw, code, min_w) = c;
        let g = floats(&out[7 * i..7 * i + 7]);
        let mut agg = Aggregate::new();
        for (k, (m, col)) in samples.iter().enumerate() {
            let w = sample_weight(m.count_ones(), Weighting::from_u32(*code), *min_w);
            weights.floats(TOL_SAMPLE_WEIGHT, c, &[w], &g[3 + k..4 + k]);
            agg.add(w, *col);
        }
        let rust = agg.resolve(*bg, *bgw).to_array();
        let radiance = |v: &Vec3| v.is_finite() && v.min_element() >= 0.0 && v.max_element() < 1e30;
        if samples.iter().all(|s| radiance(&s.1)) && radiance(bg) {
            agg_r.floats(TOL_AGGREGATE, c, &rust, &g[..3]);
        } else {
            let finite = |v: &[f32]| v.iter().all(|x| x.is_finite());
            agg_r.exact(c, finite(&rust) as u32, finite(&g[..3]) as u32);
        }
    }
    join(weights.finish(), agg_r.finish())
}

/// FXAA (`fxaa_encode` and `fxaa_pixel` on the centre of a 7×7 patch,
/// which the edge search leaves and re-enters through the clamp).
///
/// Continuous random patches and straight edges between two random colours
/// at random angles compare within 1e-4 absolute (sRGB units; the WGSL `pow`
/// of the encoding is not correctly rounded, and its error moves the luma
/// by ~1e-6). An edge can put FXAA's end-of-edge test exactly on its
/// threshold (`|lumaEnd| >= gradient/4` with a quarter-pixel mix), where an
/// ulp decides the span: such inputs count as agreeing when the outputs still
/// lie within the same centre-and-neighbour range, and are reported. Patches of
/// any f32 bits (NaN, ±∞) must give a colour in [0, 1] on both sides.
fn check_fxaa(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    use subcone_kernels::fxaa::{fxaa_encode, fxaa_pixel, FxaaParams};
    let colour = (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0).prop_map(|(r, g, b)| Vec3::new(r, g, b));
    let patch = prop_oneof![
        // Continuous random patches.
        2 => prop::collection::vec(colour.clone(), 49).prop_map(|v| (v, 0u32)),
        // A straight edge between two colours.
        3 => (colour.clone(), colour, -1.0f32..1.0, -1.0f32..1.0, -3.0f32..3.0).prop_map(
            |(a, b, nx, ny, c)| {
                let v = (0..49)
                    .map(|i| {
                        let (x, y) = ((i % 7) as f32 - 3.0, (i / 7) as f32 - 3.0);
                        if nx * x + ny * y > c { a } else { b }
                    })
                    .collect();
                (v, 1u32)
            }
        ),
        // Any bits.
        1 => prop::collection::vec(
            (any_f32(0.0, 2.0), any_f32(0.0, 2.0), any_f32(0.0, 2.0))
                .prop_map(|(r, g, b)| Vec3::new(r, g, b)),
            49,
        )
        .prop_map(|v| (v, 2u32)),
    ];
    let params = prop_oneof![
        3 => Just(FxaaParams::QUALITY),
        1 => (0.0f32..=1.0, 0.063f32..=0.333, 0.0312f32..=0.0833).prop_map(|(s, t, m)| FxaaParams {
            subpix: s,
            edge_threshold: t,
            edge_threshold_min: m,
            _pad: 0.0,
        }),
    ];
    let cases = generate((patch, params), 6);
    let mut input = Vec::new();
    for ((px, _), p) in &cases {
        for c in px {
            input.extend(words(&c.to_array()));
        }
        input.extend(words(&[
            p.subpix,
            p.edge_threshold,
            p.edge_threshold_min,
            0.0,
        ]));
    }
    let out = run(
        ctx,
        &lib.fxaa,
        "let p = subcone_FxaaParams(f(147u), f(148u), f(149u), 0.0);
         let c = subcone_fxaa_pixel(3, 3, p);
         let e = fxaa_fetch(3, 3);
         out[o] = bitcast<u32>(c.x); out[o + 1u] = bitcast<u32>(c.y); out[o + 2u] = bitcast<u32>(c.z);
         out[o + 3u] = bitcast<u32>(e.x); out[o + 4u] = bitcast<u32>(e.y);
         out[o + 5u] = bitcast<u32>(e.z); out[o + 6u] = bitcast<u32>(e.w);",
        151,
        7,
        &input,
    )?;
    let mut enc = Report::new("subcone_fxaa_encode");
    let mut pix = Report::new("subcone_fxaa_pixel (FXAA 3.11)");
    let mut ties = 0;
    for (i, c) in cases.iter().enumerate() {
        let ((px, kind), p) = c;
        let g = floats(&out[7 * i..7 * i + 7]);
        let fetch = |x: i32, y: i32| fxaa_encode(px[(y.clamp(0, 6) * 7 + x.clamp(0, 6)) as usize]);
        let rust = fxaa_pixel(&fetch, 3, 3, p).to_array();
        let input = format!("kind {kind}, centre {:?}, params {p:?}", px[24]);
        if *kind == 2 {
            let ok = |v: &[f32]| v.iter().all(|x| (0.0..=1.0).contains(x));
            enc.exact(&input, 1, ok(&g[3..7]) as u32);
            pix.exact(&input, ok(&rust) as u32, ok(&g[..3]) as u32);
            continue;
        }
        // 8-bit levels: equal, or one level apart where the sRGB value lies
        // within an ulp of a rounding boundary.
        enc.floats(TOL_FXAA_ENCODE, &input, &fetch(3, 3).to_array(), &g[3..7]);
        let close = rust
            .iter()
            .zip(&g[..3])
            .all(|(a, b)| (a - b).abs() <= TOL_FXAA_PIXEL.limit() as f32);
        if !close && *kind == 1 {
            // A threshold tie: both must still blend the centre with a
            // direct neighbour.
            let cross = [
                fetch(3, 3),
                fetch(2, 3),
                fetch(4, 3),
                fetch(3, 2),
                fetch(3, 4),
            ];
            let lo = cross
                .iter()
                .fold(Vec3::splat(f32::MAX), |a, c| a.min(c.truncate()));
            let hi = cross
                .iter()
                .fold(Vec3::splat(f32::MIN), |a, c| a.max(c.truncate()));
            let gv = Vec3::from_slice(&g[..3]);
            if gv.cmpge(lo - 1e-4).all() && gv.cmple(hi + 1e-4).all() {
                ties += 1;
                continue;
            }
        }
        pix.floats(TOL_FXAA_PIXEL, &input, &rust, &g[..3]);
    }
    let limit = CASES / 100;
    let ties_line = format!("fxaa edge-threshold ties: {ties} of {CASES} (at most {limit})");
    let ties_ok = if ties <= limit {
        Ok(ties_line)
    } else {
        Err(ties_line)
    };
    join(join(enc.finish(), pix.finish()), ties_ok)
}

/// Deterministic points of an SDF scene: along random view rays of its
/// camera at random depths (where tracing evaluates), near the camera and far.
fn view_points(scene: &subcone_scene::sdf::SdfScene, n: usize) -> Vec<Vec3> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let cam = &scene.camera;
    let right = cam.right();
    let reach = scene.max_distance.min(60.0);
    (0..n)
        .map(|i| {
            let (u, v) = (2.0 * unit() - 1.0, 2.0 * unit() - 1.0);
            let dir = (cam.forward + 0.6 * u * right + 0.4 * v * cam.up).normalize();
            let t = if i % 4 == 0 {
                unit() * reach
            } else {
                unit() * unit() * reach * 0.5
            };
            cam.position + t * dir
        })
        .collect()
}

/// A tree with every operator and primitive, including those no built-in
/// scene uses (intersection, onion, round, guarded and infinite repetition,
/// scatter without a palette, uniform scale, an oblique plane).
fn every_operator() -> subcone_scene::sdf::SdfNode {
    use glam::Quat;
    use subcone_scene::sdf::{ScatterConfig, SdfNode};
    let n = |r: Result<SdfNode, _>| r.unwrap();
    let cone = n(SdfNode::capped_cone(0.5, 0.4, 0.1));
    let shapes = vec![
        n(SdfNode::intersection(vec![
            n(SdfNode::sphere(1.0)),
            n(SdfNode::cuboid(Vec3::splat(0.8))),
        ]))
        .with_material(1),
        n(n(SdfNode::torus(0.6, 0.2)).onion(0.05)).with_material(2),
        n(n(n(SdfNode::cuboid(Vec3::new(0.4, 0.2, 0.3))).round(0.1))
            .translate(Vec3::new(1.5, 0.0, 0.0)))
        .with_material(3),
        n(
            n(n(SdfNode::ellipsoid(Vec3::new(0.5, 0.3, 0.4))).translate(Vec3::new(2.0, 0.5, 1.0)))
                .mirror([true, false, true]),
        ),
        n(cone.clone().repeat(Vec3::new(2.0, 0.0, 2.0))),
        n(cone.repeat_limited(Vec3::new(0.0, 1.5, 0.0), [0, -2, 0], [0, 2, 0])),
        n(n(n(SdfNode::link(0.3, 0.3, 0.1)).scale(1.7)).rotate(Quat::from_rotation_z(0.3))),
        n(n(SdfNode::hex_prism(0.3, 0.4)).displace(0.05, 6.0)),
        n(n(SdfNode::octahedron(0.6)).scale_distance(0.5)),
        n(n(n(SdfNode::smooth_union(
            0.3,
            vec![
                n(SdfNode::capsule(0.4, 0.2)),
                n(SdfNode::rounded_cylinder(0.4, 0.3, 0.1)),
            ],
        ))
        .subtract(n(SdfNode::box_frame(Vec3::splat(0.35), 0.05))))
        .bounded(0.2)),
        n(SdfNode::scatter(
            ScatterConfig::new(Vec3::splat(1.2), [-2, 0, -2], [2, 1, 2], 7),
            vec![
                n(SdfNode::round_box(Vec3::new(0.5, 0.4, 0.3), 0.1)).with_material(4),
                n(SdfNode::cylinder(0.3, 0.5)).with_material(5),
            ],
        )),
        n(SdfNode::plane(Vec3::new(0.2, 1.0, -0.1), 3.0)).with_material(6),
    ];
    n(SdfNode::union(shapes))
}

/// The WGSL code generator (`WgslField::compile`, its scatter table bound as
/// `sdf_data`) against `SdfNode::eval` and `eval_split`: distances within
/// [`TOL_SDF_FIELD`], materials within [`SDF_MATERIAL_TIES_PER_200`].
fn check_sdf_field(
    ctx: &GpuContext,
    name: &str,
    root: &subcone_scene::sdf::SdfNode,
    pts: &[Vec3],
) -> Result<String, String> {
    let field = subcone_sdf::wgsl::WgslField::compile(root);
    let table = Table {
        name: "sdf_data",
        wgsl_type: "array<vec4<f32>>",
        bytes: bytemuck::cast_slice(&field.data),
    };
    let tables = if field.data.is_empty() {
        vec![]
    } else {
        vec![table]
    };
    let input: Vec<[f32; 3]> = pts.iter().map(|p| p.to_array()).collect();
    let out: Vec<[f32; 6]> = run_wgsl(
        ctx,
        &Kernel {
            library: &field.source,
            body: "let e = scene_sdf(v3(0u));
                   let s = scene_sdf_split(v3(0u));
                   out[o] = bitcast<u32>(e.x); out[o + 1u] = bitcast<u32>(e.y);
                   out[o + 2u] = bitcast<u32>(s.x); out[o + 3u] = bitcast<u32>(s.y);
                   out[o + 4u] = bitcast<u32>(s.z); out[o + 5u] = 0u;",
            in_words: 3,
            out_words: 6,
            tables: &tables,
        },
        &input,
    )
    .map_err(|e| format!("{name}: {e}"))?;
    let mut worst = 0.0f32;
    let mut ties = 0;
    let mut failures = Vec::new();
    for (p, g) in pts.iter().zip(&out) {
        let (d, m) = root.eval(*p);
        let subcone_scene::sdf::SplitDistance {
            safe,
            surface: surf,
            material: ms,
        } = root.eval_split(*p);
        let tol = |x: f32| TOL_SDF_FIELD * 1f32.max(x.abs()).max(p.abs().max_element() * 1e-2);
        for (want, have) in [(d, g[0]), (safe, g[2]), (surf, g[3])] {
            let ok = if want.is_infinite() {
                want == have
            } else {
                let e = (want - have).abs();
                worst = worst.max(e / tol(want));
                e <= tol(want)
            };
            if !ok && failures.len() < 5 {
                failures.push(format!("at {p}: cpu {want} gpu {have}"));
            }
        }
        ties += usize::from(m != g[1] as u32 || ms != g[4] as u32);
    }
    let line = format!(
        "sdf field {name:<14} {} points, worst {worst:.3} of the tolerance, {ties} material ties",
        pts.len()
    );
    if failures.is_empty() && ties * 200 <= pts.len() * SDF_MATERIAL_TIES_PER_200 {
        Ok(line)
    } else {
        Err(format!(
            "{line}
  {name}: inputs fail, e.g.:
  {}",
            failures.join("\n  ")
        ))
    }
}

/// Every paper and stiff SDF scene at 4096 view points, and [`every_operator`]
/// at 8192 points of a 12-unit cube.
#[test]
fn generated_sdf_wgsl_evaluates_the_same_field() {
    use subcone_scene::builtin::{sdf_builtin, SDF_SCENES, STIFF_SCENES};
    let Some(gpu) = gpu() else { return };
    let ctx = gpu.context();
    let mut results = Vec::new();
    for name in SDF_SCENES.iter().chain(STIFF_SCENES.iter()) {
        let scene = sdf_builtin(name).unwrap().unwrap();
        results.push(check_sdf_field(
            ctx,
            name,
            &scene.root,
            &view_points(&scene, 4096),
        ));
    }
    let mut state = 99u32;
    let mut unit = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    let pts: Vec<Vec3> = (0..8192)
        .map(|_| Vec3::new(unit(), unit(), unit()) * 12.0 - Vec3::splat(6.0))
        .collect();
    results.push(check_sdf_field(
        ctx,
        "every operator",
        &every_operator(),
        &pts,
    ));
    let all = results.into_iter().reduce(join).expect("results");
    match all {
        Ok(lines) => println!("{lines}"),
        Err(e) => panic!("generated SDF WGSL disagrees with SdfNode:\n{e}"),
    }
}

/// One row per SDF primitive: an example of the shape, and the WGSL function
/// of the generator's prelude that evaluates it (`None`: an inline formula).
/// The exhaustive `match` makes a new [`Shape`](subcone_scene::sdf::Shape)
/// variant a compile error here until it has its row.
fn primitive_table() -> Vec<(subcone_scene::sdf::Shape, Option<&'static str>)> {
    use subcone_scene::sdf::Shape;
    let shapes = [
        Shape::Sphere { radius: 0.7 },
        Shape::Box {
            half: Vec3::new(0.5, 0.3, 0.8),
        },
        Shape::RoundBox {
            half: Vec3::new(0.5, 0.3, 0.8),
            radius: 0.1,
        },
        Shape::BoxFrame {
            half: Vec3::new(0.5, 0.6, 0.4),
            thickness: 0.05,
        },
        Shape::Torus {
            major: 0.6,
            minor: 0.2,
        },
        Shape::Link {
            half_length: 0.3,
            major: 0.4,
            minor: 0.1,
        },
        Shape::Capsule {
            half_height: 0.5,
            radius: 0.2,
        },
        Shape::Cylinder {
            radius: 0.4,
            half_height: 0.6,
        },
        Shape::RoundedCylinder {
            radius: 0.4,
            half_height: 0.6,
            rounding: 0.1,
        },
        Shape::CappedCone {
            half_height: 0.5,
            bottom: 0.5,
            top: 0.2,
        },
        Shape::Octahedron { size: 0.6 },
        Shape::HexPrism {
            apothem: 0.4,
            half_height: 0.3,
        },
        Shape::Ellipsoid {
            radii: Vec3::new(0.5, 0.3, 0.8),
        },
        Shape::Plane {
            normal: Vec3::new(0.6, 0.0, 0.8),
            offset: -0.1,
        },
    ];
    shapes
        .into_iter()
        .map(|s| {
            let function = match s {
                Shape::Sphere { .. }
                | Shape::Torus { .. }
                | Shape::Link { .. }
                | Shape::Capsule { .. }
                | Shape::Plane { .. } => None,
                Shape::Box { .. } | Shape::RoundBox { .. } => Some("sd_box"),
                Shape::BoxFrame { .. } => Some("sd_box_frame"),
                Shape::Cylinder { .. } | Shape::RoundedCylinder { .. } => Some("sd_cylinder"),
                Shape::CappedCone { .. } => Some("sd_capped_cone"),
                Shape::Octahedron { .. } => Some("sd_octahedron"),
                Shape::HexPrism { .. } => Some("sd_hex_prism"),
                Shape::Ellipsoid { .. } => Some("sd_ellipsoid"),
            };
            (s, function)
        })
        .collect()
}

/// The points of the primitives' table: a 9×9×9 grid over `[−1.2, 1.2]³`
/// (inside, on and outside every example shape), the axes and the origin.
fn primitive_points() -> Vec<Vec3> {
    let mut pts: Vec<Vec3> = (0..9 * 9 * 9)
        .map(|i| {
            let c = |k: usize| -1.2 + 0.3 * k as f32;
            Vec3::new(c(i % 9), c(i / 9 % 9), c(i / 81))
        })
        .collect();
    for t in [0.0, 0.05, 0.25, 0.5, 1.0, 3.0] {
        pts.extend([Vec3::X * t, Vec3::Y * t, Vec3::Z * t, -Vec3::Y * t]);
    }
    pts
}

/// The WGSL primitives against the scalar ones (`Shape::distance`, which
/// is the 8-lane program's `lane::shape_distance` too), at one table: every
/// primitive has its row, its WGSL calls the prelude function the row names
/// and the prelude defines it, and on the GPU its distances at
/// [`primitive_points`] are the scalar's within [`TOL_SDF_FIELD`].
#[test]
fn wgsl_primitives_match_the_scalar_ones() {
    use subcone_scene::sdf::SdfNode;
    use subcone_sdf::wgsl::{shape_wgsl, WgslField};
    let table = primitive_table();
    let mut fields = Vec::new();
    for (shape, function) in &table {
        let expr = shape_wgsl(shape);
        let field = WgslField::compile(&SdfNode::shape(*shape).unwrap());
        assert!(
            field.source.contains(&expr),
            "{shape:?}: the generated field does not evaluate {expr}"
        );
        if let Some(name) = function {
            assert!(
                expr.starts_with(&format!("{name}(")) || expr.contains(&format!(" {name}(")),
                "{shape:?}: {expr} does not call {name}"
            );
            assert!(
                field.source.contains(&format!("fn {name}(")),
                "{shape:?}: no `fn {name}(` in the generated source"
            );
        } else {
            assert!(
                !expr.contains("sd_"),
                "{shape:?}: {expr} calls a function its row does not name"
            );
        }
        fields.push(field);
    }
    let Some(gpu) = gpu() else { return };
    let ctx = gpu.context();
    let pts = primitive_points();
    let input: Vec<[f32; 3]> = pts.iter().map(|p| p.to_array()).collect();
    let mut failures = Vec::new();
    let mut lines = Vec::new();
    for ((shape, _), field) in table.iter().zip(&fields) {
        let out: Vec<[f32; 2]> = run_wgsl(
            ctx,
            &Kernel {
                library: &field.source,
                body: "let e = scene_sdf(v3(0u));
                       out[o] = bitcast<u32>(e.x); out[o + 1u] = bitcast<u32>(e.y);",
                in_words: 3,
                out_words: 2,
                tables: &[],
            },
            &input,
        )
        .unwrap_or_else(|e| panic!("{shape:?}: {e}"));
        let mut worst = 0.0f32;
        for (p, g) in pts.iter().zip(&out) {
            let want = shape.distance(*p);
            let tol = TOL_SDF_FIELD * 1f32.max(want.abs()).max(p.abs().max_element() * 1e-2);
            let e = (want - g[0]).abs();
            worst = worst.max(e / tol);
            if (e.is_nan() || e > tol) && failures.len() < 10 {
                failures.push(format!("{shape:?} at {p}: scalar {want}, WGSL {}", g[0]));
            }
        }
        lines.push(format!("{shape:?}: worst {worst:.3} of the tolerance"));
    }
    println!("{} points per primitive\n{}", pts.len(), lines.join("\n"));
    assert!(
        failures.is_empty(),
        "WGSL primitives disagree:\n{}",
        failures.join("\n")
    );
}

/// The ambient-occlusion directions and fraction: `ao_direction` within
/// [`TOL_AO_DIRECTION`] for generated normals (non-finite and degenerate
/// ones included, which both sides map to the +Z frame), indices and counts
/// (beyond the count and zero included); `ao_fraction` within
/// [`TOL_AO_FRACTION`]. Every output must be finite on both sides.
fn check_ao(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let mut cases: Vec<(Vec3, u32, u32)> = generate((unit_vec(), 0u32..300, 0u32..300), 9);
    for n in ao_grid_normals() {
        for (i, count) in AO_GRID_INDICES {
            cases.push((n, i, count));
        }
    }
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|(n, i, c)| [n.x.to_bits(), n.y.to_bits(), n.z.to_bits(), *i, *c])
        .collect();
    let out = run(
        ctx,
        &lib.ao,
        "let d = subcone_ao_direction(v3(0u), u(3u), u(4u));
         out[o] = bitcast<u32>(d.x); out[o + 1u] = bitcast<u32>(d.y); out[o + 2u] = bitcast<u32>(d.z);
         out[o + 3u] = bitcast<u32>(subcone_ao_fraction(u(3u), u(4u)));",
        5,
        4,
        &input,
    )?;
    let mut dir = Report::new("subcone_ao_direction");
    let mut frac = Report::new("subcone_ao_fraction");
    for (k, (n, i, count)) in cases.iter().enumerate() {
        let g = floats(&out[4 * k..4 * k + 4]);
        let rust = ao_direction(*n, *i, *count).to_array();
        let finite = g.iter().all(|v| v.is_finite());
        if finite {
            dir.floats(TOL_AO_DIRECTION, &(n, i, count), &rust, &g[..3]);
        } else {
            dir.floats(TOL_AO_DIRECTION, &(n, i, count), &rust, &[f32::NAN; 3]);
        }
        frac.floats(
            TOL_AO_FRACTION,
            &(i, count),
            &[ao_fraction(*i, *count)],
            &g[3..],
        );
    }
    join(dir.finish(), frac.finish())
}

/// Whether opacity `alpha` puts `r·(1 − α) + ½` within [`TRANSPARENCY_NEAR`]
/// of an integer for some `r` in `1..=K`, where a fused multiply-add may round
/// to the other level.
fn alpha_near_level_boundary(alpha: f32) -> bool {
    use subcone_kernels::transparency::{clamp_alpha, LEVELS};
    let a = clamp_alpha(alpha) as f64;
    (1..=LEVELS).any(|r| {
        let x = r as f64 * (1.0 - a) + 0.5;
        let frac = x - x.floor();
        // Exactly on the boundary in f32 too (a product of a small integer
        // and a power-of-two fraction) rounds the same way everywhere.
        let exact = (r as f32 * (1.0 - clamp_alpha(alpha))) as f64 == r as f64 * (1.0 - a);
        !exact && (frac < TRANSPARENCY_NEAR || 1.0 - frac < TRANSPARENCY_NEAR)
    })
}

/// The K masks of CTSS §5.3 (`transparency.wgsl`): three composited surfaces
/// (random masks, opacities on and off the quarter levels' boundaries,
/// outside `[0, 1]`, ±∞ and NaN) from a clear pixel, then every query of the
/// accumulator, `remaining_after` for every `r`, `is_opaque`,
/// `level_weight` and `clamp_alpha`, against Rust.
fn check_transparency(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    use subcone_kernels::transparency::{
        clamp_alpha, is_opaque, level_weight, remaining_after, TransparencyAccumulator,
    };
    let special = [
        0.0f32,
        1.0,
        0.5,
        0.125,
        0.375,
        0.625,
        0.875,
        0.25,
        0.75,
        0.3,
        0.7,
        -0.5,
        1.5,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1e-30,
        -0.0,
    ];
    let alpha = prop_oneof![
        3 => any_f32(0.0, 1.0),
        2 => prop::sample::select(special.to_vec()),
        1 => any::<u32>().prop_map(f32::from_bits),
    ];
    let mask = prop_oneof![
        any::<u32>(),
        Just(u32::MAX),
        Just(0u32),
        (0u32..32).prop_map(|b| (1u64 << b) as u32 - 1),
    ];
    let cases = generate(
        (
            prop::array::uniform3((mask, alpha.clone())),
            0u32..8,
            0u32..200,
            0u32..40,
        ),
        10,
    );
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|(adds, r, g, bit)| {
            adds.iter()
                .flat_map(|(m, a)| [*m, a.to_bits()])
                .chain([*r, *g, *bit])
                .collect::<Vec<_>>()
        })
        .collect();
    const OUT: usize = 6 + 6 + 5 + 6 + 4;
    let out = run(
        ctx,
        &lib.transparency,
        "var acc = subcone_transparency_accumulator_new();
         for (var k = 0u; k < 3u; k++) {
             let vg = subcone_transparency_accumulator_add(&acc, u(2u * k), f(2u * k + 1u));
             out[o + 2u * k] = vg.x; out[o + 2u * k + 1u] = vg.y;
         }
         for (var k = 0u; k < 6u; k++) {
             out[o + 6u + k] = subcone_transparency_accumulator_plane(acc, k);
         }
         out[o + 12u] = subcone_transparency_accumulator_level(acc, u(8u));
         out[o + 13u] = select(0u, 1u, subcone_transparency_accumulator_is_binary(acc));
         out[o + 14u] = subcone_transparency_accumulator_opaque(acc);
         out[o + 15u] = subcone_transparency_accumulator_total_levels(acc);
         out[o + 16u] = subcone_transparency_accumulator_level_set(acc, u(6u) % 6u);
         for (var r = 0u; r < 6u; r++) {
             out[o + 17u + r] = subcone_remaining_after(r, f(1u));
         }
         out[o + 23u] = select(0u, 1u, subcone_is_opaque(f(1u)));
         out[o + 24u] = bitcast<u32>(subcone_level_weight(u(7u)));
         out[o + 25u] = bitcast<u32>(subcone_transparency_accumulator_uncovered_weight(acc));
         out[o + 26u] = bitcast<u32>(subcone_clamp_alpha(f(1u)));",
        9,
        OUT,
        &input,
    )?;
    let mut levels = Report::new("subcone_transparency_*");
    let mut weights = Report::new("subcone_level_weight");
    let mut near = 0usize;
    for (i, c) in cases.iter().enumerate() {
        let (adds, r_in, g_in, bit) = c;
        let g = &out[OUT * i..OUT * (i + 1)];
        let mut acc = TransparencyAccumulator::new();
        let mut rust = Vec::with_capacity(OUT);
        for (m, a) in adds {
            let (v, gained) = acc.add(*m, *a);
            rust.extend([v, gained]);
        }
        rust.extend((0..6).map(|k| acc.plane(k)));
        rust.extend([
            acc.level(*bit),
            acc.is_binary() as u32,
            acc.opaque(),
            acc.total_levels(),
            acc.level_set(r_in % 6),
        ]);
        let a0 = adds[0].1;
        rust.extend((0..6).map(|r| remaining_after(r, a0)));
        rust.push(is_opaque(a0) as u32);
        if adds.iter().any(|(_, a)| alpha_near_level_boundary(*a)) {
            near += 1;
        } else {
            for (k, (x, y)) in rust.iter().zip(&g[..24]).enumerate() {
                levels.exact(&(c, k), *x, *y);
            }
        }
        let wr = [level_weight(*g_in), acc.uncovered_weight(), clamp_alpha(a0)];
        let wg = floats(&g[24..27]);
        weights.floats(TOL_TRANSPARENCY_WEIGHT, c, &wr[..1], &wg[..1]);
        if !alpha_near_level_boundary(a0)
            && !adds.iter().any(|(_, a)| alpha_near_level_boundary(*a))
        {
            weights.floats(TOL_TRANSPARENCY_WEIGHT, c, &wr[1..], &wg[1..]);
        }
    }
    within_skip_budget(
        join(levels.finish(), weights.finish()),
        (near, cases.len()),
        "transparency",
        "records near a level boundary",
        "records near a level boundary, skipped",
    )
}

/// Steps of one [`check_stepper`] record.
const STEPPER_STEPS: usize = 24;

/// The stepper's translucent parts (CTSS §5.3) on both sides: a random
/// sequence of field values (distance, safe step, object 0 opaque or
/// 1, 2 semi-transparent, a request to split the open group or to end a
/// pass before the step, the mask to record) drives `advance_object`;
/// every sample is recorded through `record_alpha_mask` with its object's
/// opacity. Events, samples, weights, and the final stop, coverage,
/// background weight and counters are compared (see [`TOL_STEPPER`]).
fn check_stepper(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    use subcone_kernels::ctss::{ConeStepper, CtssParams, Event, StopReason};
    let step = (
        prop_oneof![
            6 => any_f32(-0.05, 0.15),
            1 => any_f32(0.15, 2.0),
            1 => Just(f32::NAN),
        ],
        prop_oneof![3 => Just(1.0f32), 1 => any_f32(0.0, 1.0)],
        0u32..3,
        0u32..8,
        any::<u32>(),
    );
    let alpha = prop_oneof![
        Just(0.5f32),
        Just(0.3f32),
        Just(1.0f32),
        Just(0.0f32),
        any_f32(0.0, 1.0),
        Just(f32::NAN),
    ];
    let cases = generate(
        (
            prop::collection::vec(step, STEPPER_STEPS),
            any_f32(0.005, 0.1),
            0u32..4,
            (alpha.clone(), alpha),
            prop_oneof![Just(32u32), 8u32..33],
            prop_oneof![3 => Just(8u32), 1 => 1u32..4],
        ),
        11,
    );
    let params_of = |tan: f32, flags: u32, k: u32, cap: u32| {
        let mut p = CtssParams::new(tan)
            .with_range(1.0, 50.0)
            .with_max_steps(20)
            .with_visibility_k(k)
            .relaxed(flags & 1 != 0)
            .paper(flags & 2 != 0);
        p.max_samples = cap;
        p
    };
    let mut input = Vec::new();
    for (steps, tan, flags, (a1, a2), k, cap) in &cases {
        let p = params_of(*tan, *flags, *k, *cap);
        input.extend(
            bytemuck::cast_slice::<CtssParams, u32>(&[p])
                .iter()
                .take(12),
        );
        input.extend([a1.to_bits(), a2.to_bits()]);
        for (d, frac, obj, req, mask) in steps {
            input.extend([d.to_bits(), (frac * d).to_bits(), obj | (req << 8), *mask]);
        }
    }
    const OUT: usize = 7 * STEPPER_STEPS + 6;
    let body = format!(
        "let p = subcone_CtssParams(f(0u), f(1u), f(2u), f(3u), f(4u), f(5u), u(6u), u(7u), u(8u), u(9u), 0u, 0u);
         var st = subcone_cone_stepper_new(p);
         for (var k = 0u; k < {STEPPER_STEPS}u; k++) {{
             let b = 14u + 4u * k;
             let obj = u(b + 2u) & 0xffu;
             let req = u(b + 2u) >> 8u;
             var alpha = 1.0;
             if obj == 1u {{ alpha = f(12u); }}
             if obj == 2u {{ alpha = f(13u); }}
             let ob = o + 7u * k;
             out[ob + 4u] = 0u; out[ob + 5u] = 0u; out[ob + 6u] = 0u;
             if (req & 1u) != 0u {{
                 let sp = subcone_cone_stepper_split_group(&st);
                 if sp.kind == subcone_EVENT_SAMPLE {{
                     let r = subcone_cone_stepper_record_alpha_mask(&st, u(b + 3u), alpha);
                     out[ob + 4u] = 1u + select(0u, 2u, subcone_cone_stepper_is_passing(st));
                     out[ob + 5u] = bitcast<u32>(sp.sample.t_exit);
                     out[ob + 6u] = r.y;
                 }}
             }}
             if (req & 2u) != 0u {{
                 subcone_cone_stepper_end_pass(&st);
             }}
             let ev = subcone_cone_stepper_advance_object(&st, f(b), f(b + 1u), obj);
             out[ob] = ev.kind + 4u * ev.reason + select(0u, 64u, subcone_cone_stepper_is_passing(st));
             out[ob + 1u] = bitcast<u32>(st.t);
             out[ob + 2u] = 0u; out[ob + 3u] = 0u;
             if ev.kind == subcone_EVENT_SAMPLE {{
                 let r = subcone_cone_stepper_record_alpha_mask(&st, u(b + 3u), alpha);
                 out[ob + 2u] = bitcast<u32>(ev.sample.t);
                 out[ob + 3u] = r.y;
                 out[ob] += 128u * (r.x & 0xffu);
             }}
         }}
         let e = o + 7u * {STEPPER_STEPS}u;
         out[e] = st.stop;
         out[e + 1u] = subcone_cone_stepper_coverage(st);
         out[e + 2u] = bitcast<u32>(subcone_cone_stepper_background_weight(st));
         out[e + 3u] = st.steps;
         out[e + 4u] = st.samples;
         out[e + 5u] = subcone_transparency_accumulator_total_levels(st.layers);"
    );
    let out = run(
        ctx,
        &lib.stepper,
        &body,
        14 + 4 * STEPPER_STEPS,
        OUT,
        &input,
    )?;
    let code = |r: Option<StopReason>| match r {
        None => 0u32,
        Some(StopReason::FullOcclusion) => 1,
        Some(StopReason::HardHit) => 2,
        Some(StopReason::VisibilityThreshold) => 3,
        Some(StopReason::SampleCap) => 4,
        Some(StopReason::MaxDistance) => 5,
        Some(StopReason::StepBudget) => 6,
        Some(StopReason::InvalidDistance) => 7,
        Some(s) => panic!("a stop reason this suite does not know: {s:?}"),
    };
    let mut exact = Report::new("subcone_cone_stepper_* (§5.3)");
    let mut depths = Report::new("  depths and weights");
    let mut parted = 0usize;
    for (i, c) in cases.iter().enumerate() {
        let (steps, tan, flags, (a1, a2), k, cap) = c;
        let p = params_of(*tan, *flags, *k, *cap);
        let g = &out[OUT * i..OUT * (i + 1)];
        let mut st = ConeStepper::new(&p);
        let mut rust = vec![0u32; OUT];
        let mut floats_r = Vec::new();
        let mut floats_g = Vec::new();
        for (k, (d, frac, obj, req, mask)) in steps.iter().enumerate() {
            let alpha = [1.0, *a1, *a2][*obj as usize];
            let ob = 7 * k;
            if req & 1 != 0 {
                if let Some(sp) = st.split_group() {
                    let (_, w) = st.record_alpha_mask(*mask, alpha);
                    rust[ob + 4] = 1 + if st.is_passing() { 2 } else { 0 };
                    rust[ob + 5] = sp.t_exit.to_bits();
                    rust[ob + 6] = w.to_bits();
                }
            }
            if req & 2 != 0 {
                st.end_pass();
            }
            let ev = st.advance_object(*d, frac * d, *obj);
            let (kind, reason) = match ev {
                Event::March => (0, 0),
                Event::Sample(_) => (1, 0),
                Event::Stop(r) => (2, code(Some(r))),
                e => panic!("an event this suite does not know: {e:?}"),
            };
            rust[ob] = kind + 4 * reason + if st.is_passing() { 64 } else { 0 };
            rust[ob + 1] = st.t().to_bits();
            if let Event::Sample(s) = ev {
                let (v, w) = st.record_alpha_mask(*mask, alpha);
                rust[ob + 2] = s.t.to_bits();
                rust[ob + 3] = w.to_bits();
                rust[ob] += 128 * (v & 0xff);
            }
            for j in [1, 2, 3, 5, 6] {
                floats_r.push(f32::from_bits(rust[ob + j]));
                floats_g.push(f32::from_bits(g[ob + j]));
            }
        }
        let e = 7 * STEPPER_STEPS;
        rust[e] = code(st.stop_reason());
        rust[e + 1] = st.coverage();
        rust[e + 2] = st.background_weight().to_bits();
        rust[e + 3] = st.steps();
        rust[e + 4] = st.samples();
        rust[e + 5] = st.layers().total_levels();
        floats_r.push(f32::from_bits(rust[e + 2]));
        floats_g.push(f32::from_bits(g[e + 2]));
        let codes = |w: &[u32]| -> Vec<u32> {
            (0..STEPPER_STEPS)
                .flat_map(|k| [w[7 * k], w[7 * k + 4]])
                .chain([w[e], w[e + 1], w[e + 3], w[e + 4], w[e + 5]])
                .collect()
        };
        let (cr, cg) = (codes(&rust), codes(g));
        let depth_error = floats_r
            .iter()
            .zip(&floats_g)
            .map(|(a, b)| TOL_STEPPER.error(*a, *b))
            .fold(0.0, f64::max);
        if cr != cg && depth_error > 0.0 {
            // An ulp of a depth moved a later decision: the traces parted.
            parted += 1;
            continue;
        }
        exact.exact(c, (cr == cg) as u32, 1);
        if cr != cg && exact.failures.len() <= 5 {
            exact
                .failures
                .push(format!("codes rust {cr:?}\n  codes wgsl {cg:?}"));
        }
        depths.floats(TOL_STEPPER, c, &floats_r, &floats_g);
    }
    within_skip_budget(
        join(exact.finish(), depths.finish()),
        (parted, cases.len()),
        "stepper",
        "traces part ways after an ulp of depth",
        "traces parted by an ulp of depth",
    )
}

/// The hooks of `ctss::TRACE_WGSL` for [`check_ctss_trace`]: four analytic
/// scenes chosen per record through `trace_scene` (the twin of
/// [`TraceScene`]), their tetrahedral normals (`subcone_tetra_normal`, the
/// `ConeField` default), a shading that depends on the normal, the point and
/// the direction, and a batch of 3 (so that traces shade in several rounds).
/// `ctss_field` is `ctss.wgsl`'s hook, which the trace does not use.
const TRACE_HOOKS: &str = "
var<private> trace_scene: u32;

fn trace_sd_box(p: vec3<f32>, c: vec3<f32>, b: vec3<f32>) -> f32 {
    let q = abs(p - c) - b;
    return length(max(q, vec3<f32>(0.0))) + min(max(q.x, max(q.y, q.z)), 0.0);
}

fn trace_nearest(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return select(b, a, a.x < b.x);
}

fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    var r: vec2<f32>;
    switch trace_scene {
        case 0u: { r = vec2<f32>(length(p - vec3<f32>(0.0, 0.0, 5.0)) - 1.0, 1.0); }
        case 1u: { r = vec2<f32>(trace_sd_box(p, vec3<f32>(0.0, 0.0, 5.0), vec3<f32>(0.8, 0.5, 0.6)), 2.0); }
        case 2u: {
            r = trace_nearest(vec2<f32>(length(p - vec3<f32>(0.3, 0.2, 3.5)) - 0.6, 1.0),
                vec2<f32>(trace_sd_box(p, vec3<f32>(0.0, 0.0, 5.0), vec3<f32>(1.0, 0.7, 0.5)), 2.0));
        }
        default: {
            r = trace_nearest(vec2<f32>(trace_sd_box(p, vec3<f32>(-0.6, 0.0, 4.0), vec3<f32>(0.6, 0.6, 0.01)), 3.0),
                vec2<f32>(trace_sd_box(p, vec3<f32>(0.5, 0.0, 5.0), vec3<f32>(0.01, 0.8, 1.5)), 4.0));
        }
    }
    return vec3<f32>(r.x, r.x, r.y);
}

fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> {
    return subcone_tetra_normal(p, h);
}

fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return (vec3<f32>(0.5) + 0.5 * n) * (0.5 + 0.1 * p.z) + vec3<f32>(0.25 * abs(dir.x), 0.0, 0.0);
}

const subcone_CTSS_BATCH: u32 = 3u;

fn ctss_field(p: vec3<f32>) -> vec2<f32> {
    let f = subcone_field(p);
    return f.xy;
}
";

/// The Rust twin of [`TRACE_HOOKS`]: scene 0 a sphere, 1 a box, 2 a sphere
/// in front of a box (two objects: groups end where the nearest changes), 3
/// two thin plates, one seen face-on, one obliquely (the thin-shell rule of
/// `group_mask`).
struct TraceScene(u32);

impl TraceScene {
    fn sd_box(p: Vec3, c: Vec3, b: Vec3) -> f32 {
        let q = (p - c).abs() - b;
        q.max(Vec3::ZERO).length() + q.x.max(q.y.max(q.z)).min(0.0)
    }

    fn nearest(a: (f32, u32), b: (f32, u32)) -> (f32, u32) {
        if a.0 < b.0 {
            a
        } else {
            b
        }
    }

    fn shade(p: Vec3, n: Vec3, dir: Vec3) -> Vec3 {
        (Vec3::splat(0.5) + 0.5 * n) * (0.5 + 0.1 * p.z) + Vec3::new(0.25 * dir.x.abs(), 0.0, 0.0)
    }
}

impl subcone_kernels::ctss::ConeField for TraceScene {
    fn sample(&mut self, p: Vec3) -> subcone_kernels::ctss::FieldSample {
        let (d, object) = match self.0 {
            0 => ((p - Vec3::new(0.0, 0.0, 5.0)).length() - 1.0, 1),
            1 => (
                Self::sd_box(p, Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.8, 0.5, 0.6)),
                2,
            ),
            2 => Self::nearest(
                ((p - Vec3::new(0.3, 0.2, 3.5)).length() - 0.6, 1),
                (
                    Self::sd_box(p, Vec3::new(0.0, 0.0, 5.0), Vec3::new(1.0, 0.7, 0.5)),
                    2,
                ),
            ),
            _ => Self::nearest(
                (
                    Self::sd_box(p, Vec3::new(-0.6, 0.0, 4.0), Vec3::new(0.6, 0.6, 0.01)),
                    3,
                ),
                (
                    Self::sd_box(p, Vec3::new(0.5, 0.0, 5.0), Vec3::new(0.01, 0.8, 1.5)),
                    4,
                ),
            ),
        };
        subcone_kernels::ctss::FieldSample {
            distance: d,
            step: d,
            object,
        }
    }
}

/// The whole CTSS trace, `subcone_ctss_trace` against `ctss::trace_field`
/// (march, group masks, §5.3 splits, eq. 6), on [`TraceScene`]'s four
/// scenes: rays from the origin through the scenes' silhouettes, edges and
/// plates (and past them), with random cone widths and the configurations
/// the renderers use: the default, `FLAG_PAPER`, `FLAG_SPLIT_GROUPS` with
/// and without it, CTSS-R, a visibility threshold, the authors' code.
/// Decisions exactly (up to [`CTSS_TRACE_FLIPS_PER_200`]), colours within
/// [`TOL_CTSS_TRACE`].
fn check_ctss_trace(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    use subcone_kernels::ctss::{trace_field, CtssParams, SplitRay};
    let configs: [fn(CtssParams) -> CtssParams; 7] = [
        |p| p,
        |p| p.paper(true),
        |p| p.with_split_groups(true),
        |p| p.with_split_groups(true).paper(true),
        |p| p.relaxed(true),
        |p| p.with_visibility_k(20).with_split_groups(true),
        |p| p.authors_code(),
    ];
    // Half the rays anywhere in view, half through the ring (at z = 5) where
    // the sphere's silhouette and the boxes' and plates' edges lie.
    let aim = prop_oneof![
        (-1.7f32..1.7, -1.3f32..1.3),
        (0.45f32..1.15, 0.0f32..std::f32::consts::TAU)
            .prop_map(|(r, a)| (r * a.cos(), r * a.sin())),
    ];
    let cases: Vec<(u32, (f32, f32), f32, usize)> =
        generate((0u32..4, aim, 0.003f32..0.04, 0usize..7), 11);
    let background = Vec3::new(0.1, 0.2, 0.9);
    let mut rays = Vec::new();
    let mut input = Vec::new();
    for &(scene, (x, y), tan, config) in &cases {
        let params = configs[config](CtssParams::new(tan))
            .with_range(0.0, 100.0)
            .with_max_steps(256);
        let dir = Vec3::new(x, y, 5.0).normalize();
        let ray = SplitRay::new(Vec3::ZERO, dir, Vec3::Y);
        input.extend(words(&[
            params.tan_theta,
            params.alpha,
            params.eps,
            params.t_min,
            params.t_max,
            params.min_sample_weight,
        ]));
        input.extend([
            params.max_steps,
            params.max_samples,
            params.visibility_k,
            params.flags,
            0,
            0,
        ]);
        for v in [ray.origin, ray.dir, ray.right, ray.up] {
            input.extend(words(&v.to_array()));
        }
        input.push(scene);
        rays.push((scene, params, ray));
    }
    let body = "trace_scene = u(24u);
         let params = subcone_CtssParams(f(0u), f(1u), f(2u), f(3u), f(4u), f(5u), u(6u), u(7u), u(8u), u(9u), 0u, 0u);
         let r = subcone_ctss_trace(params, v3(12u), v3(15u), v3(18u), v3(21u), vec3<f32>(0.1, 0.2, 0.9));
         out[o] = bitcast<u32>(r.color.x); out[o + 1u] = bitcast<u32>(r.color.y); out[o + 2u] = bitcast<u32>(r.color.z);
         out[o + 3u] = r.samples; out[o + 4u] = r.steps; out[o + 5u] = r.coverage; out[o + 6u] = r.stop;
         out[o + 7u] = bitcast<u32>(r.depth);";
    let library = [lib.ctss.as_str(), &lib.trace].concat();
    let out = run(ctx, &library, body, 25, 8, &input)?;
    let stop_code = |s: subcone_kernels::ctss::StopReason| {
        use subcone_kernels::ctss::StopReason::*;
        match s {
            FullOcclusion => 1,
            HardHit => 2,
            VisibilityThreshold => 3,
            SampleCap => 4,
            MaxDistance => 5,
            StepBudget => 6,
            InvalidDistance => 7,
            s => panic!("a stop reason this suite does not know: {s:?}"),
        }
    };
    let mut colour = Report::new("subcone_ctss_trace");
    let mut decisions = Report::new("subcone_ctss_trace (counts, mask, stop)");
    let mut depth = Report::new("subcone_ctss_trace (depth)");
    let mut flipped = Vec::new();
    let (mut split_rays, mut multi_group_rays) = (0usize, 0usize);
    for (k, (scene, params, ray)) in rays.iter().enumerate() {
        let g = &out[8 * k..8 * k + 8];
        let r = trace_field(
            params,
            ray,
            &mut TraceScene(*scene),
            TraceScene::shade,
            background,
        );
        let rust = [r.samples, r.steps, r.coverage, stop_code(r.stop)];
        let case = (scene, params.tan_theta, params.flags, ray.dir);
        if rust[..] != g[3..7] {
            flipped.push((case, rust, [g[3], g[4], g[5], g[6]]));
            continue;
        }
        if params.splits_groups() && r.samples > 1 {
            split_rays += 1;
        }
        if r.samples > 1 {
            multi_group_rays += 1;
        }
        decisions.exact(&case, 1, 1);
        colour.floats(TOL_CTSS_TRACE, &case, &r.color.to_array(), &floats(&g[..3]));
        // The nearest contributing group's depth: +∞ on both sides, or the
        // same depth up to the rounding of the march.
        let gpu_depth = f32::from_bits(g[7]);
        if r.depth.is_infinite() || gpu_depth.is_infinite() {
            depth.exact(&case, r.depth.to_bits(), g[7]);
        } else {
            depth.floats(TOL_CTSS_TRACE, &case, &[r.depth], &[gpu_depth]);
        }
    }
    // Too many flips: every one is a failure.
    if flipped.len() * 200 > rays.len() * CTSS_TRACE_FLIPS_PER_200 {
        for (case, rust, gpu) in &flipped {
            decisions.inputs += 1;
            decisions.failed += 1;
            decisions.worst = 1.0;
            if decisions.failures.len() < 5 {
                decisions.failures.push(format!(
                    "input {case:?}: rust (samples, steps, coverage, stop) {rust:?}, wgsl {gpu:?}"
                ));
            }
        }
    }
    let mut d = decisions.finish();
    if let Ok(line) = &mut d {
        let _ = write!(
            line,
            " | {} of {} rays with a flipped decision; {multi_group_rays} rays with several samples, {split_rays} of them with split groups",
            flipped.len(),
            rays.len()
        );
        // The check must exercise what it claims to.
        if multi_group_rays * 20 < rays.len() || split_rays * 50 < rays.len() {
            return Err(format!(
                "{line}\n  too few rays with several groups or splits"
            ));
        }
    }
    join(join(d, colour.finish()), depth.finish())
}

const CHECKS: [(&str, Check); 13] = [
    ("weights", check_weights),
    ("material", check_material),
    ("resolve", check_resolve),
    ("resolve_tone_mapped", check_resolve_tone_mapped),
    ("reconstruction", check_reconstruct),
    ("cone", check_cone),
    ("mask", check_mask),
    ("aggregate", check_aggregate),
    ("fxaa", check_fxaa),
    ("ao", check_ao),
    ("transparency", check_transparency),
    ("stepper", check_stepper),
    ("ctss trace", check_ctss_trace),
];

#[test]
fn wgsl_kernels_match_the_rust_kernels() {
    let Some(gpu) = gpu() else { return };
    let ctx = gpu.context();
    let lib = Library::shipped();
    let mut failed = Vec::new();
    for (name, check) in CHECKS {
        match check(ctx, &lib) {
            Ok(lines) => println!("{lines}"),
            Err(e) => {
                println!("{e}");
                failed.push(name);
            }
        }
    }
    assert!(
        failed.is_empty(),
        "WGSL kernels disagree with Rust: {failed:?}"
    );
}

/// The suite must notice a broken kernel: each perturbation below is a
/// plausible porting slip, applied to the shipped WGSL, and must make its
/// check fail.
#[test]
fn perturbed_kernels_are_caught() {
    let Some(gpu) = gpu() else { return };
    let ctx = gpu.context();
    let perturbations: [(&str, &str, &str, Check); 16] = [
        (
            "bilateral weight off by 1e-3",
            "return subcone_saturate(w);",
            "return subcone_saturate(w) + 1e-3;",
            check_weights,
        ),
        (
            "mask intercept sign flipped (the paper's eq. 8 slip)",
            "h = -delta / min(len, 1.0);",
            "h = delta / min(len, 1.0);",
            check_mask,
        ),
        (
            "occlusion off by a factor 2",
            "(1.0 - d / rc) * 0.5",
            "(1.0 - d / rc)",
            check_cone,
        ),
        (
            "shadow gate ignored",
            "if si != sj {",
            "if false {",
            check_weights,
        ),
        (
            "spatial term ignored",
            "spatial = distance2 / (params.sigma_s * params.sigma_s);",
            "spatial = 0.0;",
            check_weights,
        ),
        (
            "material gate ignored",
            "return d <= tolerance && d < subcone_inf();",
            "return true;",
            check_material,
        ),
        (
            "the reconstruction loop never gates a layer by its light's shadow (eq. 2)",
            "subcone_reconstruct_layers_add(&layer, w, i > 0u,",
            "subcone_reconstruct_layers_add(&layer, w, false,",
            check_reconstruct,
        ),
        (
            "the reconstruction loop ignores the material gate",
            "if !(SRAA_MATERIAL && !secondary) ||",
            "if true ||",
            check_reconstruct,
        ),
        (
            "FXAA's sub-pixel low-pass over 8 instead of 12 weights",
            "subpix_a * (1.0 / 12.0)",
            "subpix_a * (1.0 / 8.0)",
            check_fxaa,
        ),
        (
            "AO azimuth without its half-turn",
            "(frac - floor(frac)) - 3.1415927",
            "(frac - floor(frac))",
            check_ao,
        ),
        (
            "K-mask opacity rounded down instead of to nearest",
            "floor(f32(r) * (1.0 - a) + 0.5)",
            "floor(f32(r) * (1.0 - a))",
            check_transparency,
        ),
        (
            "K-mask composite forgets the cells outside the surface's mask",
            "var next = (*acc).planes & vec4<u32>(~mask);",
            "var next = vec4<u32>(0u);",
            check_transparency,
        ),
        (
            "the pass through a semi-transparent object steps by the distance inside it",
            "            step_by = -d;",
            "            step_by = m;",
            check_stepper,
        ),
        (
            "a semi-transparent full occlusion ends the trace",
            "        (*s).stop = subcone_STOP_NONE;\n        (*s).passing = 1u;",
            "        (*s).passing = 0u;",
            check_stepper,
        ),
        (
            "CTSS group masks from the sample normal instead of the peak's",
            "let peak = subcone_group_normal_at(ray, sample, normal, sample.t_occlusion, tan);",
            "let peak = normal;",
            check_ctss_trace,
        ),
        (
            "ctss+edges never splits",
            "if subcone_group_needs_split(hit.normal",
            "if false && subcone_group_needs_split(hit.normal",
            check_ctss_trace,
        ),
    ];
    for (what, from, to, check) in perturbations {
        let shipped = Library::shipped();
        assert!(
            shipped.sraa.contains(from)
                || shipped.reconstruct.contains(from)
                || shipped.ctss.contains(from)
                || shipped.trace.contains(from)
                || shipped.fxaa.contains(from)
                || shipped.ao.contains(from)
                || shipped.transparency.contains(from)
                || shipped.stepper.contains(from),
            "perturbation {what:?}: {from:?} is not in the shipped WGSL any more; update the test"
        );
        let lib = Library {
            sraa: shipped.sraa.replacen(from, to, 1),
            reconstruct: shipped.reconstruct.replacen(from, to, 1),
            ctss: shipped.ctss.replacen(from, to, 1),
            trace: shipped.trace.replacen(from, to, 1),
            fxaa: shipped.fxaa.replacen(from, to, 1),
            ao: shipped.ao.replacen(from, to, 1),
            transparency: shipped.transparency.replacen(from, to, 1),
            stepper: shipped.stepper.replacen(from, to, 1),
        };
        match check(ctx, &lib) {
            Ok(_) => panic!("perturbation {what:?} went unnoticed"),
            Err(e) => {
                let failing: Vec<&str> = e.lines().filter(|l| l.contains("fail")).collect();
                println!("caught {what}: {}", failing.join("; "));
            }
        }
    }
}
