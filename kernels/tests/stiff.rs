//! Stiff and extreme inputs, one named test each. The policy under test (crate
//! docs): no panic, no endless loop, no NaN out of a weight, reconstruction or
//! aggregation, and every trace ends within its step budget.

use glam::{Vec2, Vec3};
use subcone_kernels::aggregate::Aggregate;
use subcone_kernels::cone::*;
use subcone_kernels::ctss::{sphere_trace, trace, ConeStepper, CtssParams, Event, StopReason};
use subcone_kernels::mask::{project_normal, visibility_mask, MaskPlacement, FULL_MASK};
use subcone_kernels::sraa::*;

const PLACEMENTS: [MaskPlacement; 3] = [
    MaskPlacement::Derived,
    MaskPlacement::AuthorsCode,
    MaskPlacement::PaperEq8,
];

/// A unit sphere 5 units down −z.
fn sphere(p: Vec3) -> f32 {
    (p - Vec3::new(0.0, 0.0, -5.0)).length() - 1.0
}
fn sphere_normal(p: Vec3) -> Vec3 {
    (p - Vec3::new(0.0, 0.0, -5.0)).normalize()
}

/// Drive a stepper over `sdf` and return (events, final stop), asserting the
/// loop ends within the budget and `t` only grows.
fn run_stepper(params: &CtssParams, mut sdf: impl FnMut(f32) -> f32) -> (u32, StopReason) {
    let mut s = ConeStepper::new(params);
    let mut calls = 0u32;
    let mut last_t = f32::NEG_INFINITY;
    loop {
        calls += 1;
        assert!(
            calls <= params.max_steps + params.max_samples + 2,
            "stepper did not stop within its budget"
        );
        let t = s.t();
        assert!(t >= last_t, "t went backwards: {last_t} -> {t}");
        last_t = t;
        match s.advance(sdf(t)) {
            Event::March => {}
            Event::Sample(g) => {
                assert!(
                    g.t <= t && g.t_entry <= t,
                    "sample {g:?} beyond current t {t}"
                );
                let (_, w) = s.record(&g, Vec2::new(0.0, 1.0));
                assert!((0.0..=1.0).contains(&w));
            }
            Event::Stop(r) => {
                assert!(s.steps() <= params.max_steps);
                return (s.steps(), r);
            }
            e => panic!("an event this test does not know: {e:?}"),
        }
    }
}

#[test]
fn cone_radius_zero_at_t_zero() {
    assert_eq!(cone_radius(0.0, 0.01), 0.0);
    assert_eq!(cone_occlusion(1.0, 0.0), OCCLUSION_MIN);
    assert_eq!(cone_occlusion(-1.0, 0.0), OCCLUSION_MAX);
    assert_eq!(cone_occlusion(0.0, 0.0), 0.5);
    assert_eq!(backtrace_cone_entry(0.0, 0.01), 0.0);
    // A trace starting at t = 0 (R_c = 0) still proceeds and finds the sphere.
    let r = trace(
        &CtssParams::new(0.001),
        Vec3::ZERO,
        Vec3::NEG_Z,
        Vec3::X,
        Vec3::Y,
        sphere,
        sphere_normal,
        |_, _| Vec3::ONE,
        Vec3::ZERO,
    );
    assert_eq!(r.stop, StopReason::FullOcclusion);
    assert_eq!(r.color, Vec3::ONE);
}

#[test]
fn cone_radius_below_1e_30() {
    for rc in [1e-31f32, 1e-38, 1e-45] {
        assert_eq!(cone_occlusion(1e-3, rc), OCCLUSION_MIN, "rc {rc}");
        assert_eq!(cone_occlusion(-1e-3, rc), OCCLUSION_MAX, "rc {rc}");
        let w = cone_occlusion(rc * 0.5, rc);
        assert!(
            w.is_finite() && (OCCLUSION_MIN..=OCCLUSION_MAX).contains(&w),
            "rc {rc}: {w}"
        );
        assert!(min_step(0.5, rc) >= 0.0);
    }
}

