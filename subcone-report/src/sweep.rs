//! The SRAA Table 1 sweep: NoAA, SRAA-RT and SSAA16 timed at 256² to 1024²
//! on the atrium, timing only.

use anyhow::Result;
use subcone_scene::Method;

use crate::named::{NOAA, SRAA_RT, SSAA16};
use crate::render::render;
use crate::row::ResultRow;
use crate::runner::Runner;
use crate::scenes::SceneJob;
use crate::summary::Failure;
use crate::timing::Timings;

/// Sizes of the SRAA Table 1 sweep (square).
pub const SWEEP_SIZES: [u32; 4] = [256, 512, 768, 1024];
/// The scene of the SRAA Table 1 sweep: our Sponza-like atrium.
pub const SWEEP_SCENE: &str = "atrium";

/// The methods of the SRAA Table 1 sweep.
pub const SWEEP_METHODS: [Method; 3] = [NOAA, SRAA_RT, SSAA16];

impl Runner<'_> {
    /// The SRAA Table 1 sweep on `job`: timing only, 256² to 1024².
    pub(crate) fn sweep(&mut self, job: &SceneJob) -> Result<Vec<ResultRow>> {
        let plan = self.plan;
        self.progress.note(&format!(
            "{}: SRAA Table 1 sweep (noaa, sraa-rt, ssaa16 at 256² to 1024²)",
            job.name
        ));
        let methods: Vec<Method> = SWEEP_METHODS.to_vec();
        let mut sweep = Vec::new();
        for (bname, backend) in &plan.backends {
            for side in SWEEP_SIZES {
                for m in &methods {
                    self.progress.bar.set_message(format!(
                        "sweep {}: {m} at {side}x{side} on {bname}",
                        job.name
                    ));
                    let settings = plan.settings(side, side, job.sdf);
                    let mut t = Timings::default();
                    let mut ok = true;
                    for k in 0..=plan.runs {
                        match render(backend.as_ref(), &job.scene, m, &settings) {
                            Ok((f, wall)) if k > 0 => t.push(wall, &f),
                            Ok(_) => {}
                            Err(e) => {
                                let what = format!("{m} (sweep at {side}x{side})");
                                self.fail(Failure::new(&job.name, what, bname.clone(), &e))?;
                                ok = false;
                            }
                        }
                        self.progress.bar.inc(1);
                        if !ok {
                            break;
                        }
                    }
                    if ok {
                        let mut row = ResultRow::timed(
                            &job.name,
                            (*m).into(),
                            bname,
                            (side, side),
                            plan.runs,
                            &t,
                        );
                        row.samples_per_pixel = f64::NAN;
                        row.rays_per_pixel = f64::NAN;
                        row.buffer_mib = f64::NAN;
                        sweep.push(row);
                    }
                }
            }
        }
        Ok(sweep)
    }
}
