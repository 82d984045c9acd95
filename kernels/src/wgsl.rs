//! The WGSL of the kernels, for GPU pipelines of your own.
//!
//! Each kernel module ships its WGSL mirror next to the Rust function, as a
//! `WGSL` constant (e.g. [`crate::sraa::WGSL`]): the same function names, the
//! same parameter structs, and a comment in the WGSL naming the Rust function
//! it mirrors. WGSL has no `#include`, so a shader is the concatenation of
//! [`PARAMS`], the kernel sources it uses, and its own entry points:
//!
//! ```
//! let source = [subcone_kernels::wgsl::PARAMS, "@compute @workgroup_size(64) fn main() {}"].concat();
//! assert!(source.contains("struct subcone_SraaParams"));
//! ```
//!
//! The sources use only WGSL core features (no extensions), so they run on any
//! WebGPU implementation, software ones included.

/// The `#[repr(C)]` parameter structs ([`crate::sraa::SraaParams`],
/// [`crate::sraa::Geometry`], [`crate::ctss::CtssParams`],
/// [`crate::fxaa::FxaaParams`]) in WGSL, with
/// identical field offsets.
pub const PARAMS: &str = include_str!("params.wgsl");
