//! A pinhole camera.

use glam::{Vec2, Vec3};
use subcone_kernels::cone::{cone_tan_theta, PixelFootprint};
use subcone_kernels::math::Euclidean;

use crate::error::SceneError;

/// A pinhole camera: position, orthonormal frame and vertical field of view.
///
/// Image coordinates are in pixels with `(0, 0)` at the top-left corner of the
/// image and `y` growing downwards; pixel `(i, j)` covers `[i, i+1) × [j, j+1)`,
/// so its centre is `(i + 0.5, j + 0.5)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Unit up vector, orthogonal to `forward`.
    pub up: Vec3,
    /// Vertical field of view in radians, in `(0, π)`.
    pub fov_y: f32,
    /// Sub-pixel offset of the image, in pixels of the image rendered: the
    /// ray of image point `p` passes through `p + jitter`, as a jittered
    /// projection matrix moves it (the jitter of a temporal method,
    /// `crate::temporal`). Zero (every constructor's) is the plain pinhole,
    /// bit for bit. Finite; [`Camera::validate`] refuses anything else.
    pub jitter: Vec2,
}

impl Camera {
    /// A camera at `position` looking at `target`, with `up_hint` roughly up.
    ///
    /// Errors when the field of view is not in `(0°, 180°)`, when any input is
    /// not finite, when `target == position`, or when `up_hint` is parallel to
    /// the view direction.
    pub fn look_at(
        position: Vec3,
        target: Vec3,
        up_hint: Vec3,
        fov_y: f32,
    ) -> Result<Self, SceneError> {
        if !(position.is_finite() && target.is_finite() && up_hint.is_finite()) {
            return Err(SceneError::Camera(
                "position, target and up must be finite".into(),
            ));
        }
        let forward = (target - position).unit_or_zero();
        if forward == Vec3::ZERO {
            return Err(SceneError::Camera("target equals position".into()));
        }
        let right = forward.cross(up_hint).unit_or_zero();
        if right == Vec3::ZERO {
            return Err(SceneError::Camera(
                "up vector is parallel to the view direction".into(),
            ));
        }
        let cam = Camera {
            position,
            forward,
            up: right.cross(forward),
            fov_y,
            jitter: Vec2::ZERO,
        };
        cam.validate()?;
        Ok(cam)
    }

    /// Check the camera: finite, unit orthogonal frame, field of view in `(0, π)`.
    pub fn validate(&self) -> Result<(), SceneError> {
        if !(self.fov_y > 0.0 && self.fov_y < std::f32::consts::PI) {
            return Err(SceneError::Camera(format!(
                "field of view {:.3}° is outside (0°, 180°)",
                self.fov_y.to_degrees()
            )));
        }
        if !self.jitter.is_finite() {
            return Err(SceneError::Camera("jitter must be finite".into()));
        }
        if !(self.position.is_finite() && self.forward.is_finite() && self.up.is_finite()) {
            return Err(SceneError::Camera("camera frame is not finite".into()));
        }
        if (self.forward.norm() - 1.0).abs() > 1e-3
            || (self.up.norm() - 1.0).abs() > 1e-3
            || self.forward.dot(self.up).abs() > 1e-3
        {
            return Err(SceneError::Camera(
                "forward and up must be orthogonal unit vectors".into(),
            ));
        }
        Ok(())
    }

    /// The same camera with its image moved by `jitter` pixels
    /// ([`Camera::jitter`]).
    pub fn with_jitter(self, jitter: Vec2) -> Self {
        Camera { jitter, ..self }
    }

    /// The unit right vector.
    pub fn right(&self) -> Vec3 {
        self.forward.cross(self.up)
    }

    /// The ray through image point `p` (pixels, see the type docs) of a
    /// `width × height` image: `(origin, unit direction)`.
    pub fn ray(&self, p: Vec2, width: u32, height: u32) -> (Vec3, Vec3) {
        self.rays(width, height).ray(p)
    }

    /// The per-image constants of [`Camera::ray`] (the `tan` of the half field
    /// of view, the right vector), for generating many rays: its
    /// [`CameraRays::ray`] is [`Camera::ray`], bit for bit.
    pub fn rays(&self, width: u32, height: u32) -> CameraRays {
        let (w, h) = (width.max(1) as f32, height.max(1) as f32);
        CameraRays {
            position: self.position,
            forward: self.forward,
            right: self.right(),
            up: self.up,
            half: (0.5 * self.fov_y).tan(),
            w,
            h,
            jitter: self.jitter,
        }
    }

