//! "Where SRAA pays" (`report --sraa-sweep`): a shading-cost axis.
//!
//! The built-in scenes shade cheaply, so supersampling's extra shading
//! costs little and SRAA's geometry-only subsamples cannot pay for their
//! reconstruction. Ambient occlusion (`RenderSettings::ao_rays`, the fixed
//! directions of `subcone_kernels::ao`) makes shading as expensive as asked:
//! `ssaa4` casts the AO rays at four samples per pixel, `sraa-rt` at its one
//! shaded sample. The section sweeps [`AO_SWEEP`] on [`AO_SWEEP_SCENES`] at
//! [`AO_SWEEP_SIZE`], times two triples of methods ([`Pair`]): the traced
//! `noaa`, `ssaa4` and `sraa-rt`, and their `-hybrid` twins, whose primary
//! samples find their triangles by rasterisation (SRAA §3.1 and §4.2: the
//! way the paper runs SRAA; AO, shadow and reflection rays stay rays). It
//! measures their FLIP on the silhouette, crease and shadow pixels (the
//! report's edge classes) against a reference rendered with the same AO,
//! and sets the ray-count ratio `ssaa4 / sraa-rt` beside the measured time
//! ratio, and per pair the crossover ([`crossover`]): the fewest AO rays at
//! which `sraa-rt` takes less time than `ssaa4` (hybrid against hybrid,
//! traced against traced). A backend that refuses a method
//! ([`Backend::supports`](subcone_scene::Backend::supports): the wgpu
//! backend has no rasteriser) skips it, listed in the section.
//!
//! Two sizes of it ([`SweepSpec`]): the default report runs
//! [`SweepSpec::default_report`] (atrium, AO 0, 1, 4 and 16, its AO rows
//! judged against a smaller reference so that the section stays short);
//! `--sraa-sweep` runs [`SweepSpec::full`] (atrium and Sponza, AO 0 to 64,
//! the run's reference). The quick report runs neither.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

pub use crate::ao_crossover::{
    crossover, crossover_sentence, crossovers, equal_quality, hybrid_crossover_judged, ratios,
    AoSweep, AoSweepRow, Crossover, FirstFaster, Pair, Refused, HYBRID_CROSSOVER_AO,
};
use crate::ao_crossover::{find, groups, opt};
use crate::classes::{Class, ClassError};
use crate::named::{SRAA_RT, SSAA4};
use crate::plot::{legend, method_line, save_chart, Chart, FAMILY, PLOT_SIZE};
use crate::timing::Timings;
use crate::{file_safe, render, Failure, Runner, SceneJob};
use subcone_metrics::{self as metrics, Rgb8};
use subcone_scene::{Method, RenderSettings};

/// Ambient-occlusion rays per shaded point swept. AO 1 is there so that a
/// crossover at one ray ([`HYBRID_CROSSOVER_AO`]) can be judged.
pub const AO_SWEEP: [u32; 5] = [0, 1, 4, 16, 64];
/// The scenes swept, when the run has them: the atrium (a paper scene) and
/// Sponza (add `--scene sponza`; read from `$SUBCONE_DATA_DIR`).
pub const AO_SWEEP_SCENES: [&str; 2] = ["atrium", "sponza"];
/// The methods swept: each [`Pair`]'s NoAA, SSAA4 and SRAA-RT, traced
/// first.
pub fn sweep_methods() -> Vec<Method> {
    Pair::ALL.iter().flat_map(|p| p.methods()).collect()
}

/// Timing and error size of the sweep.
pub const AO_SWEEP_SIZE: (u32, u32) = (512, 512);
/// The classes whose pooled FLIP the sweep reports: those an antialiasing
/// method of geometry and shadows claims.
pub const AO_SWEEP_CLASSES: [Class; 3] = [Class::Silhouette, Class::Crease, Class::Shadow];

/// Target: the measured time ratio `ssaa4 / sraa-rt` at least this share of
/// the ray-count ratio, at [`AO_TIME_SHARE_AT`].
pub const AO_TIME_SHARE: f64 = 0.85;
/// The AO ray counts at which [`AO_TIME_SHARE`] is checked.
pub const AO_TIME_SHARE_AT: [u32; 2] = [16, 64];
/// Target: at [`AO_SPEEDUP_AT`] rays, `sraa-rt` at least this many times
/// faster than `ssaa4`...
pub const AO_SPEEDUP: f64 = 3.0;
/// ... with its silhouette + crease + shadow FLIP at most this factor of
/// `ssaa4`'s.
pub const AO_EDGE_FACTOR: f64 = 1.2;
/// The AO ray count of the speed-up and quality targets.
pub const AO_SPEEDUP_AT: u32 = 64;

