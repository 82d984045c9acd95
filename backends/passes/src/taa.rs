//! [`TaaPass`]: temporal antialiasing (`subcone_kernels::taa`: Karis,
//! "High Quality Temporal Supersampling", 2014, with Salvi's variance
//! clipping, 2016) of the host's jittered frame against its history.
//!
//! An engine's motion vectors in other units or of the other sign
//! ([`TaaInputs::motion_scale`]) and its depth (closest-depth dilation,
//! `TaaSettings::depth_dilation` and [`TaaInputs::depth`]): the crate
//! README's "TAA with an engine's motion vectors and depth" has the lines a
//! Bevy- or FSR2-style host writes.

use subcone_kernels::taa::{TaaParams, TaaSettings};

use bytemuck::{Pod, Zeroable};

use crate::bind::{self, Bound, Expect, Group, PassPipeline, Rect};
use crate::bind::{
    CommandEncoder, ComputePassTimestampWrites, Device, Queue, TextureFormat, TextureUsages,
    TextureView,
};
use crate::skeleton::{self, PassNames, PassShader};
use crate::PassError;

pub(crate) const TAA_WGSL: &str = include_str!("taa.wgsl");

/// `taa_pixel_motion` without a depth input: the pixel's own vector.
const TAA_OWN_MOTION: &str = "
// taa.rs: the pixel's own motion vector.
fn taa_pixel_motion(xy: vec2<i32>) -> vec2<f32> {
    return taa_motion(xy.x, xy.y);
}
";

/// `taa_pixel_motion` with a depth input: the vector of the nearest depth
/// of the 3×3 neighbourhood (`subcone_kernels::taa::dilated_motion`), and
/// the depth fetch it calls.
const TAA_DILATED_MOTION: &str = "
// taa.rs: the host's depth of a pixel.
fn taa_depth(x: i32, y: i32) -> f32 {
    return textureLoad(taa_depth_tex, taa_at(x, y), 0).x;
}

// taa.rs: the motion vector of the nearest depth around the pixel.
fn taa_pixel_motion(xy: vec2<i32>) -> vec2<f32> {
    return subcone_taa_dilated_motion(xy, taa_params);
}
";

/// Where the resolved image lies in the textures; `TaaOrigin` in `taa.wgsl`
/// (16 bytes): the top-left pixel of the rect ([`TaaPass::encode_rect`]),
/// `(0, 0)` for whole textures.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct TaaOrigin {
    pub(crate) x: u32,
    pub(crate) y: u32,
    pub(crate) _pad: [u32; 2],
}

/// The configuration of a [`TaaPass`], fixed for its life. Start from
/// `TaaPassDesc::default()` and change what differs with the `with_`
/// methods (or assign the public fields): the struct is
/// `#[non_exhaustive]`, so a field added later breaks no host.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct TaaPassDesc {
    /// The sequence's settings (`subcone_kernels::taa::TaaSettings`):
    /// jitter phases of [`TaaPass::jitter`], where the resolve clips and
    /// blends (linear radiance by default, where a still camera converges to
    /// the box filter of its samples, or Karis' tone-mapped space with the
    /// display's exposure, for HDR content), the current frame's smallest
    /// weight, variance clipping's `γ`, and closest-depth motion dilation
    /// (off by default; on, the pass binds a depth input,
    /// [`TaaInputs::depth`], and compiles the dilation into its shader).
    pub settings: TaaSettings,
    /// The output texture's format: `Rgba16Float` (the default) or
    /// `Rgba32Float` (a storage texture; linear radiance, alpha 1). The
    /// output is the next frame's history, so an 8-bit format would
    /// quantise what accumulates and is refused.
    pub output_format: TextureFormat,
}

impl Default for TaaPassDesc {
    fn default() -> Self {
        TaaPassDesc {
            settings: TaaSettings::default(),
            output_format: TextureFormat::Rgba16Float,
        }
    }
}

impl TaaPassDesc {
    with_setters! {
        /// With the sequence's `settings` ([`Self::settings`]).
        with_settings(settings: TaaSettings);
        /// Writing `output_format` ([`Self::output_format`]).
        with_output_format(output_format: TextureFormat);
    }

