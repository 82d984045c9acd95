//! No import circle between the top-level modules of the contract crate
//! (`subcone-scene`), the report (`subcone-report`) and the other crates
//! listed in `LAYERED` below, nor between the files of one folder inside
//! them: one reader and one cycle finder for all.
//!
//! Every `crate::<module>` reference in `src/**/*.rs` (code, not comments or
//! strings: a doc link may point up a layer) is an edge from the module the
//! file belongs to; `super::` paths that climb to the crate root count the
//! same. A cycle of such edges is a failure that names the modules in order.
//! A reference through a root re-export (`crate::Scene`) hides which module
//! it needs, so code names the module (`crate::scene::Scene`).
//!
//! Inside a folder module (`sdf/mod.rs` and the files of `sdf/`) the same
//! rule holds between its children, one level down at a time: a reference
//! from a file under child `a` (`super::b::X`, `crate::sdf::b::X`) to child
//! `b` is an edge `a -> b` of the folder's graph, and the folder's own file
//! is above its children, as the crate root is above the top-level
//! modules: what it declares itself (`super::Exactness`) is no edge, while a
//! name it only re-exports from a child (`super::SdfNode`, `pub use
//! node::SdfNode`) is an edge to that child, so that a re-export cannot hide
//! a circle.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// `(top-level module, file text)` for every file under `src/`: `lib.rs` is
/// the root (`""`), `a.rs` and `a/**` are `a`.
fn sources(src: &Path) -> Vec<(String, Vec<String>, String)> {
    fn walk(dir: &Path, rel: &mut Vec<String>, out: &mut Vec<(String, Vec<String>, String)>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            let name = path.file_name().unwrap().to_str().unwrap().to_string();
            if path.is_dir() {
                rel.push(name);
                walk(&path, rel, out);
                rel.pop();
            } else if let Some(stem) = name.strip_suffix(".rs") {
                // The file's own module path: `sdf/mod.rs` is `sdf`,
                // `sdf/shape.rs` is `sdf::shape`, `lib.rs` is the root.
                let mut module = rel.clone();
                if stem != "mod" && stem != "lib" {
                    module.push(stem.to_string());
                }
                let top = module.first().cloned().unwrap_or_default();
                out.push((top, module, std::fs::read_to_string(&path).unwrap()));
            }
        }
    }
    let mut out = Vec::new();
    walk(src, &mut Vec::new(), &mut out);
    out
}

/// The text with comments, string and character literals blanked out.
fn code_only(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            let mut depth = 0;
            while i < b.len() {
                if b[i..].starts_with(b"/*") {
                    depth += 1;
                    i += 2;
                } else if b[i..].starts_with(b"*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if b[i] == b'r' && (b[i + 1..].starts_with(b"\"") || b[i + 1..].starts_with(b"#")) {
            // A raw string: r"…", r#"…"#.
            let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
            if b.get(i + 1 + hashes) != Some(&b'"') {
                out.push('r');
                i += 1;
                continue;
            }
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            i += 2 + hashes;
            while i < b.len() && !b[i..].starts_with(&close) {
                i += 1;
            }
            i += close.len();
            out.push_str("\"\"");
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if b[i] == b'\'' && i + 2 < b.len() && (b[i + 2] == b'\'' || b[i + 1] == b'\\') {
            // A character literal ('x', '\n', '\''); lifetimes ('a) pass.
            i += 2;
            while i < b.len() && b[i] != b'\'' {
                i += 1;
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(b[i] as char);
            i += 1;
        }
    }
    out
}

fn ident(s: &str) -> &str {
    let end = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    &s[..end]
}

/// The first path segment of each item of a `{…}` group (nested groups
/// included only by their first segment), after the opening brace.
fn group_heads(s: &str) -> Vec<String> {
    let mut heads = Vec::new();
    let (mut depth, mut start) = (0usize, true);
    for (i, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => break,
            '}' => depth -= 1,
            ',' if depth == 0 => start = true,
            c if start && depth == 0 && !c.is_whitespace() => {
                start = false;
                let head = ident(&s[i..]);
                if !head.is_empty() && head != "self" {
                    heads.push(head.to_string());
                }
            }
            _ => {}
        }
    }
    heads
}

