//! The two Rust steps of `scripts/gpu-check`.
//!
//! - `gpu_check adapter FILE`: open the adapter the wgpu backend opens,
//!   print it, its limits and how its passes are timed, and write them as
//!   JSON to `FILE`.
//! - `gpu_check passes FILE --sizes WxH,WxH --runs N`: time each pass of
//!   `subcone-passes` alone at each size ([`passes`]) and write the times
//!   as JSON to `FILE`.
//! - `gpu_check summary --out DIR --size WxH --runs N --seconds S`: read what
//!   the script's steps wrote into `DIR` (`adapter.json`, `steps.tsv`, the
//!   timing report's `timing/results.json`, `passes.json`) and write
//!   `summary.md` and `summary.json` beside them. Every figure comes from
//!   those files.
//!
//! They are one example of the root package, run in the test profile, so
//! that after `cargo test --workspace` the script builds almost nothing
//! new (a release example would build every dev-dependency in release; a
//! `-p subcone-wgpu` one would resolve wgpu's features anew).

use std::path::{Path, PathBuf};

mod passes;

use anyhow::{bail, Context, Result};
use serde_json::{json, Value};

/// The adapter as JSON, printing it on the way.
fn adapter(path: &Path) -> Result<()> {
    let ctx = subcone_wgpu::GpuContext::new().map_err(|e| anyhow::anyhow!("{e}"))?;
    let l = ctx.device.limits();
    let has = |f: wgpu::Features| ctx.device.features().contains(f);
    let source = ctx.timing_source();
    let value = json!({
        "adapter": ctx.info.name,
        "driver": ctx.info.driver,
        "driver_info": ctx.info.driver_info,
        "api": format!("{:?}", ctx.info.backend),
        "device_type": format!("{:?}", ctx.info.device_type),
        "timestamp_query": has(wgpu::Features::TIMESTAMP_QUERY),
        "timestamp_query_inside_encoders": has(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS),
        "timestamps_trusted": ctx.timestamps,
        "timed_by": source.tag(),
        "timed_by_text": source.to_string(),
        "limits": {
            "max_texture_dimension_2d": l.max_texture_dimension_2d,
            "max_storage_buffer_binding_size": l.max_storage_buffer_binding_size,
            "max_buffer_size": l.max_buffer_size,
            "max_storage_buffers_per_shader_stage": l.max_storage_buffers_per_shader_stage,
            "max_compute_invocations_per_workgroup": l.max_compute_invocations_per_workgroup,
        },
    });
    println!("{}", serde_json::to_string_pretty(&value)?);
    std::fs::write(path, serde_json::to_string_pretty(&value)? + "\n")
        .with_context(|| format!("writing {}", path.display()))
}

/// One step of the script: a line of `steps.tsv`.
struct Step {
    name: String,
    seconds: u64,
    exit: i32,
    log: String,
    /// Cargo's last `test result:` line, for the test steps.
    result: String,
}

fn steps(dir: &Path) -> Result<Vec<Step>> {
    let text = std::fs::read_to_string(dir.join("steps.tsv"))
        .with_context(|| format!("reading {}", dir.join("steps.tsv").display()))?;
    text.lines()
        .filter(|l| !l.is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            if f.len() < 4 {
                bail!("steps.tsv: malformed line {l:?}");
            }
            Ok(Step {
                name: f[0].into(),
                seconds: f[1].parse().context("steps.tsv: seconds")?,
                exit: f[2].parse().context("steps.tsv: exit status")?,
                log: f[3].into(),
                result: f.get(4).unwrap_or(&"").trim().to_string(),
            })
        })
        .collect()
}

/// `passed` and `failed` counts summed over the `test result:` lines of a
/// step (`None` for a step that printed none).
fn counts(result: &str) -> (Option<u64>, Option<u64>) {
    let lines: Vec<&str> = result.split("test result:").skip(1).collect();
    if lines.is_empty() {
        return (None, None);
    }
    let sum = |word: &str| -> u64 {
        lines
            .iter()
            .map(|l| {
                let words: Vec<&str> = l.split([' ', ';']).filter(|w| !w.is_empty()).collect();
                words
                    .windows(2)
                    .find(|w| w[1] == word)
                    .and_then(|w| w[0].parse::<u64>().ok())
                    .unwrap_or(0)
            })
            .sum()
    };
    (Some(sum("passed")), Some(sum("failed")))
}

/// `WxH` as a size.
fn parse_size(s: &str) -> Result<(u32, u32)> {
    let (w, h) = s
        .split_once('x')
        .with_context(|| format!("size {s:?}: expected WxH"))?;
    Ok((
        w.parse().with_context(|| format!("width of {s:?}"))?,
        h.parse().with_context(|| format!("height of {s:?}"))?,
    ))
}

fn read_json(path: &Path) -> Option<Value> {
    let text = std::fs::read_to_string(path).ok()?;
    serde_json::from_str(&text).ok()
}

