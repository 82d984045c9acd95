//! `report.md`: the header and the answer, the rules, a section per scene,
//! what was skipped or failed, then the comparisons, sweeps and targets.

use std::fmt::Write as _;

use super::paper_comparison::{paper_comparison, sdf_pick};
use super::targets::targets;
use super::verdicts::{class_section, rules, verdict_summary};
use super::{f, with_range};
use crate::classes::Metric;
use crate::context::{cpu_model, ms, Context, SceneInfo};
use crate::reference::code_version;
use crate::{crops, file_safe, Mode, ReportSummary, ResultRow};

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
        let left_out = scene_table(md, &rows);
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
    crop_lines(md, s, sc);
}

/// The scene's table: a row per method and backend, with its marks; the
/// rows left out of the fronts, returned.
fn scene_table(md: &mut String, rows: &[&ResultRow]) -> Vec<crate::answer::Excluded> {
    let _ = writeln!(
        md,
        "| method | backend | median ms | min–max ms | × NoAA | FLIP | SSIM | PSNR dB | edge FLIP | spp | rays/px | buffers MiB |"
    );
    let _ = writeln!(md, "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
    let left_out = crate::answer::exclusions(rows);
    for r in rows {
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
    left_out
}

/// The scene's crop lines, when its crops were written.
fn crop_lines(md: &mut String, s: &ReportSummary, sc: &SceneInfo) {
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

/// The report's title and the run in one paragraph: mode, backends,
/// rounds, code, machine, reference and AO.
fn run_line(md: &mut String, ctx: &Context) {
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
}

/// The Skipped section (every combination not rendered, grouped by method,
/// backend and reason) and the Failures section when any render failed.
fn skipped_and_failed(md: &mut String, s: &ReportSummary) {
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
}

/// `report.md`.
pub fn markdown(s: &ReportSummary, ctx: &Context) -> String {
    let mut md = String::new();
    run_line(&mut md, ctx);
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

    skipped_and_failed(&mut md, s);

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_rows::{ratio, row};

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
}
