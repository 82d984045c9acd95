//! Property tests (proptest) of the kernels' invariants, 2,000 cases each.
mod common;

use common::Lcg;
use glam::{Vec2, Vec3};
use proptest::prelude::*;
use subcone_kernels::aggregate::{sample_weight, Aggregate, Weighting};
use subcone_kernels::cone::*;
use subcone_kernels::ctss::{ConeStepper, CtssParams, Event};
use subcone_kernels::mask::*;
use subcone_kernels::sraa::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 2000,
        ..ProptestConfig::default()
    }
}

/// A uniformly distributed unit vector.
fn unit() -> impl Strategy<Value = Vec3> {
    (-1.0f32..=1.0, 0.0f32..std::f32::consts::TAU).prop_map(|(z, phi)| {
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z).normalize()
    })
}

/// Depths over twelve orders of magnitude.
fn depth() -> impl Strategy<Value = f32> {
    (-3.0f32..9.0).prop_map(|e| 10f32.powf(e))
}

fn params() -> impl Strategy<Value = SraaParams> {
    prop_oneof![
        Just(SraaParams::PAPER),
        Just(SraaParams::CHAJDAS),
        Just(SraaParams::PAPER.with_depth_metric(DepthMetric::Absolute)),
        (0.0f32..100.0, 0.0f32..10.0).prop_map(|(sz, sn)| SraaParams {
            sigma_z: sz,
            sigma_n: sn,
            ..SraaParams::PAPER
        }),
    ]
}

/// Rotate `n` towards a perpendicular direction by `angle`.
fn rotated(n: Vec3, towards: Vec3, angle: f32) -> Vec3 {
    let perp = (towards - n * towards.dot(n)).normalize_or(n.any_orthonormal_vector());
    (n * angle.cos() + perp * angle.sin()).normalize()
}

