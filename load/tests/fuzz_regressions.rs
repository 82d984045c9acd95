//! Inputs the `obj_loader`, `gltf_loader` and `sdf_builder` fuzz targets
//! (`fuzz/`) failed on, fixed in the scene crate; the raw inputs are in
//! `fuzz/regressions/TARGET/`.

use std::path::Path;

use glam::Vec3;
use subcone_load::{load_mesh_bytes, load_mesh_file, load_scene_bytes};
use subcone_scene::sdf::{SdfError, SdfNode};

fn assert_unit(n: Vec3, what: &str) {
    assert!(
        n.is_finite() && (n.length() - 1.0).abs() < 1e-6,
        "{what}: {n} (length {})",
        n.length()
    );
}

/// `normal` of a capped cone at a point 1.2·10⁻¹³ from the origin: the step
/// is ~10⁻¹⁹, the differences' squares subnormal, and `n / |n|` came out at
/// length 0.9993.
#[test]
fn sdf_normal_of_tiny_differences_is_unit() {
    let cone = SdfNode::capped_cone(f32::MIN_POSITIVE, 767.0 / 256.0, 5.9e-44).unwrap();
    let p = Vec3::new(1.199_284_7e-13, 0.0, 0.0);
    for h in [0.0, 1e-30, f32::MIN_POSITIVE] {
        assert_unit(cone.normal(p, h), "normal");
        assert_unit(cone.normal_central(p, h), "normal_central");
        assert_unit(cone.normal_surface(p, h), "normal_surface");
    }
}

/// A flat, wide capped cone (half height 1/256, radii 10⁻³⁰ and 87): the
/// projection onto its slanted side is nearly vertical, and Quilez's sign
/// test (`cb.x < 0`) rounded to "outside" on the axis, so the field jumped
/// from `−h` to `+h` there and the tree stopped being 1-Lipschitz. The side
/// is now tested by a cross product.
#[test]
fn flat_wide_capped_cone_is_inside_on_its_axis() {
    let (h, r1, r2) = (1.0 / 256.0, 1e-30, 22359.0 / 256.0);
    for cone in [
        SdfNode::capped_cone(h, r1, r2).unwrap(),
        SdfNode::capped_cone(h, r2, r1).unwrap(),
    ] {
        let d0 = cone.eval(Vec3::ZERO).0;
        assert!((d0 + h).abs() < 1e-6, "f(0) = {d0}, want {}", -h);
        let q = Vec3::new(0.001, -0.0005, 0.00025);
        let dq = cone.eval(q).0;
        assert!(
            (d0 - dq).abs() <= q.length() * 1.0001,
            "f(0) = {d0}, f({q}) = {dq}"
        );
        // Far outside radially, and above the top, stays outside.
        assert!(cone.eval(Vec3::new(200.0, 0.0, 0.0)).0 > 0.0);
        assert!(cone.eval(Vec3::new(0.0, 2.0 * h, 0.0)).0 > 0.0);
    }
}

/// A central difference that is NaN along `y` only (the point at
/// `y = f32::MAX` steps to `∞`, and the plane's `0 · ∞` is NaN): the
/// largest-component scale skipped the NaN and the normal came out NaN; it
/// must fall back to `+y`.
#[test]
fn sdf_normal_with_a_nan_difference_falls_back() {
    let plane = SdfNode::plane(Vec3::new(3.003_921_5, 0.0, 7.344_15e-40), -2.007_134_3e38).unwrap();
    let p = Vec3::new(1e-30, f32::MAX, 0.0);
    for h in [0.0, 1.0, f32::MAX] {
        assert_unit(plane.normal(p, h), "normal");
        assert_unit(plane.normal_central(p, h), "normal_central");
        assert_unit(plane.normal_surface(p, h), "normal_surface");
    }
}

/// A rotation quaternion with a component of 10³⁰: its squared length
/// overflowed f32, "normalising" it gave the zero quaternion, and the rotated
/// sphere evaluated to `−radius` everywhere inside a zero bounding box.
#[test]
fn huge_rotation_quaternions_are_normalised() {
    let r = 22873.0 / 256.0;
    let q = glam::Quat::from_xyzw(3.2052e-41, 1e30, r, 0.348);
    let ball = SdfNode::sphere(r).unwrap().rotate(q).unwrap();
    let p = Vec3::new(r, 0.0, 0.5);
    let d = ball.distance(p);
    let expect = p.length() - r;
    assert!((d - expect).abs() < 1e-3, "{d} vs {expect}");
    let b = ball.bounds();
    assert!(b.min.x <= -r && b.max.x >= r, "{b:?}");
    // The same rotation given at unit scale agrees.
    let unit = SdfNode::sphere(r)
        .unwrap()
        .rotate(glam::Quat::from_xyzw(0.0, 1.0, 0.0, 0.0))
        .unwrap();
    assert!((unit.distance(p) - d).abs() < 1e-3);
}

