//! The pinhole camera every GPU shader of subcone traces through, as one
//! `#[repr(C)]` uniform ([`PinholeCamera`], `subcone_PinholeCamera` in
//! WGSL) and one ray rule ([`PinholeCamera::ray_dir`],
//! `subcone_pinhole_dir`).
//!
//! Neither paper specifies a camera; this is the one of both papers'
//! figures: a pinhole with a vertical field of view, square pixels, pixel
//! `(x, y)` of a `width × height` image (x right, y down) covering image
//! points `[x, x + 1) × [y, y + 1)`. The CPU renderers' `Camera::ray`
//! (`subcone-scene`) computes the same expression in the same order, so a
//! GPU trace and a CPU trace start from the same ray, up to the GPU's
//! rounding of the reciprocal square root.

use glam::{Vec2, Vec3};

/// `v`, or, when its squared length overflows f32 or is subnormal (a
/// component of 10²⁰ or 10⁻²⁰), `v` divided by its largest component: the
/// same direction, whose length then normalises (`(10³⁰, 0, 0)` normalised
/// as it is gives the zero vector, `(10⁻³⁰, 0, 0)` a division by zero).
/// Vectors of ordinary length, and zero or non-finite ones, are returned
/// unchanged, so their bits are the renderers'.
pub fn in_normal_range(v: Vec3) -> Vec3 {
    let m = v.abs().max_element();
    if v.length_squared().is_normal() || !(m > 0.0 && m.is_finite()) {
        v
    } else {
        v / m
    }
}

/// The smallest sine of the angle between a camera's `forward` and
/// `up_hint` that [`look_frame`] makes a frame of: below it the f32 cross
/// product cancels too much to be orthogonal to `forward` (its error is
/// about 10⁻⁷ over the sine), so there is no frame.
pub const LOOK_FRAME_MIN_SINE: f32 = 1e-4;

/// The orthonormal frame `(forward, right, up)` of a camera looking along
/// `forward` with `up_hint` roughly up: `forward` normalised, `right` the
/// normalised `forward × up_hint`, `up = right × forward`. Vectors and the
/// cross product whose lengths leave f32's normal range are scaled first
/// ([`in_normal_range`]), so a frame is unit to rounding for tiny or huge
/// vectors too; `right` is orthogonal to `forward` to within about 10⁻⁷
/// over the sine of their angle. For ordinary vectors this is the plain
/// expression, bit for bit.
///
/// Outside the domain: a zero or non-finite `forward` gives a zero
/// `forward`; an `up_hint` within [`LOOK_FRAME_MIN_SINE`] of parallel to
/// it, zero or non-finite gives zero `right` and `up`. Callers that need a
/// frame check for zero.
pub fn look_frame(forward: Vec3, up_hint: Vec3) -> (Vec3, Vec3, Vec3) {
    let forward = in_normal_range(forward).normalize_or_zero();
    let up_hint = in_normal_range(up_hint);
    // The sine of the angle, from unit vectors (a check only: `right` is
    // the plain expression's).
    let sine = forward.cross(up_hint.normalize_or_zero()).length();
    if !(sine >= LOOK_FRAME_MIN_SINE) {
        return (forward, Vec3::ZERO, Vec3::ZERO);
    }
    let right = in_normal_range(forward.cross(up_hint)).normalize_or_zero();
    (forward, right, right.cross(forward))
}

/// A pinhole camera and its image size, as shaders read it (80 bytes,
/// `subcone_PinholeCamera` in WGSL, checked by `tests/wgsl_layout.rs`).
///
/// `forward`, `right` and `up` are expected to be an orthonormal frame
/// (right = forward × up); `tan_half_fov` is `tan(fov_y / 2)`, positive and
/// finite. Other values are not rejected: they give the rays
/// [`PinholeCamera::ray_dir`]'s expression gives (NaN directions for a zero
/// frame), which every trace of this crate ends at once (a NaN distance ends
/// a march).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct PinholeCamera {
    /// The eye.
    pub position: [f32; 3],
    /// Image width in pixels (0 reads as 1).
    pub width: u32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// Image height in pixels (0 reads as 1).
    pub height: u32,
    /// Unit right vector.
    pub right: [f32; 3],
    /// `tan(fov_y / 2)`.
    pub tan_half_fov: f32,
    /// Unit up vector.
    pub up: [f32; 3],
    /// Padding; zero.
    pub _pad: u32,
    /// Sub-pixel offset of every ray, in pixels: the ray of image point `p`
    /// passes through `p + jitter` (a temporal method's jitter; zero, the
    /// default, is the plain camera, bit for bit).
    pub jitter: [f32; 2],
    /// Padding to 16 bytes (WGSL's struct alignment); zero.
    pub _pad2: [u32; 2],
}

impl PinholeCamera {
    /// The camera at `position` with the orthonormal frame
    /// `(forward, right, up)` and `tan_half_fov = tan(fov_y / 2)` (the
    /// caller's `tan`: `std`'s and libm's may differ in the last bit, and a
    /// host's CPU reference should use the one its own camera uses), for a
    /// `width × height` image.
    pub fn new(
        position: Vec3,
        (forward, right, up): (Vec3, Vec3, Vec3),
        tan_half_fov: f32,
        (width, height): (u32, u32),
    ) -> Self {
        PinholeCamera {
            position: position.to_array(),
            width,
            forward: forward.to_array(),
            height,
            right: right.to_array(),
            tan_half_fov,
            up: up.to_array(),
            _pad: 0,
            jitter: [0.0; 2],
            _pad2: [0; 2],
        }
    }

    /// The same camera with every ray moved by `jitter` pixels
    /// ([`Self::jitter`]).
    pub fn with_jitter(mut self, jitter: Vec2) -> Self {
        self.jitter = jitter.to_array();
        self
    }

    /// The unit direction of the ray from [`Self::position`] through image
    /// point `p + jitter` (pixels, y down): `forward + u·right + v·up` normalised,
    /// with `u = (2 p.x / w − 1)·tan_half_fov·(w / h)` and
    /// `v = (1 − 2 p.y / h)·tan_half_fov`, a zero width or height read as 1.
    /// Any `p` is taken (points off the image give rays outside the field
    /// of view); a non-finite `p` gives a non-finite direction.
    #[inline]
    pub fn ray_dir(&self, p: Vec2) -> Vec3 {
        let p = p + Vec2::from(self.jitter);
        let (w, h) = (self.width.max(1) as f32, self.height.max(1) as f32);
        let u = (2.0 * p.x / w - 1.0) * self.tan_half_fov * (w / h);
        let v = (1.0 - 2.0 * p.y / h) * self.tan_half_fov;
        let d = Vec3::from(self.forward) + u * Vec3::from(self.right) + v * Vec3::from(self.up);
        d * (1.0 / d.length())
    }
}
