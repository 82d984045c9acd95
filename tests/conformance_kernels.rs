//! Kernel-level conformance: every WGSL kernel the kernels crate ships, run in a
//! compute shader over thousands of proptest-generated inputs (the stiff and
//! extreme domain included: zeros, subnormals, 1e±30, `f32::MAX`, ±∞, NaN),
//! against the Rust kernel it mirrors.
//!
//! How outputs are compared, per kind:
//! - **gates and codes** (the shadow gate of eq. 2, `needs_normal`): exactly;
//! - **masks** (`visibility_mask`): bit for bit, except that a row may differ
//!   by one cell where its edge lies within a few ulps of a cell centre (WGSL
//!   allows inexact division, flushed subnormals and fused multiply-adds, so a
//!   1-ulp difference can flip that cell); such rows are counted and reported;
//! - **floats**: within a stated tolerance, in ulps or absolute, per kernel;
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
use subcone_kernels::aggregate::{sample_weight, Aggregate, Weighting};
use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, min_step,
};
use subcone_kernels::mask::{needs_normal, project_normal, visibility_mask, MaskPlacement};
use subcone_kernels::sraa::{
    albedo_difference, bilateral_weight, material_gated_weight, resolve_pixel, shadow_gated_weight,
    DepthMetric, Geometry, SraaParams, WeightForm, ALBEDO_TOLERANCE,
};
use subcone_wgpu::GpuContext;

/// Inputs per kernel.
const CASES: usize = 4096;

fn gpu() -> Option<std::sync::Arc<GpuContext>> {
    match GpuContext::shared() {
        Ok(c) => Some(c),
        Err(e) if !subcone_wgpu::gpu_required() => {
            eprintln!("SKIPPED: no GPU adapter and SUBCONE_REQUIRE_GPU unset: {e}");
            None
        }
        Err(e) => panic!("no GPU adapter (SUBCONE_REQUIRE_GPU is set): {e}"),
    }
}

/// Run `body` once per input record on the GPU. `body` is WGSL that reads the
/// record through `f(k)` (word `k` as `f32`) and `u(k)` (as `u32`) and writes
/// `out[o + j]`. Returns the output words, or the shader error.
fn run_wgsl(
    ctx: &GpuContext,
    library: &str,
    body: &str,
    in_words: usize,
    out_words: usize,
    input: &[u32],
) -> Result<Vec<u32>, String> {
    use wgpu::util::DeviceExt;
    let n = input.len() / in_words;
    let source = format!(
        "{library}\n\
         @group(0) @binding(0) var<storage, read> inp: array<u32>;\n\
         @group(0) @binding(1) var<storage, read_write> out: array<u32>;\n\
         var<private> b: u32;\n\
         fn f(k: u32) -> f32 {{ return bitcast<f32>(inp[b + k]); }}\n\
         fn u(k: u32) -> u32 {{ return inp[b + k]; }}\n\
         fn v3(k: u32) -> vec3<f32> {{ return vec3<f32>(f(k), f(k + 1u), f(k + 2u)); }}\n\
         @compute @workgroup_size(64)\n\
         fn main(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
             let i = gid.x;\n\
             if i >= {n}u {{ return; }}\n\
             b = i * {in_words}u;\n\
             let o = i * {out_words}u;\n\
             {body}\n\
         }}\n"
    );
    let device = &ctx.device;
    let result = ctx.scoped("kernel conformance", || {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("kernel conformance"),
            source: wgpu::ShaderSource::Wgsl(source.as_str().into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("kernel conformance"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let inp = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("inputs"),
            contents: bytemuck::cast_slice(input),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let size = (n * out_words * 4) as u64;
        let out = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("outputs"),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: inp.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: out.as_entire_binding(),
                },
            ],
        });
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(n.div_ceil(64) as u32, 1, 1);
        }
        ctx.queue.submit([enc.finish()]);
        (out, size)
    });
    let (out, size) = result.map_err(|e| e.to_string())?;
    ctx.wait("kernel conformance").map_err(|e| e.to_string())?;
    let bytes = ctx.read_buffer(&out, 0, size).map_err(|e| e.to_string())?;
    Ok(bytemuck::cast_slice(&bytes).to_vec())
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

