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

/// A host CTSS field that binds its own `@group(1)` resources: a uniform
/// (a box's half size) and a texture read with `textureLoad`.
const FIELD_WITH_RESOURCES: &str = "\
struct HostBox { half: vec3<f32>, _pad: f32 }
@group(1) @binding(0) var<uniform> host_box: HostBox;
@group(1) @binding(1) var host_albedo: texture_2d<f32>;
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let q = abs(p - vec3<f32>(0.0, 0.0, 4.0)) - host_box.half;
    let d = length(max(q, vec3<f32>(0.0))) + min(max(q.x, max(q.y, q.z)), 0.0);
    return vec3<f32>(d, d, 0.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    let albedo = textureLoad(host_albedo, vec2<i32>(0, 0), 0).xyz;
    return albedo * (0.15 + max(dot(n, vec3<f32>(0.48, 0.8, -0.36)), 0.0));
}
";

/// The host field's shaders, as `subcone shaders --ctss-field` writes them.
fn host_field_files(field: &str) -> Result<Vec<subcone::shaders::OutputFile>, String> {
    let mut s = subcone_passes::standalone::ctss(field, &subcone_passes::CtssPassDesc::default())
        .map_err(|e| e.to_string())?;
    s.variant = "host-texture".into();
    generate(&[s]).map_err(|e| e.to_string())
}

#[test]
fn a_host_fields_own_bindings_reach_every_language_and_the_table() {
    let files = host_field_files(FIELD_WITH_RESOURCES).expect("the field translates");
    let text = |ext: &str| {
        let f = files
            .iter()
            .find(|f| f.path.to_string_lossy().ends_with(ext))
            .unwrap_or_else(|| panic!("no {ext}"));
        String::from_utf8(f.bytes.clone()).unwrap()
    };
    // MSL: the kernel is there, with the host's buffer and texture.
    let msl = text("host-texture.metal");
    assert!(msl.contains("kernel void"), "{msl}");
    assert!(msl.contains("host_box"), "{msl}");
    assert!(msl.contains("host_albedo"), "{msl}");
    // GLSL: the host's block and texture (naga names them by group and
    // binding) have binding numbers of their own, after the pass's.
    let glsl = text("host-texture.comp");
    let line = |name: &str| {
        glsl.lines()
            .find(|l| l.contains(name) && l.contains("layout"))
            .unwrap_or_else(|| panic!("no layout line for {name}:\n{glsl}"))
            .to_string()
    };
    for name in ["_group_1_binding_0", "_group_1_binding_1"] {
        assert!(line(name).contains("binding = "), "{}", line(name));
    }
    let numbers: Vec<&str> = glsl
        .lines()
        .filter_map(|l| l.split("binding = ").nth(1))
        .map(|r| r.split(|c: char| !c.is_ascii_digit()).next().unwrap())
        .collect();
    let mut unique = numbers.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(
        unique.len(),
        numbers.len(),
        "GLSL bindings collide: {numbers:?}"
    );
    // The tables list the host's group-1 bindings with their types.
    let json = text("ctss.json");
    for needle in ["\"host_box\"", "\"host_albedo\"", "texture_2d<f32>"] {
        assert!(json.contains(needle), "{needle} not in {json}");
    }
    let md = text("ctss.md");
    assert!(md.contains("host_albedo"), "{md}");
    validate_with_tools(&files);
}

/// The host field's SPIR-V through `spirv-val` (Vulkan 1.0) and its GLSL
/// and HLSL through `glslangValidator`, where the tools are installed (CI
/// installs them; elsewhere a `skipped:` line says they are not).
fn validate_with_tools(files: &[subcone::shaders::OutputFile]) {
    let have = |tool: &str| {
        std::process::Command::new(tool)
            .arg("--version")
            .output()
            .is_ok()
    };
    if !have("spirv-val") || !have("glslangValidator") {
        assert!(
            std::env::var_os("CI").is_none(),
            "spirv-val and glslangValidator are required in CI"
        );
        println!("skipped: spirv-val or glslangValidator not installed");
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    write(dir.path(), files).expect("write");
    let ctss = dir.path().join("ctss");
    let run = |args: &[&str]| {
        let out = std::process::Command::new(args[0])
            .args(&args[1..])
            .current_dir(&ctss)
            .output()
            .expect("run the tool");
        assert!(
            out.status.success(),
            "{args:?}: {}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run(&["spirv-val", "--target-env", "vulkan1.0", "host-texture.spv"]);
    run(&[
        "glslangValidator",
        "-V",
        "host-texture.comp",
        "-o",
        "glsl.spv",
    ]);
    run(&[
        "glslangValidator",
        "-V",
        "host-texture.es.comp",
        "-o",
        "es.spv",
    ]);
    run(&[
        "glslangValidator",
        "-D",
        "-V",
        "-S",
        "comp",
        "-e",
        "subcone_pass_ctss_main",
        "host-texture.hlsl",
        "-o",
        "hlsl.spv",
    ]);
    run(&["spirv-val", "--target-env", "vulkan1.0", "hlsl.spv"]);
}

#[test]
fn a_host_field_resource_no_language_can_bind_is_refused_by_name() {
    let sampled = FIELD_WITH_RESOURCES.replace(
        "fn subcone_field",
        "@group(1) @binding(2) var host_sampler: sampler;\nfn subcone_field",
    );
    let e = host_field_files(&sampled).expect_err("a sampler has no table row");
    assert!(e.contains("host_sampler") && e.contains("a sampler"), "{e}");
}
