//! The uniforms of the SRAA and CTSS passes' shaders, as C structs, and the
//! values the Rust passes write into them.

use glam::{Vec2, Vec3};
use subcone_kernels::camera::{look_frame, PinholeCamera};
use subcone_kernels::taa::ResolveSpace;
use subcone_kernels::uniforms::{CtssUniform, SraaFrame};

use crate::checks::{finite, finite_array, finite_vec, read, slice, write};
use crate::geometry::SubconeVec3;
use crate::params::{sraa_params, SubconeSraaParams};
use crate::status::{call, Refusal, SubconeStatus};
// What the documentation names.
#[cfg(doc)]
use crate::{ctss_trace::subcone_ctss_trace, params::SubconeCtssParams};

/// The uniform of the SRAA pass's shaders (`SraaFrame`, binding `frame` of
/// every `shaders/sraa/*` variant; the kernels' `uniforms::SraaFrame`, 80
/// bytes, its layout checked against naga's). Fill it with
/// [`subcone_sraa_pass_uniform`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeSraaPassUniform {
    /// The weights' parameters.
    pub sraa: SubconeSraaParams,
    /// Column-major `m[2][2], m[3][2], m[2][3], m[3][3]` of the projection
    /// that wrote hardware depth (zero for linear view depth).
    pub projection: [f32; 4],
    /// The image's (or rect's) width in pixels.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// The hardware depth of a miss (0 for reversed Z).
    pub depth_miss: f32,
    /// The material gate's tolerance (the kernels' `ALBEDO_TOLERANCE`).
    pub albedo_tolerance: f32,
    /// The rect's first pixel (0 for a whole image and for buffers).
    pub origin_x: u32,
    /// The rect's first row.
    pub origin_y: u32,
    /// The tone-mapped resolve's exposure (read only by a tone-mapped
    /// variant).
    pub exposure: f32,
    /// Padding; write 0.
    pub pad: u32,
}

impl From<SraaFrame> for SubconeSraaPassUniform {
    fn from(f: SraaFrame) -> Self {
        SubconeSraaPassUniform {
            sraa: f.sraa.into(),
            projection: f.projection,
            width: f.width,
            height: f.height,
            depth_miss: f.depth_miss,
            albedo_tolerance: f.albedo_tolerance,
            origin_x: f.origin_x,
            origin_y: f.origin_y,
            exposure: f.exposure,
            pad: f._pad,
        }
    }
}

/// The pinhole camera every CTSS shader traces through, the layout of the
/// kernels' `PinholeCamera` (80 bytes, `subcone_PinholeCamera` in WGSL):
/// pixel `(x, y)` of a `width × height` image is the ray through image
/// point `(x + ½, y + ½) + jitter` ([`subcone_pinhole_ray`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconePinholeCamera {
    /// The eye.
    pub position: [f32; 3],
    /// The image's width in pixels.
    pub width: u32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// The image's height in pixels.
    pub height: u32,
    /// Unit right vector (forward × up).
    pub right: [f32; 3],
    /// `tan(fov_y / 2)`.
    pub tan_half_fov: f32,
    /// Unit up vector.
    pub up: [f32; 3],
    /// Padding; write 0.
    pub pad0: u32,
    /// Sub-pixel offset of every ray, in pixels (a temporal method's
    /// jitter; 0 otherwise).
    pub jitter: [f32; 2],
    /// Padding; write 0.
    pub pad1: [u32; 2],
}

mirror_conversions!(SubconePinholeCamera <=> PinholeCamera {
    position: position,
    width: width,
    forward: forward,
    height: height,
    right: right,
    tan_half_fov: tan_half_fov,
    up: up,
    pad0: _pad,
    jitter: jitter,
    pad1: _pad2,
});

