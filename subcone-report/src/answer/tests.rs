use subcone_scene::TimingSource;

use super::*;
use crate::classes::Metric;
use crate::context::{Context, SceneInfo};
use crate::timing::Timings;
use crate::{Mode, ResultRow};

/// The name of the method `a` picks on the cpu backend.
fn picked(a: &Answer, kind: Kind, metric: Metric, budget: Option<f64>) -> String {
    a.pick(kind, "cpu", metric, budget)
        .unwrap()
        .method
        .to_string()
}

/// What `a` picks on the cpu backend under FLIP: `method`, with its mean
/// error ratio over NoAA's and on how many scenes it is on the front.
fn assert_pick(
    a: &Answer,
    kind: Kind,
    budget: Option<f64>,
    method: &str,
    mean_error_ratio: f64,
    on_front: usize,
) {
    let p = a.pick(kind, "cpu", Metric::Flip, budget).unwrap();
    assert_eq!(p.method.to_string(), method);
    assert!(
        (p.mean_error_ratio - mean_error_ratio).abs() < 1e-12,
        "{method}: mean error ratio {}",
        p.mean_error_ratio
    );
    assert_eq!(p.on_front, on_front, "{method}");
}

const WHY: &str = "software adapter";

#[test]
fn pareto_front_keeps_only_improvements() {
    let key = |p: &(f64, f64)| *p;
    let f = pareto_by(
        vec![(10.0, 0.2), (1.0, 0.5), (5.0, 0.6), (20.0, 0.1), (2.0, 0.3)],
        key,
    );
    assert_eq!(f, vec![(1.0, 0.5), (2.0, 0.3), (10.0, 0.2), (20.0, 0.1)]);
    assert!(pareto_by(vec![(f64::NAN, 0.1)], key).is_empty());
}

fn row(scene: &str, method: &str, ms: f64, flip: f64, ssim: f64) -> ResultRow {
    let mut r = ResultRow::timed(
        scene,
        crate::key::named(method),
        "cpu",
        (4, 4),
        3,
        &Timings::default(),
    );
    r.ms_median = ms;
    // Rounds within 10 % of the median, as on a quiet machine.
    (r.ms_min, r.ms_max) = (ms * 0.9, ms * 1.1);
    r.timed_by = vec![TimingSource::Cpu];
    r.flip_mean = Some(flip);
    r.ssim_mean = Some(ssim);
    r
}

/// `row` with its time over NoAA's, NoAA taking 1 ms.
fn timed(scene: &str, method: &str, ratio: f64, flip: f64, ssim: f64) -> ResultRow {
    let mut r = row(scene, method, ratio, flip, ssim);
    r.ratio_to_noaa = Some(ratio);
    r
}

fn scene(name: &str, sdf: bool) -> SceneInfo {
    SceneInfo {
        name: crate::key::SceneId::new(name),
        arg: name.into(),
        sdf,
        timing_size: (4, 4),
        quality_size: Some((4, 4)),
    }
}

fn methods(f: Option<&Front>) -> Vec<String> {
    f.map(|f| f.points.iter().map(|p| p.method.to_string()).collect())
        .unwrap_or_default()
}

/// One triangle scene: noaa, fxaa (cheap, a little better), ssaa4,
/// sraa (dearer than ssaa4 and worse), ssaa16.
fn triangle_rows() -> Vec<ResultRow> {
    vec![
        timed("t", "noaa", 1.0, 0.10, 0.90),
        timed("t", "fxaa", 1.2, 0.09, 0.95),
        timed("t", "ssaa4", 3.0, 0.05, 0.96),
        timed("t", "sraa", 5.0, 0.06, 0.97),
        timed("t", "ssaa16", 12.0, 0.03, 0.99),
    ]
}

