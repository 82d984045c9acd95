//! The report's files: `results.csv`, `results.json`, `report.md`, and PNG
//! images.
//!
//! Columns are stable: [`BASE_COLUMNS`] always, in that order, then one
//! `ms_<pass>` column per pass seen in the run, sorted by name, empty where a
//! method has no such pass. Missing values are empty in CSV and `null` in
//! JSON; an infinite PSNR (identical images) is `inf` in CSV and `null` in
//! JSON.
//!
//! Errors are means over the camera offsets they were measured at
//! ([`offsets`](crate::offsets), `offsets` of them): `flip_min`/`flip_max`,
//! `ssim_min`/`ssim_max` and the `_min`/`_max` of each class column are the
//! smallest and largest value over the offsets (empty with one offset);
//! `px_<class>` is the class's smallest pixel count over the offsets. The
//! near-edge band (`flip_near_edge`, `px_near_edge`, `dssim_near_edge`) is
//! measured like a class but not judged. `raster_samples_per_pixel` counts
//! the primary samples a `-hybrid` method's rasteriser resolved (0 for a
//! traced method); its rasteriser's time is the `ms_raster` pass column.
//!
//! Time ratios to NoAA are medians of per-round ratios (the methods of a
//! scene and backend are timed in interleaved rounds, see [`timing`]);
//! `ratio_min` and `ratio_max` are the smallest and largest per-round
//! ratio, empty for rows not timed in NoAA's rounds.

use std::fmt::Write as _;

use anyhow::Result;
use serde_json::{json, Map, Value};

use crate::classes::{self, Class, Metric, Verdict, CLASSES};
use crate::context::{cpu_model, ms, Context, SceneInfo};
use crate::key::RowKey;
use crate::named::{CTSS, CTSS_R, NOAA, SRAA, SRAA_RT, SSAA16, SSAA4, SSAA4_CTSS};
use crate::reference::code_version;
use crate::{crops, file_safe, kernel_timing, timing, Mode, ReportSummary, ResultRow};
use subcone_scene::Method;

/// The columns every results file has, in order.
pub const BASE_COLUMNS: [&str; 79] = [
    "scene",
    "method",
    "backend",
    "width",
    "height",
    "runs",
    "ms_median",
    "ms_min",
    "ms_max",
    "ratio_to_noaa",
    "ratio_min",
    "ratio_max",
    "flip_mean",
    "psnr_db",
    "edge_flip_mean",
    "ssim_mean",
    "samples_per_pixel",
    "rays_per_pixel",
    "buffer_mib",
    "quality_width",
    "quality_height",
    "reference",
    "flip_silhouette",
    "flip_crease",
    "flip_shadow",
    "flip_texture",
    "flip_reflection",
    "flip_flat",
    "px_silhouette",
    "px_crease",
    "px_shadow",
    "px_texture",
    "px_reflection",
    "px_flat",
    "dssim_silhouette",
    "dssim_crease",
    "dssim_shadow",
    "dssim_texture",
    "dssim_reflection",
    "dssim_flat",
    "post_process",
    "timed_by",
    "offsets",
    "flip_min",
    "flip_max",
    "ssim_min",
    "ssim_max",
    "flip_near_edge",
    "px_near_edge",
    "dssim_near_edge",
    "flip_silhouette_min",
    "flip_silhouette_max",
    "flip_crease_min",
    "flip_crease_max",
    "flip_shadow_min",
    "flip_shadow_max",
    "flip_texture_min",
    "flip_texture_max",
    "flip_reflection_min",
    "flip_reflection_max",
    "flip_flat_min",
    "flip_flat_max",
    "flip_near_edge_min",
    "flip_near_edge_max",
    "dssim_silhouette_min",
    "dssim_silhouette_max",
    "dssim_crease_min",
    "dssim_crease_max",
    "dssim_shadow_min",
    "dssim_shadow_max",
    "dssim_texture_min",
    "dssim_texture_max",
    "dssim_reflection_min",
    "dssim_reflection_max",
    "dssim_flat_min",
    "dssim_flat_max",
    "dssim_near_edge_min",
    "dssim_near_edge_max",
    "raster_samples_per_pixel",
];

pub use crate::papers::{CTSS_TABLE1, SRAA_SPEEDUP_OVER_SSAA16, SRAA_TABLE1};

/// Every `ms_<pass>` column of `rows`, sorted.
pub fn pass_columns(rows: &[ResultRow]) -> Vec<String> {
    let mut p: Vec<String> = rows
        .iter()
        .flat_map(|r| r.pass_ms.iter().map(|(n, _)| format!("ms_{n}")))
        .collect();
    p.sort();
    p.dedup();
    p
}

/// A cell value: text, a number, or nothing.
enum Cell {
    Text(String),
    Num(f64),
    Int(u64),
    Empty,
}

fn opt(v: Option<f64>) -> Cell {
    v.map(Cell::Num).unwrap_or(Cell::Empty)
}

fn row_cells(r: &ResultRow, passes: &[String]) -> Vec<Cell> {
    let mut c = vec![
        Cell::Text(r.scene.to_string()),
        Cell::Text(r.method.to_string()),
        Cell::Text(r.backend.clone()),
        Cell::Int(r.width as u64),
        Cell::Int(r.height as u64),
        Cell::Int(r.runs as u64),
        Cell::Num(r.ms_median),
        Cell::Num(r.ms_min),
        Cell::Num(r.ms_max),
        opt(r.ratio_to_noaa),
        opt(r.ratio_min),
        opt(r.ratio_max),
        opt(r.flip_mean),
        opt(r.psnr_db),
        opt(r.edge_flip_mean),
        opt(r.ssim_mean),
        Cell::Num(r.samples_per_pixel),
        Cell::Num(r.rays_per_pixel),
        Cell::Num(r.buffer_mib),
        r.quality_width
            .map(|v| Cell::Int(v as u64))
            .unwrap_or(Cell::Empty),
        r.quality_height
            .map(|v| Cell::Int(v as u64))
            .unwrap_or(Cell::Empty),
        r.reference.clone().map(Cell::Text).unwrap_or(Cell::Empty),
    ];
    // flip_<class>, px_<class>, then dssim_<class>, in `classes::CLASSES`
    // order.
    for class in CLASSES {
        c.push(opt(r.classes.and_then(|k| k.mean[class.index()])));
    }
    for class in CLASSES {
        c.push(
            r.classes
                .map(|k| Cell::Int(k.px[class.index()]))
                .unwrap_or(Cell::Empty),
        );
    }
    for class in CLASSES {
        c.push(opt(r.classes_ssim.and_then(|k| k.mean[class.index()])));
    }
    c.push(
        r.post_process
            .clone()
            .map(Cell::Text)
            .unwrap_or(Cell::Empty),
    );
    c.push(Cell::Text(timed_by_tags(r)));
    let measured = !r.errors_at.is_empty();
    c.push(if measured {
        Cell::Int(r.errors_at.len() as u64)
    } else {
        Cell::Empty
    });
    for metric in Metric::ALL {
        let range = r.range(metric);
        c.push(opt(range.map(|x| x.0)));
        c.push(opt(range.map(|x| x.1)));
    }
    c.push(opt(r.classes.and_then(|k| k.near_edge)));
    c.push(
        r.classes
            .map(|k| Cell::Int(k.near_edge_px))
            .unwrap_or(Cell::Empty),
    );
    c.push(opt(r.classes_ssim.and_then(|k| k.near_edge)));
    // flip_<class>_min/_max (the band last), then dssim_'s.
    for metric in Metric::ALL {
        let at = r.class_errors_at(metric);
        let spread = at.len() > 1;
        let slots = CLASSES
            .iter()
            .map(|c| Some(c.index()))
            .chain(std::iter::once(None));
        for slot in slots {
            let range = spread
                .then(|| {
                    classes::ClassError::range(&at, |e| match slot {
                        Some(i) => e.mean[i],
                        None => e.near_edge,
                    })
                })
                .flatten();
            c.push(opt(range.map(|x| x.0)));
            c.push(opt(range.map(|x| x.1)));
        }
    }
    c.push(Cell::Num(r.raster_samples_per_pixel));
    for p in passes {
        c.push(opt(r.pass(p.trim_start_matches("ms_"))));
    }
    c
}

/// The row's timing sources as tags joined by `+` (`cpu`, `gpu-timestamps`,
/// `gpu-wall-clock`): the `timed_by` column.
fn timed_by_tags(r: &ResultRow) -> String {
    r.timed_by
        .iter()
        .map(|s| s.tag())
        .collect::<Vec<_>>()
        .join("+")
}

