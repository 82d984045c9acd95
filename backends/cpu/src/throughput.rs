//! Ray throughput of the pipeline against obvhs' raw traversal on the same rays
//! (issue "performance push": primary rays through the pipeline should reach
//! 70 % of the raw rate; shadow rays are measured the same way).
//!
//! A [`RayWorkload`] holds one scene's rays; each `*_pass` method traces all of
//! them once, in parallel over image bands, and returns a checksum so nothing
//! is optimised away. The criterion bench (`cargo bench -p subcone-cpu --bench
//! rays`) and the report (`subcone report`, "Performance targets") both time
//! these passes, so they measure the same thing.
//!
//! - primary, raw: `CwBvh::ray_traverse` (closest hit, nothing else) on the
//!   camera rays through every pixel centre;
//! - primary, pipeline: a NoAA frame of the same scene with its lights removed
//!   and its mirrors made diffuse, so every ray is a primary ray: ray
//!   generation, traversal, hit reconstruction (barycentrics, normals), shading
//!   and the frame's buffers;
//! - shadow, raw: `ray_traverse_miss` on the shadow rays of the primary hits
//!   towards the scene's first light;
//! - shadow, pipeline: the pipeline's shadow test of the same hits (which also
//!   skips emitters and back-facing lights);
//! - primary, raster: the rasteriser's primary visibility (`-hybrid`,
//!   [`crate::raster`]) of the same pixel centres: the triangles' setup and
//!   binning, then every bin's coverage, which decides each sample's
//!   triangle (no hit reconstruction, no shading), timed against the raw
//!   traversal.
//!
//! Every pass runs on the backend's instruction-set path
//! ([`CpuBackend::isa`]), so raw and pipeline are compared on the same one.
//!
//! ```
//! use subcone_cpu::throughput::RayWorkload;
//! use subcone_cpu::CpuBackend;
//! use subcone_scene::builtin::builtin;
//!
//! let backend = CpuBackend::new();
//! let w = RayWorkload::new(&backend, &builtin("cornell").unwrap(), 32, 32).unwrap();
//! let t = w.measure(3);
//! assert_eq!(t.primary_rays, 32 * 32);
//! assert!(t.primary_ratio() > 0.0);
//! assert!(t.raster_ratio() > 0.0);
//! ```

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use subcone_scene::{Backend, Camera, Method, RenderError, RenderSettings, Scene};

use crate::raster::{sample_coordinates, PixelRect, Raster, Samples, BIN, NONE};
use crate::shade::{Surface, Tracer};
use crate::{CpuBackend, SceneBvh};

/// Rays per rayon task: four image rows of a 1024-wide frame.
pub const CHUNK: usize = 4096;

/// One scene's primary and shadow rays, ready to be traced.
pub struct RayWorkload<'a> {
    backend: &'a CpuBackend,
    /// The scene without lights and with diffuse mirrors: primary rays only.
    flat: Scene,
    /// The flat scene with the first light back: the shadow test's scene.
    lit: Option<Scene>,
    camera: Camera,
    bvh: Arc<SceneBvh>,
    width: u32,
    height: u32,
    rays: Vec<(Vec3, Vec3)>,
    hits: Vec<Surface>,
    shadow_rays: Vec<(Vec3, Vec3, f32)>,
}

fn no_mesh() -> RenderError {
    RenderError::Backend {
        backend: "cpu",
        reason: "ray throughput needs a triangle scene".into(),
    }
}

/// Median rates of the four passes, in rays per second.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayThroughput {
    /// Primary rays per pass.
    pub primary_rays: usize,
    /// Shadow rays per pass (0 when the scene has no light).
    pub shadow_rays: usize,
    /// obvhs' raw closest-hit traversal.
    pub raw_primary: f64,
    /// The pipeline's NoAA frame.
    pub pipeline_primary: f64,
    /// obvhs' raw occlusion traversal (`None` without lights).
    pub raw_shadow: Option<f64>,
    /// The pipeline's shadow test (`None` without lights).
    pub pipeline_shadow: Option<f64>,
    /// The rasteriser's primary visibility, in samples per second (one
    /// sample per pixel centre).
    pub raster_primary: f64,
    /// The raw traversal's rate in the rounds that alternated with the
    /// rasteriser's (the ratio's other side).
    pub raw_beside_raster: f64,
    /// Threads the passes ran on (rayon's), for rates per core.
    pub threads: usize,
}

impl RayThroughput {
    /// Pipeline rate over raw rate, primary rays.
    pub fn primary_ratio(&self) -> f64 {
        self.pipeline_primary / self.raw_primary
    }

    /// The rasteriser's samples per second over the raw traversal's rays
    /// per second, measured alternating.
    pub fn raster_ratio(&self) -> f64 {
        self.raster_primary / self.raw_beside_raster
    }

    /// Pipeline rate over raw rate, shadow rays.
    pub fn shadow_ratio(&self) -> Option<f64> {
        Some(self.pipeline_shadow? / self.raw_shadow?)
    }
}

