//! WGSL is composed, not edited: the GPU crates build every shader from
//! whole sources (files and generated declarations, validated by naga in the
//! crates' own tests) and never rewrite a shader's text by search and
//! replace, nor declare a dummy `var<private>` so that an included file's
//! unused entry point compiles. Each entry point that needs a binding lives
//! in a file that only the programs with that binding include.

use std::fs;
use std::path::{Path, PathBuf};

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            sources(&path, out);
        } else if (name.ends_with(".rs") || name.ends_with(".wgsl"))
            // Test code may build shaders any way it likes.
            && !matches!(name.as_str(), "test_util.rs" | "layout_tests.rs")
        {
            out.push(path);
        }
    }
}

/// The lines of `src` that edit shader text or declare a placeholder, as
/// (line number, what). Comments are skipped; so is everything after a
/// `#[cfg(test)]` line (a module of tests).
fn edits(src: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (n, line) in src.lines().enumerate() {
        let code = line.trim_start();
        if code.starts_with("#[cfg(test)]") {
            break;
        }
        if code.starts_with("//") {
            continue;
        }
        if code.contains(".replace(") || code.contains(".replacen(") {
            found.push((n + 1, format!("text replaced: `{code}`")));
        }
        // A private array of one element nobody writes: the placeholder of
        // a binding the program lacks.
        if code.contains("var<private>") && code.contains(", 1>") {
            found.push((n + 1, format!("placeholder: `{code}`")));
        }
    }
    found
}

#[test]
fn gpu_shaders_are_composed_not_edited() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["backends/wgpu/src", "backends/passes/src", "kernels/src"] {
        sources(&root.join(dir), &mut files);
    }
    let wgsl = files
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
        .count();
    assert!(wgsl >= 20, "found only {wgsl} WGSL files");
    let mut problems = Vec::new();
    for file in &files {
        let src = fs::read_to_string(file).unwrap();
        for (line, what) in edits(&src) {
            problems.push(format!("{}:{line}: {what}", file.display()));
        }
    }
    assert!(
        problems.is_empty(),
        "shader text edited:\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_check_finds_edits_and_placeholders() {
    let replace = "    let t = TRACE.replace(\"__N__\", \"4\");\n";
    let placeholder = "var<private> color: array<vec4<f32>, 1>;\n";
    let quoted = "        header += \"var<private> subsample: array<u32, 1>;\\n\";\n";
    let fine = "// a comment may say .replace(\nvar<private> counter: u32;\n#[cfg(test)]\nmod tests { fn f() { s.replace(\"a\", \"b\"); } }\n";
    assert_eq!(edits(replace).len(), 1);
    assert_eq!(edits(placeholder).len(), 1);
    assert_eq!(edits(quoted).len(), 1);
    assert!(edits(fine).is_empty(), "{:?}", edits(fine));
}
