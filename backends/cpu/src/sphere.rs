//! Sphere tracing of SDF scenes: NoAA, SSAA, CTSS, CTSS-R and SSAA+CTSS (each
//! CTSS variant with ASAP or delayed shading), and SRAA-RT with its samples
//! taken by sphere tracing.
//!
//! CTSS runs through the kernels' trace ([`subcone_kernels::ctss::trace_field`]); this module owns only the SDF
//! evaluation, the normals and the shading. NoAA uses the kernels'
//! [`sphere_trace`](subcone_kernels::ctss::sphere_trace), whose hit threshold is the same cone-based `ω > 0.5 − ε`
//! with the same ε, step budget and maximum distance (§4), so no CTSS/NoAA ratio
//! can be bought by loosening NoAA.
//!
//! Scenes with semi-transparent materials (`alpha < 1`) take the paths of
//! `translucent`: CTSS with the `K` masks of §5.3, NoAA/SSAA
//! with alpha blending along the ray.

use std::time::Instant;
use subcone_kernels::math::Euclidean;

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use subcone_kernels::aggregate::Aggregate;
use subcone_kernels::ctss::{
    cross_section_frame, march, normal_step, sphere_trace_split, trace_field, ConeField,
    CtssParams, FieldSample, SplitRay,
};
use subcone_kernels::passes::{Passes, Technique, MAX_LIGHTS};
use subcone_scene::sdf::SplitDistance;
use subcone_scene::{
    Camera, Frame, FrameStats, Light, Material, Method, PassTiming, RayCounts, RenderError,
    RenderSettings,
};

mod packet;
mod sraa_rt;
mod translucent;

use crate::isa::Isa;
use packet::{Packets, ShadowRay};
use subcone_sdf::program::SdfProgram;

/// The centre AOVs of one pixel: view depth, the field's normal, albedo,
/// light visibility (bit per light) and mirror reflectance.
pub(super) type CentreAovs = (f32, Vec3, Vec3, u32, f32);

/// [`CentreAovs`] of a ray that hits nothing.
pub(super) const MISS_AOVS: CentreAovs = (f32::INFINITY, Vec3::ZERO, Vec3::ZERO, 0, 0.0);

/// A signed distance field with per-object materials.
pub trait SdfField: Sync {
    /// Signed distance at `p` and the material of the nearest object.
    fn eval(&self, p: Vec3) -> (f32, u32);

    /// The step bound and the surface distance apart: fields that cap their
    /// distance at repetition cell walls return the capped bound as `safe`
    /// and the distance to the surface as `surface` (occlusion and hits use
    /// the surface, marching the bound). The default: both are
    /// [`eval`](SdfField::eval)'s.
    fn eval_split(&self, p: Vec3) -> SplitDistance {
        let (d, m) = self.eval(p);
        SplitDistance {
            safe: d,
            surface: d,
            material: m,
        }
    }

    /// Unit surface normal at `p` from differences of step `h`. The default is
    /// tetrahedral differences (4 evaluations, Quilez).
    fn normal(&self, p: Vec3, h: f32) -> Vec3 {
        const K: [Vec3; 4] = [
            Vec3::new(1.0, -1.0, -1.0),
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(1.0, 1.0, 1.0),
        ];
        let n = K
            .iter()
            .fold(Vec3::ZERO, |a, k| a + *k * self.eval(p + *k * h).0);
        n.unit_or_zero()
    }
}

/// An [`SdfField`] as the kernels' trace reads it: the surface distance, the
/// safe step, and the material as the object id (a group ends where it
/// changes).
pub struct ConeFieldOf<'a, F: SdfField>(pub &'a F);

impl<F: SdfField> ConeField for ConeFieldOf<'_, F> {
    fn sample(&mut self, p: Vec3) -> FieldSample {
        let SplitDistance {
            safe,
            surface,
            material,
        } = self.0.eval_split(p);
        FieldSample {
            distance: surface,
            step: safe,
            object: material,
        }
    }

    fn normal(&mut self, p: Vec3, h: f32) -> Vec3 {
        self.0.normal(p, h)
    }
}

