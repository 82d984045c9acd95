//! Triangle geometry: a flat list of triangles with per-vertex normals, uvs and a
//! material index each.

use glam::{Mat4, Vec2, Vec3};
use subcone_kernels::math::Euclidean;

/// Triangles, one entry per triangle in each vector.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub positions: Vec<[Vec3; 3]>,
    /// Per-vertex shading normals (the geometric normal when the source has none).
    pub normals: Vec<[Vec3; 3]>,
    /// Per-vertex texture coordinates (zero when the source has none).
    pub uvs: Vec<[Vec2; 3]>,
    /// Index into the scene's materials.
    pub materials: Vec<u32>,
}

/// What [`TriangleMesh::sanitize`] dropped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sanitized {
    /// Triangles with a NaN or infinite coordinate.
    pub non_finite: usize,
    /// Triangles with (numerically) zero area.
    pub degenerate: usize,
}

impl Sanitized {
    /// Whether anything was dropped.
    pub fn any(&self) -> bool {
        self.non_finite + self.degenerate > 0
    }
}

impl std::fmt::Display for Sanitized {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "dropped {} triangle(s) with NaN/Inf vertices and {} degenerate triangle(s)",
            self.non_finite, self.degenerate
        )
    }
}

impl TriangleMesh {
    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Add a flat-shaded triangle.
    pub fn push_flat(&mut self, v: [Vec3; 3], material: u32) {
        let n = (v[1] - v[0]).cross(v[2] - v[0]).unit_or_zero();
        self.push(v, [n; 3], [Vec2::ZERO; 3], material);
    }

    /// Add a triangle with normals and uvs.
    pub fn push(&mut self, v: [Vec3; 3], n: [Vec3; 3], uv: [Vec2; 3], material: u32) {
        self.positions.push(v);
        self.normals.push(n);
        self.uvs.push(uv);
        self.materials.push(material);
    }

    /// Add a planar quad `a b c d` (in order around its boundary) as two triangles.
    pub fn push_quad(&mut self, q: [Vec3; 4], material: u32) {
        self.push_flat([q[0], q[1], q[2]], material);
        self.push_flat([q[0], q[2], q[3]], material);
    }

    /// Add a floor at `y = 0` as a grid of `count.0 × count.1` quads of
    /// `step.0 × step.1`, the first at `(x, z) = corner`, column by column
    /// along `x` (smaller triangles make a better BVH than two huge ones).
    pub(crate) fn push_floor_grid(
        &mut self,
        corner: (f32, f32),
        step: (f32, f32),
        count: (u32, u32),
        material: u32,
    ) {
        for i in 0..count.0 {
            for k in 0..count.1 {
                let (x0, z0) = (corner.0 + step.0 * i as f32, corner.1 + step.1 * k as f32);
                let (x1, z1) = (x0 + step.0, z0 + step.1);
                self.push_quad(
                    [
                        Vec3::new(x0, 0.0, z0),
                        Vec3::new(x0, 0.0, z1),
                        Vec3::new(x1, 0.0, z1),
                        Vec3::new(x1, 0.0, z0),
                    ],
                    material,
                );
            }
        }
    }

    /// Add an axis-aligned box transformed by `m`.
    pub fn push_box(&mut self, m: Mat4, material: u32) {
        let c = |x: f32, y: f32, z: f32| m.transform_point3(Vec3::new(x, y, z));
        let (l, h) = (-0.5, 0.5);
        let faces = [
            [c(l, l, h), c(h, l, h), c(h, h, h), c(l, h, h)],
            [c(h, l, l), c(l, l, l), c(l, h, l), c(h, h, l)],
            [c(l, l, l), c(l, l, h), c(l, h, h), c(l, h, l)],
            [c(h, l, h), c(h, l, l), c(h, h, l), c(h, h, h)],
            [c(l, h, h), c(h, h, h), c(h, h, l), c(l, h, l)],
            [c(l, l, l), c(h, l, l), c(h, l, h), c(l, l, h)],
        ];
        for f in faces {
            self.push_quad(f, material);
        }
    }

    /// Add a UV sphere with smooth normals.
    pub fn push_sphere(
        &mut self,
        centre: Vec3,
        radius: f32,
        rings: u32,
        segments: u32,
        material: u32,
    ) {
        let p = |i: u32, j: u32| {
            // Exact poles, so that the zero-area triangles there are skipped
            // (sin π is not 0 in f32: the pole would be a ring of slivers).
            if i == 0 {
                return Vec3::Y;
            }
            if i >= rings {
                return Vec3::NEG_Y;
            }
            let th = std::f32::consts::PI * i as f32 / rings as f32;
            let ph = std::f32::consts::TAU * j as f32 / segments as f32;
            Vec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin())
        };
        for i in 0..rings {
            for j in 0..segments {
                let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
                for t in [[a, c, b], [a, d, c]] {
                    let v = t.map(|n| centre + radius * n);
                    if (v[1] - v[0]).cross(v[2] - v[0]).length_squared() > 0.0 {
                        self.push(v, t, [Vec2::ZERO; 3], material);
                    }
                }
            }
        }
    }

    /// Append another mesh.
    pub fn extend(&mut self, other: &TriangleMesh) {
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.uvs.extend_from_slice(&other.uvs);
        self.materials.extend_from_slice(&other.materials);
    }

    /// Drop triangles that would poison a BVH or a hit: NaN/Inf coordinates and
    /// zero-area triangles (including those whose squared doubled area is not a
    /// normal f32, which the renderers divide by). Non-finite or zero normals are replaced by the
    /// geometric normal, non-finite uvs by zero. Returns what was dropped.
    pub fn sanitize(&mut self) -> Sanitized {
        let mut s = Sanitized::default();
        let mut keep = 0;
        for i in 0..self.positions.len() {
            let v = self.positions[i];
            if !v.iter().all(|p| p.is_finite()) {
                s.non_finite += 1;
                continue;
            }
            let cross = (v[1] - v[0]).cross(v[2] - v[0]);
            let scale = (v[1] - v[0])
                .length_squared()
                .max((v[2] - v[0]).length_squared());
            // Zero area, area below f32 resolution relative to the edges, or
            // a squared area outside f32's normal range (renderers divide by
            // it to get barycentrics).
            let area2 = cross.length_squared();
            if !(area2.is_finite() && area2 >= f32::MIN_POSITIVE) || area2 <= scale * scale * 1e-14
            {
                s.degenerate += 1;
                continue;
            }
            let geo = cross.unit();
            let mut n = self.normals[i];
            for k in &mut n {
                if !k.is_finite() || k.length_squared() < 1e-12 {
                    *k = geo;
                } else {
                    // By the largest component first, so that huge normals
                    // (whose squared length overflows) stay unit.
                    *k = (*k / k.abs().max_element()).unit();
                }
            }
            let mut uv = self.uvs[i];
            for k in &mut uv {
                if !k.is_finite() {
                    *k = Vec2::ZERO;
                }
            }
            self.positions[keep] = v;
            self.normals[keep] = n;
            self.uvs[keep] = uv;
            self.materials[keep] = self.materials[i];
            keep += 1;
        }
        self.positions.truncate(keep);
        self.normals.truncate(keep);
        self.uvs.truncate(keep);
        self.materials.truncate(keep);
        s
    }

    /// Bounds `(min, max)`, or `None` when empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut it = self.positions.iter().flatten();
        let first = *it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))))
    }
}
