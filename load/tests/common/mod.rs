//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use subcone_load::{data_dir, load_mesh_file};
use subcone_scene::SceneError;

/// A file of the shared data directory. Fails (never skips) when the directory
/// is missing, saying how to point the tests at it.
pub fn data_file(rel: &str) -> PathBuf {
    let dir = data_dir();
    assert!(
        dir.is_dir(),
        "test data directory {} not found: set SUBCONE_DATA_DIR to the shared data \
         directory (e.g. SUBCONE_DATA_DIR=../shared/data from the workspace root)",
        dir.display()
    );
    let path = dir.join(rel);
    assert!(
        path.is_file(),
        "test data file {} not found: set SUBCONE_DATA_DIR to the shared data directory \
         holding {rel}",
        path.display()
    );
    path
}

/// Write `contents` to `dir/name` and return the path.
pub fn write(dir: &Path, name: &str, contents: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, contents).expect("write test file");
    path
}

/// Standard base64 with padding (for glTF data URIs).
pub fn base64(data: &[u8]) -> String {
    use ::base64::Engine;
    ::base64::engine::general_purpose::STANDARD.encode(data)
}

/// Little-endian bytes of f32s.
pub fn f32_bytes(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// Little-endian bytes of u16s, padded to a multiple of 4 bytes.
pub fn u16_bytes(v: &[u16]) -> Vec<u8> {
    let mut b: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    while b.len() % 4 != 0 {
        b.push(0);
    }
    b
}

/// A binary glTF container holding `json` and `bin`.
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while b.len() % 4 != 0 {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

/// The error of loading the mesh file at `path`, which must fail with a
/// message that says `what`.
pub fn load_error(path: &Path, what: &str) -> SceneError {
    let err = load_mesh_file(path).unwrap_err();
    assert!(
        err.to_string().contains(what),
        "{err} does not say {what:?}"
    );
    err
}