/// One line naming each backend's timing sources, and each post-process
/// row's sources beyond its backend's NoAA frame (its post-process), so a
/// GPU time is never read as a CPU one and no source is listed twice.
fn timed_by_lines(md: &mut String, rows: &[&ResultRow]) {
    let mut seen: Vec<(String, Vec<subcone_scene::TimingSource>)> = Vec::new();
    for r in rows {
        let (who, sources) = if r.post_process.is_some() {
            // A post-process row is NoAA's frame plus the step: only the
            // step's sources are its own.
            let base: Vec<_> = rows
                .iter()
                .filter(|x| x.backend == r.backend && x.post_process.is_none())
                .flat_map(|x| x.timed_by.iter().copied())
                .collect();
            (
                format!("{} ({}), its post-process", r.method, r.backend),
                r.timed_by
                    .iter()
                    .filter(|s| !base.contains(s))
                    .copied()
                    .collect::<Vec<_>>(),
            )
        } else {
            (r.backend.clone(), r.timed_by.clone())
        };
        let i = match seen.iter().position(|(w, _)| *w == who) {
            Some(i) => i,
            None => {
                seen.push((who, Vec::new()));
                seen.len() - 1
            }
        };
        for s in sources {
            if !seen[i].1.contains(&s) {
                seen[i].1.push(s);
            }
        }
    }
    let parts: Vec<String> = seen
        .iter()
        .filter(|(_, s)| !s.is_empty())
        .map(|(w, s)| {
            let s: Vec<String> = s.iter().map(|s| s.to_string()).collect();
            format!("{w}: {}", s.join(" and "))
        })
        .collect();
    if parts.is_empty() {
        return;
    }
    let _ = writeln!(md, "Timed by: {}.\n", parts.join("; "));
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn csv_num(v: f64) -> String {
    if v.is_nan() {
        String::new()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        // Round-trippable and short.
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s.is_empty() || s == "-" {
            "0".into()
        } else {
            s.to_string()
        }
    }
}

/// `results.csv` of `rows`.
pub fn csv(rows: &[ResultRow]) -> String {
    let passes = pass_columns(rows);
    let mut out = BASE_COLUMNS.join(",");
    for p in &passes {
        out.push(',');
        out.push_str(p);
    }
    out.push('\n');
    for r in rows {
        let cells: Vec<String> = row_cells(r, &passes)
            .into_iter()
            .map(|c| match c {
                Cell::Text(s) => csv_field(&s),
                Cell::Num(v) => csv_num(v),
                Cell::Int(v) => v.to_string(),
                Cell::Empty => String::new(),
            })
            .collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// The columns of `rows` and each row as an object of them, as in
/// `results.json`.
pub(super) fn json_rows(rows: &[ResultRow]) -> (Vec<String>, Vec<Value>) {
    let passes = pass_columns(rows);
    let mut cols: Vec<String> = BASE_COLUMNS.iter().map(|s| s.to_string()).collect();
    cols.extend(passes.iter().cloned());
    let values = rows
        .iter()
        .map(|r| {
            let mut m = Map::new();
            for (k, c) in cols.iter().zip(row_cells(r, &passes)) {
                let v = match c {
                    Cell::Text(s) => Value::String(s),
                    Cell::Num(v) if v.is_finite() => json!(v),
                    Cell::Int(v) => json!(v),
                    _ => Value::Null,
                };
                m.insert(k.clone(), v);
            }
            Value::Object(m)
        })
        .collect();
    (cols, values)
}

/// `results.json`: the run, the columns, the rows, the sweep, what was skipped.
pub fn json(s: &ReportSummary, ctx: &Context) -> Value {
    let (columns, mut results) = json_rows(&s.rows);
    for (v, r) in results.iter_mut().zip(&s.rows) {
        if let (Value::Object(m), false) = (v, r.errors_at.is_empty()) {
            m.insert("errors_at".into(), errors_at_json(r));
        }
    }
    let (_, sweep) = json_rows(&s.sweep);
    json!({
        "version": code_version(),
        "machine": {
            "cpu": cpu_model(),
            "cpu_path": subcone_cpu::isa::Isa::detected().name(),
            "threads": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1),
        },
        "mode": ctx.mode.name(),
        "backends": ctx.backends,
        "backend_descriptions": ctx.backend_descriptions,
        "runs": ctx.runs,
        "other_cpu": ctx.other_cpu.json(),
        "ao_rays": ctx.ao,
        "reference": if ctx.mode == Mode::TimingOnly { Value::Null } else { json!(ctx.reference) },
        "scenes": ctx.scenes.iter().map(|sc| json!({
            "name": sc.name,
            "arg": sc.arg,
            "kind": if sc.sdf { "sdf" } else { "triangles" },
            "timing_size": [sc.timing_size.0, sc.timing_size.1],
            "quality_size": sc.quality_size.map(|q| json!([q.0, q.1])),
        })).collect::<Vec<_>>(),
        "columns": columns,
        "results": results,
        "sweep": sweep,
        "motion": crate::motion::json(&s.motion),
        "ao_crossover": crate::ao_sweep::crossovers(&s.ao_sweep).iter().map(|c| json!({
            "scene": c.scene, "backend": c.backend, "pair": c.pair.name(),
            "ssaa4": c.pair.ssaa4().to_string(), "sraa_rt": c.pair.sraa_rt().to_string(),
            "first_faster_ao": c.first_faster.map(|f| f.ao),
            "sraa_rt_ms": c.first_faster.map(|f| f.sraa_rt_ms),
            "ssaa4_ms": c.first_faster.map(|f| f.ssaa4_ms),
            "sraa_rt_edge_flip": c.first_faster.and_then(|f| f.sraa_rt_edge_flip),
            "ssaa4_edge_flip": c.first_faster.and_then(|f| f.ssaa4_edge_flip),
            "interpolated_ao": c.interpolated,
        })).collect::<Vec<_>>(),
        "ao_sweep": s.ao_sweep.rows.iter().map(|r| json!({
            "scene": r.scene, "method": r.method.to_string(), "backend": r.backend, "ao_rays": r.ao,
            "pair": crate::ao_sweep::Pair::of(r.method).name(),
            "ms_median": r.ms_median, "rays_per_pixel": r.rays_per_pixel,
            "ao_rays_per_pixel": r.ao_rays_per_pixel, "edge_flip": r.edge_flip,
            "flip_mean": r.flip_mean,
        })).collect::<Vec<_>>(),
        "skipped": s.skipped.iter().map(|k| json!({
            "scene": k.scene, "method": k.method, "backend": k.backend, "reason": k.reason,
        })).collect::<Vec<_>>(),
        "failures": s.failures.iter().map(|k| json!({
            "scene": k.scene, "method": k.method, "backend": k.backend, "error": k.error,
        })).collect::<Vec<_>>(),
        "unavailable_scenes": s.unavailable_scenes.iter().map(|(n, r)| json!({
            "scene": n, "reason": r,
        })).collect::<Vec<_>>(),
        "crops": s.crops.iter().map(|c| json!({
            "scene": c.scene,
            "regions": c.regions.iter().map(|r| json!({
                "kind": r.kind, "x": r.window.x, "y": r.window.y, "side": r.window.side, "rule": r.rule,
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "answer": crate::answer::json(&crate::answer::Answer::of(&s.rows, &ctx.scenes)),
        "elapsed_s": s.elapsed.as_secs_f64(),
    })
}

/// A row's error at each camera offset, as `results.json` gives it beside
/// the columns (`errors_at`): per offset its `offset` (pixels), `flip`,
/// `ssim`, and per class (the near-edge band included) `flip_<class>`,
/// `dssim_<class>` and `px_<class>`, so that every verdict can be derived
/// again from the file.
fn errors_at_json(r: &ResultRow) -> Value {
    let num = |v: Option<f64>| {
        v.filter(|x| x.is_finite())
            .map_or(Value::Null, |x| json!(x))
    };
    Value::Array(
        r.errors_at
            .iter()
            .map(|e| {
                let mut m = Map::new();
                m.insert("offset".into(), json!([e.offset.0, e.offset.1]));
                m.insert("flip".into(), num(Some(e.flip)));
                m.insert("ssim".into(), num(Some(e.ssim)));
                for c in CLASSES {
                    let i = c.index();
                    m.insert(format!("flip_{c}"), num(e.classes.mean[i]));
                    m.insert(format!("dssim_{c}"), num(e.classes_ssim.mean[i]));
                    m.insert(format!("px_{c}"), json!(e.classes.px[i]));
                }
                m.insert("flip_near_edge".into(), num(e.classes.near_edge));
                m.insert("dssim_near_edge".into(), num(e.classes_ssim.near_edge));
                m.insert("px_near_edge".into(), json!(e.classes.near_edge_px));
                Value::Object(m)
            })
            .collect(),
    )
}

fn f(v: Option<f64>, digits: usize) -> String {
    match v {
        Some(x) if x.is_infinite() => "∞".into(),
        Some(x) if x.is_finite() => format!("{x:.digits$}"),
        _ => "–".into(),
    }
}

/// A row's ratio to NoAA with its per-round range, `1.18 (1.15–1.21)`.
/// The range is left out where there is none (a ratio of medians) or it is
/// a single value (NoAA itself, or one round).
fn ratio_cell(r: &ResultRow) -> String {
    match (r.ratio_min, r.ratio_max) {
        (Some(lo), Some(hi)) if lo != hi => format!(
            "{} ({}–{})",
            f(r.ratio_to_noaa, 2),
            f(Some(lo), 2),
            f(Some(hi), 2)
        ),
        _ => f(r.ratio_to_noaa, 2),
    }
}

/// A mean of ratios to NoAA over scenes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeanRatio {
    /// Mean of the rows' `ratio_to_noaa` (each a median over rounds).
    pub mean: f64,
    /// Means of the rows' `ratio_min` and of their `ratio_max`: the range
    /// the mean would take were every scene at its lowest, or its highest,
    /// round. `None` unless every row has a range.
    pub range: Option<(f64, f64)>,
    /// Rows averaged.
    pub n: usize,
}

impl MeanRatio {
    /// Over the rows that have a ratio to NoAA; `None` without one.
    pub fn of<'a>(rows: impl IntoIterator<Item = &'a ResultRow>) -> Option<MeanRatio> {
        let rows: Vec<&ResultRow> = rows
            .into_iter()
            .filter(|r| r.ratio_to_noaa.is_some())
            .collect();
        if rows.is_empty() {
            return None;
        }
        let n = rows.len() as f64;
        let mean_of = |v: &dyn Fn(&ResultRow) -> Option<f64>| -> Option<f64> {
            rows.iter()
                .map(|r| v(r))
                .sum::<Option<f64>>()
                .map(|s| s / n)
        };
        Some(MeanRatio {
            mean: mean_of(&|r| r.ratio_to_noaa)?,
            range: mean_of(&|r| r.ratio_min).zip(mean_of(&|r| r.ratio_max)),
            n: rows.len(),
        })
    }

    /// `1.153x (1.121–1.190)` with `digits` decimals, `x` after each
    /// figure when `times`.
    pub fn show(&self, digits: usize, times: bool) -> String {
        let x = if times { "x" } else { "" };
        let mut s = format!("{:.digits$}{x}", self.mean);
        if let Some((lo, hi)) = self.range {
            let _ = write!(s, " ({lo:.digits$}–{hi:.digits$}{x})");
        }
        s
    }
}

/// A mean error with its range over the camera offsets, `0.0769
/// (0.0712–0.0801)`; the mean alone without a range.
fn with_range(v: Option<f64>, range: Option<(f64, f64)>) -> String {
    match (v, range) {
        (Some(_), Some((lo, hi))) => format!("{} ({lo:.4}–{hi:.4})", f(v, 4)),
        _ => f(v, 4),
    }
}

/// One scene's section of `report.md`: the table, the plots, the class
/// errors and verdicts, what was skipped, the crops.
fn scene_section(md: &mut String, s: &ReportSummary, sc: &SceneInfo) {
    let rows: Vec<&ResultRow> = s.rows.iter().filter(|r| r.scene == sc.name).collect();
    let _ = writeln!(md, "## {}\n", sc.name);
    let _ = writeln!(
        md,
        "{} scene (`{}`); timing at {}x{}{}.\n",
        if sc.sdf { "SDF" } else { "Triangle" },
        sc.arg,
        sc.timing_size.0,
        sc.timing_size.1,
        match sc.quality_size {
            Some(q) => format!(", error at {}x{}", q.0, q.1),
            None => String::new(),
        }
    );
    if rows.is_empty() {
        let _ = writeln!(md, "No method ran on this scene.\n");
    } else {
        let _ = writeln!(
            md,
            "| method | backend | median ms | min–max ms | × NoAA | FLIP | SSIM | PSNR dB | edge FLIP | spp | rays/px | buffers MiB |"
        );
        let _ = writeln!(md, "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
        let left_out = crate::answer::exclusions(&rows);
        for r in &rows {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {}–{} | {} | {} | {} | {} | {} | {} | {} | {} |",
                match crate::answer::excluded(&left_out, r) {
                    Some(e) => format!("{} {}", r.method, e.mark()),
                    None => r.method.to_string(),
                },
                r.backend,
                ms(r.ms_median),
                ms(r.ms_min),
                ms(r.ms_max),
                ratio_cell(r),
                with_range(r.flip_mean, r.range(Metric::Flip)),
                with_range(r.ssim_mean, r.range(Metric::Ssim)),
                f(r.psnr_db, 2),
                f(r.edge_flip_mean, 4),
                f(Some(r.samples_per_pixel), 2),
                f(Some(r.rays_per_pixel), 2),
                f(Some(r.buffer_mib), 2),
            );
        }
        let _ = writeln!(md);
        timed_by_lines(md, &rows);
        for e in &left_out {
            let _ = writeln!(
                md,
                "{} {}: {}; it is left out of the Pareto fronts and the answer.\n",
                e.method,
                e.mark(),
                e.reason()
            );
        }
        for r in rows.iter().filter(|r| r.post_process.is_some()) {
            let _ = writeln!(
                md,
                "{}: the {} NoAA frame post-processed by {}.\n",
                r.method,
                r.backend,
                r.post_process.as_deref().unwrap_or("?")
            );
        }
        md.push_str(&crate::hybrid::scene_table(&rows));
        let stem = file_safe(&sc.name);
        if rows.iter().any(|r| r.flip_mean.is_some()) {
            let _ = writeln!(
                md,
                "![{0}: FLIP against time](plots/{1}_flip_vs_time.png)\n",
                sc.name, stem
            );
        }
        let _ = writeln!(
            md,
            "![{0}: time per pass](plots/{1}_passes.png)\n",
            sc.name, stem
        );
        md.push_str(&class_section(&sc.name, &rows));
    }
    let skipped: Vec<_> = s.skipped.iter().filter(|k| k.scene == sc.name).collect();
    if !skipped.is_empty() {
        let list: Vec<String> = skipped
            .iter()
            .map(|k| {
                if k.backend == "*" {
                    format!("{} ({})", k.method, k.reason)
                } else {
                    format!("{} on {} ({})", k.method, k.backend, k.reason)
                }
            })
            .collect();
        let _ = writeln!(md, "Skipped: {}.\n", list.join("; "));
    }
    if let Some(c) = s.crops.iter().find(|c| c.scene == sc.name) {
        let _ = writeln!(
            md,
            "Zoomed crops ({}×, NoAA | methods | reference; regions outlined in \
[crops_overview.png](images/{}/crops_overview.png): edge red, shadow green, reflection blue):\n",
            crops::ZOOM,
            file_safe(&sc.name)
        );
        for r in &c.regions {
            let _ = writeln!(
                md,
                "- {} at ({}, {}), {}×{} px: {}\n\n  ![{} crop](images/{}/crops_{}.png)\n",
                r.kind,
                r.window.x,
                r.window.y,
                r.window.side,
                r.window.side,
                r.rule,
                r.kind,
                file_safe(&sc.name),
                r.kind
            );
        }
    }
}

/// `report.md`.
pub fn markdown(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    let _ = writeln!(md, "# subcone report\n");
    let _ = writeln!(
        md,
        "Mode **{}**, backends {}, {} timed rounds after each method's warm-up ({}): a round renders \
every method of the scene and backend once at the timing size, round *r* starting at method *r* mod \
*n* of the *n* in table order and wrapping, so that the machine's drift falls on every method \
alike. Code {}, {} hardware threads ({}).{}{} {}\n",
        ctx.mode.name(),
        ctx.backend_descriptions.join(", "),
        ctx.runs,
        if ctx.mode == Mode::TimingOnly {
            "a render at the timing size".to_string()
        } else {
            format!(
                "the method's quality render, and a render at the timing size where that size differs and the frame is predicted under {} s",
                crate::timing::SHORT_RENDER.as_secs_f64()
            )
        },
        code_version(),
        threads,
        cpu_model(),
        if ctx.mode == Mode::TimingOnly {
            " No references and no errors (timing only).".to_string()
        } else {
            format!(" Errors against a {} reference.", ctx.reference)
        },
        if ctx.ao > 0 {
            format!(
                " Ambient occlusion: {} rays per shaded point on triangle scenes (`--ao`), references included.",
                ctx.ao
            )
        } else {
            String::new()
        },
        ctx.other_cpu.sentence()
    );
    if let Some(w) = ctx.other_cpu.warning() {
        let _ = writeln!(md, "{w}\n");
    }
    // The answer first; the definitions it rests on follow.
    let answer = crate::answer::Answer::of(&s.rows, &ctx.scenes);
    md.push_str(&crate::answer::section(&answer, &s.rows, ctx));
    let _ = writeln!(
        md,
        "Times are the median (and range) over the rounds of the wall time of `Backend::render` at the \
timing size; *× NoAA* is the median over the rounds of the method's time over NoAA's in the same \
round, with the smallest and largest per-round ratio in brackets (the smaa row, whose post-process \
is timed apart from the rounds, shows its median time over NoAA's, without a range); errors are measured on the tone-mapped 8-bit sRGB images at the quality size: mean FLIP (LDR-FLIP, \
67 pixels per degree), PSNR, and *edge FLIP*, the mean FLIP over the edge mask (pixels where the \
NoAA depth or normal changes across a 4-neighbour by more than 2 % (unless the inverse depth \
continues linearly, as across a plane) or a cosine of 0.9, where a surface meets the background, or where the reference's luminance Sobel gradient exceeds 0.1). \
*spp* is shaded samples per pixel (the mean of the samples-per-pixel AOV of the quality render, \
or shading evaluations per pixel without one); *rays/px* counts every ray cast (primary, \
geometry, shadow, secondary, ambient occlusion); *buffers MiB* is what the backend allocated for the frame, \
which leaving out passes a scene does not need (shadows, reflections) keeps down. Lower FLIP is better; the Pareto front joins the methods that no \
faster method beats.\n"
    );

    if ctx.mode != Mode::TimingOnly {
        md.push_str(&rules(&s.error_offsets, s.elapsed));
        md.push_str(&verdict_summary(s, ctx));
    }

    for sc in &ctx.scenes {
        scene_section(&mut md, s, sc);
    }

    let _ = writeln!(md, "## Skipped\n");
    if s.skipped.is_empty() && s.unavailable_scenes.is_empty() {
        let _ = writeln!(md, "Nothing was skipped.\n");
    } else {
        let _ = writeln!(
            md,
            "Combinations that were never rendered, asked of each backend before rendering \
(one line per method, backend and reason, naming the scenes):\n"
        );
        // Group by (method, backend, reason), in first-seen order.
        let mut groups: Vec<(&str, &str, &str, Vec<&str>)> = Vec::new();
        for k in &s.skipped {
            match groups
                .iter_mut()
                .find(|g| g.0 == k.method && g.1 == k.backend && g.2 == k.reason)
            {
                Some(g) => g.3.push(&k.scene),
                None => groups.push((&k.method, &k.backend, &k.reason, vec![&k.scene])),
            }
        }
        for (method, backend, reason, scenes) in groups {
            let _ = writeln!(
                md,
                "- {method}{}: {reason} ({})",
                if backend == "*" {
                    String::new()
                } else {
                    format!(" on {backend}")
                },
                scenes.join(", ")
            );
        }
        for (n, r) in &s.unavailable_scenes {
            let _ = writeln!(md, "- scene {n} is not available: {r}");
        }
        let _ = writeln!(md);
    }

    if !s.failures.is_empty() {
        let _ = writeln!(md, "## Failures\n");
        for k in &s.failures {
            let _ = writeln!(
                md,
                "- {} / {} on {}: {}",
                k.scene, k.method, k.backend, k.error
            );
        }
        let _ = writeln!(md);
    }

    md.push_str(&sdf_pick(s, ctx));
    md.push_str(&paper_comparison(s, ctx));
    md.push_str(&crate::ao_sweep::section(
        &s.ao_sweep,
        (ctx.mode != Mode::TimingOnly).then_some(ctx.reference.as_str()),
    ));
    md.push_str(&crate::motion::section(&s.motion));
    md.push_str(&targets(s, ctx));

    let _ = writeln!(
        md,
        "## How the crops are chosen\n\n\
Each region is the square window (a quarter of the image's short side, 8 to 32 px) that scores \
highest over every position. **Edge**: most edge-mask pixels, geometric edges counting 4× \
gradient-only ones. **Shadow**: most NoAA error \
(|NoAA − reference| luminance) on pixels that are geometrically smooth but on a strong gradient of \
an untextured (all albedos grey), reflection-free NoAA render, i.e. light and shadow boundaries; \
without lights, the most NoAA error on smooth, non-reflective pixels. **Reflection**: most NoAA \
error on reflective pixels (those whose NoAA colour changes when reflections are turned off), \
leaving out geometric edges; without reflective pixels, the most NoAA error off the edge mask, \
away from the shadow window.\n"
    );
    md
}

/// The edge classes' definitions and thresholds, the camera offsets the
/// errors are measured at (`offsets`, with what they cost of a run of
/// `elapsed`), and the rules of judgement.
pub fn rules(offsets: &crate::ErrorOffsets, elapsed: std::time::Duration) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## Edge classes and the rules of judgement\n\n\
Every pixel is classified from its own sub-samples: the AOVs of a CPU NoAA frame rendered at \
{s}× the quality size on each side, so each pixel has a {s}×{s} grid of sub-samples (fewer per side \
only where that frame would pass the pixel limit). A feature the one NoAA sample misses is still \
seen by a sub-sample. The classes may overlap; *flat* is a pixel in none of the others.\n\n\
| class | a pixel is in it when |\n|---|---|\n\
| silhouette | two 4-neighbouring sub-samples of the pixel see a surface and the background, or view depths that differ by more than {d} relatively, unless the inverse depth continues linearly from either side (as across one plane) |\n\
| crease | two 4-neighbouring sub-samples on one continuous surface (no silhouette between them) have normals whose cosine is below {c} |\n\
| shadow | no silhouette or crease in the pixel, and the per-light visibility of its surface sub-samples differs (a light that faces away counts as visible) |\n\
| texture | no silhouette or crease in the pixel, and its surface sub-samples' albedo differs by more than {t} in some channel of √albedo |\n\
| reflection | a sub-sample sees a mirror (reflectance above 0) |\n\
| near edge | none of the above, but within {r} px of a pixel that is (Chebyshev distance: in the {side}×{side} square around it); measured and reported, not judged |\n\
| flat | none of the above, and not near edge |\n\n\
The near-edge band holds the pixels an error metric with a spatial filter (FLIP's) charges with \
a neighbouring edge's error; flat is judged without them. \
`flip_<class>` is the mean FLIP over the class's pixels and `px_<class>` their count (in \
`results.csv` and `results.json`; the band's columns are `flip_near_edge`, `px_near_edge`, \
`dssim_near_edge`).\n\n\
{offsets_text}\n\n\
The second metric is SSIM (Wang et al. 2004): an 11×11 Gaussian window of σ = 1.5, K1 = 0.01, \
K2 = 0.03, on the luminance of the same tone-mapped 8-bit images FLIP compares, one value per \
pixel (the window renormalised where it leaves the image). `ssim_mean` is its mean over the \
image and `dssim_<class>` the mean of 1 − SSIM over the class's pixels; the `ssim_<method>.png` \
images show 1 − SSIM from 0 (black) to 0.5 or more (white).\n\n\
Which classes each method claims to fix:\n\n\
| method | claimed classes |\n|---|---|\n\
| ssaaN, ssaaN+ctss | all |\n\
| sraa | silhouette, crease |\n\
| sraa-rt | silhouette, crease, shadow, reflection |\n\
| `+mat` variants | adds texture |\n\
| ctss, ctss-r, ctss-delayed | silhouette |\n\
| ctss+edges | silhouette, crease |\n\
| fxaa, smaa | silhouette, crease, shadow, texture (luminance edges of any origin) |\n\n\
Verdicts are computed under each metric by the same rules, comparing a method with NoAA (same \
scene and backend) at each camera offset, paired: the method's error at an offset against NoAA's \
at the same offset. On a claimed class, at one offset, the method *wins* when its error there \
(FLIP, or 1 − SSIM) is at most {b} × NoAA's and *loses* when it is at least {l:.4} × (1/{b}) \
NoAA's. It **beats** NoAA on the class when it wins at every offset, **loses by N×** when it \
loses at every offset (N the ratio of its mean error to NoAA's), **ties** when it neither wins nor \
loses at any offset, and is a **tie (within noise)** when the offsets disagree: the margin does \
not clear the spread over the offsets. On flat pixels, at one offset, it *holds* when its flat \
error is at most {f} × NoAA's; it **holds** when it holds at every offset, **loses by N×** when \
it holds at none, and is a **tie (within noise)** otherwise. A class (or flat) with fewer than \
{min_px} pixels at some offset gets no verdict (**too few pixels**). Under SSIM a difference of \
mean 1 − SSIM below {floor} does not count either way (to win, a method must also be at least \
that much lower; to lose, at least that much higher): that is what rounding to 8 bits alone does \
to a flat window ((1/255)²/12 over K2², about 0.0014), chosen before any method was measured. \
Each scene's verdict lines are computed from the rows by these rules, with the range of the \
per-offset ratios to NoAA, and list where the two metrics disagree, each with a computed cause \
line; a claimed class with no pixel in the scene is listed as having none.\n",
        s = classes::SUBSAMPLES,
        d = classes::SILHOUETTE_DEPTH,
        c = classes::CREASE_COS,
        t = classes::TEXTURE_ALBEDO,
        b = classes::BEAT_FACTOR,
        l = classes::LOSE_FACTOR,
        f = classes::FLAT_FACTOR,
        floor = classes::DSSIM_FLOOR,
        r = classes::NEAR_EDGE_RADIUS,
        side = 2 * classes::NEAR_EDGE_RADIUS + 1,
        min_px = classes::MIN_VERDICT_PIXELS,
        offsets_text = offsets_text(offsets, elapsed),
    );
    md
}

/// What the rules say about the camera offsets of this run, and their cost.
fn offsets_text(o: &crate::ErrorOffsets, elapsed: std::time::Duration) -> String {
    if o.offsets.len() < 2 {
        return "Errors are measured from the scene's camera alone (one offset): verdicts are \
judged on that one frame."
            .into();
    }
    let list: Vec<String> = o
        .offsets
        .iter()
        .map(|&(x, y)| format!("({x}, {y})"))
        .collect();
    let secs = o.elapsed.as_secs_f64();
    format!(
        "Errors are measured at K = {k} sub-pixel camera offsets: the scene's camera turned right \
and down by {list} pixels' worth of angle at the image centre, each offset against its own \
reference and with its own classes (only the quality render is repeated; the timing rounds are \
not). FLIP, SSIM and every class error are the mean over the offsets, with the smallest and \
largest in brackets (`_min` and `_max` columns); PSNR, edge FLIP and the images are the first \
offset's; `px_<class>` is the fewest pixels the class has at any offset. {size} The {extra} \
further offsets took {secs:.1} s of this run's {total:.1} s ({share:.1} %).",
        k = o.offsets.len(),
        list = list.join(", "),
        size = if o.divisor > 1 {
            format!(
                "The offsets after the first are measured at 1/{d} of the quality size on each side \
(1/{d2} of the pixels) against a {r} reference, so that they fit the run's time; the range over \
the offsets includes the effect of that size and reference (a method and NoAA are always compared \
at one size, against one reference).",
                d = o.divisor,
                d2 = o.divisor * o.divisor,
                r = o.reference
            )
        } else {
            "Every offset is measured at the quality size.".into()
        },
        extra = o.offsets.len() - 1,
        total = elapsed.as_secs_f64(),
        share = 100.0 * secs / elapsed.as_secs_f64().max(1e-9),
    )
}

/// Every verdict of the run in one table: a row per method, backend and
/// metric, a column per scene, each cell the claimed classes beaten (of
/// those with pixels) and whether flat holds.
pub fn verdict_summary(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let scenes: Vec<&str> = ctx.scenes.iter().map(|sc| sc.name.as_str()).collect();
    let mut keys: Vec<(RowKey, String, Metric)> = Vec::new();
    let mut cells: Vec<((RowKey, String, Metric, String), String)> = Vec::new();
    for sc in &scenes {
        let rows: Vec<&ResultRow> = s.rows.iter().filter(|r| r.scene == *sc).collect();
        for metric in Metric::ALL {
            for (backend, v) in verdicts(&rows, metric) {
                let key = (v.method.clone(), backend.clone(), metric);
                if !keys.contains(&key) {
                    keys.push(key);
                }
                cells.push((
                    (v.method.clone(), backend, metric, sc.to_string()),
                    glance_cell(&v),
                ));
            }
        }
    }
    if keys.is_empty() {
        return md;
    }
    // Each method's FLIP row, then its SSIM row.
    let order = keys.clone();
    keys.sort_by_key(|k| {
        let first = order.iter().position(|f| f.0 == k.0 && f.1 == k.1);
        (first, k.2 == Metric::Ssim)
    });
    let _ = writeln!(
        md,
        "## Verdicts at a glance\n\n\
Per scene and metric: how many of the claimed classes with a verdict the method beats NoAA on \
(*b*/*n*), then how many it ties, ties within noise or loses, and how many have too few pixels \
for a verdict; then its flat verdict (holds, **loses N×**, tie (noise), few px). The lines under \
each scene give the classes and figures, and where the two metrics disagree, with the cause.\n"
    );
    let _ = writeln!(md, "| method | backend | metric | {} |", scenes.join(" | "));
    let _ = writeln!(md, "|---|---|---|{}", "--:|".repeat(scenes.len()));
    for (method, backend, metric) in &keys {
        let row: Vec<String> = scenes
            .iter()
            .map(|sc| {
                cells
                    .iter()
                    .find(|(k, _)| {
                        k.0 == *method && k.1 == *backend && k.2 == *metric && k.3 == *sc
                    })
                    .map(|(_, c)| c.clone())
                    .unwrap_or_else(|| "–".into())
            })
            .collect();
        let _ = writeln!(
            md,
            "| {} | {backend} | {} | {} |",
            same_image_name(s, method, backend),
            metric.name(),
            row.join(" | ")
        );
    }
    let _ = writeln!(md);
    md
}

/// `method`, or `method (same image as ctss)` when on every scene where it
/// has an error on `backend` its image is byte-identical to one other
/// method's ([`answer::exclusions`](crate::answer::exclusions)).
fn same_image_name(s: &ReportSummary, method: &RowKey, backend: &str) -> String {
    let rows: Vec<&ResultRow> = s.rows.iter().collect();
    let left_out = crate::answer::exclusions(&rows);
    let measured = rows
        .iter()
        .filter(|r| r.method == *method && r.backend == backend && r.flip_mean.is_some())
        .count();
    let same: Vec<&RowKey> = left_out
        .iter()
        .filter(|e| e.method == *method && e.backend == backend)
        .filter_map(|e| match &e.why {
            crate::answer::Why::SameImage { as_method } => Some(as_method),
            _ => None,
        })
        .collect();
    match same.first() {
        Some(first) if same.len() == measured && same.iter().all(|m| m == first) => {
            format!("{method} (same image as {first})")
        }
        _ => method.to_string(),
    }
}

/// One cell of "Verdicts at a glance": `3/4 · 1 noise · holds`.
pub fn glance_cell(v: &Verdict) -> String {
    use classes::Outcome;
    let judged = v
        .judged
        .iter()
        .filter(|j| j.outcome != Outcome::FewPixels)
        .count();
    let mut cell = format!("{}/{judged}", v.beats.len());
    for (o, word) in [
        (Outcome::Ties, "tie"),
        (Outcome::Noise, "noise"),
        (Outcome::Loses, "**lost**"),
        (Outcome::FewPixels, "few px"),
    ] {
        let n = v.with(o).count();
        if n > 0 {
            let _ = write!(cell, " · {n} {word}");
        }
    }
    let flat = match &v.flat_judged {
        None => "no flat".to_string(),
        Some(j) => match j.outcome {
            Outcome::Holds => "holds".into(),
            Outcome::Loses => format!("**loses {}**", classes::loss_text(j.mean_ratio())),
            Outcome::Noise => "tie (noise)".into(),
            _ => "few px".into(),
        },
    };
    let _ = write!(cell, " · {flat}");
    cell
}

/// A table of one metric's per-class error, a row per measured method.
fn class_table(md: &mut String, rows: &[&&ResultRow], metric: Metric) {
    let Some(first) = rows.first().and_then(|r| r.class_error(metric)) else {
        return;
    };
    let what = match metric {
        Metric::Flip => "FLIP",
        Metric::Ssim => "1 − SSIM",
    };
    let offsets = rows.iter().map(|r| r.errors_at.len()).max().unwrap_or(0);
    let _ = writeln!(
        md,
        "{what} by edge class (pixels per class in the header{}; *near edge* is measured, not judged):\n",
        if offsets > 1 {
            format!(
                ", the fewest over the {offsets} camera offsets; each cell the mean over the offsets and, in brackets, the smallest and largest"
            )
        } else {
            String::new()
        }
    );
    let mut head: Vec<String> = CLASSES
        .iter()
        .map(|c| format!("{c} ({} px)", first.px[c.index()]))
        .collect();
    head.push(format!("near edge ({} px)", first.near_edge_px));
    let _ = writeln!(md, "| method | backend | {} |", head.join(" | "));
    let _ = writeln!(md, "|---|---|{}", "--:|".repeat(CLASSES.len() + 1));
    for r in rows {
        let k = r.class_error(metric).unwrap_or_default();
        let at = r.class_errors_at(metric);
        let cell = |v: Option<f64>, get: &dyn Fn(&classes::ClassError) -> Option<f64>| {
            let range = (at.len() > 1)
                .then(|| classes::ClassError::range(&at, get))
                .flatten();
            with_range(v, range)
        };
        let mut cells: Vec<String> = CLASSES
            .iter()
            .map(|c| cell(k.mean[c.index()], &|e| e.mean[c.index()]))
            .collect();
        cells.push(cell(k.near_edge, &|e| e.near_edge));
        let _ = writeln!(
            md,
            "| {} | {} | {} |",
            r.method,
            r.backend,
            cells.join(" | ")
        );
    }
    let _ = writeln!(md);
}

/// A scene's error by class under each metric (tables and the FLIP chart),
/// its verdict lines under each, and where the two disagree.
fn class_section(scene: &str, rows: &[&ResultRow]) -> String {
    let mut md = String::new();
    let with: Vec<&&ResultRow> = rows.iter().filter(|r| r.classes.is_some()).collect();
    if with.is_empty() {
        return md;
    }
    class_table(&mut md, &with, Metric::Flip);
    let _ = writeln!(
        md,
        "![{scene}: FLIP by edge class](plots/{}_classes.png)\n",
        file_safe(scene)
    );
    class_table(&mut md, &with, Metric::Ssim);
    let flip = verdicts(rows, Metric::Flip);
    let ssim = verdicts(rows, Metric::Ssim);
    if !flip.is_empty() || !ssim.is_empty() {
        let _ = writeln!(md, "Verdicts against NoAA:\n");
        for (backend, v) in flip.iter().chain(&ssim) {
            let _ = writeln!(md, "{}", v.line(backend));
        }
        let _ = writeln!(md);
        let disagree: Vec<String> = flip
            .iter()
            .filter_map(|(b, fv)| {
                let (_, sv) = ssim
                    .iter()
                    .find(|(sb, sv)| sb == b && sv.method == fv.method)?;
                let items = disagreement(fv, sv);
                if items.is_empty() {
                    return None;
                }
                let find = |m: &RowKey| {
                    rows.iter()
                        .find(|r| r.method == *m && r.backend == *b)
                        .copied()
                };
                let band = match (
                    rows.iter()
                        .find(|r| r.method == fv.method && r.backend == *b)
                        .copied(),
                    find(&NOAA.into()),
                ) {
                    (Some(it), Some(noaa)) => near_edge_share(it, noaa),
                    _ => None,
                };
                let mut text = format!("- **{}** ({b}):\n", fv.method);
                for (what, cause) in items {
                    let _ = writeln!(text, "  - {what}.\n    Cause: {cause}.");
                }
                if let Some(band) = band {
                    let _ = writeln!(text, "  - Near-edge band: {}.", band.sentence());
                }
                Some(text)
            })
            .collect();
        if disagree.is_empty() {
            let _ = writeln!(md, "FLIP and SSIM agree on every verdict of this scene.\n");
        } else {
            let _ = writeln!(
                md,
                "Where FLIP and SSIM disagree, each with its computed cause:\n\n{}",
                disagree.join("")
            );
        }
    }
    md
}

/// Where the verdicts of one row under FLIP (`flip`) and SSIM (`ssim`)
/// differ, class by class and on flat, with both metrics' words and
/// figures, each with its computed cause: noise when one metric's
/// per-offset ratios straddle its thresholds, else a disagreement at every
/// offset, with both ranges. Empty when they agree (a class with too few
/// pixels under either metric is not compared).
fn disagreement(flip: &Verdict, ssim: &Verdict) -> Vec<(String, String)> {
    use classes::{outcome_word, Judged, Outcome};
    let mut out = Vec::new();
    let mut compare = |what: String, f: &Judged, s: &Judged| {
        let few = |j: &Judged| j.outcome == Outcome::FewPixels;
        if f.outcome == s.outcome || few(f) || few(s) {
            return;
        }
        let range = |j: &Judged| {
            format!(
                "{}–{}×",
                classes::ratio_text(j.ratio.0),
                classes::ratio_text(j.ratio.1)
            )
        };
        let thresholds = if f.class == Class::Flat {
            format!("holds at ≤ {}×", classes::FLAT_FACTOR)
        } else {
            format!(
                "wins at ≤ {}×, loses at ≥ {:.2}×",
                classes::BEAT_FACTOR,
                classes::LOSE_FACTOR
            )
        };
        let noisy: Vec<String> = [(f, "FLIP"), (s, "SSIM")]
            .iter()
            .filter(|(j, _)| j.outcome == Outcome::Noise)
            .map(|(j, m)| format!("{m}'s ({})", range(j)))
            .collect();
        let cause = if !noisy.is_empty() {
            format!(
                "noise: the per-offset ratio to NoAA, {}, does not stay on one side of the \
thresholds ({thresholds}), so the call changes with the offset; FLIP's ratios are {}, SSIM's {}",
                noisy.join(" and "),
                range(f),
                range(s)
            )
        } else {
            format!(
                "not noise: each metric gives the same call at each of the {} offsets (FLIP ratio \
to NoAA {}, SSIM {}); the two metrics weigh the change differently",
                f.offsets,
                range(f),
                range(s)
            )
        };
        out.push((
            format!(
                "{what}: {} under FLIP ({}) but {} under SSIM ({})",
                outcome_word(f),
                f.figures(),
                outcome_word(s),
                s.figures()
            ),
            cause,
        ));
    };
    for j in &flip.judged {
        if let Some(s) = ssim.judged.iter().find(|s| s.class == j.class) {
            compare(j.class.to_string(), j, s);
        }
    }
    if let (Some(f), Some(s)) = (&flip.flat_judged, &ssim.flat_judged) {
        compare("flat".into(), f, s);
    }
    out
}

/// How a method's FLIP excess over NoAA on the pixels in no class splits
/// between the near-edge band and flat: sums over the pixels and the
/// camera offsets (paired, each offset's own masks).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandShare {
    /// Σ (method − NoAA) FLIP over the band's pixels.
    pub band_excess: f64,
    /// Σ (method − NoAA) FLIP over the flat pixels.
    pub flat_excess: f64,
    /// Band pixels, summed over the offsets.
    pub band_px: u64,
    /// Flat pixels, summed over the offsets.
    pub flat_px: u64,
}

impl BandShare {
    /// The band's share of the excess, when the excess is positive.
    pub fn share(&self) -> Option<f64> {
        let total = self.band_excess + self.flat_excess;
        (total > 0.0).then(|| self.band_excess / total)
    }

    /// The band's share of the pixels in no class.
    pub fn px_share(&self) -> f64 {
        self.band_px as f64 / (self.band_px + self.flat_px).max(1) as f64
    }

    /// In words, for a cause line.
    pub fn sentence(&self) -> String {
        let px = 100.0 * self.px_share();
        match self.share() {
            Some(share) if self.band_excess >= 0.0 && self.flat_excess >= 0.0 => format!(
                "{:.0} % of the method's FLIP excess over NoAA on the pixels in no class (flat and \
near edge, summed over the pixels and the offsets) lies in the near-edge band, which holds {px:.0} % \
of those pixels; flat, judged above, carries {:.0} %",
                100.0 * share,
                100.0 * (1.0 - share)
            ),
            _ => format!(
                "the method's FLIP minus NoAA's, summed over the pixels and the offsets, is {:+.2} on \
the near-edge band ({px:.0} % of the pixels in no class) and {:+.2} on flat",
                self.band_excess, self.flat_excess
            ),
        }
    }
}

/// [`BandShare`] of row `it` against `noaa` (FLIP, paired by offset);
/// `None` when either has no per-class errors or no pixel lies in no class.
pub fn near_edge_share(it: &ResultRow, noaa: &ResultRow) -> Option<BandShare> {
    let (a, n) = (
        it.class_errors_at(Metric::Flip),
        noaa.class_errors_at(Metric::Flip),
    );
    let mut out = BandShare {
        band_excess: 0.0,
        flat_excess: 0.0,
        band_px: 0,
        flat_px: 0,
    };
    let flat = Class::Flat.index();
    for (a, n) in a.iter().zip(&n) {
        if let (Some(x), Some(y)) = (a.near_edge, n.near_edge) {
            out.band_excess += (x - y) * a.near_edge_px as f64;
            out.band_px += a.near_edge_px;
        }
        if let (Some(x), Some(y)) = (a.mean[flat], n.mean[flat]) {
            out.flat_excess += (x - y) * a.px[flat] as f64;
            out.flat_px += a.px[flat];
        }
    }
    (out.band_px + out.flat_px > 0).then_some(out)
}

/// The verdict under `metric` of every method but NoAA among `rows` (one
/// scene), against NoAA on the same backend: (backend, verdict).
pub fn verdicts(rows: &[&ResultRow], metric: Metric) -> Vec<(String, Verdict)> {
    let mut out = Vec::new();
    for r in rows {
        if r.method == NOAA {
            continue;
        }
        let noaa = rows
            .iter()
            .find(|n| n.method == NOAA && n.backend == r.backend && n.scene == r.scene)
            .map(|n| n.class_errors_at(metric))
            .unwrap_or_default();
        let it = r.class_errors_at(metric);
        if !it.is_empty() && !noaa.is_empty() {
            let v = Verdict::judge_claims(r.method.clone(), r.claims(), metric, &it, &noaa);
            out.push((r.backend.clone(), v));
        }
    }
    out
}

fn rows_for<'a>(s: &'a [ResultRow], method: Method, backend: &str) -> Vec<&'a ResultRow> {
    s.iter()
        .filter(|r| r.method == method && r.backend == backend)
        .collect()
}

/// CTSS overhead targets: average time ratio to NoAA over the SDF scenes.
pub const CTSS_TARGETS: [(Method, f64); 2] = [(CTSS, 1.20), (CTSS_R, 1.08)];
/// CTSS's quality bar on the paper's SDF scenes
/// ([`SDF_SCENES`](subcone_scene::builtin::SDF_SCENES)): `ctss` beats NoAA on
/// silhouettes and holds on flat pixels (the verdict's rules), its
/// whole-image FLIP is below NoAA's, and its silhouette FLIP is at most this
/// factor of `ssaa4`'s (the paper's "comparable to 4× supersampling").
pub const CTSS_SSAA4_FACTOR: f64 = 1.25;
/// On the stiff scenes and the semi-transparent ones, no CTSS method's
/// whole-image FLIP exceeds NoAA's by more than this factor (the default
/// methods; the `-paper` ones are the paper's behaviour, shown beside them).
pub const CTSS_STIFF_FACTOR: f64 = 1.02;

/// SRAA-RT target: at most this share of `ssaa16`'s time...
pub const SRAA_RT_TIME_SHARE: f64 = 1.0 / 6.0;
/// ...with an edge FLIP at most this factor above `ssaa16`'s.
pub const SRAA_RT_EDGE_FACTOR: f64 = 1.25;
/// Ray throughput target: the pipeline's rate at least this share of obvhs'
/// raw traversal on the same rays.
pub const RAY_THROUGHPUT_SHARE: f64 = 0.70;
/// Fewest rays per pass at which a ray-throughput figure is judged: 16 of
/// the raw passes' rayon tasks ([`subcone_cpu::throughput::CHUNK`] rays
/// each). With fewer, the raw pass is a few uneven tasks that cannot keep
/// the threads busy, so its rate is no bound on the pipeline's (which
/// splits its frame into tiles of its own).
pub const RAY_THROUGHPUT_MIN_RAYS: usize = 16 * subcone_cpu::throughput::CHUNK;

/// Whether a ray-throughput target is judged on a pass of `rays` rays whose
/// pipeline rate is `ratio` of raw traversal's: `Ok(met)`, or `Err(why
/// not)`. Raw traversal is a bound on the pipeline (which runs the same
/// traversal and more) only on a pass long enough for it to use the
/// threads; where the pipeline still outruns it, it bounds nothing.
pub fn throughput_judged(rays: usize, ratio: f64) -> Result<bool, String> {
    if rays < RAY_THROUGHPUT_MIN_RAYS {
        Err(format!(
            "not judged at this size: {rays} rays are under {RAY_THROUGHPUT_MIN_RAYS}, 16 of raw traversal's {}-ray tasks, so raw traversal is no bound",
            subcone_cpu::throughput::CHUNK
        ))
    } else if !ratio.is_finite() || ratio > 1.0 {
        Err("not judged: the pipeline outran raw traversal, which is then no bound".into())
    } else {
        Ok(ratio >= RAY_THROUGHPUT_SHARE)
    }
}

/// SRAA's quality bar against NoAA: on every triangle scene, `sraa` and
/// `sraa-rt` beat NoAA on each class they claim and hold on flat pixels (the
/// verdict's rules) and their whole-image FLIP is below NoAA's.
pub const SRAA_METHODS: [Method; 2] = [SRAA, SRAA_RT];
/// `sraa-rt`'s FLIP on silhouette, crease and shadow pixels at most this
/// factor of `ssaa4`'s...
pub const SRAA_RT_SSAA4_FACTOR: f64 = 1.25;
/// ...on these scenes, where it should also be faster than `ssaa4`.
pub const SRAA_RT_SSAA4_SCENES: [&str; 2] = ["atrium", "sponza"];

/// The word of a target's *met* column.
fn yes(ok: bool) -> &'static str {
    if ok {
        "met"
    } else {
        "**not met**"
    }
}

/// The row of `method` on `backend` and `scene`.
fn row_of<'a>(
    rows: &'a [ResultRow],
    method: Method,
    backend: &str,
    scene: &str,
) -> Option<&'a ResultRow> {
    rows.iter()
        .find(|x| x.method == method && x.backend == backend && x.scene == scene)
}