/// Which sweep a report runs: its AO ray counts, its scenes and the
/// reference its AO rows are judged against.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepSpec {
    /// AO rays per shaded point, increasing.
    pub aos: Vec<u32>,
    /// The scenes swept, when the run has them.
    pub scenes: Vec<&'static str>,
    /// The reference of the rows with AO (`None`: the run's reference). The
    /// AO 0 row uses the run's reference too, so it shares the main
    /// comparison's cached frame.
    pub ao_reference: Option<Method>,
}

impl SweepSpec {
    /// `--sraa-sweep`: [`AO_SWEEP`] on [`AO_SWEEP_SCENES`], the run's
    /// reference throughout.
    pub fn full() -> Self {
        Self {
            aos: AO_SWEEP.to_vec(),
            scenes: AO_SWEEP_SCENES.to_vec(),
            ao_reference: None,
        }
    }

    /// The default report's: atrium with AO 0, 1, 2, 4 and 16 (1 for
    /// [`HYBRID_CROSSOVER_AO`], 2 to measure near the crossings); the AO rows are judged against SSAA64 (8×8
    /// samples per pixel), not the run's SSAA256, which with AO would take
    /// minutes.
    pub fn default_report() -> Self {
        Self {
            aos: vec![0, HYBRID_CROSSOVER_AO, 2, 4, 16],
            scenes: vec!["atrium"],
            ao_reference: Some(Method::ssaa_grid(8)),
        }
    }
}

/// The mean FLIP over the pixels of `classes` together: each class's mean
/// weighted by its pixel count (the classes are disjoint).
pub fn pooled_flip(k: &ClassError, classes: &[Class]) -> Option<f64> {
    let (mut sum, mut px) = (0.0, 0u64);
    for c in classes {
        if let Some(f) = k.mean[c.index()] {
            sum += f * k.px[c.index()] as f64;
            px += k.px[c.index()];
        }
    }
    (px > 0).then(|| sum / px as f64)
}

/// The section's markdown (empty when not asked for); `reference` is the
/// reference method, `None` in a timing-only run.
pub fn section(sweep: &AoSweep, reference: Option<&str>) -> String {
    let mut md = String::new();
    if !sweep.ran {
        return md;
    }
    let _ = writeln!(md, "## Where SRAA pays\n");
    let names = |p: Pair| p.methods().map(|m| m.to_string()).join(", ");
    let [noaa, ssaa2, ssaa4, sraa_rt] = Pair::Traced.methods();
    let _ = writeln!(
        md,
        "Ambient occlusion as a shading cost: each shaded point casts N any-hit rays over {} of \
the scene's bounding diagonal, in one fixed stratified cosine-weighted set of directions (a \
noise-free function of position and normal), and the ambient term is multiplied by the \
unoccluded fraction (not at mirror hits). {ssaa4} shades 4 points per pixel, {ssaa2} 2 (the 2×2 \
grid's diagonal, so that {sraa_rt} has an SSAA neighbour on either side in error), {sraa_rt} 1. \
Two sets, each compared within itself: *traced* ({}) and *hybrid* ({}), whose primary samples \
(pixel centres, supersamples, SRAA's shaded sample and subsamples) find their triangle by \
rasterisation, as the SRAA paper runs it (§3.1, §4.2), while AO, shadow and reflection rays \
stay rays. At {}x{}{}; *edge FLIP* is the mean FLIP \
over the silhouette, crease and shadow pixels together, *FLIP* the whole image's. *rays* ratio \
is ssaa4's rays per pixel over sraa-rt's, *time* ratio the same for the median time, each within \
the row's pair (the method columns name the traced methods; a *hybrid* row holds their `-hybrid` \
twins). Times are medians, with the fastest and slowest run in the crossover lines.\n",
        subcone_scene::backend::AO_RADIUS_FRACTION,
        names(Pair::Traced),
        names(Pair::Hybrid),
        AO_SWEEP_SIZE.0,
        AO_SWEEP_SIZE.1,
        match (reference, &sweep.ao_reference) {
            (Some(r), Some(ao_r)) => format!(
                " against {r} at N = 0 and {ao_r} rendered with the same N above (a smaller \
reference, so that the section takes seconds, not minutes)"
            ),
            (Some(r), None) => format!(" against {r} rendered with the same N"),
            (None, _) => " (timing only: no errors)".into(),
        },
    );
    for c in crossovers(sweep) {
        let _ = writeln!(md, "{}\n", crossover_sentence(&c));
        let at_equal: Vec<String> = sweep
            .aos
            .iter()
            .filter_map(|&ao| equal_quality(sweep, &c.scene, &c.backend, c.pair, ao))
            .collect();
        if !at_equal.is_empty() {
            let _ = writeln!(
                md,
                "SRAA at equal quality, {} ({}), {}: {}.\n",
                c.scene,
                c.backend,
                c.pair.name(),
                at_equal.join("; ")
            );
        }
    }
    for (scene, why) in &sweep.missing {
        let _ = writeln!(md, "- `{scene}` not swept: {why}");
    }
    for r in &sweep.refused {
        let _ = writeln!(
            md,
            "- {} on {} not swept on `{}`: {}",
            r.method, r.backend, r.scene, r.reason
        );
    }
    if !sweep.missing.is_empty() || !sweep.refused.is_empty() {
        let _ = writeln!(md);
    }
    for (scene, backend) in groups(&sweep.rows) {
        let _ = writeln!(md, "### {scene} ({backend})\n");
        let _ = writeln!(
            md,
            "| AO rays | pair | {noaa} ms | {ssaa2} ms | {ssaa4} ms | {sraa_rt} ms | {noaa} edge FLIP | {ssaa2} edge FLIP | {ssaa4} edge FLIP | {sraa_rt} edge FLIP | {ssaa2} FLIP | {ssaa4} FLIP | {sraa_rt} FLIP | rays ratio | time ratio | time / rays |"
        );
        let _ = writeln!(
            md,
            "|--:|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|"
        );
        for &ao in &sweep.aos {
            for pair in Pair::ALL {
                let get = |m: Method| find(&sweep.rows, &scene, &backend, m, ao);
                let [n, s2, ss, rt] = pair.methods();
                if [n, s2, ss, rt].iter().all(|m| get(*m).is_none()) {
                    continue;
                }
                let ms = |m: Method| get(m).map_or("–".into(), |r| format!("{:.1}", r.ms_median));
                let ef = |m: Method| opt(get(m).and_then(|r| r.edge_flip), 4);
                let wf = |m: Method| opt(get(m).and_then(|r| r.flip_mean), 4);
                let rat = ratios(&sweep.rows, &scene, &backend, pair, ao);
                let _ = writeln!(
                    md,
                    "| {ao} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                    pair.name(),
                    ms(n),
                    ms(s2),
                    ms(ss),
                    ms(rt),
                    ef(n),
                    ef(s2),
                    ef(ss),
                    ef(rt),
                    wf(s2),
                    wf(ss),
                    wf(rt),
                    opt(rat.map(|r| r.0), 2),
                    opt(rat.map(|r| r.1), 2),
                    opt(rat.map(|r| r.1 / r.0), 2),
                );
            }
        }
        let _ = writeln!(
            md,
            "\n![time against AO](plots/{0}_{1}_ao_time.png) ![edge FLIP against AO](plots/{0}_{1}_ao_flip.png)\n",
            file_safe(&scene),
            file_safe(&backend)
        );
    }
    md
}

