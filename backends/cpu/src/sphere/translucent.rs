//! Semi-transparent SDF materials ([`Material::alpha`] < 1): non-binary
//! visibility (CTSS §5.3).
//!
//! - **CTSS** (and CTSS-R, SSAA+CTSS): the same stepper, with every sample
//!   composited through [`ConeStepper::record_alpha`] into the pixel's `K`
//!   masks ([`subcone_kernels::transparency`], `K = 4`) instead of the single
//!   mask `M`; a semi-transparent object's full occlusion does not end the
//!   trace, which passes through it and weights what lies behind by the
//!   transmittance left. A hit group holds one surface: where the nearest
//!   object changes inside a group and one of the two is semi-transparent, the
//!   group is split ([`ConeStepper::split_group`]), so a thin pane and the
//!   floor just behind it (within the cone) get a sample each. The methods
//!   keep their names: `ctss` renders transparency whenever the scene has it.
//! - **NoAA / SSAA** (the reference): sphere tracing with alpha blending along
//!   the ray. At a hit of opacity `α` the ray takes `α` of the shaded colour
//!   (times the transmittance so far), marches through the object (steps of
//!   `max(|d|, 0.04·R_c)`) until it is outside it and clear of the hit band,
//!   and traces on with transmittance `·(1 − α)`; the background takes what is
//!   left. The opacity is exact here (not quantised to quarters).
//!
//! In both, `alpha` is the opacity of an *object* along a ray: its entry
//! surface is shaded, its exit surface is not. A pass ends where the nearest
//! object changes, so an object touching the glass (a sphere resting on the
//! floor) is hit where the ray enters it. Objects nested inside a
//! semi-transparent one are invisible (the union field has no surface there).
//! With every opacity 1 both paths give the opaque renderers' images bit for
//! bit (tested below on every built-in SDF scene).

use glam::Vec3;
use subcone_kernels::aggregate::Aggregate;
use subcone_kernels::cone::{advance, cone_occlusion, cone_radius};
use subcone_kernels::ctss::{
    group_mask, sphere_trace_split, ConeStepper, CtssParams, Event, GroupSample,
};
use subcone_scene::sdf::SplitDistance;
use subcone_scene::Material;

use super::{ConeFieldOf, SdfField, SdfView, Tally};

/// Minimum step, as a fraction of the cone radius, when the NoAA reference
/// marches through a semi-transparent object (a twenty-fifth of the pixel's
/// footprint: the hit band is `d < 2ε·R_c = 0.02·R_c`).
const PASS_STEP: f32 = 0.04;

