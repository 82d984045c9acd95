//! Sphere tracing of SDF scenes: NoAA, SSAA, CTSS, CTSS-R and SSAA+CTSS.
//!
//! CTSS runs through the kernels' [`ConeStepper`]; this module owns only the SDF
//! evaluation, the normals and the shading. NoAA uses the kernels'
//! [`sphere_trace`](subcone_kernels::ctss::sphere_trace), whose hit threshold is the same cone-based `ω > 0.5 − ε`
//! with the same ε, step budget and maximum distance (§4), so no CTSS/NoAA ratio
//! can be bought by loosening NoAA.
//!
//! Scenes with semi-transparent materials (`alpha < 1`) take the paths of
//! [`translucent`](self::translucent): CTSS with the `K` masks of §5.3, NoAA/SSAA
//! with alpha blending along the ray.

use std::time::Instant;

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use subcone_kernels::aggregate::Aggregate;
use subcone_kernels::ctss::{
    cross_section_frame, sphere_trace_split, ConeStepper, CtssParams, Event,
};
use subcone_kernels::mask::{needs_normal, project_normal};
use subcone_kernels::passes::{Passes, Technique};
use subcone_scene::{
    Camera, Frame, FrameStats, Light, Material, Method, PassTiming, RayCounts, RenderSettings,
};

mod translucent;

/// A signed distance field with per-object materials.
pub trait SdfField: Sync {
    /// Signed distance at `p` and the material of the nearest object.
    fn eval(&self, p: Vec3) -> (f32, u32);

    /// `(safe step, surface distance, material)`: fields that cap their
    /// distance at repetition cell walls return the capped bound first and the
    /// distance to the surface second (occlusion and hits use the second,
    /// marching the first). The default: both are [`eval`](SdfField::eval)'s.
    fn eval_split(&self, p: Vec3) -> (f32, f32, u32) {
        let (d, m) = self.eval(p);
        (d, d, m)
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
        n.normalize_or_zero()
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
}

#[derive(Clone, Copy, Default)]
struct Tally {
    steps: u64,
    samples: u64,
    multi: u64,
    shadow: u64,
}

impl std::ops::Add for Tally {
    type Output = Tally;
    fn add(self, o: Tally) -> Tally {
        Tally {
            steps: self.steps + o.steps,
            samples: self.samples + o.samples,
            multi: self.multi + o.multi,
            shadow: self.shadow + o.shadow,
        }
    }
}

impl<F: SdfField> SdfView<'_, F> {
    /// Normal at `p` seen from depth `t` with cone `tan`: differences over a
    /// quarter of the cone radius (never below 1e-5 of the depth), the same for
    /// every method.
    fn normal_at(&self, p: Vec3, t: f32, tan: f32) -> Vec3 {
        let h = (0.25 * t * tan).max(1e-5 * t.max(1.0));
        self.field.normal(p, h)
    }

    /// Whether a light is blocked, by plain sphere tracing towards it.
    fn shadowed(&self, p: Vec3, n: Vec3, l: Vec3, dist: f32, tally: &mut Tally) -> bool {
        tally.shadow += 1;
        let eps = 1e-4 * (1.0 + p.length());
        let o = p + n * (4.0 * eps);
        let mut t = 0.0f32;
        let limit = dist.min(self.max_distance);
        for _ in 0..self.max_steps {
            if t >= limit {
                return false;
            }
            let (safe, d, _) = self.field.eval_split(o + l * t);
            if d.is_nan() {
                return false;
            }
            if d < eps * (1.0 + t * 1e-3) {
                return true;
            }
            let next = t + safe.min(d);
            t = if next > t { next } else { t.next_up() };
        }
        false
    }