#[test]
fn distance_infinite_nan_and_far_beyond_cone() {
    assert_eq!(cone_occlusion(f32::INFINITY, 1.0), OCCLUSION_MIN);
    assert_eq!(cone_occlusion(f32::NEG_INFINITY, 1.0), OCCLUSION_MAX);
    assert_eq!(cone_occlusion(f32::NAN, 1.0), OCCLUSION_MIN);
    assert_eq!(cone_occlusion(1e30, 1e-3), OCCLUSION_MIN);
    assert_eq!(cone_occlusion(-1e30, 1e-3), OCCLUSION_MAX);
    assert_eq!(cone_occlusion(1.0, f32::INFINITY), 0.5);
    assert_eq!(cone_occlusion(f32::INFINITY, f32::INFINITY), OCCLUSION_MIN);

    let p = CtssParams::new(0.01).with_range(0.0, 100.0);
    // +∞: one step to t = ∞, then the ray has left the scene.
    assert_eq!(
        run_stepper(&p, |_| f32::INFINITY).1,
        StopReason::MaxDistance
    );
    // −∞: full occlusion at once.
    assert_eq!(
        run_stepper(&p, |_| f32::NEG_INFINITY).1,
        StopReason::FullOcclusion
    );
    // NaN: the trace stops, the pixel is background, never NaN.
    assert_eq!(run_stepper(&p, |_| f32::NAN).1, StopReason::InvalidDistance);
    let r = trace(
        &p,
        Vec3::ZERO,
        Vec3::NEG_Z,
        Vec3::X,
        Vec3::Y,
        |_| f32::NAN,
        |_| Vec3::Y,
        |_, _| Vec3::ONE,
        Vec3::splat(0.25),
    );
    assert_eq!(r.color, Vec3::splat(0.25));
    assert_eq!(
        sphere_trace(&p, Vec3::ZERO, Vec3::NEG_Z, |_| f32::NAN).stop,
        StopReason::InvalidDistance
    );
    // A NaN that appears mid-group still ends the trace with the group sampled.
    let (_, stop) = run_stepper(&p, |t| {
        if t < 5.0 {
            5.0 - t + 0.004 * t
        } else {
            f32::NAN
        }
    });
    assert_eq!(stop, StopReason::InvalidDistance);
}

#[test]
fn projected_normal_zero() {
    for p in PLACEMENTS {
        assert_eq!(visibility_mask(0.75, Vec2::ZERO, p), FULL_MASK);
        assert_eq!(visibility_mask(0.5, Vec2::ZERO, p), FULL_MASK);
        assert_eq!(visibility_mask(0.25, Vec2::ZERO, p), 0);
    }
    // A normal facing the ray projects to (0, 0).
    assert_eq!(project_normal(Vec3::Z, Vec3::X, Vec3::Y), Vec2::ZERO);
}

#[test]
fn normal_components_at_1e_30() {
    for p in PLACEMENTS {
        for np in [
            Vec2::new(1e-30, 1.0),
            Vec2::new(-1e-30, 1.0),
            Vec2::new(1.0, 1e-30),
            Vec2::new(1.0, -1e-30),
            Vec2::new(1e-30, 1e-30),
            Vec2::new(-1e-30, -1e-30),
        ] {
            for omega in [-1.0, 0.0, 0.3, 0.5, 0.7, 1.0, 2.0] {
                let _ = visibility_mask(omega, np, p); // must not panic
            }
        }
    }
    // (1e-30, 1): a horizontal edge, rows all or nothing: half the pixel covered
    // at ω = 0.5 — rows below y = 0 (the normal points up, the solid is below).
    let m = visibility_mask(0.5, Vec2::new(1e-30, 1.0), MaskPlacement::Derived);
    assert_eq!(m.count_ones(), 16, "{m:032b}");
    assert_eq!(m, 0x0000_ffff, "the bottom three rows are bits 0..16");
    // Components too small to square: treated as fronto-parallel.
    assert_eq!(
        visibility_mask(0.3, Vec2::new(1e-30, 1e-30), MaskPlacement::Derived),
        0
    );
}

