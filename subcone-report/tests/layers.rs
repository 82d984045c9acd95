//! The report's modules form layers: no module reaches, through
//! `crate::<module>` or `super::<module>` paths, a module that reaches back
//! to it. A circle makes every module on it depend on all the others, so
//! that none can be read, tested or moved alone.
//!
//! The crate root (`lib.rs`) is the pipeline that calls the modules and
//! holds the row types they share; it is not a node of the graph. Comments
//! are skipped: a doc link is not a dependency.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Module name → the sibling modules its code names.
type Graph = BTreeMap<String, BTreeSet<String>>;

/// The graph of `sources` (module name, source text): every
/// `crate::<module>` and `super::<module>`, including each first segment of
/// a `crate::{a, b::c}` group, where `<module>` is one of the modules.
fn graph(sources: &[(String, String)]) -> Graph {
    let modules: BTreeSet<&str> = sources.iter().map(|(m, _)| m.as_str()).collect();
    let mut g = Graph::new();
    for (module, text) in sources {
        let code: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n");
        let deps = g.entry(module.clone()).or_default();
        for prefix in ["crate::", "super::"] {
            for (at, _) in code.match_indices(prefix) {
                let before = code[..at].chars().next_back();
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                    continue; // e.g. `subcone_crate::`
                }
                for name in first_segments(&code[at + prefix.len()..]) {
                    if name != module.as_str() && modules.contains(name) {
                        deps.insert(name.to_string());
                    }
                }
            }
        }
    }
    g
}

/// The first path segments after `crate::`: one identifier, or each
/// top-level item of a `{…}` group.
fn first_segments(rest: &str) -> Vec<&str> {
    fn ident(s: &str) -> &str {
        let s = s.trim_start();
        let end = s
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(s.len());
        &s[..end]
    }
    let Some(group) = rest.strip_prefix('{') else {
        return vec![ident(rest)];
    };
    let mut out = Vec::new();
    let (mut depth, mut start) = (0usize, 0usize);
    for (i, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => {
                out.push(ident(&group[start..i]));
                break;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push(ident(&group[start..i]));
                start = i + 1;
            }
            _ => {}
        }
    }
    out
}

/// Every circle of `g`, each as its modules in path order from the
/// smallest name and closed by repeating it; the strongly connected
/// components of more than one module, walked once each.
fn cycles(g: &Graph) -> Vec<Vec<String>> {
    // Tarjan's strongly connected components.
    struct State<'a> {
        g: &'a Graph,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        components: Vec<Vec<&'a str>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let i = s.index.len();
        s.index.insert(v, i);
        s.low.insert(v, i);
        s.stack.push(v);
        s.on_stack.insert(v);
        for w in s.g.get(v).into_iter().flatten() {
            let w = w.as_str();
            if !s.index.contains_key(w) {
                visit(s, w);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if s.on_stack.contains(w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut c = Vec::new();
            loop {
                let w = s.stack.pop().unwrap();
                s.on_stack.remove(w);
                c.push(w);
                if w == v {
                    break;
                }
            }
            s.components.push(c);
        }
    }
    let mut s = State {
        g,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        components: Vec::new(),
    };
    for v in g.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    let mut out: Vec<Vec<String>> = s
        .components
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|c| {
            let members: BTreeSet<&str> = c.into_iter().collect();
            circle_through(g, &members)
        })
        .collect();
    out.sort();
    out
}