    /// Check every field against its domain.
    pub(crate) fn validate(&self) -> Result<(), PassError> {
        self.settings
            .validate()
            .map_err(|e| PassError::Config(format!("TaaPassDesc: {e}")))?;
        if !matches!(
            self.output_format,
            TextureFormat::Rgba16Float | TextureFormat::Rgba32Float
        ) {
            return Err(PassError::Format {
                what: "the desc's output_format",
                found: self.output_format,
                expected: "Rgba16Float or Rgba32Float (the history accumulates in it)",
            });
        }
        Ok(())
    }
}

/// One frame's inputs of a [`TaaPass`]: views of whole one-sample textures
/// of the output's size, each `TEXTURE_BINDING` with a float, unorm or
/// snorm format. [`TaaInputs::new`] fills the optional ones (no depth,
/// vectors in pixels).
#[derive(Clone, Copy, Debug)]
pub struct TaaInputs<'a> {
    /// This frame's colour (`.xyz`, linear radiance), rendered through the
    /// projection jittered by [`TaaPass::jitter`] of the frame.
    pub current: &'a TextureView,
    /// Each pixel's motion vector (`.xy`) for the un-jittered projections,
    /// which times [`Self::motion_scale`] is its motion in pixels, current
    /// minus previous position of the surface it shows (`+x` right, `+y`
    /// down).
    pub velocity: &'a TextureView,
    /// What each motion vector is multiplied by, component by component
    /// (FSR2's `motionVectorScale`, with the sign that makes it current
    /// minus previous): `[1.0, 1.0]` for pixel vectors, `[width, height]`
    /// for Bevy's, `[-1.0, -1.0]` for FSR2's pixel vectors (see the crate
    /// README). A component that is 0 or not finite reads as 1.
    pub motion_scale: [f32; 2],
    /// Each pixel's depth (`.x`), in the order the desc's
    /// [`TaaSettings::depth_dilation`] says: given exactly when that
    /// dilation is on (a [`PassError::Config`] otherwise).
    pub depth: Option<&'a TextureView>,
    /// The previous frame's output (read only when `history_frames > 0`,
    /// but always bound). Not the output's texture: the host ping-pongs two.
    pub history: &'a TextureView,
    /// Frames accumulated in the history: 0 on the first frame and after a
    /// cut (a reset: the output is the current frame), then the host
    /// counts up (it sets how fast the running mean becomes an exponential
    /// one).
    pub history_frames: u32,
}

impl<'a> TaaInputs<'a> {
    /// The inputs of a frame whose motion vectors are pixels (current minus
    /// previous) and that binds no depth.
    pub fn new(
        current: &'a TextureView,
        velocity: &'a TextureView,
        history: &'a TextureView,
        history_frames: u32,
    ) -> Self {
        TaaInputs {
            current,
            velocity,
            motion_scale: [1.0, 1.0],
            depth: None,
            history,
            history_frames,
        }
    }

    /// The same inputs with motion vectors multiplied by `scale`
    /// ([`Self::motion_scale`]).
    pub fn with_motion_scale(mut self, scale: [f32; 2]) -> Self {
        self.motion_scale = scale;
        self
    }

    /// The same inputs with `depth` ([`Self::depth`]).
    pub fn with_depth(mut self, depth: &'a TextureView) -> Self {
        self.depth = Some(depth);
        self
    }
}

