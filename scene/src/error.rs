//! Errors as values, with messages that say what to fix.

use std::fmt;
use std::path::PathBuf;

use subcone_kernels::passes;

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
    /// A moving object cannot move as asked
    /// ([`MovingObject`](crate::moving::MovingObject)).
    #[error("invalid moving object: {0}")]
    Motion(String),
    /// An SDF scene is invalid.
    #[error(transparent)]
    Sdf(#[from] SdfError),
    /// An SDF scene file (`.sdf.ron`) could not be read: the error names the
    /// line or the path in the file. Its message is part of this one, not a
    /// `source` as well, so that a chain of causes (`{:#}`) prints it once.
    #[error("cannot load scene {0}")]
    SdfFile(SdfFileError),
}

impl From<SdfFileError> for SceneError {
    fn from(e: SdfFileError) -> Self {
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

/// Why a backend cannot render a scene with a method: the typed reason of an
/// [`Unsupported`].
///
/// These are limits of the technique or of the backend for a given scene and
/// method, known before any work starts. Resolutions, cameras, settings and
/// device failures are not among them: those stay [`RenderError`]s of
/// [`Backend::render`](crate::backend::Backend::render).
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum UnsupportedReason {
    /// The technique does not apply to the scene's geometry, whatever the
    /// backend: [`required_passes`](passes::required_passes) refused it (CTSS on triangles, plain SRAA
    /// on a signed distance field).
    Technique(passes::Unsupported),
    /// The scene has mirror materials (or the secondary passes were forced)
    /// and the backend does not trace reflections in SDF scenes.
    SdfReflections,
    /// The material gate (`sraa+mat`, `sraa-rt+mat`) asked for on an SDF
    /// scene: it runs on triangle scenes only.
    MaterialGateOnSdf,
    /// The scene has semi-transparent materials (alpha < 1) and the path that
    /// would render it does not carry opacity, so it is refused rather than
    /// drawn opaque.
    Translucency {
        /// The path that does not carry opacity (e.g. SRAA-RT).
        what: String,
        /// What renders such scenes instead.
        instead: String,
    },
    /// Implemented by the CPU backend only: what a backend whose
    /// [`Capabilities`](crate::backend::Capabilities) lack something the technique [`Needs`](crate::registry::Needs)
    /// refuses with. No backend of this workspace returns it (both render
    /// SRAA-RT on SDF scenes); it stays for backends outside it that declare
    /// such a lack.
    CpuOnly {
        /// What only the CPU backend renders (e.g. `"sraa-rt on SDF scenes"`).
        what: &'static str,
        /// What this backend lacks for it.
        why: &'static str,
    },
    /// More lights than the backend shades.
    TooManyLights {
        /// Lights in the scene.
        lights: usize,
        /// The most the backend supports.
        max: usize,
    },
    /// A temporal method (`taa`, `+taa`) asked of one frame's render: it
    /// renders a sequence, through [`crate::temporal::Taa`].
    Temporal,
    /// `ssaa2` (the diagonal of the 2×2 grid) asked for on an SDF scene:
    /// it runs on triangle scenes only.
    DiagonalSsaaOnSdf,
    /// More samples per pixel side than the backend traces.
    TooManySamples {
        /// Samples per pixel side asked for.
        side: u32,
        /// The most the backend supports.
        max: u32,
    },
}

impl fmt::Display for UnsupportedReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UnsupportedReason::Technique(u) => f.write_str(u.reason),
            UnsupportedReason::SdfReflections => {
                f.write_str("mirror reflections in SDF scenes are not implemented")
            }
            UnsupportedReason::DiagonalSsaaOnSdf => f.write_str(
                "ssaa2 (the 2×2 grid's diagonal) is not implemented on SDF scenes: it runs on triangle scenes",
            ),
            UnsupportedReason::MaterialGateOnSdf => f.write_str(
                "the material gate (+mat) is not implemented on SDF scenes: it runs on triangle scenes",
            ),
            UnsupportedReason::Translucency { what, instead } => write!(
                f,
                "{what} is not implemented for semi-transparent materials (alpha < 1); {instead}"
            ),
            UnsupportedReason::CpuOnly { what, why } => {
                write!(f, "{what} runs on the CPU backend only ({why})")
            }
            UnsupportedReason::TooManyLights { lights, max } => {
                write!(f, "{lights} lights; at most {max} are supported")
            }
            UnsupportedReason::Temporal => f.write_str(
                "a temporal method accumulates a sequence of frames: render it through \
                 subcone_scene::temporal::Taa (subcone render --frames N)",
            ),
            UnsupportedReason::TooManySamples { side, max } => write!(
                f,
                "{side}x{side} samples per pixel; at most {max}x{max} are supported"
            ),
        }
    }
}