proptest! {
    #![proptest_config(config())]

    /// `look_frame` gives a unit, orthogonal, right-handed frame whenever
    /// `forward` and `up_hint` are at least `LOOK_FRAME_MIN_SINE` from
    /// parallel, whatever their lengths (10⁻³⁰ to 10³⁰: a cross product of
    /// subnormal length included), orthogonal to within the f32 cross
    /// product's cancellation, about 10⁻⁷ over the sine; closer to parallel
    /// it gives no frame (zero `right` and `up`), never a skewed one.
    #[test]
    fn look_frame_is_orthonormal(
        forward_dir in unit(),
        up_dir in unit(),
        (forward_exp, up_exp) in (-30.0f32..30.0, -30.0f32..30.0),
        tilt in (-6.0f32..0.0).prop_map(|e| 10f32.powf(e)),
        nearly_parallel in any::<bool>(),
    ) {
        let up_dir = if nearly_parallel {
            (forward_dir + tilt * up_dir.cross(forward_dir)).normalize()
        } else {
            up_dir
        };
        let sine = forward_dir.cross(up_dir).length();
        let forward = forward_dir * 10f32.powf(forward_exp);
        let up = up_dir * 10f32.powf(up_exp);
        let (f, r, u) = subcone_kernels::camera::look_frame(forward, up);
        prop_assert!((f.length() - 1.0).abs() < 1e-5, "forward {:?}", f);
        if r == Vec3::ZERO {
            // No frame: only near the threshold (the sine from f32 unit
            // vectors, within rounding of this one) or below it.
            prop_assert!(sine < 1.01 * subcone_kernels::camera::LOOK_FRAME_MIN_SINE, "sine {}", sine);
            prop_assert_eq!(u, Vec3::ZERO);
            return Ok(());
        }
        prop_assert!(sine > 0.99 * subcone_kernels::camera::LOOK_FRAME_MIN_SINE, "a frame at sine {}", sine);
        let orthogonal = 1e-5 + 2e-7 / sine;
        for (name, v) in [("forward", f), ("right", r), ("up", u)] {
            prop_assert!((v.length() - 1.0).abs() < 1e-5, "{} {:?}", name, v);
        }
        prop_assert!(
            f.dot(r).abs() < orthogonal && f.dot(u).abs() < 1e-5 && r.dot(u).abs() < 1e-5,
            "{} {} {} (sine {})", f.dot(r), f.dot(u), r.dot(u), sine
        );
        prop_assert!(r.cross(u).dot(f) < -0.999, "right × up is −forward (right = forward × up)");
    }

    #[test]
    fn weights_in_unit_interval(p in params(), ni in unit(), nj in unit(), zi in depth(), zj in depth()) {
        let w = bilateral_weight(&p, &Geometry::new(ni, zi), &Geometry::new(nj, zj));
        prop_assert!((0.0..=1.0).contains(&w), "{w}");
    }

    #[test]
    fn weight_of_a_sample_with_itself_is_one(p in params(), n in unit(), z in depth()) {
        let g = Geometry::new(n, z);
        prop_assert_eq!(bilateral_weight(&p, &g, &g), 1.0);
    }

    #[test]
    fn weights_are_symmetric(p in params(), ni in unit(), nj in unit(), zi in depth(), zj in depth()) {
        let (a, b) = (Geometry::new(ni, zi), Geometry::new(nj, zj));
        prop_assert_eq!(bilateral_weight(&p, &a, &b), bilateral_weight(&p, &b, &a));
    }

    #[test]
    fn weights_do_not_grow_with_depth_difference(p in params(), ni in unit(), nj in unit(), zi in depth(),
        r1 in 0.0f32..2.0, r2 in 0.0f32..2.0, farther in any::<bool>()) {
        let (lo, hi) = if r1 <= r2 { (r1, r2) } else { (r2, r1) };
        let s = if farther { 1.0 } else { -0.45 };
        let gi = Geometry::new(ni, zi);
        let near = bilateral_weight(&p, &gi, &Geometry::new(nj, zi * (1.0 + s * lo)));
        let far = bilateral_weight(&p, &gi, &Geometry::new(nj, zi * (1.0 + s * hi)));
        prop_assert!(far <= near, "{far} > {near}");
    }

    #[test]
    fn weights_do_not_grow_with_normal_angle(p in params(), n in unit(), t in unit(), z in depth(), dz in 0.0f32..0.5,
        a1 in 0.0f32..std::f32::consts::PI, a2 in 0.0f32..std::f32::consts::PI) {
        let (lo, hi) = if a1 <= a2 { (a1, a2) } else { (a2, a1) };
        let gi = Geometry::new(n, z);
        let near = bilateral_weight(&p, &gi, &Geometry::new(rotated(n, t, lo), z * (1.0 + dz)));
        let far = bilateral_weight(&p, &gi, &Geometry::new(rotated(n, t, hi), z * (1.0 + dz)));
        // Rotating by `hi` can land a rounding step closer in cosine: allow 2 ulp.
        prop_assert!(far <= near + 2.0 * f32::EPSILON, "{far} > {near}");
    }

    #[test]
    fn shadow_gate_is_eq2(p in params(), ni in unit(), nj in unit(), zi in depth(), zj in depth(), si in any::<bool>(), sj in any::<bool>()) {
        let (a, b) = (Geometry::new(ni, zi), Geometry::new(nj, zj));
        let w = shadow_gated_weight(&p, &a, &b, si, sj);
        if si != sj {
            prop_assert_eq!(w, 0.0);
        } else {
            prop_assert_eq!(w, bilateral_weight(&p, &a, &b));
        }
    }

    #[test]
    fn reconstruction_stays_in_convex_hull(p in params(), tn in unit(), tz in depth(),
        ns in prop::collection::vec((unit(), 0.5f32..2.0, (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0), any::<bool>()), 1..10),
        gate in prop::option::of(any::<bool>())) {
        let samples: Vec<ShadedSample> = ns.iter().enumerate().map(|(k, &(n, zr, (r, g, b), s))| ShadedSample {
            geometry: Geometry::new(n, tz * zr), color: Vec3::new(r, g, b), shadowed: s, distance2: k as f32,
        }).collect();
        let out = reconstruct(&p, &Geometry::new(tn, tz), gate, samples.iter().copied());
        let lo = samples.iter().fold(Vec3::INFINITY, |m, s| m.min(s.color));
        let hi = samples.iter().fold(Vec3::NEG_INFINITY, |m, s| m.max(s.color));
        let tol = Vec3::splat(1e-6);
        prop_assert!(out.color.cmpge(lo - tol).all() && out.color.cmple(hi + tol).all(), "{:?} outside [{lo}, {hi}]", out);
    }

    #[test]
    fn correlated_masks_are_disjoint_and_m_only_grows(masks in prop::collection::vec(any::<u32>(), 1..12),
        min_w in prop_oneof![Just(0.0f32), Just(0.01f32), 0.0f32..0.1]) {
        let mut acc = VisibilityAccumulator::new();
        let mut seen = 0u32;
        let (mut sum0, mut sum_min) = (0.0f32, 0.0f32);
        for m in &masks {
            let before = acc.covered();
            let v = acc.add(*m);
            prop_assert_eq!(v & seen, 0, "visible masks overlap");
            prop_assert_eq!(acc.covered() & before, before, "M lost bits");
            prop_assert_eq!(acc.covered(), before | *m);
            seen |= v;
            sum0 += sample_weight(v, Weighting::Visibility, 0.0);
            sum_min += sample_weight(v, Weighting::Visibility, min_w);
        }
        prop_assert!(sum0 <= 1.0, "weights sum {sum0} > 1");
        // Stated bound with the authors' floor: 1 + min_weight · samples.
        prop_assert!(sum_min <= 1.0 + min_w * masks.len() as f32 + 1e-6, "{sum_min}");
    }

    #[test]
    fn mask_extremes_for_the_derived_placement(n in unit(), omega_lo in -1.0f32..=0.0432, omega_hi in 0.9569f32..=2.0) {
        // Empty for ω ≤ 0.0432 and full for ω > 0.9568, for every normal (mask.rs).
        let np = project_normal(n, Vec3::X, Vec3::Y);
        prop_assert_eq!(visibility_mask(omega_lo, np, MaskPlacement::Derived), 0);
        prop_assert_eq!(visibility_mask(omega_hi, np, MaskPlacement::Derived), FULL_MASK);
    }

    #[test]
    fn flipping_normal_and_distance_complements_the_mask(n in unit(), omega in -0.5f32..1.5,
        placement in prop_oneof![Just(MaskPlacement::Derived), Just(MaskPlacement::AuthorsCode), Just(MaskPlacement::PaperEq8)]) {
        // ω ↔ 1 − ω flips the sign of d/R_c. Tolerance: the boundary cells, at most
        // one per row (6 in all), where a centre lies within rounding of the line.
        let np = project_normal(n, Vec3::X, Vec3::Y);
        let a = visibility_mask(omega, np, placement);
        let b = visibility_mask(1.0 - omega, -np, placement);
        let rows = [0x0000_000fu32, 0x0000_03f0, 0x0000_fc00, 0x003f_0000, 0x0fc0_0000, 0xf000_0000];
        for r in rows {
            let both = (a & b & r).count_ones();
            let neither = (!(a | b) & r).count_ones();
            prop_assert!(both + neither <= 1, "row {r:08x}: a {a:032b} b {b:032b}");
        }
    }

    #[test]
    fn aggregation_stays_in_convex_hull(samples in prop::collection::vec((0.0f32..1.0, (0.0f32..4.0, 0.0f32..4.0, 0.0f32..4.0)), 0..9),
        bg in (0.0f32..4.0, 0.0f32..4.0, 0.0f32..4.0), bgw in 0.0f32..1.0) {
        let mut a = Aggregate::new();
        let bg = Vec3::new(bg.0, bg.1, bg.2);
        let (mut lo, mut hi) = (bg, bg);
        for &(w, (r, g, b)) in &samples {
            let c = Vec3::new(r, g, b);
            a.add(w, c);
            lo = lo.min(c);
            hi = hi.max(c);
        }
        let out = a.resolve(bg, bgw);
        let tol = Vec3::splat(4e-6);
        prop_assert!(out.is_finite());
        prop_assert!(out.cmpge(lo - tol).all() && out.cmple(hi + tol).all(), "{out} outside [{lo}, {hi}]");
    }

    #[test]
    fn cone_occlusion_is_monotone_in_d(d1 in -1e3f32..1e3, d2 in -1e3f32..1e3, rc in prop_oneof![Just(0.0f32), 1e-30f32..1e3]) {
        let (lo, hi) = if d1 <= d2 { (d1, d2) } else { (d2, d1) };
        prop_assert!(cone_occlusion(hi, rc) <= cone_occlusion(lo, rc));
    }

    #[test]
    fn backtrace_never_passes_t_and_is_strict_when_it_can_be(t in 0.0f32..1e8, tan in prop_oneof![Just(0.0f32), 1e-10f32..1.0]) {
        let ts = backtrace_cone_entry(t, tan);
        prop_assert!(ts <= t && ts >= 0.0);
        let ulp = t.next_up() - t;
        if t * tan > ulp {
            prop_assert!(ts < t, "t {t} tan {tan}: ts {ts}");
        }
    }

    #[test]
    fn backtraced_entry_cone_misses_a_plane(o in (-1.0f32..1.0, -1.0f32..1.0), dir in unit(), pn in unit(),
        dist in 0.5f32..50.0, tan in 1e-4f32..0.05) {
        // A plane n·p = −dist (the origin is `dist` outside it), traced from o.
        let origin = Vec3::new(o.0, o.1, 0.0);
        let sdf = |p: Vec3| pn.dot(p) + dist;
        prop_assume!(sdf(origin) > 0.1);
        check_entry_is_safe(origin, dir, tan, sdf)?;
    }

    #[test]
    fn backtraced_entry_cone_misses_a_sphere(dir in unit(), c in unit(), dist in 2.0f32..50.0, radius in 0.05f32..1.0, tan in 1e-4f32..0.05) {
        let centre = c * dist;
        let sdf = |p: Vec3| (p - centre).length() - radius;
        check_entry_is_safe(Vec3::ZERO, dir, tan, sdf)?;
    }
}

