//! [`CtssPass`]: cone-traced supersampling (CTSS, Algorithm 1, eq. 3–10,
//! the group masks of §3.4–3.5, §5.3's splits) of the host's own signed
//! distance field, written in WGSL, `N × N` cones per pixel, into the
//! host's texture or storage buffer.
//!
//! The trace is the kernels' `subcone_ctss_trace`
//! (`subcone_kernels::ctss::TRACE_WGSL`), the WGSL twin of
//! `subcone_kernels::ctss::trace_field`, which the CPU renderer runs: a host
//! that writes its field once in Rust (a `ConeField`) and once in WGSL gets
//! the same image from both (the example `host_ctss` measures it).

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use subcone_kernels::camera::PinholeCamera;
use subcone_kernels::ctss::CtssParams;

use crate::bind::{self, check_buffer, required, Bound, Group, PassPipeline};
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

/// Most cones per pixel side ([`CtssPassDesc::samples_per_side`]).
pub const MAX_SAMPLES_PER_SIDE: u32 = 64;

/// The NoAA hook of the kernels' CTSS WGSL (`ctss_field`, which
/// `subcone_sphere_trace_split` marches) on the host's `subcone_field`:
/// (surface distance, safe step). [`CtssPass`] adds it to every shader it
/// builds; a renderer that sphere traces the same host field in a shader
/// of its own (`subcone-wgpu`'s SDF AOVs and SRAA-RT) adds the same line.
pub const SPHERE_TRACE_HOOK: &str =
    "fn ctss_field(p: vec3<f32>) -> vec2<f32> { let f = subcone_field(p); return f.xy; }\n";

/// The frame's camera and background; `CtssUniform` in `ctss.wgsl` (96
/// bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct CtssUniform {
    pub(crate) camera: PinholeCamera,
    pub(crate) background: [f32; 3],
    pub(crate) _pad: u32,
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
    /// Sub-pixel offset of every cone's axis, in pixels: pixel `(x, y)`'s
    /// axis passes through `(x + 0.5, y + 0.5) + jitter` (a temporal
    /// method's jitter, `PinholeCamera::jitter`); zero from [`Self::new`].
    pub jitter: glam::Vec2,
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
            jitter: glam::Vec2::ZERO,
        }
    }

    /// The ray through image point `p` (pixels, y down) of a
    /// `width × height` image: `(origin, unit direction)`, exactly as the
    /// pass computes it on the GPU (`subcone_kernels::camera`).
    pub fn ray(&self, p: glam::Vec2, width: u32, height: u32) -> (Vec3, Vec3) {
        (self.position, self.uniform((width, height)).ray_dir(p))
    }

    /// The camera as the pass's shader reads it, for a `size` image.
    fn uniform(&self, size: (u32, u32)) -> PinholeCamera {
        PinholeCamera::new(
            self.position,
            (self.forward, self.right, self.up),
            (0.5 * self.fov_y).tan(),
            size,
        )
        .with_jitter(self.jitter)
    }
}

/// Which trace runs each cone of a [`CtssPass`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CtssTrace {
    /// The kernels' `subcone_ctss_trace` (CTSS Algorithm 1, eq. 3–10, the
    /// group masks of §3.4–3.5, §5.3's splits) over the host's hooks.
    #[default]
    Kernels,
    /// The host's own trace of each cone,
    /// `fn subcone_trace(params: subcone_CtssParams, origin: vec3<f32>,
    /// dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, background:
    /// vec3<f32>) -> subcone_CtssTraceResult` (`color`, `samples` and
    /// `steps` are read; `right` and `up` are the cone's cross-section
    /// axes, `subcone_cross_section_frame`): for what the kernels' trace
    /// does not do, such as §5.3's semi-transparent objects with `K` masks,
    /// or a sphere-traced reference (NoAA, SSAA) through the same pixel
    /// loop. The host still defines the field hooks: the kernels' trace is
    /// compiled with the shader.
    Host,
}

