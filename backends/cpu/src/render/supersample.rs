//! NoAA and SSAA on triangle scenes: each sample's primary hit traced, or
//! found by the rasteriser (`-hybrid`, [`crate::raster`]), then shaded.

use std::time::Instant;

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use subcone_kernels::passes::{Passes, Technique};
use subcone_kernels::sraa::Geometry;
use subcone_scene::camera::CameraRays;
use subcone_scene::{Frame, FrameStats, Method, PassTiming, RenderSettings};

use super::{pixel_centre, to_ray_counts, TileWork, BAND};
use crate::bvh::Hit;
use crate::raster::{self, sample_coordinates, PixelRect, Raster, Samples, BIN};
use crate::shade::{Counts, Surface, Tracer, MAX_LIGHTS};

/// NoAA (one ray through each pixel centre) and SSAA (a regular n×n grid,
/// or for `ssaa2` its diagonal: samples `(k, k)`, so the positions are the
/// grid's, by the same operations).
pub fn supersample(t: &Tracer, method: &Method, s: &RenderSettings, passes: Passes) -> Frame {
    let (w, h) = (s.width as usize, s.height as usize);
    let ssaa = method.technique() == Technique::Ssaa;
    let n = if ssaa { method.ssaa_side().max(1) } else { 1 };
    let diagonal = ssaa && method.ssaa_diagonal();
    let mut frame = Frame::new(s.width, s.height);
    // The pattern is a constant of each band's loop, so the grids' loops
    // are the ones they were before the diagonal existed.
    match (method.is_hybrid(), diagonal) {
        (true, false) => supersample_hybrid::<false>(t, s, n, &mut frame),
        (true, true) => supersample_hybrid::<true>(t, s, n, &mut frame),
        (false, false) => supersample_traced::<false>(t, s, n, &mut frame),
        (false, true) => supersample_traced::<true>(t, s, n, &mut frame),
    }
    frame.stats.passes = passes;
    if s.aovs {
        let spp = if diagonal { n } else { n * n };
        frame.samples_per_pixel = Some(vec![spp as f32; w * h]);
        centre_aovs(t, s, &mut frame);
    }
    frame
}

/// [`supersample`] with every sample's ray traced, band by band.
fn supersample_traced<const DIAGONAL: bool>(
    t: &Tracer,
    s: &RenderSettings,
    n: u32,
    frame: &mut Frame,
) {
    let w = s.width as usize;
    let start = Instant::now();
    let rays = t.camera.rays(s.width, s.height);
    let counts = frame
        .color
        .par_chunks_mut(w * BAND)
        .enumerate()
        .map(|(band, rows)| {
            // The band's rays on the instruction-set path (`isa`).
            t.isa.run(
                #[inline(always)]
                || supersample_band::<DIAGONAL>(t, &rays, band, rows, w, n),
            )
        })
        .reduce(Counts::default, |a, b| a + b);
    frame.stats = FrameStats {
        timings: vec![PassTiming::cpu("shading", start.elapsed())],
        buffers: vec![("color", frame.color.len() * std::mem::size_of::<Vec3>())],
        rays: to_ray_counts(counts),
        shaded_samples: counts.shaded,
        ..Default::default()
    };
}