/// The uniform of the CTSS pass's shaders (`CtssUniform`, binding
/// `subcone_pass_frame` of every `shaders/ctss/*` variant; the kernels'
/// `uniforms::CtssUniform`, 192 bytes, its layout checked against naga's).
/// Fill it with [`subcone_ctss_pass_uniform`]; the trace's parameters are a
/// [`SubconeCtssParams`] at `subcone_pass_params`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubconeCtssPassUniform {
    /// The camera.
    pub camera: SubconePinholeCamera,
    /// The colour of what no surface covers (linear RGB).
    pub background: [f32; 3],
    /// 0: the pinhole `camera`; 1 and 2: a projection matrix (written by
    /// the Rust pass's `CtssProjection`).
    pub projection: u32,
    /// NDC to world, column-major (zero for the pinhole).
    pub inverse_view_projection: [[f32; 4]; 4],
    /// The unit axis of view depth (`forward·x + depth_offset`).
    pub forward: [f32; 3],
    /// View depth's offset (the eye at depth 0).
    pub depth_offset: f32,
    /// The first pixel written.
    pub origin: [u32; 2],
    /// The output's width: a buffer row's length.
    pub row_length: u32,
    /// Padding; write 0.
    pub pad: u32,
}

impl From<CtssUniform> for SubconeCtssPassUniform {
    fn from(u: CtssUniform) -> Self {
        SubconeCtssPassUniform {
            camera: u.camera.into(),
            background: u.background,
            projection: u.projection,
            inverse_view_projection: u.inverse_view_projection,
            forward: u.forward,
            depth_offset: u.depth_offset,
            origin: u.origin,
            row_length: u.row_length,
            pad: u._pad,
        }
    }
}

/// The SRAA pass's uniform for a `width × height` image resolved with
/// `params`: geometry of linear view depth (`shaders/sraa/packed`,
/// `buffers*`) when `projection` is null, else hardware depth written by
/// `projection` (16 floats, column-major, the host's projection matrix;
/// `shaders/sraa/msaa*`) with `depth_miss` the depth of a miss. `exposure`
/// is the tone-mapped resolve's (0 for the linear one). The values the
/// Rust `SraaPass` writes (the kernels' `SraaFrame::new`).
///
/// Errors: null `params` or `out`; a zero size; non-finite parameters,
/// projection or `depth_miss`; a negative or non-finite `exposure`.
///
/// # Safety
/// `params` and `out` are null or valid; `projection` is null or points to
/// 16 floats.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_pass_uniform(
    params: *const SubconeSraaParams,
    width: u32,
    height: u32,
    projection: *const f32,
    depth_miss: f32,
    exposure: f32,
    out: *mut SubconeSraaPassUniform,
) -> SubconeStatus {
    call("subcone_sraa_pass_uniform", || {
        let p = sraa_params(params)?;
        if width == 0 || height == 0 {
            return Err(Refusal::size(format!(
                "width × height is {width} × {height}; both must be at least 1"
            )));
        }
        finite(&[("depth_miss", depth_miss), ("exposure", exposure)])?;
        if exposure < 0.0 {
            return Err(Refusal::invalid(format!(
                "exposure is {exposure}; it must not be negative (0 for the linear resolve)"
            )));
        }
        // SAFETY: forwarded contract (null: linear depth).
        let m = unsafe {
            slice(
                projection,
                if projection.is_null() { 0 } else { 16 },
                "projection",
            )
        }?;
        finite_array("projection", m)?;
        // Column c of the column-major matrix is m[4c..4c + 4].
        let hardware_depth = (!m.is_empty()).then(|| {
            let column = |c: usize| [m[4 * c], m[4 * c + 1], m[4 * c + 2], m[4 * c + 3]];
            ([column(0), column(1), column(2), column(3)], depth_miss)
        });
        let resolve = if exposure > 0.0 {
            ResolveSpace::ToneMapped { exposure }
        } else {
            ResolveSpace::Linear
        };
        let frame = SraaFrame::new(p, (0, 0), (width, height), hardware_depth, resolve);
        // SAFETY: forwarded contract.
        unsafe { write(out, frame.into(), "out") }
    })
}