impl<'a> RayWorkload<'a> {
    /// The rays through every pixel centre of a `width`×`height` frame of
    /// `scene`, and the shadow rays of their hits towards the first light.
    /// Fails for SDF scenes and sizes the backend refuses.
    pub fn new(
        backend: &'a CpuBackend,
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<Self, RenderError> {
        RenderSettings::new(width, height).validate()?;
        let mut flat = scene.clone();
        flat.lights.clear();
        for m in &mut flat.materials {
            m.mirror = 0.0;
        }
        flat.touch();
        let bvh = backend.bvh(&flat)?;
        let camera = flat.camera;
        let rays: Vec<(Vec3, Vec3)> = (0..width as usize * height as usize)
            .map(|i| {
                let (x, y) = (i % width as usize, i / width as usize);
                camera.ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), width, height)
            })
            .collect();
        let lit = scene.lights.first().map(|l| {
            let mut s = flat.clone();
            s.lights = vec![*l];
            s
        });
        let mut w = RayWorkload {
            backend,
            flat,
            lit,
            camera,
            bvh,
            width,
            height,
            rays,
            hits: Vec::new(),
            shadow_rays: Vec::new(),
        };
        let (hits, shadow_rays) = {
            let mesh = w.flat.mesh().ok_or_else(no_mesh)?;
            let tracer = Tracer::new(&w.bvh, &w.flat, mesh, &w.camera, 1);
            let hits: Vec<Surface> = w
                .rays
                .par_iter()
                .filter_map(|(o, d)| tracer.intersect(*o, *d, 0.0))
                .collect();
            let shadow_rays = match w.lit.as_ref().and_then(|s| s.lights.first()) {
                Some(light) => hits
                    .iter()
                    .filter_map(|s| {
                        let inc = light.incident(s.p)?;
                        (inc.direction.dot(s.ng) > 0.0).then(|| {
                            (
                                s.p + s.ng * tracer.eps,
                                inc.direction,
                                inc.distance - tracer.eps,
                            )
                        })
                    })
                    .collect(),
                None => Vec::new(),
            };
            (hits, shadow_rays)
        };
        w.hits = hits;
        w.shadow_rays = shadow_rays;
        Ok(w)
    }

    /// Primary rays per pass.
    pub fn primary_rays(&self) -> usize {
        self.rays.len()
    }

    /// Shadow rays per pass.
    pub fn shadow_rays(&self) -> usize {
        self.shadow_rays.len()
    }

    /// obvhs' closest-hit traversal of every primary ray; returns the sum of
    /// the finite hit distances.
    pub fn raw_primary_pass(&self) -> f32 {
        let (bvh, isa) = (&self.bvh, self.backend.isa());
        self.rays
            .par_chunks(CHUNK)
            .map(|c| {
                // Plain loops: an iterator adaptor's `fold` would be a call
                // out of the instruction-set path.
                isa.run(
                    #[inline(always)]
                    || {
                        let mut sum = 0.0f32;
                        for (o, d) in c {
                            let t = bvh.raw_closest_t(*o, *d);
                            if t.is_finite() {
                                sum += t;
                            }
                        }
                        sum
                    },
                )
            })
            .sum()
    }

    /// The rasteriser's triangle at every pixel centre: the setup and bins
    /// ([`Raster::new`]), then each [`BIN`]-row band's coverage on the
    /// backend's instruction-set path; returns how many samples found a
    /// triangle.
    pub fn raster_primary_pass(&self) -> usize {
        let (w, h) = (self.width as usize, self.height as usize);
        let cam = self.camera.rays(self.width, self.height);
        let raster = Raster::new(&self.bvh, &cam, w, h);
        let isa = self.backend.isa();
        (0..h.div_ceil(BIN))
            .into_par_iter()
            .map(|band| {
                isa.run(
                    #[inline(always)]
                    || {
                        let (mut u, mut v, mut depth, mut ids) =
                            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
                        let mut covered = 0;
                        for x0 in (0..w).step_by(BIN) {
                            let rect = PixelRect {
                                x0,
                                y0: band * BIN,
                                x1: (x0 + BIN).min(w),
                                y1: ((band + 1) * BIN).min(h),
                            };
                            let centre =
                                |x: usize, y: usize, _| Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                            sample_coordinates(&cam, rect, 1, centre, &mut u, &mut v);
                            let samples = Samples {
                                count: 1,
                                u: &u,
                                v: &v,
                            };
                            raster.rasterise(rect, samples, &mut depth, &mut ids);
                            for id in &ids {
                                covered += usize::from(*id != NONE);
                            }
                        }
                        covered
                    },
                )
            })
            .sum()
    }

    /// The pipeline's NoAA frame of the unlit scene; returns its pixel count.
    pub fn pipeline_primary_pass(&self) -> Result<usize, RenderError> {
        let noaa = Method::new(subcone_kernels::passes::Technique::NoAa);
        let settings = RenderSettings::new(self.width, self.height);
        Ok(self
            .backend
            .render(&self.flat, &self.camera, &noaa, &settings)?
            .color
            .len())
    }

    /// obvhs' occlusion traversal of every shadow ray; returns how many are
    /// blocked.
    pub fn raw_shadow_pass(&self) -> usize {
        let (bvh, isa) = (&self.bvh, self.backend.isa());
        self.shadow_rays
            .par_chunks(CHUNK)
            .map(|c| {
                isa.run(
                    #[inline(always)]
                    || {
                        let mut blocked = 0;
                        for (o, d, t) in c {
                            blocked += usize::from(bvh.raw_occluded(*o, *d, *t));
                        }
                        blocked
                    },
                )
            })
            .sum()
    }

    /// The pipeline's shadow test from every primary hit; returns how many
    /// are shadowed (0 without a light).
    pub fn pipeline_shadow_pass(&self) -> Result<usize, RenderError> {
        let Some(lit) = &self.lit else {
            return Ok(0);
        };
        let mesh = lit.mesh().ok_or_else(no_mesh)?;
        let mut tracer = Tracer::new(&self.bvh, lit, mesh, &self.camera, 1);
        tracer.isa = self.backend.isa();
        Ok(self
            .hits
            .par_chunks(CHUNK)
            .map(|c| {
                tracer.isa.run(
                    #[inline(always)]
                    || {
                        let mut counts = Default::default();
                        let mut shadowed = 0;
                        for s in c {
                            shadowed += tracer.shadow_states(s, &mut counts).count_ones() as usize;
                        }
                        shadowed
                    },
                )
            })
            .sum())
    }

    /// The raw traversal and the rasteriser alone ([`Self::measure`]'s
    /// `raw_beside_raster` and `raster_primary`): `(rays per second,
    /// samples per second)`, alternating, `runs` rounds (at least one) after a
    /// warm-up. For measuring the rasteriser on each instruction-set path
    /// (a backend [`CpuBackend::with_isa`] each).
    pub fn measure_raster(&self, runs: usize) -> (f64, f64) {
        let ok = std::cell::Cell::new(true);
        alternating(
            self.rays.len(),
            runs,
            &ok,
            || self.raw_primary_pass(),
            || Ok::<_, ()>(self.raster_primary_pass()),
        )
    }

    /// Time each pass `runs` times (at least once, after one warm-up pass each) and return
    /// the median rates. A raw pass and its pipeline pass alternate (raw,
    /// pipeline, raw, pipeline, …), so that the machine's drift during the
    /// measurement falls on both sides of a ratio alike. Errors of the
    /// pipeline's frame become a zero rate, which no target accepts.
    pub fn measure(&self, runs: usize) -> RayThroughput {
        let ok = std::cell::Cell::new(true);
        let (raw_primary, pipeline_primary) = alternating(
            self.rays.len(),
            runs,
            &ok,
            || self.raw_primary_pass(),
            || self.pipeline_primary_pass(),
        );
        let (raw_shadow, pipeline_shadow) = if self.shadow_rays.is_empty() {
            (None, None)
        } else {
            let (raw, pipeline) = alternating(
                self.shadow_rays.len(),
                runs,
                &ok,
                || self.raw_shadow_pass(),
                || self.pipeline_shadow_pass(),
            );
            (Some(raw), Some(pipeline))
        };
        let (raw_beside_raster, raster_primary) = self.measure_raster(runs);
        let fail = |r: f64| if ok.get() { r } else { 0.0 };
        RayThroughput {
            primary_rays: self.rays.len(),
            shadow_rays: self.shadow_rays.len(),
            raw_primary,
            pipeline_primary: fail(pipeline_primary),
            raw_shadow,
            pipeline_shadow: pipeline_shadow.map(fail),
            raster_primary,
            raw_beside_raster,
            threads: rayon::current_num_threads(),
        }
    }
}