/// Where a [`CtssPass`] writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CtssOutput {
    /// A storage texture of [`CtssPassDesc::output_format`]
    /// ([`CtssPass::encode`]).
    #[default]
    Texture,
    /// Storage buffers ([`CtssPass::encode_buffers`]): the colour as
    /// `array<vec4<f32>>`, row-major, alpha 1; with `counts`, also per
    /// pixel `vec4<u32>(steps, shaded samples, c.x, c.y)`, the field
    /// evaluations and shaded hit groups of its cones and the host's two
    /// counters `c = subcone_counters()` (a `fn subcone_counters() ->
    /// vec2<u32>` the host then defines, read after the pixel's last cone:
    /// shadow rays and occlusion rays, say, kept in `var<private>`s of its
    /// own, which start at zero in every invocation).
    Buffers {
        /// Write the per-pixel counts.
        counts: bool,
    },
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
    /// `Rgba32Float` (a storage texture; linear colour, alpha 1). Checked
    /// for the texture output only.
    pub output_format: wgpu::TextureFormat,
    /// The layout of the host's own bind group, which its WGSL declares as
    /// `@group(1)` (uniforms, textures its field or shading reads). The pass
    /// owns `@group(0)`.
    pub host_layout: Option<&'a wgpu::BindGroupLayout>,
    /// Cones per pixel side, in `1..=MAX_SAMPLES_PER_SIDE`: pixel `(x, y)`
    /// averages the `N × N` cones through the image points
    /// `(x + (i + ½)/N, y + (j + ½)/N)` (SSAA over CTSS; 1 is the papers'
    /// one cone through the pixel centre). The cone's angle is the
    /// parameters' `tan_theta`: a host narrows it with `N`.
    pub samples_per_side: u32,
    /// Which trace runs each cone.
    pub trace: CtssTrace,
    /// Where the pass writes.
    pub output: CtssOutput,
}

impl Default for CtssPassDesc<'_> {
    /// A batch of 8, one cone per pixel, the kernels' trace, `Rgba16Float`
    /// texture output, no host bind group.
    fn default() -> Self {
        CtssPassDesc {
            batch: 8,
            output_format: wgpu::TextureFormat::Rgba16Float,
            host_layout: None,
            samples_per_side: 1,
            trace: CtssTrace::Kernels,
            output: CtssOutput::Texture,
        }
    }
}

