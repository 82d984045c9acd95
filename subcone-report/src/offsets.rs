//! The sub-pixel camera offsets a method's error is measured at.
//!
//! One frame's error depends on where the pixel grid falls on the scene: a
//! thin feature that one frame's samples catch, the next frame's, a
//! fraction of a pixel further, miss. So the report measures each method's
//! error at [`ERROR_OFFSETS`]: the scene's camera and the same camera turned
//! by a fraction of a pixel's angle (as the motion section's pan turns it,
//! [`motion::camera_path`](crate::motion::camera_path)), each offset against
//! its own reference (cached, see [`reference`](crate::reference)) and with
//! its own edge classes, every offset at the quality size and against the
//! run's reference method, so that the offsets differ in where the pixel
//! grid falls and in nothing else. Only the error is measured again; the
//! timing rounds are not repeated.
//!
//! The verdicts compare a method with NoAA paired by offset
//! ([`Verdict::judge_claims`](crate::classes::Verdict::judge_claims)): a win
//! or a loss counts only when it holds at every offset.

use anyhow::{anyhow, Result};
use glam::Quat;
use subcone_scene::Camera;

/// The offsets, in pixels (right, down) of view turn at the image centre: the scene's
/// camera first, then three shifts on different sub-pixel phases in both
/// axes (a half pixel and the two quarter phases), so that no feature sits
/// at the same place in the pixel grid in two of them.
pub const ERROR_OFFSETS: [(f32, f32); 4] = [(0.0, 0.0), (0.5, 0.5), (0.25, 0.75), (0.75, 0.25)];

/// `base` turned right by `dx` and down by `dy` pixels' worth of angle at
/// the centre of an image `height` pixels high (`fov_y / height` per pixel,
/// as the motion section's pan; the image content moves the other way): a
/// turn about the camera's up axis, then its right axis. Errors when the
/// result is not a valid camera (a non-finite offset, say).
pub fn offset_camera(base: &Camera, (dx, dy): (f32, f32), height: u32) -> Result<Camera> {
    if dx == 0.0 && dy == 0.0 {
        return Ok(*base);
    }
    let pixel_angle = base.fov_y / height.max(1) as f32;
    let right = base.forward.cross(base.up).normalize();
    let turn = Quat::from_axis_angle(base.up, -dx * pixel_angle)
        * Quat::from_axis_angle(right, -dy * pixel_angle);
    let forward = turn * base.forward;
    let up = turn * base.up;
    Camera::look_at(base.position, base.position + forward, up, base.fov_y)
        .map_err(|e| anyhow!("camera offset ({dx}, {dy}) px: {e}"))
}

/// The offset as the reference cache keys it and the report names it,
/// e.g. `0.50,0.25 px`.
pub fn label((dx, dy): (f32, f32)) -> String {
    format!("{dx:.2},{dy:.2} px")
}

/// A camera as the reference cache's key describes it: every field, in
/// full precision, so that two cameras share a reference only when equal.
pub fn describe(c: &Camera) -> String {
    format!(
        "position={:?} forward={:?} up={:?} fov_y={:?}",
        c.position.to_array(),
        c.forward.to_array(),
        c.up.to_array(),
        c.fov_y
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn offsets_move_the_image_by_the_fraction_of_a_pixel_asked() {
        let base = Camera::look_at(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 0.8).unwrap();
        let h = 64;
        assert_eq!(offset_camera(&base, (0.0, 0.0), h).unwrap(), base);
        let pixel = base.fov_y / h as f32;
        for &(dx, dy) in &ERROR_OFFSETS[1..] {
            let c = offset_camera(&base, (dx, dy), h).unwrap();
            assert_eq!(c.position, base.position);
            // The view turned by the offset's angle, right and down.
            let yaw = c.forward.x.atan2(-c.forward.z);
            let pitch = c.forward.y.asin();
            assert!((yaw - dx * pixel).abs() < 1e-5, "yaw {yaw} for {dx}");
            assert!((pitch + dy * pixel).abs() < 1e-5, "pitch {pitch} for {dy}");
            assert!(c.up.dot(c.forward).abs() < 1e-5);
            assert_ne!(describe(&c), describe(&base));
        }
        // Distinct offsets, distinct cameras, distinct labels.
        let labels: std::collections::BTreeSet<String> =
            ERROR_OFFSETS.iter().map(|&o| label(o)).collect();
        assert_eq!(labels.len(), ERROR_OFFSETS.len());
        assert!(offset_camera(&base, (f32::NAN, 0.0), h).is_err());
    }
}
