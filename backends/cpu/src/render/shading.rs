//! Pass "shading" of SRAA and SRAA-RT on a tile's region (the paper's
//! shaded samples, §3): each pixel's one shaded sample traced or rasterised
//! (`-hybrid`), shaded (shadow rays, ambient occlusion, the mirror's
//! reflection) and kept as the plan's layers.

use super::*;

/// Pass "shading" over `region`: the shaded sample of every pixel in it, at
/// the region's row-major index in `out`.
#[inline(always)]
pub(super) fn shade_region(
    t: &Tracer,
    plan: &SubpixelPlan,
    cam: &CameraRays,
    out: &mut ShadedRegion,
    found: Option<Rasterised>,
    region: Rect,
    c: &mut Counts,
) {
    let (rw, nl) = (region.width(), plan.nl);
    for i in 0..region.len() {
        // What `shade_pixel` leaves unwritten (a miss, no mirror, no light)
        // is what a fresh buffer holds; these hold the previous tile's.
        out.values[i * nl..(i + 1) * nl].fill(Vec3::ZERO);
        if let Some(s) = out.shadow.get_mut(i) {
            *s = 0;
        }
        if let Some(g2) = out.geo2.get_mut(i) {
            *g2 = NO_SECONDARY;
        }
        if let Some(s2) = out.shadow2.get_mut(i) {
            *s2 = 0;
        }
        if let Some(a) = out.albedo.get_mut(i) {
            *a = Vec3::ZERO;
        }
        let (x, y) = (region.x0 + i % rw, region.y0 + i / rw);
        let found = found.map(|r| r.at(0, i % rw, i / rw));
        shade_pixel(t, plan, cam, out, (i, found), x, y, c);
    }
}

/// The shading pass's outputs over a tile's region, row-major: per pixel
/// the shaded sample's geometry, its layers and, where their passes run, its
/// shadow states, its mirror hit's geometry and shadow states, and its
/// albedo (empty slices where they do not).
pub(super) struct ShadedRegion<'a> {
    pub(super) geo: &'a mut [Geometry],
    pub(super) values: &'a mut [Vec3],
    pub(super) shadow: &'a mut [u32],
    pub(super) geo2: &'a mut [Geometry],
    pub(super) shadow2: &'a mut [u32],
    pub(super) albedo: &'a mut [Vec3],
}

/// The shaded sample of pixel `(x, y)`, index `i` of its region: traced,
/// shaded (shadow rays, ambient occlusion, the mirror's reflection) and kept
/// as the plan's layers.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn shade_pixel(
    t: &Tracer,
    plan: &SubpixelPlan,
    cam: &CameraRays,
    out: &mut ShadedRegion,
    (i, found): (usize, Option<(u32, f32, f32)>),
    x: usize,
    y: usize,
    c: &mut Counts,
) {
    let (layout, nl, lights) = (&plan.passes.layout, plan.nl, plan.lights);
    // `-hybrid`: the raster's triangle and the coordinates it computed for
    // the ray (`cam.ray(p)` is `cam.through(u(p.x), v(p.y))`).
    let (o, d) = match found {
        Some((_, u, v)) => cam.through(u, v),
        None => cam.ray(pixel_centre(x, y) + plan.shaded_offset),
    };
    let id = found.map(|f| f.0);
    let v = &mut out.values[i * nl..(i + 1) * nl];
    let Some(sf) = primary_hit(t, id, o, d, c) else {
        out.geo[i] = Geometry::MISS;
        v[0] = t.scene.background;
        if let Some(g2) = out.geo2.get_mut(i) {
            *g2 = NO_SECONDARY;
        }
        return;
    };
    c.shaded += 1;
    out.geo[i] = t.primary_geometry(Some(&sf));
    if let Some(a) = out.albedo.get_mut(i) {
        *a = t.primary_albedo(Some(&sf));
    }
    let sh = if plan.passes.shadows {
        t.shadow_states(&sf, c)
    } else {
        0
    };
    let ao = t.ambient_occlusion(&sf, c);
    let parts = t.parts(&sf, sh, ao);
    let m = parts.mirror;
    let reflects = m > 0.0 && plan.passes.secondary_shading && t.reflection_depth > 0;
    if layout.single {
        let diffuse = parts.diffuse(lights);
        v[0] = if reflects {
            c.secondary += 1;
            let r = t.radiance(sf.p + sf.ng * t.eps, Tracer::reflect(d, sf.n), 1, c);
            (1.0 - m) * diffuse + m * r
        } else if m > 0.0 {
            (1.0 - m) * diffuse
        } else {
            diffuse
        };
        return;
    }
    // SRAA-RT layers: primary base, then one per light.
    if layout.lights > 0 {
        out.shadow[i] = sh;
        v[0] = (1.0 - m) * parts.base;
        for l in 0..layout.lights {
            v[1 + l] = (1.0 - m) * parts.direct[l];
        }
    } else {
        v[0] = (1.0 - m) * parts.diffuse(lights);
    }
    if !reflects {
        return;
    }
    c.secondary += 1;
    let rd = Tracer::reflect(d, sf.n);
    let secondary = (&mut *out.geo2, &mut *out.shadow2);
    shade_reflection(t, plan, (&sf, rd, m), v, secondary, i, c);
}