/// `method`'s verdict against NoAA under FLIP on the classes it claims,
/// paired by camera offset as the verdict lines, and its flat figures in
/// words.
fn flip_verdict(method: Method, it: &ResultRow, noaa: &ResultRow) -> (Verdict, String) {
    let v = Verdict::judge_claims(
        method.into(),
        method.claims(),
        Metric::Flip,
        &it.class_errors_at(Metric::Flip),
        &noaa.class_errors_at(Metric::Flip),
    );
    let flat = v
        .flat
        .map(|(x, y)| format!("flat {x:.4} vs {y:.4}"))
        .unwrap_or_else(|| "no flat pixels".into());
    (v, flat)
}

/// The rows of the SRAA targets for backend `b` (triangle scenes only).
fn sraa_targets(s: &ReportSummary, sdf: &[&str], b: &str, md: &mut String) {
    let find = |method, scene: &str| row_of(&s.rows, method, b, scene);
    for method in SRAA_METHODS {
        for r in rows_for(&s.rows, method, b)
            .into_iter()
            .filter(|r| !sdf.contains(&r.scene.as_str()))
        {
            let Some(noaa) = find(NOAA, &r.scene) else {
                continue;
            };
            let (Some(_), Some(_), Some(a), Some(na)) =
                (r.classes, noaa.classes, r.flip_mean, noaa.flip_mean)
            else {
                continue;
            };
            let (v, flat) = flip_verdict(method, r, noaa);
            let met = v.misses.is_empty() && v.holds_on_flat() && a < na;
            let _ = writeln!(
                md,
                "| {method} beats NoAA on its claimed classes, holds on flat, whole FLIP below NoAA's | {b} | {} | {} of {} claimed classes beaten, {flat}, whole {a:.4} vs {na:.4} | {} |",
                r.scene,
                v.beats.len(),
                v.beats.len() + v.misses.len(),
                yes(met)
            );
        }
    }
    for scene in SRAA_RT_SSAA4_SCENES {
        let (Some(rt), Some(ss)) = (find(SRAA_RT, scene), find(SSAA4, scene)) else {
            continue;
        };
        if let (Some(a), Some(e)) = (rt.classes, ss.classes) {
            let mut figures = Vec::new();
            let mut met = true;
            for c in [Class::Silhouette, Class::Crease, Class::Shadow] {
                if let (Some(x), Some(y)) = (a.mean[c.index()], e.mean[c.index()]) {
                    let ratio = x / y;
                    met &= ratio <= SRAA_RT_SSAA4_FACTOR;
                    figures.push(format!("{c} {ratio:.2}x"));
                }
            }
            let _ = writeln!(
                md,
                "| sraa-rt FLIP ≤ {SRAA_RT_SSAA4_FACTOR}x ssaa4's on silhouette, crease and shadow | {b} | {scene} | {} | {} |",
                figures.join(", "),
                yes(met && !figures.is_empty())
            );
        }
        let _ = writeln!(
            md,
            "| sraa-rt faster than ssaa4 | {b} | {scene} ({}x{}) | {:.2} vs {:.2} ms | {} |",
            rt.width,
            rt.height,
            rt.ms_median,
            ss.ms_median,
            yes(rt.ms_median < ss.ms_median)
        );
    }
}

