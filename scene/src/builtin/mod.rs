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

/// A built-in scene by name.
pub fn builtin(name: &str) -> Result<Scene, SceneError> {
    match name {
        "cornell" => Ok(cornell(true)),
        "cornell-nomirror" => Ok(cornell(false)),
        "checker" => Ok(checker()),
        "atrium" => Ok(atrium()),
        _ => Err(SceneError::UnknownScene {
            name: name.into(),
            known: TRIANGLE_SCENES.join(", "),
        }),
    }
}
