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

use glam::{Mat4, Vec3, Vec4};
use subcone_kernels::aggregate::Weighting;
use subcone_kernels::camera::PinholeCamera;
use subcone_kernels::ctss::CtssParams;

use crate::bind::{self, check_buffer, required, Bound, Group, PassPipeline};
use crate::bind::{
    BindGroup, BindGroupLayout, Buffer, CommandEncoder, ComputePassTimestampWrites, Device, Queue,
    TextureFormat, TextureUsages, TextureView,
};
use crate::skeleton::{self, PassNames, PassShader};
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

/// The frame's camera, background and rectangle; `CtssUniform` in
/// `ctss.wgsl` (192 bytes).
pub(crate) use subcone_kernels::uniforms::CtssUniform;
use subcone_kernels::uniforms::{PROJECTION_ORTHOGRAPHIC, PROJECTION_PERSPECTIVE};

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
    /// forward × up (`subcone_kernels::camera::look_frame`: unit even for
    /// tiny, huge or nearly parallel vectors; zero where there is no frame).
    pub fn new(position: Vec3, forward: Vec3, up_hint: Vec3, fov_y: f32) -> Self {
        let (forward, right, up) = subcone_kernels::camera::look_frame(forward, up_hint);
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

/// A camera given by the host's matrices, as its rasteriser uses them: a
/// jittered projection (a temporal method's), an off-axis frustum (a tile of
/// a larger image, a stereo eye) or an orthographic projection.
///
/// Pixel `(x, y)` of the pass's `w × h` rectangle (x right, y down) is the
/// cone about the ray through NDC point `(2(x + ½)/w − 1, 1 − 2(y + ½)/h)`
/// (the pixel centre as wgpu's viewport transform maps it), unprojected
/// through `(projection · view)⁻¹`:
///
/// - **perspective** (the projection's last row is `(0, 0, ±1, 0)` up to
///   scale: clip `w` is the view depth): from the eye (`view⁻¹ · (0, 0, 0,
///   1)`) through the unprojected point at NDC depth ½, which any depth
///   convention (`[0, 1]`, reversed, infinite far plane, `[−1, 1]`) places
///   inside the frustum. With the pinhole's frame and a symmetric frustum
///   this is [`CtssCamera`]'s ray, up to rounding; the cone's half angle is
///   the parameters' `tan_theta` (CTSS eq. 3), as for the pinhole.
/// - **orthographic** (the last row is `(0, 0, 0, w)`): parallel rays
///   through the unprojected points at NDC depths ¼ and ¾, starting on the
///   plane of view depth 0 (so that the parameters' range is in view depth,
///   as for the pinhole). A pixel of an orthographic camera has a constant
///   footprint, a cone of zero angle and non-zero radius; the kernels'
///   cone has its apex at the ray's origin (eq. 3: `R_c = t·tan θ`) and no
///   constant term, so the pass traces it with `tan_theta = 0`: one ray per
///   cone, a hit or a miss (NoAA edges; `N × N` cones per pixel,
///   [`CtssPassDesc::samples_per_side`], antialias it as SSAA does). A
///   non-zero `tan_theta` is refused ([`PassError::Config`]).
///
/// Any other projection (a last row mixing both forms) is refused. The view
/// matrix is rigid (a rotation and a translation) and the view space's
/// forward axis is `±z`: the one of the two on which the frustum lies (the
/// unprojected NDC point `(0, 0, ½)`), so right- and left-handed views and
/// every depth convention work. View depth ([`CtssDepth::View`]) is the
/// distance from the eye (perspective) or from the view's origin
/// (orthographic) along that axis: `−z_view` for glam's `look_at_rh`,
/// `perspective_rh` and `orthographic_rh`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CtssProjection {
    /// World to view.
    pub view: Mat4,
    /// View to clip, as the host rasterises with it (jitter included).
    pub projection: Mat4,
}

impl CtssProjection {
    /// The camera of `view` and `projection`.
    pub fn new(view: Mat4, projection: Mat4) -> Self {
        CtssProjection { view, projection }
    }

