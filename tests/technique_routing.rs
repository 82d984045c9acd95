//! Every backend routes techniques exhaustively: the kernels'
//! `Technique` is not `#[non_exhaustive]` (its `compile_fail` doctest shows a
//! match that leaves one out does not compile), and no backend matches on it
//! with a wildcard arm or dispatches a frame by comparing it with one
//! technique. A technique added to the registry is then a compile error in
//! each backend until that backend says what it does with it.

use std::fs;
use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The arms of each `match … technique() {` in `src`: the lines of the
/// match's body at its own brace depth, as (line number, text).
fn technique_match_arms(src: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = src.lines().collect();
    let mut arms = Vec::new();
    for (n, line) in lines.iter().enumerate() {
        let opens = line.contains("match ") && line.contains("technique()") && line.ends_with('{');
        if !opens {
            continue;
        }
        let mut depth = 1i32;
        for (m, body) in lines.iter().enumerate().skip(n + 1) {
            if depth == 1 {
                arms.push((m + 1, body.trim().to_string()));
            }
            depth += body.matches('{').count() as i32 - body.matches('}').count() as i32;
            if depth <= 0 {
                break;
            }
        }
    }
    arms
}

/// What in `src` routes techniques without naming each one: wildcard or
/// binding arms of a `match … technique()`, and `if … technique() == …`
/// followed by a `return` (a frame dispatched on one technique, the rest
/// falling through), as (line number, what).
fn unnamed_routes(src: &str) -> Vec<(usize, String)> {
    let mut problems = Vec::new();
    for (line, arm) in technique_match_arms(src) {
        let Some((pattern, _)) = arm.split_once("=>") else {
            continue;
        };
        let pattern = pattern.trim();
        let catch_all = !pattern.is_empty()
            && pattern
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_');
        if catch_all {
            problems.push((line, format!("catch-all arm `{arm}`")));
        }
    }
    let lines: Vec<&str> = src.lines().collect();
    for (n, line) in lines.iter().enumerate() {
        let dispatch = line.trim_start().starts_with("if ")
            && line.contains("technique() ==")
            && lines.get(n + 1).is_some_and(|next| next.contains("return"));
        if dispatch {
            problems.push((
                n + 1,
                format!("dispatch on one technique `{}`", line.trim()),
            ));
        }
    }
    problems
}

#[test]
fn backends_route_every_technique_by_name() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in [
        "backends/cpu/src",
        "backends/wgpu/src",
        "backends/passes/src",
    ] {
        rust_files(&root.join(dir), &mut files);
    }
    assert!(
        files.len() > 10,
        "found only {} backend sources",
        files.len()
    );
    let mut routes = 0;
    let mut problems = Vec::new();
    for file in &files {
        let src = fs::read_to_string(file).unwrap();
        if !technique_match_arms(&src).is_empty() {
            routes += 1;
        }
        for (line, what) in unnamed_routes(&src) {
            problems.push(format!("{}:{line}: {what}", file.display()));
        }
    }
    // The CPU backend's triangle and SDF routes, the wgpu backend's.
    assert!(
        routes >= 4,
        "expected the backends' technique routes, found {routes} files"
    );
    assert!(
        problems.is_empty(),
        "techniques routed without naming each one:\n{}",
        problems.join("\n")
    );
}

#[test]
fn the_check_finds_catch_alls_and_dispatches() {
    let wildcard =
        "    match m.technique() {\n        Technique::NoAa => a(),\n        _ => b(),\n    }\n";
    let binding =
        "    match m.technique() {\n        Technique::NoAa => a(),\n        t => b(t),\n    }\n";
    let dispatch =
        "    if method.technique() == Technique::SraaRt {\n        return rt();\n    }\n";
    let named = "    match m.technique() {\n        Technique::NoAa\n        | Technique::Ssaa => a(),\n        t @ (Technique::Ctss | Technique::CtssR) => {\n            return b(t);\n        }\n    }\n";
    assert_eq!(unnamed_routes(wildcard).len(), 1, "{wildcard}");
    assert_eq!(unnamed_routes(binding).len(), 1, "{binding}");
    assert_eq!(unnamed_routes(dispatch).len(), 1, "{dispatch}");
    assert!(
        unnamed_routes(named).is_empty(),
        "{:?}",
        unnamed_routes(named)
    );
}
