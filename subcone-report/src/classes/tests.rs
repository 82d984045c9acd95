use glam::Vec3;
use subcone_scene::{Frame, Method};

use super::*;
use crate::key::named;
use crate::named::{SRAA, SRAA_RT};

#[test]
fn bits_hold_each_pixels_classes() {
    let mut masks: [Vec<bool>; 6] = Default::default();
    for (i, m) in masks.iter_mut().enumerate() {
        // Pixel p is in class i when bit i of p is set.
        *m = (0..64u32).map(|p| p & (1 << i) != 0).collect();
    }
    let c = ClassMasks {
        width: 8,
        height: 8,
        masks,
        near_edge: vec![false; 64],
        ssim_near_edge: vec![false; 64],
        ssim_flat: vec![false; 64],
    };
    assert_eq!(c.bits(), (0..64u8).collect::<Vec<_>>());
}

/// The classes the method named `name` claims, none for any other name.
fn claimed(name: &str) -> Vec<Class> {
    name.parse::<Method>()
        .map(|m| m.claims())
        .unwrap_or_default()
}

#[test]
fn claims_follow_the_table() {
    use Class::*;
    assert_eq!(claimed("noaa"), vec![]);
    assert_eq!(claimed("ssaa4").len(), 5);
    assert_eq!(claimed("ssaa4+ctss").len(), 5);
    assert_eq!(claimed("sraa"), vec![Silhouette, Crease]);
    assert_eq!(claimed("sraa+mat"), vec![Silhouette, Crease, Texture]);
    assert_eq!(claimed("sraa-rt-paper+mat"), claimed("sraa-rt+mat"));
    assert_eq!(claimed("sraa-paper"), claimed("sraa"));
    assert_eq!(
        claimed("sraa-rt+mat"),
        vec![Silhouette, Crease, Shadow, Texture, Reflection]
    );
    assert_eq!(claimed("ctss-r-delayed"), vec![Silhouette]);
    assert_eq!(claimed("ctss+edges"), vec![Silhouette, Crease]);
    assert_eq!(claimed("ctss-paper"), vec![Silhouette]);
    assert_eq!(claimed("ctss-delayed-paper"), vec![Silhouette]);
    assert_eq!(claimed("ctss+edges-paper"), vec![Silhouette, Crease]);
    assert_eq!(claimed("ssaa4+ctss-paper").len(), 5);
    // A post-process row claims through its row, not its name.
    assert_eq!(claimed("smaa"), vec![]);
    let mut row = crate::ResultRow::timed(
        "s",
        crate::key::named("smaa"),
        "cpu",
        (1, 1),
        1,
        &Default::default(),
    );
    assert_eq!(row.claims(), vec![]);
    row.post_process = Some("SMAA".into());
    assert_eq!(row.claims(), vec![Silhouette, Crease, Shadow, Texture]);
    row.method = crate::key::named("sraa");
    assert_eq!(row.claims(), vec![Silhouette, Crease, Shadow, Texture]);
    assert!(!claimed("ssaa16").contains(&Flat));
}

fn cf(flips: [Option<f64>; 6]) -> ClassError {
    ClassError {
        mean: flips,
        px: flips.map(|f| f.map_or(0, |_| 100)),
        ..Default::default()
    }
}

#[test]
fn judgement_applies_the_factors() {
    let noaa = cf([Some(0.2), Some(0.2), Some(0.2), None, Some(0.1), Some(0.01)]);
    // 0.19 = 0.95 × 0.2 beats (at most the factor), 0.1901 does not.
    let it = cf([
        Some(0.19),
        Some(0.1901),
        Some(0.5),
        None,
        Some(0.0),
        Some(0.0102),
    ]);
    let v = Verdict::judge(SRAA_RT, &it, &noaa);
    assert_eq!(
        v.beats.iter().map(|b| b.0).collect::<Vec<_>>(),
        vec![Class::Silhouette, Class::Reflection]
    );
    assert_eq!(
        v.misses.iter().map(|b| b.0).collect::<Vec<_>>(),
        vec![Class::Crease, Class::Shadow]
    );
    assert!(v.absent.is_empty());
    assert!(v.holds_on_flat());
    let worse = cf([None, None, None, None, None, Some(0.01021)]);
    assert!(!Verdict::judge(SRAA, &worse, &noaa).holds_on_flat());
    let line = v.line("cpu");
    assert!(
        line.starts_with("- **sraa-rt** (cpu, FLIP): beats NoAA on silhouette (0.1900 vs 0.2000)"),
        "{line}"
    );
    assert!(line.contains("flat: holds"));
    // A texture claim without texture pixels is absent.
    let v = Verdict::judge("sraa+mat".parse().unwrap(), &it, &noaa);
    assert_eq!(v.absent, vec![Class::Texture]);
}