/// The byte ranges of the inline modules (`mod name { … }`) of a file's code.
fn inline_mods(code: &str) -> Vec<(usize, usize)> {
    let mut ranges = Vec::new();
    let mut open: Vec<(usize, usize)> = Vec::new(); // (start, brace depth inside)
    let mut depth = 0usize;
    let mut pending = false; // `mod name` seen, its `{` not yet
    let b = code.as_bytes();
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'{' => {
                depth += 1;
                if pending {
                    open.push((i, depth));
                    pending = false;
                }
            }
            b'}' => {
                if open.last().is_some_and(|&(_, d)| d == depth) {
                    let (start, _) = open.pop().unwrap();
                    ranges.push((start, i));
                }
                depth = depth.saturating_sub(1);
            }
            b';' => pending = false,
            b'm' if code[i..].starts_with("mod ")
                && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')) =>
            {
                pending = true;
            }
            _ => {}
        }
    }
    ranges
}

/// The top-level modules each top-level module refers to, and the references
/// that name a root item instead of its module.
type Graph = BTreeMap<String, BTreeSet<String>>;

fn module_graph(files: &[(String, Vec<String>, String)]) -> (Graph, Vec<String>) {
    let modules: BTreeSet<String> = files
        .iter()
        .map(|(top, _, _)| top.clone())
        .filter(|t| !t.is_empty())
        .collect();
    let mut graph: Graph = modules
        .iter()
        .map(|m| (m.clone(), BTreeSet::new()))
        .collect();
    let mut through_root = Vec::new();
    for (top, module, text) in files {
        if top.is_empty() {
            continue; // lib.rs declares and re-exports; it is above every module.
        }
        let code = code_only(text);
        let mut refs: Vec<String> = Vec::new();
        for (at, _) in code.match_indices("crate::") {
            // Skip identifiers that merely end in `crate` (`subcone_crate::`).
            let before = code[..at].chars().next_back();
            if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_') {
                continue;
            }
            let rest = &code[at + "crate::".len()..];
            if let Some(group) = rest.strip_prefix('{') {
                refs.extend(group_heads(group));
            } else {
                refs.push(ident(rest).to_string());
            }
        }
        // `super::` out of a file's module: climbing to the root (from
        // `sdf/mod.rs`, `super::` is the crate) is a `crate::` reference.
        let inline = inline_mods(&code);
        for (at, _) in code.match_indices("super::") {
            let before = code[..at].chars().next_back();
            if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let mut rest = &code[at..];
            let mut up = 0;
            while let Some(r) = rest.strip_prefix("super::") {
                up += 1;
                rest = r;
            }
            // Inside an inline `mod tests { … }`, the first `super` is the
            // file's own module.
            let enclosing = inline
                .iter()
                .filter(|(open, close)| *open < at && at < *close)
                .count();
            if up >= module.len() + enclosing {
                if let Some(group) = rest.strip_prefix('{') {
                    refs.extend(group_heads(group));
                } else {
                    refs.push(ident(rest).to_string());
                }
            }
        }
        for r in refs {
            if r == *top {
                continue;
            }
            if modules.contains(&r) {
                graph.get_mut(top).unwrap().insert(r);
            } else {
                through_root.push(format!("{}: crate::{r}", module.join("::")));
            }
        }
    }
    (graph, through_root)
}