/// At each group's backtraced entry t_s (eq. 10), the safe cone of radius
/// R_s = t_s·tan θ must not reach the surface: d(t_s) ≥ R_s. (Exact when the
/// previous step saw no soft hit, since then t_s ≥ t_{i−1} and the sphere-tracing
/// ball at t_{i−1} bounds d(t_s).) Tolerance: f32 rounding of p = o + t·d,
/// 8 ulps of |p| plus 8 ulps of R_s.
fn check_entry_is_safe(
    origin: Vec3,
    dir: Vec3,
    tan: f32,
    sdf: impl Fn(Vec3) -> f32,
) -> Result<(), TestCaseError> {
    let params = CtssParams::new(tan).with_range(0.0, 200.0);
    let mut s = ConeStepper::new(&params);
    let mut first = true;
    loop {
        let t = s.t();
        let ev = s.advance(sdf(origin + t * dir));
        match ev {
            Event::March => {}
            Event::Sample(g) => {
                if g.t_entry > 0.0 && !first {
                    let ts = g.t_entry;
                    let p = origin + ts * dir;
                    let rs = cone_radius(ts, tan);
                    let tol = 8.0 * f32::EPSILON * (p.length() + rs);
                    prop_assert!(sdf(p) >= rs - tol, "entry {ts}: d {} < R_s {rs}", sdf(p));
                }
                s.record(&g, Vec2::Y);
            }
            Event::Stop(_) => return Ok(()),
            e => panic!("an event this test does not know: {e:?}"),
        }
        first = false;
    }
}