/// A smooth union of n children lowers the field by up to `k/4` per child
/// after the first (the `smin` is applied child by child), but its bounding
/// box grew by `k/4` only: with four equal spheres a point outside the box
/// was inside the surface (and unions above could skip the node there).
#[test]
fn smooth_union_bounds_cover_every_child_step() {
    let k = 4.0;
    let ball = SdfNode::sphere(1.0).unwrap();
    let blend =
        SdfNode::smooth_union(k, vec![ball.clone(), ball.clone(), ball.clone(), ball]).unwrap();
    let p = Vec3::new(0.0, 0.0, 2.5);
    let d = blend.distance(p);
    // Below the surface (the first blend step alone leaves 0.5), no lower
    // than three full steps.
    assert!(d < -0.4 && d >= 1.5 - 3.0 * 0.25 * k, "{d}");
    let b = blend.bounds();
    assert!(
        b.distance(p) == 0.0,
        "{p} is inside the surface (f = {d}) but outside {b:?}"
    );
    // Outside the box the field is positive, on a ray out to 10.
    for i in 0..100 {
        let q = Vec3::new(0.0, 0.0, 0.1 * i as f32);
        if b.distance(q) > 0.0 {
            assert!(blend.distance(q) > 0.0, "{q}");
        }
    }
}

/// `regressions/sdf_builder/crash-d218cc93…`: an onion over a scaled,
/// guarded `RepeatLimited` (cells of 10⁻³⁰) of a displaced octahedron
/// evaluated to −35.14 at (99.39, 1, 0), 64.25 outside the node's bounds.
/// The repetition's value there is its cap `wall + margin` (≈ 6·10⁻¹⁸ after
/// the scale, the point lies near a cell wall's plane), a step bound and not
/// a distance; the onion's `|d| − 35.14` read it as inside the shell. An
/// onion thicker than the repetition's margin grows every instance across
/// its cell walls, which one-cell evaluation cannot represent: such a tree
/// is now refused, as a repetition of a child that does not fit its cell is.
#[test]
fn onion_over_a_guarded_repetition_stays_inside_its_bounds() {
    let octahedron = SdfNode::octahedron(2.196_135_6e-38).unwrap();
    let pair = SdfNode::union(vec![octahedron.clone(), octahedron]).unwrap();
    let displaced = pair.displace(8.784_619e-38, 0.0).unwrap();
    let child = SdfNode::union(vec![displaced.clone(), displaced]).unwrap();
    let cells = child
        .repeat_limited(
            Vec3::new(-0.0, 1e-30, 1e-30),
            [-1_313_754_703, -1_313_754_703, 598_847_921],
            [0, -714_906_880, 1_667_457_891],
        )
        .unwrap();
    let s = 25443.0 / 256.0;
    let scaled = cells.scale(s).unwrap().scale(s).unwrap();
    let p = Vec3::new(s, 1.0, 0.0);
    match scaled.onion(8995.0 / 256.0) {
        Ok(shell) => {
            let outside = shell.bounds().distance(p);
            let d = shell.distance(p);
            assert!(
                outside <= 0.0 || d >= 0.0,
                "{p} is {outside} outside the bounds {:?} but eval = {d}",
                shell.bounds()
            );
        }
        Err(e) => assert!(matches!(e, SdfError::Overlap { .. }), "{e}"),
    }
}

/// A file normal of `(10³⁰, 0, 0)`: its squared length overflowed and
/// `sanitize` normalised it to zero.
#[test]
fn huge_file_normals_stay_unit() {
    let obj =
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 1e30 0 0\nvn 0 -3e38 0\nvn 0 0 1e-5\nf 1//1 2//2 3//3\n";
    let (mesh, _, dropped) = load_mesh_bytes(Path::new("n.obj"), obj).unwrap();
    assert!(!dropped.any(), "{dropped:?}");
    let n = mesh.normals[0];
    assert_eq!(n[0], Vec3::X);
    assert_eq!(n[1], Vec3::NEG_Y);
    assert_eq!(n[2], Vec3::Z);
}

/// A triangle whose squared doubled area `|e₁ × e₂|²` is subnormal (edges of
/// 10⁻¹⁰): the relative test's `edge⁴` underflowed to 0 and kept it, and the
/// renderers' barycentrics (`… / max(|e₁ × e₂|², f32::MIN_POSITIVE)`) came
/// out 100× too small. Also the glTF input of `regressions/gltf_loader/`,
/// whose coordinates are subnormal.
#[test]
fn triangles_with_subnormal_area_are_dropped() {
    let obj = b"v 0 0 0\nv 1e-10 0 0\nv 0 1e-10 0\nv 1e-9 0 0\nv 0 1e-9 0\nf 1 2 3\nf 1 4 5\n";
    let (mesh, _, dropped) = load_mesh_bytes(Path::new("tiny.obj"), obj).unwrap();
    assert_eq!((mesh.len(), dropped.degenerate), (1, 1));
    assert_eq!(mesh.positions[0][1], Vec3::new(1e-9, 0.0, 0.0));
    assert_eq!(mesh.normals[0][0], Vec3::Z);
    let sub = b"v 0 0 5.831554e-39\nv 0 0 0\nv 5.831554e-39 0 0\nf 1 2 3\n";
    assert!(matches!(
        load_mesh_bytes(Path::new("sub.obj"), sub),
        Err(subcone_scene::SceneError::Empty { .. })
    ));
}

