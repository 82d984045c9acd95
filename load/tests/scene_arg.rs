//! `scene_from_arg`, the command line's scene resolver: every built-in scene
//! by its registry name, and a clear error for a name that is nothing.

use subcone_load::{scene_from_arg, DATA_SCENES};
use subcone_scene::builtin::{names, SCENES};
use subcone_scene::SceneError;

#[test]
fn every_builtin_scene_resolves_by_name() {
    for entry in &SCENES {
        let scene = scene_from_arg(entry.name).unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        assert_eq!(scene.name, entry.name);
        assert_eq!(
            scene.sdf_geometry().is_some(),
            entry.is_sdf(),
            "{}",
            entry.name
        );
    }
}

#[test]
fn an_unknown_name_lists_every_scene() {
    let err = scene_from_arg("no-such-scene").unwrap_err();
    assert!(matches!(err, SceneError::UnknownScene { .. }), "{err:?}");
    let msg = err.to_string();
    for name in names().chain(DATA_SCENES) {
        assert!(msg.contains(name), "{name} missing from {msg}");
    }
}