proptest! {
    #![proptest_config(config())]

    /// The one-pass multi-layer reconstruction equals per-layer reconstruction,
    /// bit for bit.
    #[test]
    fn layered_reconstruction_equals_per_layer(p in params(), tn in unit(), tz in depth(), ts in 0u32..4,
        ns in prop::collection::vec((unit(), 0.8f32..1.25, 0u32..4, prop::collection::vec((0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0), 3)), 1..10)) {
        let gates = [None, Some(0u8), Some(1u8)];
        let colors: Vec<Vec<Vec3>> = ns.iter().map(|n| n.3.iter().map(|&(r, g, b)| Vec3::new(r, g, b)).collect()).collect();
        let target = Geometry::new(tn, tz);
        let mut out = [Vec3::ZERO; 3];
        reconstruct_layers(&p, &target, ts, &gates, ns.iter().enumerate().map(|(k, n)| LayeredSample {
            geometry: Geometry::new(n.0, tz * n.1), shadow: n.2, distance2: k as f32, colors: &colors[k],
        }), &mut out);
        for (i, gate) in gates.iter().enumerate() {
            let single = reconstruct(&p, &target, gate.map(|b| ts >> b & 1 != 0), ns.iter().enumerate().map(|(k, n)| ShadedSample {
                geometry: Geometry::new(n.0, tz * n.1), color: colors[k][i], shadowed: gate.is_some_and(|b| n.2 >> b & 1 != 0), distance2: k as f32,
            }));
            prop_assert_eq!(out[i], single.color, "layer {}", i);
        }
    }
}

