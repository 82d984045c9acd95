//! The answer as the report writes it: the section of `report.md` and the
//! answer in `results.json`.

use std::fmt::Write as _;

use serde_json::{json, Value};

use super::excluded::{same_image_twins, Excluded, Why};
use super::front::Point;
use super::pick::{backends, Answer, Kind, Pick};
use super::{error_name, BUDGETS, RULE};
use crate::classes::Metric;
use crate::context::{cpu_model, ms, Context, SceneInfo};
use crate::key::RowKey;
use crate::{Mode, ResultRow};

fn budget_name(b: Option<f64>) -> String {
    match b {
        Some(x) => format!("≤ {x}× NoAA"),
        None => "any".into(),
    }
}

/// The sizes of `kind`'s scenes, `96x64 (errors at 96x64)`, distinct ones
/// joined.
fn sizes(scenes: &[SceneInfo], kind: Kind) -> Option<String> {
    let mut s: Vec<String> = Vec::new();
    for sc in scenes.iter().filter(|sc| Kind::of(sc) == kind) {
        let t = format!(
            "{}x{}{}",
            sc.timing_size.0,
            sc.timing_size.1,
            match sc.quality_size {
                Some(q) => format!(" (errors at {}x{})", q.0, q.1),
                None => String::new(),
            }
        );
        if !s.contains(&t) {
            s.push(t);
        }
    }
    (!s.is_empty()).then(|| s.join(", "))
}

/// The regime of the run in one sentence: backend, machine, threads,
/// sizes, shading cost.
pub fn regime(ctx: &Context) -> String {
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    let mut sz = Vec::new();
    for kind in Kind::ALL {
        if let Some(s) = sizes(&ctx.scenes, kind) {
            sz.push(format!("{} scenes timed at {s}", kind.name()));
        }
    }
    format!(
        "**Regime:** backend {} on {}, {threads} hardware threads; {}; shading with {} ambient-occlusion rays per shaded point on triangle scenes (none on SDF scenes); {} timed rounds{}.",
        ctx.backend_descriptions.join(", "),
        cpu_model(),
        sz.join("; "),
        ctx.ao,
        ctx.runs,
        if ctx.mode == Mode::TimingOnly {
            String::new()
        } else {
            let list: Vec<String> = ctx
                .offsets
                .iter()
                .map(|&(x, y)| format!("({x}, {y})"))
                .collect();
            format!(
                ", errors against {} at the quality size, as the mean over {} camera offset{} of {} px (each offset at that size against its own {} frame; the images show the first)",
                ctx.reference,
                ctx.offsets.len(),
                if ctx.offsets.len() == 1 { "" } else { "s" },
                list.join(", "),
                ctx.reference,
            )
        }
    )
}

/// A point of a front as the table shows it: its name (and the rows that
/// repeat its image), its time over NoAA's with the per-round range, its
/// median ms and its error; after a step that does not hold, why.
fn point(p: &Point, twins: &[RowKey]) -> String {
    let name = if twins.is_empty() {
        p.method.to_string()
    } else {
        let twins: Vec<String> = twins.iter().map(RowKey::to_string).collect();
        format!("{} (= {})", p.method, twins.join(", "))
    };
    let time = match (p.ratio, p.ratio_range) {
        (Some(t), Some((lo, hi))) if lo != hi => {
            format!("{t:.2}× ({lo:.2}–{hi:.2}), {} ms", ms(p.ms))
        }
        (Some(t), _) => format!("{t:.2}×, {} ms", ms(p.ms)),
        (None, _) => format!("{} ms", ms(p.ms)),
    };
    let mark = match p.step.and_then(|s| s.noise()) {
        Some(why) => format!(" ({why})"),
        None => String::new(),
    };
    format!("{name} {time} · {:.4}{mark}", p.error)
}

/// A pick as its cell shows it: the method, its mean error ratio, on how
/// many scenes it is on the front, the runner-up with the margin, and a
/// mark when the decision is within noise.
fn pick_cell(p: Option<&Pick>) -> String {
    let Some(p) = p else {
        return "–".into();
    };
    let mut cell = format!(
        "{} ({:.2}, {}/{})",
        p.method,
        p.mean_error_ratio,
        p.on_front,
        p.scenes.len()
    );
    if let (Some((next, e)), Some(m)) = (&p.runner_up, p.margin()) {
        let _ = write!(cell, "; next {next} ({e:.2}, {:+.1} %)", 100.0 * m);
    }
    if !p.noise.is_empty() {
        cell.push_str("; **within noise**");
    }
    cell
}

