//! Built-in procedural scenes: no files needed.

mod cornell;

pub use cornell::cornell;

use crate::error::SceneError;
use crate::scene::Scene;

/// Names of the built-in triangle scenes.
pub const TRIANGLE_SCENES: [&str; 2] = ["cornell", "cornell-nomirror"];

/// A built-in scene by name.
pub fn builtin(name: &str) -> Result<Scene, SceneError> {
    match name {
        "cornell" => Ok(cornell(true)),
        "cornell-nomirror" => Ok(cornell(false)),
        _ => Err(SceneError::UnknownScene {
            name: name.into(),
            known: TRIANGLE_SCENES.join(", "),
        }),
    }
}