fn cell(v: &Value, digits: usize) -> String {
    v.as_f64()
        .map_or_else(|| "–".to_string(), |x| format!("{x:.digits$}"))
}

struct Args {
    out: PathBuf,
    size: String,
    runs: u32,
    seconds: u64,
}

fn summary_args(mut it: impl Iterator<Item = String>) -> Result<Args> {
    let (mut out, mut size, mut runs, mut seconds) = (None, None, None, None);
    while let Some(flag) = it.next() {
        let value = it.next().with_context(|| format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--out" => out = Some(PathBuf::from(value)),
            "--size" => size = Some(value),
            "--runs" => runs = Some(value.parse().context("--runs")?),
            "--seconds" => seconds = Some(value.parse().context("--seconds")?),
            _ => bail!("unknown argument {flag}"),
        }
    }
    Ok(Args {
        out: out.context("--out is required")?,
        size: size.context("--size is required")?,
        runs: runs.context("--runs is required")?,
        seconds: seconds.context("--seconds is required")?,
    })
}

fn main() -> Result<()> {
    let mut it = std::env::args().skip(1);
    match it.next().as_deref() {
        Some("adapter") => {
            let path = it.next().context("usage: gpu_check adapter FILE")?;
            adapter(Path::new(&path))
        }
        Some("passes") => {
            let usage = "usage: gpu_check passes FILE --sizes WxH[,WxH...] --runs N";
            let path = it.next().context(usage)?;
            let (mut sizes, mut runs) = (None, None);
            while let Some(flag) = it.next() {
                let value = it.next().with_context(|| format!("{flag} needs a value"))?;
                match flag.as_str() {
                    "--sizes" => {
                        sizes = Some(
                            value
                                .split(',')
                                .map(parse_size)
                                .collect::<Result<Vec<_>>>()?,
                        )
                    }
                    "--runs" => runs = Some(value.parse().context("--runs")?),
                    _ => bail!("unknown argument {flag}: {usage}"),
                }
            }
            passes::run(
                Path::new(&path),
                &sizes.context(usage)?,
                runs.context(usage)?,
            )
        }
        Some("summary") => summary(summary_args(it)?),
        _ => bail!("usage: gpu_check adapter FILE | gpu_check passes FILE --sizes WxH,WxH --runs N | gpu_check summary --out DIR --size WxH --runs N --seconds S"),
    }
}