/// [`supersample`] with primary visibility rasterised (`-hybrid`): the
/// triangles set up and binned once ([`Raster::new`]), then each
/// [`BIN`]-row band of the image, bin by bin: every sample's triangle, then
/// the tracer's hit on it ([`raster::primary_hit`]), shaded as
/// [`supersample_band`] shades it, each pixel's sum in the same order. A
/// sample that finds the triangle the traversal finds gives the same bits.
fn supersample_hybrid<const DIAGONAL: bool>(
    t: &Tracer,
    s: &RenderSettings,
    n: u32,
    frame: &mut Frame,
) {
    let (w, h) = (s.width as usize, s.height as usize);
    let start = Instant::now();
    let cam = t.camera.rays(s.width, s.height);
    let raster = Raster::new(t.bvh, &cam, w, h);
    let work = frame
        .color
        .par_chunks_mut(w * BIN)
        .enumerate()
        .map_init(HybridScratch::default, |scratch, (band, rows)| {
            t.isa.run(
                #[inline(always)]
                || supersample_hybrid_band::<DIAGONAL>(t, &cam, &raster, scratch, band, rows, w, n),
            )
        })
        .reduce(TileWork::default, |a, b| a + b);
    let wall = start.elapsed();
    // The setup is the raster's; the bands' time is split as the threads
    // spent it.
    let bands = wall.saturating_sub(raster.setup_time);
    let busy = (work.raster + work.shading).as_secs_f64();
    let share = if busy > 0.0 {
        work.raster.as_secs_f64() / busy
    } else {
        0.0
    };
    let raster_time = raster.setup_time + bands.mul_f64(share);
    let c = work.counts;
    frame.stats = FrameStats {
        timings: vec![
            PassTiming::cpu("raster", raster_time),
            PassTiming::cpu("shading", wall.saturating_sub(raster_time)),
        ],
        buffers: vec![
            ("color", frame.color.len() * std::mem::size_of::<Vec3>()),
            ("raster", raster.bytes()),
        ],
        rays: to_ray_counts(c),
        shaded_samples: c.shaded,
        raster_samples: c.raster,
        ..Default::default()
    };
}

/// A hybrid task's buffers, reused from tile to tile: the samples'
/// image-plane coordinates, the depth buffer and the triangles found.
#[derive(Default)]
pub(super) struct HybridScratch {
    pub(super) u: Vec<f32>,
    pub(super) v: Vec<f32>,
    depth: Vec<f32>,
    pub(super) ids: Vec<u32>,
}

impl HybridScratch {
    /// `count` samples per pixel of `rect`, sample `k` of pixel `(x, y)` at
    /// image point `at(x, y, k)`, rasterised into `ids` ([`Raster::rasterise`]'s
    /// layout).
    #[inline(always)]
    pub(super) fn rasterise(
        &mut self,
        raster: &Raster,
        cam: &CameraRays,
        rect: PixelRect,
        count: usize,
        at: impl Fn(usize, usize, usize) -> Vec2,
    ) {
        sample_coordinates(cam, rect, count, at, &mut self.u, &mut self.v);
        let samples = Samples {
            count,
            u: &self.u,
            v: &self.v,
        };
        raster.rasterise(rect, samples, &mut self.depth, &mut self.ids);
    }
}

