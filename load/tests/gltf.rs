//! glTF and GLB round trips: small files written here and loaded back.

mod common;

use common::{base64, f32_bytes, glb, load_error, u16_bytes, write};
use glam::Vec3;
use subcone_load::{load_mesh_file, load_scene};
use subcone_scene::{Albedo, SceneError};

/// A unit quad in the z = 0 plane facing +z: its buffer and the byte
/// lengths of its positions, normals and indices.
struct Quad {
    buf: Vec<u8>,
    lengths: (usize, usize, usize),
}

fn quad_buffer() -> Quad {
    let positions = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]);
    let normals = f32_bytes(&[0.0, 0.0, 1.0].repeat(4));
    let indices = u16_bytes(&[0, 1, 2, 0, 2, 3]);
    let lengths = (positions.len(), normals.len(), indices.len());
    let mut buf = positions;
    buf.extend(normals);
    buf.extend(indices);
    Quad { buf, lengths }
}

/// glTF JSON for the quad; `uri` is the buffer's uri (None for GLB's BIN chunk),
/// `nodes` the node list, `roots` the default scene's roots.
fn quad_json(uri: Option<&str>, quad: &Quad, nodes: &str, roots: &str) -> String {
    let len = quad.buf.len();
    let (p, n, i) = quad.lengths;
    let uri = uri
        .map(|u| format!(r#""uri": "{u}", "#))
        .unwrap_or_default();
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": {roots}}}],
  "nodes": {nodes},
  "materials": [{{"pbrMetallicRoughness": {{"baseColorFactor": [0.2, 0.4, 0.6, 1.0]}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1}}, "indices": 2, "material": 0}}]}}],
  "buffers": [{{{uri}"byteLength": {len}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": {p}}},
    {{"buffer": 0, "byteOffset": {p}, "byteLength": {n}}},
    {{"buffer": 0, "byteOffset": {pn2}, "byteLength": {i}}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"}},
    {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ]
}}"#,
        pn2 = p + n
    )
}

fn data_uri(buf: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", base64(buf))
}

/// [`quad_json`] with one node, the scene's root, holding the mesh, and the
/// buffer inline as a data URI.
fn inline_quad_json(quad: &Quad) -> String {
    quad_json(Some(&data_uri(&quad.buf)), quad, r#"[{"mesh": 0}]"#, "[0]")
}

#[test]
fn gltf_quad_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let quad = quad_buffer();
    let json = inline_quad_json(&quad);
    let path = write(dir.path(), "quad.gltf", json);
    let (mesh, materials, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 2);
    assert!(!dropped.any());
    assert_eq!(
        mesh.positions[0],
        [
            Vec3::ZERO,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0)
        ]
    );
    assert_eq!(mesh.normals[1], [Vec3::Z; 3]);
    let m = &materials[mesh.materials[0] as usize];
    assert_eq!(m.albedo, Albedo::Solid(Vec3::new(0.2, 0.4, 0.6)));

    let scene = load_scene(&path).unwrap();
    assert_eq!(scene.name, "quad");
    scene.camera.validate().unwrap();
}

#[test]
fn gltf_external_buffer_file() {
    let dir = tempfile::tempdir().unwrap();
    let quad = quad_buffer();
    write(dir.path(), "quad.bin", &quad.buf);
    let json = quad_json(Some("quad.bin"), &quad, r#"[{"mesh": 0}]"#, "[0]");
    let path = write(dir.path(), "external.gltf", json);
    let (mesh, _, _) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 2);

    // Without the .bin it is a load error naming the cause, not a panic.
    std::fs::remove_file(dir.path().join("quad.bin")).unwrap();
    let err = load_error(&path, "buffer");
    assert!(matches!(err, SceneError::Load { .. }), "{err}");
}

#[test]
fn glb_quad_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let quad = quad_buffer();
    let json = quad_json(None, &quad, r#"[{"mesh": 0}]"#, "[0]");
    let path = write(dir.path(), "quad.glb", glb(&json, &quad.buf));
    let (mesh, materials, dropped) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 2);
    assert!(!dropped.any());
    assert_eq!(mesh.positions[1][2], Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(
        materials[mesh.materials[0] as usize].albedo,
        Albedo::Solid(Vec3::new(0.2, 0.4, 0.6))
    );
}

