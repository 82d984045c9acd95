//! The normals a CTSS trace takes: their difference steps at a depth (the
//! shading normal's and §5.3's coarse one) and tetrahedral differences.

use crate::math::Euclidean;
use glam::Vec3;

use super::params::CtssParams;

/// Step of the shading normal at depth `t`: a quarter of the cone radius,
/// never below `10⁻⁵` of the depth (or of 1), so the differences resolve
/// the pixel's footprint and never vanish in rounding. Non-finite or
/// negative inputs give the floor `10⁻⁵`.
#[inline]
pub fn normal_step(t: f32, tan_theta: f32) -> f32 {
    let floor = 1e-5 * if t > 1.0 { t } else { 1.0 };
    let h = 0.25 * t * tan_theta;
    if h > floor {
        h
    } else {
        floor
    }
}

/// Step `h` of the coarse normal of a group sampled at depth `t`: four times
/// the fine step [`normal_step`], i.e. the cone radius `R_c = t·tan θ` (never
/// below `4·10⁻⁵·max(t, 1)`), so that the coarse differences' taps reach
/// across the pixel's footprint.
#[inline]
pub fn coarse_normal_step(t: f32, params: &CtssParams) -> f32 {
    4.0 * normal_step(t, params.tan_theta)
}

/// Unit normal of `sdf` at `p` from tetrahedral differences of step `h` (4
/// evaluations, Quilez); the CPU renderer's `SdfField::normal` is the same
/// formula. Zero when the differences are zero or not finite.
pub fn tetra_normal<S: FnMut(Vec3) -> f32>(mut sdf: S, p: Vec3, h: f32) -> Vec3 {
    const K: [Vec3; 4] = [
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(1.0, 1.0, 1.0),
    ];
    K.iter()
        .fold(Vec3::ZERO, |a, k| a + *k * sdf(p + *k * h))
        .unit_or_zero()
}
