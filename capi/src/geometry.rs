//! The plain vector and a sample's geometry, as the SRAA weights read it.

use glam::Vec3;
use subcone_kernels::sraa::Geometry;

/// A 3-vector: a point, a direction or a linear RGB colour.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeVec3 {
    /// x (red).
    pub x: f32,
    /// y (green).
    pub y: f32,
    /// z (blue).
    pub z: f32,
}

impl From<SubconeVec3> for Vec3 {
    fn from(v: SubconeVec3) -> Vec3 {
        Vec3::new(v.x, v.y, v.z)
    }
}

impl From<Vec3> for SubconeVec3 {
    fn from(v: Vec3) -> SubconeVec3 {
        SubconeVec3 {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

/// A sample's geometry for the SRAA weights: unit normal and view depth (the
/// distance along the view axis). 16 bytes; a NaN depth marks a miss.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeGeometry {
    /// Unit surface normal.
    pub normal: SubconeVec3,
    /// View depth; NaN for a miss.
    pub depth: f32,
}

impl From<SubconeGeometry> for Geometry {
    fn from(g: SubconeGeometry) -> Geometry {
        Geometry {
            normal: g.normal.into(),
            depth: g.depth,
        }
    }
}

// The mirrored structs have the kernels' layouts (a host may hand the same
// bytes to the WGSL kernels).
const _: () = {
    use std::mem::{offset_of, size_of};
    assert!(size_of::<SubconeGeometry>() == size_of::<Geometry>());
    assert!(offset_of!(SubconeGeometry, depth) == offset_of!(Geometry, depth));
};