/// One cycle of the graph, in order (the first module repeated at the end),
/// or `None`.
fn find_cycle(graph: &Graph) -> Option<Vec<String>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    fn visit<'a>(
        graph: &'a Graph,
        node: &'a String,
        marks: &mut BTreeMap<&'a String, Mark>,
        stack: &mut Vec<&'a String>,
    ) -> Option<Vec<String>> {
        marks.insert(node, Mark::Open);
        stack.push(node);
        for next in graph.get(node).into_iter().flatten() {
            match marks.get(next).copied().unwrap_or(Mark::New) {
                Mark::Open => {
                    let from = stack.iter().position(|m| *m == next).unwrap();
                    let mut cycle: Vec<String> =
                        stack[from..].iter().map(|m| m.to_string()).collect();
                    cycle.push(next.clone());
                    return Some(cycle);
                }
                Mark::New => {
                    if let Some(c) = visit(graph, next, marks, stack) {
                        return Some(c);
                    }
                }
                Mark::Done => {}
            }
        }
        stack.pop();
        marks.insert(node, Mark::Done);
        None
    }
    let mut marks = BTreeMap::new();
    for node in graph.keys() {
        if marks.get(node).copied().unwrap_or(Mark::New) == Mark::New {
            if let Some(c) = visit(graph, node, &mut marks, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

fn render(graph: &Graph) -> String {
    graph
        .iter()
        .map(|(m, uses)| {
            format!(
                "{m} -> {}",
                uses.iter().cloned().collect::<Vec<_>>().join(", ")
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// What a crate's root may hold.
#[derive(Clone, Copy, PartialEq)]
enum Root {
    /// Modules and re-exports only: code names the module that defines an
    /// item (`crate::scene::Scene`, not `crate::Scene`).
    ReExports,
    /// The crate's pipeline, whose shared types (the report's `ResultRow`,
    /// `Mode`, `SceneJob`, …) the stages use through `crate::`: the root is
    /// above every module and not a node of the graph; the rule holds
    /// between the modules.
    Pipeline,
}

/// The crates held to the rule: the folder, what its root may hold, and how
/// many modules it has at least (so that a wrong folder cannot pass by
/// finding nothing).
const LAYERED: [(&str, Root, usize); 4] = [
    ("scene", Root::ReExports, 10),
    ("subcone-report", Root::Pipeline, 20),
    ("sdf", Root::ReExports, 2),
    ("load", Root::ReExports, 3),
];

fn check_layers(crate_dir: &str, root: Root, min_modules: usize) -> Result<String, String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(crate_dir)
        .join("src");
    let (graph, through_root) = module_graph(&sources(&src));
    if root == Root::ReExports && !through_root.is_empty() {
        return Err(format!(
            "{crate_dir}: name the module, not a root re-export:\n{}",
            through_root.join("\n")
        ));
    }
    if graph.len() < min_modules {
        return Err(format!(
            "{crate_dir}: too few modules found:\n{}",
            render(&graph)
        ));
    }
    if let Some(cycle) = find_cycle(&graph) {
        return Err(format!(
            "import circle in {crate_dir}: {}\n\nthe module graph:\n{}",
            cycle.join(" -> "),
            render(&graph)
        ));
    }
    Ok(render(&graph))
}

#[test]
fn no_import_circle_between_the_modules_of_a_layered_crate() {
    let mut failures = Vec::new();
    for (dir, root, min_modules) in LAYERED {
        match check_layers(dir, root, min_modules) {
            Ok(graph) => println!("{dir}:\n{graph}\n"),
            Err(e) => failures.push(e),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

fn synthetic(files: &[(&str, &[&str], &str)]) -> Vec<(String, Vec<String>, String)> {
    files
        .iter()
        .map(|(top, module, text)| {
            (
                top.to_string(),
                module.iter().map(|s| s.to_string()).collect(),
                text.to_string(),
            )
        })
        .collect()
}

#[test]
fn the_cycle_finder_finds_a_cycle_through_groups_and_super() {
    // a -> b (a plain path), b -> c (a group), c -> a (`super::` out of
    // `c/x.rs` climbs to `c`, not out of the crate; `super::super::` does).
    let files = synthetic(&[
        ("a", &["a"], "use crate::b::Thing;\nfn f() {}"),
        ("b", &["b"], "use crate::{c::{self, Other}, b::Own};"),
        (
            "c",
            &["c", "x"],
            "use super::Local;\nfn g() { super::super::a::f() }",
        ),
        (
            "d",
            &["d"],
            "use crate::a::f;\n#[cfg(test)]\nmod tests {\n    use super::*;\n}",
        ),
    ]);
    let (graph, through_root) = module_graph(&files);
    assert!(through_root.is_empty(), "{through_root:?}");
    assert_eq!(graph["a"], BTreeSet::from(["b".to_string()]));
    assert_eq!(graph["b"], BTreeSet::from(["c".to_string()]));
    assert_eq!(graph["c"], BTreeSet::from(["a".to_string()]));
    let cycle = find_cycle(&graph).expect("a -> b -> c -> a");
    assert_eq!(cycle.first(), cycle.last());
    assert_eq!(cycle.len(), 4, "{cycle:?}");
}

#[test]
fn comments_and_strings_are_not_references() {
    let files = synthetic(&[
        (
            "a",
            &["a"],
            "/// See [`crate::b::X`].\n// crate::b\n/* crate::b */\nconst S: &str = \"crate::b\";\nconst R: &str = r#\"crate::b\"#;\nconst C: char = '\"';\nfn f<'x>() {}",
        ),
        ("b", &["b"], "use crate::a::S;"),
    ]);
    let (graph, _) = module_graph(&files);
    assert!(graph["a"].is_empty(), "{graph:?}");
    assert_eq!(find_cycle(&graph), None);
    // The same two modules with a real reference back form a cycle.
    let files = synthetic(&[
        ("a", &["a"], "fn f() { crate::b::g() }"),
        ("b", &["b"], "use crate::a::S;"),
    ]);
    assert!(find_cycle(&module_graph(&files).0).is_some());
}

#[test]
fn a_root_re_export_is_reported() {
    let files = synthetic(&[
        ("a", &["a"], "fn f(s: &crate::Scene) {}"),
        ("scene", &["scene"], ""),
    ]);
    let (_, through_root) = module_graph(&files);
    assert_eq!(through_root, vec!["a: crate::Scene".to_string()]);
}

/// A path as written, one segment per item (`["node", "SdfNode"]` for
/// `node::SdfNode`), and the name a `use … as name` gives it.
type WrittenPath = (Vec<String>, Option<String>);

/// The items of a `{…}` group, split at its top-level commas, after the
/// opening brace.
fn group_items(s: &str) -> Vec<&str> {
    let mut items = Vec::new();
    let (mut depth, mut start) = (0usize, 0usize);
    for (i, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => {
                items.push(&s[start..i]);
                return items;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&s[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items.push(&s[start..]);
    items
}

/// The paths written at the start of `s` (`a::b::{c, d::{self, e}}` is
/// `a::b::c`, `a::b::d` and `a::b::d::e`), each with its `as` name.
fn written_paths(s: &str) -> Vec<WrittenPath> {
    let mut segments = Vec::new();
    let mut rest = s;
    loop {
        let trimmed = rest.trim_start();
        if let Some(group) = trimmed.strip_prefix('{') {
            let mut out = Vec::new();
            for item in group_items(group) {
                for (tail, alias) in written_paths(item) {
                    let mut full = segments.clone();
                    if tail != ["self"] {
                        full.extend(tail);
                    }
                    out.push((full, alias));
                }
            }
            return out;
        }
        let id = ident(trimmed);
        if id.is_empty() {
            break;
        }
        segments.push(id.to_string());
        rest = &trimmed[id.len()..];
        match rest.strip_prefix("::") {
            Some(r) => rest = r,
            None => break,
        }
    }
    let alias = rest
        .trim_start()
        .strip_prefix("as ")
        .map(|a| ident(a.trim_start()).to_string());
    vec![(segments, alias)]
}

/// Every path the code of a file in `module` names from the crate root,
/// as absolute segments: `crate::…`, and `super::…` resolved from the
/// file's module (inside an inline `mod tests { … }`, the first `super` is
/// the file's own module). Paths that stay in the file are left out.
fn absolute_paths(module: &[String], code: &str) -> Vec<Vec<String>> {
    let inline = inline_mods(code);
    let mut out = Vec::new();
    for (at, _) in code.match_indices("crate::") {
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        out.extend(
            written_paths(&code[at + "crate::".len()..])
                .into_iter()
                .map(|(p, _)| p),
        );
    }
    for (at, _) in code.match_indices("super::") {
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':') {
            continue;
        }
        let mut rest = &code[at..];
        let mut up = 0;
        while let Some(r) = rest.strip_prefix("super::") {
            up += 1;
            rest = r;
        }
        let enclosing = inline
            .iter()
            .filter(|(open, close)| *open < at && at < *close)
            .count();
        if up <= enclosing || up - enclosing > module.len() {
            continue;
        }
        let base = &module[..module.len() - (up - enclosing)];
        out.extend(written_paths(rest).into_iter().map(|(p, _)| {
            let mut full = base.to_vec();
            full.extend(p);
            full
        }));
    }
    out
}

/// What each module re-exports: `(module, name)` to the absolute path the
/// name stands for, from its `pub use`, `pub(crate) use` and `pub(super)
/// use` lines (globs aside).
fn re_exports(
    files: &[(String, Vec<String>, String)],
) -> BTreeMap<(Vec<String>, String), Vec<String>> {
    let mut map = BTreeMap::new();
    for (_, module, text) in files {
        let code = code_only(text);
        for prefix in ["pub use ", "pub(crate) use ", "pub(super) use "] {
            for (at, _) in code.match_indices(prefix) {
                for (path, alias) in written_paths(&code[at + prefix.len()..]) {
                    let Some(name) = alias.or_else(|| path.last().cloned()) else {
                        continue;
                    };
                    let absolute = match path.first().map(String::as_str) {
                        Some("crate") => path[1..].to_vec(),
                        Some("self") => [module.as_slice(), &path[1..]].concat(),
                        Some("super") => {
                            let up = path.iter().take_while(|s| *s == "super").count();
                            if up > module.len() {
                                continue;
                            }
                            [&module[..module.len() - up], &path[up..]].concat()
                        }
                        Some(_) => [module.as_slice(), &path].concat(),
                        None => continue,
                    };
                    map.insert((module.clone(), name), absolute);
                }
            }
        }
    }
    map
}

/// The graph between the children of every folder module below the crate
/// root (keyed by the folder's module path), by the rule in the module's
/// doc.
fn folder_graphs(files: &[(String, Vec<String>, String)]) -> BTreeMap<Vec<String>, Graph> {
    let modules: BTreeSet<Vec<String>> = files
        .iter()
        .flat_map(|(_, m, _)| (0..=m.len()).map(move |n| m[..n].to_vec()))
        .collect();
    let exports = re_exports(files);
    // The module a path names (its longest prefix that is a module), and the
    // item after it, with re-exports followed.
    let resolve = |path: &[String]| -> Vec<String> {
        let mut path = path.to_vec();
        for _ in 0..8 {
            let n = (0..=path.len())
                .rev()
                .find(|&n| modules.contains(&path[..n]))
                .unwrap_or(0);
            let (module, rest) = path.split_at(n);
            match rest
                .first()
                .and_then(|item| exports.get(&(module.to_vec(), item.clone())))
            {
                Some(target) if target.as_slice() != path.as_slice() => {
                    path = [target.as_slice(), &rest[1..]].concat();
                }
                _ => return module.to_vec(),
            }
        }
        path
    };
    let mut graphs: BTreeMap<Vec<String>, Graph> = BTreeMap::new();
    for (_, module, text) in files {
        if module.len() < 2 {
            continue; // the crate root and its top-level modules: `module_graph`.
        }
        let code = code_only(text);
        for path in absolute_paths(module, &code) {
            let target = resolve(&path);
            let common = module
                .iter()
                .zip(&target)
                .take_while(|(a, b)| a == b)
                .count();
            if common == 0 || common >= module.len() || common >= target.len() {
                // Another top-level module, the file's own module or an
                // ancestor, or a descendant.
                continue;
            }
            let folder = module[..common].to_vec();
            let (from, to) = (module[common].clone(), target[common].clone());
            graphs
                .entry(folder)
                .or_default()
                .entry(from)
                .or_default()
                .insert(to);
        }
    }
    graphs
}

fn check_folders(crate_dir: &str) -> Result<String, String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(crate_dir)
        .join("src");
    let (mut rendered, mut circles) = (Vec::new(), Vec::new());
    for (folder, graph) in folder_graphs(&sources(&src)) {
        if let Some(cycle) = find_cycle(&graph) {
            circles.push(format!(
                "import circle between the files of {crate_dir}/src/{}: {}\n\nthe graph:\n{}",
                folder.join("/"),
                cycle.join(" -> "),
                render(&graph)
            ));
        }
        rendered.push(format!("{}:\n{}", folder.join("::"), render(&graph)));
    }
    if circles.is_empty() {
        Ok(rendered.join("\n"))
    } else {
        Err(circles.join("\n\n"))
    }
}

#[test]
fn no_import_circle_between_the_files_of_a_folder() {
    let mut failures = Vec::new();
    for (dir, _, _) in LAYERED {
        match check_folders(dir) {
            Ok(graphs) => println!("{dir}:\n{graphs}\n"),
            Err(e) => failures.push(e),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn the_folder_check_follows_paths_groups_and_re_exports() {
    // sdf/mod.rs re-exports `Shape` from `shape`; `lane` names it through
    // the folder (an edge), `shape` names `lane` by path, `node` names an
    // item the folder declares itself (no edge) and reaches `shape` from
    // the crate root inside a group.
    let files = synthetic(&[
        (
            "sdf",
            &["sdf"],
            "mod lane;\nmod node;\nmod shape;\npub use shape::Shape;\npub enum Exactness {}",
        ),
        ("sdf", &["sdf", "lane"], "use super::Shape;"),
        ("sdf", &["sdf", "shape"], "fn d() { super::lane::f() }"),
        (
            "sdf",
            &["sdf", "node"],
            "use super::Exactness;\nuse crate::{sdf::{shape::Shape as S}, scene::X};\n#[cfg(test)]\nmod tests {\n    use super::*;\n}",
        ),
    ]);
    let graphs = folder_graphs(&files);
    let sdf = &graphs[&vec!["sdf".to_string()]];
    assert_eq!(sdf["lane"], BTreeSet::from(["shape".to_string()]));
    assert_eq!(sdf["shape"], BTreeSet::from(["lane".to_string()]));
    assert_eq!(sdf["node"], BTreeSet::from(["shape".to_string()]));
    let cycle = find_cycle(sdf).expect("lane -> shape -> lane");
    assert_eq!(cycle.len(), 3, "{cycle:?}");
    assert_eq!(
        written_paths("a::b::{c, d::{self, e as f}}"),
        vec![
            (
                vec!["a", "b", "c"].into_iter().map(String::from).collect(),
                None
            ),
            (
                vec!["a", "b", "d"].into_iter().map(String::from).collect(),
                None
            ),
            (
                vec!["a", "b", "d", "e"]
                    .into_iter()
                    .map(String::from)
                    .collect(),
                Some("f".to_string())
            ),
        ]
    );
}
