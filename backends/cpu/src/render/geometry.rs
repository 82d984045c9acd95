//! Pass "geometry" of SRAA and SRAA-RT on a tile (the paper's pass 1,
//! "geometric information generation", §3.1–3.3): each pixel's four
//! subsamples traced or rasterised (`-hybrid`), with their shadow states
//! where the shaded samples around disagree, and their mirrors' reflections.

use super::*;

/// What the geometry pass reads of the shading pass's outputs, for the
/// subsample that is also the shaded sample and for the shadow agreement of
/// the others.
pub(super) struct ShadedSamples<'a> {
    pub(super) geo: &'a [Geometry],
    pub(super) values: &'a [Vec3],
    pub(super) shadow: &'a [u32],
    pub(super) geo2: &'a [Geometry],
    pub(super) shadow2: &'a [u32],
    pub(super) albedo: &'a [Vec3],
}

/// The geometry pass's outputs over a tile, row-major: per pixel its four
/// subsamples' geometry and, where their passes run, their shadow states,
/// their mirror hits' geometry and shadow states, and their albedo (empty
/// slices where they do not).
pub(super) struct TileSubsamples<'a> {
    pub(super) geo: &'a mut [[Geometry; 4]],
    pub(super) shadow: &'a mut [[u32; 4]],
    pub(super) geo2: &'a mut [[Geometry; 4]],
    pub(super) shadow2: &'a mut [[u32; 4]],
    pub(super) albedo: &'a mut [[Vec3; 4]],
}

/// Rays of [`trace_tile_subsamples`] traced together, as [`BATCH`] for SSAA.
const GEO_BATCH: usize = 64;

/// A group's adaptive subpixel shadow masks of the last pixel that needed
/// them: the pixel and its `(cast, inherited)` light masks
/// ([`shadow_agreement`]).
type Agreement = Option<(usize, (u32, u32))>;

/// The subsample each slot of a batch holds: pixel `i` of the tile,
/// subsample `k`.
type BatchJobs = [(usize, usize); GEO_BATCH];

/// The ray of each slot of a batch: origin, direction.
type BatchRays = [(Vec3, Vec3); GEO_BATCH];

/// The reflection rays of a batch's mirror hits: batch slot, the mirror
/// hit's distance, origin, direction.
type BatchReflections = [(usize, f32, Vec3, Vec3); GEO_BATCH];