proptest! {
    #![proptest_config(config())]

    /// Where `needs_normal` says the normal does not matter, every normal gives
    /// the same mask.
    #[test]
    fn masks_that_need_no_normal_ignore_it(omega in -1.0f32..2.0, a in unit(), b in unit(),
        placement in prop_oneof![Just(MaskPlacement::Derived), Just(MaskPlacement::AuthorsCode)]) {
        if !needs_normal(omega, placement) {
            let (na, nb) = (project_normal(a, Vec3::X, Vec3::Y), project_normal(b, Vec3::X, Vec3::Y));
            prop_assert_eq!(visibility_mask(omega, na, placement), visibility_mask(omega, nb, placement));
        }
    }
}

/// The frames of `resolver_equals_per_subsample_path`, drawn from the
/// tests' deterministic generator.
struct Rng(Lcg);

impl Rng {
    fn below(&mut self, n: u32) -> u32 {
        self.0.next_u32() % n
    }
    fn unit(&mut self) -> f32 {
        self.0.next_u32() as f32 / (1u64 << 31) as f32
    }
    /// Normals from a small set (equal normals are the common case) or random.
    fn normal(&mut self) -> Vec3 {
        match self.below(6) {
            0 => Vec3::Z,
            1 => Vec3::Y,
            2 => Vec3::new(0.0, 0.6, 0.8),
            3 => Vec3::new(f32::NAN, 0.0, 1.0),
            _ => Vec3::new(self.unit() - 0.5, self.unit() - 0.5, self.unit() + 0.1).normalize(),
        }
    }
    fn geometry(&mut self) -> Geometry {
        let depth = match self.below(8) {
            0 => f32::INFINITY,
            1 => f32::NAN,
            2 => 1.0,
            3 => 1.05,
            _ => 0.5 + 4.0 * self.unit(),
        };
        Geometry::new(self.normal(), depth)
    }
    fn color(&mut self) -> Vec3 {
        match self.below(10) {
            0..=2 => Vec3::ZERO,
            3 => Vec3::new(f32::NAN, 0.0, 0.0),
            4 => Vec3::new(0.0, f32::INFINITY, 1.0),
            5 => Vec3::splat(1e-30),
            _ => Vec3::new(self.unit(), self.unit(), self.unit()),
        }
    }
    fn albedo(&mut self) -> Vec3 {
        [
            Vec3::splat(0.8),
            Vec3::new(0.8, 0.1, 0.1),
            Vec3::new(0.78, 0.8, 0.8),
        ][self.below(3) as usize]
    }
    fn subsamples(&mut self, material: bool) -> Subsamples {
        Subsamples {
            geometry: core::array::from_fn(|_| self.geometry()),
            shadow: core::array::from_fn(|_| self.below(4)),
            albedo: material.then(|| core::array::from_fn(|_| self.albedo())),
        }
    }
}

