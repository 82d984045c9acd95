//! Hit group subdivision at internal edges (CTSS §5.2–5.3): the criterion, the
//! quadrant split of the mask, and whole traces across a box edge seen between
//! two faces of one box.
use glam::{Vec2, Vec3};
use proptest::prelude::*;
use subcone_kernels::ctss::{
    coarse_normal_step, cross_section_frame, group_needs_split, split_direction, split_group,
    split_weights, tetra_normal, trace, CtssParams, GroupSample, SplitRay, SPLIT_LENGTH_RATIO,
    SPLIT_MAX_STEPS, SPLIT_OFFSETS, SPLIT_QUADRANTS,
};
use subcone_kernels::mask::{cell_centre, FULL_MASK};

/// A cone of `tan θ` for a 64-pixel-high image with a 30° field of view.
const TAN: f32 = 0.006;

/// A unit cube centred at (0, 0, 5), turned 45° about y: seen from the origin
/// along +z, its front is a vertical edge at x = 0 between two faces, one
/// facing (−1, 0, −1), the other (1, 0, −1).
fn turned_box(p: Vec3) -> f32 {
    let q = p - Vec3::new(0.0, 0.0, 5.0);
    let (s, c) = std::f32::consts::FRAC_PI_4.sin_cos();
    let q = Vec3::new(c * q.x - s * q.z, q.y, s * q.x + c * q.z);
    let d = q.abs() - Vec3::splat(0.5);
    d.max(Vec3::ZERO).length() + d.max_element().min(0.0)
}

fn box_normal(p: Vec3) -> Vec3 {
    tetra_normal(turned_box, p, 1e-4)
}

/// The left face (normal x < 0) is red, the right one green: the pixel colour
/// is the share of each face it sees.
fn face_colour(_p: Vec3, n: Vec3) -> Vec3 {
    if n.x < 0.0 {
        Vec3::X
    } else {
        Vec3::Y
    }
}

fn params(split: bool) -> CtssParams {
    CtssParams::new(TAN)
        .with_range(0.0, 100.0)
        .with_split_groups(split)
}

/// The pixel whose ray goes through `(x, 0, 1)` (x in depth-1 units).
fn pixel(x: f32, split: bool) -> subcone_kernels::ctss::TraceResult {
    let dir = Vec3::new(x, 0.0, 1.0).normalize();
    let (right, up) = cross_section_frame(dir, Vec3::Y);
    trace(
        &params(split),
        Vec3::ZERO,
        dir,
        right,
        up,
        turned_box,
        box_normal,
        face_colour,
        Vec3::ZERO,
    )
}

/// The same pixel supersampled: a 16×16 grid of thin rays over the cone's
/// footprint square (the cone's disk passes through the pixel's corners, so
/// the pixel's half-side is `R_c/√2` at unit depth).
fn reference(x: f32) -> Vec3 {
    let half = TAN / std::f32::consts::SQRT_2;
    let n = 16;
    let mut sum = Vec3::ZERO;
    let thin = CtssParams::new(1e-7).with_range(0.0, 100.0);
    for i in 0..n {
        for j in 0..n {
            let ox = x + half * (2.0 * (i as f32 + 0.5) / n as f32 - 1.0);
            let oy = half * (2.0 * (j as f32 + 0.5) / n as f32 - 1.0);
            let dir = Vec3::new(ox, oy, 1.0).normalize();
            let hit = subcone_kernels::ctss::sphere_trace(&thin, Vec3::ZERO, dir, turned_box);
            if let Some(t) = hit.t {
                let p = dir * t;
                sum += face_colour(p, box_normal(p));
            }
        }
    }
    sum / (n * n) as f32
}

#[test]
fn quadrants_partition_the_mask_by_the_sign_of_the_cell_centre() {
    let mut all = 0u32;
    for (j, q) in SPLIT_QUADRANTS.iter().enumerate() {
        assert_eq!(q.count_ones(), 8, "quadrant {j}");
        assert_eq!(all & q, 0, "quadrant {j} overlaps another");
        all |= q;
        let mut mean = Vec2::ZERO;
        for bit in 0..32 {
            let c = cell_centre(bit);
            let expect = match (c.x > 0.0, c.y > 0.0) {
                (false, false) => 0,
                (true, false) => 1,
                (false, true) => 2,
                (true, true) => 3,
            };
            assert_eq!(q & (1 << bit) != 0, expect == j, "bit {bit} at {c}");
            if q & (1 << bit) != 0 {
                mean += c / 8.0;
            }
        }
        assert!(
            (mean - SPLIT_OFFSETS[j]).length() < 1e-6,
            "offset {j}: {mean} vs {}",
            SPLIT_OFFSETS[j]
        );
    }
    assert_eq!(all, FULL_MASK);
}

