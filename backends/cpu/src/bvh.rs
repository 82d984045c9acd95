//! The scene's triangles in an obvhs CWBVH: closest hits and occlusion.

use std::time::{Duration, Instant};

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

/// A closest hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray direction.
    pub t: f32,
    /// Index of the triangle in the scene's mesh.
    pub triangle: u32,
    /// Index of the triangle in BVH order ([`SceneBvh::shading`]).
    pub slot: u32,
}

/// What hit reconstruction reads of one triangle, precomputed once per
/// scene and laid out in BVH order beside the intersector's triangles: the
/// same values, computed by the same operations, that a hit would otherwise
/// derive from the mesh each time.
#[derive(Clone, Copy, Debug)]
pub struct TriangleShading {
    /// First vertex.
    pub v0: Vec3A,
    /// `v1 − v0`.
    pub e1: Vec3A,
    /// `v2 − v0`.
    pub e2: Vec3A,
    /// `e1 × e2` (twice the area, along the normal).
    pub cross: Vec3A,
    /// `|e1 × e2|²`, at least `f32::MIN_POSITIVE`.
    pub area2: f32,
    /// `e1 × e2` normalised (zero for a degenerate triangle).
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
        let (e1, e2) = (v1 - v0, v2 - v0);
        let cross = e1.cross(e2);
        TriangleShading {
            v0,
            e1,
            e2,
            cross,
            area2: cross.length_squared().max(f32::MIN_POSITIVE),
            normal: cross.normalize_or_zero(),
            normals: mesh.normals[i].map(Vec3A::from),
            uvs: mesh.uvs[i],
            material: mesh.materials[i],
        }
    }
}

/// A CWBVH over a mesh, with the triangles laid out in BVH order.
pub struct SceneBvh {
    bvh: CwBvh,
    /// Triangles in `bvh.primitive_indices` order, so leaves index them directly.
    triangles: Vec<Triangle>,
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
        let triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| tris[i as usize])
            .collect();
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
            .map(|(lo, hi)| (hi - lo).length())
            .unwrap_or(1.0)
            .max(f32::MIN_POSITIVE);
        SceneBvh {
            bvh,
            triangles,
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

    /// Closest hit along `origin + t·dir`, `t` in `(tmin, tmax]`.
    ///
    /// obvhs' `CwBvh::ray_traverse`, written out here from its `traverse!`
    /// macro so that the traversal and the intersector are inlined into the
    /// caller, and so compiled for the instruction-set path it runs on
    /// ([`crate::isa::Isa::run`]).
    #[inline(always)]
    pub fn closest(&self, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> Option<Hit> {
        let ray = make_ray(origin, dir, tmin, tmax);
        let t = self.closest_slot(ray);
        (t.0 < ray.tmax).then(|| Hit {
            t: t.0,
            triangle: self.bvh.primitive_indices[t.1 as usize],
            slot: t.1,
        })
    }

    /// `(t, slot)` of the closest hit of `ray` (`t` is `ray.tmax` or more on a miss).
    #[inline(always)]
    fn closest_slot(&self, ray: Ray) -> (f32, u32) {
        let mut hit = RayHit::none();
        let tris = &self.triangles;
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
                let t = tris[state.primitive_id as usize].intersect(&traverse_ray);
                if t < traverse_ray.tmax {
                    hit.primitive_id = state.primitive_id;
                    hit.t = t;
                    traverse_ray.tmax = t;
                }
            }
        );
        (hit.t, hit.primitive_id)
    }

    /// Whether anything for which `blocks(slot)` holds crosses `ray`: obvhs'
    /// `ray_traverse_miss`, written out from `traverse!` to be inlined.
    #[inline(always)]
    fn any_hit(&self, ray: Ray, blocks: impl Fn(usize) -> bool) -> bool {
        let tris = &self.triangles;
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
                    let id = state.primitive_id as usize;
                    if blocks(id) && tris[id].intersect(&ray) < ray.tmax {
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
        let casts = &self.casts_shadow;
        self.any_hit(ray, |id| casts[id])
    }

    /// obvhs' raw `ray_traverse_miss`, for throughput comparisons: every
    /// triangle blocks, nothing else is done.
    #[inline(always)]
    pub fn raw_occluded(&self, origin: Vec3, dir: Vec3, tmax: f32) -> bool {
        let ray = make_ray(origin, dir, 0.0, tmax);
        self.any_hit(ray, |_| true)
    }

    /// The raw traversal, for throughput comparisons: closest hit of each ray,
    /// nothing else.
    #[inline(always)]
    pub fn raw_closest_t(&self, origin: Vec3, dir: Vec3) -> f32 {
        let ray = make_ray(origin, dir, 0.0, f32::INFINITY);
        self.closest_slot(ray).0
    }
}
