//! Built-in procedural scenes: no files needed.

mod atrium;
mod checker;
mod cornell;

pub use atrium::{atrium, ATRIUM_FLOOR_REFLECTANCE};
pub use checker::{checker, CHECKER_PALETTE, CHECKER_PATCH};
pub use cornell::cornell;

use crate::error::SceneError;
use crate::scene::Scene;

/// Names of the built-in triangle scenes.
pub const TRIANGLE_SCENES: [&str; 4] = ["cornell", "cornell-nomirror", "checker", "atrium"];

/// The paper scenes of both papers, as the report runs them by default:
/// triangle scenes for the SRAA family, SDF scenes for the CTSS family.
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

/// The name of every built-in scene, each of which [`builtin`] builds:
/// [`TRIANGLE_SCENES`], then [`crate::sdf::SDF_SCENES`],
/// [`crate::sdf::STIFF_SCENES`] and [`crate::sdf::TRANSPARENT_SCENES`].
pub fn names() -> impl Iterator<Item = &'static str> {
    TRIANGLE_SCENES
        .into_iter()
        .chain(crate::sdf::SDF_SCENES)
        .chain(crate::sdf::STIFF_SCENES)
        .chain(crate::sdf::TRANSPARENT_SCENES)
}

/// A built-in scene by name: a triangle scene ([`TRIANGLE_SCENES`]) or an SDF
/// scene ([`crate::sdf::SDF_SCENES`], [`crate::sdf::STIFF_SCENES`]).
pub fn builtin(name: &str) -> Result<Scene, SceneError> {
    match name {
        "cornell" => Ok(cornell(true)),
        "cornell-nomirror" => Ok(cornell(false)),
        "checker" => Ok(checker()),
        "atrium" => Ok(atrium()),
        _ => match crate::sdf::sdf_builtin(name) {
            Some(s) => Scene::sdf(s?),
            None => Err(SceneError::UnknownScene {
                name: name.into(),
                known: names().collect::<Vec<_>>().join(", "),
            }),
        },
    }
}
