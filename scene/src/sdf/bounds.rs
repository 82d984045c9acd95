//! Conservative axis-aligned bounding boxes of SDF nodes.

use glam::{Quat, Vec3};
use subcone_kernels::math::Euclidean;

/// An axis-aligned box `[min, max]`, possibly infinite on some sides.
///
/// Boxes are conservative: the surface of a node lies inside its box. An empty
/// box has `min > max` on some axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vec3,
    /// Upper corner.
    pub max: Vec3,
}

impl Aabb {
    /// All of space.
    pub const EVERYTHING: Aabb = Aabb {
        min: Vec3::NEG_INFINITY,
        max: Vec3::INFINITY,
    };

    /// The box `[min, max]`.
    pub const fn new(min: Vec3, max: Vec3) -> Self {
        Aabb { min, max }
    }

    /// Whether every side is finite.
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// The smallest box containing both.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.min(o.min), self.max.max(o.max))
    }

    /// The intersection (may be empty).
    pub fn intersect(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.max(o.min), self.max.min(o.max))
    }

    /// Grown by `r` on every side (`r ≥ 0`).
    pub fn expand(&self, r: f32) -> Aabb {
        Aabb::new(self.min - Vec3::splat(r), self.max + Vec3::splat(r))
    }

    /// The box of `{ translation + rotation · (scale · p) : p ∈ self }`.
    pub fn transform(&self, translation: Vec3, rotation: Quat, scale: f32) -> Aabb {
        let s = Aabb::new(self.min * scale, self.max * scale);
        let r = if rotation == Quat::IDENTITY {
            s
        } else if !s.is_finite() {
            Aabb::EVERYTHING
        } else {
            let mut min = Vec3::INFINITY;
            let mut max = Vec3::NEG_INFINITY;
            for i in 0..8 {
                let c = Vec3::new(
                    if i & 1 == 0 { s.min.x } else { s.max.x },
                    if i & 2 == 0 { s.min.y } else { s.max.y },
                    if i & 4 == 0 { s.min.z } else { s.max.z },
                );
                let c = rotation * c;
                min = min.min(c);
                max = max.max(c);
            }
            // Rounding of the rotation: grow by a few ulps of the extent.
            let slack = (max - min).max_element() * 1e-6;
            Aabb::new(min - Vec3::splat(slack), max + Vec3::splat(slack))
        };
        Aabb::new(r.min + translation, r.max + translation)
    }

    /// Distance from `p` to the box (0 inside).
    #[inline]
    pub fn distance(&self, p: Vec3) -> f32 {
        let d = (self.min - p).max(p - self.max).max(Vec3::ZERO);
        d.norm()
    }

    /// The largest distance from the origin to a point of the box (∞ when
    /// unbounded).
    pub fn radius_about_origin(&self) -> f32 {
        if !self.is_finite() {
            return f32::INFINITY;
        }
        self.min.abs().max(self.max.abs()).norm()
    }
}

/// `floor(x + 0.5)` without a libm call (glam's `round` is libm's software
/// `roundf` here, which shows up in profiles of repetition). Exact for
/// `|x| < 2⁶³`; beyond, saturates (the cell index of such a point is
/// meaningless in `f32` anyway). NaN gives 0.
#[inline(always)]
pub(crate) fn round_cell(x: f32) -> f32 {
    let f = x + 0.5;
    let t = f as i64 as f32;
    if t > f {
        t - 1.0
    } else {
        t
    }
}
