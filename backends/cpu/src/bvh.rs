//! The scene's triangles in an obvhs CWBVH: closest hits and occlusion.

use std::time::{Duration, Instant};
use subcone_kernels::math::Euclidean;

use glam::{UVec2, Vec2, Vec3, Vec3A};
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use subcone_scene::TriangleMesh;

/// obvhs' `Ray::new` written out here, the same operations (its
/// `safe_inverse` per component) so the same bits: obvhs' function is not
/// `#[inline]`, so each ray was a call out of the instruction-set path into
/// a baseline-compiled copy with three scalar divisions behind branches.
/// (It leaves out the finiteness `debug_assert!`s of obvhs' function.)
#[inline(always)]
fn make_ray(origin: Vec3, direction: Vec3, tmin: f32, tmax: f32) -> Ray {
    let (origin, direction) = (Vec3A::from(origin), Vec3A::from(direction));
    #[inline(always)]
    fn safe_inverse(x: f32) -> f32 {
        if x.abs() <= f32::EPSILON {
            x.signum() / f32::EPSILON
        } else {
            1.0 / x
        }
    }
    Ray {
        origin,
        direction,
        inv_direction: Vec3A::new(
            safe_inverse(direction.x),
            safe_inverse(direction.y),
            safe_inverse(direction.z),
        ),
        tmin,
        tmax,
    }
}

/// A triangle prepared for obvhs' Möller–Trumbore test
/// (`obvhs::triangle::Triangle::intersect`): its first vertex, its two edges
/// and their cross product, which obvhs derives from the vertices at every
/// test. The test below is obvhs' with those values read instead, the same
/// operations in the same order, so the same `t`, bit for bit; and it also
/// returns the hit's barycentrics, which obvhs computes and drops.
#[derive(Clone, Copy, Debug)]
struct PreparedTriangle {
    v0: Vec3A,
    /// `v0 − v1` (obvhs' sign).
    e1: Vec3A,
    /// `v2 − v0`.
    e2: Vec3A,
    /// `e1 × e2`.
    n: Vec3A,
}

impl PreparedTriangle {
    fn new(t: &Triangle) -> Self {
        let e1 = t.v0 - t.v1;
        let e2 = t.v2 - t.v0;
        PreparedTriangle {
            v0: t.v0,
            e1,
            e2,
            n: e1.cross(e2),
        }
    }

    /// `(t, u, v)` of `ray`'s hit, `t` in `[ray.tmin, ray.tmax]`, or `t = ∞`
    /// on a miss. The hit point is `(1 − u − v)·v0 + u·v1 + v·v2`.
    ///
    /// Domain: any ray. A degenerate triangle (`n · d = 0`) or a NaN
    /// anywhere is a miss (every comparison with NaN fails), as in obvhs.
    #[inline(always)]
    fn intersect(&self, ray: &Ray) -> (f32, f32, f32) {
        let c = self.v0 - ray.origin;
        let r = ray.direction.cross(c);
        let inv_det = 1.0 / self.n.dot(ray.direction);
        let u = r.dot(self.e2) * inv_det;
        let v = r.dot(self.e1) * inv_det;
        let w = 1.0 - u - v;
        // obvhs' test: every barycentric's sign bit clear (so `-0.0` misses).
        let hit = u.to_bits() | v.to_bits() | w.to_bits();
        if inv_det != 0.0 && hit & 0x8000_0000 == 0 {
            let t = self.n.dot(c) * inv_det;
            if t >= ray.tmin && t <= ray.tmax {
                return (t, u, v);
            }
        }
        (f32::INFINITY, 0.0, 0.0)
    }
}

/// A closest hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray direction.
    pub t: f32,
    /// Index of the triangle in the scene's mesh.
    pub triangle: u32,
    /// Index of the triangle in BVH order ([`SceneBvh::shading`]).
    pub slot: u32,
    /// The intersector's barycentrics `(u, v)`: the hit point is
    /// `(1 − u − v)·v0 + u·v1 + v·v2` of the mesh's triangle.
    pub barycentrics: Vec2,
}

/// What hit reconstruction reads of one triangle beside the intersector's
/// barycentrics, precomputed once per scene and laid out in BVH order: the
/// same values, computed by the same operations, that a hit would otherwise
/// derive from the mesh each time.
#[derive(Clone, Copy, Debug)]
pub struct TriangleShading {
    /// `(v1 − v0) × (v2 − v0)` normalised (zero for a degenerate triangle).
    pub normal: Vec3A,
    /// Per-vertex shading normals.
    pub normals: [Vec3A; 3],
    /// Per-vertex texture coordinates.
    pub uvs: [Vec2; 3],
    /// Material index.
    pub material: u32,
}

