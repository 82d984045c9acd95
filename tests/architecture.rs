//! `ARCHITECTURE.md` against the repository: the paths it names exist, and
//! its crate tree is the workspace.
//!
//! **Paths.** Every span in backticks is read, in the prose and in the
//! crate tree (a fenced block's fence lines aside). A span is taken as a
//! path when it is made only of ASCII letters, digits and `_ - . / < > *`
//! and it contains a `/` or ends in `.rs`, `.md`, `.toml`, `.wgsl`, `.c` or
//! `.h`. So these are not paths and are not checked: Rust paths
//! (`crate::module`, `subcone_passes::bind`: `:` is not a path character),
//! calls and expressions (`exp(−d²/σs²)`), commands with arguments
//! (whitespace), and an extension alone (`.wgsl`: a leading dot and no
//! `/`). A path exists when
//!
//! 1. it names a file or directory from the repository root
//!    (`backends/cpu/tests/isa.rs`, `capi/smoke`), or
//! 2. it is written relative to the crate or folder its sentence is about
//!    (`post/fxaa.rs` in a paragraph on the wgpu backend, `timing.rs` in one
//!    on the report) and some file or directory of the repository ends with
//!    it: its path is `…/` followed by the span.
//!
//! A placeholder (`<name>`, `*`) stands for any part: the span up to the
//! last `/` before the first placeholder must exist by the same rules
//! (`fuzz/seeds/sdf_file/<name>.sdf.ron` needs `fuzz/seeds/sdf_file/`).
//! Two kinds of path name no file of the repository and are skipped: an
//! absolute path (`/proc/stat`: the system's), and what builds and runs
//! write (a span starting with one of [`OUTPUTS`]). The repository is
//! walked from its root without `.git/` and any `target/`.
//!
//! **Crates.** The crate tree (the first fenced block) lists one folder per
//! line after `├── ` or `└── `, then the crate's name and a colon, or
//! `not a crate`; its folders that are crates are exactly the root
//! `Cargo.toml`'s workspace members, each under the name its own
//! `Cargo.toml` gives, and its first word is the root package's name.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// Spans naming what builds and runs write, outside the repository's files:
/// build output, and the directory `subcone report` writes by default.
const OUTPUTS: [&str; 2] = ["target/", "report/"];

/// Extensions that make a span without `/` a path.
const PATH_EXTENSIONS: [&str; 6] = [".rs", ".md", ".toml", ".wgsl", ".c", ".h"];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn architecture() -> String {
    std::fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md")
}

/// The text of every backticked span, whitespace collapsed (a span may
/// wrap), fence lines left out.
fn spans(markdown: &str) -> Vec<String> {
    let text: String = markdown
        .lines()
        .filter(|l| !l.trim_start().starts_with("```"))
        .collect::<Vec<_>>()
        .join("\n");
    text.split('`')
        .skip(1)
        .step_by(2)
        .map(|s| s.split_whitespace().collect::<Vec<_>>().join(" "))
        .collect()
}

/// Whether `span` is a path by the rule in the module's doc.
fn is_path(span: &str) -> bool {
    let chars_ok = !span.is_empty()
        && span
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_-./<>*".contains(c));
    let extension_alone = span.starts_with('.') && !span.contains('/');
    chars_ok
        && !extension_alone
        && (span.contains('/') || PATH_EXTENSIONS.iter().any(|e| span.ends_with(e)))
}

/// Every file and directory of the repository, relative to its root, with
/// `/` separators; `.git/` and `target/` directories left out.
fn repository_paths() -> BTreeSet<String> {
    fn walk(dir: &Path, rel: &str, out: &mut BTreeSet<String>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            let path = if rel.is_empty() {
                name.clone()
            } else {
                format!("{rel}/{name}")
            };
            let is_dir = e.file_type().is_ok_and(|t| t.is_dir());
            if is_dir && (name == ".git" || name == "target") {
                continue;
            }
            out.insert(path.clone());
            if is_dir {
                walk(&e.path(), &path, out);
            }
        }
    }
    let mut out = BTreeSet::new();
    walk(root(), "", &mut out);
    out
}

/// Why `span` (a path) names nothing in `paths`, or `None` when it exists.
fn missing(span: &str, paths: &BTreeSet<String>) -> Option<String> {
    if span.starts_with('/') || OUTPUTS.iter().any(|o| span.starts_with(o)) {
        return None;
    }
    let (path, placeholder) = match span.find(['<', '*']) {
        Some(at) => match span[..at].rfind('/') {
            Some(slash) => (&span[..slash], true),
            None => return Some(format!("`{span}`: a placeholder with no folder before it")),
        },
        None => (span.trim_end_matches('/'), false),
    };
    let suffix = format!("/{path}");
    let exists = paths.contains(path) || paths.iter().any(|p| p.ends_with(&suffix));
    (!exists).then(|| {
        if placeholder {
            format!("`{span}`: no folder `{path}`")
        } else {
            format!("`{span}`")
        }
    })
}