#[test]
fn gltf_node_transforms_compose_and_normals_use_the_inverse_transpose() {
    let dir = tempfile::tempdir().unwrap();
    let quad = quad_buffer();
    // Node 0 rotates the quad about x by 45° (the quad's normal tilts), its child
    // node 1 holds the mesh under a non-uniform scale (1, 1, 3) and a
    // translation; node 2 holds the mesh again with a mirroring scale.
    let half = 22.5f32.to_radians();
    let nodes = format!(
        r#"[
      {{"rotation": [{s}, 0, 0, {c}], "children": [1]}},
      {{"mesh": 0, "scale": [1, 1, 3], "translation": [0, 0, 2]}},
      {{"mesh": 0, "scale": [-1, 1, 1], "translation": [10, 0, 0]}}
    ]"#,
        s = half.sin(),
        c = half.cos()
    );
    let json = quad_json(Some(&data_uri(&quad.buf)), &quad, &nodes, "[0, 2]");
    let path = write(dir.path(), "nodes.gltf", json);
    let (mesh, _, _) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 4, "the mesh is placed twice");

    // Placement 1: world = R(45° about x) · T(0,0,2) · S(1,1,3).
    let r = glam::Mat4::from_rotation_x(45f32.to_radians());
    let world = r
        * glam::Mat4::from_translation(Vec3::new(0.0, 0.0, 2.0))
        * glam::Mat4::from_scale(Vec3::new(1.0, 1.0, 3.0));
    let v = world.transform_point3(Vec3::new(1.0, 1.0, 0.0));
    assert!(
        (mesh.positions[0][2] - v).length() < 1e-5,
        "{:?} vs {v}",
        mesh.positions[0][2]
    );
    // A z-normal under S(1,1,3) stays a z-normal (inverse transpose), then rotates.
    let expect = r.transform_vector3(Vec3::Z);
    for n in mesh.normals[0] {
        assert!((n - expect).length() < 1e-5, "normal {n} vs {expect}");
    }
    // Normals stay perpendicular to the transformed surface.
    let t = mesh.positions[0];
    let geo = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
    assert!(geo.dot(mesh.normals[0][0]) > 0.9999);

    // Placement 2 mirrors x: winding is flipped so the geometric normal still
    // agrees with the (mirrored) shading normal.
    let t = mesh.positions[2];
    assert!(t.iter().all(|p| p.x >= 9.0 - 1e-6 && p.x <= 10.0 + 1e-6));
    let geo = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
    assert!(
        geo.dot(mesh.normals[2][0]) > 0.9999,
        "{geo} vs {}",
        mesh.normals[2][0]
    );
}

#[test]
fn gltf_points_and_lines_are_skipped() {
    let dir = tempfile::tempdir().unwrap();
    let quad = quad_buffer();
    let json = inline_quad_json(&quad)
        .replace(r#""material": 0}"#, r#""material": 0}, {"attributes": {"POSITION": 0}, "mode": 0}, {"attributes": {"POSITION": 0}, "mode": 1}"#);
    let path = write(dir.path(), "mixed.gltf", &json);
    let (mesh, _, _) = load_mesh_file(&path).unwrap();
    assert_eq!(mesh.len(), 2, "only the triangle primitive counts");

    // A file with points only has no triangles: a load error.
    let points = inline_quad_json(&quad).replace(r#""indices": 2, "material": 0"#, r#""mode": 0"#);
    let path = write(dir.path(), "points.gltf", points);
    let err = load_error(&path, "no triangles");
    assert!(matches!(err, SceneError::Load { .. }), "{err}");
}

#[test]
fn gltf_out_of_range_index_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    // The quad's last index, 3, becomes 9: past its four vertices.
    let mut quad = quad_buffer();
    let last = quad.buf.len() - 2;
    quad.buf[last..].copy_from_slice(&9u16.to_le_bytes());
    let json = inline_quad_json(&quad);
    let path = write(dir.path(), "badindex.gltf", json);
    let err = load_error(&path, "vertex that does not exist");
    assert!(matches!(err, SceneError::Load { .. }), "{err}");
}