/// The section of `report.md`: the regime, the picks per kind and budget
/// under both metrics and where they disagree, the fronts per scene, and
/// what was left out.
pub fn section(a: &Answer, rows: &[ResultRow], ctx: &Context) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "## The answer: what to use at each cost\n");
    let _ = writeln!(md, "{}\n", regime(ctx));
    if a.fronts.is_empty() {
        let _ = writeln!(
            md,
            "No errors were measured, so there is no front and no pick.\n"
        );
        return md;
    }
    picks_table(&mut md, a, rows);
    fronts_table(&mut md, a, rows);
    noise_notes(&mut md, a);
    left_out_notes(&mut md, a);
    md
}

/// The picks table: a row per kind, backend and budget, both metrics'
/// picks and whether they agree.
fn picks_table(md: &mut String, a: &Answer, rows: &[ResultRow]) {
    if !a.picks.is_empty() {
        let _ = writeln!(
            md,
            "Which method to use per kind of scene and budget of time over NoAA's, under each metric (FLIP, and 1 − SSIM so that lower is better under both): {RULE}. In brackets: that mean error ratio, and on how many of the scenes the method is on the front below; then the runner-up by the same rule, its mean error ratio and how much more that is. A pick is **within noise** when the runner-up has the lower error ratio at some camera offset, when the pick's own time goes over the budget in a round, or when a method with less error is out of the budget by its median but within it in a round; the notes under the fronts say which.\n"
        );
        let _ = writeln!(
            md,
            "| scenes | backend | budget | use (FLIP) | use (SSIM) | the metrics |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|---|");
        for kind in Kind::ALL {
            for b in backends(&rows.iter().collect::<Vec<_>>()) {
                for budget in BUDGETS {
                    let fl = a.pick(kind, &b, Metric::Flip, budget);
                    let ss = a.pick(kind, &b, Metric::Ssim, budget);
                    if fl.is_none() && ss.is_none() {
                        continue;
                    }
                    let n = fl.or(ss).map_or(0, |p| p.scenes.len());
                    let agree = match (fl, ss) {
                        (Some(x), Some(y)) if x.method == y.method => "agree".to_string(),
                        (Some(x), Some(y)) => {
                            format!("**disagree**: {} or {}", x.method, y.method)
                        }
                        _ => "–".into(),
                    };
                    let _ = writeln!(
                        md,
                        "| {} ({n}) | {b} | {} | {} | {} | {agree} |",
                        kind.name(),
                        budget_name(budget),
                        pick_cell(fl),
                        pick_cell(ss),
                    );
                }
            }
        }
        let _ = writeln!(md);
    }
}

/// The fronts table: per scene and backend, both metrics' fronts in time
/// order, each point with the rows that repeat its image.
fn fronts_table(md: &mut String, a: &Answer, rows: &[ResultRow]) {
    let twins_of = |scene: &str, backend: &str, method: &RowKey| -> Vec<RowKey> {
        rows.iter()
            .find(|r| r.scene == scene && r.backend == backend && r.method == *method)
            .map(|r| same_image_twins(&a.excluded, r))
            .unwrap_or_default()
    };
    let _ = writeln!(
        md,
        "Pareto fronts per scene: methods in order of time over NoAA's (the median of the per-round ratios, as the budgets; in brackets the range over the rounds, then the median ms at the timing size) with their error (the mean over the camera offsets); a method is on the front when every faster method has a higher error. A step to a method holds when its error is lower than the faster method's at every camera offset and its time higher in every round; otherwise the front says it is within noise.\n"
    );
    let _ = writeln!(
        md,
        "| scene | backend | FLIP front (× NoAA · FLIP) | SSIM front (× NoAA · 1 − SSIM) |"
    );
    let _ = writeln!(md, "|---|---|---|---|");
    let mut keys: Vec<(&str, &str)> = Vec::new();
    for f in &a.fronts {
        if !keys.contains(&(f.scene.as_str(), f.backend.as_str())) {
            keys.push((f.scene.as_str(), f.backend.as_str()));
        }
    }
    for (scene, b) in keys {
        let show = |metric: Metric| match a.front(scene, b, metric) {
            Some(f) => f
                .points
                .iter()
                .map(|p| point(p, &twins_of(scene, b, &p.method)))
                .collect::<Vec<_>>()
                .join(" → "),
            None => "–".into(),
        };
        let _ = writeln!(
            md,
            "| {scene} | {b} | {} | {} |",
            show(Metric::Flip),
            show(Metric::Ssim)
        );
    }
    let _ = writeln!(md);
}