/// NoAA's error at four offsets, and a method's at `ratios` of it,
/// per offset, on silhouette and flat alike.
fn offsets(ratios: [f64; 4], px: u64) -> (Vec<ClassError>, Vec<ClassError>) {
    let base = [0.20, 0.22, 0.18, 0.21];
    let at = |k: usize, r: f64| {
        let mut e = cf([Some(base[k] * r), None, None, None, None, Some(base[k] * r)]);
        e.px[Class::Silhouette.index()] = px;
        e.px[Class::Flat.index()] = px;
        e
    };
    (
        (0..4).map(|k| at(k, ratios[k])).collect(),
        (0..4).map(|k| at(k, 1.0)).collect(),
    )
}

fn outcome(ratios: [f64; 4], px: u64) -> (Outcome, Outcome) {
    let (it, noaa) = offsets(ratios, px);
    let v = Verdict::judge_claims(
        SRAA.into(),
        vec![Class::Silhouette],
        Metric::Flip,
        &it,
        &noaa,
    );
    (v.judged[0].outcome, v.flat_judged.unwrap().outcome)
}

#[test]
fn a_verdict_needs_every_offset_to_agree() {
    use Outcome::*;
    // Wins at every offset: beats; flat holds (at most 1.02×) too.
    assert_eq!(outcome([0.9, 0.8, 0.95, 0.7], 100), (Beats, Holds));
    // One offset short of the factor, all four better: it leans better,
    // it is not a win, and not noise either (the offsets agree in
    // direction).
    assert_eq!(outcome([0.9, 0.8, 0.96, 0.7], 100), (LeansBetter, Holds));
    // Better at every offset, never by the margin: a consistent tie.
    assert_eq!(outcome([0.99, 0.97, 0.96, 0.98], 100), (TiesBetter, Holds));
    // Worse at every offset, by the margin at some: leans worse; flat,
    // past 1.02× at two offsets and worse at all four, leans worse too.
    assert_eq!(
        outcome([1.01, 1.06, 1.03, 1.1], 100),
        (LeansWorse, LeansWorse)
    );
    // Worse at every offset, never by the margin: a consistent tie; flat
    // holds (at most 1.02×) at every offset.
    assert_eq!(outcome([1.01, 1.02, 1.01, 1.02], 100), (TiesWorse, Holds));
    // Worse beyond 1/0.95 at every offset: a loss, on flat too.
    assert_eq!(outcome([1.3, 1.25, 1.4, 1.06], 100), (Loses, Loses));
    // Inside the band at every offset: a tie; flat straddles 1.02×.
    assert_eq!(outcome([1.0, 0.97, 1.03, 1.01], 100), (Ties, Noise));
    // Win at one offset, loss at another: noise.
    assert_eq!(outcome([0.9, 1.1, 1.0, 1.0], 100).0, Noise);
    // 63 pixels at some offset: no verdict, whatever the figures.
    assert_eq!(outcome([0.5, 0.5, 0.5, 0.5], 63), (FewPixels, FewPixels));
    assert_eq!(outcome([0.5, 0.5, 0.5, 0.5], MIN_VERDICT_PIXELS).0, Beats);
}

