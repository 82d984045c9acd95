//! The methods of the SRAA family on the CPU: NoAA, SSAA, SRAA and SRAA-RT.

use std::time::{Duration, Instant};

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use subcone_kernels::passes::{LayerLayout, Passes, SubpixelPasses};
use subcone_kernels::sraa::{
    FrameFlags, Geometry, LayerFlags, Resolver, ShadedFrame, ShadedGroup, SraaParams, Subsamples,
    ALBEDO_TOLERANCE, SUBPIXEL_OFFSETS,
};
use subcone_scene::camera::CameraRays;
use subcone_scene::{Frame, FrameStats, Method, PassTiming, RayCounts, RenderSettings};

use crate::bvh::Hit;
use crate::isa::Isa;
use crate::shade::{Counts, Surface, Tracer, MAX_LIGHTS};

mod geometry;
mod shading;
mod supersample;
use crate::raster::{self, PixelRect, Raster};
#[doc(hidden)]
pub use geometry::shadow_agreement;
use geometry::{trace_tile_subsamples, ShadedSamples, TileSubsamples};
use shading::{shade_region, Rasterised, ShadedRegion};
use supersample::centre_aovs;
pub use supersample::supersample;
use supersample::HybridScratch;

/// Rows per rayon task: a band of the image, so neighbouring rays stay coherent.
pub(crate) const BAND: usize = 4;

/// "No secondary geometry here" (the surface is not a mirror): NaN depth, which
/// the bilateral weight excludes.
const NO_SECONDARY: Geometry = Geometry {
    normal: Vec3::ZERO,
    depth: f32::NAN,
};

pub(crate) fn pixel_centre(x: usize, y: usize) -> Vec2 {
    Vec2::new(x as f32 + 0.5, y as f32 + 0.5)
}

fn to_ray_counts(c: Counts) -> RayCounts {
    RayCounts {
        primary: c.primary,
        geometry: c.geometry,
        shadow: c.shadow,
        secondary: c.secondary,
        ao: c.ao,
    }
}

/// Buffers of one frame (SRAA-RT on SDF scenes, `sphere.rs`, which leaves the
/// secondary ones empty) or of one tile and its apron ([`subpixel`]),
/// allocated only for the passes it runs.
pub(crate) struct Buffers {
    pub(crate) geo: Vec<Geometry>,
    pub(crate) values: Vec<Vec3>,
    pub(crate) shadow: Vec<u32>,
    pub(crate) geo2: Vec<Geometry>,
    pub(crate) shadow2: Vec<u32>,
    pub(crate) sub_geo: Vec<[Geometry; 4]>,
    pub(crate) sub_shadow: Vec<[u32; 4]>,
    pub(crate) sub_geo2: Vec<[Geometry; 4]>,
    pub(crate) sub_shadow2: Vec<[u32; 4]>,
    /// `+mat` only: albedo of each shaded sample and of each subsample.
    pub(crate) albedo: Vec<Vec3>,
    pub(crate) sub_albedo: Vec<[Vec3; 4]>,
    /// What the antialiasing pass reads of each shaded sample's layers before
    /// any weight ([`LayerFlags`]), per group: filled once per region, not
    /// scanned again by each of the nine neighbourhoods a sample is in.
    pub(crate) flags: Vec<LayerFlags>,
    pub(crate) flags2: Vec<LayerFlags>,
}

impl Buffers {
    /// Subsample buffer entry `j`'s four subsamples as the resolver reads
    /// them, and their secondary hits' where the frame has `secondary`
    /// layers.
    #[inline(always)]
    fn subsamples(&self, secondary: bool, j: usize) -> (Subsamples, Option<Subsamples>) {
        let primary = Subsamples {
            geometry: self.sub_geo[j],
            shadow: self.sub_shadow.get(j).copied().unwrap_or([0; 4]),
            albedo: self.sub_albedo.get(j).copied(),
        };
        let secondary = secondary.then(|| Subsamples {
            geometry: self.sub_geo2.get(j).copied().unwrap_or([NO_SECONDARY; 4]),
            shadow: self.sub_shadow2.get(j).copied().unwrap_or([0; 4]),
            albedo: None,
        });
        (primary, secondary)
    }