/// A backend cannot render a scene with a method: what [`Backend::supports`](crate::backend::Backend::supports)
/// answers, and what [`Backend::render`](crate::backend::Backend::render) returns (as
/// [`RenderError::NotSupported`]) for the same scene and method.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the {backend} backend cannot render scene {scene:?} with {method}: {reason}")]
pub struct Unsupported {
    /// The backend's [`Backend::name`](crate::backend::Backend::name).
    pub backend: &'static str,
    /// The scene's name.
    pub scene: String,
    /// The method, as it is written (`"sraa-rt+mat"`).
    pub method: String,
    /// Why not.
    pub reason: UnsupportedReason,
}

/// An SDF tree or scene could not be built.
///
/// Callers that need a [`SceneError`] map it, e.g. to
/// `SceneError::Load { path: "<sdf>".into(), reason: e.to_string() }`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SdfError {
    /// A parameter is NaN or infinite.
    #[error("{node}: {param} must be finite")]
    NonFinite {
        /// The node kind.
        node: &'static str,
        /// The parameter.
        param: &'static str,
    },
    /// A size or radius is negative.
    #[error("{node}: {param} must not be negative, got {value}")]
    Negative {
        /// The node kind.
        node: &'static str,
        /// The parameter.
        param: &'static str,
        /// The value given.
        value: f32,
    },
    /// A scale or factor is zero or negative.
    #[error("{node}: {param} must be positive, got {value}")]
    NonPositive {
        /// The node kind.
        node: &'static str,
        /// The parameter.
        param: &'static str,
        /// The value given.
        value: f32,
    },
    /// An operator has no operand.
    #[error("{node} needs at least one child")]
    Empty {
        /// The node kind.
        node: &'static str,
    },
    /// Repeated or mirrored instances would overlap their neighbours.
    #[error("{node}: {reason}")]
    Overlap {
        /// The node kind.
        node: &'static str,
        /// What overlaps.
        reason: String,
    },
    /// The tree is deeper than [`MAX_DEPTH`](crate::sdf::MAX_DEPTH).
    #[error("{node}: the tree would be deeper than {max} levels")]
    TooDeep {
        /// The node that would exceed it.
        node: &'static str,
        /// The limit.
        max: u32,
    },
    /// Another invalid parameter.
    #[error("{node}: {reason}")]
    Invalid {
        /// The node kind.
        node: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// A material index points past the scene's materials.
    #[error("material index {index} is out of range: the scene has {count} materials")]
    Material {
        /// The largest index used.
        index: u32,
        /// How many materials there are.
        count: usize,
    },
    /// The camera is unusable.
    #[error("invalid camera: {0}")]
    Camera(String),
    /// A moving object cannot move as asked
    /// ([`MovingObject`](crate::moving::MovingObject)).
    #[error("invalid moving object: {0}")]
    Motion(String),
    /// A scene-level setting is unusable.
    #[error("SDF scene {name:?}: {reason}")]
    Scene {
        /// The scene.
        name: String,
        /// What is wrong.
        reason: String,
    },
}

/// An SDF scene file (`.sdf.ron`, read and written by `subcone-load`) could
/// not be read, or a scene could not be written. Plain data, so that
/// [`SceneError::SdfFile`] can carry it without the contract knowing the
/// format.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct SdfFileError {
    /// The file, as the caller named it.
    pub file: String,
    /// Line and column (1-based) where the problem was found, when known.
    pub position: Option<(usize, usize)>,
    /// Where in the document: `root.Union[2].Transform.child`,
    /// `materials[1]`; empty for the whole file.
    pub path: String,
    /// What is wrong.
    pub reason: String,
}

impl SdfFileError {
    fn describe(&self) -> String {
        let mut s = self.file.clone();
        if let Some((line, col)) = self.position {
            s += &format!(":{line}:{col}");
        }
        if !self.path.is_empty() {
            s += &format!(": {}", self.path);
        }
        s + ": " + &self.reason
    }

    /// An error in `file` at `path` in the document, with no line known.
    pub fn at(file: &str, path: impl Into<String>, reason: impl Into<String>) -> Self {
        SdfFileError {
            file: file.into(),
            position: None,
            path: path.into(),
            reason: reason.into(),
        }
    }
}