/// The per-subsample, per-group path the CPU backend took before
/// [`Resolver`]: [`reconstruct_layers`] (or its material form) over
/// [`neighbourhood`] for each subsample and group, layers summed, then
/// [`resolve_pixel`].
fn per_subsample_path(
    p: &SraaParams,
    gates: &[Option<u8>],
    frame: &ShadedFrame,
    x: u32,
    y: u32,
    primary: &Subsamples,
    secondary: Option<&Subsamples>,
) -> Vec3 {
    let mut subs = [Vec3::ZERO; 4];
    for (k, sub) in subs.iter_mut().enumerate() {
        let run = |group: &ShadedGroup, targets: &Subsamples, albedo: Option<Vec3>| {
            let hood = neighbourhood(
                x,
                y,
                k,
                p.shaded_offset(),
                p.radius(),
                frame.width,
                frame.height,
            );
            let samples = hood.map(|np| {
                let j = (np.y * frame.width + np.x) as usize;
                let base = j * frame.layers + group.first_layer;
                let s = LayeredSample {
                    geometry: group.geometry[j],
                    shadow: group.shadow.get(j).copied().unwrap_or(0),
                    distance2: np.distance2,
                    colors: &frame.colors[base..base + gates.len()],
                };
                (s, frame.albedo.get(j).copied().unwrap_or(Vec3::ZERO))
            });
            let mut out = [Vec3::ZERO; MAX_LAYERS];
            let (t, ts) = (&targets.geometry[k], targets.shadow[k]);
            match albedo {
                Some(a) => reconstruct_layers_material(
                    p,
                    t,
                    ts,
                    a,
                    ALBEDO_TOLERANCE,
                    gates,
                    samples,
                    &mut out,
                ),
                None => reconstruct_layers(p, t, ts, gates, samples.map(|(s, _)| s), &mut out),
            }
            out[..gates.len()].iter().fold(Vec3::ZERO, |a, c| a + *c)
        };
        *sub = run(&frame.primary, primary, primary.albedo.map(|a| a[k]));
        if let (Some(g), Some(s)) = (frame.secondary.as_ref(), secondary) {
            if !s.geometry[k].depth.is_nan() {
                *sub += run(g, s, None);
            }
        }
    }
    resolve_pixel(&subs)
}

