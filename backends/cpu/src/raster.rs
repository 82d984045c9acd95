//! Primary visibility by rasterisation: the hybrid mode of SRAA §3.1 and
//! §4.2, for every triangle method.
//!
//! The paper rasterises its subsample G-buffers ("very efficiently, this
//! overhead is insignificant when compared to the ray tracing stage") and
//! ray traces only what rasterisation cannot give (shadows, reflections,
//! ambient occlusion); its 6× over 16× SSAA (Fig. 3, Table 1) is that
//! hybrid's. Here the rasteriser decides only **which triangle** each
//! sample sees. The hit itself (distance, barycentrics, and from them
//! position, normals and material) is then computed by the tracer's own
//! ray–triangle test on that triangle ([`SceneBvh::hit_on`]), with the ray
//! the tracer would cast, so a sample that finds the triangle the traversal
//! finds gives bit-identical data.
//!
//! **Edge functions in the camera's frame** (homogeneous rasterisation,
//! Olano and Greer 1997). Every ray of [`CameraRays::through`] has the
//! direction `D(u, v) = forward + u·right + v·up` (normalised), with `u`
//! and `v` the image-plane coordinates the tracer computes per sample. For
//! a triangle's edge `(a, b)`, seen from the camera at `o`, the plane
//! through `o`, `a` and `b` gives the edge function
//! `E(u, v) = ((a − o) × (b − o)) · D(u, v)`, linear in `u` and `v`; a ray
//! hits the triangle in front of the camera exactly when the three edge
//! functions have the sign of the triple product
//! `(a − o) · ((b − o) × (c − o))`, and behind it when all three have the
//! other sign, so no clipping decides coverage; the near-plane clip below
//! only bounds the triangle on screen. Depth is `w = 1/t` along
//! `D(u, v)`, also linear in `u` and `v`: the nearest triangle has the
//! largest `w`.
//!
//! **Watertight.** Two triangles that share an edge compute its function
//! from the same two vertices in opposite order, so their coefficients are
//! exact negatives and so are their values at every sample (the same
//! operations in the same order on negated inputs). A sample strictly
//! inside one is strictly outside the other; a sample exactly on the edge
//! (`E = 0`) goes to the triangle on whose side the edge's gradient points
//! (`b > 0`, or `b = 0` and `c > 0`): the top-left rule, which is again
//! antisymmetric. So no sample of a closed mesh falls between its
//! triangles, and none is claimed twice at one depth.
//!
//! **Where the raster and the tracer disagree** (the conformance suite
//! counts it): at shared edges, where the tracer's world-space test rounds
//! differently (the raster's triangle is then tested by the tracer's own
//! function, and when that misses the sample falls back to a traced ray,
//! [`primary_hit`]), at depth ties between overlapping triangles, and where
//! the near-plane clip (at [`NEAR`] of the scene's size) leaves out a
//! sliver within that distance of the camera.
//!
//! **Bins.** [`Raster::new`] sets up every triangle once per frame (its
//! edge and depth functions and its bounds in pixels, clipped against the
//! near plane) and bins it into the [`BIN`]×[`BIN`]-pixel squares its
//! bounds touch, in BVH order. [`Raster::rasterise`] covers a rectangle of
//! pixels bin by bin, each bin's triangles over the rectangle's part of
//! that bin, so a sample is visited by its bin's triangles alone and in
//! BVH order: every tiling of the image gives the same triangles, and a
//! depth tie goes to the earlier triangle. The inner loop runs along a row
//! of samples, branch-free, which the instruction-set paths
//! ([`crate::isa`]) vectorise 8 lanes wide (AVX2) or 16 (AVX-512); every
//! path computes the same operations, so the same triangles.

use std::time::{Duration, Instant};

use glam::{Mat3, Vec2, Vec3};
use rayon::prelude::*;
use subcone_scene::camera::CameraRays;

use crate::bvh::{Hit, SceneBvh};

/// No triangle: a sample the rasteriser found empty.
pub const NONE: u32 = u32::MAX;

/// Side of a bin, in pixels (the SRAA tiles' side, [`crate::TILE`], so a
/// tile is one bin and its apron's slivers).
pub const BIN: usize = 64;