/// The section's rows of the *Performance targets* table, computed from
/// the sweep's data.
pub fn target_rows(sweep: &AoSweep) -> String {
    let mut md = String::new();
    let yes = |ok: bool| if ok { "met" } else { "**not met**" };
    let traced = Pair::Traced;
    for (scene, backend) in groups(&sweep.rows) {
        for ao in AO_TIME_SHARE_AT {
            if let Some((rays, time)) = ratios(&sweep.rows, &scene, &backend, traced, ao) {
                let share = time / rays;
                let _ = writeln!(
                    md,
                    "| ssaa4/sraa-rt time ratio ≥ {:.0}% of the ray-count ratio at AO {ao} | {backend} | {scene} ({}x{}) | {time:.2} of {rays:.2} ({:.0}%) | {} |",
                    100.0 * AO_TIME_SHARE,
                    AO_SWEEP_SIZE.0,
                    AO_SWEEP_SIZE.1,
                    100.0 * share,
                    yes(share >= AO_TIME_SHARE)
                );
            }
        }
        if let Some((_, time)) = ratios(&sweep.rows, &scene, &backend, traced, AO_SPEEDUP_AT) {
            let _ = writeln!(
                md,
                "| sraa-rt ≥ {AO_SPEEDUP}x faster than ssaa4 at AO {AO_SPEEDUP_AT} | {backend} | {scene} ({}x{}) | {time:.2}x | {} |",
                AO_SWEEP_SIZE.0,
                AO_SWEEP_SIZE.1,
                yes(time >= AO_SPEEDUP)
            );
        }
        let edge = |m: Method| {
            find(&sweep.rows, &scene, &backend, m, AO_SPEEDUP_AT).and_then(|r| r.edge_flip)
        };
        if let (Some(rt), Some(ss)) = (edge(SRAA_RT), edge(SSAA4)) {
            let factor = rt / ss;
            let _ = writeln!(
                md,
                "| sraa-rt silhouette+crease+shadow FLIP ≤ {AO_EDGE_FACTOR}x ssaa4's at AO {AO_SPEEDUP_AT} | {backend} | {scene} ({}x{}) | {rt:.4} vs {ss:.4} ({factor:.2}x) | {} |",
                AO_SWEEP_SIZE.0,
                AO_SWEEP_SIZE.1,
                yes(factor <= AO_EDGE_FACTOR)
            );
        }
    }
    for c in crossovers(sweep).iter().filter(|c| c.pair == Pair::Hybrid) {
        let (rt, ss) = (c.pair.sraa_rt(), c.pair.ssaa4());
        let (figure, met) = hybrid_crossover_judged(c);
        let _ = writeln!(
            md,
            "| hybrid crossover ({rt} faster than {ss}) at ≤ {HYBRID_CROSSOVER_AO} AO ray per shaded point | {} | {} ({}x{}) | {figure} | {} |",
            c.backend,
            c.scene,
            AO_SWEEP_SIZE.0,
            AO_SWEEP_SIZE.1,
            met.map_or_else(|why| why, |ok| yes(ok).to_string())
        );
    }
    md
}