#[test]
fn a_row_slower_changes_the_front_and_the_pick() {
    let scenes = [scene("t", false)];
    let mut rows = triangle_rows();
    let a = Answer::of(&rows, &scenes);
    assert_eq!(
        methods(a.front("t", "cpu", Metric::Flip)),
        ["noaa", "fxaa", "ssaa4", "ssaa16"]
    );
    assert_pick(&a, Kind::Triangles, Some(4.0), "ssaa4", 0.5, 1);
    assert_eq!(picked(&a, Kind::Triangles, Metric::Flip, Some(1.5)), "fxaa");
    assert_eq!(picked(&a, Kind::Triangles, Metric::Flip, None), "ssaa16");

    // ssaa4 now takes 6× NoAA: sraa (5×, worse than ssaa4) joins the
    // front, and nothing but fxaa is left within 4×.
    let s4 = rows
        .iter_mut()
        .find(|r| r.method.to_string() == "ssaa4")
        .unwrap();
    s4.ms_median = 6.0;
    s4.ratio_to_noaa = Some(6.0);
    let b = Answer::of(&rows, &scenes);
    assert_eq!(
        methods(b.front("t", "cpu", Metric::Flip)),
        ["noaa", "fxaa", "sraa", "ssaa4", "ssaa16"]
    );
    assert_eq!(picked(&b, Kind::Triangles, Metric::Flip, Some(4.0)), "fxaa");
    let md = section(&b, &rows, &context(&scenes));
    assert!(
        md.contains("noaa 1.00×, 1.00 ms · 0.1000 → fxaa 1.20×, 1.20 ms · 0.0900 → sraa 5.00×, 5.00 ms · 0.0600"),
        "{md}"
    );
}

fn context(scenes: &[SceneInfo]) -> Context {
    Context {
        mode: Mode::Quick,
        backends: vec!["cpu".into()],
        backend_descriptions: vec!["cpu (test)".into()],
        runs: 3,
        reference: "ssaa64".into(),
        offsets: crate::offsets::ERROR_OFFSETS.to_vec(),
        scenes: scenes
            .iter()
            .map(|s| SceneInfo {
                name: s.name.clone(),
                arg: s.arg.clone(),
                ..*s
            })
            .collect(),
        ao: 0,
        other_cpu: Default::default(),
    }
}

#[test]
fn the_metrics_can_disagree_and_the_section_says_so() {
    let scenes = [scene("t", false)];
    // Under SSIM fxaa is better than ssaa4 within 4×, under FLIP worse.
    let mut rows = triangle_rows();
    rows[1].ssim_mean = Some(0.98);
    let a = Answer::of(&rows, &scenes);
    assert_eq!(picked(&a, Kind::Triangles, Metric::Ssim, Some(4.0)), "fxaa");
    assert_eq!(
        picked(&a, Kind::Triangles, Metric::Flip, Some(4.0)),
        "ssaa4"
    );
    let md = section(&a, &rows, &context(&scenes));
    let line = md
        .lines()
        .find(|l| l.starts_with("| triangle (1) | cpu | ≤ 4× NoAA |"))
        .unwrap_or_else(|| panic!("{md}"));
    assert!(line.ends_with("| **disagree**: ssaa4 or fxaa |"), "{line}");
    assert!(md
        .lines()
        .any(|l| l.starts_with("| triangle (1) | cpu | any |") && l.ends_with("| agree |")));
}

#[test]
fn a_repeated_image_is_named_and_plotted_once() {
    let mut rows = vec![
        timed("s", "noaa", 1.0, 0.10, 0.90),
        timed("s", "ctss", 1.2, 0.08, 0.92),
        timed("s", "ctss-delayed", 1.4, 0.08, 0.92),
    ];
    rows[1].image_digest = Some(7);
    rows[2].image_digest = Some(7);
    rows[0].image_digest = Some(8);
    let all: Vec<&ResultRow> = rows.iter().collect();
    let ex = exclusions(&all);
    assert_eq!(ex.len(), 1);
    assert_eq!(ex[0].method.to_string(), "ctss-delayed");
    assert_eq!(ex[0].mark(), "(same image as ctss)");
    assert_eq!(
        same_image_twins(&ex, &rows[1]),
        [crate::key::named("ctss-delayed")]
    );
    assert_eq!(
        methods(Some(&Front {
            scene: "s".into(),
            backend: "cpu".into(),
            metric: Metric::Flip,
            points: front(&all, &ex, Metric::Flip)
        })),
        ["noaa", "ctss"]
    );
    // Were the delayed one faster within the rounds' noise, the name
    // would not change with the clock: ctss, first in table order,
    // stands for the image.
    rows[2].ms_median = 1.1;
    let all: Vec<&ResultRow> = rows.iter().collect();
    let ex = exclusions(&all);
    assert_eq!(ex.len(), 1);
    assert_eq!(ex[0].method.to_string(), "ctss-delayed");
    let a = Answer::of(&rows, &[scene("s", true)]);
    let md = section(&a, &rows, &context(&[scene("s", true)]));
    assert!(md.contains("ctss (= ctss-delayed) 1.20×, 1.20 ms"), "{md}");
    assert!(
        md.contains(
            "ctss-delayed (same image as ctss) on cpu (s): its image is byte-identical to ctss's"
        ),
        "{md}"
    );
}