/// Where the near-plane clip of a triangle's bounds lies, as a fraction of
/// the scene's size ([`SceneBvh::scale`]) in front of the camera.
pub const NEAR: f32 = 1e-6;

/// One triangle set up for the camera.
#[derive(Clone, Copy, Debug)]
struct RasterTriangle {
    /// The three edge functions `(a + b·u) + c·v`, oriented so that the
    /// triangle's inside is positive.
    edges: [[f32; 3]; 3],
    /// Whether a sample exactly on each edge (`E = 0`) is inside.
    ties: [bool; 3],
    /// The inverse depth along `D(u, v)`: `w = (a + b·u) + c·v`.
    depth: [f32; 3],
    /// The triangle's BVH slot ([`Hit::slot`]).
    slot: u32,
    /// Its bounds in pixels, `[x0, y0, x1, y1)`, inside the image.
    bounds: [u32; 4],
}

/// A frame's triangles set up and binned for rasterisation (see the
/// module's documentation).
pub struct Raster {
    triangles: Vec<RasterTriangle>,
    /// Bin `b`'s triangles are `items[offsets[b]..offsets[b + 1]]`
    /// (indices into `triangles`, in BVH order).
    offsets: Vec<u32>,
    items: Vec<u32>,
    bins_x: usize,
    width: usize,
    height: usize,
    /// The time [`Raster::new`] took.
    pub setup_time: Duration,
}

/// A rectangle of pixels, `[x0, x1) × [y0, y1)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    /// First column.
    pub x0: usize,
    /// First row.
    pub y0: usize,
    /// One past the last column.
    pub x1: usize,
    /// One past the last row.
    pub y1: usize,
}

impl PixelRect {
    /// Columns.
    pub fn width(&self) -> usize {
        self.x1.saturating_sub(self.x0)
    }

    /// Rows.
    pub fn height(&self) -> usize {
        self.y1.saturating_sub(self.y0)
    }

    fn intersect(&self, o: &PixelRect) -> PixelRect {
        PixelRect {
            x0: self.x0.max(o.x0),
            y0: self.y0.max(o.y0),
            x1: self.x1.min(o.x1),
            y1: self.y1.min(o.y1),
        }
    }

    fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }
}

/// Where the samples of a rectangle lie: `count` per pixel; sample `k` of
/// pixel `(x, y)` is at image-plane point `(u[k·cols + x − x0], v[k·rows +
/// y − y0])`, the coordinates the tracer computes for its ray
/// ([`CameraRays::u`], [`CameraRays::v`]).
#[derive(Clone, Copy, Debug)]
pub struct Samples<'a> {
    /// Samples per pixel.
    pub count: usize,
    /// `u` per sample and column.
    pub u: &'a [f32],
    /// `v` per sample and row.
    pub v: &'a [f32],
}

/// The image-plane coordinates of `count` samples per pixel over `rect`
/// into `u` and `v` ([`Samples`]' layout), sample `k` of pixel `(x, y)`
/// at image point `at(x, y, k)`: the point the tracer's ray goes through,
/// computed by the same operations.
pub fn sample_coordinates(
    cam: &CameraRays,
    rect: PixelRect,
    count: usize,
    at: impl Fn(usize, usize, usize) -> Vec2,
    u: &mut Vec<f32>,
    v: &mut Vec<f32>,
) {
    u.clear();
    v.clear();
    for k in 0..count {
        u.extend((rect.x0..rect.x1).map(|x| cam.u(at(x, rect.y0, k).x)));
        v.extend((rect.y0..rect.y1).map(|y| cam.v(at(rect.x0, y, k).y)));
    }
}

impl Raster {
    /// Sets up and bins the triangles of `bvh` for a `width × height` image
    /// through `cam`. Triangles with a non-finite vertex, seen edge-on
    /// (zero triple product) or wholly behind the near plane are left out:
    /// the tracer's test misses the first two too.
    pub fn new(bvh: &SceneBvh, cam: &CameraRays, width: usize, height: usize) -> Self {
        Self::of_triangles(
            bvh.len(),
            |slot| bvh.vertices(slot),
            bvh.scale,
            cam,
            width,
            height,
        )
    }