#[test]
fn weights_underflow_and_fallback_applies() {
    // σz·Δz = 1e20 for every neighbour: every weight is exp(−1e40) = 0.
    let p = SraaParams {
        sigma_z: 1e20,
        ..SraaParams::PAPER
    };
    let target = Geometry::new(Vec3::Y, 1.0);
    let far = Geometry::new(Vec3::Y, 3.0); // Δz = 1 (relative)
    assert_eq!(bilateral_weight(&p, &target, &far), 0.0);
    let n = [(2.0, Vec3::X), (0.5, Vec3::Y), (1.0, Vec3::Z)].map(|(d2, c)| ShadedSample {
        geometry: far,
        color: c,
        shadowed: false,
        distance2: d2,
    });
    let r = reconstruct(&p, &target, None, n);
    assert!(r.fell_back);
    assert_eq!(r.color, Vec3::Y, "the nearest shaded sample");
    // Subnormal sums also fall back rather than divide.
    let p = SraaParams {
        sigma_z: 13.0,
        ..SraaParams::PAPER
    };
    let w = bilateral_weight(&p, &target, &far);
    assert!(w < f32::MIN_POSITIVE, "{w}");
    assert!(reconstruct(&p, &target, None, n).fell_back);
    // No neighbours at all: black, not NaN.
    assert_eq!(reconstruct(&p, &target, None, []).color, Vec3::ZERO);
}

#[test]
fn normals_not_unit_or_nan() {
    let p = SraaParams::PAPER;
    let g = Geometry::new(Vec3::Y, 2.0);
    for n in [
        Vec3::Y * 5.0,
        Vec3::Y * 0.2,
        Vec3::new(3.0, 4.0, 0.0),
        Vec3::ZERO,
        Vec3::splat(1e30),
    ] {
        let w = bilateral_weight(&p, &g, &Geometry::new(n, 2.0));
        assert!((0.0..=1.0).contains(&w), "{n}: {w}");
    }
    // Longer-than-unit normals saturate the cosine, so they weigh as equal normals.
    assert_eq!(
        bilateral_weight(&p, &g, &Geometry::new(Vec3::Y * 5.0, 2.0)),
        1.0
    );
    // NaN normals exclude the neighbour.
    assert_eq!(
        bilateral_weight(&p, &g, &Geometry::new(Vec3::NAN, 2.0)),
        0.0
    );
    assert_eq!(
        bilateral_weight(&p, &Geometry::new(Vec3::NAN, 2.0), &g),
        0.0
    );
    // A NaN depth excludes too; misses match misses only.
    assert_eq!(
        bilateral_weight(&p, &g, &Geometry::new(Vec3::Y, f32::NAN)),
        0.0
    );
    assert_eq!(bilateral_weight(&p, &Geometry::MISS, &Geometry::MISS), 1.0);
    assert_eq!(bilateral_weight(&p, &g, &Geometry::MISS), 0.0);
    // The mask normalises non-unit normals; NaN ones read as fronto-parallel.
    let (r, u) = (Vec3::X, Vec3::Y);
    let n = Vec3::new(0.6, 0.0, 0.8);
    assert_eq!(
        visibility_mask(0.4, project_normal(n * 7.0, r, u), MaskPlacement::Derived),
        visibility_mask(0.4, project_normal(n, r, u), MaskPlacement::Derived)
    );
    assert_eq!(project_normal(Vec3::NAN, r, u), Vec2::ZERO);
    assert_eq!(project_normal(Vec3::splat(f32::INFINITY), r, u), Vec2::ZERO);
    // A NaN shaded colour never reaches the pixel.
    assert_eq!(aggregate(&[(0.5, Vec3::NAN), (0.5, Vec3::ONE)]), Vec3::ONE);
}

