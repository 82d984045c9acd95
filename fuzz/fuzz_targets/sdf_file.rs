//! Arbitrary bytes as an SDF scene file (`.sdf.ron`) through
//! `subcone_load::load_scene_bytes`, the reader behind `--scene FILE`, and
//! `sdf::file::parse_sdf_scene`: never a panic, errors are values
//! (`SceneError::SdfFile`/`Load`/`Sdf`) whose message starts with the file's
//! name; a scene that reads is a valid `Scene`, and it writes out and reads
//! back as the same scene, bit for bit (compared by `Debug`, which prints every
//! cached field and every float exactly). CI starts it from the exported
//! built-in scenes and the examples (`fuzz/seeds/sdf_file`).
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use subcone_load::file::{parse_sdf_scene, write_sdf_scene};
use subcone_load::load_scene_bytes;
use subcone_scene::SceneError;

const FILE: &str = "f.sdf.ron";

fuzz_target!(|data: &[u8]| {
    match load_scene_bytes(Path::new(FILE), data) {
        Ok(scene) => assert!(scene.sdf_geometry().is_some(), "not an SDF scene"),
        Err(SceneError::SdfFile(e)) => {
            assert!(e.to_string().starts_with(FILE), "{e}");
            assert!(!e.reason.is_empty(), "{e:?}");
        }
        Err(SceneError::Load { .. }) => assert!(std::str::from_utf8(data).is_err()),
        Err(e) => panic!("unexpected error kind: {e:?}"),
    }
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = parse_sdf_scene(text, FILE) else {
        return;
    };
    scene.validate().expect("a scene that reads is valid");
    let written = write_sdf_scene(&scene).expect("every scene that reads can be written");
    let again = parse_sdf_scene(&written, FILE)
        .unwrap_or_else(|e| panic!("a written scene does not read back: {e}\n{written}"));
    assert_eq!(
        format!("{again:?}"),
        format!("{scene:?}"),
        "written and read back, the scene changed:\n{written}"
    );
});