/// The rows of the CTSS quality targets for backend `b` (SDF scenes only).
fn ctss_targets(s: &ReportSummary, b: &str, md: &mut String) {
    use subcone_scene::builtin::{SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};
    let find = |method, scene: &str| row_of(&s.rows, method, b, scene);
    for scene in SDF_SCENES {
        let (Some(r), Some(noaa)) = (find(CTSS, scene), find(NOAA, scene)) else {
            continue;
        };
        let (Some(it), Some(n), Some(a), Some(na)) =
            (r.classes, noaa.classes, r.flip_mean, noaa.flip_mean)
        else {
            continue;
        };
        let (v, flat) = flip_verdict(CTSS, r, noaa);
        let sil = Class::Silhouette.index();
        let silhouettes = match (it.mean[sil], n.mean[sil]) {
            (Some(x), Some(y)) => format!("silhouette {x:.4} vs {y:.4}"),
            _ => "no silhouette pixels".into(),
        };
        let met = v.misses.is_empty() && !v.beats.is_empty() && v.holds_on_flat() && a < na;
        let _ = writeln!(
            md,
            "| ctss beats NoAA on silhouettes, holds on flat, whole FLIP below NoAA's | {b} | {scene} | {silhouettes}, {flat}, whole {a:.4} vs {na:.4} | {} |",
            yes(met)
        );
        if let Some(ss) = find(SSAA4, scene).and_then(|x| x.classes) {
            if let (Some(x), Some(y)) = (it.mean[sil], ss.mean[sil]) {
                let ratio = x / y;
                let _ = writeln!(
                    md,
                    "| ctss silhouette FLIP ≤ {CTSS_SSAA4_FACTOR}x ssaa4's | {b} | {scene} | {x:.4} vs {y:.4} ({ratio:.2}x) | {} |",
                    yes(ratio <= CTSS_SSAA4_FACTOR)
                );
            }
        }
    }
    for scene in STIFF_SCENES.iter().chain(&TRANSPARENT_SCENES) {
        let Some(na) = find(NOAA, scene).and_then(|x| x.flip_mean) else {
            continue;
        };
        let mut worst: Option<(&RowKey, f64)> = None;
        for r in s.rows.iter().filter(|x| {
            x.backend == b
                && x.scene == *scene
                && x.method
                    .method()
                    .is_some_and(|m| m.technique().is_cone_traced() && !m.is_paper())
                && x.flip_mean.is_some()
        }) {
            let ratio = r.flip_mean.unwrap_or(0.0) / na.max(f64::MIN_POSITIVE);
            if worst.is_none_or(|(_, w)| ratio > w) {
                worst = Some((&r.method, ratio));
            }
        }
        if let Some((m, ratio)) = worst {
            let _ = writeln!(
                md,
                "| every CTSS method's whole FLIP ≤ {CTSS_STIFF_FACTOR}x NoAA's | {b} | {scene} | worst {m}: {ratio:.3}x | {} |",
                yes(ratio <= CTSS_STIFF_FACTOR)
            );
        }
    }
}

