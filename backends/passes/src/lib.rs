//! subcone's GPU passes for a host wgpu renderer.
//!
//! Each pass works on the host's `wgpu::Device`, `wgpu::Queue` and texture
//! views and never opens a device of its own, never installs a device-lost or
//! uncaptured-error callback and never waits on the GPU: it records into the
//! host's `wgpu::CommandEncoder` and the host submits. (The one callback it
//! registers is on that encoder, `on_submitted_work_done`, to take its
//! uniform slots back once the work ran; wgpu calls it from the host's own
//! poll or submit.) Like the `smaa` crate,
//! a pass is built once for a configuration (`new`, which compiles its
//! pipeline and makes its uniform buffers) and recorded every frame
//! (`encode(&device, &queue, &mut encoder, inputs, timestamps)`).
//!
//! A pass lives in the host's frame loop: after the first frame with given
//! views, `encode` creates no buffer, texture, bind group or pipeline. Its
//! per-frame constants are written with `Queue::write_buffer` into slots of
//! a ring per constant, and its bind groups are cached per set of input
//! views, at most [`BIND_GROUP_CACHE`] of them. A write lands before *any*
//! command of the next submission runs, so a slot that an encode not yet
//! submitted binds is never rewritten: a submission may hold any number of
//! encodes of a pass, each reading its own values, and one with more
//! distinct values of a constant than the ring has ([`UNIFORM_SLOTS`] at
//! first) grows it (an allocation, that once), up to [`MAX_UNIFORM_SLOTS`]
//! waiting for one submission; past that `encode` returns
//! [`PassError::UniformSlotsExhausted`]. After each `Queue::submit` a host
//! calls the pass's `end_submission` (e.g. [`CtssPass::end_submission`]) to
//! give the slots back at once; without it they come back once the work
//! has run and the host polled the device or submitted again, which is
//! correct but may grow the ring. Each `encode` takes optional `wgpu::ComputePassTimestampWrites`
//! for a host that times the pass on the GPU (its own query set, which it
//! resolves).
//!
//! - [`SraaPass`]: SRAA's antialiasing pass (Chiu et al., §3, eq. 1–2,
//!   secondary hits §3.3) from the host's subsample geometry (a 4x MSAA
//!   depth + normal prepass, or four layers) and its one shaded colour per
//!   pixel.
//! - [`CtssPass`]: cone-traced supersampling (CTSS, Algorithm 1, eq. 3–10)
//!   of the host's own signed distance field, written in WGSL.
//! - [`FxaaPass`]: FXAA 3.11 (`subcone_kernels::fxaa`) over a host texture.
//! - [`TaaPass`]: temporal antialiasing (`subcone_kernels::taa`: Karis 2014
//!   with Salvi's variance clipping) of the host's jittered frame against its
//!   history, with the jitter sequence to render it with, the engine's
//!   motion vectors scaled into pixels ([`TaaInputs::motion_scale`]) and,
//!   optionally, closest-depth motion dilation from its depth
//!   ([`TaaInputs::depth`]).
//! - [`bind`]: bindings declared once, from which both the WGSL
//!   declarations and the wgpu layouts and bind groups are made: what the
//!   passes are built on, and what `subcone-wgpu` builds its own programs
//!   on, so a host's program can use it too.
//!
//! Every pass runs the kernels' WGSL (`subcone_kernels::sraa::WGSL` and
//! `RECONSTRUCT_WGSL`, `subcone_kernels::ctss::TRACE_WGSL`,
//! `subcone_kernels::fxaa::WGSL`): the mathematics is written once, in the
//! kernels crate, and this crate only binds textures (or, for
//! [`SraaPass::encode_buffers`], storage buffers) to it. Each GPU pass is one `.rs` beside one `.wgsl`.
//!
//! Inputs are checked before anything is recorded: a view of a texture of the
//! wrong size, format, sample count, layer count or usage is a [`PassError`],
//! never a wgpu validation error raised on the host's device. So is host WGSL
//! that does not compile ([`PassError::Shader`], with naga's message): a
//! pass's `new` makes its shader and pipeline inside an error scope of its
//! own and pops it before returning. (wgpu 30
//! exposes a view's texture, `TextureView::texture`, but not the view's
//! dimension, aspect or range: a view of the whole texture, as
//! `create_view(&Default::default())` makes, is the host's part.)

#![forbid(unsafe_code)]
#![warn(missing_docs)]

