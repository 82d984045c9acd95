//! [`CtssPass`]: cone-traced supersampling (CTSS, Algorithm 1, eq. 3–10,
//! the group masks of §3.4–3.5, §5.3's splits) of the host's own signed
//! distance field, written in WGSL, one cone per pixel, into the host's
//! texture.
//!
//! The trace is the kernels' `subcone_ctss_trace`
//! (`subcone_kernels::ctss::TRACE_WGSL`), the WGSL twin of
//! `subcone_kernels::ctss::trace_field`, which the CPU renderer runs: a host
//! that writes its field once in Rust (a `ConeField`) and once in WGSL gets
//! the same image from both (the example `host_ctss` measures it).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use subcone_kernels::ctss::CtssParams;

use crate::bind::{self, Bound, Group, PassPipeline};
use crate::PassError;

pub(crate) const CTSS_WGSL: &str = include_str!("ctss.wgsl");
/// The kernels' WGSL a CTSS trace (`subcone_ctss_trace`) runs, in the order
/// a shader includes them, after `subcone_kernels::wgsl::PARAMS`: the cone
/// (eq. 3–5), the masks (eq. 7–8), the aggregate (eq. 6), §5.3's K masks,
/// the stepper and the trace. [`CtssPass`] composes its shader from them;
/// a renderer tracing CTSS in a shader of its own (`subcone-wgpu`'s SDF
/// renderer) includes the same.
pub const CTSS_KERNELS: [&str; 6] = [
    subcone_kernels::cone::WGSL,
    subcone_kernels::mask::WGSL,
    subcone_kernels::aggregate::WGSL,
    subcone_kernels::transparency::WGSL,
    subcone_kernels::ctss::WGSL,
    subcone_kernels::ctss::TRACE_WGSL,
];

/// Most hit groups a trace may march ahead of shading them.
pub const MAX_BATCH: u32 = 64;

/// The frame's camera; `CtssUniform` in `ctss.wgsl` (80 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct CtssUniform {
    pub(crate) position: [f32; 3],
    pub(crate) width: u32,
    pub(crate) forward: [f32; 3],
    pub(crate) height: u32,
    pub(crate) right: [f32; 3],
    pub(crate) half: f32,
    pub(crate) up: [f32; 3],
    pub(crate) _pad0: u32,
    pub(crate) background: [f32; 3],
    pub(crate) _pad1: u32,
}

/// A pinhole camera: the eye and an orthonormal frame. Pixel `(x, y)` of a
/// `width × height` image (x right, y down) is the cone around the ray
/// through image point `(x + 0.5, y + 0.5)` ([`CtssCamera::ray`]), of half
/// angle `params.tan_theta` (CTSS eq. 3: `cone_tan_theta`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CtssCamera {
    /// The eye.
    pub position: Vec3,
    /// Unit view direction.
    pub forward: Vec3,
    /// Unit right vector, orthogonal to `forward`.
    pub right: Vec3,
    /// Unit up vector, orthogonal to both.
    pub up: Vec3,
    /// Vertical field of view in radians.
    pub fov_y: f32,
}

impl CtssCamera {
    /// A camera at `position` looking along `forward`, `up_hint` roughly up
    /// (not parallel to `forward`); the frame is orthonormalised, right =
    /// forward × up.
    pub fn new(position: Vec3, forward: Vec3, up_hint: Vec3, fov_y: f32) -> Self {
        let forward = forward.normalize_or_zero();
        let right = forward.cross(up_hint).normalize_or_zero();
        let up = right.cross(forward);
        CtssCamera {
            position,
            forward,
            right,
            up,
            fov_y,
        }
    }

    /// The ray through image point `p` (pixels, y down) of a
    /// `width × height` image: `(origin, unit direction)`, exactly as the
    /// pass computes it on the GPU.
    pub fn ray(&self, p: glam::Vec2, width: u32, height: u32) -> (Vec3, Vec3) {
        let (w, h) = (width.max(1) as f32, height.max(1) as f32);
        let half = (0.5 * self.fov_y).tan();
        let u = (2.0 * p.x / w - 1.0) * half * (w / h);
        let v = (1.0 - 2.0 * p.y / h) * half;
        let d = self.forward + u * self.right + v * self.up;
        (self.position, d * (1.0 / d.length()))
    }
}

/// The configuration of a [`CtssPass`], fixed for its life. Start from
/// `CtssPassDesc::default()` and change what differs with the `with_`
/// methods (or assign the public fields): the struct is
/// `#[non_exhaustive]`, so a field added later breaks no host.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub struct CtssPassDesc<'a> {
    /// `subcone_CTSS_BATCH`: hit groups marched ahead of shading them, in
    /// `1..=MAX_BATCH` (64). 8 suits shading that is cheap; the result does
    /// not depend on it (eq. 6 adds the same terms in the same order).
    pub batch: u32,
    /// The output texture's format: `Rgba8Unorm`, `Rgba16Float` or
    /// `Rgba32Float` (a storage texture; linear colour, alpha 1).
    pub output_format: wgpu::TextureFormat,
    /// The layout of the host's own bind group, which its WGSL declares as
    /// `@group(1)` (uniforms, textures its field or shading reads). The pass
    /// owns `@group(0)`.
    pub host_layout: Option<&'a wgpu::BindGroupLayout>,
}