#[test]
fn every_path_architecture_md_names_exists() {
    let paths = repository_paths();
    assert!(
        paths.contains("Cargo.toml") && paths.len() > 100,
        "{} paths",
        paths.len()
    );
    let spans = spans(&architecture());
    let checked: BTreeSet<&String> = spans.iter().filter(|s| is_path(s)).collect();
    assert!(checked.len() > 50, "only {} paths found", checked.len());
    let problems: Vec<String> = checked.iter().filter_map(|s| missing(s, &paths)).collect();
    assert!(
        problems.is_empty(),
        "ARCHITECTURE.md names paths that do not exist:\n  {}",
        problems.join("\n  ")
    );
}

#[test]
fn the_path_rule_reads_spans_as_documented() {
    let md = "`crate::sdf::lane` `exp(−d²/σs²)` `cargo tree -p x` `.wgsl` `a/b.rs` `x.rs`\n\
              ```\n`fenced/too.rs`\n```\n`wraps\n  over/lines`";
    let found: Vec<String> = spans(md).into_iter().filter(|s| is_path(s)).collect();
    assert_eq!(found, ["a/b.rs", "x.rs", "fenced/too.rs"]);
    let paths: BTreeSet<String> = ["src", "src/shaders.rs", "backends/wgpu/src/post/fxaa.rs"]
        .map(String::from)
        .into();
    assert_eq!(missing("src/shaders.rs", &paths), None);
    assert_eq!(missing("src/", &paths), None);
    assert_eq!(missing("post/fxaa.rs", &paths), None);
    assert_eq!(missing("shaders.rs", &paths), None);
    assert_eq!(
        missing("ost/fxaa.rs", &paths).as_deref(),
        Some("`ost/fxaa.rs`")
    );
    assert_eq!(missing("src/<name>.rs", &paths), None);
    assert!(missing("lib/<name>.rs", &paths).is_some());
    assert_eq!(missing("target/conformance/x/", &paths), None);
    assert_eq!(missing("/proc/stat", &paths), None);
}

/// `(folder, crate name or None for "not a crate")` of every entry of the
/// crate tree, and the tree's first word.
fn crate_tree(markdown: &str) -> (String, Vec<(String, Option<String>)>) {
    let mut blocks = markdown.split("```").skip(1).step_by(2);
    let tree = blocks.next().expect("a fenced crate tree");
    let first_word = tree
        .split_whitespace()
        .next()
        .expect("the root package")
        .to_owned();
    let entries = tree
        .lines()
        .filter_map(|l| {
            let at = l.find("├── ").or_else(|| l.find("└── "))?;
            let rest = l[at..].split_once(' ')?.1.trim_start();
            let (folder, rest) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
            let folder = folder.trim_end_matches('/').to_owned();
            let rest = rest.trim_start();
            let name = if rest.starts_with("not a crate") {
                None
            } else {
                Some(rest.split(':').next().unwrap_or_default().trim().to_owned())
            };
            Some((folder, name))
        })
        .collect();
    (first_word, entries)
}

/// The value of the first `key = "…"` line of `toml` after `[package]`.
fn package_name(toml: &str) -> Option<String> {
    let package = toml.split("[package]").nth(1)?;
    package.lines().find_map(|l| {
        let value = l
            .trim()
            .strip_prefix("name")?
            .trim_start()
            .strip_prefix('=')?;
        Some(value.trim().trim_matches('"').to_owned())
    })
}

/// The root `Cargo.toml`'s `[workspace] members`.
fn workspace_members(toml: &str) -> BTreeSet<String> {
    let after = toml.split("members").nth(1).expect("workspace members");
    let list = after
        .split_once('[')
        .expect("[")
        .1
        .split_once(']')
        .expect("]")
        .0;
    list.split(',')
        .map(|m| m.trim().trim_matches('"').to_owned())
        .filter(|m| !m.is_empty())
        .collect()
}

#[test]
fn the_crate_tree_is_the_workspace() {
    let read = |p: PathBuf| std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{p:?}: {e}"));
    let root_toml = read(root().join("Cargo.toml"));
    let members = workspace_members(&root_toml);
    assert!(
        members.contains("kernels") && members.len() > 5,
        "{members:?}"
    );
    let (first_word, entries) = crate_tree(&architecture());
    assert_eq!(
        Some(first_word),
        package_name(&root_toml),
        "the tree's root"
    );
    let mut problems = Vec::new();
    let mut crates = BTreeSet::new();
    for (folder, name) in &entries {
        let manifest = root().join(folder).join("Cargo.toml");
        match name {
            None if members.contains(folder) => problems.push(format!(
                "{folder} is a workspace member, not \"not a crate\""
            )),
            None => {}
            Some(name) => {
                crates.insert(folder.clone());
                let actual = std::fs::read_to_string(&manifest)
                    .ok()
                    .and_then(|t| package_name(&t));
                if actual.as_deref() != Some(name.as_str()) {
                    problems.push(format!(
                        "{folder}: the tree says {name}, its Cargo.toml {actual:?}"
                    ));
                }
            }
        }
    }
    for m in members.difference(&crates) {
        problems.push(format!("{m}: a workspace member the tree does not list"));
    }
    for c in crates.difference(&members) {
        problems.push(format!("{c}: in the tree, not a workspace member"));
    }
    assert!(
        problems.is_empty(),
        "ARCHITECTURE.md's crate tree and the workspace differ:\n  {}",
        problems.join("\n  ")
    );
}
