//! The committed `shaders/` is what `subcone shaders` writes: every pass's
//! SPIR-V, HLSL, GLSL, MSL and resource table regenerated from the passes'
//! WGSL and compared byte for byte, so a change to a pass or a kernel that
//! leaves a stale file fails here (and in CI's `subcone shaders --check`).

use std::path::Path;

use subcone::shaders::{generate, stale, write, GENERATED};
use subcone_passes::standalone::catalog;

#[test]
fn committed_shaders_are_up_to_date() {
    let files = generate(&catalog().expect("catalog")).expect("every pass translates");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let problems = stale(&dir, &files);
    assert!(
        problems.is_empty(),
        "shaders/ is stale; regenerate with `cargo run --release -- shaders --out shaders`:\n  {}",
        problems.join("\n  ")
    );
}

#[test]
fn a_stale_missing_or_extra_file_is_reported() {
    let files = generate(&catalog().expect("catalog")).expect("every pass translates");
    let dir = tempfile::tempdir().expect("temp dir");
    write(dir.path(), &files).expect("write");
    assert!(stale(dir.path(), &files).is_empty());
    let changed = &files[1].path;
    std::fs::write(dir.path().join(changed), b"stale").expect("overwrite");
    std::fs::remove_file(dir.path().join(&files[2].path)).expect("remove");
    std::fs::write(dir.path().join("sraa/old.spv"), b"").expect("extra");
    let problems = stale(dir.path(), &files);
    assert_eq!(problems.len(), 3, "{problems:?}");
    assert!(problems.iter().any(|p| p.ends_with("differs")));
    assert!(problems.iter().any(|p| p.ends_with("is missing")));
    assert!(problems
        .iter()
        .any(|p| p.contains("old.spv is not generated")));
}

#[test]
fn every_pass_has_four_languages_and_a_table() {
    let shaders = catalog().expect("catalog");
    let files = generate(&shaders).expect("every pass translates");
    let has = |p: &str| files.iter().any(|f| f.path == Path::new(p));
    for s in &shaders {
        for ext in ["wgsl", "spv", "hlsl", "comp", "es.comp", "metal"] {
            let p = format!("{}/{}.{ext}", s.pass, s.variant);
            assert!(has(&p), "{p} is not written");
        }
    }
    for pass in ["sraa", "ctss", "fxaa", "taa"] {
        assert!(has(&format!("{pass}.json")) && has(&format!("{pass}.md")));
        let json: serde_json::Value = serde_json::from_slice(
            &files
                .iter()
                .find(|f| f.path == Path::new(&format!("{pass}.json")))
                .expect("table")
                .bytes,
        )
        .expect("valid JSON");
        for v in json["variants"].as_array().expect("variants") {
            assert_eq!(v["workgroup_size"], serde_json::json!([8, 8, 1]));
            let bindings = v["bindings"].as_array().expect("bindings");
            assert!(!bindings.is_empty());
            // Every uniform's struct is laid out, member by member.
            for b in bindings.iter().filter(|b| b["kind"] == "uniform buffer") {
                let members = b["layout"]["members"].as_array().expect("uniform layout");
                assert!(!members.is_empty(), "{pass}: {} has no members", b["name"]);
            }
        }
    }
    // SPIR-V starts with its magic number.
    let spv = files
        .iter()
        .find(|f| f.path.extension().is_some_and(|e| e == "spv"));
    assert_eq!(
        spv.expect("a .spv").bytes[..4],
        0x0723_0203u32.to_le_bytes()
    );
}

/// The table's `_mslBufferSizes` members are the ones, in the order, of
/// the struct the MSL declares (naga orders them by global, not binding).
#[test]
fn msl_buffer_sizes_are_listed_as_the_msl_declares_them() {
    let shaders = catalog().expect("catalog");
    let files = generate(&shaders).expect("every pass translates");
    let file = |p: String| {
        let f = files.iter().find(|f| f.path == Path::new(&p)).expect(&p);
        String::from_utf8(f.bytes.clone()).expect("text")
    };
    let mut checked = 0;
    for pass in ["sraa", "ctss", "fxaa", "taa"] {
        let json: serde_json::Value =
            serde_json::from_str(&file(format!("{pass}.json"))).expect("valid JSON");
        for v in json["variants"].as_array().expect("variants") {
            let metal = file(format!(
                "{pass}/{}.metal",
                v["variant"].as_str().expect("name")
            ));
            let declared: Vec<String> = match metal.split_once("struct _mslBufferSizes {") {
                Some((_, rest)) => rest
                    .split_once("};")
                    .expect("struct end")
                    .0
                    .split(';')
                    .filter_map(|m| m.trim().strip_prefix("uint ").map(str::to_owned))
                    .collect(),
                None => Vec::new(),
            };
            let listed: Vec<String> = v["msl_buffer_sizes"]["members"]
                .as_array()
                .into_iter()
                .flatten()
                .map(|m| m["member"].as_str().expect("member").to_owned())
                .collect();
            assert_eq!(listed, declared, "{pass}/{}", v["variant"]);
            checked += usize::from(!declared.is_empty());
        }
    }
    assert!(checked >= 3, "only {checked} variants declare buffer sizes");
}

/// Every text file says on its first line, in its own comment syntax, that
/// it is generated (GLSL on its second, after `#version`, which GLSL ES
/// wants first); JSON (no comments) and SPIR-V (binary) are written as
/// they are.
#[test]
fn every_text_file_says_it_is_generated() {
    let files = generate(&catalog().expect("catalog")).expect("every pass translates");
    let mut marked = 0;
    for f in &files {
        let name = f.path.display().to_string();
        let ext = f.path.extension().and_then(|e| e.to_str()).unwrap_or("");
        let text = || String::from_utf8(f.bytes.clone()).expect("text");
        match ext {
            "wgsl" | "hlsl" | "metal" => {
                assert_eq!(
                    text().lines().next(),
                    Some(&*format!("// {GENERATED}")),
                    "{name}"
                );
            }
            "md" => {
                let expected = format!("<!-- {GENERATED} -->");
                assert_eq!(text().lines().next(), Some(&*expected), "{name}");
            }
            "comp" => {
                let text = text();
                let mut lines = text.lines();
                assert!(
                    lines.next().is_some_and(|l| l.starts_with("#version ")),
                    "{name}"
                );
                assert_eq!(lines.next(), Some(&*format!("// {GENERATED}")), "{name}");
            }
            "json" | "spv" => {
                let head = &f.bytes[..f.bytes.len().min(200)];
                assert!(!String::from_utf8_lossy(head).contains(GENERATED), "{name}");
                continue;
            }
            other => panic!("{name}: no header rule for .{other}"),
        }
        marked += 1;
    }
    assert_eq!(
        marked,
        files
            .iter()
            .filter(|f| !f
                .path
                .extension()
                .is_some_and(|e| e == "json" || e == "spv"))
            .count()
    );
}