/// The performance targets, each met or not met, with its figure.
pub fn targets(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "## Performance targets\n");
    let _ = writeln!(
        md,
        "Each target as measured by this run (its sizes and runs; the targets are stated for \
1280x720 on the CTSS scenes and 1024x1024 on `cornell` and Sponza). Ray throughput is \
measured on the CPU backend, on every instruction-set path this machine runs ({}; the \
default is the widest), at each triangle scene's timing size (median of \
the run's timed passes, raw and pipeline on the same path; `cargo bench -p subcone-cpu --bench rays` measures the same passes with criterion; judged only where raw traversal is a bound: on a pass of at least {min} rays, \
16 of raw traversal's rayon tasks, on which the pipeline does not outrun it), \
ns per kernel call on one thread (\"a few ns\" read as ≤ {} ns; `cargo bench --bench kernels` \
has the full set). Time ratios between methods are medians of per-round ratios (the methods of \
a scene are timed in interleaved rounds); a target is judged on them. In brackets: for one scene, \
the smallest and largest per-round ratio; for a mean over scenes, the means of the scenes' smallest \
and of their largest per-round ratios, the range the mean would take were every scene at its \
lowest or its highest round.\n",
        subcone_cpu::isa::Isa::supported()
            .iter()
            .map(|i| i.name())
            .collect::<Vec<_>>()
            .join(", "),
        kernel_timing::FEW_NS,
        min = RAY_THROUGHPUT_MIN_RAYS
    );
    let _ = writeln!(md, "| target | backend | scenes | figure | met |");
    let _ = writeln!(md, "|---|---|---|--:|---|");
    let sdf = ctx.sdf_scenes();
    for b in &ctx.backends {
        for (method, limit) in CTSS_TARGETS {
            let Some(avg) = MeanRatio::of(s.rows.iter().filter(|r| {
                &r.backend == b && r.method == method && sdf.contains(&r.scene.as_str())
            })) else {
                continue;
            };
            // Judged on the medians; a limit inside the range is worth a word.
            let close = match avg.range {
                Some((lo, hi)) if lo <= limit && limit <= hi => ", the limit inside the range",
                _ => "",
            };
            let _ = writeln!(
                md,
                "| {method} ≤ {limit:.2}x NoAA (mean time ratio) | {b} | {} SDF scenes | {}{close} | {} |",
                avg.n,
                avg.show(3, true),
                yes(avg.mean <= limit)
            );
        }
        ctss_targets(s, b, &mut md);
        sraa_targets(s, &sdf, b, &mut md);
        // The SRAA-RT target is the paper's, on triangle scenes.
        for rt in rows_for(&s.rows, SRAA_RT, b)
            .into_iter()
            .filter(|r| !sdf.contains(&r.scene.as_str()))
        {
            let Some(ss) = s
                .rows
                .iter()
                .find(|x| x.method == SSAA16 && &x.backend == b && x.scene == rt.scene)
            else {
                continue;
            };
            // Per round where both were timed in the same rounds; else the
            // ratio of medians.
            let per_round = timing::round_ratios(&rt.round_ms, &ss.round_ms);
            let share = per_round.map_or(rt.ms_median / ss.ms_median, |p| p.median);
            let range = per_round
                .filter(|p| p.min != p.max)
                .map(|p| format!(" (1/{:.2}–1/{:.2})", 1.0 / p.max, 1.0 / p.min))
                .unwrap_or_default();
            let edge = match (rt.edge_flip_mean, ss.edge_flip_mean) {
                (Some(a), Some(e)) if e > 0.0 => Some(a / e),
                _ => None,
            };
            let met = share <= SRAA_RT_TIME_SHARE && edge.is_some_and(|e| e <= SRAA_RT_EDGE_FACTOR);
            let _ = writeln!(
                md,
                "| sraa-rt ≤ 1/6 of ssaa16's time, edge FLIP ≤ {SRAA_RT_EDGE_FACTOR}x ssaa16's | {b} | {} ({}x{}) | 1/{:.2}{range} of the time, edge FLIP {}x | {} |",
                rt.scene,
                rt.width,
                rt.height,
                1.0 / share,
                f(edge, 2),
                yes(met)
            );
        }
    }
    md.push_str(&crate::ao_sweep::target_rows(&s.ao_sweep));
    md.push_str(&crate::hybrid::target_rows(&s.rows, ctx));
    let pct = |x: f64| format!("{:.1}%", 100.0 * x);
    for t in &s.throughput {
        let r = &t.rates;
        let _ = writeln!(
            md,
            "| primary rays ≥ {} of raw traversal | cpu ({}) | {} ({}x{}) | {:.2} of {:.2} Mrays/s ({}) | {} |",
            pct(RAY_THROUGHPUT_SHARE),
            t.isa.name(),
            t.scene,
            t.width,
            t.height,
            r.pipeline_primary / 1e6,
            r.raw_primary / 1e6,
            pct(r.primary_ratio()),
            throughput_judged(r.primary_rays, r.primary_ratio())
                .map_or_else(|why| why, |met| yes(met).to_string())
        );
        if let (Some(p), Some(raw), Some(ratio)) =
            (r.pipeline_shadow, r.raw_shadow, r.shadow_ratio())
        {
            let _ = writeln!(
                md,
                "| shadow rays ≥ {} of raw traversal | cpu ({}) | {} ({} rays) | {:.2} of {:.2} Mrays/s ({}) | {} |",
                pct(RAY_THROUGHPUT_SHARE),
                t.isa.name(),
                t.scene,
                r.shadow_rays,
                p / 1e6,
                raw / 1e6,
                pct(ratio),
                throughput_judged(r.shadow_rays, ratio)
                    .map_or_else(|why| why, |met| yes(met).to_string())
            );
        }
    }
    for k in &s.kernels {
        let Some(target) = k.target_ns else { continue };
        let _ = writeln!(
            md,
            "| {} ≤ {} ns per call | cpu | one thread | {:.2} ns | {} |",
            k.name,
            target,
            k.ns_per_call,
            yes(k.ns_per_call <= target)
        );
    }
    if !s.kernels.is_empty() {
        let _ = writeln!(md, "\nns per call of every timed kernel (one thread, median of {} batches of {} inputs):\n", kernel_timing::BATCHES, kernel_timing::INPUTS);
        let _ = writeln!(md, "| kernel | ns per call |");
        let _ = writeln!(md, "|---|--:|");
        for k in &s.kernels {
            let _ = writeln!(md, "| {} | {:.2} |", k.name, k.ns_per_call);
        }
    }
    md.push_str(&crate::hybrid::raster_throughput(&s.throughput));
    let _ = writeln!(md);
    md
}