#[test]
fn a_repeated_image_faster_in_every_round_stands_for_it_and_stays_a_candidate() {
    // A hybrid gives its traced twin's image sooner in every round: the
    // front shows the hybrid's time, and the picks may take either.
    let mut rows = vec![
        timed("s", "noaa", 1.0, 0.10, 0.90),
        timed("s", "ssaa4", 3.0, 0.05, 0.95),
        timed("s", "ssaa4-hybrid", 2.0, 0.05, 0.95),
    ];
    rows[0].image_digest = Some(8);
    rows[1].image_digest = Some(7);
    rows[2].image_digest = Some(7);
    let a = Answer::of(&rows, &[scene("s", false)]);
    assert_eq!(a.excluded.len(), 1);
    assert_eq!(a.excluded[0].mark(), "(same image as ssaa4-hybrid)");
    assert_eq!(
        methods(a.front("s", "cpu", Metric::Flip)),
        ["noaa", "ssaa4-hybrid"]
    );
    // Same error, lower worst time: the hybrid is the pick; and the
    // traced twin, no longer left out of the picks, is no partial.
    assert_eq!(
        picked(&a, Kind::Triangles, Metric::Flip, Some(4.0)),
        "ssaa4-hybrid"
    );
    assert!(a.partial.is_empty(), "{:?}", a.partial);
    let p = a.pick(Kind::Triangles, "cpu", Metric::Flip, None).unwrap();
    assert_eq!(p.on_front, 1);
    // Within a budget only the traced twin meets, the traced twin is
    // picked, and counted on the front through the hybrid that stands
    // for its image.
    rows[2].ratio_to_noaa = Some(5.0);
    let a = Answer::of(&rows, &[scene("s", false)]);
    let p = a
        .pick(Kind::Triangles, "cpu", Metric::Flip, Some(4.0))
        .unwrap();
    assert_eq!((p.method.to_string(), p.on_front), ("ssaa4".into(), 1));
}

#[test]
fn a_row_timed_on_another_device_is_left_out_with_its_reason() {
    let mut rows = triangle_rows();
    let mut smaa = timed("t", "smaa", 1.1, 0.01, 0.999);
    smaa.timed_by = vec![TimingSource::Cpu, TimingSource::GpuWallClock { why: WHY }];
    rows.push(smaa);
    let a = Answer::of(&rows, &[scene("t", false)]);
    assert!(!methods(a.front("t", "cpu", Metric::Flip)).contains(&"smaa".to_string()));
    assert_eq!(picked(&a, Kind::Triangles, Metric::Flip, Some(1.5)), "fxaa");
    assert_eq!(a.excluded.len(), 1);
    assert_eq!(a.excluded[0].mark(), "†");
    let reason = a.excluded[0].reason();
    assert!(
        reason.contains(WHY) && reason.contains("CPU wall clock"),
        "{reason}"
    );
    // Without NoAA there is no axis to be off.
    rows.retain(|r| r.method.to_string() != "noaa");
    let all: Vec<&ResultRow> = rows.iter().collect();
    assert!(exclusions(&all).is_empty());
}

