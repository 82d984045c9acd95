//! Pins the conventions chosen where the papers are ambiguous or the authors'
//! code differs from them (see ARCHITECTURE.md, rule 3).
use glam::{Vec2, Vec3};
use subcone_kernels::aggregate::{sample_weight, Weighting};
use subcone_kernels::cone::*;
use subcone_kernels::ctss::{sphere_trace, trace, ConeStepper, CtssParams, Event, StopReason};
use subcone_kernels::mask::{cell_centre, visibility_mask, MaskPlacement, GRID_SCALE};
use subcone_kernels::sraa::*;

#[test]
fn rotated_grid_has_one_sample_per_row_and_column_of_the_4x4_grid() {
    let mut rows = [0; 4];
    let mut cols = [0; 4];
    for o in SUBPIXEL_OFFSETS {
        // Cell centres of a 4×4 grid over [−0.5, 0.5]² are at ±0.125, ±0.375.
        let c = ((o.x + 0.5) * 4.0 - 0.5, (o.y + 0.5) * 4.0 - 0.5);
        assert_eq!(c.0.fract(), 0.0, "{o} is not a cell centre");
        assert_eq!(c.1.fract(), 0.0, "{o} is not a cell centre");
        cols[c.0 as usize] += 1;
        rows[c.1 as usize] += 1;
        assert_eq!(
            o.length_squared(),
            0.15625,
            "all four are equidistant from the centre"
        );
    }
    assert_eq!(rows, [1; 4]);
    assert_eq!(cols, [1; 4]);
    const { assert!(SHADED_SUBSAMPLE < 4) };
}

#[test]
fn neighbourhood_is_the_fixed_radius_window() {
    let paper = SraaParams::PAPER.shaded_offset();
    assert_eq!(paper, SUBPIXEL_OFFSETS[SHADED_SUBSAMPLE]);
    let n: Vec<_> = neighbourhood(5, 5, SHADED_SUBSAMPLE, paper, 1, 10, 10).collect();
    assert_eq!(n.len(), 9);
    assert!(n.iter().any(|p| (p.x, p.y, p.distance2) == (5, 5, 0.0)));
    assert_eq!(
        neighbourhood(0, 0, 2, paper, 1, 10, 10).count(),
        4,
        "clipped at the corner"
    );
    assert_eq!(neighbourhood(5, 5, 1, paper, 2, 10, 10).count(), 25);
    // Subsample 1 is (0.5, 0.25) away from the shaded one of its own pixel.
    let own = neighbourhood(5, 5, 1, paper, 1, 10, 10)
        .find(|p| (p.x, p.y) == (5, 5))
        .unwrap();
    assert_eq!(own.distance2, 0.5f32 * 0.5 + 0.25 * 0.25);
    assert_eq!(
        neighbourhood(20, 20, 0, paper, 1, 10, 10).count(),
        0,
        "outside the image"
    );
    // The shaded sample at the centre: every subsample is |offset| from its
    // own pixel's shaded sample, and SHADED_SAMPLE is the shaded sample.
    let centre = SraaParams::TUNED.shaded_offset();
    assert_eq!(centre, Vec2::ZERO);
    for (k, offset) in SUBPIXEL_OFFSETS.iter().enumerate() {
        let own = neighbourhood(5, 5, k, centre, 1, 10, 10)
            .find(|p| (p.x, p.y) == (5, 5))
            .unwrap();
        assert_eq!(own.distance2, offset.length_squared());
    }
    let own = neighbourhood(5, 5, SHADED_SAMPLE, centre, 1, 10, 10)
        .find(|p| (p.x, p.y) == (5, 5))
        .unwrap();
    assert_eq!(own.distance2, 0.0);
}