/// A plane seen face-on: fine and coarse normals agree, the group is short.
#[test]
fn no_split_on_a_flat_surface() {
    let plane = |p: Vec3| 5.0 - p.z;
    let p = Vec3::new(0.1, -0.2, 5.0);
    let h = coarse_normal_step(5.0, &params(true));
    let fine = tetra_normal(plane, p, 0.25 * h);
    let coarse = tetra_normal(plane, p, h);
    let rc = 5.0 * TAN;
    assert!(!group_needs_split(
        fine,
        coarse,
        2.5 * rc,
        5.0,
        &params(true)
    ));
    // Whole traces on a face far from the edge: one sample, its face's colour.
    for x in [-0.06, 0.06] {
        let r = pixel(x, true);
        assert_eq!(r.samples, 1, "x = {x}: {r:?}");
        assert_eq!(r.color, pixel(x, false).color, "x = {x}");
    }
}

/// Across the box's front edge the coarse normal straddles both faces.
#[test]
fn split_on_a_box_edge() {
    // The front edge is at (0, 0, 5 − √2/2); a point of the left face one
    // fifth of a cone radius from it.
    let t = 5.0 - std::f32::consts::FRAC_1_SQRT_2;
    let rc = t * TAN;
    let p = Vec3::new(-0.2 * rc, 0.0, t + 0.2 * rc);
    let h = coarse_normal_step(t, &params(true));
    let fine = tetra_normal(turned_box, p, 0.25 * h);
    let coarse = tetra_normal(turned_box, p, h);
    assert!(
        group_needs_split(fine, coarse, 2.5 * rc, t, &params(true)),
        "fine {fine}, coarse {coarse}: {}°",
        fine.dot(coarse).acos().to_degrees()
    );
    // A long group splits whatever its normals.
    let n = Vec3::Z;
    assert!(group_needs_split(
        n,
        n,
        (SPLIT_LENGTH_RATIO + 0.5) * rc,
        t,
        &params(true)
    ));
    assert!(!group_needs_split(
        n,
        n,
        (SPLIT_LENGTH_RATIO - 0.5) * rc,
        t,
        &params(true)
    ));
}

/// Pixels straddling the internal edge, at 16 offsets evenly spread over the
/// edge crossing the footprint (none exactly on it: there the fine and coarse
/// normals are the same symmetric blend and the group is not split, a blind
/// spot of measure zero): plain CTSS paints each pixel with one face; the
/// split shades both and lands nearer the supersampled truth. The bound: for
/// a straight edge at a uniformly distributed offset, a single sample errs by
/// a quarter of the contrast on average, a 2×2 stratified estimate by an
/// eighth, half as much; our sub-samples sit at 0.43 cone radii instead of
/// the pixel quadrants' 0.35 and groups whose edge is near the footprint's
/// rim are not split, so we require three quarters, not a half.
#[test]
fn split_follows_the_edge_inside_a_pixel() {
    let xs: Vec<f32> = (-8..8).map(|i| (i as f32 + 0.5) * 0.15 * TAN).collect();
    let (mut e_ctss, mut e_split) = (0.0f32, 0.0f32);
    for &x in &xs {
        let r = reference(x);
        let (a, b) = (pixel(x, false), pixel(x, true));
        assert!(b.color.is_finite(), "{b:?}");
        let err = |c: Vec3| ((c - r).abs().x + (c - r).abs().y) * 0.5;
        e_ctss += err(a.color);
        e_split += err(b.color);
        println!(
            "x {x:+.5}: ref {:.3} ctss {:.3} (1 sample) split {:.3} ({} samples)",
            r.x, a.color.x, b.color.x, b.samples
        );
        assert!(b.steps > a.steps || b.samples == 1);
    }
    let (e_ctss, e_split) = (e_ctss / xs.len() as f32, e_split / xs.len() as f32);
    println!(
        "mean |Δ| over {} edge pixels: ctss {e_ctss:.4}, split {e_split:.4}",
        xs.len()
    );
    assert!(e_split < 0.75 * e_ctss, "split {e_split} vs ctss {e_ctss}");
}