#[test]
fn verdict_lines_use_one_word_per_outcome() {
    let (mut it, noaa) = offsets([1.3, 1.25, 1.4, 1.3], 100);
    // Crease: noise; shadow: too few pixels.
    for (k, e) in it.iter_mut().enumerate() {
        e.mean[Class::Crease.index()] = Some([0.9, 1.1, 1.0, 1.0][k]);
        e.px[Class::Crease.index()] = 100;
        e.mean[Class::Shadow.index()] = Some(0.1);
        e.px[Class::Shadow.index()] = 8;
    }
    let mut noaa = noaa;
    for e in &mut noaa {
        e.mean[Class::Crease.index()] = Some(1.0);
        e.px[Class::Crease.index()] = 100;
        e.mean[Class::Shadow.index()] = Some(0.2);
        e.px[Class::Shadow.index()] = 8;
    }
    let claims = vec![
        Class::Silhouette,
        Class::Crease,
        Class::Shadow,
        Class::Texture,
    ];
    let v = Verdict::judge_claims(named("x"), claims, Metric::Flip, &it, &noaa);
    let line = v.line("cpu");
    assert!(
        line.contains("tie (within noise) on crease (1.0000 vs 1.0000, 0.90–1.10× over 4 offsets)"),
        "{line}"
    );
    // The mean ratio: (0.26 + 0.275 + 0.252 + 0.273) / 0.81 = 1.33.
    assert!(line.contains("loses by 1.3× on silhouette"), "{line}");
    assert!(
        line.contains("too few pixels for a verdict on shadow (8 px)"),
        "{line}"
    );
    assert!(line.contains("no pixels of texture"), "{line}");
    assert!(line.contains("flat: loses by 1.3×"), "{line}");
    assert!(!line.contains("does not beat"));
    assert_eq!(v.beats.len(), 0);
    assert_eq!(
        v.misses.len(),
        2,
        "noise and loss are misses; too few pixels is not"
    );
    assert!(!v.holds_on_flat());
    assert_eq!(loss_text(1.06), "1.06×");
    assert_eq!(loss_text(2.0), "2.0×");
}

#[test]
fn errors_over_offsets_average_and_keep_the_fewest_pixels() {
    let mut a = cf([Some(0.1), None, None, None, None, Some(0.02)]);
    let mut b = cf([Some(0.3), Some(0.5), None, None, None, Some(0.04)]);
    a.px[0] = 120;
    b.px[0] = 80;
    (a.near_edge, a.near_edge_px) = (Some(0.05), 30);
    (b.near_edge, b.near_edge_px) = (Some(0.07), 20);
    let m = ClassError::over_offsets(&[a, b]).unwrap();
    assert!((m.mean[0].unwrap() - 0.2).abs() < 1e-12);
    assert_eq!(m.px[0], 80);
    // A class at one offset only: its mean there, its fewest pixels 0.
    assert_eq!(m.mean[1], Some(0.5));
    assert_eq!(m.px[1], 0);
    assert!((m.near_edge.unwrap() - 0.06).abs() < 1e-12);
    assert_eq!(m.near_edge_px, 20);
    assert_eq!(
        ClassError::range(&[a, b], |e| e.mean[5]),
        Some((0.02, 0.04))
    );
    assert_eq!(ClassError::over_offsets(&[]), None);
}

#[test]
fn pixels_within_each_metrics_reach_of_a_class_are_near_edge_not_flat() {
    // 31×31 pixels, a one-sub-sample pole in the centre pixel only.
    let (pw, s, c) = (31usize, 4usize, 15usize);
    let mut f = uniform((pw * s) as u32, (pw * s) as u32);
    let w = pw * s;
    let mut depth = vec![2.0f32; w * w];
    for j in 0..s {
        depth[(c * s + j) * w + c * s + 1] = 1.0;
    }
    f.depth = Some(depth);
    let m = classify(&f, s as u32).unwrap();
    let at = |x: usize, y: usize| y * pw + x;
    assert!(m.mask(Class::Silhouette)[at(c, c)]);
    assert_eq!(m.count(Class::Silhouette), 1);
    // FLIP's filters reach 10 px, SSIM's window 5: Chebyshev squares,
    // corners included.
    assert_eq!(
        (
            near_edge_radius(Metric::Flip),
            near_edge_radius(Metric::Ssim)
        ),
        (10, 5)
    );
    for (metric, r) in [(Metric::Flip, 10usize), (Metric::Ssim, 5)] {
        let (near, flat) = (m.near(metric), m.flat(metric));
        for (x, y) in [(c - r, c), (c + r, c + r), (c - r, c - r), (c + 1, c)] {
            assert!(near[at(x, y)], "{metric:?}: ({x}, {y}) is within {r}");
            assert!(!flat[at(x, y)]);
        }
        for (x, y) in [(c - r - 1, c), (c + r + 1, c + r + 1), (c, c - r - 1)] {
            assert!(!near[at(x, y)], "{metric:?}: ({x}, {y}) is {} away", r + 1);
            assert!(flat[at(x, y)]);
        }
        assert!(!near[at(c, c)], "a classed pixel is not in the band");
        let side = 2 * r + 1;
        assert_eq!(near.iter().filter(|&&b| b).count(), side * side - 1);
        assert_eq!(flat.iter().filter(|&&b| b).count(), pw * pw - side * side);
        // The band's error is measured apart from flat's.
        let map: Vec<f32> = (0..pw * pw)
            .map(|p| if near[p] { 0.5 } else { 0.1 })
            .collect();
        let e = ClassError::measure(&map, &m, metric);
        assert_eq!(
            (e.near_edge, e.near_edge_px),
            (Some(0.5), (side * side - 1) as u64)
        );
        assert!((e.mean[Class::Flat.index()].unwrap() - 0.1).abs() < 1e-7);
        assert_eq!(e.px[Class::Flat.index()], (pw * pw - side * side) as u64);
    }
    assert_eq!(m.mask(Class::Flat), m.flat(Metric::Flip));
}