/// The block comparing our numbers with the papers' published ones.
pub fn paper_comparison(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "## Against the papers' numbers\n");
    let _ = writeln!(
        md,
        "The papers time GPU implementations; ours are {} wall times, so absolute milliseconds \
do not compare, but the split between passes and the ratios between methods do.\n",
        ctx.backends.join(" and ")
    );
    let _ = writeln!(md, "### SRAA for ray tracing, Table 1 (Sponza)\n");
    let _ = writeln!(
        md,
        "Paper: pass 1 (geometric information, ray tracer) and pass 2 (antialiasing), ms; about \
{SRAA_SPEEDUP_OVER_SSAA16}× faster than 16× SSAA with the GPU hybrid (Fig. 3). Ours: the passes \
`geometry` and `antialiasing` of sraa-rt (`shading` is the one shaded sample per pixel), and \
ssaa16's median time over sraa-rt's.\n"
    );
    let sdf_scene = |name: &str| ctx.scenes.iter().any(|sc| sc.sdf && sc.name == name);
    for b in &ctx.backends {
        let sweep: Vec<&ResultRow> = rows_for(&s.sweep, SRAA_RT, b);
        let (source, rows): (&[ResultRow], Vec<&ResultRow>) = if sweep.is_empty() {
            // Table 1 is about triangle scenes: SDF rows are in `sdf_pick`.
            let rows = rows_for(&s.rows, SRAA_RT, b)
                .into_iter()
                .filter(|r| !sdf_scene(&r.scene))
                .collect();
            (&s.rows, rows)
        } else {
            (&s.sweep, sweep)
        };
        if rows.is_empty() {
            let _ = writeln!(md, "No sraa-rt results on {b}.\n");
            continue;
        }
        let _ = writeln!(
            md,
            "| scene | size | paper pass 1 | paper pass 2 | paper total | ours geometry | ours antialiasing | ours shading | ours sraa-rt | ours ssaa16 / sraa-rt |"
        );
        let _ = writeln!(md, "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|");
        for r in rows {
            let paper = SRAA_TABLE1
                .iter()
                .find(|p| p.0 == r.width && p.0 == r.height);
            let ss = source.iter().find(|x| {
                x.method == SSAA16
                    && x.backend == r.backend
                    && x.scene == r.scene
                    && x.width == r.width
                    && x.height == r.height
            });
            let p = |i: usize| {
                paper
                    .map(|p| format!("{:.0}", [p.1, p.2, p.3][i]))
                    .unwrap_or_else(|| "–".into())
            };
            let _ = writeln!(
                md,
                "| {} ({b}) | {}x{} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r.scene,
                r.width,
                r.height,
                p(0),
                p(1),
                p(2),
                f(r.pass("geometry"), 1),
                f(r.pass("antialiasing"), 1),
                f(r.pass("shading"), 1),
                ms(r.ms_median),
                f(ss.map(|x| x.ms_median / r.ms_median), 2),
            );
        }
        let _ = writeln!(
            md,
            "\nPaper: ssaa16 / SRAA ≈ {SRAA_SPEEDUP_OVER_SSAA16:.0} (GPU hybrid, Fig. 3).\n"
        );
    }
    md.push_str(&crate::hybrid::paper_section(&s.rows, ctx));

    let _ = writeln!(md, "### CTSS, Table 1 (average frame-time ratio to NoAA)\n");
    let sdf = ctx.sdf_scenes();
    if sdf.is_empty() {
        let _ = writeln!(md, "No SDF scene was reported on.\n");
        return md;
    }
    let _ = writeln!(
        md,
        "Ours: the mean over the scenes of each scene's median per-round ratio to NoAA; in brackets \
the means of the scenes' smallest and of their largest per-round ratios.\n"
    );
    for b in &ctx.backends {
        let _ = writeln!(
            md,
            "| method | paper avg ratio | ours avg ratio ({b}, {}) | scenes |",
            sdf.join(", ")
        );
        let _ = writeln!(md, "|---|--:|--:|--:|");
        let mut lines = CTSS_TABLE1
            .iter()
            .map(|(paper, ours, ratio)| (format!("{paper} / {ours}"), Some(*ratio), *ours))
            .collect::<Vec<_>>();
        lines.push((format!("4x SS + CTSS / {SSAA4_CTSS}"), None, SSAA4_CTSS));
        for (name, paper, ours) in lines {
            let avg = MeanRatio::of(s.rows.iter().filter(|r| {
                r.backend == *b && r.method == ours && sdf.contains(&r.scene.as_str())
            }));
            let _ = writeln!(
                md,
                "| {name} | {} | {} | {} |",
                f(paper, 2),
                avg.map_or_else(|| "–".into(), |a| a.show(2, false)),
                avg.map_or(0, |a| a.n)
            );
        }
        let _ = writeln!(md);
    }
    md
}

