//! `subcone-load`: the file formats of subcone, beside its contract crate
//! `subcone-scene`, which reads and writes none.
//!
//! - triangle scenes from OBJ (with its MTL diffuse colours), glTF and GLB
//!   files, with image textures ([`load_scene`], [`load_mesh_file`]), and
//!   the Sponza atrium of the SRAA paper ([`sponza`], from [`data_dir`]);
//! - SDF scene files, `.sdf.ron` ([`file`](mod@file), documented there);
//! - a scene named on a command line: a built-in scene, a data scene or a
//!   file ([`scene_from_arg`]);
//! - frames written as PNG (8-bit sRGB) or EXR (linear f32) ([`SaveFrame`]).
//!
//! Loaders never panic on bad input: unreadable, malformed or empty files are a
//! [`SceneError::Load`](subcone_scene::SceneError::Load), files whose
//! triangles are all unusable a
//! [`SceneError::Empty`](subcone_scene::SceneError::Empty) that says how many
//! were dropped.
//!
//! ```
//! use subcone_load::{load_scene_bytes, scene_from_arg, SaveFrame};
//! use subcone_scene::Frame;
//!
//! let cornell = scene_from_arg("cornell")?;
//! assert_eq!(cornell.name, "cornell");
//! let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
//! let triangle = load_scene_bytes(std::path::Path::new("tri.obj"), obj)?;
//! assert!(triangle.sdf_geometry().is_none());
//!
//! let dir = std::env::temp_dir();
//! Frame::new(4, 4).save(&dir.join("subcone-load-doc.png")).unwrap();
//! # std::fs::remove_file(dir.join("subcone-load-doc.png")).unwrap();
//! # Ok::<(), subcone_scene::SceneError>(())
//! ```
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod file;
mod frame;
mod scenes;

pub use frame::SaveFrame;
pub use scenes::{
    data_dir, framing_camera, load_mesh_bytes, load_mesh_file, load_scene, load_scene_bytes,
    scene_from_arg, sponza, DATA_SCENES, DEFAULT_ALBEDO, SPONZA_FLOOR_REFLECTANCE, SPONZA_PATH,
    SPONZA_STONE,
};
