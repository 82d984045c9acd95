//! `subcone-scene`: what backends render and what they return.
//!
//! The contract between subcone's renderers and their callers, and nothing
//! else: scenes as data (triangles, SDF trees, materials, lights, a camera),
//! the built-in procedural scenes (they need no files), the [`Method`] (a
//! kernel technique with its parameters) and its registry, the [`Frame`] a
//! backend returns, and the [`Backend`] trait with its support plan.
//!
//! No file format is read or written here: loaders (glTF, OBJ, image
//! textures, `.sdf.ron`) and frame output (PNG, EXR) are `subcone-load`'s, and
//! SDF trees are compiled (the 8-lane interpreter, WGSL) by `subcone-sdf`, so
//! a backend that sees the contract does not build a codec.
//!
//! ```
//! use subcone_scene::{builtin::builtin, Method};
//! let scene = builtin("cornell").unwrap();
//! let method: Method = "sraa-rt".parse().unwrap();
//! assert!(scene.features().contains(subcone_kernels::passes::SceneFeatures::HAS_REFLECTIONS));
//! assert_eq!(method.to_string(), "sraa-rt");
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod backend;
pub mod builtin;
pub mod camera;
pub mod conformance;
pub mod error;
pub mod frame;
pub mod history;
pub mod light;
pub mod material;
pub mod mesh;
pub mod method;
pub mod moving;
pub mod registry;
pub mod scene;
pub mod sdf;
pub mod temporal;

pub use backend::{Backend, RenderSettings, Unsupported, UnsupportedReason};
pub use camera::Camera;
pub use error::{RenderError, SceneError, SdfFileError};
pub use frame::{Frame, FrameStats, PassTiming, RayCounts, TimingSource};
pub use light::Light;
pub use material::{Albedo, Material};
pub use mesh::{Sanitized, TriangleMesh};
pub use method::{Method, MethodError, Preset};
pub use registry::EdgeClass;
pub use scene::{Geometry, Scene};