impl TriangleShading {
    fn new(mesh: &TriangleMesh, i: usize) -> Self {
        let [v0, v1, v2] = mesh.positions[i].map(Vec3A::from);
        TriangleShading {
            normal: (v1 - v0).cross(v2 - v0).normalize_or_zero(),
            normals: mesh.normals[i].map(Vec3A::from),
            uvs: mesh.uvs[i],
            material: mesh.materials[i],
        }
    }
}

/// A CWBVH over a mesh, with the triangles laid out in BVH order.
pub struct SceneBvh {
    bvh: CwBvh,
    /// Triangles in `bvh.primitive_indices` order, so leaves index them
    /// directly: what obvhs' own intersector reads (the raw traversal).
    triangles: Vec<Triangle>,
    /// The same triangles prepared for the pipeline's intersector.
    prepared: Vec<PreparedTriangle>,
    /// Whether each triangle (in BVH order) blocks shadow rays. Emitters do not:
    /// a point light placed at a drawn light quad must not be shadowed by it.
    casts_shadow: Vec<bool>,
    /// Hit reconstruction data, in BVH order.
    shading: Vec<TriangleShading>,
    /// Time the build took.
    pub build_time: Duration,
    /// Length of the scene's bounding-box diagonal, for ray offsets.
    pub scale: f32,
}

impl SceneBvh {
    /// Build the BVH (obvhs' medium-quality PLOC build). `casts_shadow(i)` says
    /// whether triangle `i` of the mesh blocks shadow rays.
    pub fn build(mesh: &TriangleMesh, casts_shadow: impl Fn(usize) -> bool) -> Self {
        let start = Instant::now();
        let tris: Vec<Triangle> = mesh
            .positions
            .iter()
            .map(|v| Triangle {
                v0: v[0].into(),
                v1: v[1].into(),
                v2: v[2].into(),
            })
            .collect();
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let triangles: Vec<Triangle> = bvh
            .primitive_indices
            .iter()
            .map(|&i| tris[i as usize])
            .collect();
        let prepared = triangles.iter().map(PreparedTriangle::new).collect();
        let casts_shadow = bvh
            .primitive_indices
            .iter()
            .map(|&i| casts_shadow(i as usize))
            .collect();
        let shading = bvh
            .primitive_indices
            .iter()
            .map(|&i| TriangleShading::new(mesh, i as usize))
            .collect();
        let scale = mesh
            .bounds()
            .map(|(lo, hi)| (hi - lo).norm())
            .unwrap_or(1.0)
            .max(f32::MIN_POSITIVE);
        SceneBvh {
            bvh,
            triangles,
            prepared,
            casts_shadow,
            shading,
            build_time: start.elapsed(),
            scale,
        }
    }

    /// The hit reconstruction data of triangle `slot` (BVH order, [`Hit::slot`]).
    #[inline(always)]
    pub fn shading(&self, slot: u32) -> &TriangleShading {
        &self.shading[slot as usize]
    }

    /// Triangles in the BVH.
    pub fn len(&self) -> usize {
        self.prepared.len()
    }

    /// Whether the BVH holds no triangle.
    pub fn is_empty(&self) -> bool {
        self.prepared.is_empty()
    }

    /// The vertices of triangle `slot` (BVH order). Panics if `slot ≥
    /// len()`.
    pub fn vertices(&self, slot: u32) -> [Vec3; 3] {
        let t = &self.triangles[slot as usize];
        [t.v0.into(), t.v1.into(), t.v2.into()]
    }

    /// The hit of `origin + t·dir`, `t ≥ 0`, on triangle `slot` alone (BVH
    /// order), by the intersector [`Self::closest`] runs: when the traversal
    /// finds this triangle, the same [`Hit`], bit for bit. `None` on a miss
    /// or for a slot out of range. The rasteriser's hits
    /// ([`crate::raster::primary_hit`]).
    #[inline(always)]
    pub fn hit_on(&self, slot: u32, origin: Vec3, dir: Vec3) -> Option<Hit> {
        let tri = self.prepared.get(slot as usize)?;
        // The intersector reads the origin, the direction and the range,
        // not the inverse direction (the traversal's).
        let ray = Ray {
            origin: origin.into(),
            direction: dir.into(),
            inv_direction: Vec3A::ZERO,
            tmin: 0.0,
            tmax: f32::INFINITY,
        };
        let (t, u, v) = tri.intersect(&ray);
        (t < ray.tmax).then(|| Hit {
            t,
            triangle: self.bvh.primitive_indices[slot as usize],
            slot,
            barycentrics: Vec2::new(u, v),
        })
    }