/// Pass "geometry" (the paper's pass 1, "geometric information
/// generation") on `tile`: the four subsamples of each of its pixels, at the
/// tile's row-major index in `out`, each traced for geometry, albedo, shadow
/// states and its mirror's reflection as the plan asks, or, for the shaded
/// sample's subsample, copied from the shading pass (`shaded`, over
/// `region`).
///
/// The subsample rays go in batches of [`GEO_BATCH`]: generated, traversed,
/// their surfaces reconstructed and their geometry written, then their
/// shadow rays cast, then their mirrors' reflection rays generated,
/// traversed and reconstructed, then those hits' shadow rays. Every ray is
/// the one the subsample-at-a-time loop casts, with the same inputs, so every
/// value is the same bits; only the order of the work differs.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn trace_tile_subsamples(
    t: &Tracer,
    plan: &SubpixelPlan,
    cam: &CameraRays,
    shaded: &ShadedSamples,
    out: &mut TileSubsamples,
    found: Option<Rasterised>,
    tile: Rect,
    region: Rect,
    c: &mut Counts,
) {
    let (tw, rw) = (tile.width(), region.width());
    let dims = (rw, region.height());
    // Region coordinates and index of tile pixel `i`.
    let local = |i: usize| {
        let (lx, ly) = (tile.x0 - region.x0 + i % tw, tile.y0 - region.y0 + i / tw);
        (lx, ly, ly * rw + lx)
    };
    // The subsample each batch slot holds: pixel `i` of the tile, subsample
    // `k`.
    let mut job: BatchJobs = [(0usize, 0usize); GEO_BATCH];
    let mut ray: BatchRays = [(Vec3::ZERO, Vec3::ZERO); GEO_BATCH];
    let mut hit: [Option<Hit>; GEO_BATCH] = [None; GEO_BATCH];
    let mut surface: [Option<Surface>; GEO_BATCH] = [None; GEO_BATCH];
    // Reflection rays of the batch's mirror hits: batch slot, the mirror
    // hit's distance, origin, direction; their hits.
    let mut reflection: BatchReflections = [(0usize, 0.0f32, Vec3::ZERO, Vec3::ZERO); GEO_BATCH];
    let mut hit2: [Option<Hit>; GEO_BATCH] = [None; GEO_BATCH];
    // Adaptive subpixel shadows: the last pixel's (cast, inherited) masks
    // per group, computed on first use (a pixel whose subsamples all miss
    // needs none); a pixel's subsamples are consecutive in the batches.
    let mut primary_agree: Agreement = None;
    let mut secondary_agree: Agreement = None;
    let agreement = |cache: &mut Agreement, i: usize, bits: &[u32], first| match *cache {
        Some((p, a)) if p == i => a,
        _ => {
            let (lx, ly, _) = local(i);
            let a = plan.agreement(shaded.values, bits, first, (lx, ly), dims);
            *cache = Some((i, a));
            a
        }
    };
    let reflects = !out.geo2.is_empty() && t.reflection_depth > 0;

    let (mut next_i, mut next_k) = (0usize, 0usize);
    let total = tile.len();
    while next_i < total {
        // Generate: the shaded sample's subsample is copied, not traced.
        let mut m = 0;
        while m < GEO_BATCH && next_i < total {
            let (i, k) = (next_i, next_k);
            next_k += 1;
            if next_k == 4 {
                (next_i, next_k) = (next_i + 1, 0);
            }
            if Some(k) == plan.shaded_subsample {
                let (_, _, j) = local(i);
                copy_shaded_subsample(shaded, out, i, k, j);
                continue;
            }
            clear_traced_subsample(out, i, k);
            let (x, y) = (tile.x0 + i % tw, tile.y0 + i / tw);
            job[m] = (i, k);
            ray[m] = match found {
                Some(r) => {
                    let (_, u, v) = r.at(k, i % tw, i / tw);
                    cam.through(u, v)
                }
                None => cam.ray(pixel_centre(x, y) + SUBPIXEL_OFFSETS[k]),
            };
            m += 1;
        }
        // Traverse, or take the rasteriser's triangle (`-hybrid`).
        traverse_subsamples(t, found, tw, (&job, &ray, m), &mut hit, c);
        // Surfaces, geometry and albedo.
        for q in 0..m {
            let (i, k) = job[q];
            let (o, d) = ray[q];
            surface[q] = hit[q].map(|h| t.surface(o, d, h));
            out.geo[i][k] = t.primary_geometry(surface[q].as_ref());
            if let Some(a) = out.albedo.get_mut(i) {
                a[k] = t.primary_albedo(surface[q].as_ref());
            }
        }
        // Subpixel shadow rays.
        if !out.shadow.is_empty() {
            for q in 0..m {
                let Some(sf) = &surface[q] else { continue };
                let (i, k) = job[q];
                let (cast, inherited) = agreement(&mut primary_agree, i, shaded.shadow, 0);
                out.shadow[i][k] = t.shadow_states_masked(sf, cast, inherited, c);
            }
        }
        if !reflects {
            continue;
        }
        // Reflection rays of the mirror hits and their shadow rays.
        trace_reflections(
            t,
            plan,
            shaded,
            out,
            (&job, &ray, &surface, m),
            (&mut reflection, &mut hit2),
            (&agreement, &mut secondary_agree),
            c,
        );
    }
}

