//! Errors as values, with messages that say what to fix.

use std::path::PathBuf;

use crate::backend::Unsupported;

/// A scene could not be built or loaded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// A file could not be read or parsed.
    #[error("cannot load scene {path}: {reason}")]
    Load {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// The file format is not one we read.
    #[error("cannot load scene {path}: unknown format (expected .obj, .gltf, .glb or .sdf.ron)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// No built-in scene has that name.
    #[error("no built-in scene named {name:?} (built-in: {known})")]
    UnknownScene {
        /// The name asked for.
        name: String,
        /// The names that exist.
        known: String,
    },
    /// The scene has no usable triangles (or SDF objects).
    #[error("scene {name:?} has no usable geometry{detail}")]
    Empty {
        /// The scene.
        name: String,
        /// What was dropped, if anything.
        detail: String,
    },
    /// The camera is unusable.
    #[error("invalid camera: {0}")]
    Camera(String),
    /// An SDF scene is invalid.
    #[error(transparent)]
    Sdf(#[from] crate::sdf::SdfError),
    /// An SDF scene file (`.sdf.ron`) could not be read: the error names the
    /// line or the path in the file. Its message is part of this one, not a
    /// `source` as well, so that a chain of causes (`{:#}`) prints it once.
    #[error("cannot load scene {0}")]
    SdfFile(crate::sdf::file::SdfFileError),
}

impl From<crate::sdf::file::SdfFileError> for SceneError {
    fn from(e: crate::sdf::file::SdfFileError) -> Self {
        SceneError::SdfFile(e)
    }
}

/// A frame could not be rendered or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The technique cannot render this scene, as
    /// [`subcone_kernels::passes::required_passes`] answers it to code that
    /// calls it directly. Backends report this (and every other scene or
    /// method they refuse) as [`RenderError::NotSupported`].
    #[error(transparent)]
    Unsupported(#[from] subcone_kernels::passes::Unsupported),
    /// The backend does not render this scene with this method (what
    /// [`crate::Backend::supports`] predicts).
    #[error(transparent)]
    NotSupported(#[from] Unsupported),
    /// The resolution is zero or beyond the limit.
    #[error("invalid resolution {width}x{height}: {reason}")]
    Resolution {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// Why it is refused.
        reason: String,
    },
    /// The scene or camera is unusable.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The method's parameters are unusable.
    #[error("invalid method: {0}")]
    Method(String),
    /// No GPU adapter could be opened: the message names the fix (a driver,
    /// or `WGPU_BACKEND`).
    #[error("{backend} backend: {reason}")]
    NoAdapter {
        /// Backend name.
        backend: &'static str,
        /// What was tried and what to install.
        reason: String,
    },
    /// The adapter cannot do what is needed (a device with the required
    /// features and limits could not be opened, a format is not
    /// renderable, …).
    #[error("{backend} backend: {reason}")]
    GpuUnsupported {
        /// Backend name.
        backend: &'static str,
        /// What is missing.
        reason: String,
    },
    /// The GPU ran out of memory during `what`.
    #[error("{backend} backend: {what}: out of GPU memory: {reason}")]
    OutOfMemory {
        /// Backend name.
        backend: &'static str,
        /// The pass or upload.
        what: String,
        /// The driver's message.
        reason: String,
    },
    /// The GPU API refused a call during `what` (a bug in a pass, or input
    /// the pass should have refused earlier).
    #[error("{backend} backend: {what}: {reason}")]
    Validation {
        /// Backend name.
        backend: &'static str,
        /// The pass or upload.
        what: String,
        /// The validation message.
        reason: String,
    },
    /// The device was lost (driver reset, GPU removed), or an error was raised
    /// outside every error scope; the context cannot be used again.
    #[error("{backend} backend: {reason}")]
    DeviceLost {
        /// Backend name.
        backend: &'static str,
        /// The driver's message.
        reason: String,
    },
    /// A resource would exceed one of the adapter's limits.
    #[error("{backend} backend: {what} needs {requested}, over this adapter's {limit} of {max}")]
    LimitExceeded {
        /// Backend name.
        backend: &'static str,
        /// The resource.
        what: String,
        /// The limit's name (as wgpu names it).
        limit: &'static str,
        /// What was asked for.
        requested: u64,
        /// The adapter's limit.
        max: u64,
    },
    /// Another backend failure (a wait that timed out, a read-back, data the
    /// backend cannot lay out).
    #[error("{backend} backend: {reason}")]
    Backend {
        /// Backend name.
        backend: &'static str,
        /// What went wrong.
        reason: String,
    },
    /// Writing the output failed.
    #[error("cannot write {path}: {reason}")]
    Output {
        /// The output path.
        path: PathBuf,
        /// What went wrong.
        reason: String,
    },
}