/// Why each pick within noise is, one line each.
fn noise_notes(md: &mut String, a: &Answer) {
    let noisy: Vec<String> = a
        .picks
        .iter()
        .filter(|p| !p.noise.is_empty())
        .map(|p| {
            format!(
                "{} scenes, {}, {}, {} ({}): {}",
                p.kind.name(),
                p.backend,
                budget_name(p.budget),
                error_name(p.metric),
                p.method,
                p.noise.join("; ")
            )
        })
        .collect();
    if !noisy.is_empty() {
        let _ = writeln!(md, "Within noise:\n");
        for n in noisy {
            let _ = writeln!(md, "- {n}.");
        }
        let _ = writeln!(md);
    }
}

/// The rows left out of the fronts, and the methods no candidate for a
/// kind, with the reasons.
fn left_out_notes(md: &mut String, a: &Answer) {
    let mut notes: Vec<String> = Vec::new();
    // One line per method, backend and reason, naming the scenes.
    let mut groups: Vec<(&Excluded, Vec<&str>)> = Vec::new();
    for e in &a.excluded {
        match groups.iter_mut().find(|(g, _)| {
            g.method == e.method && g.backend == e.backend && g.reason() == e.reason()
        }) {
            Some((_, s)) => s.push(&e.scene),
            None => groups.push((e, vec![&e.scene])),
        }
    }
    for (e, scenes) in groups {
        let label = match &e.why {
            Why::SameImage { as_method } => {
                format!("{} (same image as {as_method})", e.method)
            }
            Why::OtherDevice { .. } => format!("{} †", e.method),
        };
        notes.push(format!(
            "{label} on {} ({}): {}",
            e.backend,
            scenes.join(", "),
            e.reason()
        ));
    }
    if !notes.is_empty() {
        let _ = writeln!(md, "Left out of the fronts: {}.\n", notes.join("; "));
    }
    let partial: Vec<String> = a
        .partial
        .iter()
        .map(|p| {
            format!(
                "{} on {} scenes ({}; not on {})",
                p.method,
                p.kind.name(),
                p.backend,
                p.missing.join(", ")
            )
        })
        .collect();
    if !partial.is_empty() {
        let _ = writeln!(
            md,
            "No candidate for a kind because it did not run (or was timed on another device) on every scene of it: {}.\n",
            partial.join("; ")
        );
    }
}

/// The answer in `results.json`: the budgets, the rule, the fronts, the
/// picks and what was left out.
pub fn json(a: &Answer) -> Value {
    let metric = |m: Metric| match m {
        Metric::Flip => "flip",
        Metric::Ssim => "ssim",
    };
    json!({
        "error": {"flip": "mean FLIP", "ssim": "1 - mean SSIM"},
        "budgets": BUDGETS,
        "rule": RULE,
        "fronts": a.fronts.iter().map(|f| json!({
            "scene": f.scene,
            "backend": f.backend,
            "metric": metric(f.metric),
            "points": f.points.iter().map(|p| json!({
                "method": p.method, "ms_median": p.ms, "ratio_to_noaa": p.ratio,
                "ratio_min": p.ratio_range.map(|r| r.0), "ratio_max": p.ratio_range.map(|r| r.1),
                "error": p.error,
                "step": p.step.map(|s| json!({
                    "error_at_every_offset": s.error_at_every_offset,
                    "time_in_every_round": s.time_in_every_round,
                    "holds": s.holds(),
                })),
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "picks": a.picks.iter().map(|p| json!({
            "kind": match p.kind { Kind::Triangles => "triangles", Kind::Sdf => "sdf" },
            "backend": p.backend,
            "metric": metric(p.metric),
            "budget": p.budget,
            "scenes": p.scenes,
            "method": p.method,
            "mean_error_ratio": p.mean_error_ratio,
            "worst_time_ratio": if p.worst_time_ratio.is_finite() { json!(p.worst_time_ratio) } else { Value::Null },
            "on_front": p.on_front,
            "runner_up": p.runner_up.as_ref().map(|(m, e)| json!({"method": m, "mean_error_ratio": e})),
            "margin": p.margin(),
            "within_noise": p.noise,
        })).collect::<Vec<_>>(),
        "excluded": a.excluded.iter().map(|e| json!({
            "scene": e.scene,
            "backend": e.backend,
            "method": e.method,
            "same_image_as": match &e.why { Why::SameImage { as_method } => json!(as_method), _ => Value::Null },
            "other_device": matches!(e.why, Why::OtherDevice { .. }),
            "reason": e.reason(),
        })).collect::<Vec<_>>(),
        "partial": a.partial.iter().map(|p| json!({
            "kind": match p.kind { Kind::Triangles => "triangles", Kind::Sdf => "sdf" },
            "backend": p.backend, "method": p.method, "missing": p.missing,
        })).collect::<Vec<_>>(),
    })
}