/// §3.1: the cone's base passes through the pixel's four corners. For the pixel
/// on the optical axis (odd resolution), the corner ray's tangent is tan θ.
#[test]
fn cone_base_passes_through_the_pixel_corners() {
    for (fov, h) in [(0.8f32, 101u32), (1.2, 721), (0.1, 2161)] {
        let pixel = 2.0 * (fov as f64 / 2.0).tan() / h as f64;
        let corner = (pixel / 2.0) * std::f64::consts::SQRT_2; // |(p/2, p/2)| at unit distance
        let t = cone_tan_theta(fov, h, 1.0, PixelFootprint::Circumscribed) as f64;
        assert!(
            (t - corner).abs() <= 4.0 * f32::EPSILON as f64 * corner,
            "fov {fov} h {h}: {t} vs {corner}"
        );
        // Eq. 3 with F = 1/tan(fov/2) on the authors' 2-unit screen.
        let eq3 = std::f64::consts::SQRT_2 / ((1.0 / (fov as f64 / 2.0).tan()) * h as f64);
        assert!((t - eq3).abs() <= 4.0 * f32::EPSILON as f64 * eq3);
        // The authors' cone, 2·0.586/(I_y·F), is about 17 % narrower.
        let b = cone_tan_theta(fov, h, 1.0, PixelFootprint::Balanced) as f64;
        assert!((b / t - 0.828).abs() < 1e-3, "{}", b / t);
        assert_eq!(
            cone_tan_theta(fov, h, 2.0, PixelFootprint::Circumscribed),
            2.0 * t as f32
        );
    }
    assert_eq!(
        cone_tan_theta(f32::NAN, 100, 1.0, PixelFootprint::Circumscribed),
        0.0
    );
    assert_eq!(
        cone_tan_theta(1.0, 0, 1.0, PixelFootprint::Circumscribed),
        0.0
    );
}

#[test]
fn mask_rows_are_sampled_at_scaled_cell_centres() {
    // A vertical edge through the middle, solid on the left: columns 0–2 of each
    // 6-wide row and columns 1–2 of the 4-wide rows.
    let m = visibility_mask(0.5, Vec2::X, MaskPlacement::Derived);
    let want = 0x3 | (0x7 << 4) | (0x7 << 10) | (0x7 << 16) | (0x7 << 22) | (0x3 << 28);
    assert_eq!(m, want, "{m:032b}");
    assert_eq!(cell_centre(0), Vec2::new(-0.5, -5.0 / 6.0) * GRID_SCALE);
    assert_eq!(cell_centre(31), Vec2::new(0.5, 5.0 / 6.0) * GRID_SCALE);
    // 32 cells of side 2s/6 have the unit disk's area.
    let area = 32.0 * (2.0 * GRID_SCALE / 6.0).powi(2);
    assert!((area - std::f32::consts::PI).abs() < 1e-5, "{area}");
}

#[test]
fn mask_placements_differ_as_documented() {
    // A soft hit (d = +0.4·R_c, ω = 0.3) on a surface seen at 60° from edge-on
    // (|n_p| = 0.5): the solid covers less than half of the disk.
    let np = Vec2::new(0.5, 0.0);
    let derived = visibility_mask(0.3, np, MaskPlacement::Derived).count_ones();
    let authors = visibility_mask(0.3, np, MaskPlacement::AuthorsCode).count_ones();
    let paper = visibility_mask(0.3, np, MaskPlacement::PaperEq8).count_ones();
    // Derived: line at h = −0.8, a thin sliver. Authors: h = −0.4. Eq. 8: h = +0.2,
    // more than half, the wrong side of the middle.
    assert!(
        derived < authors && authors < 16 && paper > 16,
        "{derived} {authors} {paper}"
    );
}

#[test]
fn sample_weight_floor_is_off_by_default_and_001_for_the_authors_code() {
    assert_eq!(CtssParams::new(0.01).min_sample_weight, 0.0);
    assert_eq!(CtssParams::new(0.01).authors_code().min_sample_weight, 0.01);
    assert_eq!(sample_weight(0, Weighting::Visibility, 0.0), 0.0);
    assert_eq!(sample_weight(0, Weighting::Visibility, 0.01), 0.01);
    assert_eq!(sample_weight(0xffff, Weighting::Visibility, 0.01), 0.5);
    assert_eq!(sample_weight(0, Weighting::Uniform, 0.0), 1.0);
}