/// One circle inside a strongly connected component `members`, from its
/// smallest module: the shortest way back to it (breadth first).
fn circle_through(g: &Graph, members: &BTreeSet<&str>) -> Vec<String> {
    let start = *members.iter().next().unwrap();
    let mut came_from: BTreeMap<&str, &str> = BTreeMap::new();
    let mut queue = std::collections::VecDeque::from([start]);
    while let Some(v) = queue.pop_front() {
        for w in g.get(v).into_iter().flatten() {
            let w = w.as_str();
            if !members.contains(w) {
                continue;
            }
            if w == start {
                // Walk back from `v` to `start`, then turn it round.
                let mut path = vec![v.to_string()];
                let mut at = v;
                while at != start {
                    at = came_from[at];
                    path.push(at.to_string());
                }
                path.reverse();
                path.push(start.to_string());
                return path;
            }
            if !came_from.contains_key(w) {
                came_from.insert(w, v);
                queue.push_back(w);
            }
        }
    }
    unreachable!("a strongly connected component has a circle through each member")
}

fn sources(dir: &Path, prefix: &str, out: &mut Vec<(String, String)>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let stem = path.file_stem().unwrap().to_str().unwrap().to_string();
        if path.is_dir() {
            sources(&path, &format!("{prefix}{stem}::"), out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            if prefix.is_empty() && (stem == "lib" || stem == "main") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            // A file `a/b.rs` is module `a::b`; its `crate::` paths name the
            // top-level modules, which is what the graph is made of.
            let name = if prefix.is_empty() {
                stem
            } else {
                prefix.split("::").next().unwrap().to_string()
            };
            out.push((name, text));
        }
    }
}

#[test]
fn the_report_modules_form_no_circle() {
    let mut src = Vec::new();
    sources(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        "",
        &mut src,
    );
    assert!(
        src.len() >= 20,
        "read only {} modules of the report: is the path right?",
        src.len()
    );
    let g = graph(&src);
    // The graph is not empty: the parser finds the edges that exist.
    assert!(
        g["output"].contains("classes") && g["smaa"].contains("post"),
        "the parser missed known dependencies: {g:?}"
    );
    let found = cycles(&g);
    assert!(
        found.is_empty(),
        "import circles between the report's modules (each from its first module back to it): {}",
        found
            .iter()
            .map(|c| c.join(" → "))
            .collect::<Vec<_>>()
            .join("; ")
    );
}

fn synthetic(files: &[(&str, &str)]) -> Graph {
    let src: Vec<(String, String)> = files
        .iter()
        .map(|(m, t)| (m.to_string(), t.to_string()))
        .collect();
    graph(&src)
}

#[test]
fn the_parser_reads_paths_groups_and_skips_comments() {
    let g = synthetic(&[
        (
            "a",
            "use crate::{b::{X, Y}, c, Row};\nuse super::d::Z;\n\
             // crate::e in a comment\n/// [`e`](crate::e)\nfn f() { subcone_crate::e(); }",
        ),
        ("b", "fn g() -> crate::c::T { todo!() }"),
        ("c", ""),
        ("d", ""),
        ("e", ""),
    ]);
    let names = |m: &str| g[m].iter().cloned().collect::<Vec<_>>();
    assert_eq!(names("a"), ["b", "c", "d"]);
    assert_eq!(names("b"), ["c"]);
    assert!(names("e").is_empty());
}

#[test]
fn the_cycle_finder_finds_every_circle_and_only_circles() {
    // a → b → c → a is a circle; d → a and c → e hang off it; f ↔ g is a
    // second, two-module circle; h → h (a module naming itself) is none.
    let g = synthetic(&[
        ("a", "use crate::b::X;"),
        ("b", "use crate::c;"),
        ("c", "use crate::{a, e};"),
        ("d", "use crate::a;"),
        ("e", ""),
        ("f", "use super::g::Y;"),
        ("g", "use crate::f::Z;"),
        ("h", "use crate::h::W;"),
    ]);
    assert_eq!(
        cycles(&g),
        vec![vec!["a", "b", "c", "a"], vec!["f", "g", "f"]]
    );
    // A layered graph has none.
    let layered = synthetic(&[
        ("top", "use crate::{mid, low};"),
        ("mid", "use crate::low;"),
        ("low", ""),
    ]);
    assert!(cycles(&layered).is_empty());
}