/// SRAA-RT (sphere-traced samples) against CTSS on the SDF scenes: error and
/// time side by side, and which of the two are on each scene's Pareto fronts.
pub fn sdf_pick(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    let sdf = ctx.sdf_scenes();
    if sdf.is_empty() {
        return md;
    }
    let _ = writeln!(
        md,
        "## SRAA-RT or CTSS on SDF content
"
    );
    let _ = writeln!(
        md,
        "SRAA-RT here takes its one shaded sample and four geometric subsamples per pixel by \
sphere tracing; CTSS cone traces one ray per pixel. Error: mean FLIP against the reference (whole \
image and edge mask); time: median ms at the timing size. *On the front* names which of the two \
are on the scene's Pareto front under FLIP and under SSIM; which method to use at each cost, \
these two and every other, is *The answer* at the top, computed from the fronts.\n"
    );
    let answer = crate::answer::Answer::of(&s.rows, &ctx.scenes);
    for b in &ctx.backends {
        let find = |scene: &str, method| row_of(&s.rows, method, b, scene);
        let mut lines = Vec::new();
        for sc in &sdf {
            let (Some(rt), Some(ct)) = (find(sc, SRAA_RT), find(sc, CTSS)) else {
                continue;
            };
            if rt.flip_mean.is_none() || ct.flip_mean.is_none() {
                continue;
            }
            let on_front = |metric: Metric| {
                let on: Vec<String> = [rt, ct]
                    .iter()
                    .map(|r| &r.method)
                    .filter(|m| {
                        answer
                            .front(sc, b, metric)
                            .is_some_and(|f| f.points.iter().any(|p| p.method == **m))
                    })
                    .map(RowKey::to_string)
                    .collect();
                if on.is_empty() {
                    "neither".to_string()
                } else {
                    on.join(", ")
                }
            };
            let noaa = find(sc, NOAA).and_then(|r| r.flip_mean);
            lines.push(format!(
                "| {sc} | {} | {} | {} | {} | {} | {} | {} | {} / {} |",
                f(noaa, 4),
                f(rt.flip_mean, 4),
                f(ct.flip_mean, 4),
                f(rt.edge_flip_mean, 4),
                f(ct.edge_flip_mean, 4),
                ms(rt.ms_median),
                ms(ct.ms_median),
                on_front(Metric::Flip),
                on_front(Metric::Ssim),
            ));
        }
        if lines.is_empty() {
            let _ = writeln!(md, "No sraa-rt and ctss errors on {b} to compare.\n");
            continue;
        }
        let _ = writeln!(
            md,
            "| scene ({b}) | noaa FLIP | sraa-rt FLIP | ctss FLIP | sraa-rt edge FLIP | ctss edge FLIP | sraa-rt ms | ctss ms | on the front (FLIP / SSIM) |"
        );
        let _ = writeln!(md, "|---|--:|--:|--:|--:|--:|--:|--:|---|");
        for l in &lines {
            let _ = writeln!(md, "{l}");
        }
        let _ = writeln!(md);
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(method: &str, passes: &[(&str, f64)]) -> ResultRow {
        ResultRow {
            scene: crate::key::SceneId::new("s,1"),
            method: crate::key::named(method),
            backend: "cpu".into(),
            width: 4,
            height: 2,
            runs: 3,
            ms_median: 2.5,
            ms_min: 2.0,
            ms_max: 3.0,
            ratio_to_noaa: None,
            ratio_min: None,
            ratio_max: None,
            flip_mean: Some(0.125),
            psnr_db: Some(f64::INFINITY),
            edge_flip_mean: None,
            classes: None,
            ssim_mean: None,
            classes_ssim: None,
            errors_at: Vec::new(),
            samples_per_pixel: 1.0,
            rays_per_pixel: 2.0,
            raster_samples_per_pixel: 0.0,
            buffer_mib: 0.5,
            quality_width: Some(4),
            quality_height: Some(2),
            reference: Some("ssaa64".into()),
            pass_ms: passes.iter().map(|(n, v)| (n.to_string(), *v)).collect(),
            round_ms: Vec::new(),
            post_process: None,
            timed_by: vec![subcone_scene::TimingSource::Cpu],
            image_digest: None,
        }
    }

    fn ratio(mut r: ResultRow, median: f64, range: Option<(f64, f64)>) -> ResultRow {
        r.ratio_to_noaa = Some(median);
        (r.ratio_min, r.ratio_max) = (range.map(|r| r.0), range.map(|r| r.1));
        r
    }

    #[test]
    fn timed_by_names_each_source_once() {
        let noaa = row("noaa", &[]);
        let mut smaa = row("smaa", &[]);
        smaa.post_process = Some("SMAA 1x".into());
        let gpu = subcone_scene::TimingSource::GpuWallClock { why: "software" };
        smaa.timed_by = vec![subcone_scene::TimingSource::Cpu, gpu];
        let mut md = String::new();
        timed_by_lines(&mut md, &[&noaa, &smaa]);
        assert_eq!(
            md,
            format!("Timed by: cpu: CPU wall clock; smaa (cpu), its post-process: {gpu}.\n\n")
        );
        assert_eq!(md.matches("CPU wall clock").count(), 1, "{md}");
        // A post-process timed like its backend adds no entry of its own.
        smaa.timed_by = vec![subcone_scene::TimingSource::Cpu];
        let mut md = String::new();
        timed_by_lines(&mut md, &[&noaa, &smaa]);
        assert_eq!(md, "Timed by: cpu: CPU wall clock.\n\n");
    }

    #[test]
    fn ray_throughput_is_judged_only_where_raw_traversal_is_a_bound() {
        let small = 96 * 64;
        assert!(throughput_judged(small, 0.5)
            .unwrap_err()
            .starts_with("not judged at this size"));
        assert!(throughput_judged(small, 1.1).is_err());
        let big = RAY_THROUGHPUT_MIN_RAYS;
        assert_eq!(throughput_judged(big, 0.8), Ok(true));
        assert_eq!(throughput_judged(big, 0.6), Ok(false));
        assert!(throughput_judged(big, 1.1)
            .unwrap_err()
            .contains("outran raw traversal"));
        assert!(throughput_judged(big, f64::NAN).is_err());
    }

    #[test]
    fn every_class_has_its_three_columns() {
        for c in CLASSES {
            for col in [format!("flip_{c}"), format!("px_{c}"), format!("dssim_{c}")] {
                assert!(BASE_COLUMNS.contains(&col.as_str()), "no column {col}");
            }
        }
    }

    #[test]
    fn csv_columns_are_stable_and_passes_sorted() {
        let rows = vec![
            row("noaa", &[("shading", 1.0)]),
            ratio(
                row("sraa", &[("shading", 1.0), ("geometry", 0.5)]),
                1.2,
                Some((1.1, 1.3)),
            ),
        ];
        let text = csv(&rows);
        let mut lines = text.lines();
        let header = lines.next().unwrap();
        assert!(header.starts_with("scene,method,backend,width,height,runs,ms_median"));
        assert!(header.contains(",dssim_flat,post_process,timed_by,offsets,flip_min,"));
        assert!(header.ends_with(
            ",dssim_near_edge_min,dssim_near_edge_max,raster_samples_per_pixel,ms_geometry,ms_shading"
        ));
        assert!(header.contains(",ms_max,ratio_to_noaa,ratio_min,ratio_max,flip_mean,"));
        let first = lines.next().unwrap();
        // No ratios, no SSIM, no classes (18 empty columns), no post-process
        // adapter: 19 empty fields between the reference and the timing
        // source; no offsets; no rasterised sample (a traced method); then
        // no geometry pass, and the shading pass.
        let expected = format!(
            "\"s,1\",noaa,cpu,4,2,3,2.5,2,3,,,,0.125,inf,,,1,2,0.5,4,2,ssaa64{}cpu{}0,,1",
            ",".repeat(20),
            ",".repeat(BASE_COLUMNS.len() - 42)
        );
        assert_eq!(first, expected);
        let second = lines.next().unwrap();
        assert!(second.contains(",2.5,2,3,1.2,1.1,1.3,0.125,"), "{second}");
    }

    #[test]
    fn json_has_nulls_for_missing_and_infinite() {
        let (cols, vals) = json_rows(&[row("noaa", &[("shading", 1.0)])]);
        assert_eq!(cols.last().unwrap(), "ms_shading");
        assert_eq!(vals[0]["psnr_db"], Value::Null);
        assert_eq!(vals[0]["edge_flip_mean"], Value::Null);
        assert_eq!(vals[0]["flip_mean"], json!(0.125));
        assert_eq!(vals[0]["ratio_min"], Value::Null);
        let (_, vals) = json_rows(&[ratio(row("ctss", &[]), 1.2, Some((1.1, 1.3)))]);
        assert_eq!(
            (&vals[0]["ratio_min"], &vals[0]["ratio_max"]),
            (&json!(1.1), &json!(1.3))
        );
    }

    /// A row measured at four offsets: per offset `k`, FLIP `flip[k]` on
    /// silhouette, `flat[k]` on flat and `band[k]` on the near-edge band,
    /// and 1 − SSIM `dssim[k]` on silhouette and flat; 100 pixels in each
    /// (300 flat).
    fn measured(
        method: &str,
        flip: [f64; 4],
        flat: [f64; 4],
        band: [f64; 4],
        dssim: [f64; 4],
    ) -> ResultRow {
        let mut r = row(method, &[]);
        r.scene = crate::key::SceneId::new("s");
        let err = |sil: f64, fl: f64, ne: Option<f64>| {
            let mut e = classes::ClassError::default();
            e.mean[Class::Silhouette.index()] = Some(sil);
            e.px[Class::Silhouette.index()] = 100;
            e.mean[Class::Flat.index()] = Some(fl);
            e.px[Class::Flat.index()] = 300;
            (e.near_edge, e.near_edge_px) = (ne, 100);
            e
        };
        r.errors_at = (0..4)
            .map(|k| crate::OffsetError {
                offset: crate::offsets::ERROR_OFFSETS[k],
                flip: flip[k],
                ssim: 1.0 - dssim[k],
                classes: err(flip[k], flat[k], Some(band[k])),
                classes_ssim: err(dssim[k], dssim[k], None),
            })
            .collect();
        r.settle_offsets();
        r
    }

    #[test]
    fn flip_and_ssim_disagreements_get_a_computed_cause() {
        let noaa = measured("noaa", [0.2; 4], [0.05; 4], [0.1; 4], [0.1; 4]);
        // fxaa-like: FLIP loses on silhouette at every offset, SSIM beats;
        // flat holds under both; the band carries most of the excess.
        let fx = measured(
            "fxaa",
            [0.24, 0.25, 0.23, 0.24],
            [0.0505, 0.0505, 0.0505, 0.0505],
            [0.13, 0.14, 0.13, 0.12],
            [0.08; 4],
        );
        let rows = [&noaa, &fx];
        let md = class_section("s", &rows);
        assert!(
            md.contains("silhouette: loses by 1.2× under FLIP (0.2400 vs 0.2000, 1.15–1.25× over 4 offsets) but beats under SSIM"),
            "{md}"
        );
        assert!(md.contains("Cause: not noise: each metric gives the same call at each of the 4 offsets (FLIP ratio to NoAA 1.15–1.25×, SSIM 0.80–0.80×)"), "{md}");
        // Band: 0.03 × 100 per offset; flat: 0.0005 × 300: 12 / 12.6.
        let share = near_edge_share(&fx, &noaa).unwrap();
        assert!((share.share().unwrap() - 12.0 / 12.6).abs() < 1e-9);
        assert!((share.px_share() - 0.25).abs() < 1e-12);
        assert!(
            md.contains("Near-edge band: 95 % of the method's FLIP excess"),
            "{md}"
        );
        assert!(md.contains("which holds 25 % of those pixels"), "{md}");
        // Noise: FLIP wins at two offsets and not at the others.
        let noisy = measured(
            "fxaa",
            [0.18, 0.2, 0.18, 0.2],
            [0.05; 4],
            [0.1; 4],
            [0.08; 4],
        );
        let md = class_section("s", &[&noaa, &noisy]);
        assert!(
            md.contains("silhouette: tie (within noise) under FLIP"),
            "{md}"
        );
        assert!(md.contains("Cause: noise: the per-offset ratio to NoAA, FLIP's (0.90–1.00×), does not stay on one side"), "{md}");
        // Agreement: no disagreement section.
        let same = measured("fxaa", [0.1; 4], [0.05; 4], [0.1; 4], [0.05; 4]);
        let md = class_section("s", &[&noaa, &same]);
        assert!(md.contains("FLIP and SSIM agree on every verdict"), "{md}");
        // The table shows the spread and the band.
        assert!(md.contains("near edge (100 px)"), "{md}");
        // No excess: said so, not a share.
        let better = measured("fxaa", [0.1; 4], [0.04; 4], [0.05; 4], [0.05; 4]);
        let b = near_edge_share(&better, &noaa).unwrap();
        assert_eq!(b.share(), None);
        assert!(b.sentence().contains("is -20.00 on the near-edge band (25 % of the pixels in no class) and -12.00 on flat"), "{}", b.sentence());
    }

    #[test]
    fn glance_cells_count_each_outcome() {
        let noaa = measured("noaa", [0.2; 4], [0.05; 4], [0.1; 4], [0.1; 4]);
        let it = measured("sraa", [0.1, 0.2, 0.1, 0.1], [0.06; 4], [0.1; 4], [0.05; 4]);
        let v = &verdicts(&[&noaa, &it], Metric::Flip)[0].1;
        // sraa claims silhouette and crease; crease has no pixels.
        assert_eq!(glance_cell(v), "0/1 · 1 noise · **loses 1.2×**");
        let v = &verdicts(&[&noaa, &it], Metric::Ssim)[0].1;
        assert_eq!(glance_cell(v), "1/1 · holds");
    }

    #[test]
    fn spread_columns_hold_the_offsets_range() {
        let r = measured(
            "noaa",
            [0.2, 0.3, 0.25, 0.2],
            [0.05; 4],
            [0.1, 0.2, 0.1, 0.1],
            [0.1; 4],
        );
        let (cols, vals) = json_rows(std::slice::from_ref(&r));
        assert!(cols.iter().any(|c| c == "flip_near_edge_max"));
        let v = &vals[0];
        assert_eq!(v["offsets"], json!(4));
        assert_eq!((&v["flip_min"], &v["flip_max"]), (&json!(0.2), &json!(0.3)));
        assert!((v["flip_mean"].as_f64().unwrap() - 0.2375).abs() < 1e-12);
        assert_eq!(v["flip_silhouette_max"], json!(0.3));
        assert_eq!(v["flip_near_edge_max"], json!(0.2));
        assert_eq!(v["px_near_edge"], json!(100));
        assert_eq!(v["dssim_near_edge"], Value::Null);
        assert_eq!(
            with_range(Some(0.2375), r.range(Metric::Flip)),
            "0.2375 (0.2000–0.3000)"
        );
    }

    #[test]
    fn ratio_cells_show_the_range_where_there_is_one() {
        let r = ratio(row("ctss", &[]), 1.184, Some((1.151, 1.2149)));
        assert_eq!(ratio_cell(&r), "1.18 (1.15–1.21)");
        // A ratio of medians (the smaa row), NoAA itself: no range.
        assert_eq!(ratio_cell(&ratio(row("smaa", &[]), 1.5, None)), "1.50");
        assert_eq!(
            ratio_cell(&ratio(row("noaa", &[]), 1.0, Some((1.0, 1.0)))),
            "1.00"
        );
        assert_eq!(ratio_cell(&row("noaa", &[])), "–");
    }

    #[test]
    fn mean_ratio_over_scenes_averages_the_ranges() {
        let rows = [
            ratio(row("ctss", &[]), 1.2, Some((1.1, 1.3))),
            ratio(row("ctss", &[]), 1.0, Some((0.9, 1.5))),
            row("ctss", &[]),
        ];
        let m = MeanRatio::of(&rows).unwrap();
        assert_eq!(m.n, 2, "a row without a ratio is not averaged");
        assert!((m.mean - 1.1).abs() < 1e-12);
        let (lo, hi) = m.range.unwrap();
        assert!((lo - 1.0).abs() < 1e-12 && (hi - 1.4).abs() < 1e-12);
        assert_eq!(m.show(3, true), "1.100x (1.000–1.400x)");
        // One row without a range: the mean has none.
        let mixed = [rows[0].clone(), ratio(row("ctss", &[]), 1.5, None)];
        let m = MeanRatio::of(&mixed).unwrap();
        assert_eq!((m.range, m.show(2, false)), (None, "1.35".to_string()));
        assert_eq!(MeanRatio::of(&rows[2..]), None);
    }
}