#[test]
fn small_figures_keep_three_significant_digits() {
    assert_eq!(figure(0.12345), "0.1235");
    assert_eq!(figure(0.0), "0.0000");
    assert_eq!(figure(2.5e-5), "2.50e-5");
    assert_eq!(figure(0.001), "0.0010");
}

#[test]
fn ssim_differences_under_the_floor_do_not_count() {
    let f = DSSIM_FLOOR;
    let noaa = cf([Some(0.02), Some(0.01), None, None, None, Some(0.001)]);
    // Silhouette: 0.95× and more than the floor lower, beats. Crease:
    // 0.94×, but lower by less than the floor, does not.
    let it = cf([
        Some(0.02 * 0.95 - f),
        Some(0.0094),
        None,
        None,
        None,
        Some(0.001 + f * 0.9),
    ]);
    let v = Verdict::judge_claims(SRAA.into(), SRAA.claims(), Metric::Ssim, &[it], &[noaa]);
    assert_eq!(
        v.beats.iter().map(|b| b.0).collect::<Vec<_>>(),
        vec![Class::Silhouette]
    );
    assert_eq!(
        v.misses.iter().map(|b| b.0).collect::<Vec<_>>(),
        vec![Class::Crease]
    );
    // Flat: twice NoAA's, but higher by less than the floor: holds.
    assert!(v.holds_on_flat());
    assert!(v
        .line("cpu")
        .starts_with("- **sraa** (cpu, SSIM): beats NoAA on silhouette"));
    let worse = cf([None, None, None, None, None, Some(0.001 + f * 1.1)]);
    assert!(
        !Verdict::judge_claims(SRAA.into(), vec![], Metric::Ssim, &[worse], &[noaa])
            .holds_on_flat()
    );
    // Under FLIP the same figures are judged by the factors alone.
    let v = Verdict::judge_claims(SRAA.into(), SRAA.claims(), Metric::Flip, &[it], &[noaa]);
    assert_eq!(v.beats.len(), 2);
    assert!(!v.holds_on_flat());
}

/// A 2×1-pixel sub-sample frame (8×4 sub-samples), every AOV uniform.
fn uniform(w: u32, h: u32) -> Frame {
    let mut f = Frame::new(w, h);
    let n = (w * h) as usize;
    f.depth = Some(vec![2.0; n]);
    f.normal = Some(vec![Vec3::Z; n]);
    f.albedo = Some(vec![Vec3::splat(0.5); n]);
    f.light_visibility = Some(vec![1; n]);
    f.mirror = Some(vec![0.0; n]);
    f
}

