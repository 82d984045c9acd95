//! The coloured-patch floor of the SRAA paper's Fig. 6: the case SRAA cannot
//! fix, because the edges between patches are colour (texture) edges, not
//! geometric ones, so the geometry samples see one flat floor.

use glam::{Mat4, Quat, Vec3};
use subcone_kernels::math::Euclidean;

use crate::camera::Camera;
use crate::light::Light;
use crate::material::{Albedo, Material};
use crate::mesh::TriangleMesh;
use crate::scene::Scene;

/// Side of a floor patch in metres: about 6 pixels wide at 256×256 where the
/// view centre meets the floor (5.8 m away).
pub const CHECKER_PATCH: f32 = 0.125;

/// The six saturated patch colours.
pub const CHECKER_PALETTE: [Vec3; 6] = [
    Vec3::new(0.80, 0.08, 0.06),
    Vec3::new(0.10, 0.65, 0.12),
    Vec3::new(0.08, 0.18, 0.85),
    Vec3::new(0.85, 0.78, 0.08),
    Vec3::new(0.75, 0.10, 0.70),
    Vec3::new(0.08, 0.72, 0.78),
];

/// A large floor of coloured square patches receding from a camera 2 m up that
/// looks 20° down with a 50° field of view, a box and a sphere casting sun
/// shadows on it. No mirrors. Units: metres.
pub fn checker() -> Scene {
    let (floor, box_mat, ball) = (0, 1, 2);
    let materials = vec![
        Material {
            albedo: Albedo::Patches {
                palette: CHECKER_PALETTE.to_vec(),
                size: CHECKER_PATCH,
            },
            ..Material::diffuse("patches", Vec3::splat(0.5))
        },
        Material::diffuse("box", Vec3::new(0.75, 0.74, 0.70)),
        Material::diffuse("sphere", Vec3::new(0.82, 0.62, 0.35)),
    ];
    let mut m = TriangleMesh::default();
    // The floor: y = 0, x in [-30, 30], z in [-70, 10], as a grid of 5 m tiles.
    m.push_floor_grid((-30.0, -70.0), (5.0, 5.0), (12, 16), floor);
    m.push_box(
        Mat4::from_scale_rotation_translation(
            Vec3::splat(0.8),
            Quat::from_rotation_y(30f32.to_radians()),
            Vec3::new(-1.1, 0.4, -0.6),
        ),
        box_mat,
    );
    m.push_sphere(Vec3::new(1.0, 0.5, 0.1), 0.5, 24, 48, ball);

    let fov = 50f32.to_radians();
    let eye = Vec3::new(0.0, 2.0, 6.0);
    let down = 20f32.to_radians();
    let forward = Vec3::new(0.0, -down.sin(), -down.cos());
    let camera = Camera::look_at(eye, eye + forward, Vec3::Y, fov).expect("valid camera");
    let sun = Light::Directional {
        direction: Vec3::new(-0.5, 1.0, 0.6).unit(),
        irradiance: Vec3::new(1.0, 0.97, 0.9) * 3.0,
    };
    let mut s = Scene::triangles("checker", m, materials, vec![sun], camera)
        .expect("the checker scene is valid");
    s.background = Vec3::new(0.6, 0.72, 0.88);
    s.ambient = Vec3::splat(0.08);
    s
}