impl<'a> CtssPassDesc<'a> {
    with_setters! {
        /// With `batch` hit groups marched ahead of shading ([`Self::batch`]).
        with_batch(batch: u32);
        /// Writing `output_format` ([`Self::output_format`]).
        with_output_format(output_format: wgpu::TextureFormat);
        /// With `samples_per_side × samples_per_side` cones per pixel
        /// ([`Self::samples_per_side`]).
        with_samples_per_side(samples_per_side: u32);
        /// Tracing each cone with `trace` ([`Self::trace`]).
        with_trace(trace: CtssTrace);
        /// Writing to `output` ([`Self::output`]).
        with_output(output: CtssOutput);
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

/// One frame of a [`CtssPass`] that writes buffers
/// ([`CtssOutput::Buffers`], [`CtssPass::encode_buffers`]).
#[derive(Clone, Copy, Debug)]
pub struct CtssBuffers<'a> {
    /// The camera.
    pub camera: CtssCamera,
    /// The trace's parameters ([`CtssFrame::params`]).
    pub params: CtssParams,
    /// The colour of the part of a pixel no surface covers (linear RGB).
    pub background: Vec3,
    /// The host's bind group: given exactly when the desc had a layout.
    pub host_group: Option<&'a wgpu::BindGroup>,
    /// The image's width and height in pixels.
    pub size: (u32, u32),
    /// The colours: `width × height` `vec4<f32>`s, `STORAGE` usage.
    pub output: &'a wgpu::Buffer,
    /// The counts: `width × height` `vec4<u32>`s, `STORAGE` usage; given
    /// exactly when the desc asks for them.
    pub counts: Option<&'a wgpu::Buffer>,
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
/// With [`CtssTrace::Host`] it also defines `subcone_trace`, and with
/// counted buffer output `subcone_counters` ([`CtssOutput::Buffers`]).
///
/// It must not declare `@group(0)` bindings, `subcone_CTSS_BATCH`,
/// `ctss_field` ([`SPHERE_TRACE_HOOK`], which the pass adds) or names
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
#[derive(Debug)]
pub struct CtssPass {
    output_format: wgpu::TextureFormat,
    output: CtssOutput,
    host_group: bool,
    pipeline: PassPipeline,
}

/// The shader's variant functions and constant, from the desc's typed
/// choices: the cones per side (`subcone_pass_SIDE`), the trace
/// (`subcone_pass_trace`) and where a pixel is stored
/// (`subcone_pass_store`).
fn variant_wgsl(desc: &CtssPassDesc<'_>) -> String {
    let trace = match desc.trace {
        CtssTrace::Kernels => "subcone_ctss_trace",
        CtssTrace::Host => "subcone_trace",
    };
    let store = match desc.output {
        CtssOutput::Texture => {
            "textureStore(subcone_pass_output, vec2<i32>(p), vec4<f32>(color, 1.0));"
        }
        CtssOutput::Buffers { counts: false } => {
            "subcone_pass_output[subcone_pass_index(p)] = vec4<f32>(color, 1.0);"
        }
        CtssOutput::Buffers { counts: true } => {
            "let i = subcone_pass_index(p);\n    \
             subcone_pass_output[i] = vec4<f32>(color, 1.0);\n    \
             subcone_pass_counts[i] = vec4<u32>(steps, samples, subcone_counters());"
        }
    };
    format!(
        "const subcone_pass_SIDE: u32 = {side}u;\n\
         fn subcone_pass_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, \
         right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {{\n    \
         return {trace}(params, origin, dir, right, up, background);\n}}\n\
         fn subcone_pass_store(p: vec2<u32>, color: vec3<f32>, steps: u32, samples: u32) {{\n    \
         {store}\n}}\n",
        side = desc.samples_per_side
    )
}

impl CtssPass {
    /// Build the pass for the host's WGSL (compile its pipeline). Refuses a
    /// batch outside `1..=MAX_BATCH`, cones per side outside
    /// `1..=MAX_SAMPLES_PER_SIDE` and a texture format it cannot write; a
    /// host source that does not compile is a validation error on the
    /// host's device, reported through the host's own error handling.
    pub fn new(
        device: &wgpu::Device,
        host_wgsl: &str,
        desc: &CtssPassDesc<'_>,
    ) -> Result<Self, PassError> {
        if desc.output == CtssOutput::Texture {
            bind::check_output_format(desc.output_format)?;
        }
        if !(1..=MAX_BATCH).contains(&desc.batch) {
            return Err(PassError::Config(format!(
                "batch {}: subcone_CTSS_BATCH must be in 1..={MAX_BATCH}",
                desc.batch
            )));
        }
        if !(1..=MAX_SAMPLES_PER_SIDE).contains(&desc.samples_per_side) {
            return Err(PassError::Config(format!(
                "samples_per_side {}: must be in 1..={MAX_SAMPLES_PER_SIDE}",
                desc.samples_per_side
            )));
        }
        let group = Self::group(desc.output_format, desc.output)?;
        let source = Self::source(host_wgsl, desc, &group);
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
            output: desc.output,
            host_group: desc.host_layout.is_some(),
            pipeline,
        })
    }