/// The `with_` methods of a pass's `#[non_exhaustive]` desc: each entry
/// `doc, with_field(field: Type)` sets that one field of the desc it is
/// given and returns it.
macro_rules! with_setters {
    ($($(#[$doc:meta])* $with:ident($field:ident: $ty:ty);)*) => {
        $(
            $(#[$doc])*
            pub fn $with(mut self, $field: $ty) -> Self {
                self.$field = $field;
                self
            }
        )*
    };
}

pub mod bind;
mod ctss;
mod fxaa;
#[cfg(test)]
#[macro_use]
mod layout_check;
#[cfg(test)]
mod layout_tests;
mod skeleton;
mod sraa;
pub mod standalone;
mod taa;

use bind::{BufferUsages, TextureDimension, TextureFormat, TextureUsages};
pub use bind::{Rect, BIND_GROUP_CACHE, MAX_UNIFORM_SLOTS, UNIFORM_SLOTS};
pub use ctss::{
    CtssBackground, CtssBuffers, CtssCamera, CtssDepth, CtssFrame, CtssOutput, CtssPass,
    CtssPassDesc, CtssProjection, CtssRect, CtssTrace, CtssView, CTSS_KERNELS, MAX_BATCH,
    MAX_SAMPLES_PER_SIDE, SPHERE_TRACE_HOOK,
};
pub use fxaa::{FxaaInput, FxaaPass, FxaaPassDesc};
pub use sraa::{
    CentreGeometry, DepthKind, GeometryLayout, NormalEncoding, Samples, SecondaryBuffers,
    SecondaryInputs, SraaBuffers, SraaInputs, SraaPass, SraaPassDesc, SubsampleGeometry,
    RECONSTRUCT_WGSL,
};
pub use taa::{TaaInputs, TaaPass, TaaPassDesc};
/// The wgpu this release's passes take (`wgpu::Device`, `TextureView`…):
/// build the host's objects with `subcone_passes::wgpu` and the versions
/// cannot disagree.
pub use wgpu;

/// README.md's code blocks (its "Embedding" section), compiled as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeSnippets;

/// Why a pass refused its configuration or its inputs. Nothing was recorded.
/// `#[non_exhaustive]`: a new kind of refusal is not a breaking change, so a
/// host's `match` keeps a wildcard arm.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PassError {
    /// A texture has the wrong size.
    Size {
        /// Which input.
        what: &'static str,
        /// The size the pass needs (the output's), `(width, height)`.
        expected: (u32, u32),
        /// The texture's size.
        found: (u32, u32),
    },
    /// A texture is not two-dimensional.
    Dimension {
        /// Which input.
        what: &'static str,
        /// The texture's dimension.
        found: TextureDimension,
    },
    /// A texture has the wrong sample count.
    SampleCount {
        /// Which input.
        what: &'static str,
        /// The count the configuration needs.
        expected: u32,
        /// The texture's.
        found: u32,
    },
    /// A texture has the wrong number of array layers.
    Layers {
        /// Which input.
        what: &'static str,
        /// The layers the configuration needs.
        expected: u32,
        /// The texture's.
        found: u32,
    },
    /// A texture's format does not fit its role.
    Format {
        /// Which input.
        what: &'static str,
        /// The texture's format.
        found: TextureFormat,
        /// What the role accepts.
        expected: &'static str,
    },
    /// A texture lacks a usage the pass needs (`TEXTURE_BINDING` to read,
    /// `STORAGE_BINDING` to write).
    Usage {
        /// Which input.
        what: &'static str,
        /// The usage it lacks.
        missing: TextureUsages,
    },
    /// An input the configuration needs was not given.
    Missing(&'static str),
    /// An input was given that the configuration does not read (so the host
    /// and the pass disagree about what is being resolved).
    Unexpected(&'static str),
    /// A configuration value is out of range.
    Config(String),
    /// A buffer is smaller than its role takes for the frame's size.
    BufferSize {
        /// Which input.
        what: &'static str,
        /// The bytes the role takes.
        expected: u64,
        /// The buffer's size.
        found: u64,
    },
    /// A buffer lacks a usage the pass needs (`STORAGE`).
    BufferUsage {
        /// Which input.
        what: &'static str,
        /// The usage it lacks.
        missing: BufferUsages,
    },
    /// The rect a pass was given ([`bind::Rect`]) is empty or does not lie
    /// inside a texture it reads or writes.
    Rect {
        /// Which input.
        what: &'static str,
        /// The rect given.
        rect: bind::Rect,
        /// The texture's size, `(width, height)`.
        size: (u32, u32),
    },
    /// The exposure of a tone-mapped resolve
    /// (`subcone_kernels::sraa::ResolveSpace::ToneMapped`) is not positive
    /// and finite.
    Exposure {
        /// The exposure given, as `f32::to_bits` (so that the error stays
        /// `Eq`, a NaN's payload included).
        found_bits: u32,
    },
    /// An input's format can hold HDR (scene-referred) values that the pass
    /// would clip: FXAA 3.11 filters display-referred colour in `[0, 1]`.
    HdrInput {
        /// Which input.
        what: &'static str,
        /// The texture's format.
        found: TextureFormat,
    },
    /// An encode needs a uniform slot for a new value, but every slot of the
    /// pass's ring may still be read by an encode not yet submitted, and
    /// the ring has grown to its bound ([`MAX_UNIFORM_SLOTS`]): more
    /// distinct values (cameras, rects, parameters) are waiting for one
    /// submission than a pass holds. Rewriting a slot would make an earlier
    /// encode read this one's value, so nothing was written or recorded.
    UniformSlotsExhausted {
        /// The pass (its wgpu label).
        pass: &'static str,
        /// The slots of the ring, all held for unsubmitted encodes.
        slots: usize,
    },
    /// The pass's shader did not compile: the host's WGSL (a
    /// [`CtssPass`]'s field, shading or trace) has a syntax or type error,
    /// or does not fit the pass (a missing hook, a host layout the shader
    /// does not match). Caught in the pass's own error scope, so the
    /// device's uncaptured-error handler does not see it.
    Shader {
        /// wgpu's report, with naga's message and the offending line of
        /// the whole shader (the kernels', the host's WGSL and the pass's).
        message: String,
    },
}

impl std::fmt::Display for PassError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PassError::Size {
                what,
                expected,
                found,
            } => write!(
                f,
                "{what}: {}x{} texture, the pass needs {}x{}",
                found.0, found.1, expected.0, expected.1
            ),
            PassError::Dimension { what, found } => {
                write!(f, "{what}: a {found:?} texture, the pass reads 2D textures")
            }
            PassError::SampleCount {
                what,
                expected,
                found,
            } => write!(f, "{what}: {found} samples per pixel, needs {expected}"),
            PassError::Layers {
                what,
                expected,
                found,
            } => write!(f, "{what}: {found} array layers, needs {expected}"),
            PassError::Format {
                what,
                found,
                expected,
            } => write!(f, "{what}: format {found:?}, needs {expected}"),
            PassError::Usage { what, missing } => write!(f, "{what}: lacks usage {missing:?}"),
            PassError::Missing(what) => write!(f, "{what} is required by this configuration"),
            PassError::Unexpected(what) => {
                write!(
                    f,
                    "{what} was given but this configuration does not read it"
                )
            }
            PassError::Config(m) => f.write_str(m),
            PassError::BufferSize {
                what,
                expected,
                found,
            } => write!(f, "{what}: a buffer of {found} bytes, needs {expected}"),
            PassError::BufferUsage { what, missing } => {
                write!(f, "{what}: the buffer lacks usage {missing:?}")
            }
            PassError::Rect { what, rect, size } => write!(
                f,
                "{what}: the rect of {}x{} pixels at ({}, {}) is empty or does not lie inside the {}x{} texture",
                rect.width, rect.height, rect.x, rect.y, size.0, size.1
            ),
            PassError::Exposure { found_bits } => write!(
                f,
                "exposure {}: a tone-mapped resolve needs an exposure > 0 and finite",
                f32::from_bits(*found_bits)
            ),
            PassError::HdrInput { what, found } => write!(
                f,
                "{what}: format {found:?} can hold HDR values, which FXAA would clip to [0, 1]: \
                 FXAA 3.11 runs on display-referred colour, so tone map first (into a unorm \
                 texture such as Rgba8Unorm), or, if this texture already holds tone-mapped \
                 colour in [0, 1], build the pass with FxaaInput::ToneMapped"
            ),
            PassError::UniformSlotsExhausted { pass, slots } => write!(
                f,
                "{pass}: all {slots} uniform slots hold values of encodes not yet submitted, \
                 the most a pass keeps (MAX_UNIFORM_SLOTS): submit the command buffers \
                 encoded so far (Queue::submit) and call the pass's end_submission before \
                 encoding more, or encode fewer distinct cameras, rects or parameters per \
                 submission"
            ),
            PassError::Shader { message } => write!(
                f,
                "the pass's shader, with the host WGSL it was given, does not compile: \
                 {message}"
            ),
        }
    }
}

impl std::error::Error for PassError {}