fn summary(a: Args) -> Result<()> {
    let steps = steps(&a.out)?;
    let adapter = read_json(&a.out.join("adapter.json"));
    let timing = read_json(&a.out.join("timing").join("results.json"));
    let rows: Vec<Value> = timing
        .as_ref()
        .and_then(|t| t["results"].as_array().cloned())
        .unwrap_or_default();
    let passes = read_json(&a.out.join("passes.json"));
    let mut md = String::from("# GPU check\n\n");
    let software = adapter
        .as_ref()
        .is_some_and(|ad| ad["device_type"].as_str() == Some("Cpu"));
    if software {
        md += &format!(
            "**The adapter is software ({}): it runs the shaders on this machine's CPU, so every \
             time below says how fast that CPU runs them, nothing about any GPU.** The test steps \
             still check that the passes and methods are right.\n\n",
            adapter
                .as_ref()
                .and_then(|ad| ad["adapter"].as_str())
                .unwrap_or("?")
        );
    }
    md += "Written by `scripts/gpu-check`";
    md += &format!(
        " (`--size {} --runs {}`) in {} s.\n\n",
        a.size, a.runs, a.seconds
    );
    md += "## Adapter\n\n";
    match &adapter {
        Some(ad) => {
            md += &format!(
                "- {} ({}, {} {}), {}\n",
                ad["adapter"].as_str().unwrap_or("?"),
                ad["api"].as_str().unwrap_or("?"),
                ad["driver"].as_str().unwrap_or("?"),
                ad["driver_info"].as_str().unwrap_or("?"),
                ad["device_type"].as_str().unwrap_or("?"),
            );
            md += &format!(
                "- timestamp queries: {}, inside encoders: {}; timestamps trusted: {}\n",
                ad["timestamp_query"],
                ad["timestamp_query_inside_encoders"],
                ad["timestamps_trusted"]
            );
            md += &format!(
                "- passes timed by: {}\n",
                ad["timed_by_text"].as_str().unwrap_or("?")
            );
            let l = &ad["limits"];
            md += &format!(
                "- limits: 2D texture {}, storage binding {} bytes, buffer {} bytes, {} storage buffers per stage\n\n",
                l["max_texture_dimension_2d"],
                l["max_storage_buffer_binding_size"],
                l["max_buffer_size"],
                l["max_storage_buffers_per_shader_stage"]
            );
        }
        None => md += "No adapter: see `adapter.log`.\n\n",
    }
    md += "## Steps\n\n| step | result | passed | failed | seconds | log |\n|---|---|--:|--:|--:|---|\n";
    for s in &steps {
        let (passed, failed) = counts(&s.result);
        let show = |v: Option<u64>| v.map_or("–".to_string(), |v| v.to_string());
        md += &format!(
            "| {} | {} | {} | {} | {} | `{}` |\n",
            s.name,
            if s.exit == 0 {
                "ok".to_string()
            } else {
                format!("FAILED (exit {})", s.exit)
            },
            show(passed),
            show(failed),
            s.seconds,
            s.log
        );
    }
    md += "\n## Passes alone\n\n";
    let pass_rows: Vec<Value> = passes
        .as_ref()
        .and_then(|p| p["rows"].as_array().cloned())
        .unwrap_or_default();
    if pass_rows.is_empty() {
        md += "No pass was timed: see `passes.log`.\n";
    } else {
        md += &format!(
            "Median ms of each `subcone-passes` pass encoded and submitted alone (`gpu_check passes`), \
             {} runs after a warm-up, timed as the wgpu backend times its passes.\n\n",
            pass_rows[0]["runs"],
        );
        md += "| pass | size | ms | timed by |\n|---|---|--:|---|\n";
        for r in &pass_rows {
            md += &format!(
                "| {} | {}x{} | {} | {} |\n",
                r["pass"].as_str().unwrap_or("?"),
                r["width"],
                r["height"],
                cell(&r["ms_median"], 1),
                r["timed_by"].as_str().unwrap_or("?")
            );
        }
    }
    md += "\n## Timing\n\n";
    let mut scenes: Vec<String> = Vec::new();
    let mut methods: Vec<String> = Vec::new();
    for r in &rows {
        for (list, key) in [(&mut scenes, "scene"), (&mut methods, "method")] {
            let v = r[key].as_str().unwrap_or("?").to_string();
            if !list.contains(&v) {
                list.push(v);
            }
        }
    }
    if rows.is_empty() {
        md += "The timing report wrote no rows: see `timing.log`.\n";
    } else {
        md += "Median ms of `Backend::render` (and × NoAA in the same rounds), wgpu backend; \
               `–` where the method does not apply to the scene.\n\n";
        md += &format!("| method | {} |\n", scenes.join(" | "));
        md += &format!("|---|{}\n", "--:|".repeat(scenes.len()));
        for m in &methods {
            md += &format!("| {m} |");
            for sc in &scenes {
                match rows
                    .iter()
                    .find(|r| r["scene"] == **sc && r["method"] == **m)
                {
                    Some(r) => {
                        md += &format!(
                            " {} ({}×) |",
                            cell(&r["ms_median"], 1),
                            cell(&r["ratio_to_noaa"], 2)
                        )
                    }
                    None => md += " – |",
                }
            }
            md += "\n";
        }
        let mut timed_by: Vec<&str> = rows.iter().filter_map(|r| r["timed_by"].as_str()).collect();
        timed_by.sort_unstable();
        timed_by.dedup();
        md += &format!(
            "\nTimed by: {} (per pass, in `timing/results.csv`; the full report is `timing/report.md`).\n",
            timed_by.join(", ")
        );
        let skipped: Vec<String> = timing
            .as_ref()
            .and_then(|t| t["skipped"].as_array().cloned())
            .unwrap_or_default()
            .iter()
            .map(|k| {
                format!(
                    "{} on {}: {}",
                    k["method"].as_str().unwrap_or("?"),
                    k["scene"].as_str().unwrap_or("?"),
                    k["reason"].as_str().unwrap_or("?")
                )
            })
            .collect();
        if !skipped.is_empty() {
            md += "\nNot timed (the report's *Skipped*):\n\n";
            for k in skipped {
                md += &format!("- {k}\n");
            }
        }
    }
    let summary = json!({
        "size": a.size,
        "runs": a.runs,
        "seconds": a.seconds,
        "adapter": adapter,
        "steps": steps.iter().map(|s| {
            let (passed, failed) = counts(&s.result);
            json!({"name": s.name, "seconds": s.seconds, "exit": s.exit, "log": s.log,
                   "passed": passed, "failed": failed})
        }).collect::<Vec<_>>(),
        "timing": rows.iter().map(|r| json!({
            "scene": r["scene"], "method": r["method"], "backend": r["backend"],
            "width": r["width"], "height": r["height"], "ms_median": r["ms_median"],
            "ratio_to_noaa": r["ratio_to_noaa"], "timed_by": r["timed_by"],
        })).collect::<Vec<_>>(),
        "skipped": timing.as_ref().map_or(Value::Null, |t| t["skipped"].clone()),
        "software_adapter": software,
        "passes": pass_rows.iter().map(|r| json!({
            "pass": r["pass"], "width": r["width"], "height": r["height"],
            "ms_median": r["ms_median"], "timed_by": r["timed_by"],
        })).collect::<Vec<_>>(),
    });
    std::fs::write(a.out.join("summary.md"), md)?;
    std::fs::write(
        a.out.join("summary.json"),
        serde_json::to_string_pretty(&summary)? + "\n",
    )?;
    if steps.iter().any(|s| s.exit != 0) {
        bail!("a step failed: see the table in summary.md");
    }
    Ok(())
}