/// One band of [`supersample_hybrid`]: rows `band · BIN` on, bin by bin.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn supersample_hybrid_band<const DIAGONAL: bool>(
    t: &Tracer,
    cam: &CameraRays,
    raster: &Raster,
    b: &mut HybridScratch,
    band: usize,
    rows: &mut [Vec3],
    w: usize,
    n: u32,
) -> TileWork {
    let mut work = TileWork::default();
    let c = &mut work.counts;
    let n = n.max(1) as usize;
    let spp = if DIAGONAL { n } else { n * n };
    let y0 = band * BIN;
    let y1 = y0 + rows.len() / w.max(1);
    let mut ray = [(Vec3::ZERO, Vec3::ZERO); BATCH];
    let mut hit: [Option<Hit>; BATCH] = [None; BATCH];
    let mut surface: [Option<Surface>; BATCH] = [None; BATCH];
    for x0 in (0..w).step_by(BIN) {
        let start = Instant::now();
        let rect = PixelRect {
            x0,
            y0,
            x1: (x0 + BIN).min(w),
            y1,
        };
        // Sample `k = sy·n + sx` at `(x, y) + ((sx + ½)/n, (sy + ½)/n)`
        // (on the diagonal, `sx = sy = k`): the traced band's point, by the
        // same operations.
        let off = |k: usize| {
            let (sx, sy) = if DIAGONAL { (k, k) } else { (k % n, k / n) };
            Vec2::new((sx as f32 + 0.5) / n as f32, (sy as f32 + 0.5) / n as f32)
        };
        let at = |x: usize, y: usize, k: usize| Vec2::new(x as f32, y as f32) + off(k);
        sample_coordinates(cam, rect, spp, at, &mut b.u, &mut b.v);
        let samples = Samples {
            count: spp,
            u: &b.u,
            v: &b.v,
        };
        raster.rasterise(rect, samples, &mut b.depth, &mut b.ids);
        let shading = Instant::now();
        work.raster += shading - start;
        let (cols, nrows) = (rect.width(), rect.height());
        c.raster += (spp * cols * nrows) as u64;
        // Every pixel's samples in order, in batches.
        let total = cols * nrows * spp;
        let (mut px, mut taken, mut sum) = (0usize, 0usize, Vec3::ZERO);
        let mut done = 0;
        while done < total {
            let m = BATCH.min(total - done);
            for (q, slot) in ray[..m].iter_mut().enumerate() {
                let i = done + q;
                let (p, k) = (i / spp, i % spp);
                let (x, y) = (p % cols, p / cols);
                *slot = cam.through(b.u[k * cols + x], b.v[k * nrows + y]);
            }
            for (q, (h, (o, d))) in hit[..m].iter_mut().zip(&ray[..m]).enumerate() {
                let i = done + q;
                let (p, k) = (i / spp, i % spp);
                let (x, y) = (p % cols, p / cols);
                let id = b.ids[(k * nrows + y) * cols + x];
                let (found, traced) = raster::primary_hit(t.bvh, id, *o, *d);
                c.primary += traced as u64;
                *h = found;
            }
            for ((s, h), (o, d)) in surface[..m].iter_mut().zip(&hit[..m]).zip(&ray[..m]) {
                *s = h.map(|h| t.surface(*o, *d, h));
            }
            for (s, (_, d)) in surface[..m].iter().zip(&ray[..m]) {
                sum += t.radiance_at(*d, s.as_ref(), 0, c);
                taken += 1;
                if taken == spp {
                    let (x, y) = (px % cols, px / cols);
                    rows[y * w + x0 + x] = if spp == 1 { sum } else { sum / spp as f32 };
                    (px, taken, sum) = (px + 1, 0, Vec3::ZERO);
                }
            }
            done += m;
        }
        work.shading += shading.elapsed();
    }
    work
}

/// Samples traced together in [`supersample_band`]: the rays of a batch are
/// generated, then traversed, then their hits reconstructed, then shaded, each
/// step as its own loop, so that the processor overlaps the long division and
/// square-root chains of neighbouring rays instead of waiting on each.
const BATCH: usize = 64;

