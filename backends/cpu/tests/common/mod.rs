//! What the CPU backend's tests share: rendering a method by name, and the
//! camera and material of the hand-built SDF scenes.
// Each test binary uses only part of this module.
#![allow(dead_code)]

use glam::Vec3;
use subcone_cpu::CpuBackend;
use subcone_scene::{Backend, Camera, Frame, Material, Method, RenderSettings, Scene};

/// `method` (a CLI word) on `scene` from its own camera, at `settings`.
pub fn render_with(scene: &Scene, method: &str, settings: &RenderSettings) -> Frame {
    let m: Method = method.parse().unwrap();
    CpuBackend::new()
        .render(scene, &scene.camera, &m, settings)
        .unwrap()
}

/// [`render_with`] the default settings at `w × h`.
pub fn render(scene: &Scene, method: &str, w: u32, h: u32) -> Frame {
    render_with(scene, method, &RenderSettings::new(w, h))
}

/// Six units up +z looking at the origin, a 30° field of view: a unit-sized
/// object fills about half the image.
pub fn front_camera() -> Camera {
    Camera::look_at(
        Vec3::new(0.0, 0.0, 6.0),
        Vec3::ZERO,
        Vec3::Y,
        30f32.to_radians(),
    )
    .unwrap()
}

/// A white diffuse material that does not glow.
pub fn white() -> Material {
    Material {
        emission: Vec3::ZERO,
        ..Material::diffuse("white", Vec3::ONE)
    }
}