/// tan θ = 1e-8 (an extreme telephoto) at t = 1e7: α·R_c = 0.05 < ulp(1e7)/2 = 0.5,
/// so `t + max(d, α·R_c)` rounds back to `t` once `d` is small.
#[test]
fn narrow_cone_at_far_depth_makes_progress() {
    let t0 = 1.0e7f32;
    assert!(min_step(0.5, cone_radius(t0, 1e-8)) < (t0.next_up() - t0) / 2.0);
    assert!(advance(t0, 0.01, 0.5, cone_radius(t0, 1e-8)) > t0);
    let p = CtssParams::new(1e-8)
        .with_range(t0, 2.0e7)
        .with_max_steps(300);
    // A surface 50 units ahead: d shrinks to 0 then goes negative.
    let surface = t0 + 50.0;
    let (steps, stop) = run_stepper(&p, |t| surface - t);
    assert!(steps <= 300);
    assert!(
        matches!(stop, StopReason::FullOcclusion | StopReason::StepBudget),
        "{stop:?}"
    );
    // Nothing ahead, but a tiny constant distance: only the budget can end it.
    let (steps, stop) = run_stepper(&p, |_| 1e-3);
    assert_eq!((steps, stop), (300, StopReason::StepBudget));
    // Plain sphere tracing with the same threshold also ends.
    let hit = sphere_trace(&p, Vec3::ZERO, Vec3::NEG_Z, |q| (-q.z) - surface);
    assert!(hit.steps <= 300);
}

#[test]
fn denormal_inputs() {
    let tiny = 1e-40f32;
    assert!(tiny != 0.0 && !tiny.is_normal());
    let w = cone_occlusion(tiny, tiny);
    assert_eq!(w, 0.0);
    let w = cone_occlusion(tiny, 2.0 * tiny);
    assert!(w.is_finite() && w > 0.0);
    let ts = backtrace_cone_entry(tiny, 0.01);
    assert!((0.0..=tiny).contains(&ts));
    assert!(advance(tiny, tiny, 0.5, tiny) > tiny);
    let p = SraaParams::PAPER;
    let w = bilateral_weight(
        &p,
        &Geometry::new(Vec3::Y, tiny),
        &Geometry::new(Vec3::Y, 2.0 * tiny),
    );
    assert!(w.is_finite() && (0.0..=1.0).contains(&w));
    let w = bilateral_weight(
        &p,
        &Geometry::new(Vec3::Y, 0.0),
        &Geometry::new(Vec3::Y, tiny),
    );
    assert_eq!(w, 0.0, "a relative step from 0 is total");
    for pl in PLACEMENTS {
        let _ = visibility_mask(0.5 + tiny, Vec2::new(tiny, 1.0), pl);
        let _ = visibility_mask(tiny, Vec2::new(1.0, tiny), pl);
    }
    assert!(aggregate(&[(tiny, Vec3::ONE)]).is_finite());
}

/// |∇f| = 0.2 (an underestimating SDF: slow but safe) and |∇f| = 5 (an
/// overestimate: steps overshoot). Neither may hang or produce NaN; §5.2 warns
/// that coverage is then unreliable, which we print rather than hide.
#[test]
fn non_eikonal_distances() {
    let p = CtssParams::new(0.002)
        .with_range(0.0, 100.0)
        .with_max_steps(4096);
    let dir = Vec3::new(0.0, 0.19, -1.0).normalize(); // grazes the silhouette
    for scale in [1.0f32, 0.2, 5.0] {
        for (name, d) in [("centre", Vec3::NEG_Z), ("silhouette", dir)] {
            let r = trace(
                &p,
                Vec3::ZERO,
                d,
                Vec3::X,
                Vec3::Y,
                |q| scale * sphere(q),
                sphere_normal,
                |_, _| Vec3::ONE,
                Vec3::ZERO,
            );
            println!(
                "[non-eikonal] |∇f| = {scale:<3} {name:<10} coverage {:.3}  steps {:>4}  samples {}  stop {:?}",
                r.color.x, r.steps, r.samples, r.stop
            );
            assert!(r.color.is_finite() && (0.0..=1.0).contains(&r.color.x));
            assert!(r.steps <= p.max_steps);
            if name == "centre" && scale <= 1.0 {
                // Underestimates are slow but safe: the head-on hit is found.
                assert_eq!(
                    r.color,
                    Vec3::ONE,
                    "a head-on hit covers the pixel at |∇f| = {scale}"
                );
            }
            if name == "centre" && scale > 1.0 {
                // Overestimates step straight through the sphere (20 units from t = 0
                // over a sphere 4..6 away): the object is missed, as §5.2 warns. The
                // kernels cannot detect that; they must only end cleanly.
                assert_eq!(r.stop, StopReason::MaxDistance);
            }
            let hit = sphere_trace(&p, Vec3::ZERO, d, |q| scale * sphere(q));
            assert!(hit.steps <= p.max_steps);
        }
    }
}

