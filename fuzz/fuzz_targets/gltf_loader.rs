//! Arbitrary bytes as a glTF file (JSON, or binary GLB when they start with
//! `glTF`; and, after the separator line `#--8<--`, as the `b.bin` a `.gltf`
//! may name as a buffer URI) through `subcone_load::load_mesh_bytes`, the
//! loader behind `load_scene`: never a panic (not even one the loader
//! catches), errors are values, and a loaded mesh keeps the loader's promises
//! (see `common::loader::check_mesh`).
#![no_main]

#[path = "common/loader.rs"]
mod loader;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (file, bin) = loader::split(data);
    loader::side_file("b.bin", bin);
    let name = if file.starts_with(b"glTF") {
        "f.glb"
    } else {
        "f.gltf"
    };
    loader::load_and_check(name, file);
});
