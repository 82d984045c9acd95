//! A procedural arcade in the spirit of Sponza: a courtyard between two rows of
//! columns joined by round arches, an upper gallery with thin railing bars, and
//! a reflective stone floor under a sun that casts shadows through the arches.
//! Units: metres; `x` runs along the courtyard, `y` is up.

use std::f32::consts::{PI, TAU};
use subcone_kernels::math::Euclidean;

use glam::{Mat4, Vec2, Vec3};

use crate::camera::Camera;
use crate::light::Light;
use crate::material::Material;
use crate::mesh::TriangleMesh;
use crate::scene::Scene;

/// Mirror reflectance of the atrium floor.
pub const ATRIUM_FLOOR_REFLECTANCE: f32 = 0.4;

const FLOOR: u32 = 0;
const STONE: u32 = 1;
const WALL: u32 = 2;
const METAL: u32 = 3;

/// Columns per row and their spacing (centre to centre).
const COLUMNS: usize = 9;
const SPACING: f32 = 2.5;
/// Distance of each row of columns from the courtyard's axis.
const ROW_Z: f32 = 3.5;
const COLUMN_RADIUS: f32 = 0.28;
const COLUMN_SIDES: u32 = 12;
/// Height of the shaft, and of the springing line of the arches (shaft + capital).
const SHAFT: f32 = 3.6;
const SPRING: f32 = 3.85;
/// Arch radii: the intrados clears the columns, the extrados meets the next arch
/// above each column.
const ARCH_INNER: f32 = 0.95;
const ARCH_OUTER: f32 = 1.25;
const ARCH_SEGMENTS: u32 = 12;
/// Depth of the arcade wall (spandrels), and of the arch rings, which stand
/// proud of it.
const WALL_DEPTH: f32 = 0.6;
const RING_DEPTH: f32 = 0.7;
/// Gallery slab: bottom and top.
const SLAB_BOTTOM: f32 = 5.35;
const SLAB_TOP: f32 = 5.6;
/// Aisle back walls and their height.
const BACK_Z: f32 = 7.0;
const WALL_HEIGHT: f32 = 7.0;
/// Railing: baluster spacing and size, rail height.
const BALUSTER_SPACING: f32 = 0.25;
const BALUSTER_SIDE: f32 = 0.045;
const RAIL_HEIGHT: f32 = 1.0;

/// A box from its minimum and maximum corners.
fn push_aabb(m: &mut TriangleMesh, lo: Vec3, hi: Vec3, material: u32) {
    m.push_box(
        Mat4::from_translation(0.5 * (lo + hi)) * Mat4::from_scale(hi - lo),
        material,
    );
}

/// The four sides of an axis-aligned box (no top or bottom): for bars whose
/// ends are hidden.
fn push_bar_sides(m: &mut TriangleMesh, lo: Vec3, hi: Vec3, material: u32) {
    let c = |x: f32, z: f32, y: f32| Vec3::new(x, y, z);
    let (y0, y1) = (lo.y, hi.y);
    let corners = [(lo.x, lo.z), (hi.x, lo.z), (hi.x, hi.z), (lo.x, hi.z)];
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        // Counter-clockwise seen from outside.
        m.push_quad(
            [
                c(b.0, b.1, y0),
                c(a.0, a.1, y0),
                c(a.0, a.1, y1),
                c(b.0, b.1, y1),
            ],
            material,
        );
    }
}

/// A vertical prism with `sides` faces and smooth normals, standing on
/// `base` (side faces only: plinth and capital cover the ends).
fn push_prism(
    m: &mut TriangleMesh,
    base: Vec3,
    radius: f32,
    height: f32,
    sides: u32,
    material: u32,
) {
    let dir = |k: u32| {
        let a = TAU * k as f32 / sides as f32;
        Vec3::new(a.cos(), 0.0, a.sin())
    };
    let up = Vec3::Y * height;
    for k in 0..sides {
        let (d0, d1) = (dir(k), dir(k + 1));
        let (p0, p1) = (base + radius * d0, base + radius * d1);
        let uv = [Vec2::ZERO; 3];
        m.push([p0, p1 + up, p1], [d0, d1, d1], uv, material);
        m.push([p0, p0 + up, p1 + up], [d0, d0, d1], uv, material);
    }
}

