//! SDF scene files: every built-in written and read back is the same scene;
//! every class of bad input is an error that names where it is, never a panic
//! and never part of a scene.

use subcone_load::file::{parse_sdf_scene, write_sdf_scene, SdfFileError, MAX_NESTING};
use subcone_scene::builtin::{sdf_builtin, SDF_SCENES, STIFF_SCENES, TRANSPARENT_SCENES};
use subcone_scene::sdf::MAX_DEPTH;

fn builtins() -> impl Iterator<Item = &'static str> {
    SDF_SCENES
        .into_iter()
        .chain(STIFF_SCENES)
        .chain(TRANSPARENT_SCENES)
}

/// `Debug` prints every field of every node (bounds, cached inverses, scatter
/// tables), floats in their shortest exact form: equal text, equal bits.
#[test]
fn every_builtin_reads_back_as_the_same_scene() {
    for name in builtins() {
        let scene = sdf_builtin(name).unwrap().unwrap();
        let text = write_sdf_scene(&scene).unwrap();
        let again = parse_sdf_scene(&text, &format!("{name}.sdf.ron"))
            .unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        assert_eq!(format!("{again:?}"), format!("{scene:?}"), "{name}");
        // And writing is deterministic.
        assert_eq!(write_sdf_scene(&again).unwrap(), text, "{name}");
    }
}

#[test]
fn the_example_scenes_load() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let scene = subcone_load::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(scene.sdf_geometry().is_some(), "{}", path.display());
        n += 1;
    }
    assert!(n >= 2, "examples/scenes holds {n} files");
}

/// A small valid scene; each case below breaks one thing in it.
const BASE: &str = r#"SdfScene(
    camera: (position: (0, 1, -5), target: (0, 1, 0)),
    materials: [
        (name: "floor"),
        (name: "ball", albedo: Solid((0.8, 0.2, 0.1)), alpha: 1),
    ],
    lights: [Directional(direction: (0, 1, 0), irradiance: (1, 1, 1))],
    root: Union([
        Plane(normal: (0, 1, 0)),
        Transform(
            translate: (0, 1, 0),
            child: Sphere(radius: 1, material: 1),
        ),
    ]),
)
"#;

fn broken(from: &str, to: &str) -> SdfFileError {
    assert!(BASE.contains(from), "{from}");
    let text = BASE.replacen(from, to, 1);
    match parse_sdf_scene(&text, "case.sdf.ron") {
        Ok(_) => panic!("accepted {to:?}"),
        Err(e) => e,
    }
}

/// `e` says `what`, at `path`, on `line` when given.
fn check(e: &SdfFileError, line: Option<usize>, path: &str, what: &str) {
    let text = e.to_string();
    assert!(text.starts_with("case.sdf.ron"), "{text}");
    assert_eq!(e.path, path, "{text}");
    assert!(text.contains(what), "{text} does not say {what:?}");
    if let Some(line) = line {
        assert_eq!(e.position.map(|p| p.0), Some(line), "{text}");
        assert!(text.starts_with(&format!("case.sdf.ron:{line}:")), "{text}");
    }
}

#[test]
fn the_base_scene_is_valid() {
    let s = parse_sdf_scene(BASE, "case.sdf.ron").unwrap();
    assert_eq!(s.name, "case");
    assert_eq!(s.materials.len(), 2);
}

const SPHERE: &str = "root.Union[1].Transform.child";

#[test]
fn nan_is_refused_where_it_is() {
    let e = broken("radius: 1,", "radius: NaN,");
    check(&e, Some(12), SPHERE, "sphere: radius must be finite");
    let e = broken("translate: (0, 1, 0)", "translate: (0, inf, 0)");
    check(&e, Some(13), "root.Union[1]", "translation must be finite");
    let e = broken("(0.8, 0.2, 0.1)", "(0.8, NaN, 0.1)");
    check(&e, None, "materials[1]", "albedo");
}

#[test]
fn negative_sizes_are_refused_where_they_are() {
    let e = broken("radius: 1,", "radius: -1,");
    check(&e, Some(12), SPHERE, "must not be negative, got -1");
    let e = broken(
        "Plane(normal: (0, 1, 0))",
        "Box(half: (1, -2, 1)), Plane(normal: (0, 1, 0))",
    );
    check(
        &e,
        Some(9),
        "root.Union[0]",
        "box: half extents must not be negative",
    );
}