#[test]
fn picks_are_per_kind_and_need_every_scene_of_it() {
    let scenes = [scene("t", false), scene("u", false), scene("d", true)];
    let mut rows = triangle_rows();
    rows.extend([
        timed("u", "noaa", 1.0, 0.20, 0.90),
        timed("u", "ssaa4", 3.0, 0.12, 0.95),
        // fxaa did not run on u: no candidate for triangle scenes.
        timed("d", "noaa", 1.0, 0.10, 0.90),
        timed("d", "ctss", 1.2, 0.07, 0.93),
        timed("d", "ssaa4", 3.5, 0.05, 0.96),
    ]);
    let a = Answer::of(&rows, &scenes);
    let t = a
        .pick(Kind::Triangles, "cpu", Metric::Flip, Some(1.5))
        .unwrap();
    assert_eq!((t.method.to_string().as_str(), t.scenes.len()), ("noaa", 2));
    // (0.05/0.10 + 0.12/0.20) / 2
    assert_pick(&a, Kind::Triangles, Some(4.0), "ssaa4", 0.55, 2);
    assert_eq!(picked(&a, Kind::Sdf, Metric::Flip, Some(1.5)), "ctss");
    assert_eq!(picked(&a, Kind::Sdf, Metric::Flip, Some(4.0)), "ssaa4");
    let missing: Vec<(String, &[String])> = a
        .partial
        .iter()
        .filter(|p| p.kind == Kind::Triangles)
        .map(|p| (p.method.to_string(), p.missing.as_slice()))
        .collect();
    assert!(
        missing
            .iter()
            .any(|(m, s)| *m == "fxaa" && *s == ["u".to_string()]),
        "{missing:?}"
    );
}

#[test]
fn no_errors_no_front() {
    let mut rows = triangle_rows();
    for r in &mut rows {
        (r.flip_mean, r.ssim_mean) = (None, None);
    }
    let a = Answer::of(&rows, &[scene("t", false)]);
    assert!(a.fronts.is_empty() && a.picks.is_empty());
    assert!(section(&a, &rows, &context(&[scene("t", false)])).contains("no front"));
}

/// `r` with its error under both metrics at four camera offsets (FLIP
/// `flip[k]`, SSIM 1 − `flip[k]`), its means set from them.
fn at_offsets(mut r: ResultRow, flip: [f64; 4]) -> ResultRow {
    r.errors_at = flip
        .iter()
        .map(|&f| crate::row::OffsetError {
            offset: (0.0, 0.0),
            flip: f,
            ssim: 1.0 - f,
            classes: Default::default(),
            classes_ssim: Default::default(),
        })
        .collect();
    r.settle_offsets();
    r
}

#[test]
fn a_front_step_holds_only_at_every_offset_and_in_every_round() {
    let scenes = [scene("t", false)];
    let mut rows = vec![
        at_offsets(timed("t", "noaa", 1.0, 0.1, 0.9), [0.10; 4]),
        // Lower error at every offset than noaa: holds.
        at_offsets(timed("t", "ssaa4", 3.0, 0.0, 0.0), [0.05, 0.06, 0.05, 0.06]),
        // Lower by the mean, higher at offset 1: within noise.
        at_offsets(timed("t", "sraa", 4.0, 0.0, 0.0), [0.03, 0.07, 0.03, 0.04]),
    ];
    for (r, rounds) in rows
        .iter_mut()
        .zip([[1.0, 1.0, 1.0], [3.0, 3.1, 2.9], [4.0, 4.2, 3.8]])
    {
        r.round_ms = rounds.to_vec();
    }
    let a = Answer::of(&rows, &scenes);
    let f = a.front("t", "cpu", Metric::Flip).unwrap();
    assert_eq!(methods(Some(f)), ["noaa", "ssaa4", "sraa"]);
    assert_eq!(f.points[0].step, None);
    assert!(f.points[1].step.unwrap().holds());
    let s = f.points[2].step.unwrap();
    assert!(!s.error_at_every_offset && s.time_in_every_round);
    let md = section(&a, &rows, &context(&scenes));
    assert!(
        md.contains("sraa 4.00×, 4.00 ms · 0.0425 (within noise: the error order changes with the camera offset)"),
        "{md}"
    );
    // sraa faster than ssaa4 in one round: the time order is noise too.
    rows[2].round_ms = vec![4.0, 3.0, 3.8];
    let a = Answer::of(&rows, &scenes);
    let s = a.front("t", "cpu", Metric::Flip).unwrap().points[2]
        .step
        .unwrap();
    assert!(!s.time_in_every_round);
    assert!(!s.holds());
}

