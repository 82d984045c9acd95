//! wgpu is named in one module (`src/bind/`): every other source file of
//! the crate takes the host's wgpu types from there, so the next wgpu
//! upgrade touches that module (and `Cargo.toml`), not every pass.

use std::path::{Path, PathBuf};

/// The `.rs` files under `dir`, its folders' included, but for the `bind`
/// module's (`bind/`).
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src/") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            if !path.ends_with("bind") {
                sources(&path, out);
            }
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn only_bind_names_wgpu_items() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    assert!(
        src.join("bind").join("mod.rs").is_file(),
        "the bind module is src/bind/"
    );
    let mut paths = Vec::new();
    sources(&src, &mut paths);
    let mut offenders = Vec::new();
    for path in &paths {
        let text = std::fs::read_to_string(path).expect("source");
        for (i, line) in text.lines().enumerate() {
            // Code only: documentation may name wgpu's types.
            let code = line.split("//").next().unwrap_or_default();
            if code.contains("wgpu::") {
                offenders.push(format!("{}:{}: {}", path.display(), i + 1, line.trim()));
            }
        }
    }
    let files = paths.len();
    assert!(files >= 5, "found only {files} source files besides bind/");
    assert!(
        offenders.is_empty(),
        "name wgpu's items through crate::bind:\n{}",
        offenders.join("\n")
    );
}
