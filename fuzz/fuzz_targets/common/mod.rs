//! Helpers shared by the fuzz targets (included with `mod common;`; not a target).
#![allow(dead_code)]

use glam::{Vec2, Vec3};

pub fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from_array(a)
}

pub fn v2(a: [f32; 2]) -> Vec2 {
    Vec2::from_array(a)
}

/// Normalise a finite non-zero vector as well as f32 allows (in f64, so no
/// overflow for huge inputs and no precision loss for subnormal ones).
/// `None` for a zero or non-finite vector.
pub fn unit(v: Vec3) -> Option<Vec3> {
    if !v.is_finite() {
        return None;
    }
    let (x, y, z) = (v.x as f64, v.y as f64, v.z as f64);
    let l = (x * x + y * y + z * z).sqrt();
    if !(l > 0.0) {
        return None;
    }
    let u = Vec3::new((x / l) as f32, (y / l) as f32, (z / l) as f32);
    assert!(u.is_finite() && (u.length() - 1.0).abs() < 1e-6, "harness: unit({v:?}) = {u:?}");
    Some(u)
}

/// Map any f32 to a finite non-negative one (the domain of the SRAA parameters).
pub fn finite_nonneg(x: f32) -> f32 {
    if x.is_finite() {
        x.abs()
    } else {
        1.0
    }
}

/// Per-channel bounding box of a set of colours: the convex hull's projection
/// on each channel, which is what "lies in the convex hull" can be checked
/// against without solving an LP.
#[derive(Clone, Copy, Debug)]
pub struct Hull {
    pub min: Vec3,
    pub max: Vec3,
    pub count: usize,
}

impl Hull {
    pub fn new() -> Self {
        Self {
            min: Vec3::splat(f32::INFINITY),
            max: Vec3::splat(f32::NEG_INFINITY),
            count: 0,
        }
    }

    /// Add a colour (must be finite).
    pub fn add(&mut self, c: Vec3) {
        assert!(c.is_finite(), "harness: hull colour {c:?}");
        self.min = self.min.min(c);
        self.max = self.max.max(c);
        self.count += 1;
    }

    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Whether `c` lies in the per-channel `[min, max]`, with the tolerance
    /// `1e-5 · max|channel| + 1e-30` on each side.
    pub fn contains(&self, c: Vec3) -> bool {
        if self.is_empty() || !c.is_finite() {
            return false;
        }
        (0..3).all(|k| {
            let (lo, hi, x) = (self.min[k] as f64, self.max[k] as f64, c[k] as f64);
            let mag = lo.abs().max(hi.abs());
            let tol = 1e-5 * mag + 1e-30;
            x >= lo - tol && x <= hi + tol
        })
    }
}