/// The CTSS pass's uniform for a pinhole camera at `eye` looking along
/// `forward` (`up_hint` roughly up, not parallel to it), vertical field of
/// view `fov_y` radians, a `width × height` image and `background`: pixel
/// `(x, y)` is the cone around the ray through `(x + ½, y + ½)`, exactly the
/// rays of the Rust `CtssCamera` (the kernels' `PinholeCamera`), which
/// [`subcone_ctss_trace`] takes as `origin`, `dir` and `up_hint`. The values
/// the Rust `CtssPass` writes (the kernels' `CtssUniform::pinhole`).
///
/// Errors: null `out`; a zero size; non-finite or degenerate camera
/// vectors (zero, or `forward` within a sine of 10⁻⁴ of parallel to
/// `up_hint`, the kernels' `LOOK_FRAME_MIN_SINE`, where the cross product
/// cancels too much to give a frame); `fov_y` outside `(0, π)`; a
/// non-finite background.
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn subcone_ctss_pass_uniform(
    eye: SubconeVec3,
    forward: SubconeVec3,
    up_hint: SubconeVec3,
    fov_y: f32,
    width: u32,
    height: u32,
    background: SubconeVec3,
    out: *mut SubconeCtssPassUniform,
) -> SubconeStatus {
    call("subcone_ctss_pass_uniform", || {
        if width == 0 || height == 0 {
            return Err(Refusal::size(format!(
                "width × height is {width} × {height}; both must be at least 1"
            )));
        }
        let (eye, forward, up_hint, background) = (
            Vec3::from(eye),
            Vec3::from(forward),
            Vec3::from(up_hint),
            Vec3::from(background),
        );
        finite(&[("fov_y", fov_y)])?;
        for (name, v) in [
            ("eye", eye),
            ("forward", forward),
            ("up_hint", up_hint),
            ("background", background),
        ] {
            finite_vec(name, v)?;
        }
        if !(fov_y > 0.0 && fov_y < std::f32::consts::PI) {
            return Err(Refusal::invalid(format!(
                "fov_y is {fov_y}; it must be in (0, π) radians"
            )));
        }
        // The Rust `CtssCamera::new`'s frame: right = forward × up.
        let (frame_forward, right, up) = look_frame(forward, up_hint);
        if frame_forward == Vec3::ZERO || right == Vec3::ZERO {
            return Err(Refusal::invalid(format!(
                "forward ({}, {}, {}) and up_hint ({}, {}, {}) give no camera frame: one is \
                     zero, or they are within a sine of 1e-4 of parallel",
                forward.x, forward.y, forward.z, up_hint.x, up_hint.y, up_hint.z
            )));
        }
        let forward = frame_forward;
        let camera = PinholeCamera::new(
            eye,
            (forward, right, up),
            (0.5 * fov_y).tan(),
            (width, height),
        );
        let uniform = CtssUniform::pinhole(camera, background, [0, 0], width);
        // SAFETY: forwarded contract.
        unsafe { write(out, uniform.into(), "out") }
    })
}

/// The unit direction of the ray through image point `(x, y)` (pixels, y
/// down; a pixel's centre is `(x + ½, y + ½)`) of the pinhole camera of
/// `uniform`: the direction the CTSS shaders trace (`subcone_pinhole_dir`),
/// to the bit on the CPU, for a host that traces the same pixel with
/// [`subcone_ctss_trace`] (`origin` the camera's `position`, `up_hint` its
/// `up`).
///
/// Errors: null pointers; a uniform that is not a pinhole (`projection`
/// not 0); non-finite `x`, `y` or camera.
///
/// # Safety
/// `uniform` and `out` are null or valid.
#[no_mangle]
pub unsafe extern "C" fn subcone_pinhole_ray(
    uniform: *const SubconeCtssPassUniform,
    x: f32,
    y: f32,
    out: *mut SubconeVec3,
) -> SubconeStatus {
    call("subcone_pinhole_ray", || {
        // SAFETY: forwarded contract.
        let u = unsafe { read(uniform, "uniform") }?;
        if u.projection != 0 {
            return Err(Refusal::invalid(format!(
                "uniform->projection is {}; the ray needs a pinhole uniform (projection 0)",
                u.projection
            )));
        }
        let camera = PinholeCamera::from(u.camera);
        finite(&[
            ("x", x),
            ("y", y),
            ("uniform->camera.tan_half_fov", camera.tan_half_fov),
        ])?;
        finite_array("uniform->camera.forward", &camera.forward)?;
        finite_array("uniform->camera.right", &camera.right)?;
        finite_array("uniform->camera.up", &camera.up)?;
        finite_array("uniform->camera.jitter", &camera.jitter)?;
        // SAFETY: forwarded contract.
        unsafe { write(out, camera.ray_dir(Vec2::new(x, y)).into(), "out") }
    })
}

// The pass uniforms have the layouts of the shaders' (the test
// `pass_uniforms` compares every member with naga's layout of the WGSL).
const _: () = {
    use std::mem::size_of;
    assert!(size_of::<SubconeSraaPassUniform>() == 80);
    assert!(size_of::<SubconeCtssPassUniform>() == 192);
};