    /// The pass's uniform fields for this camera over a `size` rectangle,
    /// or why it cannot be traced with `params`.
    fn uniform(
        &self,
        params: &CtssParams,
        size: (u32, u32),
    ) -> Result<(PinholeCamera, u32, Mat4, Vec3), PassError> {
        let refuse = |why: &str| PassError::Config(format!("CtssProjection: {why}"));
        let last = self.projection.row(3);
        let projection = if last.truncate() == Vec3::ZERO && last.w != 0.0 {
            PROJECTION_ORTHOGRAPHIC
        } else if last.w == 0.0 && last.truncate() != Vec3::ZERO {
            PROJECTION_PERSPECTIVE
        } else {
            return Err(refuse(
                "the projection is neither perspective (last row (0, 0, ±1, 0)) nor \
                 orthographic (last row (0, 0, 0, w))",
            ));
        };
        if projection == PROJECTION_ORTHOGRAPHIC && params.tan_theta != 0.0 {
            return Err(refuse(&format!(
                "tan_theta {}: an orthographic pixel's cone has zero angle and a constant \
                 radius, which the kernels' cone (R_c = t·tan θ, CTSS eq. 3) cannot trace; \
                 trace it with tan_theta 0",
                params.tan_theta
            )));
        }
        let inverse_view = self.view.inverse();
        let inverse = (self.projection * self.view).inverse();
        let middle = self.projection.inverse() * Vec4::new(0.0, 0.0, 0.5, 1.0);
        let side = if middle.z / middle.w < 0.0 { -1.0 } else { 1.0 };
        let forward = inverse_view
            .transform_vector3(Vec3::new(0.0, 0.0, side))
            .normalize_or_zero();
        let up = inverse_view.transform_vector3(Vec3::Y).normalize_or_zero();
        let eye = inverse_view.transform_point3(Vec3::ZERO);
        if !(inverse.is_finite() && eye.is_finite() && forward != Vec3::ZERO && up != Vec3::ZERO) {
            return Err(refuse("the view or the view-projection is not invertible"));
        }
        let right = forward.cross(up);
        let camera = PinholeCamera::new(eye, (forward, right, up), 0.0, size);
        Ok((camera, projection, inverse, forward))
    }
}

/// The camera of one [`CtssPass`] frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CtssView {
    /// A pinhole: the rays of [`CtssCamera::ray`], bit for bit (subcone's
    /// own SDF frames trace these).
    Pinhole(CtssCamera),
    /// The host's view and projection matrices.
    Projection(CtssProjection),
}

impl From<CtssCamera> for CtssView {
    fn from(camera: CtssCamera) -> Self {
        CtssView::Pinhole(camera)
    }
}

impl From<CtssProjection> for CtssView {
    fn from(projection: CtssProjection) -> Self {
        CtssView::Projection(projection)
    }
}

/// The part of a frame's output a [`CtssPass`] writes: `size` pixels from
/// `origin` (x right, y down), for dynamic resolution or split screen. The
/// camera's image is the rectangle: its pixel `(x, y)` is the one a
/// `size[0] × size[1]` output would hold at `(x, y)`, written at
/// `origin + (x, y)`; pixels outside it are not written. `None` in a frame
/// is the whole output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CtssRect {
    /// The rectangle's first pixel.
    pub origin: [u32; 2],
    /// Its width and height, both above 0.
    pub size: [u32; 2],
}

impl CtssRect {
    /// The rectangle, checked against an output of `full` pixels.
    fn within(rect: Option<CtssRect>, full: (u32, u32)) -> Result<CtssRect, PassError> {
        let Some(r) = rect else {
            return Ok(CtssRect {
                origin: [0, 0],
                size: [full.0, full.1],
            });
        };
        let fits = |o: u32, s: u32, f: u32| s > 0 && o.checked_add(s).is_some_and(|e| e <= f);
        if fits(r.origin[0], r.size[0], full.0) && fits(r.origin[1], r.size[1], full.1) {
            Ok(r)
        } else {
            Err(PassError::Config(format!(
                "CtssRect at ({}, {}) of {}×{} does not fit in the {}×{} output \
                 (or is empty)",
                r.origin[0], r.origin[1], r.size[0], r.size[1], full.0, full.1
            )))
        }
    }
}