#[test]
fn unknown_names_are_refused_where_they_are() {
    let e = broken("child: Sphere(", "child: Spher(");
    check(&e, Some(12), SPHERE, "Unexpected variant named `Spher`");
    let e = broken("radius: 1,", "radus: 1,");
    check(
        &e,
        Some(12),
        &format!("{SPHERE}.Sphere.radus"),
        "Unexpected field named `radus`",
    );
    let e = broken("lights:", "lamps:");
    check(&e, Some(7), "lamps", "Unexpected field named `lamps`");
    let e = broken("Solid(", "Marble(");
    check(
        &e,
        Some(5),
        "materials[1].albedo",
        "Unexpected variant named `Marble`",
    );
    // A material index past the list is named by the object that uses it.
    let e = broken("material: 1)", "material: 7)");
    check(
        &e,
        None,
        &format!("{SPHERE}.Sphere.material"),
        "material index 7 is out of range: the scene has 2 materials",
    );
}

#[test]
fn wrong_types_are_refused_where_they_are() {
    let e = broken("radius: 1,", "radius: \"one\",");
    check(
        &e,
        Some(12),
        &format!("{SPHERE}.Sphere.radius"),
        "Expected float",
    );
    let e = broken("material: 1)", "material: -1)");
    check(&e, Some(12), &format!("{SPHERE}.Sphere.material"), "");
    let e = broken("translate: (0, 1, 0)", "translate: (0, 1)");
    check(&e, Some(11), "root.Union[1].Transform.translate", "");
    let e = broken("Union([", "Union((");
    check(&e, Some(8), "root.Union", "");
    // A required field left out.
    let e = broken("Sphere(radius: 1, material: 1)", "Sphere(material: 1)");
    check(
        &e,
        Some(12),
        &format!("{SPHERE}.Sphere"),
        "missing field named `radius`",
    );
}

#[test]
fn absurd_nesting_is_refused_without_exhausting_the_stack() {
    // Deeper than the tree allows: the constructor's limit, at the node.
    let mut deep = String::from("Sphere(radius: 1)");
    for _ in 0..MAX_DEPTH + 4 {
        deep = format!("Round(radius: 0, child: {deep})");
    }
    let e = broken("Plane(normal: (0, 1, 0))", &deep);
    // The Round that would be level 65 has four more around it.
    let path = format!("root.Union[0]{}", ".Round.child".repeat(4));
    check(
        &e,
        Some(9),
        &path,
        "round: the tree would be deeper than 64 levels",
    );
    // Deeper than any tree: refused before it is read.
    let n = 100_000;
    let absurd = "Transform(child: ".repeat(n) + "Sphere(radius: 1)" + &")".repeat(n);
    let e = broken("Plane(normal: (0, 1, 0))", &absurd);
    check(
        &e,
        Some(9),
        "",
        &format!("nested deeper than {MAX_NESTING} brackets"),
    );
}

#[test]
fn scene_level_errors_name_their_field() {
    let e = broken("target: (0, 1, 0)", "target: (0, 1, -5)");
    check(&e, None, "camera", "target equals position");
    let e = broken("target: (0, 1, 0)", "target: (0, 1, 0), fov_degrees: 180");
    check(&e, None, "camera", "field of view");
    let e = broken("alpha: 1", "alpha: 2");
    check(&e, None, "materials[1]", "alpha 2 must be in [0, 1]");
    let e = broken("direction: (0, 1, 0)", "direction: (0, 0, 0)");
    check(&e, None, "lights[0]", "direction has no length");
    let e = broken("root:", "max_steps: 0, root:");
    check(&e, None, "max_steps", "step budget is zero");
    let e = broken("root:", "max_distance: -1, root:");
    check(&e, None, "max_distance", "max distance -1");
    let e = broken("root:", "version: 2, root:");
    check(&e, None, "version", "format version 2");
    let e = broken("camera: (position: (0, 1, -5), target: (0, 1, 0)),", "");
    check(&e, None, "", "missing field named `camera`");
    let e = broken(
        "translate: (0, 1, 0),",
        "translate: (0, 1, 0), rotate: Quat(0, 0, 0, 0),",
    );
    check(&e, Some(13), "root.Union[1]", "zero length");
}