impl Default for CtssPassDesc<'_> {
    /// A batch of 8, `Rgba16Float` output, no host bind group.
    fn default() -> Self {
        CtssPassDesc {
            batch: 8,
            output_format: wgpu::TextureFormat::Rgba16Float,
            host_layout: None,
        }
    }
}

impl<'a> CtssPassDesc<'a> {
    /// With `batch` hit groups marched ahead of shading ([`Self::batch`]).
    pub fn with_batch(mut self, batch: u32) -> Self {
        self.batch = batch;
        self
    }

    /// Writing `format` ([`Self::output_format`]).
    pub fn with_output_format(mut self, format: wgpu::TextureFormat) -> Self {
        self.output_format = format;
        self
    }

    /// With the host's own bind group `layout` as `@group(1)`
    /// ([`Self::host_layout`]).
    pub fn with_host_layout(mut self, layout: &'a wgpu::BindGroupLayout) -> Self {
        self.host_layout = Some(layout);
        self
    }
}

/// One frame of a [`CtssPass`].
#[derive(Clone, Copy, Debug)]
pub struct CtssFrame<'a> {
    /// The camera.
    pub camera: CtssCamera,
    /// The trace's parameters: `CtssParams::new(tan_theta)` with
    /// `tan_theta = subcone_kernels::cone::cone_tan_theta(fov_y, height,
    /// subcone_kernels::ctss::CONE_COVERAGE, PixelFootprint::Circumscribed)`
    /// for subcone's default cone, `.with_range(0.0, far)` and
    /// `.with_max_steps(n)` (every trace ends within `n` field evaluations
    /// plus a few).
    pub params: CtssParams,
    /// The colour of the part of a pixel no surface covers (linear RGB).
    pub background: Vec3,
    /// The host's bind group: given exactly when the desc had a layout.
    pub host_group: Option<&'a wgpu::BindGroup>,
    /// Where the image is written: a view of a whole one-sample 2D texture
    /// of one layer, with `STORAGE_BINDING` (checked on
    /// `TextureView::texture`).
    pub output: &'a wgpu::TextureView,
}

/// CTSS of the host's field on the host's device.
///
/// The host's WGSL defines, after the kernels' sources (so it may call any
/// `subcone_` function, e.g. `subcone_tetra_normal`):
///
/// - `fn subcone_field(p: vec3<f32>) -> vec3<f32>`: (signed distance, a safe
///   step `≤` distance, object id). The id is the `u32` of the kernels'
///   `ctss::FieldSample::object` and the C ABI's `SubconeFieldSample::object`
///   (a material index, say), carried in an `f32`: an integer below 2²⁴ is
///   exact; a negative or NaN value reads as
///   `subcone_kernels::ctss::NO_OBJECT` (`0xFFFFFFFF`, `subcone_NO_OBJECT`
///   in WGSL), no object, which never ends a group. A group of hits ends
///   where the id changes (CTSS §3.4: one group, one surface).
/// - `fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32>`:
///   the linear colour of surface point `p` with unit normal `n` seen along
///   `dir`.
/// - optionally `fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32>`: the
///   unit normal from differences of step `h`; when the source has no
///   `fn subcone_normal`, the pass adds the default, tetrahedral differences
///   of `subcone_field` (`subcone_tetra_normal`, the CPU's
///   `ConeField::normal`).
///
/// It must not declare `@group(0)` bindings, `subcone_CTSS_BATCH` or names
/// starting with `subcone_pass_`.
///
/// Built once, encoded every frame: after the first frame with a given
/// output view, `encode` creates no buffer, texture, bind group or
/// pipeline (the camera and parameters go into slots of uniform buffers
/// made in `new`, [`crate::UNIFORM_SLOTS`]; the bind group of the output
/// view is cached, [`crate::BIND_GROUP_CACHE`]).
///
/// ```no_run
/// # fn f(device: &wgpu::Device, queue: &wgpu::Queue, encoder: &mut wgpu::CommandEncoder,
/// #      output: &wgpu::TextureView)
/// # -> Result<(), subcone_passes::PassError> {
/// use glam::Vec3;
/// use subcone_kernels::ctss::CtssParams;
/// use subcone_passes::{CtssCamera, CtssFrame, CtssPass, CtssPassDesc};
/// let host_wgsl = "
///     fn subcone_field(p: vec3<f32>) -> vec3<f32> {
///         let d = length(p - vec3<f32>(0.0, 0.0, 5.0)) - 1.0;
///         return vec3<f32>(d, d, 0.0);
///     }
///     fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
///         return vec3<f32>(max(n.y, 0.0));
///     }";
/// let pass = CtssPass::new(device, host_wgsl, &CtssPassDesc::default())?;
/// let camera = CtssCamera::new(Vec3::ZERO, Vec3::Z, Vec3::Y, 0.8);
/// pass.encode(device, queue, encoder, &CtssFrame {
///     camera,
///     params: CtssParams::new(0.002).with_range(0.0, 100.0).with_max_steps(256),
///     background: Vec3::ZERO,
///     host_group: None,
///     output,
/// }, None)?;
/// # Ok(()) }
/// ```
pub struct CtssPass {
    output_format: wgpu::TextureFormat,
    host_group: bool,
    pipeline: PassPipeline,
}