/// What a [`CtssPass`] writes for the part of a pixel no surface covers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CtssBackground {
    /// The frame's background colour, weighted into eq. 6 as a sample of
    /// its own; alpha 1.
    #[default]
    Opaque,
    /// Nothing: premultiplied colour (eq. 6 resolved against black) and
    /// alpha the pixel's coverage from the group masks (CTSS §3.4–3.5,
    /// `subcone_kernels::ctss::coverage_alpha`: `bitCount(M)/32`, or 1 when
    /// the trace ended on full occlusion, a hard hit of the axis or the
    /// visibility threshold), the mean over a pixel's `N × N` cones. The
    /// host composites it with `over` (`c + (1 − α)·background`), which
    /// gives the [`Self::Opaque`] image up to rounding. The frame's
    /// background is not read. Needs the parameters' default weighting
    /// (visibility weights, `min_sample_weight` 0: then the hit weights sum
    /// to the coverage); others are refused ([`PassError::Config`]). With
    /// [`CtssTrace::Host`] the host's `subcone_trace` gives the coverage
    /// (`coverage`, `stop`) and resolves against the black background it is
    /// passed.
    Transparent,
}

/// Whether a [`CtssPass`] also writes each pixel's view depth.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CtssDepth {
    /// No depth.
    #[default]
    None,
    /// View depth, an `R32Float` storage texture ([`CtssFrame::depth`]) or
    /// one `f32` a pixel ([`CtssBuffers::depth`]): the distance along the
    /// camera's forward axis to the nearest hit group that adds to the
    /// pixel's colour (weight above 0 in eq. 6; its sample depth, the
    /// backtraced entry of eq. 10 or the backtraced hard hit of §3.6), the
    /// least over the pixel's `N × N` cones; `+∞` where none does.
    ///
    /// The nearest group, not a coverage-weighted mean: an edge pixel's
    /// fractional alpha belongs to the surface it partly shows, so a host
    /// that depth-tests it against its raster scene and composites it with
    /// `over` ([`CtssBackground::Transparent`]) puts the fringe in front of
    /// what that surface is in front of; a mean of depths would lie between
    /// surfaces (or be infinite) and match none of them.
    View,
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
    /// `steps` are read, `coverage` and `stop` with
    /// [`CtssBackground::Transparent`], `depth` with [`CtssDepth::View`];
    /// `right` and `up` are the cone's cross-section
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
    /// `array<vec4<f32>>`, row-major (alpha as [`CtssPassDesc::background`]
    /// says); with `counts`, also per
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
    /// `Rgba32Float` (a storage texture; linear colour, alpha as
    /// [`Self::background`] says). Checked
    /// for the texture output only.
    pub output_format: TextureFormat,
    /// The layout of the host's own bind group, which its WGSL declares as
    /// `@group(1)` (uniforms, textures its field or shading reads). The pass
    /// owns `@group(0)`.
    pub host_layout: Option<&'a BindGroupLayout>,
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
    /// What the part of a pixel no surface covers becomes.
    pub background: CtssBackground,
    /// Whether view depth is written too.
    pub depth: CtssDepth,
}

impl Default for CtssPassDesc<'_> {
    /// A batch of 8, one cone per pixel, the kernels' trace, `Rgba16Float`
    /// texture output, an opaque background, no depth, no host bind group.
    fn default() -> Self {
        CtssPassDesc {
            batch: 8,
            output_format: TextureFormat::Rgba16Float,
            host_layout: None,
            samples_per_side: 1,
            trace: CtssTrace::Kernels,
            output: CtssOutput::Texture,
            background: CtssBackground::Opaque,
            depth: CtssDepth::None,
        }
    }
}