    /// The frame's buffers by name, the allocated ones only, after `color`.
    pub(crate) fn list(&self, color: &[Vec3]) -> Vec<(&'static str, usize)> {
        let mut buffers = vec![
            ("color", bytes(color)),
            ("geometry", bytes(&self.geo)),
            ("shading layers", bytes(&self.values)),
            ("subpixel geometry", bytes(&self.sub_geo)),
        ];
        for (name, size) in [
            ("shadow states", bytes(&self.shadow)),
            ("secondary geometry", bytes(&self.geo2)),
            ("secondary shadow states", bytes(&self.shadow2)),
            ("subpixel shadow states", bytes(&self.sub_shadow)),
            ("subpixel secondary geometry", bytes(&self.sub_geo2)),
            ("subpixel secondary shadow states", bytes(&self.sub_shadow2)),
            ("albedo", bytes(&self.albedo)),
            ("subpixel albedo", bytes(&self.sub_albedo)),
            ("layer flags", bytes(&self.flags)),
            ("secondary layer flags", bytes(&self.flags2)),
        ] {
            if size > 0 {
                buffers.push((name, size));
            }
        }
        buffers
    }
}

/// The shadow bit gating each layer of a group (eq. 2): layer 0 ungated,
/// layer `1 + l` gated by light `l`; SRAA's one layer ungated.
fn layer_gates(layout: &LayerLayout) -> Vec<Option<u8>> {
    if layout.single {
        vec![None]
    } else {
        (0..1 + layout.lights.min(MAX_LIGHTS))
            .map(|l| l.checked_sub(1).map(|l| l as u8))
            .collect()
    }
}

/// Pass 2 of SRAA (the paper's antialiasing pass) on instruction-set path
/// `isa`: every layer of every subsample reconstructed from the
/// neighbourhood's shaded samples (eq. 1, gated by eq. 2 per light), then the
/// box resolve of the four subsamples into the frame's colours, by the
/// kernels' [`Resolver`].
pub(crate) fn reconstruct_frame_on(
    isa: Isa,
    b: &mut Buffers,
    layout: &LayerLayout,
    params: &SraaParams,
    color: &mut [Vec3],
    w: usize,
    h: usize,
) {
    let gates = layer_gates(layout);
    let resolver = Resolver::new(params, &gates, ALBEDO_TOLERANCE);
    // Each shaded sample's layers summarised once, band by band on every
    // thread, for the nine neighbourhoods it is in.
    let mut flags = std::mem::take(&mut b.flags);
    let mut flags2 = std::mem::take(&mut b.flags2);
    {
        let frame = shaded_frame(b, layout, w, h);
        let fill = |flags: &mut [LayerFlags], group: &ShadedGroup| {
            flags
                .par_chunks_mut(w * BAND)
                .enumerate()
                .for_each(|(band, out)| resolver.layer_flags(&frame, group, band * w * BAND, out));
        };
        fill(&mut flags, &frame.primary);
        if let Some(group) = frame.secondary.as_ref() {
            fill(&mut flags2, group);
        }
    }
    (b.flags, b.flags2) = (flags, flags2);
    let b = &*b;
    let frame = shaded_frame(b, layout, w, h);
    let flags = FrameFlags {
        primary: &b.flags,
        secondary: &b.flags2,
    };
    color
        .par_chunks_mut(w * BAND)
        .enumerate()
        .for_each(|(band, rows)| {
            isa.run(
                #[inline(always)]
                || reconstruct_band(b, layout, &resolver, &frame, &flags, band, rows, w),
            )
        });
}

/// The shaded samples of a `w × h` frame or region in `b` (the first
/// `w·h` of each buffer), as the resolver reads them.
fn shaded_frame<'a>(b: &'a Buffers, layout: &LayerLayout, w: usize, h: usize) -> ShadedFrame<'a> {
    let n = w * h;
    ShadedFrame {
        width: w as u32,
        height: h as u32,
        colors: head(&b.values, n * layout.len()),
        layers: layout.len(),
        albedo: head(&b.albedo, n),
        primary: ShadedGroup {
            geometry: head(&b.geo, n),
            shadow: head(&b.shadow, n),
            first_layer: 0,
        },
        secondary: layout.secondary.then(|| ShadedGroup {
            geometry: head(&b.geo2, n),
            shadow: head(&b.shadow2, n),
            first_layer: layout.secondary_base(),
        }),
    }
}