/// A line per method of `value(row)` against the AO ray count.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    y_desc: &str,
    rows: &[&AoSweepRow],
    value: fn(&AoSweepRow) -> Option<f64>,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let pe = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow::anyhow!("AO sweep plot: {e:?}");
    root.fill(&WHITE).map_err(pe)?;
    let ymax = rows
        .iter()
        .filter_map(|r| value(r))
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let xmax = rows.iter().map(|r| r.ao).max().unwrap_or(64).max(1) as f64;
    let size = (PLOT_SIZE.1 / 32) as i32;
    let mut chart = ChartBuilder::on(root)
        .caption(title, (FAMILY, size + 4))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..xmax * 1.05, 0.0..(ymax * 1.15).max(1e-3))
        .map_err(pe)?;
    chart
        .configure_mesh()
        .x_desc("ambient-occlusion rays per shaded point")
        .y_desc(y_desc)
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| {
            if *v >= 10.0 {
                format!("{v:.0}")
            } else {
                format!("{v:.3}")
            }
        })
        .label_style((FAMILY, size - 4))
        .axis_desc_style((FAMILY, size - 2))
        .draw()
        .map_err(pe)?;
    for m in sweep_methods() {
        let mut pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.method == m)
            .filter_map(|r| value(r).filter(|v| v.is_finite()).map(|v| (r.ao as f64, v)))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        if pts.is_empty() {
            continue;
        }
        method_line(&mut chart, &m.to_string(), &pts, 5)?;
    }
    legend(
        &mut chart,
        SeriesLabelPosition::UpperLeft,
        size - 4,
        "AO sweep plot",
    )?;
    root.present().map_err(pe)?;
    Ok(())
}

/// One plot of `value` against the AO ray count.
struct AoChart<'a> {
    title: &'a str,
    y_desc: &'a str,
    rows: &'a [&'a AoSweepRow],
    value: fn(&AoSweepRow) -> Option<f64>,
}

impl Chart for AoChart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        draw(root, self.title, self.y_desc, self.rows, self.value)
    }
}

/// One plot as PNG and SVG in `dir`.
fn save_both(
    dir: &Path,
    stem: &str,
    title: &str,
    y_desc: &str,
    rows: &[&AoSweepRow],
    value: fn(&AoSweepRow) -> Option<f64>,
) -> Result<Vec<PathBuf>> {
    let chart = AoChart {
        title,
        y_desc,
        rows,
        value,
    };
    save_chart(dir, stem, &chart)
}

/// The section's plots, per scene and backend: time, and silhouette +
/// crease + shadow FLIP, of each method against the AO ray count.
pub fn plots(dir: &Path, sweep: &AoSweep) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    if sweep.rows.is_empty() {
        return Ok(out);
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for (scene, backend) in groups(&sweep.rows) {
        let rows: Vec<&AoSweepRow> = sweep
            .rows
            .iter()
            .filter(|r| r.scene == scene && r.backend == backend)
            .collect();
        let stem = format!("{}_{}", file_safe(&scene), file_safe(&backend));
        out.extend(save_both(
            dir,
            &format!("{stem}_ao_time"),
            &format!("{scene} ({backend}): median time against AO rays"),
            "median time per frame (ms)",
            &rows,
            |r| Some(r.ms_median),
        )?);
        out.extend(save_both(
            dir,
            &format!("{stem}_ao_flip"),
            &format!("{scene} ({backend}): silhouette + crease + shadow FLIP"),
            "mean FLIP over silhouette, crease and shadow pixels",
            &rows,
            |r| r.edge_flip,
        )?);
    }
    Ok(out)
}