/// The median rates, in rays per second, of a raw pass and a pipeline pass
/// over `n` rays: one warm-up each, then `runs` (at least one) rounds of
/// `raw` followed by `pipeline`. Each result goes through `black_box`, so
/// that no pass is optimised away; a pipeline error clears `ok`. A zero
/// median time gives a zero rate.
fn alternating<R, P, E>(
    n: usize,
    runs: usize,
    ok: &std::cell::Cell<bool>,
    raw: impl Fn() -> R,
    pipeline: impl Fn() -> Result<P, E>,
) -> (f64, f64) {
    let a = || {
        std::hint::black_box(raw());
    };
    let b = || ok.set(ok.get() && std::hint::black_box(pipeline()).is_ok());
    let time = |f: &dyn Fn()| {
        let s = Instant::now();
        f();
        s.elapsed()
    };
    a();
    b();
    let (mut ta, mut tb): (Vec<Duration>, Vec<Duration>) =
        (0..runs.max(1)).map(|_| (time(&a), time(&b))).unzip();
    let rate = |t: &mut Vec<Duration>| {
        t.sort();
        let median = t[t.len() / 2].as_secs_f64();
        if median > 0.0 {
            n as f64 / median
        } else {
            0.0
        }
    };
    (rate(&mut ta), rate(&mut tb))
}
