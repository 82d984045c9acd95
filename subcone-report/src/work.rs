//! What a run measures: the scenes it loads, the methods each backend
//! renders on each scene (the others skipped, with the reason), and how
//! many renders that makes for the progress bar.

use anyhow::{bail, Context, Result};
use subcone_kernels::passes::SceneFeatures;
use subcone_scene::{Scene, Unsupported, UnsupportedReason};

use crate::args::ReportArgs;
use crate::key::SceneId;
use crate::plan::{Applicable, Mode, Plan, PostPlan};
use crate::scenes::{file_safe, paper_scenes, SceneJob, Unavailable, QUICK_EXTRA_SCENES};
use crate::setup;
use crate::summary::Skipped;
use crate::sweep::{SWEEP_METHODS, SWEEP_SIZES};

pub(crate) fn load_scenes(args: &ReportArgs, plan: &Plan) -> Result<(Vec<SceneJob>, Unavailable)> {
    let mut loaded: Vec<(String, Scene)> = Vec::new();
    let mut unavailable = Vec::new();
    if !args.no_paper_scenes {
        let (ok, missing) = paper_scenes();
        loaded = ok;
        unavailable = missing;
        if plan.mode == Mode::Quick {
            for name in QUICK_EXTRA_SCENES {
                match setup::scene(name) {
                    Ok(s) => loaded.push((name.to_string(), s)),
                    Err(e) => unavailable.push((name.to_string(), format!("{e:#}"))),
                }
            }
        }
    }
    for arg in &args.scenes {
        if loaded.iter().any(|(a, _)| a == arg) {
            continue;
        }
        let s = setup::scene(arg).with_context(|| format!("--scene {arg}"))?;
        loaded.push((arg.clone(), s));
    }
    if loaded.is_empty() {
        bail!("no scene could be loaded");
    }
    let mut jobs: Vec<SceneJob> = Vec::new();
    for (arg, scene) in loaded {
        let base = file_safe(if scene.name.is_empty() {
            &arg
        } else {
            &scene.name
        });
        let mut name = base.clone();
        let mut k = 2;
        while jobs.iter().any(|j| j.name == name) {
            name = format!("{base}-{k}");
            k += 1;
        }
        let sdf = scene.features().contains(SceneFeatures::IS_SDF);
        let (timing_size, quality_size) = plan.sizes(sdf);
        jobs.push(SceneJob {
            arg,
            name: SceneId::new(name),
            scene,
            sdf,
            timing_size,
            quality_size,
        });
    }
    Ok((jobs, unavailable))
}

/// Per scene (by index in `jobs`), each method that some backend renders,
/// with the backends that do (asked of [`Backend::supports`](subcone_scene::Backend::supports) before anything
/// renders), and the combinations skipped, with the reason.
pub(crate) fn applicable(
    plan: &Plan,
    jobs: &[SceneJob],
    default_methods: bool,
) -> (Vec<(usize, Vec<Applicable>)>, Vec<Skipped>) {
    let mut skipped = Vec::new();
    let mut work = Vec::new();
    let skip = |job: &SceneJob, method: String, backend: &str, reason: String| Skipped {
        scene: job.name.to_string(),
        method,
        backend: backend.into(),
        reason,
    };
    for (i, job) in jobs.iter().enumerate() {
        let mut ms = Vec::new();
        for m in &plan.methods {
            // ssaa16 on an SDF scene at 1280x720 costs minutes per run and is
            // not in the CTSS comparison (its Table 1 stops at 4x SS); the
            // default run leaves it out there, an explicit --method keeps it.
            if job.sdf && default_methods && m.supersamples() > 4 && plan.mode != Mode::Quick {
                skipped.push(skip(job, m.to_string(), "*", "left out of the default run on SDF scenes (minutes per frame at 1280x720; pass --method to include it)".into()));
                continue;
            }
            // No triangles to rasterise: a hybrid is its traced method there.
            if job.sdf && m.is_hybrid() {
                skipped.push(skip(job, m.to_string(), "*", format!("an SDF scene has no triangles to rasterise: {m} would trace its rays as {} does", m.traced())));
                continue;
            }
            let mut able = Vec::new();
            let mut refused = Vec::new();
            for (bi, (bname, backend)) in plan.backends.iter().enumerate() {
                match backend.supports(&job.scene, m) {
                    Ok(()) => able.push(bi),
                    Err(u) => refused.push((bname.as_str(), u)),
                }
            }
            // A refusal of the technique itself holds for every backend: one
            // line for all of them.
            let technique = |u: &Unsupported| matches!(u.reason, UnsupportedReason::Technique(_));
            if able.is_empty() && refused.iter().all(|(_, u)| technique(u)) {
                if let Some((_, u)) = refused.first() {
                    skipped.push(skip(job, m.to_string(), "*", u.reason.to_string()));
                }
            } else {
                for (bname, u) in refused {
                    skipped.push(skip(job, m.to_string(), bname, u.reason.to_string()));
                }
            }
            if !able.is_empty() {
                ms.push((*m, able));
            }
        }
        for p in &plan.post {
            if let PostPlan::Unavailable { name, reason } = p {
                skipped.push(skip(job, name.clone(), "*", reason.clone()));
            }
        }
        work.push((i, ms));
    }
    (work, skipped)
}

/// Renders the progress bar counts: per method and backend a warm-up (the
/// quality render when errors are measured) and one render in each timed
/// round, two per scene with errors (reference and masks), and the sweep's.
/// A second warm-up at the timing size adds itself to the length when it
/// happens; a method dropped after a failure counts its renders left as done.
pub(crate) fn progress_length(plan: &Plan, work: &[(usize, Vec<Applicable>)], sweep: bool) -> u64 {
    let quality = plan.mode != Mode::TimingOnly;
    let per_method = 1 + plan.runs as u64;
    let extra = plan.offsets.len().saturating_sub(1) as u64;
    let mut total: u64 = 0;
    for (_, ms) in work {
        let renders: u64 = ms.iter().map(|(_, b)| b.len() as u64).sum();
        total += renders * per_method;
        if quality && !ms.is_empty() {
            // Reference and masks, then a reference and classes and each
            // method's render at every further camera offset.
            total += 2 + extra * (2 + renders);
        }
    }
    if sweep {
        total +=
            (SWEEP_SIZES.len() * SWEEP_METHODS.len() * plan.backends.len()) as u64 * per_method;
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::named::NOAA;

    #[test]
    fn progress_counts_a_warm_up_and_every_round() {
        let args = ReportArgs {
            quick: true,
            runs: Some(4),
            methods: vec!["noaa".into(), "sraa".into()],
            ..Default::default()
        };
        let plan = Plan::new(&args).unwrap();
        let noaa = NOAA;
        // Scene 0: two methods on backend 0; scene 1: nothing applies.
        let work = vec![(0, vec![(noaa, vec![0]), (noaa, vec![0])]), (1, vec![])];
        // 2 methods × (1 warm-up + 4 rounds) + reference and masks, then
        // at each of the 3 further camera offsets a reference, classes and
        // each method's render.
        assert_eq!(plan.offsets.len(), 4);
        assert_eq!(
            progress_length(&plan, &work, false),
            2 * 5 + 2 + 3 * (2 + 2)
        );
    }
}