impl Runner<'_> {
    /// The "Where SRAA pays" sweep over the run's scenes named in
    /// [`AO_SWEEP_SCENES`] (triangle scenes), every backend of the run.
    pub(super) fn ao_sweep(&mut self, jobs: &[SceneJob], spec: &SweepSpec) -> Result<AoSweep> {
        let plan = self.plan;
        let mut sweep = AoSweep {
            ran: true,
            aos: spec.aos.clone(),
            ao_reference: spec.ao_reference.map(|m| m.to_string()),
            ..Default::default()
        };
        let methods: Vec<Method> = sweep_methods();
        let names: Vec<String> = methods.iter().map(Method::to_string).collect();
        let quality = plan.mode != crate::Mode::TimingOnly;
        for &name in &spec.scenes {
            let Some(base) = jobs.iter().find(|j| j.arg == name && !j.sdf) else {
                sweep.missing.push((
                    name.to_string(),
                    format!("not in this run (add --scene {name})"),
                ));
                continue;
            };
            let job = SceneJob {
                arg: base.arg.clone(),
                name: base.name.clone(),
                scene: base.scene.clone(),
                sdf: false,
                timing_size: AO_SWEEP_SIZE,
                quality_size: AO_SWEEP_SIZE,
            };
            self.progress.note(&format!(
                "{}: where SRAA pays ({} with AO {:?} at {}x{})",
                job.name,
                names.join(", "),
                spec.aos,
                AO_SWEEP_SIZE.0,
                AO_SWEEP_SIZE.1
            ));
            // What each backend refuses is skipped, not failed.
            let mut able: Vec<(usize, Method)> = Vec::new();
            for (bi, (bname, backend)) in plan.backends.iter().enumerate() {
                for m in &methods {
                    match backend.supports(&job.scene, m) {
                        Ok(()) => able.push((bi, *m)),
                        Err(u) => sweep.refused.push(Refused {
                            scene: job.name.to_string(),
                            backend: bname.clone(),
                            method: *m,
                            reason: u.reason.to_string(),
                        }),
                    }
                }
            }
            let masks = if quality {
                Some(self.classes(&job)?)
            } else {
                None
            };
            let (w, h) = AO_SWEEP_SIZE;
            for &ao in &spec.aos {
                let reference = match &masks {
                    Some(_) => {
                        let mut s = RenderSettings::new(w, h);
                        s.ao_rays = ao;
                        let by = spec.ao_reference.filter(|_| ao > 0);
                        Some(Rgb8::from_frame(&self.reference_by(&job, &s, by)?)?)
                    }
                    None => None,
                };
                for (bi, (bname, backend)) in plan.backends.iter().enumerate() {
                    for m in able.iter().filter(|a| a.0 == bi).map(|a| &a.1) {
                        let row = self.sweep_row(
                            &job,
                            (bname, backend.as_ref()),
                            *m,
                            ao,
                            reference.as_ref(),
                            masks.as_ref(),
                        )?;
                        sweep.rows.extend(row);
                    }
                }
            }
        }
        self.plots.extend(plots(&plan.out.join("plots"), &sweep)?);
        Ok(sweep)
    }

    /// One row of the sweep: `m` at `ao` AO rays on `job` with the backend
    /// `(bname, backend)`, timed over the run's rounds after a warm-up, its
    /// FLIP against `reference` with `masks`' classes when measured; `None`
    /// when a render failed (the failure recorded).
    #[allow(clippy::too_many_arguments)]
    fn sweep_row(
        &mut self,
        job: &SceneJob,
        (bname, backend): (&String, &dyn subcone_scene::Backend),
        m: Method,
        ao: u32,
        reference: Option<&Rgb8>,
        masks: Option<&crate::classes::ClassMasks>,
    ) -> Result<Option<AoSweepRow>> {
        let (w, h) = AO_SWEEP_SIZE;
        self.progress.bar.set_message(format!(
            "where SRAA pays, {}: {m} with AO {ao} on {bname}",
            job.name
        ));
        let mut settings = RenderSettings::new(w, h);
        settings.ao_rays = ao;
        let mut t = Timings::default();
        let mut first = None;
        let mut failed = false;
        for k in 0..=self.plan.runs {
            match render(backend, &job.scene, &m, &settings) {
                Ok((f, wall)) => {
                    if k > 0 {
                        t.push(wall, &f);
                    }
                    first.get_or_insert(f);
                }
                Err(e) => {
                    let what = format!("{m} (AO {ao})");
                    self.fail(Failure::new(&job.name, what, bname.clone(), &e))?;
                    failed = true;
                    break;
                }
            }
        }
        let Some(frame) = first.filter(|_| !failed) else {
            return Ok(None);
        };
        let px = (w as f64 * h as f64).max(1.0);
        let mut row = AoSweepRow {
            scene: job.name.to_string(),
            method: m,
            backend: bname.clone(),
            ao,
            ms_median: t.median(),
            ms_range: (t.min(), t.max()),
            rays_per_pixel: frame.stats.rays.total() as f64 / px,
            ao_rays_per_pixel: frame.stats.rays.ao as f64 / px,
            edge_flip: None,
            flip_mean: None,
        };
        if let (Some(r), Some(k)) = (reference, masks) {
            let fl = metrics::flip(r, &Rgb8::from_frame(&frame)?)?;
            row.flip_mean = Some(fl.mean);
            row.edge_flip = pooled_flip(
                &ClassError::measure(&fl.map, k, crate::classes::Metric::Flip),
                &AO_SWEEP_CLASSES,
            );
        }
        Ok(Some(row))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A sweep row of atrium on the CPU (shared with the crossover tests).
    pub(crate) fn row(method: &str, ao: u32, ms: f64, rays: f64, edge: f64) -> AoSweepRow {
        AoSweepRow {
            scene: "atrium".into(),
            method: method.parse().unwrap(),
            backend: "cpu".into(),
            ao,
            ms_median: ms,
            ms_range: (ms, ms),
            rays_per_pixel: rays,
            ao_rays_per_pixel: 0.0,
            edge_flip: Some(edge),
            flip_mean: None,
        }
    }

    #[test]
    fn targets_are_computed_from_the_rows() {
        let sweep = AoSweep {
            ran: true,
            aos: AO_SWEEP.to_vec(),
            ao_reference: None,
            rows: vec![
                row("ssaa4", 16, 400.0, 80.0, 0.05),
                row("sraa-rt", 16, 200.0, 20.0, 0.05),
                row("ssaa4", 64, 1200.0, 260.0, 0.05),
                row("sraa-rt", 64, 300.0, 70.0, 0.055),
            ],
            missing: vec![],
            refused: vec![],
        };
        assert_eq!(
            ratios(&sweep.rows, "atrium", "cpu", Pair::Traced, 16),
            Some((4.0, 2.0))
        );
        let t = target_rows(&sweep);
        // AO 16: 2.0 of 4.0 is 50 %: not met. AO 64: 4.0 of 3.71: met;
        // 4x faster: met; 0.055 / 0.05 = 1.1x: met.
        let lines: Vec<&str> = t.lines().collect();
        assert_eq!(lines.len(), 4, "{t}");
        assert!(lines[0].contains("AO 16") && lines[0].ends_with("**not met** |"));
        assert!(lines[1].contains("AO 64") && lines[1].ends_with("| met |"));
        assert!(lines[2].contains("4.00x") && lines[2].ends_with("| met |"));
        assert!(lines[3].contains("1.10x") && lines[3].ends_with("| met |"));
        assert!(section(&sweep, Some("ssaa256")).contains("## Where SRAA pays"));
        assert!(section(&AoSweep::default(), Some("ssaa256")).is_empty());
    }

    /// The default report's sweep: AO 1 is swept, so that the hybrid
    /// crossover target can be judged.
    #[test]
    fn the_default_sweep_has_one_ao_ray() {
        assert!(SweepSpec::default_report()
            .aos
            .contains(&HYBRID_CROSSOVER_AO));
        assert!(SweepSpec::full().aos.contains(&HYBRID_CROSSOVER_AO));
        let names: Vec<String> = sweep_methods().iter().map(Method::to_string).collect();
        assert_eq!(
            names,
            [
                "noaa",
                "ssaa2",
                "ssaa4",
                "sraa-rt",
                "noaa-hybrid",
                "ssaa2-hybrid",
                "ssaa4-hybrid",
                "sraa-rt-hybrid"
            ]
        );
        assert_eq!(Pair::of(Pair::Hybrid.sraa_rt()), Pair::Hybrid);
        assert_eq!(Pair::of(SRAA_RT), Pair::Traced);
    }

    #[test]
    fn pooled_flip_weights_by_pixels() {
        let mut k = ClassError::default();
        k.mean[Class::Silhouette.index()] = Some(0.1);
        k.px[Class::Silhouette.index()] = 3;
        k.mean[Class::Shadow.index()] = Some(0.5);
        k.px[Class::Shadow.index()] = 1;
        k.mean[Class::Flat.index()] = Some(9.0);
        k.px[Class::Flat.index()] = 100;
        let p = pooled_flip(&k, &AO_SWEEP_CLASSES).unwrap();
        assert!((p - 0.2).abs() < 1e-12);
        assert_eq!(pooled_flip(&ClassError::default(), &AO_SWEEP_CLASSES), None);
    }
}

