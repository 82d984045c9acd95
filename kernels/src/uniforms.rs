//! The uniforms of subcone's GPU passes, and the one way to fill them.
//!
//! `subcone-passes` uploads these structs to its SRAA and CTSS shaders
//! (`SraaFrame` and `CtssUniform` in their WGSL, layouts checked by naga in
//! that crate), and the C ABI hands them to engines that run the generated
//! shaders themselves (`SubconeSraaPassUniform`, `SubconeCtssPassUniform`),
//! so both fill them through the constructors here: the projection
//! coefficients of hardware depth, the material gate's tolerance, the
//! exposure of a tone-mapped resolve and the view-depth axis of a CTSS
//! camera are derived in one place.

use glam::Vec3;

use crate::camera::PinholeCamera;
use crate::sraa::{ResolveSpace, SraaParams, ALBEDO_TOLERANCE};

/// The SRAA pass's constants (`SraaFrame` in its WGSL, 80 bytes): the
/// weights' parameters (SRAA eq. 1–2), how to read hardware depth, the rect
/// resolved and the resolve's exposure.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct SraaFrame {
    /// The weights' parameters.
    pub sraa: SraaParams,
    /// Column-major `m[2][2], m[3][2], m[2][3], m[3][3]` of the projection
    /// that wrote hardware depth, which view depth
    /// `|(m32 − d·m33) / (d·m23 − m22)|` inverts; zero for linear depth.
    pub projection: [f32; 4],
    /// The rect's width in pixels.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// The hardware depth of a miss (the clear value); 0 for linear depth.
    pub depth_miss: f32,
    /// The material gate's tolerance ([`ALBEDO_TOLERANCE`]).
    pub albedo_tolerance: f32,
    /// The rect's first column in the output (0 for whole images and for
    /// buffers).
    pub origin_x: u32,
    /// Its first row.
    pub origin_y: u32,
    /// The tone-mapped resolve's exposure; 0 for the linear resolve.
    pub exposure: f32,
    /// Padding; zero.
    pub _pad: u32,
}

impl SraaFrame {
    /// The constants of a `size` rect at `origin` resolved with `params` in
    /// `resolve`, from linear view depth (`hardware_depth` `None`) or from
    /// hardware depth written by the column-major projection `m`, a miss
    /// being the depth `miss` (`Some((m, miss))`).
    ///
    /// Every value is stored as given; the shader reads a non-finite or
    /// out-of-range one as its own domain says (a non-positive exposure is
    /// never read: only a tone-mapped variant reads it).
    pub fn new(
        params: SraaParams,
        origin: (u32, u32),
        size: (u32, u32),
        hardware_depth: Option<([[f32; 4]; 4], f32)>,
        resolve: ResolveSpace,
    ) -> Self {
        let (projection, depth_miss) = match hardware_depth {
            Some((m, miss)) => ([m[2][2], m[3][2], m[2][3], m[3][3]], miss),
            None => ([0.0; 4], 0.0),
        };
        SraaFrame {
            sraa: params,
            projection,
            width: size.0,
            height: size.1,
            depth_miss,
            albedo_tolerance: ALBEDO_TOLERANCE,
            origin_x: origin.0,
            origin_y: origin.1,
            exposure: match resolve {
                ResolveSpace::ToneMapped { exposure } => exposure,
                ResolveSpace::Linear => 0.0,
            },
            _pad: 0,
        }
    }
}

/// [`CtssUniform::projection`]: the pinhole's rays (`subcone_pinhole_dir`).
pub const PROJECTION_PINHOLE: u32 = 0;
/// [`CtssUniform::projection`]: rays from the eye through the unprojected
/// pixel.
pub const PROJECTION_PERSPECTIVE: u32 = 1;
/// [`CtssUniform::projection`]: parallel rays from the plane of view depth 0.
pub const PROJECTION_ORTHOGRAPHIC: u32 = 2;

/// The CTSS pass's frame (`CtssUniform` in its WGSL, 192 bytes): the camera,
/// the background and the rect written.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "bytemuck", derive(bytemuck::Pod, bytemuck::Zeroable))]
pub struct CtssUniform {
    /// The pinhole ([`PROJECTION_PINHOLE`]), or the eye and frame of a
    /// projection; its width and height are the rect's.
    pub camera: PinholeCamera,
    /// The colour of what no surface covers (linear RGB).
    pub background: [f32; 3],
    /// [`PROJECTION_PINHOLE`], [`PROJECTION_PERSPECTIVE`] or
    /// [`PROJECTION_ORTHOGRAPHIC`].
    pub projection: u32,
    /// NDC to world, column-major (zero for a pinhole).
    pub inverse_view_projection: [[f32; 4]; 4],
    /// The unit forward axis: view depth of `x` is `forward·x + depth_offset`.
    pub forward: [f32; 3],
    /// View depth's offset, so that the eye is at depth 0.
    pub depth_offset: f32,
    /// The rect's first pixel in the output.
    pub origin: [u32; 2],
    /// The output's width: a buffer row's length.
    pub row_length: u32,
    /// Padding; zero.
    pub _pad: u32,
}

impl CtssUniform {
    /// The frame of `camera` traced as `projection` (with NDC-to-world
    /// `inverse_view_projection` for the matrix projections), view depth
    /// measured along `forward` from the camera's position, over a rect at
    /// `origin` of an output `row_length` pixels wide.
    pub fn new(
        camera: PinholeCamera,
        projection: u32,
        inverse_view_projection: [[f32; 4]; 4],
        forward: Vec3,
        background: Vec3,
        origin: [u32; 2],
        row_length: u32,
    ) -> Self {
        CtssUniform {
            camera,
            background: background.to_array(),
            projection,
            inverse_view_projection,
            forward: forward.to_array(),
            depth_offset: -forward.dot(Vec3::from(camera.position)),
            origin,
            row_length,
            _pad: 0,
        }
    }

    /// The frame of the pinhole `camera` (CTSS's cone about each pixel's
    /// ray, eq. 3), view depth along its own forward axis.
    pub fn pinhole(
        camera: PinholeCamera,
        background: Vec3,
        origin: [u32; 2],
        row_length: u32,
    ) -> Self {
        Self::new(
            camera,
            PROJECTION_PINHOLE,
            [[0.0; 4]; 4],
            Vec3::from(camera.forward),
            background,
            origin,
            row_length,
        )
    }
}