impl std::fmt::Debug for CtssPass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CtssPass")
            .field("output_format", &self.output_format)
            .field("host_group", &self.host_group)
            .finish()
    }
}

impl CtssPass {
    /// Build the pass for the host's WGSL (compile its pipeline). Refuses a
    /// batch outside `1..=MAX_BATCH` and an output format it cannot write;
    /// a host source that does not compile is a validation error on the
    /// host's device, reported through the host's own error handling.
    pub fn new(
        device: &wgpu::Device,
        host_wgsl: &str,
        desc: &CtssPassDesc<'_>,
    ) -> Result<Self, PassError> {
        bind::check_output_format(desc.output_format)?;
        if !(1..=MAX_BATCH).contains(&desc.batch) {
            return Err(PassError::Config(format!(
                "batch {}: subcone_CTSS_BATCH must be in 1..={MAX_BATCH}",
                desc.batch
            )));
        }
        let group = Self::group(desc.output_format)?;
        let source = Self::source(host_wgsl, desc.batch, &group);
        let pipeline = PassPipeline::new(
            device,
            "subcone ctss",
            group,
            source,
            desc.host_layout,
            "subcone_pass_ctss_main",
        )?;
        Ok(CtssPass {
            output_format: desc.output_format,
            host_group: desc.host_layout.is_some(),
            pipeline,
        })
    }

    #[cfg(test)]
    pub(crate) fn group_for_tests(output_format: wgpu::TextureFormat) -> Group {
        Self::group(output_format).expect("an output format")
    }

    fn group(output_format: wgpu::TextureFormat) -> Result<Group, PassError> {
        let mut g = Group::default();
        g.ring_uniform::<CtssUniform>("subcone_pass_frame", "CtssUniform");
        g.ring_uniform::<CtssParams>("subcone_pass_params", "subcone_CtssParams");
        g.storage_texture("subcone_pass_output", output_format)?;
        Ok(g)
    }

    /// The whole shader: the kernels, the batch, the host's WGSL (and the
    /// default normal), the pass's entry point, the declarations.
    pub(crate) fn source(host_wgsl: &str, batch: u32, group: &Group) -> String {
        let normal = if host_wgsl.contains("fn subcone_normal") {
            ""
        } else {
            "fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> { return subcone_tetra_normal(p, h); }\n"
        };
        let [cone, mask, aggregate, transparency, ctss, trace] = CTSS_KERNELS;
        [
            subcone_kernels::wgsl::PARAMS,
            cone,
            mask,
            aggregate,
            transparency,
            ctss,
            trace,
            &format!("const subcone_CTSS_BATCH: u32 = {batch}u;\n"),
            // ctss::WGSL's NoAA hook, on the host's field.
            "fn ctss_field(p: vec3<f32>) -> vec2<f32> { let f = subcone_field(p); return f.xy; }\n",
            host_wgsl,
            "\n",
            normal,
            CTSS_WGSL,
            &group.declarations(),
        ]
        .concat()
    }

    /// Record the trace of one frame into `encoder` (one compute pass), its
    /// camera and parameters written through `queue`. Checks the output and
    /// the host group first: on an error nothing is recorded or written.
    ///
    /// `timestamps`, when given, are written at the start and end of the
    /// compute pass: the host creates the query set (`QueryType::Timestamp`,
    /// on a device with `Features::TIMESTAMP_QUERY`), resolves it and reads
    /// it back.
    pub fn encode(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame: &CtssFrame<'_>,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let out = frame.output;
        let size = bind::check_output(out, self.output_format, "the desc's output_format")?;
        match (self.host_group, frame.host_group) {
            (true, None) => return Err(PassError::Missing("host bind group")),
            (false, Some(_)) => return Err(PassError::Unexpected("host bind group")),
            _ => {}
        }
        let c = &frame.camera;
        let uniform = CtssUniform {
            position: c.position.into(),
            width: size.0,
            forward: c.forward.into(),
            height: size.1,
            right: c.right.into(),
            half: (0.5 * c.fov_y).tan(),
            up: c.up.into(),
            _pad0: 0,
            background: frame.background.into(),
            _pad1: 0,
        };
        self.pipeline.encode(
            device,
            queue,
            encoder,
            size,
            &[
                bytemuck::bytes_of(&uniform),
                bytemuck::bytes_of(&frame.params),
            ],
            &[("subcone_pass_output", Bound::Texture(out))],
            frame.host_group,
            timestamps,
        )
    }

    /// Drop the bind groups cached for the output views seen so far, and
    /// with them the pass's clones of those views.
    pub fn release_views(&self) {
        self.pipeline.release_views();
    }
}
