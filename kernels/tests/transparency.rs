//! The `K` transparency masks of CTSS §5.3 (`transparency.rs`) and the
//! stepper's semi-transparent path (`ConeStepper::record_alpha`): properties
//! (2,000 cases each) and named cases.
use glam::{Vec2, Vec3};
use proptest::prelude::*;
use subcone_kernels::ctss::{
    cross_section_frame, trace, trace_translucent, ConeStepper, CtssParams, Event,
};
use subcone_kernels::mask::{mask_weight, VisibilityAccumulator, FULL_MASK};
use subcone_kernels::transparency::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 2000,
        ..ProptestConfig::default()
    }
}

/// Opacities, with the stiff ones (NaN, outside `[0, 1]`, the ends).
fn alpha() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => 0.0f32..=1.0,
        1 => Just(f32::NAN),
        1 => Just(0.0f32),
        1 => Just(1.0f32),
        1 => -3.0f32..4.0,
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
    ]
}

fn check_nested(acc: &TransparencyAccumulator) -> Result<(), TestCaseError> {
    for k in 1..LEVELS {
        // M_{k+1} ⊆ M_k
        prop_assert_eq!(
            acc.plane(k + 1) & !acc.plane(k),
            0,
            "level {} not nested",
            k
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    /// With α = 1 every step equals the single-mask accumulator of §3.4: the
    /// visible bits, the weight (bit for bit), `M = M_K` and the background's
    /// share.
    #[test]
    fn opaque_reduces_to_the_single_mask(masks in prop::collection::vec(any::<u32>(), 1..12)) {
        let mut one = VisibilityAccumulator::new();
        let mut k = TransparencyAccumulator::new();
        for m in masks {
            let v = one.add(m);
            let (vk, gained) = k.add(m, 1.0);
            prop_assert_eq!(v, vk);
            prop_assert_eq!(gained, LEVELS * v.count_ones());
            prop_assert_eq!(level_weight(gained).to_bits(), mask_weight(v).to_bits());
            prop_assert_eq!(k.opaque(), one.covered());
            for l in 1..=LEVELS {
                prop_assert_eq!(k.plane(l), one.covered());
            }
            prop_assert_eq!(k.uncovered_weight().to_bits(), one.uncovered_weight().to_bits());
        }
    }

    /// Weights are in [0, 1], sum (with the background's share) to exactly 1,
    /// the masks stay nested, every cell's level only grows, and the K levels
    /// are monotone in α.
    #[test]
    fn weights_telescope_and_levels_grow(layers in prop::collection::vec((any::<u32>(), alpha()), 1..12)) {
        let mut acc = TransparencyAccumulator::new();
        let mut total = 0u32;
        for (m, a) in layers {
            let before: Vec<u32> = (0..32).map(|b| acc.level(b)).collect();
            let (visible, gained) = acc.add(m, a);
            let w = level_weight(gained);
            prop_assert!((0.0..=1.0).contains(&w), "weight {}", w);
            prop_assert_eq!(visible & !m, 0, "only cells of the mask gain");
            total += gained;
            check_nested(&acc)?;
            for b in 0..32 {
                let l = acc.level(b);
                prop_assert!(l >= before[b as usize] && l <= LEVELS);
                if m & (1 << b) == 0 {
                    prop_assert_eq!(l, before[b as usize]);
                }
            }
        }
        prop_assert!(total <= 32 * LEVELS);
        prop_assert_eq!(total, acc.total_levels());
        let sum = level_weight(total) + acc.uncovered_weight();
        prop_assert!((sum - 1.0).abs() <= 1e-6, "weights + background = {}", sum);
    }

    /// A more opaque surface never leaves a cell more transmittance, and a
    /// clearer cell never ends more opaque than a darker one (monotone levels).
    #[test]
    fn levels_are_monotone(r1 in 0u32..=LEVELS, r2 in 0u32..=LEVELS, a1 in alpha(), a2 in alpha()) {
        let (lo_r, hi_r) = (r1.min(r2), r1.max(r2));
        let (ca1, ca2) = (clamp_alpha(a1), clamp_alpha(a2));
        let (lo_a, hi_a) = if ca1 <= ca2 { (a1, a2) } else { (a2, a1) };
        prop_assert!(remaining_after(hi_r, lo_a) >= remaining_after(hi_r, hi_a));
        prop_assert!(remaining_after(lo_r, lo_a) <= remaining_after(hi_r, lo_a));
        prop_assert!(remaining_after(hi_r, lo_a) <= hi_r);
    }
}

#[test]
fn alpha_domain() {
    assert_eq!(clamp_alpha(f32::NAN), 1.0, "NaN is opaque");
    assert_eq!(clamp_alpha(-1.0), 0.0);
    assert_eq!(clamp_alpha(7.0), 1.0);
    assert!(is_opaque(f32::NAN) && is_opaque(1.0) && is_opaque(0.9));
    assert!(!is_opaque(0.85) && !is_opaque(0.0));
    for r in 0..=LEVELS {
        assert_eq!(remaining_after(r, 1.0), 0);
        assert_eq!(remaining_after(r, 0.0), r);
    }
    // Two half-opaque layers: 1/2, then 1/4 more.
    let mut acc = TransparencyAccumulator::new();
    let (_, g1) = acc.add(FULL_MASK, 0.5);
    let (_, g2) = acc.add(FULL_MASK, 0.5);
    assert_eq!((level_weight(g1), level_weight(g2)), (0.5, 0.25));
    assert_eq!(acc.uncovered_weight(), 0.25);
    assert_eq!(acc.opaque(), 0);
}

/// A unit sphere at `z = 5` in front of a wall at `z = 9`, as one field with a
/// material lookup: sphere = colour (1, 0, 0) with opacity `a`, wall = (0, 0, 1)
/// opaque.
fn glass_scene(a: f32) -> (impl Fn(Vec3) -> f32, impl Fn(Vec3, Vec3) -> (Vec3, f32)) {
    let sphere = |p: Vec3| (p - Vec3::new(0.0, 0.0, 5.0)).length() - 1.0;
    let wall = |p: Vec3| 9.0 - p.z;
    let sdf = move |p: Vec3| sphere(p).min(wall(p));
    let shade = move |p: Vec3, _n: Vec3| {
        if sphere(p) < wall(p) {
            (Vec3::X, a)
        } else {
            (Vec3::Z, 1.0)
        }
    };
    (sdf, shade)
}

fn normal_of(sdf: impl Fn(Vec3) -> f32) -> impl Fn(Vec3) -> Vec3 {
    move |p: Vec3| {
        let h = 1e-3;
        Vec3::new(
            sdf(p + Vec3::X * h) - sdf(p - Vec3::X * h),
            sdf(p + Vec3::Y * h) - sdf(p - Vec3::Y * h),
            sdf(p + Vec3::Z * h) - sdf(p - Vec3::Z * h),
        )
        .normalize_or_zero()
    }
}

/// Through the sphere's middle: the pixel is `α·red + (1 − α)·blue`, the
/// sphere's back face is not sampled, and the trace ends on the wall.
#[test]
fn half_opaque_sphere_shows_the_wall_behind() {
    let params = CtssParams::new(0.01);
    for (a, expect) in [(0.5f32, 0.5f32), (0.25, 0.25), (0.75, 0.75), (0.0, 0.0)] {
        let (sdf, shade) = glass_scene(a);
        let (r, u) = cross_section_frame(Vec3::Z, Vec3::Y);
        let n = normal_of(&sdf);
        let res = trace_translucent(
            &params,
            Vec3::ZERO,
            Vec3::Z,
            r,
            u,
            &sdf,
            n,
            &shade,
            Vec3::ONE,
        );
        assert!((res.color.x - expect).abs() < 1e-5, "alpha {a}: {:?}", res);
        assert!(
            (res.color.z - (1.0 - expect)).abs() < 1e-5,
            "alpha {a}: {:?}",
            res
        );
        assert_eq!(res.color.y, 0.0, "no background: {:?}", res);
        assert_eq!(res.coverage, FULL_MASK);
        // The sphere's entry and the wall; an α = 0 sphere is sampled with weight 0.
        assert_eq!(res.samples, 2, "alpha {a}: {:?}", res);
    }
}

/// With every opacity 1 the translucent driver is the opaque one, bit for bit,
/// on rays across the sphere's silhouette (partial masks).
#[test]
fn opaque_translucent_trace_equals_trace() {
    let params = CtssParams::new(0.02);
    let (sdf, shade) = glass_scene(1.0);
    let shade_rgb = |p: Vec3, n: Vec3| shade(p, n).0;
    for i in 0..200 {
        let x = 0.15 + 0.1 * i as f32 / 200.0;
        let dir = Vec3::new(x, 0.03, 1.0).normalize();
        let (r, u) = cross_section_frame(dir, Vec3::Y);
        let a = trace(
            &params,
            Vec3::ZERO,
            dir,
            r,
            u,
            &sdf,
            normal_of(&sdf),
            shade_rgb,
            Vec3::ONE,
        );
        let b = trace_translucent(
            &params,
            Vec3::ZERO,
            dir,
            r,
            u,
            &sdf,
            normal_of(&sdf),
            &shade,
            Vec3::ONE,
        );
        assert_eq!(a, b, "ray {i}");
    }
}

/// Pass-through is bounded: a fully transparent object behind the camera's
/// whole range never sets a stop it cannot reach; the step budget holds.
#[test]
fn transparent_trace_ends_within_budget() {
    let params = CtssParams::new(0.01).with_max_steps(300);
    let mut st = ConeStepper::new(&params);
    let mut n = 0;
    loop {
        n += 1;
        assert!(n < 1000);
        // Inside a transparent medium everywhere.
        match st.advance(-1.0) {
            Event::March => {}
            Event::Sample(s) => {
                st.record_alpha(&s, Vec2::ZERO, 0.0);
            }
            Event::Stop(_) => break,
            e => panic!("an event this test does not know: {e:?}"),
        }
    }
    assert!(st.steps() <= 300);
}

/// `split_group` closes the open group where the caller says the surface
/// changes, and the next step near a surface opens a new one: two samples,
/// the first with the occlusion seen before the split only.
#[test]
fn split_group_gives_each_surface_its_sample() {
    let params = CtssParams::new(0.01);
    let mut st = ConeStepper::new(&params);
    assert!(st.split_group().is_none(), "no group open");
    // Approach a surface at depth 5 (a plane facing the ray) until a group
    // is open and partly occluded.
    let d = |t: f32| 5.0 - t;
    let mut guard = 0;
    while !st.in_group() {
        guard += 1;
        assert!(guard < 10_000);
        assert_eq!(st.advance(d(st.t())), Event::March);
    }
    let first = st.split_group().expect("an open group");
    assert!(!st.in_group());
    assert!(first.occlusion < 1.0 - params.eps);
    // The next step is still near the surface: a new group opens there.
    let t = st.t();
    let _ = st.advance(d(t));
    assert!(st.in_group(), "no new group after the split");
    assert_eq!(st.samples(), 1);
}