impl<F: SdfField> SdfView<'_, F> {
    /// Whether the renderer takes the semi-transparent path: some material has
    /// `alpha < 1`.
    pub fn has_translucency(&self) -> bool {
        self.materials.iter().any(Material::is_translucent)
    }

    /// Opacity of material `m` ([`Material::opacity`]: NaN is 1); indices
    /// past the list read the last material, as shading does.
    fn material_opacity(&self, m: u32) -> f32 {
        self.materials
            .get(m as usize)
            .or(self.materials.last())
            .map_or(1.0, Material::opacity)
    }

    /// One CTSS sample with `K` transparency masks (§5.3).
    pub(super) fn ctss_translucent(
        &self,
        o: Vec3,
        d: Vec3,
        p: &CtssParams,
        tally: &mut Tally,
    ) -> (Vec3, u32) {
        let ray = self.cone_ray(o, d);
        let mut stepper = ConeStepper::new(p);
        let mut agg = Aggregate::new();
        // The object nearest where the open group began, and the one the trace
        // is passing through.
        let mut group_material: Option<u32> = None;
        let mut passing_material = 0;
        let mut sample = |stepper: &mut ConeStepper, s: &GroupSample, m: u32, tally: &mut Tally| {
            let q = o + s.t * d;
            let n = self.normal_at(q, s.t, p.tan_theta);
            let mask = group_mask(p, &ray, s, n, &mut ConeFieldOf(self.field));
            let alpha = self.material_opacity(m);
            let (_, w) = stepper.record_alpha_mask(mask, alpha);
            agg.add(w, self.shade(q, n, d, tally));
        };
        loop {
            let t = stepper.t();
            let SplitDistance {
                safe,
                surface,
                material: m,
            } = self.field.eval_split(o + t * d);
            // One surface per group: split where the nearest object changes
            // between a semi-transparent object and another one.
            if let Some(gm) = group_material {
                if gm != m && (self.material_opacity(gm) < 1.0 || self.material_opacity(m) < 1.0) {
                    if let Some(s) = stepper.split_group() {
                        sample(&mut stepper, &s, gm, tally);
                        if stepper.is_passing() {
                            passing_material = gm;
                        }
                    }
                    group_material = None;
                }
            }
            // Through a semi-transparent object into another one (touching it).
            if stepper.is_passing() && m != passing_material {
                stepper.end_pass();
            }
            let event = stepper.advance_object(surface, safe, m);
            let gm = group_material.unwrap_or(m);
            group_material = stepper.in_group().then_some(gm);
            match event {
                Event::March => {}
                Event::Sample(s) => {
                    sample(&mut stepper, &s, gm, tally);
                    if stepper.is_passing() {
                        passing_material = gm;
                    }
                }
                // Stop, or an event this loop does not know.
                _ => break,
            }
        }
        tally.steps += stepper.steps() as u64;
        tally.samples += stepper.samples() as u64;
        (
            agg.resolve(self.background, stepper.background_weight()),
            stepper.samples(),
        )
    }

    /// One NoAA sample with alpha blending along the ray.
    pub(super) fn noaa_translucent(
        &self,
        o: Vec3,
        d: Vec3,
        p: &CtssParams,
        tally: &mut Tally,
    ) -> Vec3 {
        let hard = p.thresholds().hard;
        let mut color = Vec3::ZERO;
        let mut transmittance = 1.0f32;
        let mut t0 = p.t_min;
        let mut budget = p.max_steps;
        let split = |q| {
            let SplitDistance { safe, surface, .. } = self.field.eval_split(q);
            (surface, safe)
        };
        loop {
            let params = p.with_range(t0, p.t_max).with_max_steps(budget);
            let hit = sphere_trace_split(&params, o, d, split);
            tally.steps += hit.steps as u64;
            budget = budget.saturating_sub(hit.steps);
            let Some(t) = hit.t else {
                return color + transmittance * self.background;
            };
            tally.samples += 1;
            let q = o + t * d;
            let SplitDistance {
                material: hit_material,
                ..
            } = self.field.eval_split(q);
            let alpha = self.material_opacity(hit_material);
            color +=
                transmittance * alpha * self.shade(q, self.normal_at(q, t, p.tan_theta), d, tally);
            transmittance *= 1.0 - alpha;
            if transmittance <= 0.0 {
                return color;
            }
            // Through the object: on until outside and clear of the hit band.
            let mut t = t;
            loop {
                if budget == 0 || t.is_nan() || t >= p.t_max {
                    return color + transmittance * self.background;
                }
                let SplitDistance {
                    safe,
                    surface: dist,
                    material: m,
                } = self.field.eval_split(o + t * d);
                budget -= 1;
                tally.steps += 1;
                if dist.is_nan() {
                    return color + transmittance * self.background;
                }
                // Another object is nearest (or, if it touches this one, the
                // ray is inside it): trace on from here.
                if m != hit_material {
                    break;
                }
                let rc = cone_radius(t, p.tan_theta);
                if dist > 0.0 && cone_occlusion(dist, rc) <= hard {
                    break;
                }
                let s = if dist < 0.0 { -dist } else { safe.min(dist) };
                t = advance(t, s, PASS_STEP, rc);
            }
            t0 = t;
        }
    }
}