#[cfg(test)]
mod crossover_tests {
    use super::tests::row;
    use super::*;

    #[test]
    fn the_crossover_states_its_range_and_sraa_at_equal_quality() {
        // ssaa4 − sraa-rt by the medians: −20 at AO 0, +20 at AO 2: they
        // meet at 1. The runs: ±10 ms each side.
        let ranged = |m: &str, ao, ms: f64, edge, flip| {
            let mut r = row(m, ao, ms, 1.0, edge);
            r.ms_range = (ms - 10.0, ms + 10.0);
            r.flip_mean = Some(flip);
            r
        };
        let rows = vec![
            ranged("ssaa2", 0, 70.0, 0.10, 0.030),
            ranged("ssaa4", 0, 100.0, 0.06, 0.020),
            ranged("sraa-rt", 0, 120.0, 0.08, 0.025),
            ranged("ssaa2", 2, 110.0, 0.11, 0.031),
            ranged("ssaa4", 2, 180.0, 0.07, 0.021),
            ranged("sraa-rt", 2, 160.0, 0.12, 0.026),
        ];
        let s = AoSweep {
            ran: true,
            aos: vec![0, 2],
            ao_reference: None,
            rows,
            missing: vec![],
            refused: vec![],
        };
        let c = crossover(&s, "atrium", "cpu", Pair::Traced);
        assert_eq!(c.interpolated, Some(1.0));
        // The runs most favourable to sraa-rt: gaps 0 at AO 0 and +40 at
        // 2, meeting at 0; least favourable: −40 and 0, faster nowhere. So
        // the runs do not bound the crossing inside the sweep.
        assert_eq!(c.interpolated_range, None);
        let f = c.first_faster.unwrap();
        assert_eq!(
            (f.sraa_rt_ms_range, f.ssaa4_ms_range),
            ((150.0, 170.0), (170.0, 190.0))
        );
        let text = crossover_sentence(&c);
        assert!(
            text.contains("160.0 ms (150.0–170.0) against 180.0 ms (170.0–190.0)"),
            "{text}"
        );
        assert!(
            text.contains("whole-image FLIP 0.0260 against 0.0210"),
            "{text}"
        );
        assert!(
            text.contains("the runs do not bound it inside the sweep"),
            "{text}"
        );
        // Equal quality: between ssaa2 and ssaa4 at AO 0, above ssaa2 at 2.
        let e0 = equal_quality(&s, "atrium", "cpu", Pair::Traced, 0).unwrap();
        assert!(e0.starts_with("at AO 0, sraa-rt's edge FLIP 0.0800 is between ssaa2's and ssaa4's (ssaa2 0.1000, ssaa4 0.0600)"), "{e0}");
        assert!(
            e0.contains(
                "in 120.0 (110.0–130.0) ms against 70.0 (60.0–80.0) and 100.0 (90.0–110.0)"
            ),
            "{e0}"
        );
        let e2 = equal_quality(&s, "atrium", "cpu", Pair::Traced, 2).unwrap();
        assert!(e2.contains("is above ssaa2's"), "{e2}");
        assert_eq!(equal_quality(&s, "atrium", "cpu", Pair::Hybrid, 0), None);
    }