/// [`reconstruct_frame_on`] on one band of rows, inlined into the
/// instruction-set path's function (which a profile shows as one function).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn reconstruct_band(
    b: &Buffers,
    layout: &LayerLayout,
    resolver: &Resolver,
    frame: &ShadedFrame,
    flags: &FrameFlags,
    band: usize,
    rows: &mut [Vec3],
    w: usize,
) {
    for (i, out) in rows.iter_mut().enumerate() {
        let (x, y) = (i % w, band * BAND + i / w);
        let (primary, secondary) = b.subsamples(layout.secondary, y * w + x);
        *out = resolver.resolve_flagged(
            frame,
            flags,
            x as u32,
            y as u32,
            &primary,
            secondary.as_ref(),
        );
    }
}

fn bytes<T>(v: &[T]) -> usize {
    std::mem::size_of_val(v)
}

/// SRAA (Chajdas et al.) and SRAA for ray tracing (Chiu et al., §3), in the
/// passes named after what they compute, run tile by tile.
///
/// Pass "shading" ([`shade_region`]): one shaded sample per pixel, where the
/// method's [`SraaParams::shaded_offset`] puts it: subsample
/// [`SHADED_SUBSAMPLE`](subcone_kernels::sraa::SHADED_SUBSAMPLE) of the
/// rotated grid (the paper) or the pixel centre (the default). For SRAA-RT its
/// shading is kept in layers that are reconstructed separately: the
/// shadow-independent part; each light's direct part (gated by eq. 2 with that
/// light's shadow state); and, on mirrors, the same split of the reflected
/// radiance, reconstructed on the geometry of the secondary hits (§3.3) and
/// gated by the secondary hits' shadow states ("reflected shadow", Fig. 5).
/// Every layer already carries its mirror factor, `(1 − m)` or `m`, so the
/// subsample's colour is the sum of its layers. SRAA keeps one layer, the
/// final colour, reconstructed with eq. 1 on primary geometry.
///
/// Pass "geometry" ([`trace_tile_subsamples`], the paper's pass 1): the
/// subsamples, traced for geometry only (normal and view depth); for SRAA-RT
/// also their shadow states (subpixel shadow rays) and, on mirrors, the
/// geometry and shadow states of their reflection rays. A subsample that is
/// also the shaded sample (the paper's layout) reuses the shaded ray's, not
/// traced again. The rays go in batches, as SSAA's do ([`supersample_band`]):
/// traversal for the batch, then surfaces, then shadow rays, then reflection
/// rays, so that each loop stays hot.
///
/// Pass "antialiasing" ([`resolve_tile`], pass 2): every layer of every
/// subsample reconstructed from the 3×3 neighbourhood's shaded samples by the
/// kernels, then the box resolve of the four subsamples.
///
/// **Tiles.** The frame is cut into [`TILE`]×[`TILE`] tiles (the tracer's
/// `tile`, `CpuBackend::with_tile`); each runs the
/// three passes before the next, on every thread, so the per-subsample data
/// stays in cache and the buffers are one tile's per thread, not the frame's
/// per layer. The shaded samples of a tile's apron (the neighbourhood's
/// radius around it, inside the image) are shaded with it: a pixel's
/// reconstruction reads exactly the samples it reads over the whole frame,
/// so the image is the same bits; the apron's samples are shaded twice (once
/// per tile that reads them), which [`FrameStats::rays`] counts. Each pass's
/// time is its share of the threads' time, scaled to the frame's wall time.
pub fn subpixel(t: &Tracer, method: &Method, s: &RenderSettings, passes: Passes) -> Frame {
    let plan = SubpixelPlan::new(t, method, passes, s);
    // The camera's per-image constants, once (`CameraRays::ray` is
    // `Camera::ray` bit for bit).
    let cam = t.camera.rays(s.width, s.height);
    let (w, h) = (plan.w, plan.h);
    let gates = layer_gates(&plan.passes.layout);
    let resolver = Resolver::new(&method.sraa(), &gates, ALBEDO_TOLERANCE);
    let mut frame = Frame::new(s.width, s.height);

    let start = Instant::now();
    // `-hybrid`: the triangles set up and binned once per frame.
    let raster = method.is_hybrid().then(|| Raster::new(t.bvh, &cam, w, h));
    let tiles = cut_tiles(&mut frame.color, w, h, plan.tile);
    let in_flight = rayon::current_num_threads().min(tiles.len()).max(1);
    let work = tiles
        .into_par_iter()
        // Buffers reused from tile to tile within a rayon job.
        .map_init(
            || (plan.tile_buffers(), HybridScratch::default()),
            |(b, scratch), (tile, mut out)| {
                let mut work = TileWork::default();
                let raster = raster.as_ref().map(|r| (r, &mut *scratch));
                t.isa.run(
                    #[inline(always)]
                    || {
                        subpixel_tile(
                            t, &plan, &cam, &resolver, b, raster, tile, &mut out, &mut work,
                        )
                    },
                );
                work
            },
        )
        .reduce(TileWork::default, |a, b| a + b);
    let wall = start.elapsed();
    let timings = pass_timings(&work, raster.as_ref(), wall);

    let counts = work.counts;
    // What is allocated at once: one tile's buffers per thread.
    let mut buffers: Vec<(&'static str, usize)> = plan
        .tile_buffers()
        .list(&frame.color)
        .into_iter()
        .map(|(name, bytes)| {
            if name == "color" {
                (name, bytes)
            } else {
                (name, bytes * in_flight)
            }
        })
        .collect();
    if let Some(r) = &raster {
        buffers.push(("raster", r.bytes()));
    }
    frame.stats = FrameStats {
        passes,
        timings,
        buffers,
        rays: to_ray_counts(counts),
        shaded_samples: counts.shaded,
        raster_samples: counts.raster,
        ..Default::default()
    };
    if s.aovs {
        centre_aovs(t, s, &mut frame);
        frame.samples_per_pixel = Some(vec![1.0; w * h]);
    }
    frame
}

/// The `side`×`side` tiles of a `w`×`h` frame (the last ones in a row or
/// column cut by the image's edge), row by row, each with its pixels' rows of
/// `color` (disjoint borrows), so that the tiles, not just the tile rows, are
/// rayon's tasks: a 1024² frame has 256 tiles to balance over the threads,
/// not 16 rows.
fn cut_tiles(color: &mut [Vec3], w: usize, h: usize, side: usize) -> Vec<(Rect, Vec<&mut [Vec3]>)> {
    let mut tiles: Vec<(Rect, Vec<&mut [Vec3]>)> = Vec::new();
    for (row, rows) in color.chunks_mut(w * side).enumerate() {
        let y0 = row * side;
        let y1 = (y0 + side).min(h);
        let first = tiles.len();
        for x0 in (0..w).step_by(side) {
            let tile = Rect {
                x0,
                y0,
                x1: (x0 + side).min(w),
                y1,
            };
            tiles.push((tile, Vec::with_capacity(y1 - y0)));
        }
        for line in rows.chunks_mut(w) {
            for (k, piece) in line.chunks_mut(side).enumerate() {
                tiles[first + k].1.push(piece);
            }
        }
    }
    tiles
}

/// Each pass's time of [`subpixel`]: the raster's setup is its own; the
/// tiles' `wall` time (setup included) is split as the threads spent it
/// (`work`), evenly over the three passes when no time was measured.
fn pass_timings(work: &TileWork, raster: Option<&Raster>, wall: Duration) -> Vec<PassTiming> {
    let mut timings = Vec::new();
    let setup = raster.map_or(Duration::ZERO, |r| r.setup_time);
    let wall = wall.saturating_sub(setup);
    let busy = work.raster + work.shading + work.geometry + work.antialiasing;
    if let Some(r) = raster {
        let share = if busy.is_zero() {
            0.0
        } else {
            work.raster.as_secs_f64() / busy.as_secs_f64()
        };
        timings.push(PassTiming::cpu(
            "raster",
            r.setup_time + wall.mul_f64(share),
        ));
    }
    for (name, d) in [
        ("shading", work.shading),
        ("geometry", work.geometry),
        ("antialiasing", work.antialiasing),
    ] {
        let share = if busy.is_zero() {
            1.0 / 3.0
        } else {
            d.as_secs_f64() / busy.as_secs_f64()
        };
        timings.push(PassTiming::cpu(name, wall.mul_f64(share)));
    }
    timings
}

/// Side of [`subpixel`]'s tiles, in pixels: 64×64 pixels' subsamples and the
/// 66×66 shaded samples around them fit in a core's L2 cache.
pub(crate) const TILE: usize = 64;

/// A rectangle of pixels, `[x0, x1) × [y0, y1)`.
#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: usize,
    y0: usize,
    x1: usize,
    y1: usize,
}