/// Eq. 6 over `samples` (weight, colour) with no background weight.
fn aggregate(samples: &[(f32, Vec3)]) -> Vec3 {
    let mut a = Aggregate::new();
    for &(w, c) in samples {
        a.add(w, c);
    }
    a.resolve(Vec3::ZERO, 0.0)
}

/// The colour and the fallback flag of a target at depth 0 reconstructed
/// from one unshadowed sample of `color` at `depth` (both facing +Y), with
/// eq. 1 on absolute depths and σz = 1: the weight `exp(−depth²)` is tiny or
/// underflows.
fn reconstruct_from_far_sample(depth: f32, color: Vec3) -> (Vec3, bool) {
    let p = SraaParams::new(1.0, 0.0, 1.0, WeightForm::Product, DepthMetric::Absolute, 1);
    let n = [ShadedSample {
        geometry: Geometry::new(Vec3::Y, depth),
        color,
        shadowed: false,
        distance2: 0.0,
    }];
    let r = reconstruct(&p, &Geometry::new(Vec3::Y, 0.0), None, n);
    (r.color, r.fell_back)
}

/// Inputs the fuzz targets found; each was a bug, kept as a regression test.
#[test]
fn fuzz_regressions() {
    // 1. w_ii < 1 for a normal whose f32 normalisation leaves n·n = 1 − 2⁻²⁴.
    let g = Geometry::new(Vec3::ONE.normalize(), 5.0);
    assert_eq!(bilateral_weight(&SraaParams::CHAJDAS, &g, &g), 1.0);
    // 2. Weights so small that w·C underflows: fall back instead of returning 0.
    assert_eq!(
        aggregate(&[(2e-38, Vec3::splat(1e-10))]),
        Vec3::splat(1e-10)
    );
    assert_eq!(
        reconstruct_from_far_sample(9.3, Vec3::splat(1e-10)),
        (Vec3::splat(1e-10), true)
    );
    // 3. The pixel resolve of finite colours near f32::MAX stays finite.
    let big = Vec3::splat(2e38);
    assert_eq!(
        resolve_pixel(&[big, big, Vec3::ZERO, Vec3::ZERO]),
        Vec3::splat(1e38)
    );
    // 4. Weights above 1 cannot overflow the weight sum.
    assert_eq!(
        aggregate(&[(3e38, Vec3::splat(0.1)), (3e38, Vec3::splat(0.1))]),
        Vec3::splat(0.1)
    );
    // 5. Normals whose squared length leaves f32's range still project.
    for n in [
        Vec3::new(1e20, 0.0, 0.0),
        Vec3::new(1e-23, 0.0, 0.0),
        Vec3::new(4.5e-23, 0.0, 0.0),
    ] {
        assert_eq!(project_normal(n, Vec3::X, Vec3::Y), Vec2::X, "{n}");
    }
    assert_eq!(
        visibility_mask(
            0.3,
            project_normal(Vec3::new(1e20, 0.0, 0.0), Vec3::X, Vec3::Y),
            MaskPlacement::Derived
        ),
        visibility_mask(0.3, Vec2::X, MaskPlacement::Derived)
    );
}

/// Fuzzing found these after the first fix: products `w·C` of a small weight
/// and a tiny colour left f32's normal range. Sums are now accumulated in f64.
#[test]
fn fuzz_regressions_tiny_products() {
    assert_eq!(
        Aggregate::new().resolve(Vec3::splat(1e-28), 1e-18),
        Vec3::splat(1e-28)
    );
    assert_eq!(
        aggregate(&[(1e-18, Vec3::splat(1e-28))]),
        Vec3::splat(1e-28)
    );
    assert_eq!(
        reconstruct_from_far_sample(6.6, Vec3::splat(1e-28)),
        (Vec3::splat(1e-28), false)
    );
    // The aggregate fuzzer's input: a NaN-weight sample and a background alone.
    let bg = Vec3::new(1.1368807e-13, 1.4356219e-28, 6.7498003e-21);
    let mut a = Aggregate::new();
    a.add(f32::NAN, Vec3::ONE);
    assert_eq!(a.resolve(bg, 6.938894e-18), bg);
}
