//! The wgpu backend on SDF scenes against the CPU reference: the WGSL code
//! generator evaluates the same field, and every method renders the same
//! images (up to GPU rounding) on every paper and stiff scene.

use std::time::Instant;
use subcone_scene::sdf::SplitDistance;

use glam::Vec3;
use subcone_cpu::CpuBackend;
use subcone_scene::builtin::builtin;
use subcone_scene::sdf::{sdf_builtin, SDF_SCENES, STIFF_SCENES};
use subcone_scene::{Backend, Frame, Method, RenderSettings};
use subcone_wgpu::{gpu_required, WgpuBackend};

/// The backend, or `None` (test skipped, reason printed) when no adapter
/// exists and `SUBCONE_REQUIRE_GPU` is unset; with it set, no adapter fails.
fn gpu() -> Option<WgpuBackend> {
    match WgpuBackend::new() {
        Ok(b) => Some(b),
        Err(e) if !gpu_required() => {
            eprintln!("skipped: {e}");
            None
        }
        Err(e) => panic!("SUBCONE_REQUIRE_GPU is set but {e}"),
    }
}

/// Deterministic points: the camera's view volume, near the surface and far.
fn points(scene: &subcone_scene::sdf::SdfScene, n: usize) -> Vec<Vec3> {
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
            // Along random view rays at random depths: where tracing evaluates.
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

/// The generated WGSL evaluates SdfNode::eval and eval_split: at 4096 points
/// per scene, distances agree within 2e-6 of max(1, |d|, |p|/100) (GPU sqrt
/// and fused multiply-adds differ in the last bits; the scale term covers
/// the far scene, whose coordinates reach 10⁷), and materials agree wherever
/// the nearest object is not a near tie (|d| differences above the tolerance
/// would show in the distance check first). Ties may pick either material:
/// at most 0.5 % of points may differ in material.
#[test]
fn generated_wgsl_evaluates_the_same_field() {
    let Some(gpu) = gpu() else { return };
    for name in SDF_SCENES.iter().chain(STIFF_SCENES.iter()) {
        let scene = sdf_builtin(name).unwrap().unwrap();
        let pts = points(&scene, 4096);
        let start = Instant::now();
        let got = subcone_wgpu::sdf::evaluate_field(gpu.context(), &scene.root, &pts).unwrap();
        let mut worst = 0.0f32;
        let mut mat_diff = 0;
        for (p, g) in pts.iter().zip(&got) {
            let (d, m) = scene.root.eval(*p);
            let SplitDistance {
                safe,
                surface: surf,
                material: ms,
            } = scene.root.eval_split(*p);
            let tol = |x: f32| 2e-6 * (1.0f32).max(x.abs()).max(p.abs().max_element() * 1e-2);
            for (want, have) in [(d, g.eval.0), (safe, g.split.0), (surf, g.split.1)] {
                if want.is_infinite() {
                    assert_eq!(want, have, "{name} at {p}");
                    continue;
                }
                let e = (want - have).abs();
                assert!(
                    e <= tol(want),
                    "{name}: at {p}: cpu {want} gpu {have} (eval {:?} split {:?})",
                    (d, m),
                    (safe, surf, ms)
                );
                worst = worst.max(e / tol(want));
            }
            if m != g.eval.1 || ms != g.split.2 {
                mat_diff += 1;
            }
        }
        assert!(
            mat_diff * 200 <= pts.len(),
            "{name}: {mat_diff} material mismatches"
        );
        eprintln!(
            "{name}: {} points, worst error {worst:.3} of tolerance, {mat_diff} material ties, {:.2?}",
            pts.len(),
            start.elapsed()
        );
    }
}

/// Every operator and primitive, including those no built-in scene uses
/// (intersection, onion, round, guarded and infinite repetition, scatter
/// without a palette, uniform scale, an oblique plane), against the CPU at
/// 8192 points of a 12-unit cube: distances within 2e-6 of max(1, |d|).
#[test]
fn generated_wgsl_covers_every_operator() {
    use glam::Quat;
    use subcone_scene::sdf::{ScatterConfig, SdfNode};
    let Some(gpu) = gpu() else { return };
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
    let root = n(SdfNode::union(shapes));
    let mut state = 99u32;
    let mut unit = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    let pts: Vec<Vec3> = (0..8192)
        .map(|_| Vec3::new(unit(), unit(), unit()) * 12.0 - Vec3::splat(6.0))
        .collect();
    let got = subcone_wgpu::sdf::evaluate_field(gpu.context(), &root, &pts).unwrap();
    let mut mat_diff = 0;
    for (p, g) in pts.iter().zip(&got) {
        let (d, m) = root.eval(*p);
        let SplitDistance {
            safe,
            surface: surf,
            material: ms,
        } = root.eval_split(*p);
        for (want, have) in [(d, g.eval.0), (safe, g.split.0), (surf, g.split.1)] {
            let tol = 2e-6 * want.abs().max(1.0);
            assert!(
                (want - have).abs() <= tol || (want.is_infinite() && want == have),
                "at {p}: cpu {want} gpu {have}"
            );
        }
        mat_diff += usize::from(m != g.eval.1 || ms != g.split.2);
    }
    assert!(
        mat_diff * 200 <= pts.len(),
        "{mat_diff} material mismatches"
    );
}

/// Mean absolute error over all channels, and the fraction of pixels whose
/// largest channel differs by more than 0.05.
fn compare(a: &Frame, b: &Frame) -> (f32, f32) {
    let mut sum = 0.0f64;
    let mut bad = 0;
    for (x, y) in a.color.iter().zip(&b.color) {
        let d = (*x - *y).abs();
        sum += (d.x + d.y + d.z) as f64;
        if d.max_element() > 0.05 {
            bad += 1;
        }
    }
    let n = a.color.len();
    ((sum / (3 * n) as f64) as f32, bad as f32 / n as f32)
}

const METHODS: [&str; 5] = ["noaa", "ssaa4", "ctss", "ctss-r", "ssaa4+ctss"];

/// Thresholds: sphere and cone tracing decide hits by comparisons of f32
/// values that the GPU computes within a few ulps of the CPU; a flipped
/// decision changes a silhouette or shadow pixel, nothing else. On lavapipe
/// every scene and method agrees to the last printed digit (mean < 5e-6, no
/// pixel off); other GPUs round differently, so the bounds leave room for a
/// few flipped pixels: mean absolute error ≤ 0.002 and ≤ 1 % of pixels off by
/// more than 0.05 (64×48: ≤ 30 pixels).
const MAX_MEAN: f32 = 0.002;
const MAX_BAD: f32 = 0.01;

fn agree(names: &[&str], w: u32, h: u32) {
    let Some(gpu) = gpu() else { return };
    let cpu = CpuBackend::new();
    for name in names {
        let scene = builtin(name).unwrap();
        for m in METHODS {
            let method: Method = m.parse().unwrap();
            let mut s = RenderSettings::new(w, h);
            s.aovs = true;
            let t0 = Instant::now();
            let want = cpu.render(&scene, &scene.camera, &method, &s).unwrap();
            let t1 = Instant::now();
            let got = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
            let t2 = Instant::now();
            assert!(
                got.color.iter().all(|c| c.is_finite()),
                "{name} {m}: non-finite pixels"
            );
            let (mean, bad) = compare(&want, &got);
            eprintln!(
                "{name:>13} {m:>10}: mean {mean:.5} bad {:.2}% | cpu {:.2?} gpu {:.2?} (pass {:.2?}) | samples {} vs {}, evals {} vs {}, multi {} vs {}",
                bad * 100.0,
                t1 - t0,
                t2 - t1,
                got.stats.total_time(),
                want.stats.shaded_samples,
                got.stats.shaded_samples,
                want.stats.sdf_evaluations,
                got.stats.sdf_evaluations,
                want.stats.multi_sample_pixels,
                got.stats.multi_sample_pixels,
            );
            assert!(
                mean <= MAX_MEAN && bad <= MAX_BAD,
                "{name} {m}: mean abs error {mean}, {:.2}% pixels off by > 0.05",
                bad * 100.0
            );
            // Work counters agree within 1 % (the same flipped decisions).
            let close =
                |a: u64, b: u64| (a as f64 - b as f64).abs() <= 0.01 * a.max(b) as f64 + 8.0;
            assert!(
                close(want.stats.sdf_evaluations, got.stats.sdf_evaluations),
                "{name} {m}: evaluations {} vs {}",
                want.stats.sdf_evaluations,
                got.stats.sdf_evaluations
            );
            assert!(
                close(want.stats.shaded_samples, got.stats.shaded_samples),
                "{name} {m}: samples {} vs {}",
                want.stats.shaded_samples,
                got.stats.shaded_samples
            );
            assert_eq!(want.stats.passes, got.stats.passes);
            assert_eq!(want.stats.rays.primary, got.stats.rays.primary);
            assert_eq!(got.stats.timings.len(), 1);
            // AOVs: hits agree on ≥ 98 % of pixels, normals of agreeing hits within 0.05.
            let (dw, dg) = (want.depth.as_ref().unwrap(), got.depth.as_ref().unwrap());
            let (nw, ng) = (want.normal.as_ref().unwrap(), got.normal.as_ref().unwrap());
            let mut same = 0;
            for i in 0..dw.len() {
                if dw[i].is_finite() == dg[i].is_finite() {
                    same += 1;
                    if dw[i].is_finite() && (dw[i] - dg[i]).abs() < 1e-3 * dw[i].abs().max(1.0) {
                        assert!((nw[i] - ng[i]).length() < 0.05, "{name} {m}: normal {i}");
                    }
                }
            }
            assert!(same * 50 >= dw.len() * 49, "{name} {m}: depth hits differ");
            assert_eq!(
                got.samples_per_pixel.as_ref().unwrap().len(),
                (w * h) as usize
            );
        }
    }
}

#[test]
fn paper_scenes_match_the_cpu() {
    agree(&SDF_SCENES, 64, 48);
}

#[test]
fn stiff_scenes_are_finite_and_match_the_cpu() {
    agree(&STIFF_SCENES, 64, 48);
}

/// Only what the scene needs is built: no shadow rays without lights, and
/// the same image with shadows forced on a scene without lights.
#[test]
fn no_shadow_work_without_lights() {
    let Some(gpu) = gpu() else { return };
    let scene = builtin("thin").unwrap();
    assert!(scene.lights.is_empty());
    let method: Method = "ctss".parse().unwrap();
    let s = RenderSettings::new(32, 24);
    let f = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
    assert_eq!(f.stats.rays.shadow, 0);
    assert!(!f
        .stats
        .passes
        .contains(subcone_kernels::passes::Passes::SHADOW));
    let lit = builtin("primitives").unwrap();
    let f = gpu.render(&lit, &lit.camera, &method, &s).unwrap();
    assert!(f.stats.rays.shadow > 0);
}

/// Bad input is an error, not a panic or a hang.
#[test]
fn bad_input_is_an_error() {
    let Some(gpu) = gpu() else { return };
    let scene = builtin("primitives").unwrap();
    let method: Method = "ctss".parse().unwrap();
    assert!(gpu
        .render(&scene, &scene.camera, &method, &RenderSettings::new(0, 10))
        .is_err());
    let mut s = RenderSettings::new(16, 16);
    s.max_distance = Some(f32::NAN);
    assert!(gpu.render(&scene, &scene.camera, &method, &s).is_err());
    let sraa: Method = "sraa".parse().unwrap();
    assert!(gpu.render(&scene, &scene.camera, &sraa, &s).is_err());
    assert!(subcone_wgpu::sdf::evaluate_field(
        gpu.context(),
        &sdf_builtin("thin").unwrap().unwrap().root,
        &[]
    )
    .is_err());
    s.max_distance = Some(f32::INFINITY);
    assert!(gpu.render(&scene, &scene.camera, &method, &s).is_err());
    // A step budget of one, or a huge distance, still ends, with finite pixels.
    for (steps, dist) in [(1, 100.0), (100_000, 1e30)] {
        let mut s = RenderSettings::new(16, 16);
        s.max_steps = Some(steps);
        s.max_distance = Some(dist);
        for m in METHODS {
            let f = gpu
                .render(&scene, &scene.camera, &m.parse().unwrap(), &s)
                .unwrap();
            assert!(f.color.iter().all(|c| c.is_finite()), "{m}");
        }
    }
}

/// Run `body` (WGSL statements reading `x: vec4<f32>`, writing `y: vec4<u32>`)
/// for every input on the GPU, after PARAMS and the kernels' WGSL.
fn run_kernels(gpu: &WgpuBackend, body: &str, inputs: &[[f32; 4]]) -> Vec<[u32; 4]> {
    use wgpu::util::DeviceExt;
    let ctx = gpu.context();
    let source = [
        subcone_kernels::wgsl::PARAMS,
        subcone_kernels::cone::WGSL,
        subcone_kernels::mask::WGSL,
        subcone_kernels::aggregate::WGSL,
        subcone_kernels::ctss::WGSL,
        "fn ctss_field(p: vec3<f32>) -> vec2<f32> { return vec2<f32>(length(p) - 1.0); }\n",
        "@group(0) @binding(0) var<storage, read> xs: array<vec4<f32>>;\n",
        "@group(0) @binding(1) var<storage, read_write> ys: array<vec4<u32>>;\n",
        "@compute @workgroup_size(64) fn main(@builtin(global_invocation_id) gid: vec3<u32>) {\n",
        "    if gid.x >= arrayLength(&xs) { return; }\n    let x = xs[gid.x];\n    var y = vec4<u32>(0u);\n",
        body,
        "\n    ys[gid.x] = y;\n}\n",
    ]
    .concat();
    let n = inputs.len() as u64;
    let (pipeline, xs, ys) = ctx
        .scoped("kernel test", || {
            let module = ctx
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: None,
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                });
            let pipeline = ctx
                .device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: None,
                    layout: None,
                    module: &module,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    cache: None,
                });
            let xs = ctx
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: None,
                    contents: bytemuck::cast_slice(inputs),
                    usage: wgpu::BufferUsages::STORAGE,
                });
            let ys = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: n * 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (pipeline, xs, ys)
        })
        .unwrap();
    let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: xs.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: ys.as_entire_binding(),
            },
        ],
    });
    let mut t = Vec::new();
    ctx.timed_pass("kernel test", &mut t, |enc| {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(n.div_ceil(64) as u32, 1, 1);
    })
    .unwrap();
    bytemuck::pod_collect_to_vec(&ctx.read_buffer(&ys, 0, n * 16).unwrap())
}