fn ulps(a: f32, b: f32) -> u32 {
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

/// How two floats may differ.
#[derive(Clone, Copy, Debug)]
enum Tol {
    /// At most this many ulps apart (or both NaN).
    Ulps(u32),
    /// `|a − b| ≤ abs`, or at most 4 ulps apart (or both NaN).
    Abs(f32),
    /// `|a − b| ≤ rel · max(1, |a|, |b|)` (or both NaN).
    Rel(f32),
}

impl Tol {
    fn error(self, a: f32, b: f32) -> f64 {
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

    fn limit(self) -> f64 {
        match self {
            Tol::Ulps(u) => u as f64,
            Tol::Abs(a) | Tol::Rel(a) => a as f64,
        }
    }
}

/// One kernel's comparison: the worst case, and the failures.
struct Report {
    kernel: &'static str,
    worst: f64,
    worst_case: String,
    failures: Vec<String>,
    failed: usize,
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
            near_boundary_rows: 0,
        }
    }

    fn floats(&mut self, tol: Tol, input: &dyn std::fmt::Debug, rust: &[f32], gpu: &[f32]) {
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
        if rust != gpu {
            self.worst = 1.0;
            self.failed += 1;
            if self.failures.len() < 5 {
                self.failures
                    .push(format!("input {input:?}: rust {rust}, wgsl {gpu}"));
            }
        }
    }

    /// Masks: the rows of the 32-bit mask (4, 6, 6, 6, 6, 4 cells).
    fn mask(&mut self, input: &dyn std::fmt::Debug, rust: u32, gpu: u32) {
        const ROWS: [(u32, u32); 6] = [(0, 4), (4, 6), (10, 6), (16, 6), (22, 6), (28, 4)];
        let diff = rust ^ gpu;
        let mut worst_row = 0;
        for (shift, len) in ROWS {
            let d = ((diff >> shift) & ((1 << len) - 1)).count_ones();
            worst_row = worst_row.max(d);
            if d == 1 {
                self.near_boundary_rows += 1;
            }
        }
        let e = worst_row as f64;
        if e > self.worst {
            self.worst = e;
            self.worst_case = format!("input {input:?}: rust {rust:#010x}, wgsl {gpu:#010x}");
        }
        if worst_row > 1 {
            self.failed += 1;
        }
        if worst_row > 1 && self.failures.len() < 5 {
            self.failures.push(format!(
                "input {input:?}: rust {rust:#010x}, wgsl {gpu:#010x} ({worst_row} cells of one row differ)"
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
                " | rows differing by one cell at a boundary: {} of {}",
                self.near_boundary_rows,
                CASES * 6
            );
        }
        if self.failures.is_empty() {
            Ok(line)
        } else {
            Err(format!(
                "{line}\n  {}: {} of {CASES} inputs fail, e.g.:\n  {}",
                self.kernel,
                self.failed,
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

/// The WGSL library under test: `PARAMS` plus the given kernel sources.
struct Library {
    sraa: String,
    ctss: String,
    fxaa: String,
}

impl Library {
    fn shipped() -> Self {
        use subcone_kernels::*;
        Library {
            sraa: [wgsl::PARAMS, sraa::WGSL].concat(),
            ctss: [wgsl::PARAMS, cone::WGSL, mask::WGSL, aggregate::WGSL].concat(),
            fxaa: [wgsl::PARAMS, FXAA_FETCH, fxaa::WGSL].concat(),
        }
    }
}

/// The pixel fetch `fxaa.wgsl` expects from its including shader: a 7×7
/// patch of linear colours (the record's first 147 words, row-major),
/// clamped to its edge and encoded as the backends encode frames.
const FXAA_FETCH: &str = "
fn fxaa_fetch(x: i32, y: i32) -> vec4<f32> {
    let cx = u32(clamp(x, 0, 6));
    let cy = u32(clamp(y, 0, 6));
    return fxaa_encode(v3(3u * (cy * 7u + cx)));
}
";

type Check = fn(&GpuContext, &Library) -> Result<String, String>;

fn sraa_params() -> BoxedStrategy<SraaParams> {
    prop_oneof![
        6 => Just(SraaParams::PAPER),
        2 => Just(SraaParams::CHAJDAS),
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

fn params_words(p: &SraaParams) -> [u32; 4] {
    [
        p.sigma_z.to_bits(),
        p.sigma_n.to_bits(),
        p.scale.to_bits(),
        p.packed,
    ]
}

fn geometry_words(g: &Geometry) -> [u32; 4] {
    [
        g.normal.x.to_bits(),
        g.normal.y.to_bits(),
        g.normal.z.to_bits(),
        g.depth.to_bits(),
    ]
}

/// Eq. 1 and eq. 2. Weights are in [0, 1]: the Rust kernel is within 2e-6 of
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
    );
    let mut input = Vec::new();
    for (p, gi, gj, si, sj) in &cases {
        input.extend(params_words(p));
        input.extend(geometry_words(gi));
        input.extend(geometry_words(gj));
        input.extend([*si as u32, *sj as u32]);
    }
    let out = run_wgsl(
        ctx,
        &lib.sraa,
        "let p = SraaParams(f(0u), f(1u), f(2u), u(3u));
         let gi = Geometry(v3(4u), f(7u));
         let gj = Geometry(v3(8u), f(11u));
         out[o] = bitcast<u32>(bilateral_weight(p, gi, gj));
         out[o + 1u] = bitcast<u32>(shadow_gated_weight(p, gi, gj, u(12u) != 0u, u(13u) != 0u));",
        14,
        2,
        &input,
    )?;
    let mut bilateral = Report::new("bilateral_weight");
    let mut gated = Report::new("shadow_gated_weight");
    for (i, c) in cases.iter().enumerate() {
        let (p, gi, gj, si, sj) = c;
        let g = floats(&out[2 * i..2 * i + 2]);
        bilateral.floats(Tol::Abs(4e-6), c, &[bilateral_weight(p, gi, gj)], &g[..1]);
        let r = shadow_gated_weight(p, gi, gj, *si, *sj);
        if si != sj {
            gated.exact(c, r.to_bits(), g[1].to_bits());
        } else {
            gated.floats(Tol::Abs(4e-6), c, &[r], &g[1..]);
        }
    }
    let a = bilateral.finish();
    let b = gated.finish();
    join(a, b)
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
    let out = run_wgsl(
        ctx,
        &lib.sraa,
        "let p = SraaParams(f(0u), f(1u), f(2u), u(3u));
         let gi = Geometry(v3(4u), f(7u));
         let gj = Geometry(v3(8u), f(11u));
         out[o] = bitcast<u32>(albedo_difference(v3(12u), v3(15u)));
         out[o + 1u] = bitcast<u32>(material_gated_weight(p, gi, gj, v3(12u), v3(15u), f(18u)));",
        19,
        2,
        &input,
    )?;
    let mut diff = Report::new("albedo_difference");
    let mut gated = Report::new("material_gated_weight");
    let mut near = 0;
    for (i, c) in cases.iter().enumerate() {
        let (p, gi, gj, (ai, aj), tol) = c;
        let g = floats(&out[2 * i..2 * i + 2]);
        let d = albedo_difference(*ai, *aj);
        let domain = |a: &Vec3| a.is_finite() && a.max_element() <= 4.0;
        if domain(ai) && domain(aj) {
            diff.floats(Tol::Abs(1e-6), c, &[d], &g[..1]);
        } else {
            diff.exact(c, d.is_infinite() as u32, g[0].is_infinite() as u32);
        }
        if d.is_finite() && tol.is_finite() && (d - tol).abs() <= 1e-5 {
            near += 1;
            continue;
        }
        let r = material_gated_weight(p, gi, gj, *ai, *aj, *tol);
        if !(d <= *tol && d.is_finite()) {
            gated.exact(c, r.to_bits(), g[1].to_bits());
        } else {
            gated.floats(Tol::Abs(4e-6), c, &[r], &g[1..]);
        }
    }
    let b = gated
        .finish()
        .map(|s| format!("{s} ({near} cases within 1e-5 of the tolerance skipped)"));
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
    let out = run_wgsl(
        ctx,
        &lib.sraa,
        "let c = resolve_pixel(v3(0u), v3(3u), v3(6u), v3(9u));
         out[o] = bitcast<u32>(c.x); out[o + 1u] = bitcast<u32>(c.y); out[o + 2u] = bitcast<u32>(c.z);",
        12,
        3,
        &input,
    )?;
    let mut r = Report::new("resolve_pixel");
    for (i, c) in cases.iter().enumerate() {
        let rust = resolve_pixel(c).to_array();
        // Colours this large overflow the sum on one side and not the other;
        // the documented contract (finite colours) excludes them.
        let huge = c.iter().any(|v| v.is_finite() && v.max_element() > 1e37);
        if !huge {
            r.floats(Tol::Abs(1e-6), c, &rust, &floats(&out[3 * i..3 * i + 3]));
        }
    }
    r.finish()
}

/// CTSS eq. 4, 5, the minimum step, the advance, eq. 9–10 and §3.6's hard
/// hit. Each is a handful of roundings: within 4 ulps (the Rust kernels are
/// within 2–4 ulps of f64, kernels/tests/f64_reference.rs), except the
/// occlusion, which divides and subtracts from 1: within 2e-6 absolute (twice
/// its f64 bound of 1e-6).
fn check_cone(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let cases = generate(
        (
            any_f32(0.0, 1e3),
            any_f32(-1.0, 1.0),
            any_f32(0.0, 0.01),
            any_f32(0.0, 1.0),
            any_f32(0.0, 10.0),
        ),
        3,
    );
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|&(t, d, tan, alpha, rc)| words(&[t, d, tan, alpha, rc]).collect::<Vec<_>>())
        .collect();
    let out = run_wgsl(
        ctx,
        &lib.ctss,
        "let t = f(0u); let d = f(1u); let tan_theta = f(2u); let alpha = f(3u); let rc = f(4u);
         out[o] = bitcast<u32>(cone_radius(t, tan_theta));
         out[o + 1u] = bitcast<u32>(cone_occlusion(d, rc));
         out[o + 2u] = bitcast<u32>(min_step(alpha, rc));
         out[o + 3u] = bitcast<u32>(advance(t, d, alpha, rc));
         out[o + 4u] = bitcast<u32>(backtrace_cone_entry(t, tan_theta));
         out[o + 5u] = bitcast<u32>(backtrace_hard_hit(t, d, t + rc));",
        5,
        6,
        &input,
    )?;
    let mut reports = [
        Report::new("cone_radius"),
        Report::new("cone_occlusion"),
        Report::new("min_step"),
        Report::new("advance"),
        Report::new("backtrace_cone_entry"),
        Report::new("backtrace_hard_hit"),
    ];
    for (i, c) in cases.iter().enumerate() {
        let &(t, d, tan, alpha, rc) = c;
        let g = floats(&out[6 * i..6 * i + 6]);
        let rust = [
            cone_radius(t, tan),
            cone_occlusion(d, rc),
            min_step(alpha, rc),
            advance(t, d, alpha, rc),
            backtrace_cone_entry(t, tan),
            backtrace_hard_hit(t, d, t + rc),
        ];
        for (k, rep) in reports.iter_mut().enumerate() {
            let tol = if k == 1 { Tol::Abs(2e-6) } else { Tol::Ulps(4) };
            rep.floats(tol, c, &rust[k..k + 1], &g[k..k + 1]);
        }
    }
    reports
        .into_iter()
        .map(Report::finish)
        .reduce(join)
        .expect("reports")
}

/// Eq. 7–8: the visibility mask, for all three line placements, with the
/// normal projected on the GPU as well (`project_normal`, within 4 ulps or
/// 1e-6) and `needs_normal` (exact, except where |d/R_c| lies within 1e-5 of
/// the farthest cell centre, where one rounding decides it).
fn check_mask(ctx: &GpuContext, lib: &Library) -> Result<String, String> {
    let cases = generate((any_f32(-0.2, 1.2), unit_vec(), unit_vec(), 0u32..3), 4);
    let input: Vec<u32> = cases
        .iter()
        .flat_map(|&(omega, n, r, placement)| {
            let up = r.cross(n).try_normalize().unwrap_or(Vec3::Y);
            let mut w: Vec<u32> = vec![omega.to_bits()];
            w.extend(words(&n.to_array()));
            w.extend(words(&r.to_array()));
            w.extend(words(&up.to_array()));
            w.push(placement);
            w
        })
        .collect();
    let out = run_wgsl(
        ctx,
        &lib.ctss,
        "let np = project_normal(v3(1u), v3(4u), v3(7u));
         out[o] = bitcast<u32>(np.x);
         out[o + 1u] = bitcast<u32>(np.y);
         out[o + 2u] = visibility_mask(f(0u), np, u(10u));
         out[o + 3u] = select(0u, 1u, needs_normal(f(0u), u(10u)));",
        11,
        4,
        &input,
    )?;
    let mut proj = Report::new("project_normal");
    let mut mask = Report::new("visibility_mask");
    let mut needs = Report::new("needs_normal");
    for (i, c) in cases.iter().enumerate() {
        let &(omega, n, r, code) = c;
        let up = r.cross(n).try_normalize().unwrap_or(Vec3::Y);
        let placement = MaskPlacement::from_u32(code);
        let g = &out[4 * i..4 * i + 4];
        let np_rust = project_normal(n, r, up);
        let np_gpu = Vec2::new(f32::from_bits(g[0]), f32::from_bits(g[1]));
        proj.floats(Tol::Abs(1e-6), c, &np_rust.to_array(), &np_gpu.to_array());
        // The mask is compared on the same projected normal (the GPU's), so
        // that a 1-ulp difference in the projection is not counted twice.
        mask.mask(c, visibility_mask(omega, np_gpu, placement), g[2]);
        let near = ((1.0 - 2.0 * omega).abs() - 0.9399856 * 0.9718253).abs() < 1e-5;
        if !near {
            needs.exact(c, needs_normal(omega, placement) as u32, g[3]);
        }
    }
    [proj.finish(), mask.finish(), needs.finish()]
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
    let out = run_wgsl(
        ctx,
        &lib.ctss,
        "var agg = aggregate_new();
         for (var k = 0u; k < 4u; k++) {
             let w = sample_weight(countOneBits(u(4u * k)), u(20u), f(21u));
             out[o + 3u + k] = bitcast<u32>(w);
             aggregate_add(&agg, w, v3(4u * k + 1u));
         }
         let c = aggregate_resolve(agg, v3(16u), f(19u));
         out[o] = bitcast<u32>(c.x); out[o + 1u] = bitcast<u32>(c.y); out[o + 2u] = bitcast<u32>(c.z);",
        22,
        7,
        &input,
    )?;
    let mut weights = Report::new("sample_weight");
    let mut agg_r = Report::new("Aggregate (eq. 6)");
    for (i, c) in cases.iter().enumerate() {
        let (samples, bg, bgw, code, min_w) = c;
        let g = floats(&out[7 * i..7 * i + 7]);
        let mut agg = Aggregate::new();
        for (k, (m, col)) in samples.iter().enumerate() {
            let w = sample_weight(m.count_ones(), Weighting::from_u32(*code), *min_w);
            weights.floats(Tol::Ulps(0), c, &[w], &g[3 + k..4 + k]);
            agg.add(w, *col);
        }
        let rust = agg.resolve(*bg, *bgw).to_array();
        let radiance = |v: &Vec3| v.is_finite() && v.min_element() >= 0.0 && v.max_element() < 1e30;
        if samples.iter().all(|s| radiance(&s.1)) && radiance(bg) {
            agg_r.floats(Tol::Rel(1e-6), c, &rust, &g[..3]);
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
    let out = run_wgsl(
        ctx,
        &lib.fxaa,
        "let p = FxaaParams(f(147u), f(148u), f(149u), 0.0);
         let c = fxaa_pixel(3, 3, p);
         let e = fxaa_fetch(3, 3);
         out[o] = bitcast<u32>(c.x); out[o + 1u] = bitcast<u32>(c.y); out[o + 2u] = bitcast<u32>(c.z);
         out[o + 3u] = bitcast<u32>(e.x); out[o + 4u] = bitcast<u32>(e.y);
         out[o + 5u] = bitcast<u32>(e.z); out[o + 6u] = bitcast<u32>(e.w);",
        151,
        7,
        &input,
    )?;
    let mut enc = Report::new("fxaa_encode");
    let mut pix = Report::new("fxaa_pixel (FXAA 3.11)");
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
        enc.floats(
            Tol::Abs(1.0 / 255.0 + 1e-6),
            &input,
            &fetch(3, 3).to_array(),
            &g[3..7],
        );
        let close = rust.iter().zip(&g[..3]).all(|(a, b)| (a - b).abs() <= 1e-4);
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
        pix.floats(Tol::Abs(1e-4), &input, &rust, &g[..3]);
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

const CHECKS: [(&str, Check); 7] = [
    ("weights", check_weights),
    ("material", check_material),
    ("resolve", check_resolve),
    ("cone", check_cone),
    ("mask", check_mask),
    ("aggregate", check_aggregate),
    ("fxaa", check_fxaa),
];

#[test]
fn wgsl_kernels_match_the_rust_kernels() {
    let Some(ctx) = gpu() else { return };
    let lib = Library::shipped();
    let mut failed = Vec::new();
    for (name, check) in CHECKS {
        match check(&ctx, &lib) {
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
    let Some(ctx) = gpu() else { return };
    let perturbations: [(&str, &str, &str, Check); 5] = [
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
            "material gate ignored",
            "if d <= tolerance && d < subcone_miss_depth() {",
            "if true {",
            check_material,
        ),
        (
            "FXAA's sub-pixel low-pass over 8 instead of 12 weights",
            "subpix_a * (1.0 / 12.0)",
            "subpix_a * (1.0 / 8.0)",
            check_fxaa,
        ),
    ];
    for (what, from, to, check) in perturbations {
        let shipped = Library::shipped();
        assert!(
            shipped.sraa.contains(from)
                || shipped.ctss.contains(from)
                || shipped.fxaa.contains(from),
            "perturbation {what:?}: {from:?} is not in the shipped WGSL any more; update the test"
        );
        let lib = Library {
            sraa: shipped.sraa.replacen(from, to, 1),
            ctss: shipped.ctss.replacen(from, to, 1),
            fxaa: shipped.fxaa.replacen(from, to, 1),
        };
        match check(&ctx, &lib) {
            Ok(_) => panic!("perturbation {what:?} went unnoticed"),
            Err(e) => {
                let failing: Vec<&str> = e.lines().filter(|l| l.contains("inputs fail")).collect();
                println!("caught {what}: {}", failing.join("; "));
            }
        }
    }
}