impl<'a> CtssPassDesc<'a> {
    with_setters! {
        /// With `batch` hit groups marched ahead of shading ([`Self::batch`]).
        with_batch(batch: u32);
        /// Writing `output_format` ([`Self::output_format`]).
        with_output_format(output_format: TextureFormat);
        /// With `samples_per_side × samples_per_side` cones per pixel
        /// ([`Self::samples_per_side`]).
        with_samples_per_side(samples_per_side: u32);
        /// Tracing each cone with `trace` ([`Self::trace`]).
        with_trace(trace: CtssTrace);
        /// Writing to `output` ([`Self::output`]).
        with_output(output: CtssOutput);
        /// With `background` ([`Self::background`]).
        with_background(background: CtssBackground);
        /// Writing `depth` too ([`Self::depth`]).
        with_depth(depth: CtssDepth);
    }

    /// With the host's own bind group `layout` as `@group(1)`
    /// ([`Self::host_layout`]).
    pub fn with_host_layout(mut self, layout: &'a BindGroupLayout) -> Self {
        self.host_layout = Some(layout);
        self
    }
}

/// One frame of a [`CtssPass`].
#[derive(Clone, Copy, Debug)]
pub struct CtssFrame<'a> {
    /// The camera (a [`CtssCamera`] or a [`CtssProjection`], `.into()`).
    pub camera: CtssView,
    /// The trace's parameters: `CtssParams::new(tan_theta)` with
    /// `tan_theta = subcone_kernels::cone::cone_tan_theta(fov_y, height,
    /// subcone_kernels::ctss::CONE_COVERAGE, PixelFootprint::Circumscribed)`
    /// for subcone's default cone, `.with_range(0.0, far)` and
    /// `.with_max_steps(n)` (every trace ends within `n` field evaluations
    /// plus a few).
    pub params: CtssParams,
    /// The colour of the part of a pixel no surface covers (linear RGB;
    /// read with [`CtssBackground::Opaque`]).
    pub background: Vec3,
    /// The host's bind group: given exactly when the desc had a layout.
    pub host_group: Option<&'a BindGroup>,
    /// Where the image is written: a view of a whole one-sample 2D texture
    /// of one layer, with `STORAGE_BINDING` (checked on
    /// `TextureView::texture`).
    pub output: &'a TextureView,
    /// Where view depth is written ([`CtssDepth::View`]): a texture as
    /// `output`, of its size, `R32Float`; given exactly when the desc asks
    /// for depth.
    pub depth: Option<&'a TextureView>,
    /// The part of `output` (and `depth`) written; `None`: all of it.
    pub rect: Option<CtssRect>,
}

/// One frame of a [`CtssPass`] that writes buffers
/// ([`CtssOutput::Buffers`], [`CtssPass::encode_buffers`]).
#[derive(Clone, Copy, Debug)]
pub struct CtssBuffers<'a> {
    /// The camera ([`CtssFrame::camera`]).
    pub camera: CtssView,
    /// The trace's parameters ([`CtssFrame::params`]).
    pub params: CtssParams,
    /// The colour of the part of a pixel no surface covers (linear RGB;
    /// read with [`CtssBackground::Opaque`]).
    pub background: Vec3,
    /// The host's bind group: given exactly when the desc had a layout.
    pub host_group: Option<&'a BindGroup>,
    /// The image's width and height in pixels (the buffers' rows).
    pub size: (u32, u32),
    /// The part of the image written; `None`: all of it.
    pub rect: Option<CtssRect>,
    /// The colours: `width × height` `vec4<f32>`s, `STORAGE` usage.
    pub output: &'a Buffer,
    /// The counts: `width × height` `vec4<u32>`s, `STORAGE` usage; given
    /// exactly when the desc asks for them.
    pub counts: Option<&'a Buffer>,
    /// The view depths ([`CtssDepth::View`]): `width × height` `f32`s,
    /// `STORAGE` usage; given exactly when the desc asks for depth.
    pub depth: Option<&'a Buffer>,
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
/// view is cached, [`crate::BIND_GROUP_CACHE`]). Many encodes in one
/// submission (viewports, [`CtssRect`]s) each read their own camera: a
/// slot an unsubmitted encode binds is never rewritten (the ring grows
/// instead); call [`CtssPass::end_submission`] after each submit.
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
///     camera: camera.into(),
///     params: CtssParams::new(0.002).with_range(0.0, 100.0).with_max_steps(256),
///     background: Vec3::ZERO,
///     host_group: None,
///     output,
///     depth: None,
///     rect: None,
/// }, None)?;
/// // After the host's `queue.submit(…)` of this encoder:
/// pass.end_submission();
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct CtssPass {
    output_format: TextureFormat,
    output: CtssOutput,
    background: CtssBackground,
    depth: CtssDepth,
    host_group: bool,
    pipeline: PassPipeline,
}

