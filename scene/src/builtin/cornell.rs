//! The measured Cornell box (Cornell University Program of Computer Graphics),
//! in millimetres, with a mirror sphere on the floor and a point light just below
//! the light quad, so that shadows are hard and reflections exist.

use glam::Vec3;

use crate::camera::Camera;
use crate::light::Light;
use crate::material::Material;
use crate::mesh::TriangleMesh;
use crate::scene::Scene;

const WHITE: Vec3 = Vec3::new(0.725, 0.71, 0.68);
const RED: Vec3 = Vec3::new(0.63, 0.065, 0.05);
const GREEN: Vec3 = Vec3::new(0.14, 0.45, 0.091);

/// Material indices, in the order of [`materials`].
const MAT_WHITE: u32 = 0;
const MAT_RED: u32 = 1;
const MAT_GREEN: u32 = 2;
const MAT_LIGHT: u32 = 3;
const MAT_SPHERE: u32 = 4;

const fn v(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(x, y, z)
}

/// The room: floor, light, ceiling, back wall, the green wall (x = 0) and
/// the red wall (x ≈ 556), each with its material.
const ROOM: [([Vec3; 4], u32); 6] = [
    (
        [
            v(552.8, 0.0, 0.0),
            v(0.0, 0.0, 0.0),
            v(0.0, 0.0, 559.2),
            v(549.6, 0.0, 559.2),
        ],
        MAT_WHITE,
    ),
    // The light quad is coplanar with the ceiling in the measured data: lowered 0.1 mm.
    (
        [
            v(343.0, 548.7, 227.0),
            v(343.0, 548.7, 332.0),
            v(213.0, 548.7, 332.0),
            v(213.0, 548.7, 227.0),
        ],
        MAT_LIGHT,
    ),
    (
        [
            v(556.0, 548.8, 0.0),
            v(556.0, 548.8, 559.2),
            v(0.0, 548.8, 559.2),
            v(0.0, 548.8, 0.0),
        ],
        MAT_WHITE,
    ),
    (
        [
            v(549.6, 0.0, 559.2),
            v(0.0, 0.0, 559.2),
            v(0.0, 548.8, 559.2),
            v(556.0, 548.8, 559.2),
        ],
        MAT_WHITE,
    ),
    (
        [
            v(0.0, 0.0, 559.2),
            v(0.0, 0.0, 0.0),
            v(0.0, 548.8, 0.0),
            v(0.0, 548.8, 559.2),
        ],
        MAT_GREEN,
    ),
    (
        [
            v(552.8, 0.0, 0.0),
            v(549.6, 0.0, 559.2),
            v(556.0, 548.8, 559.2),
            v(556.0, 548.8, 0.0),
        ],
        MAT_RED,
    ),
];

/// The short block: its top, then its four sides.
const SHORT_BLOCK: [[Vec3; 4]; 5] = [
    [
        v(130.0, 165.0, 65.0),
        v(82.0, 165.0, 225.0),
        v(240.0, 165.0, 272.0),
        v(290.0, 165.0, 114.0),
    ],
    [
        v(290.0, 0.0, 114.0),
        v(290.0, 165.0, 114.0),
        v(240.0, 165.0, 272.0),
        v(240.0, 0.0, 272.0),
    ],
    [
        v(130.0, 0.0, 65.0),
        v(130.0, 165.0, 65.0),
        v(290.0, 165.0, 114.0),
        v(290.0, 0.0, 114.0),
    ],
    [
        v(82.0, 0.0, 225.0),
        v(82.0, 165.0, 225.0),
        v(130.0, 165.0, 65.0),
        v(130.0, 0.0, 65.0),
    ],
    [
        v(240.0, 0.0, 272.0),
        v(240.0, 165.0, 272.0),
        v(82.0, 165.0, 225.0),
        v(82.0, 0.0, 225.0),
    ],
];

/// The tall block: its top, then its four sides.
const TALL_BLOCK: [[Vec3; 4]; 5] = [
    [
        v(423.0, 330.0, 247.0),
        v(265.0, 330.0, 296.0),
        v(314.0, 330.0, 456.0),
        v(472.0, 330.0, 406.0),
    ],
    [
        v(423.0, 0.0, 247.0),
        v(423.0, 330.0, 247.0),
        v(472.0, 330.0, 406.0),
        v(472.0, 0.0, 406.0),
    ],
    [
        v(472.0, 0.0, 406.0),
        v(472.0, 330.0, 406.0),
        v(314.0, 330.0, 456.0),
        v(314.0, 0.0, 456.0),
    ],
    [
        v(314.0, 0.0, 456.0),
        v(314.0, 330.0, 456.0),
        v(265.0, 330.0, 296.0),
        v(265.0, 0.0, 296.0),
    ],
    [
        v(265.0, 0.0, 296.0),
        v(265.0, 330.0, 296.0),
        v(423.0, 330.0, 247.0),
        v(423.0, 0.0, 247.0),
    ],
];

/// The Cornell box. With `mirror`, a mirror sphere (reflectance 0.8, radius
/// 90 mm) stands on the floor in the free front-left corner, where it reflects
/// the red wall, both blocks, the floor's shadows and the light; without, the
/// box is the measured one alone.
pub fn cornell(mirror: bool) -> Scene {
    let name = if mirror {
        "cornell"
    } else {
        "cornell-nomirror"
    };
    let mut s = Scene::triangles(
        name,
        geometry(mirror),
        materials(mirror),
        lights(),
        camera(),
    )
    .expect("the Cornell box is valid");
    s.background = Vec3::ZERO;
    s.ambient = Vec3::splat(0.04);
    s
}

/// The materials, indexed by the `MAT_` constants; without `mirror`, the
/// sphere's slot is a white one that nothing uses.
fn materials(mirror: bool) -> Vec<Material> {
    vec![
        Material::diffuse("white", WHITE),
        Material::diffuse("red", RED),
        Material::diffuse("green", GREEN),
        Material {
            emission: Vec3::splat(1.0),
            ..Material::diffuse("light", Vec3::splat(0.78))
        },
        if mirror {
            Material::mirror("mirror", WHITE * 0.2, 0.8)
        } else {
            Material::diffuse("white", WHITE)
        },
    ]
}

/// The room, the short block, the tall block and (with `mirror`) the sphere,
/// in that order.
fn geometry(mirror: bool) -> TriangleMesh {
    let mut m = TriangleMesh::default();
    for (q, mat) in ROOM {
        m.push_quad(q, mat);
    }
    for q in SHORT_BLOCK {
        m.push_quad(q, MAT_WHITE);
    }
    for q in TALL_BLOCK {
        m.push_quad(q, MAT_WHITE);
    }
    if mirror {
        m.push_sphere(v(420.0, 90.0, 150.0), 90.0, 48, 96, MAT_SPHERE);
    }
    m
}

/// A point light 10 mm below the centre of the light quad: hard shadows.
/// Intensity so that the floor below receives about 4.5 (π·1.4) irradiance.
fn lights() -> Vec<Light> {
    vec![Light::Point {
        position: v(278.0, 538.8, 279.5),
        intensity: Vec3::new(1.0, 0.9, 0.75) * 1.3e6,
    }]
}

/// The measured camera.
fn camera() -> Camera {
    Camera {
        position: v(278.0, 273.0, -800.0),
        forward: Vec3::Z,
        up: Vec3::Y,
        fov_y: 39.31f32.to_radians(),
        jitter: glam::Vec2::ZERO,
    }
}
