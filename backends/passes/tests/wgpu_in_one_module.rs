//! wgpu is named in one module (`src/bind.rs`): every other source file of
//! the crate takes the host's wgpu types from there, so the next wgpu
//! upgrade touches that module (and `Cargo.toml`), not every pass.

use std::path::Path;

#[test]
fn only_bind_names_wgpu_items() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut offenders = Vec::new();
    let mut files = 0;
    for entry in std::fs::read_dir(&src).expect("src/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "rs") || path.ends_with("bind.rs") {
            continue;
        }
        files += 1;
        let text = std::fs::read_to_string(&path).expect("source");
        for (i, line) in text.lines().enumerate() {
            // Code only: documentation may name wgpu's types.
            let code = line.split("//").next().unwrap_or_default();
            if code.contains("wgpu::") {
                offenders.push(format!("{}:{}: {}", path.display(), i + 1, line.trim()));
            }
        }
    }
    assert!(
        files >= 5,
        "found only {files} source files besides bind.rs"
    );
    assert!(
        offenders.is_empty(),
        "name wgpu's items through crate::bind:\n{}",
        offenders.join("\n")
    );
}
