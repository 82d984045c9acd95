//! `ctss+edges`: CTSS with hit groups subdivided at internal edges (§5.2–5.3).
//!
//! The kernels decide ([`group_needs_split`]) and trace the sub-samples
//! ([`split_group`]); this module evaluates the coarse normal, shades the
//! parts and adds them to eq. 6 in place of the group's single sample.

use glam::Vec3;
use subcone_kernels::aggregate::Aggregate;
use subcone_kernels::ctss::{
    coarse_normal_step, group_needs_split, split_group, CtssParams, GroupSample, SplitRay,
};
use subcone_scene::sdf::SplitDistance;

use super::{SdfField, SdfView, Tally};

impl<F: SdfField> SdfView<'_, F> {
    /// Split the group `s` if the criterion says so and add its parts to
    /// `agg`. `n` is the fine normal at the group's sample point, `visible`
    /// and `w` what the stepper's `record` returned. Returns the number of
    /// extra shaded samples (parts beyond the first), or `None` when the
    /// group stays whole and the caller shades it as plain CTSS does.
    ///
    /// Cost: the coarse normal (4 SDF evaluations) for every group, and for a
    /// split group up to four short sphere traces (counted in the SDF
    /// evaluations) and up to four shadings (with their shadow rays).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn split_sample(
        &self,
        ray: &SplitRay,
        p: &CtssParams,
        s: &GroupSample,
        n: Vec3,
        visible: u32,
        w: f32,
        agg: &mut Aggregate,
        tally: &mut Tally,
    ) -> Option<u32> {
        let q = ray.origin + s.t * ray.dir;
        let h = coarse_normal_step(s.t, p).max(4e-5 * s.t.max(1.0));
        let coarse = self.field.normal(q, h);
        if !group_needs_split(n, coarse, s.t_exit - s.t_entry, s.t, p) {
            return None;
        }
        let g = split_group(p, s, ray, visible, w, |x| {
            let SplitDistance { safe, surface, .. } = self.field.eval_split(x);
            (surface, safe)
        })?;
        tally.steps += g.steps as u64;
        let mut group_color = None;
        let mut shaded = 0u32;
        for part in g.parts.iter().filter(|part| part.weight > 0.0) {
            let c = match part.t {
                Some(t) => {
                    let x = ray.origin + t * part.dir;
                    let nx = self.normal_at(x, t, p.tan_theta);
                    self.shade(x, nx, part.dir, tally)
                }
                None => *group_color.get_or_insert_with(|| self.shade(q, n, ray.dir, tally)),
            };
            agg.add(part.weight, c);
            shaded += 1;
        }
        Some(shaded.saturating_sub(1))
    }
}