    /// Closest hit along `origin + t·dir`, `t` in `(tmin, tmax]`.
    ///
    /// obvhs' `CwBvh::ray_traverse`, written out here from its `traverse!`
    /// macro so that the traversal and the intersector are inlined into the
    /// caller, and so compiled for the instruction-set path it runs on
    /// ([`crate::isa::Isa::run`]). Each triangle is tested by obvhs'
    /// intersector on prepared edges (the same `t`, bit for bit), which also
    /// gives the hit's barycentrics.
    #[inline(always)]
    pub fn closest(&self, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> Option<Hit> {
        let ray = make_ray(origin, dir, tmin, tmax);
        let prepared = &self.prepared;
        let (t, slot, u, v) = self.closest_by(ray, |i, r| prepared[i].intersect(r));
        (t < ray.tmax).then(|| Hit {
            t,
            triangle: self.bvh.primitive_indices[slot as usize],
            slot,
            barycentrics: Vec2::new(u, v),
        })
    }

    /// `(t, slot, u, v)` of the closest hit of `ray` by the intersector
    /// `test(slot, ray) = (t, u, v)` (`t` is `ray.tmax` or more on a miss).
    #[inline(always)]
    fn closest_by(
        &self,
        ray: Ray,
        test: impl Fn(usize, &Ray) -> (f32, f32, f32),
    ) -> (f32, u32, f32, f32) {
        let mut hit = RayHit::none();
        let (mut u, mut v) = (0.0, 0.0);
        let bvh = &self.bvh;
        let mut traverse_ray = ray;
        let mut state = bvh.new_traversal(ray.direction);
        let mut node;
        obvhs::traverse!(
            bvh,
            node,
            state,
            node.intersect_ray(&traverse_ray, state.oct_inv4),
            {
                let (t, tu, tv) = test(state.primitive_id as usize, &traverse_ray);
                if t < traverse_ray.tmax {
                    hit.primitive_id = state.primitive_id;
                    hit.t = t;
                    (u, v) = (tu, tv);
                    traverse_ray.tmax = t;
                }
            }
        );
        (hit.t, hit.primitive_id, u, v)
    }

    /// Whether anything for which `blocks(slot)` holds crosses `ray`: obvhs'
    /// `ray_traverse_miss`, written out from `traverse!` to be inlined.
    #[inline(always)]
    fn any_hit(&self, ray: Ray, blocks: impl Fn(usize, &Ray) -> bool) -> bool {
        let bvh = &self.bvh;
        let mut state = bvh.new_traversal(ray.direction);
        let mut node;
        let mut hit = false;
        'outer: {
            obvhs::traverse!(
                bvh,
                node,
                state,
                node.intersect_ray(&ray, state.oct_inv4),
                {
                    if blocks(state.primitive_id as usize, &ray) {
                        hit = true;
                        break 'outer;
                    }
                }
            );
        }
        hit
    }

    /// Whether anything blocks `origin + t·dir` for `t` in `(tmin, tmax)`.
    /// (`ray_traverse_miss` stops at the first blocker; `ray_traverse_anyhit`
    /// would visit every one.)
    #[inline(always)]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> bool {
        let ray = make_ray(origin, dir, tmin, tmax);
        let (casts, prepared) = (&self.casts_shadow, &self.prepared);
        self.any_hit(ray, |id, r| {
            casts[id] && prepared[id].intersect(r).0 < r.tmax
        })
    }

    /// obvhs' raw `ray_traverse_miss`, for throughput comparisons: every
    /// triangle blocks, each tested by obvhs' own intersector, nothing else
    /// is done.
    #[inline(always)]
    pub fn raw_occluded(&self, origin: Vec3, dir: Vec3, tmax: f32) -> bool {
        let ray = make_ray(origin, dir, 0.0, tmax);
        let tris = &self.triangles;
        self.any_hit(ray, |id, r| tris[id].intersect(r) < r.tmax)
    }

    /// The raw traversal, for throughput comparisons: closest hit of each ray
    /// by obvhs' own intersector, nothing else.
    #[inline(always)]
    pub fn raw_closest_t(&self, origin: Vec3, dir: Vec3) -> f32 {
        let ray = make_ray(origin, dir, 0.0, f32::INFINITY);
        let tris = &self.triangles;
        self.closest_by(ray, |i, r| (tris[i].intersect(r), 0.0, 0.0))
            .0
    }
}