/// §3.6: the first hard hit is sampled at t_{i−1} + d_{i−1}, not at t_i
/// (Algorithm 1, line 14).
#[test]
fn first_hard_hit_is_sampled_at_the_last_safe_depth() {
    let tan = 0.01;
    // A plane crossing the ray at t = 10, tilted 60° from head-on (d = cos 60°·(10 − t)),
    // so sphere tracing converges geometrically until the minimum step overshoots.
    let plane = 10.0f32;
    let mut s = ConeStepper::new(&CtssParams::new(tan));
    let mut history = Vec::new();
    let sample = loop {
        let t = s.t();
        let d = 0.5 * (plane - t);
        history.push((t, d));
        match s.advance(d) {
            Event::March => {}
            Event::Sample(g) => break g,
            Event::Stop(r) => panic!("stopped without a sample: {r:?}"),
            e => panic!("an event this test does not know: {e:?}"),
        }
    };
    let hard = OcclusionThresholds::PAPER.hard;
    let i = history
        .iter()
        .position(|&(t, d)| cone_occlusion(d, cone_radius(t, tan)) > hard)
        .unwrap();
    assert!(i > 0);
    let (tp, dp) = history[i - 1];
    assert!(sample.hard);
    assert_eq!(sample.t, tp + dp);
    assert!(
        sample.t < history[i].0,
        "the hard hit itself lies beyond the safe depth"
    );
    assert!(sample.t_entry <= sample.t);
}

/// The authors' sample cap of 8 is our default.
#[test]
fn sample_cap_is_eight() {
    let params = CtssParams::new(0.01).with_range(1.0, 20.0);
    assert_eq!(params.max_samples, 8);
    let mut s = ConeStepper::new(&params);
    // Soft, never hard, groups once per unit of depth.
    let d_of = |t: f32| {
        let rc = cone_radius(t, 0.01);
        if t.fract() < 0.2 {
            0.6 * rc
        } else {
            3.0 * rc
        }
    };
    let stop = loop {
        match s.advance(d_of(s.t())) {
            Event::March => {}
            Event::Sample(g) => {
                assert!(!g.hard);
                s.record(&g, Vec2::Y);
            }
            Event::Stop(r) => break r,
            e => panic!("an event this test does not know: {e:?}"),
        }
    };
    assert_eq!((s.samples(), stop), (8, StopReason::SampleCap));
}

/// NoAA uses the same adaptive cone-based threshold as CTSS (§4): it stops at the
/// first depth with ω > 0.5 − ε, i.e. d < 2ε·R_c, and not before.
#[test]
fn noaa_stops_at_the_cone_based_hard_threshold() {
    let p = CtssParams::new(0.004);
    let plane = 7.5f32;
    let mut seen = Vec::new();
    let hit = sphere_trace(&p, Vec3::ZERO, Vec3::NEG_Z, |q| {
        let d = plane - (-q.z);
        seen.push(d);
        d
    });
    let t = hit.t.expect("the plane is hit");
    let rc = cone_radius(t, p.tan_theta);
    assert!(
        plane - t < 2.0 * p.eps * rc + 1e-6,
        "stopped at d = {} with R_c = {rc}",
        plane - t
    );
    assert_eq!(hit.stop, StopReason::HardHit);
    // Every earlier evaluation was above the threshold.
    assert!(seen[..seen.len() - 1].iter().all(|&d| d > 0.0));
    // The loosest NoAA cannot be bought: CTSS's hard threshold is the same number.
    assert_eq!(p.thresholds().hard, 0.5 - p.eps);
}

#[test]
fn background_is_a_sample() {
    let sphere = |p: Vec3| (p - Vec3::new(0.0, 0.0, -5.0)).length() - 1.0;
    let normal = |p: Vec3| (p - Vec3::new(0.0, 0.0, -5.0)).normalize();
    let p = CtssParams::new(0.01).with_range(0.0, 50.0);
    let run = |dir: Vec3| {
        trace(
            &p,
            Vec3::ZERO,
            dir.normalize(),
            Vec3::X,
            Vec3::Y,
            sphere,
            normal,
            |_, _| Vec3::ONE,
            Vec3::ZERO,
        )
    };
    // A clean miss is pure background.
    let miss = run(Vec3::new(0.0, 1.0, -1.0));
    assert_eq!((miss.color, miss.samples), (Vec3::ZERO, 0));
    // A head-on hit is pure surface, with no background weight.
    assert_eq!(run(Vec3::NEG_Z).color, Vec3::ONE);
    // A near miss at the silhouette is a blend, weighted by the mask.
    let edge = run(Vec3::new(0.0, 0.2041, -1.0));
    assert!(
        edge.samples >= 1 && edge.color.x > 0.0 && edge.color.x < 1.0,
        "{edge:?}"
    );
    assert_eq!(edge.color.x, edge.coverage.count_ones() as f32 / 32.0);
}