impl Rect {
    fn width(&self) -> usize {
        self.x1 - self.x0
    }

    fn height(&self) -> usize {
        self.y1 - self.y0
    }

    fn len(&self) -> usize {
        self.width() * self.height()
    }

    /// The same rectangle as the rasteriser's [`PixelRect`].
    fn pixels(&self) -> PixelRect {
        PixelRect {
            x0: self.x0,
            y0: self.y0,
            x1: self.x1,
            y1: self.y1,
        }
    }

    /// Grown by `r` pixels on every side, clipped to a `w × h` image.
    fn grown(&self, r: usize, w: usize, h: usize) -> Rect {
        Rect {
            x0: self.x0.saturating_sub(r),
            y0: self.y0.saturating_sub(r),
            x1: (self.x1 + r).min(w),
            y1: (self.y1 + r).min(h),
        }
    }
}

/// What a task of [`subpixel`] or of the hybrid [`supersample`] did: its
/// rays and the time of each pass (the passes it does not run stay zero).
#[derive(Clone, Copy, Default)]
struct TileWork {
    counts: Counts,
    raster: std::time::Duration,
    shading: std::time::Duration,
    geometry: std::time::Duration,
    antialiasing: std::time::Duration,
}

impl std::ops::Add for TileWork {
    type Output = TileWork;
    fn add(self, o: TileWork) -> TileWork {
        TileWork {
            counts: self.counts + o.counts,
            raster: self.raster + o.raster,
            shading: self.shading + o.shading,
            geometry: self.geometry + o.geometry,
            antialiasing: self.antialiasing + o.antialiasing,
        }
    }
}