/// A subsample that is also the shaded sample (pixel `i`'s subsample `k`,
/// the region's sample `j`): everything the geometry pass writes for it
/// copied from the shading pass's outputs, not traced again.
#[inline(always)]
fn copy_shaded_subsample(
    shaded: &ShadedSamples,
    out: &mut TileSubsamples,
    i: usize,
    k: usize,
    j: usize,
) {
    out.geo[i][k] = shaded.geo[j];
    if let Some(ss) = out.shadow.get_mut(i) {
        ss[k] = shaded.shadow[j];
    }
    if let Some(g2) = out.geo2.get_mut(i) {
        g2[k] = shaded.geo2.get(j).copied().unwrap_or(NO_SECONDARY);
    }
    if let Some(s2) = out.shadow2.get_mut(i) {
        s2[k] = shaded.shadow2.get(j).copied().unwrap_or(0);
    }
    if let Some(a) = out.albedo.get_mut(i) {
        a[k] = shaded.albedo[j];
    }
}

/// What a traced subsample (pixel `i`'s subsample `k`) that misses, or hits
/// no mirror, keeps: the buffers hold the previous tile's, so they are
/// cleared before it is traced.
#[inline(always)]
fn clear_traced_subsample(out: &mut TileSubsamples, i: usize, k: usize) {
    if let Some(ss) = out.shadow.get_mut(i) {
        ss[k] = 0;
    }
    if let Some(g2) = out.geo2.get_mut(i) {
        g2[k] = NO_SECONDARY;
    }
    if let Some(s2) = out.shadow2.get_mut(i) {
        s2[k] = 0;
    }
}

/// The first `m` subsamples of a batch of [`trace_tile_subsamples`] (tile
/// pixel and subsample of each slot, and its ray) traversed into `hit`, or,
/// under `-hybrid`, on the rasteriser's triangle (`found`, over a tile `tw`
/// pixels wide). Counts the rays it casts.
#[inline(always)]
fn traverse_subsamples(
    t: &Tracer,
    found: Option<Rasterised>,
    tw: usize,
    (job, ray, m): (&BatchJobs, &BatchRays, usize),
    hit: &mut [Option<Hit>; GEO_BATCH],
    c: &mut Counts,
) {
    match found {
        None => {
            c.geometry += m as u64;
            for (h, (o, d)) in hit[..m].iter_mut().zip(&ray[..m]) {
                *h = t.bvh.closest(*o, *d, 0.0, f32::INFINITY);
            }
        }
        Some(r) => {
            for (q, (h, (o, d))) in hit[..m].iter_mut().zip(&ray[..m]).enumerate() {
                let (i, k) = job[q];
                let id = r.at(k, i % tw, i / tw).0;
                let (found, traced) = raster::primary_hit(t.bvh, id, *o, *d);
                c.geometry += traced as u64;
                *h = found;
            }
        }
    }
}