/// What the SDF renderer needs besides the field.
pub struct SdfView<'a, F: SdfField> {
    /// The field.
    pub field: &'a F,
    /// Materials indexed by the field.
    pub materials: &'a [Material],
    /// Lights (hard shadows traced through the field).
    pub lights: &'a [Light],
    /// Ambient light.
    pub ambient: Vec3,
    /// Colour of misses.
    pub background: Vec3,
    /// The camera.
    pub camera: &'a Camera,
    /// Maximum ray distance.
    pub max_distance: f32,
    /// Step budget per ray.
    pub max_steps: u32,
    /// SRAA-RT: cast every subsample's shadow rays instead of only where the
    /// shaded samples around it disagree about a light (as the triangle path's
    /// `CpuBackend::with_exhaustive_subpixel_shadows`).
    pub exhaustive_subpixel_shadows: bool,
    /// The field compiled for packets of rays: NoAA, SSAA, SRAA-RT, the CTSS
    /// family on opaque scenes and the centre AOVs trace
    /// [`LANES`](subcone_sdf::program::LANES) rays at once through
    /// it; `None`: one ray at a time through [`field`](Self::field). Both
    /// give the same frames bit for bit.
    pub program: Option<SdfProgram<'a>>,
    /// The instruction-set path of the hot loops ([`Isa::run`]).
    pub isa: Isa,
    /// Ambient-occlusion rays per shaded point
    /// ([`RenderSettings::ao_rays`]; 0: off). Occlusion rays are traced one
    /// at a time: with rays, set [`program`](Self::program) to `None`, as
    /// `CpuBackend::render` does (the packets shade without occlusion).
    pub ao_rays: u32,
    /// Their length ([`SdfGeometry::ao_radius`](subcone_scene::scene::SdfGeometry::ao_radius)).
    pub ao_radius: f32,
}

/// A hit-group sample waiting to be shaded (delayed shading).
impl<'a> SdfView<'a, subcone_scene::sdf::SdfNode> {
    /// The view of an SDF scene through `camera`, with the scene's own ray
    /// reach and step budget and adaptive subpixel shadows; `None` for a
    /// triangle scene.
    pub fn of_scene(scene: &'a subcone_scene::Scene, camera: &'a Camera) -> Option<Self> {
        let g = scene.sdf_geometry()?;
        Some(SdfView {
            field: &g.root,
            materials: &scene.materials,
            lights: &scene.lights,
            ambient: scene.ambient,
            background: scene.background,
            camera,
            max_distance: g.max_distance,
            max_steps: g.max_steps,
            exhaustive_subpixel_shadows: false,
            program: Some(SdfProgram::compile(&g.root)),
            isa: Isa::detected(),
            ao_rays: 0,
            ao_radius: g.ao_radius(),
        })
    }
}

struct PendingSample {
    q: Vec3,
    n: Vec3,
    w: f32,
}

/// A traced cone whose samples wait in the batch up to index `end`.
struct PendingRay {
    d: Vec3,
    background_weight: f32,
    end: usize,
    samples: u32,
}

#[derive(Clone, Copy, Default)]
struct Tally {
    steps: u64,
    samples: u64,
    multi: u64,
    shadow: u64,
    ao: u64,
}

impl std::ops::Add for Tally {
    type Output = Tally;
    fn add(self, o: Tally) -> Tally {
        Tally {
            steps: self.steps + o.steps,
            samples: self.samples + o.samples,
            multi: self.multi + o.multi,
            shadow: self.shadow + o.shadow,
            ao: self.ao + o.ao,
        }
    }
}