/// The first `n` entries of a buffer, or nothing where it was not allocated
/// (its pass does not run).
fn first<T>(v: &mut [T], n: usize) -> &mut [T] {
    let n = n.min(v.len());
    &mut v[..n]
}

/// [`first`] of a buffer that is only read.
fn head<T>(v: &[T], n: usize) -> &[T] {
    &v[..n.min(v.len())]
}

/// The three passes of [`subpixel`] on one tile, writing its pixels into
/// `out`, the tile's part of each of its rows of the frame.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn subpixel_tile(
    t: &Tracer,
    plan: &SubpixelPlan,
    cam: &CameraRays,
    resolver: &Resolver,
    b: &mut Buffers,
    mut raster: Option<(&Raster, &mut HybridScratch)>,
    tile: Rect,
    out: &mut [&mut [Vec3]],
    work: &mut TileWork,
) {
    let region = tile.grown(plan.radius as usize, plan.w, plan.h);
    let (n, nl) = (region.len(), plan.nl);

    // `-hybrid`: the shaded samples' triangles over the region.
    let raster_start = Instant::now();
    if let Some((r, scratch)) = raster.as_mut() {
        let offset = plan.shaded_offset;
        scratch.rasterise(r, cam, region.pixels(), 1, |x, y, _| {
            pixel_centre(x, y) + offset
        });
        work.counts.raster += region.len() as u64;
    }
    let start = Instant::now();
    work.raster += start - raster_start;
    let mut shaded = ShadedRegion {
        geo: first(&mut b.geo, n),
        values: first(&mut b.values, n * nl),
        shadow: first(&mut b.shadow, n),
        geo2: first(&mut b.geo2, n),
        shadow2: first(&mut b.shadow2, n),
        albedo: first(&mut b.albedo, n),
    };
    let found = raster.as_ref().map(|(_, s)| Rasterised::of(s, region));
    shade_region(t, plan, cam, &mut shaded, found, region, &mut work.counts);
    let raster_start = Instant::now();
    work.shading += raster_start - start;
    // `-hybrid`: the subsamples' triangles over the tile.
    if let Some((r, scratch)) = raster.as_mut() {
        scratch.rasterise(r, cam, tile.pixels(), 4, |x, y, k| {
            pixel_centre(x, y) + SUBPIXEL_OFFSETS[k]
        });
        // The subsample that is the shaded sample is copied, not looked up.
        let copied = plan.shaded_subsample.is_some() as usize;
        work.counts.raster += ((4 - copied) * tile.len()) as u64;
    }
    let geometry_start = Instant::now();
    work.raster += geometry_start - raster_start;
    let found = raster.as_ref().map(|(_, s)| Rasterised::of(s, tile));

    let m = tile.len();
    let samples = ShadedSamples {
        geo: head(&b.geo, n),
        values: head(&b.values, n * nl),
        shadow: head(&b.shadow, n),
        geo2: head(&b.geo2, n),
        shadow2: head(&b.shadow2, n),
        albedo: head(&b.albedo, n),
    };
    let mut subs = TileSubsamples {
        geo: first(&mut b.sub_geo, m),
        shadow: first(&mut b.sub_shadow, m),
        geo2: first(&mut b.sub_geo2, m),
        shadow2: first(&mut b.sub_shadow2, m),
        albedo: first(&mut b.sub_albedo, m),
    };
    trace_tile_subsamples(
        t,
        plan,
        cam,
        &samples,
        &mut subs,
        found,
        tile,
        region,
        &mut work.counts,
    );
    let resolve_start = Instant::now();
    work.geometry += resolve_start - geometry_start;

    resolve_tile(plan, resolver, b, tile, region, out);
    work.antialiasing += resolve_start.elapsed();
}

