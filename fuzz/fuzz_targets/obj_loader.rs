//! Arbitrary bytes as an OBJ file (and, after the separator line `#--8<--`,
//! as the `m.mtl` it may name with `mtllib m.mtl`) through
//! `subcone_load::load_mesh_bytes`, the loader behind `load_scene`: never a
//! panic (not even one the loader catches), errors are values, and a loaded
//! mesh keeps the loader's promises (see `common::loader::check_mesh`).
#![no_main]

#[path = "common/loader.rs"]
mod loader;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = loader::split(data);
    loader::side_file("m.mtl", mtl);
    loader::load_and_check("f.obj", obj);
});
