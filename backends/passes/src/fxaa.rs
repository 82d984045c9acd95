//! [`FxaaPass`]: FXAA 3.11 quality preset 12 (`subcone_kernels::fxaa`, the
//! kernels' WGSL twin of the CPU backend's post-process) over a host texture.
//!
//! FXAA is a filter of display-referred colour: FXAA 3.11 runs "after tone
//! mapping" on the final LDR image, its luma from the gamma-encoded colour,
//! and its thresholds are fractions of that range. The kernel makes its
//! input the way an engine stores it for FXAA (`fxaa::fxaa_encode`: clamped
//! to `[0, 1]`, sRGB-encoded, 8 bits), so HDR radiance above 1 is clipped.
//! The pass does not tone map for the host: it refuses an input whose
//! format can hold HDR values ([`crate::PassError::HdrInput`]) unless the
//! host says the texture holds tone-mapped colour ([`FxaaInput`]).

use bytemuck::{Pod, Zeroable};
use subcone_kernels::fxaa::FxaaParams;

use crate::bind::{self, Bound, Expect, Group, PassPipeline};
use crate::bind::{
    CommandEncoder, ComputePassTimestampWrites, Device, Queue, TextureFormat, TextureUsages,
    TextureView,
};
use crate::skeleton::{self, PassNames, PassShader};
use crate::PassError;

pub(crate) const FXAA_WGSL: &str = include_str!("fxaa.wgsl");

/// The frame's size; `FxaaFrame` in `fxaa.wgsl` (16 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub(crate) struct FxaaFrame {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) _pad: [u32; 2],
}

/// What the host's input texture holds, which decides the formats
/// [`FxaaPass::encode`] accepts. FXAA 3.11 filters display-referred colour
/// in `[0, 1]` (after tone mapping); the pass clamps its input to `[0, 1]`
/// (`subcone_kernels::fxaa::fxaa_encode`), so a float texture of HDR
/// radiance would lose its highlights without a word. A float texture is
/// therefore refused ([`crate::PassError::HdrInput`]) unless the host
/// declares it tone mapped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum FxaaInput {
    /// A unorm or snorm colour texture (`Rgba8Unorm`, `Rgb10a2Unorm`, …),
    /// whose values lie in `[0, 1]` by its format (snorm's negatives clamp
    /// to 0): display-referred by construction. A float format
    /// (`Rgba16Float`, `Rgba32Float`, `Rg11b10Ufloat`, …) is refused. The
    /// default.
    #[default]
    Unorm,
    /// Any float, unorm or snorm colour texture whose linear RGB the host
    /// has already tone mapped into `[0, 1]` (display-referred; values
    /// outside are clamped, as FXAA 3.11's RGBA8 input clamps them).
    ToneMapped,
}

/// The configuration of a [`FxaaPass`], fixed for its life. Start from
/// `FxaaPassDesc::default()` and change what differs with the `with_`
/// methods (or assign the public fields): the struct is
/// `#[non_exhaustive]`, so a field added later breaks no host.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct FxaaPassDesc {
    /// FXAA's thresholds: `FxaaParams::QUALITY`, the defaults of FXAA 3.11.
    pub params: FxaaParams,
    /// The output texture's format: `Rgba8Unorm`, `Rgba16Float` or
    /// `Rgba32Float` (a storage texture; display-referred linear RGB in
    /// `[0, 1]`, alpha 1, whatever the format).
    pub output_format: TextureFormat,
    /// What the input holds, and so which formats it may have
    /// ([`FxaaInput::Unorm`] by default: float formats are refused).
    pub input: FxaaInput,
}

impl Default for FxaaPassDesc {
    /// `FxaaParams::QUALITY`, from a unorm input ([`FxaaInput::Unorm`]),
    /// writing `Rgba16Float`.
    fn default() -> Self {
        FxaaPassDesc {
            params: FxaaParams::QUALITY,
            output_format: TextureFormat::Rgba16Float,
            input: FxaaInput::Unorm,
        }
    }
}

impl FxaaPassDesc {
    with_setters! {
        /// With FXAA's thresholds `params` ([`Self::params`]).
        with_params(params: FxaaParams);
        /// Writing `output_format` ([`Self::output_format`]).
        with_output_format(output_format: TextureFormat);
        /// Reading an input that holds `input` ([`Self::input`]).
        with_input(input: FxaaInput);
    }
}