    /// [`Raster::new`] for `count` triangles whose vertices `vertices(slot)`
    /// gives, slot by slot, in a scene of size `scale` (for the near plane):
    /// what [`Raster::new`] reads of a BVH. Any input is accepted: a
    /// triangle with a non-finite vertex or product is left out.
    pub fn of_triangles(
        count: usize,
        vertices: impl Fn(u32) -> [Vec3; 3] + Sync,
        scale: f32,
        cam: &CameraRays,
        width: usize,
        height: usize,
    ) -> Self {
        let start = Instant::now();
        let (o, [f, r, up]) = cam.frame();
        let to_camera = Mat3::from_cols(f, r, up).inverse();
        let near = NEAR * scale;
        let triangles: Vec<RasterTriangle> = (0..count as u32)
            .into_par_iter()
            .filter_map(|slot| {
                let [a, b, c] = vertices(slot);
                setup(
                    [a, b, c],
                    [a - o, b - o, c - o],
                    [f, r, up],
                    to_camera,
                    near,
                    cam,
                    (width, height),
                    slot,
                )
            })
            .collect();
        let bins_x = width.div_ceil(BIN).max(1);
        let bins_y = height.div_ceil(BIN).max(1);
        let bin_range = |t: &RasterTriangle| {
            let [x0, y0, x1, y1] = t.bounds.map(|b| b as usize);
            (x0 / BIN, y0 / BIN, (x1 - 1) / BIN, (y1 - 1) / BIN)
        };
        let mut counts = vec![0u32; bins_x * bins_y + 1];
        for t in &triangles {
            let (bx0, by0, bx1, by1) = bin_range(t);
            for by in by0..=by1 {
                for bx in bx0..=bx1 {
                    counts[by * bins_x + bx + 1] += 1;
                }
            }
        }
        for i in 1..counts.len() {
            counts[i] += counts[i - 1];
        }
        let offsets = counts;
        let mut fill = offsets.clone();
        let mut items = vec![0u32; *offsets.last().unwrap_or(&0) as usize];
        for (i, t) in triangles.iter().enumerate() {
            let (bx0, by0, bx1, by1) = bin_range(t);
            for by in by0..=by1 {
                for bx in bx0..=bx1 {
                    let b = by * bins_x + bx;
                    items[fill[b] as usize] = i as u32;
                    fill[b] += 1;
                }
            }
        }
        Raster {
            triangles,
            offsets,
            items,
            bins_x,
            width,
            height,
            setup_time: start.elapsed(),
        }
    }

    /// Bytes held: the set-up triangles and the bins.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.triangles.as_slice())
            + std::mem::size_of_val(self.offsets.as_slice())
            + std::mem::size_of_val(self.items.as_slice())
    }

    /// Triangles set up (those left out are not counted).
    pub fn triangles(&self) -> usize {
        self.triangles.len()
    }

    /// Triangle entries over all bins (a triangle counts once per bin it
    /// touches).
    pub fn binned(&self) -> usize {
        self.items.len()
    }

    /// The nearest triangle's BVH slot at every sample of `rect` (or
    /// [`NONE`]) into `ids`, at index `(k·rows + y − y0)·cols + x − x0`;
    /// `depth` (the same layout) is scratch. Both are resized to fit. A
    /// rectangle reaching outside the image is cut to it (its outside
    /// samples are [`NONE`]).
    #[inline(always)]
    pub fn rasterise(
        &self,
        rect: PixelRect,
        samples: Samples,
        depth: &mut Vec<f32>,
        ids: &mut Vec<u32>,
    ) {
        let (cols, rows) = (rect.width(), rect.height());
        let n = samples.count * cols * rows;
        depth.clear();
        depth.resize(n, 0.0);
        ids.clear();
        ids.resize(n, NONE);
        let image = PixelRect {
            x0: 0,
            y0: 0,
            x1: self.width,
            y1: self.height,
        };
        let inside = rect.intersect(&image);
        if inside.is_empty() || samples.u.len() < samples.count * cols {
            return;
        }
        if samples.v.len() < samples.count * rows {
            return;
        }
        for by in inside.y0 / BIN..=(inside.y1 - 1) / BIN {
            for bx in inside.x0 / BIN..=(inside.x1 - 1) / BIN {
                let bin = PixelRect {
                    x0: bx * BIN,
                    y0: by * BIN,
                    x1: (bx + 1) * BIN,
                    y1: (by + 1) * BIN,
                };
                let part = inside.intersect(&bin);
                let b = by * self.bins_x + bx;
                let list = &self.items[self.offsets[b] as usize..self.offsets[b + 1] as usize];
                for &i in list {
                    let t = &self.triangles[i as usize];
                    let [x0, y0, x1, y1] = t.bounds.map(|b| b as usize);
                    let span = part.intersect(&PixelRect { x0, y0, x1, y1 });
                    if span.is_empty() {
                        continue;
                    }
                    cover(t, rect, span, samples, depth, ids);
                }
            }
        }
    }
}

