//! Built-in procedural scenes: no files needed.

mod atrium;
mod checker;
mod cornell;

pub use atrium::{atrium, ATRIUM_FLOOR_REFLECTANCE};
pub use checker::{checker, CHECKER_PALETTE, CHECKER_PATCH};
pub use cornell::cornell;

use crate::error::SceneError;
use crate::scene::Scene;
use crate::sdf::{SdfError, SdfScene};

/// What a built-in scene is for, which decides the lists it is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneKind {
    /// A triangle scene ([`TRIANGLE_SCENES`]): ray traced through a BVH.
    Triangles,
    /// One of the CTSS paper's SDF scenes (CTSS §4, Table 1;
    /// [`SDF_SCENES`]).
    PaperSdf,
    /// An SDF scene of the stability suite ([`STIFF_SCENES`]).
    Stiff,
    /// An SDF scene with semi-transparent materials (CTSS §5.3;
    /// [`TRANSPARENT_SCENES`]).
    Transparent,
}

/// How a built-in scene is made.
#[derive(Clone, Copy)]
pub enum Constructor {
    /// A triangle scene.
    Triangles(fn() -> Scene),
    /// A signed distance field scene.
    Sdf(fn() -> Result<SdfScene, SdfError>),
}

/// One built-in scene: the registry's entry, from which the name lists,
/// the command line's scene help and the lookups ([`builtin`],
/// [`find`], [`sdf_builtin`]) are derived, so a scene's name is
/// written once.
#[derive(Clone, Copy)]
pub struct BuiltinScene {
    /// The name `--scene` takes.
    pub name: &'static str,
    /// What the scene is for.
    pub kind: SceneKind,
    /// One line: what the scene shows.
    pub description: &'static str,
    /// How it is made.
    pub constructor: Constructor,
}

impl BuiltinScene {
    /// Build the scene.
    ///
    /// # Errors
    /// [`SceneError`] when an SDF scene's field is invalid (a built-in one
    /// never is; the error is kept as a value all the same).
    pub fn build(&self) -> Result<Scene, SceneError> {
        match self.constructor {
            Constructor::Triangles(f) => Ok(f()),
            Constructor::Sdf(f) => Scene::sdf(f()?),
        }
    }

    /// Whether the scene is a signed distance field.
    pub const fn is_sdf(&self) -> bool {
        matches!(self.constructor, Constructor::Sdf(_))
    }
}

const fn entry(
    name: &'static str,
    kind: SceneKind,
    description: &'static str,
    constructor: Constructor,
) -> BuiltinScene {
    BuiltinScene {
        name,
        kind,
        description,
        constructor,
    }
}

/// Every built-in scene, one entry each, in the order of the lists derived
/// from it.
pub const SCENES: [BuiltinScene; 14] = {
    use crate::sdf;
    use Constructor::{Sdf, Triangles};
    use SceneKind::{PaperSdf, Stiff, Transparent, Triangles as Tri};
    [
        entry(
            "cornell",
            Tri,
            "the measured Cornell box with a mirror sphere and a point light: hard shadows, reflections",
            Triangles(|| cornell(true)),
        ),
        entry(
            "cornell-nomirror",
            Tri,
            "the measured Cornell box alone, no mirror sphere: no secondary pass",
            Triangles(|| cornell(false)),
        ),
        entry(
            "checker",
            Tri,
            "the coloured-patch floor of SRAA's Fig. 6: texture edges the geometry cannot see",
            Triangles(checker),
        ),
        entry(
            "atrium",
            Tri,
            "a Sponza-like arcade: columns, arches, thin railings, a reflective floor under a sun",
            Triangles(atrium),
        ),
        entry(
            "primitives",
            PaperSdf,
            "the twelve exact primitives in a grid on a checkered floor (CTSS Table 1)",
            Sdf(sdf::primitives),
        ),
        entry(
            "random-box",
            PaperSdf,
            "about 1,400 random boxes in a grid of cells over a floor (CTSS Table 1)",
            Sdf(sdf::random_box),
        ),
        entry(
            "random-shape",
            PaperSdf,
            "about 1,400 random shapes of ten kinds over a floor (CTSS Table 1)",
            Sdf(sdf::random_shape),
        ),
        entry(
            "sdf-atrium",
            PaperSdf,
            "a Sponza-like courtyard built with CSG and repetition (CTSS Table 1)",
            Sdf(sdf::atrium),
        ),
        entry(
            "sparse-shape",
            PaperSdf,
            "five objects far apart in an empty sky: most rays miss (CTSS Table 1)",
            Sdf(sdf::sparse_shape),
        ),
        entry(
            "thin",
            Stiff,
            "stability: rods, wires and a plate thinner than a pixel; no lights",
            Sdf(sdf::thin),
        ),
        entry(
            "grazing",
            Stiff,
            "stability: a plane seen at 89° from its normal, posts to 400 m",
            Sdf(sdf::grazing),
        ),
        entry(
            "far",
            Stiff,
            "stability: a camera 4·10⁷ m from the origin, stored camera-relative",
            Sdf(sdf::far),
        ),
        entry(
            "non-eikonal",
            Stiff,
            "stability: fields that are not distances (|∇f| of 0.2 and 5) beside exact ones",
            Sdf(sdf::non_eikonal),
        ),
        entry(
            "glass",
            Transparent,
            "semi-transparent objects before opaque ones (CTSS §5.3)",
            Sdf(sdf::glass),
        ),
    ]
};