/// An MTL colour with two components (`Kd 0.8 0`): `tobj` panicked (the
/// loader caught it and failed the whole file). One component means grey.
#[test]
fn short_mtl_colours_do_not_panic() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n";
    std::fs::write(
        dir.path().join("m.mtl"),
        "newmtl a\nKd 0.8 0\nKe\nnewmtl b\nKd 0.25\nKs 1 2\n",
    )
    .unwrap();
    let (_, materials, _) = load_mesh_bytes(&dir.path().join("t.obj"), obj.as_bytes()).unwrap();
    let albedo = |name: &str| {
        let m = materials.iter().find(|m| m.name == name).unwrap();
        m.albedo_at(Vec3::ZERO, glam::Vec2::ZERO)
    };
    assert_eq!(albedo("a"), subcone_load::DEFAULT_ALBEDO);
    assert_eq!(albedo("b"), Vec3::splat(0.25));
}

/// Face indices `tobj` multiplies or offsets unchecked: huge ones overflowed
/// (a panic with overflow checks, as in tests), as did relative ones reaching
/// before the first vertex and index 0.
#[test]
fn out_of_range_face_indices_are_errors() {
    let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    for face in [
        "f 1/9223372036854775807 2 3",
        "f 1 2 9223372036854775807",
        "f 1//4611686018427387904 2 3",
        "f -4 -2 -1",
        "f 1/-2 2 3",
        "f 0 1 2",
        "l 1 99999",
    ] {
        let obj = format!("{head}{face}\n");
        match load_mesh_bytes(Path::new("i.obj"), obj.as_bytes()) {
            Err(subcone_scene::SceneError::Load { reason, .. }) => {
                assert!(reason.contains("out of range"), "{face}: {reason}")
            }
            other => panic!("{face}: {other:?}"),
        }
    }
    // Valid relative and absolute indices still load.
    let obj = format!("{head}f -3/-1/-1 -2/1/1 -1/1/-1\n");
    let (mesh, _, _) = load_mesh_bytes(Path::new("i.obj"), obj.as_bytes()).unwrap();
    assert_eq!(mesh.len(), 1);
}

/// A relative buffer URI that percent-decodes to invalid UTF-8 (`%AA`):
/// `gltf` unwrapped the decoding and panicked.
#[test]
fn gltf_buffer_uri_of_invalid_utf8_is_an_error() {
    for uri in ["b%AA.bin", "%c3%28", "%ff"] {
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":4,"uri":"{uri}"}}]}}"#
        );
        match load_mesh_bytes(Path::new("u.gltf"), json.as_bytes()) {
            Err(subcone_scene::SceneError::Load { reason, .. }) => {
                assert!(reason.contains("not UTF-8"), "{uri}: {reason}")
            }
            other => panic!("{uri}: {other:?}"),
        }
    }
    // Valid escapes and lone percent signs are left to the loader (a missing
    // file here), not refused.
    for uri in ["b%20x.bin", "100%.bin", "%e2%82%ac.bin"] {
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":4,"uri":"{uri}"}}]}}"#
        );
        match load_mesh_bytes(Path::new("/nonexistent/u.gltf"), json.as_bytes()) {
            Err(subcone_scene::SceneError::Load { reason, .. }) => {
                assert!(
                    reason.contains("cannot read the glTF buffers"),
                    "{uri}: {reason}"
                )
            }
            other => panic!("{uri}: {other:?}"),
        }
    }
}

/// `load_mesh_bytes` is `load_mesh_file` without the read.
#[test]
fn bytes_and_file_agree() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    std::fs::write(dir.path().join("m.mtl"), "newmtl red\nKd 0.8 0.1 0.1\n").unwrap();
    let path = dir.path().join("t.obj");
    std::fs::write(&path, obj).unwrap();
    let from_file = load_mesh_file(&path).unwrap();
    let from_bytes = load_mesh_bytes(&path, obj.as_bytes()).unwrap();
    assert_eq!(from_file.0, from_bytes.0);
    assert_eq!(from_file.1, from_bytes.1);
    assert_eq!(from_bytes.1[0].name, "red");
    let scene = load_scene_bytes(&path, obj.as_bytes()).unwrap();
    assert_eq!(scene.name, "t");
    assert!(load_mesh_bytes(&path, b"").is_err());
    assert!(load_mesh_bytes(Path::new("x.stl"), obj.as_bytes()).is_err());
}