/// Pass "antialiasing" on `tile`: each pixel's subsamples reconstructed from
/// the shaded samples of `region` (the tile and its apron) by the kernels'
/// [`Resolver`], in the region's own coordinates. The region holds every
/// in-image neighbour of the tile's pixels and ends where the image ends, so
/// each reconstruction sees the neighbourhood it sees in the whole frame.
#[inline(always)]
fn resolve_tile(
    plan: &SubpixelPlan,
    resolver: &Resolver,
    b: &mut Buffers,
    tile: Rect,
    region: Rect,
    out: &mut [&mut [Vec3]],
) {
    // The flags are written while the rest of the buffers are read.
    let (mut flags, mut flags2) = (std::mem::take(&mut b.flags), std::mem::take(&mut b.flags2));
    resolve_tile_with(
        plan,
        resolver,
        b,
        &mut flags,
        &mut flags2,
        tile,
        region,
        out,
    );
    (b.flags, b.flags2) = (flags, flags2);
}

/// [`resolve_tile`] with the region's flag buffers apart from the rest.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn resolve_tile_with(
    plan: &SubpixelPlan,
    resolver: &Resolver,
    b: &Buffers,
    flags: &mut [LayerFlags],
    flags2: &mut [LayerFlags],
    tile: Rect,
    region: Rect,
    out: &mut [&mut [Vec3]],
) {
    let (n, layout) = (region.len(), &plan.passes.layout);
    let frame = shaded_frame(b, layout, region.width(), region.height());
    // Each shaded sample's layers summarised once for the nine
    // neighbourhoods it is in (the same bits as scanning each).
    let flags = first(flags, n);
    resolver.layer_flags(&frame, &frame.primary, 0, flags);
    let flags2 = first(flags2, n);
    if let Some(group) = frame.secondary.as_ref() {
        resolver.layer_flags(&frame, group, 0, flags2);
    }
    let flags = FrameFlags {
        primary: flags,
        secondary: flags2,
    };
    let tw = tile.width();
    for i in 0..tile.len() {
        let (x, y) = (tile.x0 + i % tw, tile.y0 + i / tw);
        let (primary, secondary) = b.subsamples(layout.secondary, i);
        let (lx, ly) = ((x - region.x0) as u32, (y - region.y0) as u32);
        out[y - tile.y0][x - tile.x0] =
            resolver.resolve_flagged(&frame, &flags, lx, ly, &primary, secondary.as_ref());
    }
}

/// What one frame of [`subpixel`] computes, decided once from its method,
/// planned passes and scene: which buffers exist and which rays each pass
/// casts.
struct SubpixelPlan {
    /// The image's width in pixels.
    w: usize,
    /// Its height in pixels.
    h: usize,
    /// The side of the tiles the passes run on.
    tile: usize,
    /// Lights the shading reads (at most [`MAX_LIGHTS`]).
    lights: usize,
    /// What the frame computes beyond primary visibility (the plan every
    /// backend shares).
    passes: SubpixelPasses,
    /// `passes.layout.len()`: layers per pixel in [`Buffers::values`].
    nl: usize,
    /// Where the shaded sample lies from the pixel centre.
    shaded_offset: Vec2,
    /// The subsample that is also the shaded sample, if one is.
    shaded_subsample: Option<usize>,
    /// The reconstruction's neighbourhood radius, in pixels.
    radius: u32,
    /// Subpixel shadow rays only where the shaded samples around disagree
    /// ([`shadow_agreement`]).
    adaptive: bool,
}