/// Awkward f32s: signed zeros, infinities, NaN, tiny and huge values, and
/// ordinary ones.
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

/// Floats equal, or both NaN, or within `ulps` units in the last place.
fn close_bits(a: f32, b: u32, ulps: u32) -> bool {
    let b = f32::from_bits(b);
    if a.is_nan() || b.is_nan() {
        return a.is_nan() && b.is_nan();
    }
    if a == b {
        return true;
    }
    a.is_finite()
        && b.is_finite()
        && a.signum() == b.signum()
        && a.to_bits().abs_diff(b.to_bits()) <= ulps
}

/// The kernels' WGSL mirrors compute what the Rust functions compute, on
/// ordinary and awkward inputs (NaN, ±∞, ±0, extremes): cone_occlusion,
/// advance, backtrace_cone_entry, backtrace_hard_hit within 2 ulps (WGSL
/// allows 2.5 ulps for division); visibility_mask, needs_normal and
/// sample_weight exactly on ≥ 99.9 % of random half-planes (a cell centre
/// within an ulp of the line may flip).
#[test]
fn kernel_wgsl_mirrors_the_rust_kernels() {
    use glam::Vec2;
    use subcone_kernels::aggregate::{sample_weight, Weighting};
    use subcone_kernels::cone::{
        advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion,
    };
    use subcone_kernels::mask::{needs_normal, visibility_mask, MaskPlacement};
    let Some(gpu) = gpu() else { return };
    let mut state = 0x9e37_79b9u32;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    let inputs: Vec<[f32; 4]> = (0..20_000)
        .map(|i| {
            [
                awkward(i, &mut unit),
                awkward(i + 1, &mut unit),
                awkward(i + 2, &mut unit).abs(),
                awkward(i + 3, &mut unit),
            ]
        })
        .collect();
    let got = run_kernels(
        &gpu,
        "y = vec4<u32>(bitcast<u32>(cone_occlusion(x.x, x.z)), bitcast<u32>(advance(x.x, x.y, 0.5, x.z)), \
         bitcast<u32>(backtrace_cone_entry(x.x, x.z)), bitcast<u32>(backtrace_hard_hit(x.x, x.y, x.w)));",
        &inputs,
    );
    for (x, y) in inputs.iter().zip(&got) {
        let want = [
            cone_occlusion(x[0], x[2]),
            advance(x[0], x[1], 0.5, x[2]),
            backtrace_cone_entry(x[0], x[2]),
            backtrace_hard_hit(x[0], x[1], x[3]),
        ];
        for k in 0..4 {
            // Subnormal results may be flushed to zero on GPUs.
            let flushed =
                want[k] != 0.0 && want[k].abs() < f32::MIN_POSITIVE && f32::from_bits(y[k]) == 0.0;
            assert!(
                close_bits(want[k], y[k], 2) || flushed,
                "function {k} at {x:?}: cpu {} gpu {}",
                want[k],
                f32::from_bits(y[k])
            );
        }
    }

    // Masks: occlusion in [−0.2, 1.2] (and awkward), unit and non-unit normals.
    let inputs: Vec<[f32; 4]> = (0..20_000)
        .map(|i| {
            let occ = if i % 50 == 0 {
                awkward(i, &mut unit)
            } else {
                unit() * 1.4 - 0.2
            };
            let a = unit() * std::f32::consts::TAU;
            let len = if i % 3 == 0 { unit() } else { 1.0 };
            [occ, a.cos() * len, a.sin() * len, (i % 3) as f32]
        })
        .collect();
    let got = run_kernels(
        &gpu,
        "let m = visibility_mask(x.x, x.yz, u32(x.w));\n    \
         y = vec4<u32>(m, select(0u, 1u, needs_normal(x.x, u32(x.w))), \
         bitcast<u32>(sample_weight(m, WEIGHTING_VISIBILITY, 0.0)), bitcast<u32>(sample_weight(m, WEIGHTING_VISIBILITY, 0.01)));",
        &inputs,
    );
    let mut differ = 0;
    for (x, y) in inputs.iter().zip(&got) {
        let placement = MaskPlacement::from_u32(x[3] as u32);
        let m = visibility_mask(x[0], Vec2::new(x[1], x[2]), placement);
        if m != y[0] {
            differ += 1;
            assert!(
                (m ^ y[0]).count_ones() <= 6,
                "mask at {x:?}: {m:#x} vs {:#x}",
                y[0]
            );
            continue;
        }
        assert_eq!(needs_normal(x[0], placement), y[1] == 1, "{x:?}");
        assert_eq!(
            sample_weight(m, Weighting::Visibility, 0.0).to_bits(),
            y[2],
            "{x:?}"
        );
        assert_eq!(
            sample_weight(m, Weighting::Visibility, 0.01).to_bits(),
            y[3],
            "{x:?}"
        );
    }
    assert!(differ * 1000 <= inputs.len(), "{differ} masks differ");
    eprintln!("{differ} of {} masks differ", inputs.len());
}

/// Pipelines are cached per device: a second device renders the same image,
/// and a scene changed in place (its lights) is compiled anew.
#[test]
fn pipelines_follow_the_device_and_the_scene() {
    let Some(gpu) = gpu() else { return };
    let other = WgpuBackend::with_context(std::sync::Arc::new(
        subcone_wgpu::GpuContext::new().unwrap(),
    ));
    let mut scene = builtin("sparse-shape").unwrap();
    let method: Method = "ctss".parse().unwrap();
    let s = RenderSettings::new(32, 24);
    let a = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
    let b = other.render(&scene, &scene.camera, &method, &s).unwrap();
    assert_eq!(a.color, b.color);
    for l in scene.lights.iter_mut() {
        if let subcone_scene::Light::Directional { irradiance, .. } = l {
            *irradiance *= 0.25;
        }
    }
    let c = gpu.render(&scene, &scene.camera, &method, &s).unwrap();
    let want = CpuBackend::new()
        .render(&scene, &scene.camera, &method, &s)
        .unwrap();
    assert_ne!(a.color, c.color);
    let (mean, _) = compare(&want, &c);
    assert!(mean < 1e-4, "{mean}");
}