/// The reflection rays of a batch's mirror hits (§3.3), from the first `m`
/// slots of the batch (tile pixel and subsample, primary ray, surface):
/// generated into `reflection`, traversed into `hit2`, and their hits' geometry and,
/// where the pass runs, shadow states written, the shadow rays cast as
/// `agreement` finds the shaded samples' secondary shadow states disagree
/// (through the secondary group's cache). Counts the rays it casts.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn trace_reflections(
    t: &Tracer,
    plan: &SubpixelPlan,
    shaded: &ShadedSamples,
    out: &mut TileSubsamples,
    (job, ray, surface, m): (&BatchJobs, &BatchRays, &[Option<Surface>; GEO_BATCH], usize),
    (reflection, hit2): (&mut BatchReflections, &mut [Option<Hit>; GEO_BATCH]),
    (agreement, secondary_agree): (
        &impl Fn(&mut Agreement, usize, &[u32], usize) -> (u32, u32),
        &mut Agreement,
    ),
    c: &mut Counts,
) {
    let mut r = 0;
    for q in 0..m {
        let Some(sf) = &surface[q] else { continue };
        if t.scene.materials[sf.material as usize].mirror > 0.0 {
            let rd = Tracer::reflect(ray[q].1, sf.n);
            reflection[r] = (q, sf.t, sf.p + sf.ng * t.eps, rd);
            r += 1;
        }
    }
    c.geometry += r as u64;
    for (h, (_, _, o, d)) in hit2[..r].iter_mut().zip(&reflection[..r]) {
        *h = t.bvh.closest(*o, *d, 0.0, f32::INFINITY);
    }
    for (h, &(q, t1, o, d)) in hit2[..r].iter().zip(&reflection[..r]) {
        let (i, k) = job[q];
        out.geo2[i][k] = match h {
            None => Geometry::MISS,
            Some(h) => {
                let s2 = t.surface(o, d, *h);
                if !out.shadow2.is_empty() {
                    let first = plan.passes.layout.secondary_base();
                    let (cast, inherited) = agreement(secondary_agree, i, shaded.shadow2, first);
                    out.shadow2[i][k] = t.shadow_states_masked(&s2, cast, inherited, c);
                }
                Geometry::new(s2.n, t1 + s2.t)
            }
        };
    }
}

/// Adaptive subpixel shadow rays: which lights' shadow rays a subsample of pixel
/// `(x, y)` must cast, and the states it inherits for the others, from the
/// shaded samples of the neighbourhood its layers are reconstructed from (the
/// same pixels for all four subsamples). `bits` are those samples' shadow
/// states, `first` the index of the base layer of the group (light `l`'s layer
/// is `first + 1 + l`). Returns `(cast, inherited)` as light bit masks.
///
/// A light's ray is skipped when the neighbourhood agrees about it:
/// - every neighbour's layer of that light is exactly black (among them: all
///   shadowed): the layer reconstructs to 0 whatever the target's gate, so the
///   image is the same bit for bit;
/// - every neighbour is lit: the subsample inherits "lit". The image is the same
///   unless the subsample is in a shadow that no shaded sample around it sees:
///   there the exhaustive ray gates every neighbour out (eq. 2) and the
///   reconstruction falls back to the nearest shaded sample's (lit) colour,
///   while the inherited state gives the bilateral mean of the same lit
///   colours. Both are lit; neither can show that shadow.
///
/// The free answers ([`Tracer::shadow_states_masked`]: no incident light,
/// facing away) are still taken from the subsample's own surface.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn shadow_agreement(
    bits: &[u32],
    values: &[Vec3],
    nl: usize,
    first: usize,
    lights: usize,
    x: usize,
    y: usize,
    radius: u32,
    w: usize,
    h: usize,
) -> (u32, u32) {
    let all_lights = if lights >= 32 {
        u32::MAX
    } else {
        (1u32 << lights) - 1
    };
    let (mut all_shadowed, mut any_shadowed, mut dark) = (u32::MAX, 0u32, all_lights);
    // Only which pixels: the window `neighbourhood` visits (the square of
    // `radius` around the pixel, inside the image), in plain loops; the
    // result does not depend on the order.
    let r = radius as usize;
    let (x1, y1) = (
        x.saturating_add(r).saturating_add(1).min(w),
        y.saturating_add(r).saturating_add(1).min(h),
    );
    for yy in y.saturating_sub(r)..y1 {
        for xx in x.saturating_sub(r)..x1 {
            let jj = yy * w + xx;
            let b = bits.get(jj).copied().unwrap_or(0);
            all_shadowed &= b;
            any_shadowed |= b;
            for l in 0..lights {
                if values.get(jj * nl + first + 1 + l) != Some(&Vec3::ZERO) {
                    dark &= !(1 << l);
                }
            }
        }
    }
    let agreed = (all_shadowed | !any_shadowed | dark) & all_lights;
    (all_lights & !agreed, all_shadowed & all_lights)
}