#[test]
fn trailing_text_and_garbage_are_refused() {
    let e = parse_sdf_scene(&format!("{BASE} extra"), "case.sdf.ron").unwrap_err();
    assert!(e.position.is_some(), "{e}");
    for text in [
        "",
        "(",
        "SdfScene(",
        "\u{0}",
        "[[[",
        "SdfScene(camera: 3)",
        "// only",
    ] {
        let e = parse_sdf_scene(text, "case.sdf.ron").unwrap_err();
        assert!(e.to_string().starts_with("case.sdf.ron"), "{e}");
    }
}

#[test]
fn every_node_of_the_format_builds() {
    // One of each node kind the format has, valid, in one tree.
    let text = r#"SdfScene(
        camera: (position: (0, 2, -9), forward: (0, 0, 1), fov_radians: 0.8),
        materials: [(), (albedo: Patches(palette: [(1, 0, 0), (0, 1, 0)], size: 0.5), mirror: 0.5, emission: (0.1, 0, 0))],
        root: Union([
            Sphere(radius: 0.5), Box(half: (0.5, 0.5, 0.5)), RoundBox(half: (0.5, 0.5, 0.5), radius: 0.1),
            BoxFrame(half: (0.5, 0.5, 0.5), thickness: 0.05), Torus(major: 0.4, minor: 0.1),
            Link(half_length: 0.2, major: 0.3, minor: 0.1), Capsule(half_height: 0.3, radius: 0.2),
            Cylinder(radius: 0.3, half_height: 0.4), RoundedCylinder(radius: 0.3, half_height: 0.4, rounding: 0.1),
            CappedCone(half_height: 0.4, bottom: 0.4, top: 0.1), Octahedron(size: 0.5),
            HexPrism(apothem: 0.3, half_height: 0.4), Ellipsoid(radii: (0.5, 0.3, 0.2)),
            Plane(normal: (0, 2, 0), offset: 3),
            Intersection([Sphere(radius: 1), Box(half: (0.8, 0.8, 0.8))]),
            SmoothUnion(k: 0.2, children: [Sphere(radius: 0.5), Transform(translate: (0.6, 0, 0), child: Sphere(radius: 0.4))]),
            Subtract(from: Box(half: (1, 1, 1)), remove: Sphere(radius: 1.2, material: 1)),
            Transform(translate: (1, 2, 3), rotate: AxisAngle(axis: (0, 0, 2), degrees: 30), scale: 2, child: Sphere(radius: 0.1)),
            Mirror(axes: [X, Z], child: Transform(translate: (2, 0, 2), child: Sphere(radius: 0.5))),
            Repeat(period: (2, 0, 2), child: Sphere(radius: 0.5)),
            Repeat(period: (2, 0, 2), lo: (-2, 0, -2), hi: (2, 0, 2), child: Sphere(radius: 0.5)),
            Round(radius: 0.1, child: Box(half: (0.2, 0.2, 0.2))),
            Onion(thickness: 0.05, child: Sphere(radius: 0.5)),
            ScaleDistance(factor: 0.5, child: Sphere(radius: 0.5)),
            Displace(amplitude: 0.05, frequency: 4, child: Sphere(radius: 0.5)),
            Bounded(pad: 0.5, child: Sphere(radius: 0.5)),
            Scatter(cell: (1, 1, 1), lo: (0, 0, 0), hi: (3, 0, 3), seed: 7, fill: 0.7, palette: [0, 1],
                    templates: [Sphere(radius: 1), Box(half: (1, 1, 1))]),
            Material(index: 1, child: Union([Sphere(radius: 0.3), Box(half: (0.2, 0.2, 0.2))])),
        ]),
    )"#;
    let s = parse_sdf_scene(text, "all.sdf.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.name, "all");
    assert_eq!(s.root.materials_used(), vec![0, 1]);
    // And it survives a round trip too.
    let again = parse_sdf_scene(&write_sdf_scene(&s).unwrap(), "all.sdf.ron").unwrap();
    assert_eq!(format!("{again:?}"), format!("{s:?}"));
}