proptest! {
    #![proptest_config(config())]

    /// The frame resolver equals the per-subsample path bit for bit, on
    /// random frames (misses, NaN geometry, black, non-finite and tiny
    /// colours, shadow bits, albedos, mirrors), every weight form, both
    /// shaded positions and radii 1 and 2, at every pixel (borders included).
    #[test]
    fn resolver_equals_per_subsample_path(seed in any::<u64>(), preset in 0usize..6) {
        let mut r = Rng(Lcg::new(seed));
        let p = match preset {
            0 => SraaParams::TUNED,
            1 => SraaParams::PAPER,
            2 => SraaParams::CHAJDAS.with_spatial(0.5),
            3 => SraaParams::TUNED.with_radius(2),
            4 => SraaParams::PAPER.with_depth_metric(DepthMetric::Absolute).with_spatial(r.unit()),
            _ => SraaParams {
                sigma_z: 30.0 * r.unit(),
                sigma_n: 4.0 * r.unit(),
                ..SraaParams::TUNED.with_spatial(0.05 + r.unit())
            },
        };
        let (w, h) = (1 + r.below(5), 1 + r.below(5));
        let n = (w * h) as usize;
        let all_gates = [None, Some(0u8), Some(1u8)];
        let gates = &all_gates[..1 + r.below(3) as usize];
        let mirrors = r.below(2) == 1;
        let material = r.below(3) == 0;
        let layers = gates.len() * if mirrors { 2 } else { 1 };
        let mut colors: Vec<Vec3> = (0..n * layers).map(|_| r.color()).collect();
        // Some layers one colour nearly everywhere (a lit wall, a black
        // layer), so that the uniform shortcut and its flags are reached.
        for l in 0..layers {
            if r.below(2) == 0 {
                let c = r.color();
                for j in 0..n {
                    if r.below(8) != 0 {
                        colors[j * layers + l] = c;
                    }
                }
            }
        }
        let geo: Vec<Geometry> = (0..n).map(|_| r.geometry()).collect();
        let geo2: Vec<Geometry> = (0..n).map(|_| r.geometry()).collect();
        let shadow: Vec<u32> = (0..n).map(|_| r.below(4)).collect();
        let shadow2: Vec<u32> = (0..n).map(|_| r.below(4)).collect();
        let albedo: Vec<Vec3> = if material { (0..n).map(|_| r.albedo()).collect() } else { Vec::new() };
        let frame = ShadedFrame {
            width: w,
            height: h,
            colors: &colors,
            layers,
            albedo: &albedo,
            primary: ShadedGroup { geometry: &geo, shadow: &shadow, first_layer: 0 },
            secondary: mirrors.then_some(ShadedGroup { geometry: &geo2, shadow: &shadow2, first_layer: gates.len() }),
        };
        let resolver = Resolver::new(&p, gates, ALBEDO_TOLERANCE);
        let mut flags = vec![LayerFlags::default(); n];
        let mut flags2 = vec![LayerFlags::default(); n];
        // Filled in two parts, as threads fill bands of rows.
        let half = r.below(n as u32 + 1) as usize;
        resolver.layer_flags(&frame, &frame.primary, 0, &mut flags[..half]);
        resolver.layer_flags(&frame, &frame.primary, half, &mut flags[half..]);
        if let Some(g) = frame.secondary.as_ref() {
            resolver.layer_flags(&frame, g, 0, &mut flags2);
        }
        let flags = FrameFlags { primary: &flags, secondary: if mirrors { &flags2 } else { &[] } };
        for i in 0..n as u32 {
            let (x, y) = (i % w, i / w);
            // Targets near the frame's own samples, so that weights are often 1.
            let mut primary = r.subsamples(material);
            let mut secondary = r.subsamples(false);
            for k in 0..4 {
                if r.below(2) == 0 {
                    primary.geometry[k] = geo[i as usize];
                    secondary.geometry[k] = geo2[i as usize];
                }
            }
            let secondary = mirrors.then_some(&secondary);
            let got = resolver.resolve(&frame, x, y, &primary, secondary);
            let want = per_subsample_path(&p, gates, &frame, x, y, &primary, secondary);
            prop_assert_eq!(got.to_array().map(f32::to_bits), want.to_array().map(f32::to_bits),
                "pixel ({}, {}): {} against {}", x, y, got, want);
            let flagged = resolver.resolve_flagged(&frame, &flags, x, y, &primary, secondary);
            prop_assert_eq!(flagged.to_array().map(f32::to_bits), want.to_array().map(f32::to_bits),
                "pixel ({}, {}) from the flags: {} against {}", x, y, flagged, want);
        }
    }
}
