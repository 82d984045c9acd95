//! Lights that cast hard shadows.

use glam::Vec3;
use subcone_kernels::math::Euclidean;

/// A light. Both kinds cast hard shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A point light with radiant intensity `intensity` (falls off with 1/r²).
    Point {
        /// Position.
        position: Vec3,
        /// Intensity (RGB).
        intensity: Vec3,
    },
    /// A distant light arriving from `direction` (unit, pointing towards the light).
    Directional {
        /// Unit direction towards the light.
        direction: Vec3,
        /// Irradiance on a surface facing it (RGB).
        irradiance: Vec3,
    },
}

/// What a light delivers to a point: unit direction towards the light, distance
/// to it (∞ for directional lights) and irradiance on a surface facing it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incident {
    /// Unit direction from the point towards the light.
    pub direction: Vec3,
    /// Distance to the light.
    pub distance: f32,
    /// Irradiance at normal incidence.
    pub irradiance: Vec3,
}

impl Light {
    /// Whether every number of the light is finite (a non-finite one would
    /// put NaN or ∞ into every pixel it lights).
    pub fn is_finite(&self) -> bool {
        match *self {
            Light::Point {
                position,
                intensity,
            } => position.is_finite() && intensity.is_finite(),
            Light::Directional {
                direction,
                irradiance,
            } => direction.is_finite() && irradiance.is_finite(),
        }
    }

    /// The light arriving at `p`, or `None` when `p` is at the light.
    pub fn incident(&self, p: Vec3) -> Option<Incident> {
        match *self {
            Light::Point {
                position,
                intensity,
            } => {
                let to = position - p;
                let d2 = to.length_squared();
                if !(d2.is_finite() && d2 > 0.0) {
                    return None;
                }
                let d = d2.sqrt();
                Some(Incident {
                    direction: to / d,
                    distance: d,
                    irradiance: intensity / d2,
                })
            }
            Light::Directional {
                direction,
                irradiance,
            } => {
                let dir = direction.unit_or_zero();
                (dir != Vec3::ZERO).then_some(Incident {
                    direction: dir,
                    distance: f32::INFINITY,
                    irradiance,
                })
            }
        }
    }
}