impl<F: SdfField> SdfView<'_, F> {
    /// The material the field names `m` (the last one for an index past
    /// the end).
    fn material(&self, m: u32) -> &Material {
        &self.materials[(m as usize).min(self.materials.len().saturating_sub(1))]
    }

    /// Normal at `p` seen from depth `t` with cone `tan`: differences over a
    /// quarter of the cone radius (never below 1e-5 of the depth), the same for
    /// every method.
    fn normal_at(&self, p: Vec3, t: f32, tan: f32) -> Vec3 {
        self.field.normal(p, normal_step(t, tan))
    }

    /// Whether a light is blocked, by plain sphere tracing towards it.
    fn shadowed(&self, p: Vec3, n: Vec3, l: Vec3, dist: f32, tally: &mut Tally) -> bool {
        tally.shadow += 1;
        let mut ray = ShadowRay::new(p, n, l, dist, self.max_distance);
        loop {
            let q = match ray.next(self.max_steps) {
                Ok(q) => q,
                Err(lit) => return lit,
            };
            let SplitDistance { safe, surface, .. } = self.field.eval_split(q);
            if let Some(blocked) = ray.feed(safe, surface) {
                return blocked;
            }
        }
    }

    /// Whether the any-hit ray from `p` (normal `n`, facing the ray) along
    /// unit `d` meets the field within [`ao_radius`](Self::ao_radius): an
    /// occlusion ray of ambient occlusion ([`subcone_kernels::ao`]), sphere
    /// traced exactly as a shadow ray towards a light that far
    /// ([`shadowed`](Self::shadowed): origin lifted off the surface, hit
    /// threshold, the safe step, at least an ulp per step).
    ///
    /// Domain: a march that reaches the radius (or the scene's
    /// `max_distance`, if nearer) without coming within the threshold of the
    /// surface is a miss, unoccluded; so is a NaN distance (the field is
    /// undefined there: the ray stops, as shadow rays stop, and counts as
    /// open) and a march that spends the scene's step budget first (a ray
    /// that grazes a surface for that long is not taken as blocked). A NaN
    /// radius is taken as 0, which ends the march at once: unoccluded. Every
    /// march ends within the step budget.
    fn ao_occluded(&self, p: Vec3, n: Vec3, d: Vec3, tally: &mut Tally) -> bool {
        tally.ao += 1;
        let radius = if self.ao_radius.is_nan() {
            0.0
        } else {
            self.ao_radius
        };
        let mut ray = ShadowRay::new(p, n, d, radius, self.max_distance);
        loop {
            let q = match ray.next(self.max_steps) {
                Ok(q) => q,
                Err(blocked) => return blocked,
            };
            let SplitDistance { safe, surface, .. } = self.field.eval_split(q);
            if let Some(blocked) = ray.feed(safe, surface) {
                return blocked;
            }
        }
    }

    /// The unoccluded fraction at `p` with unit normal `n` facing the ray:
    /// of [`ao_rays`](Self::ao_rays) fixed directions around `n`
    /// ([`ao_direction`](subcone_kernels::ao::ao_direction), all above the
    /// surface: on a field the shading normal is the geometric one), those
    /// whose [`ao_occluded`](Self::ao_occluded) ray is open
    /// ([`ao_fraction`](subcone_kernels::ao::ao_fraction)). Exactly 1 when
    /// occlusion is off.
    fn ambient_occlusion(&self, p: Vec3, n: Vec3, tally: &mut Tally) -> f32 {
        let count = self.ao_rays;
        let mut open = 0;
        for i in 0..count {
            let d = subcone_kernels::ao::ao_direction(n, i, count);
            if !self.ao_occluded(p, n, d, tally) {
                open += 1;
            }
        }
        subcone_kernels::ao::ao_fraction(open, count)
    }

    /// Lambert shading with hard shadows and ambient light (times the
    /// [`ambient_occlusion`](Self::ambient_occlusion), bit for bit the
    /// plain term when it is off).
    fn shade(&self, p: Vec3, n: Vec3, dir: Vec3, tally: &mut Tally) -> Vec3 {
        let SplitDistance { material: m, .. } = self.field.eval_split(p);
        let mat = self.material(m);
        let albedo = mat.albedo_at(p, Vec2::ZERO);
        // Shade the side facing the ray.
        let n = if n.dot(dir) > 0.0 { -n } else { n };
        let ao = self.ambient_occlusion(p, n, tally);
        let mut c = mat.emission + self.ambient * ao * albedo;
        for light in self.lights {
            let Some(inc) = light.incident(p) else {
                continue;
            };
            let cos = inc.direction.dot(n);
            if cos <= 0.0 || self.shadowed(p, n, inc.direction, inc.distance, tally) {
                continue;
            }
            c += albedo * std::f32::consts::FRAC_1_PI * cos * inc.irradiance;
        }
        c
    }

    /// The method's CTSS parameters on this view ([`Method::ctss_params`]).
    fn params(&self, method: &Method, height: u32) -> CtssParams {
        method.ctss_params(self.camera, height, self.max_distance, self.max_steps)
    }

    /// One NoAA sample.
    fn noaa(&self, o: Vec3, d: Vec3, p: &CtssParams, tally: &mut Tally) -> Vec3 {
        let hit = sphere_trace_split(p, o, d, |q| {
            let SplitDistance { safe, surface, .. } = self.field.eval_split(q);
            (surface, safe)
        });
        tally.steps += hit.steps as u64;
        match hit.t {
            Some(t) => {
                tally.samples += 1;
                let q = o + t * d;
                self.shade(q, self.normal_at(q, t, p.tan_theta), d, tally)
            }
            None => self.background,
        }
    }

    /// The ray `o + t·d` with its cone's cross-section axes.
    fn cone_ray(&self, o: Vec3, d: Vec3) -> SplitRay {
        let (right, up) = cross_section_frame(d, self.camera.up);
        SplitRay {
            origin: o,
            dir: d,
            right,
            up,
        }
    }

    /// One CTSS sample through the kernels' trace, shading each hit group's
    /// sample as soon as the group closes (ASAP).
    fn ctss(&self, o: Vec3, d: Vec3, p: &CtssParams, tally: &mut Tally) -> (Vec3, u32) {
        let ray = self.cone_ray(o, d);
        let mut shadow = Tally::default();
        let r = trace_field(
            p,
            &ray,
            &mut ConeFieldOf(self.field),
            |q, n, dir| self.shade(q, n, dir, &mut shadow),
            self.background,
        );
        tally.shadow += shadow.shadow;
        tally.ao += shadow.ao;
        tally.steps += r.steps as u64;
        tally.samples += r.samples as u64;
        (r.color, r.samples)
    }

    /// One row of CTSS with delayed shading (CTSS §5.1): every cone of the row
    /// is traced first, its samples recorded in `batch` (point, normal,
    /// weight) and its background weight in `rays`; then the recorded samples
    /// are shaded in one loop, in the order they were found, so eq. 6 sums the
    /// same terms in the same order as [`ctss`](Self::ctss) and the row is
    /// bit for bit the ASAP row. Writes the row's colours and samples per
    /// pixel; returns the number of pixels with more samples than rays.
    #[allow(clippy::too_many_arguments)]
    fn ctss_delayed_row(
        &self,
        y: usize,
        side: usize,
        p: &CtssParams,
        s: &RenderSettings,
        (batch, rays): &mut (Vec<PendingSample>, Vec<PendingRay>),
        row: &mut [Vec3],
        spp_row: &mut [f32],
        tally: &mut Tally,
    ) -> u64 {
        batch.clear();
        rays.clear();
        // Pass 1: coverage.
        for x in 0..row.len() {
            for sy in 0..side {
                for sx in 0..side {
                    let off = Vec2::new(
                        (sx as f32 + 0.5) / side as f32,
                        (sy as f32 + 0.5) / side as f32,
                    );
                    let (o, d) =
                        self.camera
                            .ray(Vec2::new(x as f32, y as f32) + off, s.width, s.height);
                    let ray = self.cone_ray(o, d);
                    let stepper = march(p, &ray, &mut ConeFieldOf(self.field), |_, g| {
                        batch.push(PendingSample {
                            q: g.point,
                            n: g.normal,
                            w: g.weight,
                        });
                    });
                    tally.steps += stepper.steps() as u64;
                    tally.samples += stepper.samples() as u64;
                    rays.push(PendingRay {
                        d,
                        background_weight: stepper.background_weight(),
                        end: batch.len(),
                        samples: stepper.samples(),
                    });
                }
            }
        }
        // Pass 2: shading, ray by ray in trace order.
        let mut multi = 0;
        let per_pixel = side * side;
        let mut first = 0;
        for (x, pixel_rays) in rays.chunks(per_pixel).enumerate() {
            let mut sum = Vec3::ZERO;
            let mut samples = 0;
            for r in pixel_rays {
                let mut agg = Aggregate::new();
                for b in &batch[first..r.end] {
                    agg.add(b.w, self.shade(b.q, b.n, r.d, tally));
                }
                first = r.end;
                sum += agg.resolve(self.background, r.background_weight);
                samples += r.samples;
            }
            row[x] = sum / per_pixel as f32;
            spp_row[x] = samples as f32;
            if samples as usize > per_pixel {
                multi += 1;
            }
        }
        multi
    }

    /// The surface hit by sphere tracing `o + t·d` (the NoAA trace): point,
    /// normal facing the ray, distance along the ray.
    fn hit(&self, o: Vec3, d: Vec3, p: &CtssParams, tally: &mut Tally) -> Option<(Vec3, Vec3)> {
        let hit = sphere_trace_split(p, o, d, |q| {
            let SplitDistance { safe, surface, .. } = self.field.eval_split(q);
            (surface, safe)
        });
        tally.steps += hit.steps as u64;
        let t = hit.t?;
        let q = o + t * d;
        let n = self.normal_at(q, t, p.tan_theta);
        Some((q, if n.dot(d) > 0.0 { -n } else { n }))
    }

    /// [`shade_layers`](Self::shade_layers) with the field's material at `q`
    /// already known (the packets read it off the program) and the
    /// ambient term's unoccluded fraction `ao` (1 without occlusion rays).
    fn shade_layers_of(
        &self,
        m: u32,
        q: Vec3,
        n: Vec3,
        bits: u32,
        (split, ao): (bool, f32),
        out: &mut [Vec3],
    ) {
        let mat = self.material(m);
        let albedo = mat.albedo_at(q, Vec2::ZERO);
        out[0] = mat.emission + self.ambient * ao * albedo;
        for (l, light) in self.lights.iter().enumerate().take(MAX_LIGHTS) {
            let mut direct = Vec3::ZERO;
            if bits & (1 << l) == 0 {
                if let Some(inc) = light.incident(q) {
                    let cos = inc.direction.dot(n);
                    if cos > 0.0 {
                        direct = albedo * std::f32::consts::FRAC_1_PI * cos * inc.irradiance;
                    }
                }
            }
            if split {
                out[1 + l] = direct;
            } else {
                out[0] += direct;
            }
        }
    }

    /// The AOVs through each pixel centre (not timed): view depth, normal,
    /// albedo, per-light visibility (a light the surface faces away from
    /// counts as visible, as on triangles) and mirror reflectance.
    fn centre_aovs(&self, frame: &mut Frame, s: &RenderSettings) {
        let w = s.width as usize;
        let plain = self.params(&Method::new(Technique::NoAa), s.height);
        let lights = self.lights.len().min(subcone_kernels::passes::MAX_LIGHTS);
        let g: Vec<CentreAovs> = if let Some(program) = &self.program {
            // In packets, row by row: the same values.
            let mut g = vec![MISS_AOVS; w * s.height as usize];
            g.par_chunks_mut(w).enumerate().for_each_init(
                || Packets::new(self, program),
                |pk, (y, row)| pk.aov_row(y, &plain, s, row),
            );
            g
        } else {
            (0..w * s.height as usize)
                .into_par_iter()
                .map(|i| {
                    let (o, d) = self.camera.ray(
                        Vec2::new((i % w) as f32 + 0.5, (i / w) as f32 + 0.5),
                        s.width,
                        s.height,
                    );
                    let split = |q| {
                        let SplitDistance { safe, surface, .. } = self.field.eval_split(q);
                        (surface, safe)
                    };
                    match sphere_trace_split(&plain, o, d, split).t {
                        Some(t) => {
                            let q = o + t * d;
                            let n = self.normal_at(q, t, plain.tan_theta);
                            let SplitDistance { material: m, .. } = self.field.eval_split(q);
                            let mat = self.material(m);
                            let facing = if n.dot(d) > 0.0 { -n } else { n };
                            let mut visible = 0u32;
                            let mut tally = Tally::default();
                            for (l, light) in self.lights.iter().enumerate().take(lights) {
                                let Some(inc) = light.incident(q) else {
                                    continue;
                                };
                                if inc.direction.dot(facing) <= 0.0
                                    || !self.shadowed(
                                        q,
                                        facing,
                                        inc.direction,
                                        inc.distance,
                                        &mut tally,
                                    )
                                {
                                    visible |= 1 << l;
                                }
                            }
                            (
                                self.camera.view_depth(q),
                                n,
                                mat.albedo_at(q, Vec2::ZERO),
                                visible,
                                mat.mirror,
                            )
                        }
                        None => MISS_AOVS,
                    }
                })
                .collect()
        };
        frame.depth = Some(g.iter().map(|g| g.0).collect());
        frame.normal = Some(g.iter().map(|g| g.1).collect());
        frame.albedo = Some(g.iter().map(|g| g.2).collect());
        frame.light_visibility = Some(g.iter().map(|g| g.3).collect());
        frame.mirror = Some(g.iter().map(|g| g.4).collect());
    }

    /// Render a frame (the semi-transparent path when the scene has
    /// [translucency](Self::has_translucency)).
    ///
    /// # Errors
    /// [`RenderError::Method`] for a technique without a sphere-traced path
    /// (plain SRAA, which the plan already refuses on SDF scenes).
    pub fn render(
        &self,
        method: &Method,
        s: &RenderSettings,
        passes: Passes,
    ) -> Result<Frame, RenderError> {
        self.render_with(method, s, passes, self.has_translucency())
    }

    /// Render a frame, on the semi-transparent path (CTSS §5.3) when
    /// `translucent`; with every opacity 1 both paths give the same image.
    ///
    /// # Errors
    /// As [`render`](Self::render).
    pub fn render_with(
        &self,
        method: &Method,
        s: &RenderSettings,
        passes: Passes,
        translucent: bool,
    ) -> Result<Frame, RenderError> {
        // Every technique named (no wildcard): a new one must be routed.
        match method.technique() {
            Technique::SraaRt => return Ok(self.sraa_rt(method, s, passes)),
            Technique::NoAa
            | Technique::Ssaa
            | Technique::Fxaa
            | Technique::Ctss
            | Technique::CtssR
            | Technique::SsaaCtss => {}
            t @ Technique::Sraa => {
                return Err(RenderError::Method(format!(
                    "{t:?} has no sphere-traced path (sraa-rt renders SDF scenes)"
                )))
            }
        }
        let (w, h) = (s.width as usize, s.height as usize);
        // Samples per pixel side (1 without supersampling), and whether a
        // cone is traced per sample (the CTSS family).
        let side = method.ssaa_side().max(1);
        let cone = method.technique().is_cone_traced();
        // Each supersample's cone covers its own sub-pixel.
        let params = self.params(method, s.height);
        let mut frame = Frame::new(s.width, s.height);
        let mut spp = vec![0.0f32; w * h];
        let start = Instant::now();
        let tally = frame
            .color
            .par_chunks_mut(w)
            .zip(spp.par_chunks_mut(w))
            .enumerate()
            .map_init(
                || {
                    (
                        (Vec::new(), Vec::new()),
                        self.program.as_ref().map(|p| Packets::new(self, p)),
                    )
                },
                |(buffers, packets), (y, (row, spp_row))| {
                    let mut t = Tally::default();
                    // Packets of rays: every opaque method (`ctss+edges`'
                    // split groups trace their sub-rays one at a time).
                    if let Some(pk) = packets.as_mut().filter(|_| !translucent) {
                        let side = side as usize;
                        t.multi += if cone {
                            pk.cone_row(y, side, &params, s, row, spp_row, &mut t)
                        } else {
                            pk.sphere_row(y, side, &params, s, row, spp_row, &mut t)
                        };
                        return t;
                    }
                    // Split groups shade several samples per group, and the
                    // semi-transparent path its own way: neither is recorded
                    // by the delayed path (the backend refuses the latter).
                    if cone && method.delayed_shading() && !params.splits_groups() && !translucent {
                        t.multi += self.ctss_delayed_row(
                            y,
                            side as usize,
                            &params,
                            s,
                            buffers,
                            row,
                            spp_row,
                            &mut t,
                        );
                        return t;
                    }
                    let path = (cone, translucent);
                    self.sample_row(y, side, path, &params, s, row, spp_row, &mut t);
                    t
                },
            )
            .reduce(Tally::default, |a, b| a + b);
        frame.stats = frame_stats(passes, cone, start.elapsed(), &frame, side, tally);
        if s.aovs {
            frame.samples_per_pixel = Some(spp);
            self.centre_aovs(&mut frame, s);
        }
        Ok(frame)
    }

    /// Row `y` of a frame traced one sample at a time, on the
    /// semi-transparent path (CTSS §5.3) when `translucent`: each pixel's
    /// `side × side` samples, a cone each when `cone` (the CTSS family), a
    /// sphere-traced ray otherwise, box-filtered into `row`, with the
    /// pixel's shaded samples in `spp_row`; a pixel with more samples than
    /// rays is counted as multi-sample.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn sample_row(
        &self,
        y: usize,
        side: u32,
        (cone, translucent): (bool, bool),
        params: &CtssParams,
        s: &RenderSettings,
        row: &mut [Vec3],
        spp_row: &mut [f32],
        t: &mut Tally,
    ) {
        let w = s.width as usize;
        for x in 0..w {
            let mut sum = Vec3::ZERO;
            let mut samples = 0;
            for sy in 0..side {
                for sx in 0..side {
                    let off = Vec2::new(
                        (sx as f32 + 0.5) / side as f32,
                        (sy as f32 + 0.5) / side as f32,
                    );
                    let (o, d) =
                        self.camera
                            .ray(Vec2::new(x as f32, y as f32) + off, s.width, s.height);
                    if cone {
                        let (c, n) = if translucent {
                            self.ctss_translucent(o, d, params, t)
                        } else {
                            self.ctss(o, d, params, t)
                        };
                        sum += c;
                        samples += n;
                    } else {
                        let before = t.samples;
                        sum += if translucent {
                            self.noaa_translucent(o, d, params, t)
                        } else {
                            self.noaa(o, d, params, t)
                        };
                        samples += (t.samples - before) as u32;
                    }
                }
            }
            row[x] = sum / (side * side) as f32;
            spp_row[x] = samples as f32;
            if samples > side * side {
                t.multi += 1;
            }
        }
    }
}

/// The statistics of a sphere-traced or cone-traced frame of
/// [`SdfView::render_with`]: its one pass's `time`, its colour buffer, and
/// the rays and samples its rows tallied (`side × side` primary rays per
/// pixel).
fn frame_stats(
    passes: Passes,
    cone: bool,
    time: std::time::Duration,
    frame: &Frame,
    side: u32,
    tally: Tally,
) -> FrameStats {
    let name = if cone {
        "cone tracing"
    } else {
        "sphere tracing"
    };
    let (w, h) = (frame.width as usize, frame.height as usize);
    FrameStats {
        passes,
        timings: vec![PassTiming::cpu(name, time)],
        buffers: vec![("color", std::mem::size_of_val(frame.color.as_slice()))],
        rays: RayCounts {
            primary: (w * h) as u64 * (side * side) as u64,
            shadow: tally.shadow,
            ao: tally.ao,
            ..Default::default()
        },
        shaded_samples: tally.samples,
        sdf_evaluations: tally.steps,
        multi_sample_pixels: tally.multi,
        raster_samples: 0,
    }
}
