//! `subcone-scene`: what backends render and what they return.
//!
//! Scenes (triangles, materials, lights, a camera), built-in procedural scenes,
//! mesh loading, the [`Method`] (a kernel technique with its parameters), the
//! [`Frame`] a backend returns, and the [`Backend`] trait.
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
pub mod light;
pub mod load;
pub mod material;
pub mod mesh;
pub mod method;
pub mod registry;
pub mod scene;
pub mod sdf;

pub use backend::{Backend, RenderSettings, Unsupported, UnsupportedReason};
pub use camera::Camera;
pub use error::{RenderError, SceneError};
pub use frame::{Frame, FrameStats, PassTiming, RayCounts, TimingSource};
pub use light::Light;
pub use load::{
    data_dir, load_mesh_bytes, load_mesh_file, load_scene, load_scene_bytes, scene_from_arg, sponza,
};
pub use material::{Albedo, Material};
pub use mesh::{Sanitized, TriangleMesh};
pub use method::{Method, MethodError, Preset};
pub use registry::EdgeClass;
pub use scene::{Geometry, Scene};