/// One round arch of the arcade at row `z`, centred at `x`: the ring (a
/// half-annulus extruded to `RING_DEPTH`) and the spandrel wall above it up to
/// the gallery slab (`WALL_DEPTH`).
fn push_arch(m: &mut TriangleMesh, x: f32, z: f32) {
    let centre = Vec3::new(x, SPRING, z);
    let arc = |r: f32, k: u32| {
        let a = PI * k as f32 / ARCH_SEGMENTS as f32;
        centre + Vec3::new(r * a.cos(), r * a.sin(), 0.0)
    };
    let ring = Vec3::Z * (0.5 * RING_DEPTH);
    let wall = Vec3::Z * (0.5 * WALL_DEPTH);
    for k in 0..ARCH_SEGMENTS {
        let (i0, i1) = (arc(ARCH_INNER, k), arc(ARCH_INNER, k + 1));
        let (o0, o1) = (arc(ARCH_OUTER, k), arc(ARCH_OUTER, k + 1));
        // Ring faces: front (+z), back (-z), intrados (soffit), extrados.
        m.push_quad([i0 + ring, o0 + ring, o1 + ring, i1 + ring], STONE);
        m.push_quad([i1 - ring, o1 - ring, o0 - ring, i0 - ring], STONE);
        m.push_quad([i0 - ring, i0 + ring, i1 + ring, i1 - ring], STONE);
        m.push_quad([o1 - ring, o1 + ring, o0 + ring, o0 - ring], STONE);
        // Spandrel: from the extrados straight up to the slab, front and back.
        let (t0, t1) = (
            Vec3::new(o0.x, SLAB_BOTTOM, z),
            Vec3::new(o1.x, SLAB_BOTTOM, z),
        );
        let (o0z, o1z) = (Vec3::new(o0.x, o0.y, z), Vec3::new(o1.x, o1.y, z));
        m.push_quad([o0z + wall, t0 + wall, t1 + wall, o1z + wall], WALL);
        m.push_quad([o1z - wall, t1 - wall, t0 - wall, o0z - wall], WALL);
    }
}