/// One band of [`supersample`]: `n`×`n` rays per pixel of `rows` (`n` on
/// the grid's diagonal when `DIAGONAL`), the rows from `band · BAND` on.
/// Per ray the same operations as [`Tracer::radiance`] on each sample in
/// turn, and each pixel's sum in the same order, so the same bits.
#[inline(always)]
fn supersample_band<const DIAGONAL: bool>(
    t: &Tracer,
    rays: &CameraRays,
    band: usize,
    rows: &mut [Vec3],
    w: usize,
    n: u32,
) -> Counts {
    let mut c = Counts::default();
    let n = n.max(1) as usize;
    let spp = if DIAGONAL { n } else { n * n };
    let mut ray = [(Vec3::ZERO, Vec3::ZERO); BATCH];
    let mut hit: [Option<Hit>; BATCH] = [None; BATCH];
    let mut surface: [Option<Surface>; BATCH] = [None; BATCH];
    for (r, row) in rows.chunks_mut(w).enumerate() {
        let y = band * BAND + r;
        // Each sub-row's image-plane coordinate (`n` ≤ 16 for every SSAA
        // the methods name; more sub-rows are computed per ray).
        let mut row_v = [0.0f32; 16];
        for (sy, v) in row_v.iter_mut().enumerate().take(n) {
            let off_y = (sy as f32 + 0.5) / n as f32;
            *v = rays.v(y as f32 + off_y);
        }
        // The next sample to generate: pixel `x`, sub-sample (`sx`, `sy`).
        let (mut x, mut sx, mut sy) = (0usize, 0usize, 0usize);
        // The pixel being summed and its samples so far.
        let (mut px, mut taken, mut sum) = (0usize, 0usize, Vec3::ZERO);
        let total = row.len() * spp;
        let mut done = 0;
        while done < total {
            let m = BATCH.min(total - done);
            for slot in &mut ray[..m] {
                // `rays.ray(p)` with the row's coordinate computed once per
                // sub-row: the same operations, so the same ray.
                let off = Vec2::new((sx as f32 + 0.5) / n as f32, (sy as f32 + 0.5) / n as f32);
                let p = Vec2::new(x as f32, y as f32) + off;
                let v = row_v.get(sy).copied().unwrap_or_else(|| rays.v(p.y));
                *slot = rays.through(rays.u(p.x), v);
                sx += 1;
                if DIAGONAL {
                    // The next sample on the diagonal, or the next pixel.
                    sy = sx;
                    if sx == n {
                        (sx, sy) = (0, 0);
                        x += 1;
                    }
                } else if sx == n {
                    sx = 0;
                    sy += 1;
                    if sy == n {
                        sy = 0;
                        x += 1;
                    }
                }
            }
            for (h, (o, d)) in hit[..m].iter_mut().zip(&ray[..m]) {
                *h = t.bvh.closest(*o, *d, 0.0, f32::INFINITY);
            }
            for ((s, h), (o, d)) in surface[..m].iter_mut().zip(&hit[..m]).zip(&ray[..m]) {
                *s = h.map(|h| t.surface(*o, *d, h));
            }
            for (s, (_, d)) in surface[..m].iter().zip(&ray[..m]) {
                c.primary += 1;
                sum += t.radiance_at(*d, s.as_ref(), 0, &mut c);
                taken += 1;
                if taken == spp {
                    // `x / 1 = x`: NoAA's pixels skip the division.
                    row[px] = if spp == 1 { sum } else { sum / spp as f32 };
                    (px, taken, sum) = (px + 1, 0, Vec3::ZERO);
                }
            }
            done += m;
        }
    }
    c
}

/// The AOVs of the ray through each pixel centre (not timed): view depth,
/// normal, albedo, per-light visibility and mirror reflectance.
pub(super) fn centre_aovs(t: &Tracer, s: &RenderSettings, frame: &mut Frame) {
    let w = s.width as usize;
    let lights = t.scene.lights.len().min(MAX_LIGHTS);
    let cam = t.camera.rays(s.width, s.height);
    let g: Vec<(Geometry, Vec3, u32, f32)> = (0..w * s.height as usize)
        .into_par_iter()
        .map(|i| {
            let (o, d) = cam.ray(pixel_centre(i % w, i / w));
            let hit = t.intersect(o, d, 0.0);
            let (visible, mirror) = match &hit {
                Some(h) => (
                    t.light_visibility(h),
                    t.scene.materials[h.material as usize].mirror,
                ),
                None => (0, 0.0),
            };
            let visible = visible & ((1u64 << lights) - 1) as u32;
            (
                t.primary_geometry(hit.as_ref()),
                t.primary_albedo(hit.as_ref()),
                visible,
                mirror,
            )
        })
        .collect();
    frame.depth = Some(g.iter().map(|g| g.0.depth).collect());
    frame.normal = Some(g.iter().map(|g| g.0.normal).collect());
    frame.albedo = Some(g.iter().map(|g| g.1).collect());
    frame.light_visibility = Some(g.iter().map(|g| g.2).collect());
    frame.mirror = Some(g.iter().map(|g| g.3).collect());
}
