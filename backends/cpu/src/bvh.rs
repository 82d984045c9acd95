//! The scene's triangles in an obvhs CWBVH: closest hits and occlusion.

use std::time::{Duration, Instant};

use glam::{Vec3, Vec3A};
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use subcone_scene::TriangleMesh;

/// A closest hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the (unit) ray direction.
    pub t: f32,
    /// Index of the triangle in the scene's mesh.
    pub triangle: u32,
}

/// A CWBVH over a mesh, with the triangles laid out in BVH order.
pub struct SceneBvh {
    bvh: CwBvh,
    /// Triangles in `bvh.primitive_indices` order, so leaves index them directly.
    triangles: Vec<Triangle>,
    /// Whether each triangle (in BVH order) blocks shadow rays. Emitters do not:
    /// a point light placed at a drawn light quad must not be shadowed by it.
    casts_shadow: Vec<bool>,
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
        let scale = mesh
            .bounds()
            .map(|(lo, hi)| (hi - lo).length())
            .unwrap_or(1.0)
            .max(f32::MIN_POSITIVE);
        SceneBvh {
            bvh,
            triangles,
            casts_shadow,
            build_time: start.elapsed(),
            scale,
        }
    }

    /// Closest hit along `origin + t·dir`, `t` in `(tmin, tmax]`.
    #[inline]
    pub fn closest(&self, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> Option<Hit> {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(dir), tmin, tmax);
        let mut hit = RayHit::none();
        let tris = &self.triangles;
        if self
            .bvh
            .ray_traverse(ray, &mut hit, |r, id| tris[id].intersect(r))
        {
            let triangle = self.bvh.primitive_indices[hit.primitive_id as usize];
            Some(Hit { t: hit.t, triangle })
        } else {
            None
        }
    }

    /// Whether anything blocks `origin + t·dir` for `t` in `(tmin, tmax)`.
    /// (`ray_traverse_miss` stops at the first blocker; `ray_traverse_anyhit`
    /// would visit every one.)
    #[inline]
    pub fn occluded(&self, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> bool {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(dir), tmin, tmax);
        let (tris, casts) = (&self.triangles, &self.casts_shadow);
        !self.bvh.ray_traverse_miss(ray, |r, id| {
            if casts[id] {
                tris[id].intersect(r)
            } else {
                f32::INFINITY
            }
        })
    }

    /// obvhs' raw `ray_traverse_miss`, for throughput comparisons: every
    /// triangle blocks, nothing else is done.
    pub fn raw_occluded(&self, origin: Vec3, dir: Vec3, tmax: f32) -> bool {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(dir), 0.0, tmax);
        let tris = &self.triangles;
        !self
            .bvh
            .ray_traverse_miss(ray, |r, id| tris[id].intersect(r))
    }

    /// The raw traversal, for throughput comparisons: closest hit of each ray,
    /// nothing else.
    pub fn raw_closest_t(&self, origin: Vec3, dir: Vec3) -> f32 {
        let ray = Ray::new(Vec3A::from(origin), Vec3A::from(dir), 0.0, f32::INFINITY);
        let mut hit = RayHit::none();
        let tris = &self.triangles;
        self.bvh
            .ray_traverse(ray, &mut hit, |r, id| tris[id].intersect(r));
        hit.t
    }
}