/// The procedural atrium: 2 × 9 twelve-sided columns, 16 round arches, an upper
/// gallery with 2 × 88 thin balusters, aisle walls, an end wall, a mirror floor
/// (reflectance [`ATRIUM_FLOOR_REFLECTANCE`] over light stone) and a sun that
/// shines through the arches. About five thousand triangles.
pub fn atrium() -> Scene {
    let materials = vec![
        Material::mirror(
            "floor",
            Vec3::new(0.80, 0.77, 0.70),
            ATRIUM_FLOOR_REFLECTANCE,
        ),
        Material::diffuse("stone", Vec3::new(0.74, 0.68, 0.57)),
        Material::diffuse("wall", Vec3::new(0.80, 0.70, 0.58)),
        Material::diffuse("railing", Vec3::new(0.22, 0.20, 0.18)),
    ];
    let mut m = TriangleMesh::default();
    let half = 0.5 * SPACING * (COLUMNS - 1) as f32;
    let x_end = half + 4.0;

    // Floor: x in [-x_end, x_end], z in [-BACK_Z, BACK_Z], a 4 × 2 grid of quads.
    m.push_floor_grid((-x_end, -BACK_Z), (0.5 * x_end, BACK_Z), (4, 2), FLOOR);

    for side in [-1.0f32, 1.0] {
        let z = side * ROW_Z;
        // Columns: plinth, shaft, capital.
        for i in 0..COLUMNS {
            let x = -half + SPACING * i as f32;
            push_aabb(
                &mut m,
                Vec3::new(x - 0.4, 0.0, z - 0.4),
                Vec3::new(x + 0.4, 0.3, z + 0.4),
                STONE,
            );
            push_prism(
                &mut m,
                Vec3::new(x, 0.3, z),
                COLUMN_RADIUS,
                SHAFT - 0.3,
                COLUMN_SIDES,
                STONE,
            );
            push_aabb(
                &mut m,
                Vec3::new(x - 0.38, SHAFT, z - 0.38),
                Vec3::new(x + 0.38, SPRING, z + 0.38),
                STONE,
            );
        }
        // Arches between neighbouring columns.
        for i in 0..COLUMNS - 1 {
            push_arch(&mut m, -half + SPACING * (i as f32 + 0.5), z);
        }
        // Gallery slab over the aisle, from the arcade to the back wall.
        let (z_in, z_out) = (z - side * 0.5 * WALL_DEPTH, side * BACK_Z);
        push_aabb(
            &mut m,
            Vec3::new(-half - 0.4, SLAB_BOTTOM, z_in.min(z_out)),
            Vec3::new(half + 0.4, SLAB_TOP, z_in.max(z_out)),
            STONE,
        );
        // Aisle back wall.
        let zw = side * BACK_Z;
        push_aabb(
            &mut m,
            Vec3::new(-x_end, 0.0, zw.min(zw + side * 0.3)),
            Vec3::new(x_end, WALL_HEIGHT, zw.max(zw + side * 0.3)),
            WALL,
        );
        // Railing along the gallery edge: top and bottom rails, thin balusters.
        let zr = z_in + side * 0.1;
        let (r0, r1) = (SLAB_TOP + 0.08, SLAB_TOP + RAIL_HEIGHT);
        let rail = 0.04;
        push_aabb(
            &mut m,
            Vec3::new(-half - 0.4, r1, zr - rail),
            Vec3::new(half + 0.4, r1 + 2.0 * rail, zr + rail),
            METAL,
        );
        push_aabb(
            &mut m,
            Vec3::new(-half - 0.4, SLAB_TOP, zr - rail),
            Vec3::new(half + 0.4, r0, zr + rail),
            METAL,
        );
        let n = ((2.0 * half + 0.8) / BALUSTER_SPACING) as i32;
        let b = 0.5 * BALUSTER_SIDE;
        for j in 0..n {
            let x = -half - 0.4 + BALUSTER_SPACING * (j as f32 + 0.5);
            push_bar_sides(
                &mut m,
                Vec3::new(x - b, r0, zr - b),
                Vec3::new(x + b, r1, zr + b),
                METAL,
            );
        }
    }
    // The far end wall, facing the camera.
    push_aabb(
        &mut m,
        Vec3::new(x_end, 0.0, -BACK_Z - 0.3),
        Vec3::new(x_end + 0.3, WALL_HEIGHT, BACK_Z + 0.3),
        WALL,
    );

    let camera = Camera::look_at(
        Vec3::new(-half - 2.5, 1.8, 0.6),
        Vec3::new(half, 2.6, -0.4),
        Vec3::Y,
        60f32.to_radians(),
    )
    .expect("valid camera");
    // High sun behind the camera on the +z side: the -z arcade's arches throw
    // their shapes into its aisle, the +z arcade shades the courtyard's edge.
    let sun = Light::Directional {
        direction: Vec3::new(-0.35, 1.0, 0.5).unit(),
        irradiance: Vec3::new(1.0, 0.95, 0.85) * 3.0,
    };
    let mut s =
        Scene::triangles("atrium", m, materials, vec![sun], camera).expect("the atrium is valid");
    s.background = Vec3::new(0.55, 0.7, 0.9);
    s.ambient = Vec3::new(0.16, 0.17, 0.2);
    s
}
