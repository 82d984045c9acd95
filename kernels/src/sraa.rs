//! Subpixel Reconstruction Antialiasing for ray tracing (Chiu et al., §3).
//!
//! One shaded sample and four geometric subsamples per pixel. The colour of each
//! geometric subsample is reconstructed from the shaded samples of the
//! neighbouring pixels with bilateral weights ([`bilateral_weight`], eq. 1),
//! gated by shadow state ([`shadow_gated_weight`], eq. 2), and the four
//! reconstructed subsamples are filtered into the pixel ([`resolve_pixel`]).
//!
//! The API takes any geometry: a backend calls it once on primary-hit geometry
//! and, separately, on secondary-hit geometry (§3.3), so reflections are
//! reconstructed from the geometry they show.

use glam::Vec2;

mod material;
mod neighbourhood;
mod params;
mod reconstruct;
mod resolve;
mod resolver;
mod weights;

pub use material::{albedo_difference, material_gate, material_gated_weight, ALBEDO_TOLERANCE};
pub(crate) use material::{albedo_root, root_difference};
pub use neighbourhood::{neighbourhood, NeighbourPixel, Neighbourhood};
pub use params::{DepthMetric, Geometry, ShadedPosition, SraaParams, WeightForm};
pub use reconstruct::{
    reconstruct, reconstruct_layers, reconstruct_layers_material, LayeredSample, Reconstruction,
    ShadedSample, MAX_LAYERS,
};
pub use resolve::{
    resolve_pixel, resolve_pixel_tone_mapped, tone_map_weight, ResolveSpace, RESOLVE_LUMA,
};
pub use resolver::{
    gaussian_sum_lanes, gaussian_sum_wide, weights_product_lanes, weights_product_wide, FrameFlags,
    GeometryLanes, GeometryWide, LayerFlags, Resolver, ShadedFrame, ShadedGroup, Subsamples,
    WIDE_LANES,
};
pub use weights::{
    bilateral_weight, depth_difference, gaussian, reconstruction_weight, saturate,
    shadow_gated_weight, NEGLIGIBLE_WEIGHT, NORMAL_COS_SNAP,
};

/// The WGSL mirror of this module's functions (same names; functions only, no
/// bindings). Concatenate after [`crate::wgsl::PARAMS`]. Its header lists the
/// differences in rounding (GPU `exp`, compensated f32 sums instead of f64).
pub const WGSL: &str = include_str!("sraa.wgsl");

/// The WGSL twin of [`reconstruct_layers`] (and, with the albedo gate, of
/// [`reconstruct_layers_material`]) over [`neighbourhood`]: the SRAA
/// reconstruction loop, eq. 1 with the spatial term ([`reconstruction_weight`])
/// gated per light by eq. 2 (§3.1–3.2), on the primary or, for mirrors, the
/// secondary hits' geometry (§3.3). `subcone_sraa_reconstruct_run(tgt,
/// target_shadow, ta, secondary, first, x, y, k) -> vec3<f32>` reconstructs
/// subsample `k` of pixel `(x, y)` from one group of layers (`first ..
/// first + SRAA_GATES`: layer 0 ungated, layer `1 + l` gated by light `l`'s
/// shadow bit) and returns the sum of the group's layers, as [`Resolver`]
/// sums a subsample's layers. It drives [`WGSL`]'s
/// `subcone_reconstruct_layers_begin/add/end` in the order of the Rust loop.
/// Every GPU resolve runs it (`subcone_passes::SraaPass` and the wgpu
/// backend's SRAA-RT resolve); `tests/conformance_kernels.rs` holds it to
/// [`reconstruct_layers`] and [`Resolver`].
///
/// Concatenate after [`crate::wgsl::PARAMS`], [`WGSL`] and the hooks the
/// including shader defines (the source's header lists them):
///
/// - `const SRAA_GATES: u32`: layers per group, `1 +` gated lights (≤ 9);
/// - `const SRAA_MATERIAL: bool`: the albedo gate on the primary group;
/// - `fn sraa_params() -> subcone_SraaParams`, `fn sraa_size() -> vec2<u32>`
///   (the image's width and height), `fn sraa_albedo_tolerance() -> f32`;
/// - `fn sraa_shaded_geometry(x, y, secondary) -> subcone_Geometry`,
///   `fn sraa_shaded_shadow(x, y, secondary) -> u32`,
///   `fn sraa_shaded_albedo(x, y) -> vec3<f32>`,
///   `fn sraa_shaded_value(x, y, layer) -> vec3<f32>`: pixel `(x, y)`'s
///   shaded sample (its geometry, shadow bits, albedo and colour layers).
pub const RECONSTRUCT_WGSL: &str = include_str!("sraa/reconstruct.wgsl");

/// The four subpixel offsets of the 4x rotated grid on a 4×4 grid (§3.1, Fig. 2),
/// relative to the pixel's centre, in pixels.
///
/// Cell `(col, row)` of the 4×4 grid holds a sample for `(1,0)`, `(3,1)`,
/// `(0,2)`, `(2,3)`: every row and every column of the grid holds exactly one
/// sample, which is what makes a rotated grid resolve near-horizontal and
/// near-vertical edges at four levels each.
pub const SUBPIXEL_OFFSETS: [Vec2; 4] = [
    Vec2::new(-0.125, -0.375),
    Vec2::new(0.375, -0.125),
    Vec2::new(-0.375, 0.125),
    Vec2::new(0.125, 0.375),
];

/// Which of [`SUBPIXEL_OFFSETS`] is also the shaded sample.
///
/// All four lie at the same distance from the pixel centre, so any one serves;
/// a fixed index makes the shaded samples a regular lattice across the image,
/// which the reconstruction's fixed-radius neighbourhood relies on.
pub const SHADED_SUBSAMPLE: usize = 0;

/// The `sub` of [`neighbourhood`] that means the shaded sample itself,
/// wherever [`SraaParams::shaded_offset`] puts it.
pub const SHADED_SAMPLE: usize = 4;