    /// The image point (pixels, see the type docs) of a `width × height`
    /// image whose ray passes through `point`: [`Camera::ray`] inverted
    /// (jitter included). `None` for a point not in front of the camera
    /// (or not finite).
    pub fn project(&self, point: Vec3, width: u32, height: u32) -> Option<Vec2> {
        self.project_direction(point - self.position, width, height)
    }

    /// The image point whose ray runs along `direction` (a point at
    /// infinity), as [`Camera::project`]; `None` for a direction not in
    /// front of the camera.
    pub fn project_direction(&self, direction: Vec3, width: u32, height: u32) -> Option<Vec2> {
        let z = direction.dot(self.forward);
        if !(z > 0.0 && z.is_finite()) {
            return None;
        }
        let (w, h) = (width.max(1) as f32, height.max(1) as f32);
        let half = (0.5 * self.fov_y).tan();
        let u = direction.dot(self.right()) / z;
        let v = direction.dot(self.up) / z;
        let p = Vec2::new(
            (u / (half * (w / h)) + 1.0) * 0.5 * w,
            (1.0 - v / half) * 0.5 * h,
        ) - self.jitter;
        p.is_finite().then_some(p)
    }

    /// Depth of a point along the view axis (what SRAA's `z` is).
    #[inline]
    pub fn view_depth(&self, p: Vec3) -> f32 {
        (p - self.position).dot(self.forward)
    }

    /// `tan θ` of a pixel's cone at `height` pixels (CTSS eq. 3, §3.1).
    pub fn cone_tan_theta(&self, height: u32, coverage: f32) -> f32 {
        cone_tan_theta(self.fov_y, height, coverage, PixelFootprint::Circumscribed)
    }
}

/// Ray generation for one `width × height` image of a camera (see
/// [`Camera::rays`]).
#[derive(Clone, Copy, Debug)]
pub struct CameraRays {
    position: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    half: f32,
    w: f32,
    h: f32,
    jitter: Vec2,
}

impl CameraRays {
    /// The ray through image point `p`: `(origin, unit direction)`, the same
    /// as [`Camera::ray`].
    #[inline]
    pub fn ray(&self, p: Vec2) -> (Vec3, Vec3) {
        self.through(self.u(p.x), self.v(p.y))
    }

    /// The horizontal image-plane coordinate of column `x` (pixels), for
    /// [`Self::through`]: a renderer that sweeps a row computes each
    /// column's once.
    #[inline]
    pub fn u(&self, x: f32) -> f32 {
        let x = x + self.jitter.x;
        (2.0 * x / self.w - 1.0) * self.half * (self.w / self.h)
    }

    /// The vertical image-plane coordinate of row `y` (pixels), for
    /// [`Self::through`].
    #[inline]
    pub fn v(&self, y: f32) -> f32 {
        let y = y + self.jitter.y;
        (1.0 - 2.0 * y / self.h) * self.half
    }

    /// The camera's position and its (forward, right, up) vectors: every ray
    /// [`Self::through`] makes is `position + t·(forward + u·right + v·up)`
    /// normalised, which a rasteriser projects against.
    pub fn frame(&self) -> (Vec3, [Vec3; 3]) {
        (self.position, [self.forward, self.right, self.up])
    }

    /// The image point (pixels) whose [`Self::u`] and [`Self::v`] are `(u,
    /// v)`: their inverse, up to rounding (for bounds, not for rays).
    pub fn pixel_of(&self, u: f32, v: f32) -> Vec2 {
        let x = (u / (self.half * (self.w / self.h)) + 1.0) * 0.5 * self.w;
        let y = (1.0 - v / self.half) * 0.5 * self.h;
        Vec2::new(x, y) - self.jitter
    }

    /// The ray through image-plane point `(u, v)`: `ray(p)` is
    /// `through(u(p.x), v(p.y))`, bit for bit.
    #[inline]
    pub fn through(&self, u: f32, v: f32) -> (Vec3, Vec3) {
        let d = (self.forward + u * self.right + v * self.up).unit();
        (self.position, d)
    }
}
