//! The CPU-side performance targets: the pipeline's ray throughput against
//! raw traversal on every instruction-set path, and ns per call of the hot
//! kernels.

use crate::kernel_timing;
use crate::runner::Runner;
use crate::scenes::SceneJob;
use crate::summary::ThroughputRow;

impl Runner<'_> {
    /// The CPU-side performance targets (when the CPU backend is in the run):
    /// ray throughput on every triangle scene at its timing size, and ns per
    /// kernel call.
    pub(crate) fn cpu_targets(
        &mut self,
        jobs: &[SceneJob],
    ) -> (Vec<ThroughputRow>, Vec<kernel_timing::KernelTiming>) {
        let mut throughput = Vec::new();
        if !self.plan.backends.iter().any(|b| b.0 == "cpu") {
            return (throughput, Vec::new());
        }
        // Every path the machine runs, not only the one it picks: a path
        // chosen at run time must never be slower than the baseline, and a
        // figure from one path says nothing about another (issue 37).
        for isa in subcone_cpu::isa::Isa::supported() {
            let cpu = subcone_cpu::CpuBackend::new().with_isa(isa);
            for job in jobs.iter().filter(|j| !j.sdf) {
                self.progress.note(&format!(
                    "{}: ray throughput on the {} path",
                    job.name,
                    isa.name()
                ));
                let (w, h) = job.timing_size;
                match subcone_cpu::throughput::RayWorkload::new(&cpu, &job.scene, w, h) {
                    Ok(work) => throughput.push(ThroughputRow {
                        scene: job.name.to_string(),
                        isa,
                        width: w,
                        height: h,
                        rates: work.measure(self.plan.runs as usize),
                    }),
                    Err(e) => self
                        .progress
                        .note(&format!("{}: no ray throughput: {e}", job.name)),
                }
            }
        }
        self.progress.note("kernels: ns per call");
        (throughput, kernel_timing::measure())
    }
}