/// One triangle over `span` (inside `rect`) at every sample: the depth test
/// and the store, along rows.
#[inline(always)]
fn cover(
    t: &RasterTriangle,
    rect: PixelRect,
    span: PixelRect,
    samples: Samples,
    depth: &mut [f32],
    ids: &mut [u32],
) {
    let (cols, rows) = (rect.width(), rect.height());
    let [e0, e1, e2] = t.edges;
    let [t0, t1, t2] = t.ties;
    let [da, db, dc] = t.depth;
    let slot = t.slot;
    let (c0, c1) = (span.x0 - rect.x0, span.x1 - rect.x0);
    for k in 0..samples.count {
        let us = &samples.u[k * cols + c0..k * cols + c1];
        for y in span.y0..span.y1 {
            let v = samples.v[k * rows + y - rect.y0];
            // Each function's `c·v`, once per row: `(a + b·u) + c·v`.
            let (v0, v1, v2, dv) = (e0[2] * v, e1[2] * v, e2[2] * v, dc * v);
            let row = (k * rows + y - rect.y0) * cols;
            let d_row = &mut depth[row + c0..row + c1];
            let i_row = &mut ids[row + c0..row + c1];
            for ((u, d), id) in us.iter().zip(d_row.iter_mut()).zip(i_row.iter_mut()) {
                let f0 = (e0[0] + e0[1] * u) + v0;
                let f1 = (e1[0] + e1[1] * u) + v1;
                let f2 = (e2[0] + e2[1] * u) + v2;
                // `&` and `|` on booleans: no branch, so the loop vectorises.
                let in0 = (f0 > 0.0) | ((f0 == 0.0) & t0);
                let in1 = (f1 > 0.0) | ((f1 == 0.0) & t1);
                let in2 = (f2 > 0.0) | ((f2 == 0.0) & t2);
                let w = (da + db * u) + dv;
                // `d` starts at 0: only a hit in front (`w > 0`) is stored.
                let take = in0 & in1 & in2 & (w > *d);
                *d = if take { w } else { *d };
                *id = if take { slot } else { *id };
            }
        }
    }
}

