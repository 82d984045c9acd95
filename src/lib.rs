//! `subcone`: geometry-aware antialiasing for ray tracing and sphere tracing.
//!
//! This crate holds the CLI (`subcone render`; `subcone report` runs
//! [`subcone_report`]) and re-exports the kernels, [`subcone_kernels`], which engine
//! developers can also depend on directly in `no_std` code.
//!
//! ```
//! use subcone::kernels::cone::{cone_occlusion, cone_radius};
//! let rc = cone_radius(10.0, 0.001);
//! assert_eq!(cone_occlusion(0.0, rc), 0.5); // the ray touches the surface
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod cli;
pub mod shaders;
pub mod vectors;

pub use subcone_kernels as kernels;
pub use subcone_kernels::{aggregate, cone, ctss, mask, passes, sraa};