/// The shader's variant functions and constant, from the desc's typed
/// choices: the cones per side (`subcone_pass_SIDE`), the trace
/// (`subcone_pass_trace`), the pixel's colour (`subcone_pass_color`: alpha
/// 1, or premultiplied with coverage) and where a pixel is stored
/// (`subcone_pass_store`).
fn variant_wgsl(desc: &CtssPassDesc<'_>) -> String {
    let trace = match desc.trace {
        CtssTrace::Kernels => "subcone_ctss_trace",
        CtssTrace::Host => "subcone_trace",
    };
    let color = match desc.background {
        CtssBackground::Opaque => "vec4<f32>(color, 1.0)",
        CtssBackground::Transparent => "vec4<f32>(color, alpha)",
    };
    let depth = desc.depth == CtssDepth::View;
    let store = match (desc.output, depth) {
        (CtssOutput::Texture, false) => {
            "textureStore(subcone_pass_output, vec2<i32>(p), c);".to_string()
        }
        (CtssOutput::Texture, true) => "textureStore(subcone_pass_output, vec2<i32>(p), c);\n    \
             textureStore(subcone_pass_depth, vec2<i32>(p), vec4<f32>(depth, 0.0, 0.0, 1.0));"
            .to_string(),
        (CtssOutput::Buffers { counts }, _) => {
            let mut s = "let i = subcone_pass_index(p);\n    \
                         subcone_pass_output[i] = c;"
                .to_string();
            if counts {
                s +=
                    "\n    subcone_pass_counts[i] = vec4<u32>(steps, samples, subcone_counters());";
            }
            if depth {
                s += "\n    subcone_pass_depth[i] = depth;";
            }
            s
        }
    };
    format!(
        "const subcone_pass_SIDE: u32 = {side}u;\n\
         fn subcone_pass_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, \
         right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {{\n    \
         return {trace}(params, origin, dir, right, up, background);\n}}\n\
         fn subcone_pass_color(color: vec3<f32>, alpha: f32) -> vec4<f32> {{\n    \
         return {color};\n}}\n\
         fn subcone_pass_store(p: vec2<u32>, c: vec4<f32>, depth: f32, steps: u32, samples: u32) {{\n    \
         {store}\n}}\n",
        side = desc.samples_per_side
    )
}

impl CtssPass {
    /// Build the pass for the host's WGSL (compile its pipeline). Refuses a
    /// batch outside `1..=MAX_BATCH`, cones per side outside
    /// `1..=MAX_SAMPLES_PER_SIDE` and a texture format it cannot write. A
    /// host source that does not compile (a syntax or type error, a missing
    /// hook) is [`PassError::Shader`] with naga's message, caught in the
    /// pass's own error scope: the device's uncaptured-error handler does
    /// not see it, so the host learns it where it built the pass.
    pub fn new(
        device: &Device,
        host_wgsl: &str,
        desc: &CtssPassDesc<'_>,
    ) -> Result<Self, PassError> {
        let pipeline = skeleton::pipeline::<Self>(device, &CtssKey { host_wgsl, desc })?;
        Ok(CtssPass {
            output_format: desc.output_format,
            output: desc.output,
            background: desc.background,
            depth: desc.depth,
            host_group: desc.host_layout.is_some(),
            pipeline,
        })
    }