/// FXAA on the host's device: reads a one-sample texture of
/// display-referred linear RGB (`.xyz`, `TEXTURE_BINDING`: a unorm or snorm
/// format, or with [`FxaaInput::ToneMapped`] also a float format holding
/// tone-mapped colour) and writes the filtered display-referred linear RGB,
/// in `[0, 1]`, alpha 1, into a storage texture of the same size
/// (`STORAGE_BINDING`, the desc's output format). As FXAA 3.11 reads an
/// RGBA8 texture, each pixel is clamped to `[0, 1]`, sRGB-encoded and
/// rounded to 8 bits before it is filtered (`fxaa::fxaa_encode`), and the
/// result is decoded back to linear (`fxaa::fxaa_decode`): HDR input is not
/// handled, it is refused ([`crate::PassError::HdrInput`], for a float
/// format without [`FxaaInput::ToneMapped`]); tone map first. Pixels
/// outside the image are clamped to its edge. Input and output must be
/// views of different textures, each of the whole texture (checked on
/// `TextureView::texture`).
///
/// Built once, encoded every frame: after the first frame with given views,
/// `encode` creates no buffer, texture, bind group or pipeline
/// ([`crate::UNIFORM_SLOTS`], [`crate::BIND_GROUP_CACHE`]); call its
/// `end_submission` after each submit that holds its encodes, so that its
/// uniform slots are free for the next.
#[derive(Debug)]
pub struct FxaaPass {
    desc: FxaaPassDesc,
    pipeline: PassPipeline,
}

impl FxaaPass {
    /// Build the pass (compile its pipeline, make its uniform buffers) for
    /// `desc`. Refuses an output format it cannot write.
    pub fn new(device: &Device, desc: &FxaaPassDesc) -> Result<Self, PassError> {
        let pipeline = skeleton::pipeline::<Self>(device, desc)?;
        Ok(FxaaPass {
            desc: *desc,
            pipeline,
        })
    }

    /// The configuration.
    pub fn desc(&self) -> &FxaaPassDesc {
        &self.desc
    }

    /// Record FXAA of `input` into `output` (one compute pass), the frame's
    /// size written through `queue`. Checks both first: on an error nothing
    /// is recorded or written.
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
        input: &TextureView,
        output: &TextureView,
        timestamps: Option<ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        let size = bind::check_output(output, self.desc.output_format, "the desc's output_format")?;
        bind::check(
            input,
            &Expect {
                what: "input",
                size,
                samples: 1,
                layers: 1,
                usage: TextureUsages::TEXTURE_BINDING,
            },
        )?;
        bind::check_float_color("input", input)?;
        let format = input.texture().format();
        if self.desc.input == FxaaInput::Unorm && holds_hdr(format) {
            return Err(PassError::HdrInput {
                what: "input",
                found: format,
            });
        }
        if input.texture() == output.texture() {
            return Err(PassError::Config(
                "FXAA cannot filter a texture in place".into(),
            ));
        }
        let frame = FxaaFrame {
            width: size.0,
            height: size.1,
            _pad: [0; 2],
        };
        self.pipeline.encode(
            device,
            queue,
            encoder,
            size,
            &[
                bytemuck::bytes_of(&self.desc.params),
                bytemuck::bytes_of(&frame),
            ],
            &[
                ("fxaa_src", Bound::Texture(input)),
                ("fxaa_dst", Bound::Texture(output)),
            ],
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

impl PassShader for FxaaPass {
    const NAMES: PassNames = PassNames::new("fxaa", "subcone fxaa", "fxaa_main");
    type Key<'a> = FxaaPassDesc;

    /// Refuses an output format it cannot write.
    fn check(desc: &FxaaPassDesc) -> Result<(), PassError> {
        bind::check_output_format(desc.output_format)
    }

    /// The bindings, writing the desc's output format.
    fn group(desc: &FxaaPassDesc) -> Result<Group, PassError> {
        let mut g = Group::default();
        g.ring_uniform::<FxaaParams>("fxaa_params", "subcone_FxaaParams");
        g.ring_uniform::<FxaaFrame>("fxaa_frame", "FxaaFrame");
        skeleton::filter_textures(g, &["fxaa_src"], "fxaa_dst", desc.output_format)
    }

    /// The kernels' FXAA and `fxaa.wgsl`.
    fn wgsl(_desc: &FxaaPassDesc) -> String {
        [subcone_kernels::fxaa::WGSL, FXAA_WGSL].concat()
    }
}

/// Whether a colour texture of `format` can hold values above 1 (a float
/// format: scene-referred radiance before tone mapping).
fn holds_hdr(format: TextureFormat) -> bool {
    use TextureFormat as F;
    matches!(
        format,
        F::R16Float
            | F::Rg16Float
            | F::Rgba16Float
            | F::R32Float
            | F::Rg32Float
            | F::Rgba32Float
            | F::Rg11b10Ufloat
            | F::Rgb9e5Ufloat
    )
}