/// How many entries of [`SCENES`] are of `kind`.
const fn count(kind: SceneKind) -> usize {
    let mut n = 0;
    let mut i = 0;
    while i < SCENES.len() {
        if SCENES[i].kind as u8 == kind as u8 {
            n += 1;
        }
        i += 1;
    }
    n
}

/// The names of the entries of [`SCENES`] of `kind`, in order (`N` their
/// [`count`]).
const fn names_of<const N: usize>(kind: SceneKind) -> [&'static str; N] {
    let mut out = [""; N];
    let (mut i, mut n) = (0, 0);
    while i < SCENES.len() {
        if SCENES[i].kind as u8 == kind as u8 {
            out[n] = SCENES[i].name;
            n += 1;
        }
        i += 1;
    }
    out
}

/// Names of the built-in triangle scenes, from [`SCENES`].
pub const TRIANGLE_SCENES: [&str; count(SceneKind::Triangles)] = names_of(SceneKind::Triangles);

/// The paper's scenes (CTSS §4, Table 1), in its order: the
/// [`SceneKind::PaperSdf`] entries of
/// [`SCENES`].
pub const SDF_SCENES: [&str; count(SceneKind::PaperSdf)] = names_of(SceneKind::PaperSdf);

/// Scenes for the stability suite ([`SceneKind::Stiff`]).
pub const STIFF_SCENES: [&str; count(SceneKind::Stiff)] = names_of(SceneKind::Stiff);

/// Scenes with semi-transparent materials (CTSS §5.3): rendered by both
/// backends with the SDF methods that support them (not `ctss+edges`, not
/// delayed shading); kept apart from [`SDF_SCENES`] (the paper's scenes) and
/// checked against the CPU by the conformance suite's
/// `transparent_scenes_match_the_cpu`
/// ([`SceneKind::Transparent`]).
pub const TRANSPARENT_SCENES: [&str; count(SceneKind::Transparent)] =
    names_of(SceneKind::Transparent);

/// A built-in SDF scene by name ([`SDF_SCENES`], [`STIFF_SCENES`] or
/// [`TRANSPARENT_SCENES`]); `None` when no SDF scene has that name.
pub fn sdf_builtin(name: &str) -> Option<Result<SdfScene, SdfError>> {
    match find(name)?.constructor {
        Constructor::Sdf(f) => Some(f()),
        Constructor::Triangles(_) => None,
    }
}

/// The paper scenes of both papers, as the report runs them by default:
/// triangle scenes for the SRAA family, SDF scenes for the CTSS family. A
/// selection in the report's order, not a registry: each is an entry of
/// [`SCENES`] (a test checks).
pub const PAPER_SCENES: [&str; 8] = [
    "cornell",
    "checker",
    "atrium",
    "primitives",
    "random-box",
    "random-shape",
    "sparse-shape",
    "sdf-atrium",
];

/// The name of every built-in scene, in [`SCENES`]' order.
pub fn names() -> impl Iterator<Item = &'static str> {
    SCENES.iter().map(|s| s.name)
}

/// The entry of the built-in scene `name`, without building it.
pub fn find(name: &str) -> Option<&'static BuiltinScene> {
    SCENES.iter().find(|s| s.name == name)
}

/// A built-in scene by name (any entry of [`SCENES`]).
///
/// # Errors
/// [`SceneError::UnknownScene`], listing the built-in names, when no scene
/// has that name.
pub fn builtin(name: &str) -> Result<Scene, SceneError> {
    match find(name) {
        Some(entry) => entry.build(),
        None => Err(SceneError::UnknownScene {
            name: name.into(),
            known: names().collect::<Vec<_>>().join(", "),
        }),
    }
}

/// The command line's help for a scene argument: every built-in scene with
/// its description, from [`SCENES`], then `extra` (other names the argument
/// takes, e.g. data scenes and file paths).
pub fn scene_help(intro: &str, sdf_only: bool, extra: &str) -> String {
    let mut s = format!("{intro}\n");
    for e in SCENES.iter().filter(|e| !sdf_only || e.is_sdf()) {
        s.push_str(&format!("\n{}: {}", e.name, e.description));
    }
    if !extra.is_empty() {
        s.push_str(&format!("\n\n{extra}"));
    }
    s
}