/// TAA on the host's device: resolves this frame's jittered colour against
/// the reprojected history into a storage texture, which is the next frame's
/// history (`subcone_kernels::taa::resolve_pixel`, the CPU twin, computes
/// the same per pixel). Neighbourhood and history taps are clamped to the
/// image; a pixel whose reprojected point lies off the image takes the
/// current colour. Motion vectors are scaled per frame
/// ([`TaaInputs::motion_scale`]: Bevy's UV vectors by `(width, height)`,
/// FSR2's by `(−1, −1)`); with `TaaSettings::depth_dilation` on, each pixel
/// takes the vector of the nearest depth of its 3×3 neighbourhood
/// (`subcone_kernels::taa::dilated_motion`, Karis 2014; FSR2's
/// reconstruct & dilate) from the depth input ([`TaaInputs::depth`]).
/// The crate README shows the lines an engine host writes.
///
/// Built once, encoded every frame: after the first frame with given views,
/// `encode` creates no buffer, texture, bind group or pipeline
/// ([`crate::UNIFORM_SLOTS`], [`crate::BIND_GROUP_CACHE`]); call its
/// `end_submission` after each submit that holds its encodes, so that its
/// uniform slots are free for the next.
///
/// ```no_run
/// # fn frame(device: &wgpu::Device, queue: &wgpu::Queue, encoder: &mut wgpu::CommandEncoder,
/// #     current: &wgpu::TextureView, velocity: &wgpu::TextureView,
/// #     history: [&wgpu::TextureView; 2], frame_index: u32) -> Result<(), subcone_passes::PassError> {
/// use subcone_passes::{TaaInputs, TaaPass, TaaPassDesc};
///
/// let taa = TaaPass::new(device, &TaaPassDesc::default())?;
/// // Jitter the projection by `taa.jitter(frame_index)` pixels, render
/// // `current` and `velocity`, then resolve, ping-ponging two histories.
/// let (read, write) = (history[(frame_index % 2) as usize], history[((frame_index + 1) % 2) as usize]);
/// let inputs = TaaInputs::new(current, velocity, read, frame_index);
/// taa.encode(device, queue, encoder, &inputs, write, None)?;
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct TaaPass {
    desc: TaaPassDesc,
    pipeline: PassPipeline,
}

impl TaaPass {
    /// Build the pass (compile its pipeline, make its uniform buffers) for
    /// `desc`. Refuses a desc outside its domain.
    pub fn new(device: &Device, desc: &TaaPassDesc) -> Result<Self, PassError> {
        let pipeline = skeleton::pipeline::<Self>(device, desc)?;
        Ok(TaaPass {
            desc: *desc,
            pipeline,
        })
    }

    /// The configuration.
    pub fn desc(&self) -> &TaaPassDesc {
        &self.desc
    }

    /// The sub-pixel offset, in pixels, to jitter frame `frame`'s projection
    /// by: Halton (2, 3) over the desc's phases
    /// (`subcone_kernels::taa::jitter`). For a projection matrix, add
    /// `(2·x / width, −2·y / height)` to its third column's NDC offsets.
    pub fn jitter(&self, frame: u32) -> glam::Vec2 {
        self.desc.settings.jitter(frame)
    }

    /// Record the resolve of `inputs` into `output` (one compute pass), the
    /// parameters written through `queue`. Checks every view first: on an
    /// error nothing is recorded or written. Every texture is the output's
    /// size.
    ///
    /// `timestamps`, when given, are written at the start and end of the
    /// compute pass (the host's query set, which it resolves).
    pub fn encode(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        inputs: &TaaInputs<'_>,
        output: &TextureView,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        self.encode_region(device, queue, encoder, inputs, output, None, timestamps)
    }

    /// Record the resolve of `rect` of the textures (a viewport: dynamic
    /// resolution, split screen): every input is read, and the output
    /// written, at the rect's pixels, and the output's pixels outside it are
    /// left as they were. Each texture must hold the rect (a
    /// [`PassError::Rect`] otherwise, also for an empty rect). The rect is
    /// the image: the 3×3 neighbourhood and the history's taps are clamped
    /// to it, and a point reprojected off it has no history, so the rect's
    /// pixels are exactly those of the pass over textures of the rect's size
    /// holding the same inputs.
    #[allow(clippy::too_many_arguments)]
    pub fn encode_rect(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        inputs: &TaaInputs<'_>,
        output: &TextureView,
        rect: Rect,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        self.encode_region(
            device,
            queue,
            encoder,
            inputs,
            output,
            Some(&rect),
            timestamps,
        )
    }

