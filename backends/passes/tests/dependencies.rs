//! What a host links: `subcone-passes` depends on the kernels, wgpu,
//! bytemuck and glam, and nothing else (no scene crate, BVH, image loaders
//! or executor). `cargo tree -p subcone-passes -e normal` shows the graph;
//! this test pins the manifest's `[dependencies]` table.

#[test]
fn the_pass_crate_depends_only_on_the_kernels_and_wgpu() {
    let manifest = include_str!("../Cargo.toml");
    let mut in_deps = false;
    let mut deps = Vec::new();
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_deps = line == "[dependencies]";
            continue;
        }
        if in_deps && !line.is_empty() && !line.starts_with('#') {
            let name = line.split(['=', '.']).next().unwrap_or("").trim();
            deps.push(name.to_string());
        }
    }
    deps.sort();
    assert_eq!(deps, ["bytemuck", "glam", "subcone-kernels", "wgpu"]);
    for forbidden in ["[target", "[build-dependencies]"] {
        assert!(
            !manifest.contains(forbidden),
            "the manifest has {forbidden}"
        );
    }
}