    /// Record the trace of one frame into `encoder` (one compute pass), its
    /// camera and parameters written through `queue`. Checks the output, the
    /// depth texture, the rectangle, the host group and the camera first: on
    /// an error nothing is recorded or written.
    ///
    /// `timestamps`, when given, are written at the start and end of the
    /// compute pass: the host creates the query set (`QueryType::Timestamp`,
    /// on a device with `Features::TIMESTAMP_QUERY`), resolves it and reads
    /// it back.
    pub fn encode(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        frame: &CtssFrame<'_>,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        if self.output != CtssOutput::Texture {
            return Err(PassError::Config(format!(
                "CtssOutput::{:?} is encoded with encode_buffers",
                self.output
            )));
        }
        let out = frame.output;
        let size = bind::check_output(out, self.output_format, "the desc's output_format")?;
        let rect = CtssRect::within(frame.rect, size)?;
        let host = "host bind group";
        required(frame.host_group, self.host_group, host, host)?;
        let depth = "depth texture";
        required(frame.depth, self.depth == CtssDepth::View, depth, depth)?;
        let mut bound = vec![("subcone_pass_output", Bound::Texture(out))];
        if let Some(d) = frame.depth {
            bind::check(
                d,
                &bind::Expect {
                    what: "depth",
                    size,
                    samples: 1,
                    layers: 1,
                    usage: TextureUsages::STORAGE_BINDING,
                },
            )?;
            if d.texture().format() != TextureFormat::R32Float {
                return Err(PassError::Format {
                    what: "depth",
                    found: d.texture().format(),
                    expected: "R32Float",
                });
            }
            bound.push(("subcone_pass_depth", Bound::Texture(d)));
        }
        self.record(
            device,
            queue,
            encoder,
            (&frame.camera, &frame.params, frame.background, size, rect),
            &bound,
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
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        frame: &CtssBuffers<'_>,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
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
        let rect = CtssRect::within(frame.rect, frame.size)?;
        let n = u64::from(width) * u64::from(height);
        check_buffer("output", frame.output, n, 16)?;
        let counts_buffer = "counts buffer";
        required(frame.counts, counts, counts_buffer, counts_buffer)?;
        let depth_buffer = "depth buffer";
        let depth = self.depth == CtssDepth::View;
        required(frame.depth, depth, depth_buffer, depth_buffer)?;
        let host = "host bind group";
        required(frame.host_group, self.host_group, host, host)?;
        let mut bound = vec![("subcone_pass_output", Bound::Buffer(frame.output))];
        if let Some(c) = frame.counts {
            check_buffer("counts", c, n, 16)?;
            bound.push(("subcone_pass_counts", Bound::Buffer(c)));
        }
        if let Some(d) = frame.depth {
            check_buffer("depth", d, n, 4)?;
            bound.push(("subcone_pass_depth", Bound::Buffer(d)));
        }
        self.record(
            device,
            queue,
            encoder,
            (
                &frame.camera,
                &frame.params,
                frame.background,
                frame.size,
                rect,
            ),
            &bound,
            frame.host_group,
            timestamps,
        )
    }

