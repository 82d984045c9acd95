//! The `capi` fuzz target (`fuzz/fuzz_targets/capi.rs`) calls every function
//! this crate exports: a function added to `src/` without a call there
//! fails this test.

use std::collections::BTreeSet;
use std::path::Path;

/// The names of the `#[no_mangle]` functions of `src`: the symbols a C host
/// links against.
fn exported_functions(src: &str) -> BTreeSet<String> {
    let lines: Vec<&str> = src.lines().map(str::trim).collect();
    let mut names = BTreeSet::new();
    for (i, line) in lines.iter().enumerate() {
        if !line.starts_with("#[") || !line.contains("no_mangle") {
            continue;
        }
        // The item follows its attributes.
        let item = lines[i + 1..]
            .iter()
            .find(|l| !l.starts_with("#["))
            .unwrap_or_else(|| panic!("no item after the attribute on line {}", i + 1));
        let name = item
            .split_once("fn ")
            .map(|(_, rest)| rest)
            .and_then(|rest| rest.split(['(', '<']).next())
            .unwrap_or_else(|| panic!("`{item}` (line {}) is not a function", i + 2));
        names.insert(name.trim().to_string());
    }
    names
}

/// `src` without its `//` comments, so a name that is only mentioned does
/// not count as called.
fn code_only(src: &str) -> String {
    src.lines()
        .map(|l| l.split_once("//").map_or(l, |(code, _)| code))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_fuzz_target_calls_every_exported_function() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    // `lib.rs` and its modules.
    let mut files: Vec<_> = std::fs::read_dir(crate_dir.join("src"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    let lib = files
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect::<Vec<_>>()
        .join("\n");
    let exported = exported_functions(&lib);
    // They are the functions the header declares (the header is current:
    // `tests/header.rs`), so the list cannot come up short.
    let header = std::fs::read_to_string(crate_dir.join("include/subcone.h")).unwrap();
    let declarations = header
        .lines()
        .filter(|l| {
            !["//", "/*", "*"]
                .iter()
                .any(|c| l.trim_start().starts_with(c))
        })
        .collect::<Vec<_>>()
        .join("\n");
    let declared: BTreeSet<String> = declarations
        .match_indices("subcone_")
        .filter_map(|(i, _)| {
            let rest = &declarations[i..];
            let end = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            rest[end..]
                .starts_with('(')
                .then(|| rest[..end].to_string())
        })
        .collect();
    assert_eq!(
        exported, declared,
        "src/'s #[no_mangle] functions and include/subcone.h's declarations differ"
    );
    assert!(exported.contains("subcone_ctss_trace"), "{exported:?}");

    let target_path = crate_dir.join("../fuzz/fuzz_targets/capi.rs");
    let target = code_only(&std::fs::read_to_string(&target_path).unwrap());
    let missing: Vec<&String> = exported
        .iter()
        .filter(|name| !target.contains(&format!("{name}(")))
        .collect();
    assert!(
        missing.is_empty(),
        "the capi fuzz target ({}) does not call {missing:?}: add a `Call` variant for each",
        target_path.display()
    );
}

#[test]
fn exported_functions_are_read_from_their_attributes() {
    let src = "#[no_mangle]\npub extern \"C\" fn subcone_a() -> u32 {}\n\
               /// doc\n#[no_mangle]\n#[allow(x)]\npub unsafe extern \"C\" fn subcone_b(x: u32) {}\n\
               pub fn subcone_not_exported() {}\n\
               pub type F = Option<extern \"C\" fn(u32)>;\n";
    let names: Vec<String> = exported_functions(src).into_iter().collect();
    assert_eq!(names, ["subcone_a", "subcone_b"]);
    assert!(!code_only("// subcone_a(\nx").contains("subcone_a("));
}