    /// Lambert shading with hard shadows and ambient light.
    fn shade(&self, p: Vec3, n: Vec3, dir: Vec3, tally: &mut Tally) -> Vec3 {
        let (_, _, m) = self.field.eval_split(p);
        let mat = &self.materials[(m as usize).min(self.materials.len().saturating_sub(1))];
        let albedo = mat.albedo_at(p, Vec2::ZERO);
        // Shade the side facing the ray.
        let n = if n.dot(dir) > 0.0 { -n } else { n };
        let mut c = mat.emission + self.ambient * albedo;
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

    fn params(&self, tan: f32, method: &Method) -> CtssParams {
        CtssParams::new(tan)
            .with_range(0.0, self.max_distance)
            .with_max_steps(self.max_steps)
            .relaxed(method.technique == Technique::CtssR)
            .with_visibility_k(method.visibility_k)
    }

    /// One NoAA sample.
    fn noaa(&self, o: Vec3, d: Vec3, p: &CtssParams, tally: &mut Tally) -> Vec3 {
        let hit = sphere_trace_split(p, o, d, |q| {
            let (safe, surface, _) = self.field.eval_split(q);
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

    /// One CTSS sample (Algorithm 1 through the kernels' stepper).
    fn ctss(&self, o: Vec3, d: Vec3, p: &CtssParams, tally: &mut Tally) -> (Vec3, u32) {
        let (right, up) = cross_section_frame(d, self.camera.up);
        let mut stepper = ConeStepper::new(p);
        let mut agg = Aggregate::new();
        loop {
            let t = stepper.t();
            let (safe, surface, _) = self.field.eval_split(o + t * d);
            match stepper.advance_split(surface, safe) {
                Event::March => {}
                Event::Sample(s) => {
                    let q = o + s.t * d;
                    let n = self.normal_at(q, s.t, p.tan_theta);
                    // The mask's plane model relates the group's peak occlusion to
                    // the surface normal where that peak was measured; shading
                    // uses the sample point. The second normal is only computed
                    // when the mask depends on it (partial coverage).
                    let nm = if s.t_occlusion != s.t && needs_normal(s.occlusion, p.placement()) {
                        self.normal_at(o + s.t_occlusion * d, s.t_occlusion, p.tan_theta)
                    } else {
                        n
                    };
                    let (_, w) = stepper.record(&s, project_normal(nm, right, up));
                    agg.add(w, self.shade(q, n, d, tally));
                }
                Event::Stop(_) => break,
            }
        }
        tally.steps += stepper.steps() as u64;
        tally.samples += stepper.samples() as u64;
        (
            agg.resolve(self.background, stepper.background_weight()),
            stepper.samples(),
        )
    }

    /// Render a frame (the semi-transparent path when the scene has
    /// [translucency](Self::has_translucency)).
    pub fn render(&self, method: &Method, s: &RenderSettings, passes: Passes) -> Frame {
        self.render_with(method, s, passes, self.has_translucency())
    }

    /// Render a frame, on the semi-transparent path (CTSS §5.3) when
    /// `translucent`; with every opacity 1 both paths give the same image.
    pub fn render_with(
        &self,
        method: &Method,
        s: &RenderSettings,
        passes: Passes,
        translucent: bool,
    ) -> Frame {
        let (w, h) = (s.width as usize, s.height as usize);
        let side = match method.technique {
            Technique::Ssaa | Technique::SsaaCtss => method.ssaa_side.max(1),
            _ => 1,
        };
        let cone = matches!(
            method.technique,
            Technique::Ctss | Technique::CtssR | Technique::SsaaCtss
        );
        // Each supersample's cone covers its own sub-pixel.
        let tan = self.camera.cone_tan_theta(s.height, method.cone_coverage) / side as f32;
        let params = self.params(tan, method);
        let mut frame = Frame::new(s.width, s.height);
        let mut spp = vec![0.0f32; w * h];
        let start = Instant::now();
        let tally = frame
            .color
            .par_chunks_mut(w)
            .zip(spp.par_chunks_mut(w))
            .enumerate()
            .map(|(y, (row, spp_row))| {
                let mut t = Tally::default();
                for x in 0..w {
                    let mut sum = Vec3::ZERO;
                    let mut samples = 0;
                    for sy in 0..side {
                        for sx in 0..side {
                            let off = Vec2::new(
                                (sx as f32 + 0.5) / side as f32,
                                (sy as f32 + 0.5) / side as f32,
                            );
                            let (o, d) = self.camera.ray(
                                Vec2::new(x as f32, y as f32) + off,
                                s.width,
                                s.height,
                            );
                            if cone {
                                let (c, n) = if translucent {
                                    self.ctss_translucent(o, d, &params, &mut t)
                                } else {
                                    self.ctss(o, d, &params, &mut t)
                                };
                                sum += c;
                                samples += n;
                            } else {
                                let before = t.samples;
                                sum += if translucent {
                                    self.noaa_translucent(o, d, &params, &mut t)
                                } else {
                                    self.noaa(o, d, &params, &mut t)
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
                t
            })
            .reduce(Tally::default, |a, b| a + b);
        let name = if cone {
            "cone tracing"
        } else {
            "sphere tracing"
        };
        frame.stats = FrameStats {
            passes,
            timings: vec![PassTiming {
                name,
                time: start.elapsed(),
            }],
            buffers: vec![("color", std::mem::size_of_val(frame.color.as_slice()))],
            rays: RayCounts {
                primary: (w * h) as u64 * (side * side) as u64,
                shadow: tally.shadow,
                ..Default::default()
            },
            shaded_samples: tally.samples,
            sdf_evaluations: tally.steps,
            multi_sample_pixels: tally.multi,
        };
        if s.aovs {
            frame.samples_per_pixel = Some(spp);
            // Depth and normal through each pixel centre (not timed).
            let plain = self.params(
                self.camera.cone_tan_theta(s.height, 1.0),
                &Method::new(Technique::NoAa),
            );
            let g: Vec<(f32, Vec3)> = (0..w * h)
                .into_par_iter()
                .map(|i| {
                    let (o, d) = self.camera.ray(
                        Vec2::new((i % w) as f32 + 0.5, (i / w) as f32 + 0.5),
                        s.width,
                        s.height,
                    );
                    let split = |q| {
                        let (safe, surface, _) = self.field.eval_split(q);
                        (surface, safe)
                    };
                    match sphere_trace_split(&plain, o, d, split).t {
                        Some(t) => {
                            let q = o + t * d;
                            (
                                self.camera.view_depth(q),
                                self.normal_at(q, t, plain.tan_theta),
                            )
                        }
                        None => (f32::INFINITY, Vec3::ZERO),
                    }
                })
                .collect();
            frame.depth = Some(g.iter().map(|g| g.0).collect());
            frame.normal = Some(g.iter().map(|g| g.1).collect());
        }
        frame
    }
}
