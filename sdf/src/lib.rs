//! `subcone-sdf`: the SDF trees of `subcone-scene` compiled for the
//! renderers.
//!
//! - [`program`]: the tree flattened once into an [`SdfProgram`] that
//!   evaluates eight points at once, bit for bit the tree's own values (the
//!   CPU backend's packets of rays);
//! - [`wgsl`]: the tree as WGSL functions of the same field ([`WgslField`],
//!   the wgpu backend's SDF scenes).
//!
//! The primitives' distance functions are written once, over the [`Lane`](subcone_scene::sdf::lane::Lane)
//! trait of `subcone-scene`, for a scalar and for the eight lanes; their
//! WGSL forms are checked against the scalar ones at a table of points.
//!
//! ```
//! use glam::Vec3;
//! use subcone_scene::sdf::SdfNode;
//! use subcone_sdf::{program::Points, SdfProgram, WgslField, LANES};
//!
//! let tree = SdfNode::sphere(1.0).unwrap();
//! let program = SdfProgram::compile(&tree);
//! let mut points = Points::default();
//! for k in 0..LANES {
//!     points.set(k, Vec3::new(0.0, 2.0 + k as f32, 0.0));
//! }
//! let out = program.eval_split(&points, 0xff, &mut program.scratch());
//! assert_eq!(out.surface[0], 1.0);
//! assert!(WgslField::compile(&tree).source.contains("fn scene_sdf("));
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod program;
pub mod wgsl;

pub use program::{SdfProgram, LANES};
pub use wgsl::WgslField;