#[test]
fn non_finite_inputs_never_split() {
    let p = params(true);
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let v = Vec3::splat(bad);
        // A plane-like group length: 2 cone radii at depth 5.
        let len = 2.0 * 5.0 * TAN;
        assert!(!group_needs_split(v, Vec3::Z, len, 5.0, &p));
        assert!(!group_needs_split(Vec3::Z, v, len, 5.0, &p));
        assert!(!group_needs_split(Vec3::Z, Vec3::Z, bad, 5.0, &p));
        assert!(!group_needs_split(Vec3::Z, Vec3::Z, len, bad, &p));
        let mut q = p;
        q.tan_theta = bad;
        assert!(!group_needs_split(Vec3::Z, Vec3::Z, len, 5.0, &q));
        assert_eq!(split_weights(FULL_MASK, bad), None);
    }
    assert!(!group_needs_split(Vec3::ZERO, Vec3::X, 0.0, 5.0, &p));
    assert_eq!(split_weights(0, 1.0), None);
}

/// A NaN field or NaN sample depths end every sub-trace without a hit.
#[test]
fn split_group_survives_nan() {
    let ray = SplitRay {
        origin: Vec3::ZERO,
        dir: Vec3::Z,
        right: Vec3::X,
        up: Vec3::Y,
    };
    let s = GroupSample {
        t: 5.0,
        t_entry: 4.9,
        t_exit: 5.1,
        occlusion: 1.0,
        t_occlusion: 5.05,
        t_first: 4.95,
        t_last: 5.1,
        hard: true,
    };
    let g = split_group(&params(true), &s, &ray, FULL_MASK, 1.0, |_| {
        (f32::NAN, f32::NAN)
    })
    .expect("split");
    assert!(g.parts.iter().all(|p| p.t.is_none() && p.weight == 0.25));
    let nan = GroupSample {
        t: f32::NAN,
        t_entry: f32::NAN,
        t_exit: f32::NAN,
        t_occlusion: f32::NAN,
        t_first: f32::NAN,
        t_last: f32::NAN,
        ..s
    };
    let g = split_group(&params(true), &nan, &ray, FULL_MASK, 1.0, |p| {
        let d = 5.0 - p.z;
        (d, d)
    })
    .expect("split");
    assert!(g.steps <= 4 * SPLIT_MAX_STEPS);
    assert!(g.parts.iter().all(|p| p.dir.is_finite()));
}

fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        any::<u32>().prop_map(f32::from_bits),
        Just(f32::NAN),
        Just(f32::INFINITY),
        -1e3f32..1e3,
    ]
}

fn any_vec3() -> impl Strategy<Value = Vec3> {
    (any_f32(), any_f32(), any_f32()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Arbitrary bits: no panic; with a non-finite normal and a non-finite
    /// length, never a split.
    #[test]
    fn criterion_is_total(a in any_vec3(), b in any_vec3(), len in any_f32(), depth in any_f32(), tan in any_f32()) {
        let mut p = params(true);
        p.tan_theta = tan;
        let split = group_needs_split(a, b, len, depth, &p);
        if (!a.is_finite() || !b.is_finite()) && !len.is_finite() {
            prop_assert!(!split);
        }
    }

    /// The split shares never change the group's weight.
    #[test]
    fn split_weights_sum_to_the_group_weight(v in any::<u32>(), w in 0.0f32..=1.0) {
        match split_weights(v, w) {
            None => prop_assert_eq!(v, 0),
            Some(ws) => {
                let sum: f32 = ws.iter().sum();
                prop_assert!((sum - w).abs() <= 1e-6, "{:?} sums to {} not {}", ws, sum, w);
                for (j, wj) in ws.iter().enumerate() {
                    prop_assert!(*wj >= 0.0);
                    prop_assert_eq!(*wj == 0.0, v & SPLIT_QUADRANTS[j] == 0);
                }
            }
        }
    }

    /// Any plane, any point on it, any depth: the fine and coarse normals agree
    /// and a group of plane-like length never splits.
    #[test]
    fn planes_never_split(nx in -1.0f32..1.0, ny in -1.0f32..1.0, nz in 0.2f32..1.0, depth in 0.5f32..200.0) {
        let n = Vec3::new(nx, ny, nz).normalize();
        let p0 = Vec3::new(0.0, 0.0, depth);
        let plane = |p: Vec3| n.dot(p - p0);
        let pr = params(true);
        let h = coarse_normal_step(depth, &pr);
        let fine = tetra_normal(plane, p0, 0.25 * h);
        let coarse = tetra_normal(plane, p0, h);
        let rc = depth * TAN;
        prop_assert!(!group_needs_split(fine, coarse, 2.0 * rc / n.z.max(0.25), depth, &pr));
    }

    /// Sub-ray directions are unit and finite for unit rays.
    #[test]
    fn split_directions_are_unit(j in 0usize..4, tan in any_f32()) {
        let d = split_direction(Vec3::Z, Vec3::X, Vec3::Y, tan, SPLIT_OFFSETS[j]);
        prop_assert!(d.is_finite());
        prop_assert!((d.length() - 1.0).abs() < 1e-5);
    }
}
