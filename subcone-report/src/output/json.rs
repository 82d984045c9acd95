//! `results.json`: the run, the columns, the rows (each with its error at
//! every camera offset), the sweeps, the crops and the answer.

use serde_json::{json, Map, Value};

use super::columns::{pass_columns, row_cells, Cell, BASE_COLUMNS};
use crate::classes::CLASSES;
use crate::context::{cpu_model, Context};
use crate::reference::code_version;
use crate::{Mode, ReportSummary, ResultRow};

/// The columns of `rows` and each row as an object of them, as in
/// `results.json`.
pub(crate) fn json_rows(rows: &[ResultRow]) -> (Vec<String>, Vec<Value>) {
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
            "interpolated_ao_range": c.interpolated_range.map(|r| [r.0, r.1]),
            "sraa_rt_ms_range": c.first_faster.map(|f| [f.sraa_rt_ms_range.0, f.sraa_rt_ms_range.1]),
            "ssaa4_ms_range": c.first_faster.map(|f| [f.ssaa4_ms_range.0, f.ssaa4_ms_range.1]),
            "sraa_rt_flip": c.first_faster.and_then(|f| f.sraa_rt_flip),
            "ssaa4_flip": c.first_faster.and_then(|f| f.ssaa4_flip),
        })).collect::<Vec<_>>(),
        "ao_sweep": s.ao_sweep.rows.iter().map(|r| json!({
            "scene": r.scene, "method": r.method.to_string(), "backend": r.backend, "ao_rays": r.ao,
            "pair": crate::ao_sweep::Pair::of(r.method).name(),
            "ms_median": r.ms_median, "ms_min": r.ms_range.0, "ms_max": r.ms_range.1,
            "rays_per_pixel": r.rays_per_pixel,
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
/// `dssim_<class>` and `px_<class>` (FLIP's flat and band; SSIM's, whose
/// band is narrower, are `px_ssim_flat` and `px_ssim_near_edge`), so that
/// every verdict can be derived again from the file.
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
                // SSIM's flat and band are its own (its window's reach).
                m.insert(
                    "px_ssim_flat".into(),
                    json!(e.classes_ssim.px[crate::classes::Class::Flat.index()]),
                );
                m.insert(
                    "px_ssim_near_edge".into(),
                    json!(e.classes_ssim.near_edge_px),
                );
                Value::Object(m)
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::classes::Metric;
    use crate::output::test_rows::{measured, ratio, row};
    use crate::output::with_range;

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
}