#[test]
fn a_pick_names_its_runner_up_and_says_when_it_is_within_noise() {
    let scenes = [scene("t", false)];
    let mut rows = vec![
        at_offsets(timed("t", "noaa", 1.0, 0.0, 0.0), [0.10; 4]),
        at_offsets(timed("t", "fxaa", 1.2, 0.0, 0.0), [0.09; 4]),
        at_offsets(timed("t", "ssaa4", 3.0, 0.0, 0.0), [0.05, 0.05, 0.05, 0.05]),
        // Less error than ssaa4 on the mean, more at offset 2.
        at_offsets(timed("t", "sraa", 3.5, 0.0, 0.0), [0.03, 0.04, 0.06, 0.04]),
        at_offsets(timed("t", "ssaa16", 12.0, 0.0, 0.0), [0.02; 4]),
    ];
    let a = Answer::of(&rows, &scenes);
    let p = a
        .pick(Kind::Triangles, "cpu", Metric::Flip, Some(4.0))
        .unwrap();
    assert_eq!(p.method.to_string(), "sraa");
    let (next, e) = p.runner_up.clone().unwrap();
    assert_eq!(next.to_string(), "ssaa4");
    assert!((e - 0.5).abs() < 1e-12);
    assert!((p.margin().unwrap() - (0.5 / 0.425 - 1.0)).abs() < 1e-12);
    assert_eq!(
        p.noise,
        ["ssaa4 has the lower mean error ratio at camera offset 2 of 4"]
    );
    // Without the flip, the pick holds.
    rows[3] = at_offsets(timed("t", "sraa", 3.5, 0.0, 0.0), [0.03, 0.04, 0.045, 0.04]);
    let a = Answer::of(&rows, &scenes);
    let p = a
        .pick(Kind::Triangles, "cpu", Metric::Flip, Some(4.0))
        .unwrap();
    assert!(p.noise.is_empty(), "{:?}", p.noise);
    // ssaa16 out of the 4× budget by its median (4.01×) but within it in a
    // round: the 4.01× call is marked.
    rows[4].ratio_to_noaa = Some(4.01);
    (rows[4].ratio_min, rows[4].ratio_max) = (Some(3.72), Some(4.43));
    let a = Answer::of(&rows, &scenes);
    let p = a
        .pick(Kind::Triangles, "cpu", Metric::Flip, Some(4.0))
        .unwrap();
    assert_eq!(p.method.to_string(), "sraa");
    assert_eq!(p.noise.len(), 1, "{:?}", p.noise);
    assert!(
        p.noise[0].starts_with("ssaa16 (mean error ratio 0.20) is out of the 4× budget by its median, 4.01× on t (rounds 3.72–4.43×)"),
        "{}",
        p.noise[0]
    );
    // The pick's own rounds over the budget.
    (rows[3].ratio_min, rows[3].ratio_max) = (Some(3.2), Some(4.2));
    let a = Answer::of(&rows, &scenes);
    let p = a
        .pick(Kind::Triangles, "cpu", Metric::Flip, Some(4.0))
        .unwrap();
    assert!(
        p.noise
            .iter()
            .any(|n| n.contains("reaches 4.20× in a round")),
        "{:?}",
        p.noise
    );
    let md = section(&a, &rows, &context(&scenes));
    assert!(
        md.contains("sraa (0.39, 1/1); next ssaa4 (0.50, +29.0 %); **within noise**"),
        "{md}"
    );
    assert!(
        md.contains("Within noise:\n\n- triangle scenes, cpu, ≤ 4× NoAA, FLIP (sraa): "),
        "{md}"
    );
    let j = json(&a);
    let picks = j["picks"].as_array().unwrap();
    assert!(picks.iter().any(|p| p["runner_up"]["method"] == "ssaa4"
        && p["within_noise"].as_array().is_some_and(|w| !w.is_empty())));
}

#[test]
fn a_picks_runner_up_is_not_its_own_image_again() {
    let scenes = [scene("t", false)];
    let mut rows = vec![
        timed("t", "noaa", 1.0, 0.10, 0.90),
        timed("t", "ssaa4", 3.0, 0.05, 0.95),
        timed("t", "ssaa4-hybrid", 2.0, 0.05, 0.95),
        timed("t", "ssaa16", 12.0, 0.03, 0.99),
    ];
    for (r, d) in rows.iter_mut().zip([1, 2, 2, 3]) {
        r.image_digest = Some(d);
    }
    let a = Answer::of(&rows, &scenes);
    let p = a
        .pick(Kind::Triangles, "cpu", Metric::Flip, Some(4.0))
        .unwrap();
    assert_eq!(p.method.to_string(), "ssaa4-hybrid");
    // ssaa4 is the same image: the runner-up is the next other image.
    assert_eq!(p.runner_up.as_ref().unwrap().0.to_string(), "noaa");
}