impl SubpixelPlan {
    fn new(t: &Tracer, method: &Method, passes: Passes, s: &RenderSettings) -> Self {
        let lights = t.scene.lights.len().min(MAX_LIGHTS);
        let sp = SubpixelPasses::new(method.technique(), passes, lights, method.gates_material());
        let sraa = method.sraa();
        SubpixelPlan {
            w: s.width as usize,
            h: s.height as usize,
            tile: t.tile.max(1),
            lights,
            passes: sp,
            nl: sp.layout.len(),
            shaded_offset: sraa.shaded_offset(),
            shaded_subsample: sraa.shaded_subsample(),
            radius: sraa.radius(),
            adaptive: !t.exhaustive_subpixel_shadows,
        }
    }

    /// One tile's buffers (`tile`×`tile` subsamples, the shaded samples
    /// of the tile and its apron), each allocated only when a pass of the
    /// plan writes it (an empty one costs nothing), and no larger than the
    /// image.
    fn tile_buffers(&self) -> Buffers {
        let apron = 2 * self.radius as usize;
        let (tw, th) = (self.tile.min(self.w), self.tile.min(self.h));
        let n = (tw + apron).min(self.w) * (th + apron).min(self.h);
        let m = tw * th;
        let layout = &self.passes.layout;
        let lit = layout.lights > 0;
        fn allocated_if<T: Clone>(on: bool, value: T, n: usize) -> Vec<T> {
            if on {
                vec![value; n]
            } else {
                Vec::new()
            }
        }
        Buffers {
            geo: vec![Geometry::MISS; n],
            values: vec![Vec3::ZERO; n * self.nl],
            shadow: allocated_if(lit, 0, n),
            geo2: allocated_if(layout.secondary, NO_SECONDARY, n),
            shadow2: allocated_if(layout.secondary && lit, 0, n),
            sub_geo: vec![[Geometry::MISS; 4]; m],
            sub_shadow: allocated_if(self.passes.sub_shadows && lit, [0; 4], m),
            sub_geo2: allocated_if(self.passes.sub_secondary, [NO_SECONDARY; 4], m),
            sub_shadow2: allocated_if(self.passes.sub_secondary && lit, [0; 4], m),
            albedo: allocated_if(self.passes.material, Vec3::ZERO, n),
            sub_albedo: allocated_if(self.passes.material, [Vec3::ZERO; 4], m),
            // The flags serve the 3×3 neighbourhood (radius 1) only.
            flags: allocated_if(self.radius == 1, LayerFlags::default(), n),
            flags2: allocated_if(
                self.radius == 1 && layout.secondary,
                LayerFlags::default(),
                n,
            ),
        }
    }

    /// [`shadow_agreement`] for a subsample of the pixel at `(x, y)` of a
    /// `w × h` region of shaded samples, whose group's shadow states are
    /// `bits` and base layer `first`; every light's ray is cast when the
    /// plan is exhaustive or the group has no shadow states.
    #[inline(always)]
    fn agreement(
        &self,
        values: &[Vec3],
        bits: &[u32],
        first: usize,
        (x, y): (usize, usize),
        (w, h): (usize, usize),
    ) -> (u32, u32) {
        if !self.adaptive || bits.is_empty() {
            return (u32::MAX, 0);
        }
        let (nl, lights, radius) = (self.nl, self.passes.layout.lights, self.radius);
        shadow_agreement(bits, values, nl, first, lights, x, y, radius, w, h)
    }
}

/// Split a per-pixel buffer into bands of `band` elements; a buffer that was not
/// allocated (its pass does not run) yields `nb` empty bands, so it zips with the
/// others and costs nothing.
pub(crate) fn bands<T: Send>(v: &mut [T], band: usize, nb: usize) -> Vec<&mut [T]> {
    if v.is_empty() {
        (0..nb).map(|_| <&mut [T]>::default()).collect()
    } else {
        v.chunks_mut(band).collect()
    }
}