    /// Write the frame's uniforms and record the dispatch over `rect` of a
    /// `size` output. Refuses a transparent background under weights that
    /// do not sum to the coverage, and a projection the pass cannot trace.
    #[allow(clippy::too_many_arguments)]
    fn record(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        (view, params, background, size, rect): (
            &CtssView,
            &CtssParams,
            Vec3,
            (u32, u32),
            CtssRect,
        ),
        resources: &[(&'static str, Bound<'_>)],
        host_group: Option<&BindGroup>,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let background = match self.background {
            CtssBackground::Opaque => background,
            CtssBackground::Transparent => {
                if params.weighting() != Weighting::Visibility || params.min_sample_weight > 0.0 {
                    return Err(PassError::Config(
                        "CtssBackground::Transparent: the hit weights must sum to the coverage \
                         (visibility weighting, min_sample_weight 0)"
                            .into(),
                    ));
                }
                Vec3::ZERO
            }
        };
        let rect_size = (rect.size[0], rect.size[1]);
        let uniform = match view {
            CtssView::Pinhole(c) => {
                CtssUniform::pinhole(c.uniform(rect_size), background, rect.origin, size.0)
            }
            CtssView::Projection(p) => {
                let (camera, projection, inverse, forward) = p.uniform(params, rect_size)?;
                CtssUniform::new(
                    camera,
                    projection,
                    inverse.to_cols_array_2d(),
                    forward,
                    background,
                    rect.origin,
                    size.0,
                )
            }
        };
        self.pipeline.encode(
            device,
            queue,
            encoder,
            rect_size,
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

    /// Tell the pass that every command buffer it was encoded into so far
    /// has been submitted (`Queue::submit`), so its uniform slots may be
    /// rewritten: call it after each submit that holds this pass's encodes.
    ///
    /// Why: `encode` writes its uniforms with `Queue::write_buffer`, which
    /// lands before *any* command of the next submission runs, so a slot
    /// still bound by an unsubmitted encode is never rewritten; a new value
    /// takes a free slot, or the ring grows ([`crate::UNIFORM_SLOTS`] to
    /// [`crate::MAX_UNIFORM_SLOTS`]). Without this call a slot is freed only
    /// once its command buffer has run on the GPU and the host polled the
    /// device (or submitted again): still correct, but the ring may grow
    /// further, and a host that never submits gets
    /// [`PassError::UniformSlotsExhausted`]. Calling it while an encode of
    /// this pass is recorded but not submitted breaks that encode: it may
    /// read a later encode's values.
    pub fn end_submission(&self) {
        self.pipeline.end_submission();
    }
}

/// What a [`CtssPass`] is built for: the host's WGSL and the desc (what
/// [`CtssPass::new`] and `standalone::ctss` take).
#[derive(Clone, Copy, Debug)]
pub(crate) struct CtssKey<'a> {
    /// The host's field, shading and optional hooks.
    pub(crate) host_wgsl: &'a str,
    /// The configuration.
    pub(crate) desc: &'a CtssPassDesc<'a>,
}

impl PassShader for CtssPass {
    const NAMES: PassNames = PassNames::new("ctss", "subcone ctss", "subcone_pass_ctss_main");
    type Key<'a> = CtssKey<'a>;

    /// Refuse what [`CtssPass::new`] refuses before compiling: a batch
    /// or cones per side out of range, a texture format it cannot write.
    fn check(&CtssKey { desc, .. }: &CtssKey<'_>) -> Result<(), PassError> {
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
        Ok(())
    }

    fn group(&CtssKey { desc, .. }: &CtssKey<'_>) -> Result<Group, PassError> {
        let mut g = Group::default();
        g.ring_uniform::<CtssUniform>("subcone_pass_frame", "CtssUniform");
        g.ring_uniform::<CtssParams>("subcone_pass_params", "subcone_CtssParams");
        let depth = desc.depth == CtssDepth::View;
        match desc.output {
            CtssOutput::Texture => {
                g.storage_texture("subcone_pass_output", desc.output_format)?;
                if depth {
                    g.storage_texture("subcone_pass_depth", TextureFormat::R32Float)?;
                }
            }
            CtssOutput::Buffers { counts } => {
                let rw = bind::BufferAccess::ReadWrite;
                g.buffer("subcone_pass_output", "array<vec4<f32>>", rw);
                if counts {
                    g.buffer("subcone_pass_counts", "array<vec4<u32>>", rw);
                }
                if depth {
                    g.buffer("subcone_pass_depth", "array<f32>", rw);
                }
            }
        }
        Ok(g)
    }

    /// The kernels, the batch, the host's WGSL (and the default normal),
    /// the desc's variant, the pass's entry point.
    fn wgsl(&CtssKey { host_wgsl, desc }: &CtssKey<'_>) -> String {
        let normal = if host_wgsl.contains("fn subcone_normal") {
            ""
        } else {
            "fn subcone_normal(p: vec3<f32>, h: f32) -> vec3<f32> { return subcone_tetra_normal(p, h); }\n"
        };
        let [cone, mask, aggregate, transparency, ctss, trace] = CTSS_KERNELS;
        [
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
        ]
        .concat()
    }

    fn host_layout<'a>(key: &Self::Key<'a>) -> Option<&'a BindGroupLayout> {
        key.desc.host_layout
    }

    /// The desc alone: the host's WGSL is in the shader.
    fn summary(key: &CtssKey<'_>) -> String {
        format!("{:?}", key.desc)
    }
}