    pub(crate) fn group(
        output_format: wgpu::TextureFormat,
        output: CtssOutput,
    ) -> Result<Group, PassError> {
        let mut g = Group::default();
        g.ring_uniform::<CtssUniform>("subcone_pass_frame", "CtssUniform");
        g.ring_uniform::<CtssParams>("subcone_pass_params", "subcone_CtssParams");
        match output {
            CtssOutput::Texture => g.storage_texture("subcone_pass_output", output_format)?,
            CtssOutput::Buffers { counts } => {
                let rw = bind::BufferAccess::ReadWrite;
                g.buffer("subcone_pass_output", "array<vec4<f32>>", rw);
                if counts {
                    g.buffer("subcone_pass_counts", "array<vec4<u32>>", rw);
                }
            }
        }
        Ok(g)
    }

    /// The whole shader: the kernels, the batch, the host's WGSL (and the
    /// default normal), the desc's variant, the pass's entry point, the
    /// declarations.
    pub(crate) fn source(host_wgsl: &str, desc: &CtssPassDesc<'_>, group: &Group) -> String {
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
            &format!("const subcone_CTSS_BATCH: u32 = {}u;\n", desc.batch),
            SPHERE_TRACE_HOOK,
            host_wgsl,
            "\n",
            normal,
            &variant_wgsl(desc),
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
        if self.output != CtssOutput::Texture {
            return Err(PassError::Config(format!(
                "CtssOutput::{:?} is encoded with encode_buffers",
                self.output
            )));
        }
        let out = frame.output;
        let size = bind::check_output(out, self.output_format, "the desc's output_format")?;
        let host = "host bind group";
        required(frame.host_group, self.host_group, host, host)?;
        self.record(
            device,
            queue,
            encoder,
            (&frame.camera, &frame.params, frame.background, size),
            &[("subcone_pass_output", Bound::Texture(out))],
            frame.host_group,
            timestamps,
        )
    }

    /// Record the trace of one frame into storage buffers, as
    /// [`Self::encode`] does into a texture: one compute pass, every buffer
    /// checked first (usage and size for `frame.size`; the counts given
    /// exactly when the desc asks for them), so that on an error nothing is
    /// recorded or written.
    pub fn encode_buffers(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame: &CtssBuffers<'_>,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let CtssOutput::Buffers { counts } = self.output else {
            return Err(PassError::Config(
                "CtssOutput::Texture is encoded with encode (a texture)".into(),
            ));
        };
        let (width, height) = frame.size;
        if width == 0 || height == 0 {
            return Err(PassError::Config(format!(
                "size {width}×{height}: nothing to trace"
            )));
        }
        let n = u64::from(width) * u64::from(height);
        check_buffer("output", frame.output, n, 16)?;
        let counts_buffer = "counts buffer";
        required(frame.counts, counts, counts_buffer, counts_buffer)?;
        let host = "host bind group";
        required(frame.host_group, self.host_group, host, host)?;
        let mut bound = vec![("subcone_pass_output", Bound::Buffer(frame.output))];
        if let Some(c) = frame.counts {
            check_buffer("counts", c, n, 16)?;
            bound.push(("subcone_pass_counts", Bound::Buffer(c)));
        }
        self.record(
            device,
            queue,
            encoder,
            (&frame.camera, &frame.params, frame.background, frame.size),
            &bound,
            frame.host_group,
            timestamps,
        )
    }

    /// Write the frame's uniforms and record the dispatch over `size`.
    #[allow(clippy::too_many_arguments)]
    fn record(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        (camera, params, background, size): (&CtssCamera, &CtssParams, Vec3, (u32, u32)),
        resources: &[(&'static str, Bound<'_>)],
        host_group: Option<&wgpu::BindGroup>,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let uniform = CtssUniform {
            camera: camera.uniform(size),
            background: background.into(),
            _pad: 0,
        };
        self.pipeline.encode(
            device,
            queue,
            encoder,
            size,
            &[bytemuck::bytes_of(&uniform), bytemuck::bytes_of(params)],
            resources,
            host_group,
            timestamps,
        )
    }

    /// Drop the bind groups cached for the output views seen so far, and
    /// with them the pass's clones of those views.
    pub fn release_views(&self) {
        self.pipeline.release_views();
    }
}
