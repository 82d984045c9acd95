//! [`SraaPass`]: SRAA's antialiasing pass (Chiu et al., *Subpixel
//! Reconstruction Antialiasing for Ray Tracing*, §3, the paper's pass 2) over
//! a host renderer's textures.
//!
//! SRAA shades one sample per pixel and reconstructs four geometric
//! subsamples per pixel from the shaded samples of the 3×3 neighbourhood,
//! each weighted by how alike its geometry is (eq. 1: depth and normal;
//! eq. 2: the same shadow state per light), then box-filters the four
//! (`subcone_kernels::sraa::resolve_pixel`). The four subsamples lie at
//! [`subcone_kernels::sraa::SUBPIXEL_OFFSETS`] from the pixel centre,
//! `(−1/8, −3/8), (3/8, −1/8), (−3/8, 1/8), (1/8, 3/8)` pixels (x right,
//! y down): the standard 4x MSAA sample pattern of Vulkan, Metal and D3D,
//! sample `k` at offset `k`. So a host's 4x multisampled depth + normal
//! prepass already holds SRAA's geometric subsamples.
//!
//! The maths is the kernels' WGSL (`subcone_kernels::sraa::WGSL` and the
//! reconstruction loop, `subcone_kernels::sraa::RECONSTRUCT_WGSL`); this
//! module binds the host's textures to it (`sraa.wgsl`).
//!
//! # The module's rules
//!
//! One file per concern, each reached through this module's re-exports (the
//! crate root re-exports the public types), the files depending one way,
//! from the pass down to its configuration:
//!
//! - `desc.rs`: the configuration, [`SraaPassDesc`] and how the host
//!   stores its geometry ([`GeometryLayout`], [`DepthKind`],
//!   [`NormalEncoding`]), and what the pass refuses of it;
//! - `inputs.rs`: one frame's views ([`SraaInputs`]) or buffers
//!   ([`SraaBuffers`]);
//! - `checks.rs`: those inputs checked against the configuration;
//! - `pass.rs`: [`SraaPass`], its `new` and its encodes;
//! - `group.rs`: the pass's bindings for a configuration;
//! - `shader.rs`: the pass's WGSL for a configuration (the kernels, a
//!   generated header of constants and loaders, `sraa.wgsl`), and the
//!   pass on the crate's pass skeleton (`skeleton.rs`): its checks,
//!   bindings and shader, with the float-depth variant GLSL reads.
//!
//! The impl blocks of [`SraaPass`] that build its bindings and its shader
//! live in `group.rs` and `shader.rs`; a file above names the ones below,
//! never the reverse.

mod checks;
mod desc;
mod group;
mod inputs;
mod pass;
mod shader;

/// The SRAA reconstruction loop every GPU resolve shares ([`SraaPass`]
/// and the wgpu backend's own), `subcone_sraa_reconstruct_run`: the
/// kernels' WGSL twin of `sraa::reconstruct_layers` (with the albedo gate,
/// `sraa::reconstruct_layers_material`), re-exported from
/// [`subcone_kernels::sraa::RECONSTRUCT_WGSL`], whose documentation lists
/// the hooks the including shader defines. `sraa.wgsl` defines them over
/// the host's textures.
pub use subcone_kernels::sraa::RECONSTRUCT_WGSL;

/// The pass's constants; `SraaFrame` in `sraa.wgsl` (80 bytes).
pub(crate) use subcone_kernels::uniforms::SraaFrame;

pub use desc::{DepthKind, GeometryLayout, NormalEncoding, SraaPassDesc};
pub use inputs::{
    CentreGeometry, Samples, SecondaryBuffers, SecondaryInputs, SraaBuffers, SraaInputs,
    SubsampleGeometry,
};
pub use pass::SraaPass;
/// The tests' view of the shader: `sraa.wgsl` alone, and the whole source
/// of a configuration.
#[cfg(test)]
pub(crate) use shader::{test_source, SRAA_WGSL};