    /// [`Self::encode`] of `rect` (the whole output for `None`).
    #[allow(clippy::too_many_arguments)]
    fn encode_region(
        &self,
        device: &Device,
        queue: &Queue,
        encoder: &mut CommandEncoder,
        inputs: &TaaInputs<'_>,
        output: &TextureView,
        rect: Option<&Rect>,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let region = bind::check_output_region(
            output,
            self.desc.output_format,
            "the desc's output_format",
            rect,
        )?;
        let dilation = self.desc.settings.depth_dilation;
        match (dilation.is_on(), inputs.depth) {
            (true, None) => {
                return Err(PassError::Config(format!(
                    "TAA with depth dilation {dilation:?} needs a depth: set TaaInputs::depth"
                )))
            }
            (false, Some(_)) => {
                return Err(PassError::Config(
                    "TAA given a depth with depth dilation off: set the desc's \
                     settings.depth_dilation, or give no depth"
                        .into(),
                ))
            }
            _ => {}
        }
        let mut views = vec![
            ("current", inputs.current),
            ("velocity", inputs.velocity),
            ("history", inputs.history),
        ];
        views.extend(inputs.depth.map(|d| ("depth", d)));
        for &(what, view) in &views {
            bind::check_region(
                view,
                &Expect {
                    what,
                    size: region.size(),
                    samples: 1,
                    layers: 1,
                    usage: TextureUsages::TEXTURE_BINDING,
                },
                rect,
            )?;
            bind::check_float_color(what, view)?;
            if view.texture() == output.texture() {
                return Err(PassError::Config(format!(
                    "TAA cannot write the {what} texture it reads: ping-pong two histories"
                )));
            }
        }
        let params: TaaParams = self
            .desc
            .settings
            .params(region.size(), inputs.history_frames)
            .with_motion_scale(inputs.motion_scale);
        let origin = TaaOrigin {
            x: region.x,
            y: region.y,
            _pad: [0; 2],
        };
        let mut bound = vec![
            ("taa_current_tex", Bound::Texture(inputs.current)),
            ("taa_velocity", Bound::Texture(inputs.velocity)),
            ("taa_history_tex", Bound::Texture(inputs.history)),
        ];
        bound.extend(inputs.depth.map(|d| ("taa_depth_tex", Bound::Texture(d))));
        bound.push(("taa_dst", Bound::Texture(output)));
        self.pipeline.encode(
            device,
            queue,
            encoder,
            region.size(),
            &[bytemuck::bytes_of(&params), bytemuck::bytes_of(&origin)],
            &bound,
            None,
            timestamps,
        )
    }

    /// Drop the bind groups cached for the views seen so far, and with them
    /// the pass's clones of those views.
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

impl PassShader for TaaPass {
    const NAMES: PassNames = PassNames::new("taa", "subcone taa", "taa_main");
    type Key<'a> = TaaPassDesc;

    /// Refuses a desc outside its domain.
    fn check(desc: &TaaPassDesc) -> Result<(), PassError> {
        desc.validate()?;
        bind::check_output_format(desc.output_format)
    }

    /// The bindings, writing the desc's output format; with depth dilation,
    /// the depth after the history.
    fn group(desc: &TaaPassDesc) -> Result<Group, PassError> {
        let mut g = Group::default();
        g.ring_uniform::<TaaParams>("taa_params", "subcone_TaaParams");
        g.ring_uniform::<TaaOrigin>("taa_origin", "TaaOrigin");
        let mut inputs = vec!["taa_current_tex", "taa_velocity", "taa_history_tex"];
        if desc.settings.depth_dilation.is_on() {
            inputs.push("taa_depth_tex");
        }
        skeleton::filter_textures(g, &inputs, "taa_dst", desc.output_format)
    }

    /// The kernels' TAA, the pixel's motion fetch (with depth dilation, the
    /// kernels' dilation over the depth input) and `taa.wgsl`.
    fn wgsl(desc: &TaaPassDesc) -> String {
        let motion = if desc.settings.depth_dilation.is_on() {
            [subcone_kernels::taa::DILATION_WGSL, TAA_DILATED_MOTION].concat()
        } else {
            TAA_OWN_MOTION.to_string()
        };
        [subcone_kernels::taa::WGSL, &motion, TAA_WGSL].concat()
    }
}