/// One triangle's setup: `v` its vertices, `p` the same relative to the
/// camera, `basis` the camera's (forward, right, up) and `to_camera` its
/// inverse.
#[allow(clippy::too_many_arguments)]
fn setup(
    v: [Vec3; 3],
    p: [Vec3; 3],
    basis: [Vec3; 3],
    to_camera: Mat3,
    near: f32,
    cam: &CameraRays,
    (width, height): (usize, usize),
    slot: u32,
) -> Option<RasterTriangle> {
    let [f, r, up] = basis;
    let [v0, v1, v2] = v;
    // Bounds first: most triangles of a large scene are off screen or
    // behind the camera, and need nothing else.
    let bounds = bounds(p.map(|q| to_camera * q), near, cam, (width, height))?;
    // The orientation as seen from the camera: the sign of
    // `(v0 − o) · ((v1 − v0) × (v2 − v0))`, which a ray hitting the triangle in
    // front of the camera gives its three edge functions.
    let n = (v1 - v0).cross(v2 - v0);
    let nc = n.dot(p[0]);
    if !nc.is_finite() || nc == 0.0 {
        return None;
    }
    // ±1; multiplying by it is exact.
    let s = nc.signum();
    // Edge `(a, b)`'s plane normal `(a − o) × (b − o)`, computed as
    // `(a − o) × (b − a)` (the same vector, without the cancellation of two
    // long, nearly parallel vectors when the edge is small and far), from
    // the edge's vertices in one canonical order, negated when the triangle
    // runs the other way: the two triangles sharing an edge get exact
    // negatives, which keeps the raster watertight.
    let edge = |(a, pa): (Vec3, Vec3), (b, pb): (Vec3, Vec3)| {
        let first = (a.x, a.y, a.z) <= (b.x, b.y, b.z);
        let m = if first {
            pa.cross(b - a)
        } else {
            -pb.cross(a - b)
        };
        [m.dot(f) * s, m.dot(r) * s, m.dot(up) * s]
    };
    let (q0, q1, q2) = ((v0, p[0]), (v1, p[1]), (v2, p[2]));
    let edges = [edge(q0, q1), edge(q1, q2), edge(q2, q0)];
    if edges.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    let ties = edges.map(|[_, b, c]| b > 0.0 || (b == 0.0 && c > 0.0));
    let depth = [n.dot(f) / nc, n.dot(r) / nc, n.dot(up) / nc];
    if !(depth.iter().all(|x| x.is_finite())) {
        return None;
    }
    Some(RasterTriangle {
        edges,
        ties,
        depth,
        slot,
        bounds,
    })
}

/// A triangle's bounds in pixels, `[x0, y0, x1, y1)` inside the image,
/// from its vertices in camera coordinates `(λ, λ·u, λ·v)`: the triangle
/// is clipped against the plane `λ = near` first (Sutherland–Hodgman on one
/// plane), and the bounds grown by two pixels, more than any sample lies
/// from its pixel. `None` when nothing is in front or nothing is inside.
fn bounds(
    q: [Vec3; 3],
    near: f32,
    cam: &CameraRays,
    (width, height): (usize, usize),
) -> Option<[u32; 4]> {
    let mut lo = Vec2::splat(f32::INFINITY);
    let mut hi = Vec2::splat(f32::NEG_INFINITY);
    let mut any = false;
    let mut add = |c: Vec3| {
        let px = cam.pixel_of(c.y / c.x, c.z / c.x);
        lo = lo.min(px);
        hi = hi.max(px);
        any = true;
    };
    for i in 0..3 {
        let (a, b) = (q[i], q[(i + 1) % 3]);
        let (ina, inb) = (a.x >= near, b.x >= near);
        if ina {
            add(a);
        }
        if ina != inb {
            let s = (near - a.x) / (b.x - a.x);
            let c = a + (b - a) * s;
            add(Vec3::new(near, c.y, c.z));
        }
    }
    if !any {
        return None;
    }
    const MARGIN: f32 = 2.0;
    // Clamped into the image; an infinite bound is the image's edge.
    let (w, h) = (width as f32, height as f32);
    let low = |x: f32, max: f32| {
        if x.is_nan() {
            0.0
        } else {
            (x - MARGIN).floor().clamp(0.0, max)
        }
    };
    let high = |x: f32, max: f32| {
        if x.is_nan() {
            max
        } else {
            ((x + MARGIN).floor() + 1.0).clamp(0.0, max)
        }
    };
    let (x0, y0, x1, y1) = (low(lo.x, w), low(lo.y, h), high(hi.x, w), high(hi.y, h));
    (x0 < x1 && y0 < y1).then_some([x0 as u32, y0 as u32, x1 as u32, y1 as u32])
}

/// The primary hit of the sample the rasteriser gave triangle `id`, along
/// the tracer's ray `(o, d)`: the tracer's own test on that triangle, or,
/// when it misses (a shared edge the two round differently), the traced
/// ray; `None` when the rasteriser found no triangle. Returns whether the
/// ray was traced too.
#[inline(always)]
pub fn primary_hit(bvh: &SceneBvh, id: u32, o: Vec3, d: Vec3) -> (Option<Hit>, bool) {
    if id == NONE {
        return (None, false);
    }
    match bvh.hit_on(id, o, d) {
        Some(h) => (Some(h), false),
        None => (bvh.closest(o, d, 0.0, f32::INFINITY), true),
    }
}