/// The rasteriser's answer over a rectangle (`-hybrid`): each sample's
/// triangle and the image-plane coordinates of its ray, in
/// [`Raster::rasterise`]'s layout.
#[derive(Clone, Copy)]
pub(super) struct Rasterised<'a> {
    ids: &'a [u32],
    u: &'a [f32],
    v: &'a [f32],
    cols: usize,
    rows: usize,
}

impl<'a> Rasterised<'a> {
    pub(super) fn of(s: &'a HybridScratch, rect: Rect) -> Self {
        Rasterised {
            ids: &s.ids,
            u: &s.u,
            v: &s.v,
            cols: rect.width(),
            rows: rect.height(),
        }
    }

    /// Sample `k` of the rectangle's pixel `(x, y)`: its triangle and `(u, v)`.
    #[inline(always)]
    pub(super) fn at(&self, k: usize, x: usize, y: usize) -> (u32, f32, f32) {
        (
            self.ids[(k * self.rows + y) * self.cols + x],
            self.u[k * self.cols + x],
            self.v[k * self.rows + y],
        )
    }
}

/// The shaded sample's surface along `(o, d)`: traced, or on the
/// rasteriser's triangle `id` (`-hybrid`, [`raster::primary_hit`]). Counts
/// the rays it casts.
#[inline(always)]
fn primary_hit(t: &Tracer, id: Option<u32>, o: Vec3, d: Vec3, c: &mut Counts) -> Option<Surface> {
    let hit = match id {
        None => {
            c.primary += 1;
            t.bvh.closest(o, d, 0.0, f32::INFINITY)
        }
        Some(id) => {
            let (hit, traced) = raster::primary_hit(t.bvh, id, o, d);
            c.primary += traced as u64;
            hit
        }
    };
    hit.map(|h| t.surface(o, d, h))
}

/// SRAA-RT's secondary layers of a shaded sample on a mirror `sf` of
/// reflectance `m` (§3.3): the reflection ray along `rd` traced and shaded, its hit's geometry and
/// shadow states kept for the subsamples' reflected layers, its radiance
/// split as the primary's (times the mirror's reflectance), or folded into
/// the primary base when the layout has no secondary layers.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn shade_reflection(
    t: &Tracer,
    plan: &SubpixelPlan,
    (sf, rd, m): (&Surface, Vec3, f32),
    v: &mut [Vec3],
    (geo2, shadow2): (&mut [Geometry], &mut [u32]),
    i: usize,
    c: &mut Counts,
) {
    let (layout, lights) = (&plan.passes.layout, plan.lights);
    let sb = layout.secondary_base();
    match t.intersect(sf.p + sf.ng * t.eps, rd, 0.0) {
        None => {
            if let Some(g2) = geo2.get_mut(i) {
                *g2 = Geometry::MISS;
            }
            let bg = m * t.scene.background;
            if layout.secondary {
                v[sb] = bg;
            } else {
                v[0] += bg;
            }
        }
        Some(s2) => {
            c.shaded += 1;
            let sh2 = if plan.passes.shadows {
                t.shadow_states(&s2, c)
            } else {
                0
            };
            // No ambient occlusion at mirror hits.
            let p2 = t.parts(&s2, sh2, 1.0);
            let m2 = p2.mirror;
            let deeper = if m2 > 0.0 && t.reflection_depth > 1 {
                c.secondary += 1;
                t.radiance(s2.p + s2.ng * t.eps, Tracer::reflect(rd, s2.n), 2, c)
            } else {
                Vec3::ZERO
            };
            if layout.secondary {
                geo2[i] = Geometry::new(s2.n, sf.t + s2.t);
                if layout.lights > 0 {
                    shadow2[i] = sh2;
                    v[sb] = m * ((1.0 - m2) * p2.base + m2 * deeper);
                    for l in 0..layout.lights {
                        v[sb + 1 + l] = m * (1.0 - m2) * p2.direct[l];
                    }
                } else {
                    v[sb] = m * ((1.0 - m2) * p2.diffuse(lights) + m2 * deeper);
                }
            } else {
                // Reflections forced off: fold them into the primary base.
                v[0] += m * ((1.0 - m2) * p2.diffuse(lights) + m2 * deeper);
            }
        }
    }
}