#[test]
fn uniform_aovs_are_flat_and_errors_are_values() {
    let f = uniform(8, 4);
    let m = classify(&f, 4).unwrap();
    assert_eq!((m.width, m.height), (2, 1));
    assert_eq!(m.mask(Class::Flat), &[true, true]);
    assert!(classify(&f, 3).is_err());
    assert!(classify(&f, 0).is_err());
    let mut g = f.clone();
    g.albedo = None;
    assert!(classify(&g, 4).is_err());
    let mut g = f.clone();
    g.depth = Some(vec![f32::NAN; 32]);
    g.normal = Some(vec![Vec3::NAN; 32]);
    // NaN depth reads as a miss everywhere: background, flat.
    assert_eq!(classify(&g, 4).unwrap().mask(Class::Flat), &[true, true]);
}

/// The acceptance frame: each class known by construction. Two rows of
/// 11 pixels at 4×4 sub-samples. Row 0, by pixel: wall; a box's
/// silhouette against the wall; the box's face; a crease of the box;
/// wall; a shadow edge; a texture step; a mirror; sky; the wall's edge
/// against the sky; a pole one sub-sample wide (missed by a centre
/// sample). Row 1: a floor seen at a grazing angle, whose depth grows by
/// 20 % to 33 % per sub-sample but is one plane.
#[test]
fn classes_of_a_frame_built_to_contain_each() {
    let (pw, ph, s) = (11usize, 2usize, 4usize);
    let (w, h) = (pw * s, ph * s);
    let mut f = uniform(w as u32, h as u32);
    let n = w * h;
    let mut depth = vec![10.0f32; n];
    let mut normal = vec![Vec3::Z; n];
    let mut albedo = vec![Vec3::splat(0.5); n];
    let mut vis = vec![1u32; n];
    let mut mirror = vec![0.0f32; n];
    for y in 0..s {
        for i in 0..s {
            let at = |px: usize| y * w + px * s + i;
            // 1: the box's left edge over the wall.
            if i >= 2 {
                depth[at(1)] = 5.0;
            }
            // 2: the box's front face.
            depth[at(2)] = 5.0;
            // 3: the box's corner: front face, then its side (continuous depth).
            depth[at(3)] = 5.0;
            if i >= 2 {
                normal[at(3)] = Vec3::X;
            }
            // 5: a shadow edge.
            if i >= 2 {
                vis[at(5)] = 0;
            }
            // 6: a texture step.
            albedo[at(6)] = Vec3::splat(if i >= 2 { 0.8 } else { 0.2 });
            // 7: a mirror.
            mirror[at(7)] = 0.9;
            // 8: sky.
            depth[at(8)] = f32::INFINITY;
            // 9: the wall's edge against the sky.
            if i >= 2 {
                depth[at(9)] = f32::INFINITY;
            }
            // 10: a pole one sub-sample wide.
            if i == 1 {
                depth[at(10)] = 3.0;
            }
        }
    }
    // Row 1: a grazing floor, inverse depth affine in the sub-sample row.
    for y in s..2 * s {
        for x in 0..w {
            depth[y * w + x] = 1.0 / (1.0 - 0.1 * y as f32);
            normal[y * w + x] = Vec3::Y;
        }
    }
    f.depth = Some(depth);
    f.normal = Some(normal);
    f.albedo = Some(albedo);
    f.light_visibility = Some(vis);
    f.mirror = Some(mirror);
    let m = classify(&f, s as u32).unwrap();
    // Near edge reads as flat here: this test is about the five classes
    // (every pixel of this small frame is within 2 of one).
    let of = |p: usize| -> Vec<Class> {
        let mut v: Vec<Class> = CLASSES.into_iter().filter(|c| m.mask(*c)[p]).collect();
        if m.near_edge[p] {
            v.push(Flat);
        }
        v
    };
    use Class::*;
    let expected = [
        vec![Flat],
        vec![Silhouette],
        vec![Flat],
        vec![Crease],
        vec![Flat],
        vec![Shadow],
        vec![Texture],
        vec![Reflection],
        vec![Flat],
        vec![Silhouette],
        vec![Silhouette],
    ];
    for (p, e) in expected.iter().enumerate() {
        assert_eq!(&of(p), e, "pixel {p} of row 0");
    }
    for p in pw..2 * pw {
        assert_eq!(of(p), vec![Flat], "pixel {} of the grazing floor", p - pw);
    }
    assert_eq!(m.count(Silhouette), 3);
    let near = m.near_edge.iter().filter(|&&b| b).count() as u64;
    assert_eq!(m.count(Flat) + near, 4 + pw as u64);
}
