//! The special values and the fixed grids of awkward inputs that the
//! generators mix in, shared with the kernel conformance suite.

use glam::Vec3;
use subcone_kernels::sraa::{DepthMetric, SraaParams, WeightForm};

/// The special values every generator mixes in: signed zeros, subnormals
/// (the smallest, and 1e-40), the smallest normal, 1e±30, ±1, ½, ±`f32::MAX`,
/// ±∞ and NaN.
pub const SPECIALS: [f32; 18] = [
    0.0,
    -0.0,
    1.4e-45,
    -1.4e-45,
    1e-40,
    f32::MIN_POSITIVE,
    1e-30,
    -1e-30,
    0.5,
    1.0,
    -1.0,
    1e30,
    -1e30,
    f32::MAX,
    f32::MIN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
];

/// The depths of the weight grids (here and in the conformance suite): equal,
/// close and double, 0, a subnormal, near `f32::MAX`, ∞, NaN and a miss-like
/// 1e6.
pub const AWKWARD_DEPTHS: [f32; 9] = [
    1.0,
    1.05,
    2.0,
    0.0,
    1e-40,
    3e38,
    f32::INFINITY,
    f32::NAN,
    1e6,
];

/// The parameter sets of the weight grids: both weight forms, both depth
/// metrics, and sigmas so large that every exponent is ~0.
pub const AWKWARD_WEIGHT_PARAMS: [SraaParams; 4] = [
    SraaParams::PAPER,
    SraaParams::CHAJDAS,
    SraaParams::PAPER.with_depth_metric(DepthMetric::Absolute),
    SraaParams::new(
        1e20,
        1e20,
        1.0,
        WeightForm::Product,
        DepthMetric::Relative,
        1,
    ),
];

/// The normals of the ambient-occlusion grids (here and in the conformance
/// suite): the signed axes, signed and unsigned zero, NaN, ∞, huge and tiny
/// vectors, and one unit vector off the axes.
pub fn ao_grid_normals() -> [Vec3; 13] {
    [
        Vec3::X,
        -Vec3::X,
        Vec3::Y,
        -Vec3::Y,
        Vec3::Z,
        -Vec3::Z,
        Vec3::new(0.0, 0.0, -0.0),
        Vec3::ZERO,
        Vec3::NAN,
        Vec3::new(f32::INFINITY, 0.0, 1.0),
        Vec3::splat(f32::MAX),
        Vec3::splat(1e-30),
        Vec3::new(0.6, 0.0, -0.8),
    ]
}

/// The (index, count) pairs of the ambient-occlusion grids: a zero count,
/// the first index of one and the last of 4, 64 and 256, indices beyond
/// their count (`u32::MAX` among them).
pub const AO_GRID_INDICES: [(u32, u32); 7] = [
    (0, 0),
    (0, 1),
    (3, 4),
    (63, 64),
    (255, 256),
    (9, 4),
    (u32::MAX, 16),
];