    #[test]
    fn the_crossover_is_computed_from_the_rows() {
        let sweep = |rows| AoSweep {
            ran: true,
            aos: vec![0, 4, 16],
            ao_reference: None,
            rows,
            missing: vec![],
            refused: vec![],
        };
        // sraa-rt 40 ms slower at AO 0, 120 ms faster at AO 4: the gap
        // crosses 0 a quarter of the way, at AO 1.
        let s = sweep(vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 140.0, 6.0, 0.08),
            row("ssaa4", 4, 300.0, 20.0, 0.08),
            row("sraa-rt", 4, 180.0, 9.0, 0.09),
            row("ssaa4", 16, 800.0, 70.0, 0.08),
            row("sraa-rt", 16, 300.0, 20.0, 0.09),
        ]);
        let c = crossover(&s, "atrium", "cpu", Pair::Traced);
        let f = c.first_faster.unwrap();
        assert_eq!((f.ao, f.sraa_rt_ms, f.ssaa4_ms), (4, 180.0, 300.0));
        assert_eq!(
            (f.sraa_rt_edge_flip, f.ssaa4_edge_flip),
            (Some(0.09), Some(0.08))
        );
        assert_eq!(c.interpolated, Some(1.0));
        let text = crossover_sentence(&c);
        assert!(
            text.contains("from 4 AO rays") && text.contains("about 1.0 AO rays"),
            "{text}"
        );
        assert!(section(&s, Some("ssaa256")).contains("**Crossover, atrium (cpu), traced:**"));

        // Faster from the first count: no interpolation; never faster: none.
        let s = sweep(vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 90.0, 6.0, 0.08),
        ]);
        let c = crossover(&s, "atrium", "cpu", Pair::Traced);
        assert_eq!((c.first_faster.unwrap().ao, c.interpolated), (0, None));
        let s = sweep(vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 190.0, 6.0, 0.08),
        ]);
        let c = crossover(&s, "atrium", "cpu", Pair::Traced);
        assert!(c.first_faster.is_none());
        assert!(crossover_sentence(&c).contains("at no swept AO ray count"));
    }

    #[test]
    fn each_pair_has_its_own_crossover() {
        let sweep = |rows| AoSweep {
            ran: true,
            aos: vec![0, 1, 4, 16],
            ao_reference: None,
            rows,
            missing: vec![],
            refused: vec![],
        };
        // Traced: sraa-rt slower at 0 and 1, faster from 4 on. Hybrid:
        // slower at 0, faster from 1 on (gap −20 at 0, +60 at 1: they
        // meet at 0.25). A hybrid ssaa4 row alone at 16 changes nothing.
        let rows = vec![
            row("ssaa4", 0, 100.0, 8.0, 0.07),
            row("sraa-rt", 0, 140.0, 6.0, 0.08),
            row("ssaa4", 1, 150.0, 12.0, 0.07),
            row("sraa-rt", 1, 160.0, 7.0, 0.08),
            row("ssaa4", 4, 300.0, 20.0, 0.08),
            row("sraa-rt", 4, 180.0, 9.0, 0.09),
            row("ssaa4-hybrid", 0, 60.0, 4.0, 0.07),
            row("sraa-rt-hybrid", 0, 80.0, 2.0, 0.08),
            row("ssaa4-hybrid", 1, 150.0, 8.0, 0.07),
            row("sraa-rt-hybrid", 1, 90.0, 3.0, 0.08),
            row("ssaa4-hybrid", 16, 700.0, 68.0, 0.07),
        ];
        let s = sweep(rows.clone());
        let all = crossovers(&s);
        assert_eq!(
            all.iter().map(|c| c.pair).collect::<Vec<_>>(),
            [Pair::Traced, Pair::Hybrid]
        );
        let (traced, hybrid) = (&all[0], &all[1]);
        assert_eq!(traced.first_faster.unwrap().ao, 4);
        assert_eq!(traced.timed_at, [0, 1, 4]);
        let f = hybrid.first_faster.unwrap();
        assert_eq!((f.ao, f.sraa_rt_ms, f.ssaa4_ms), (1, 90.0, 150.0));
        assert_eq!(hybrid.timed_at, [0, 1]);
        assert_eq!(hybrid.interpolated, Some(0.25));
        let text = crossover_sentence(hybrid);
        assert!(
            text.starts_with(
                "**Crossover, atrium (cpu), hybrid:** sraa-rt-hybrid is faster than ssaa4-hybrid from 1 AO rays"
            ),
            "{text}"
        );
        // The pair's rows only: the hybrid ratios at AO 1.
        assert_eq!(
            ratios(&s.rows, "atrium", "cpu", Pair::Hybrid, 1),
            Some((8.0 / 3.0, 150.0 / 90.0))
        );
        assert_eq!(ratios(&s.rows, "atrium", "cpu", Pair::Hybrid, 16), None);
        // The table: a row per AO count and pair, the pair named.
        let md = section(&s, Some("ssaa256"));
        assert!(md.contains("| 1 | hybrid | – | – | 150.0 | 90.0 |"), "{md}");
        assert!(
            md.contains("| 1 | traced | – | – | 150.0 | 160.0 |"),
            "{md}"
        );
        assert!(md.contains("| 16 | hybrid | – | – | 700.0 | – |"), "{md}");
        assert!(!md.contains("| 16 | traced |"), "{md}");
        // The target: met at AO 1.
        let t = target_rows(&s);
        let line = t
            .lines()
            .find(|l| {
                l.starts_with(
                    "| hybrid crossover (sraa-rt-hybrid faster than ssaa4-hybrid) at ≤ 1 AO ray",
                )
            })
            .unwrap_or_else(|| panic!("{t}"));
        assert!(
            line.contains("faster from AO 1: 90.0 vs 150.0 ms, the times meet at about 0.2"),
            "{line}"
        );
        assert!(line.ends_with("| met |"), "{line}");

        // Hybrid slower at 0 and 1, faster at 16: not met.
        let mut late = rows.clone();
        late[9] = row("sraa-rt-hybrid", 1, 200.0, 3.0, 0.08);
        late.push(row("sraa-rt-hybrid", 16, 300.0, 20.0, 0.08));
        let c = crossover(&sweep(late.clone()), "atrium", "cpu", Pair::Hybrid);
        assert_eq!(c.first_faster.unwrap().ao, 16);
        assert_eq!(hybrid_crossover_judged(&c).1, Ok(false));
        assert!(target_rows(&sweep(late)).contains("**not met** |"));
        // Never faster: the figure says so, not met.
        let mut never = rows.clone();
        never[9] = row("sraa-rt-hybrid", 1, 200.0, 3.0, 0.08);
        let c = crossover(&sweep(never), "atrium", "cpu", Pair::Hybrid);
        let (figure, met) = hybrid_crossover_judged(&c);
        assert_eq!(
            (figure.as_str(), met),
            ("slower at every swept AO (0, 1)", Ok(false))
        );
        // Not timed at AO 1 and not faster at 0: not judged.
        let no_one: Vec<AoSweepRow> = rows
            .iter()
            .filter(|r| !(r.ao == 1 && r.method.is_hybrid()))
            .cloned()
            .collect();
        let c = crossover(&sweep(no_one), "atrium", "cpu", Pair::Hybrid);
        assert!(hybrid_crossover_judged(&c).1.is_err());
        // A backend without hybrids: no hybrid crossover, no target row.
        let traced_only: Vec<AoSweepRow> = rows
            .iter()
            .filter(|r| !r.method.is_hybrid())
            .cloned()
            .collect();
        let s = sweep(traced_only);
        assert_eq!(crossovers(&s).len(), 1);
        assert!(!target_rows(&s).contains("hybrid crossover"));
    }
}
