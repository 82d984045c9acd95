//! Loading scenes from files: OBJ (with its MTL diffuse colours), glTF and GLB,
//! and the Sponza atrium of the SRAA paper.
//!
//! Loaders never panic on bad input: unreadable, malformed or empty files are a
//! [`SceneError::Load`], files whose triangles are all unusable (NaN/Inf or
//! zero-area) a [`SceneError::Empty`] that says how many were dropped.
//!
//! ```no_run
//! use subcone_load::{load_scene, scene_from_arg};
//! let bunny = load_scene(std::path::Path::new("bunny.obj"))?;
//! let atrium = scene_from_arg("sponza-mirror")?;
//! # Ok::<(), subcone_scene::SceneError>(())
//! ```

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use subcone_kernels::math::Euclidean;

use glam::{Mat3, Mat4, Vec2, Vec3};

use crate::file::{is_sdf_file, load_sdf_scene, parse_sdf_scene};
use subcone_scene::builtin;
use subcone_scene::camera::Camera;
use subcone_scene::error::SceneError;
use subcone_scene::light::Light;
use subcone_scene::material::Material;
use subcone_scene::mesh::{Sanitized, TriangleMesh};
use subcone_scene::scene::Scene;

/// Albedo of surfaces whose file gives no colour.
pub const DEFAULT_ALBEDO: Vec3 = Vec3::new(0.7, 0.7, 0.7);

/// Albedo given to Sponza, which has no materials: a warm stone.
pub const SPONZA_STONE: Vec3 = Vec3::new(0.6, 0.55, 0.45);

/// Mirror reflectance of Sponza's floor in `sponza-mirror`.
pub const SPONZA_FLOOR_REFLECTANCE: f32 = 0.5;

/// Sponza's file inside the data directory.
pub const SPONZA_PATH: &str = "sponza/sponza_dabrovic.obj";

/// Names [`scene_from_arg`] accepts besides the built-in scenes and file paths:
/// Sponza from [`data_dir`], with a plain floor and with a mirror floor.
pub const DATA_SCENES: [&str; 2] = ["sponza", "sponza-mirror"];

/// The data scene `name` of [`DATA_SCENES`]: whether its floor is a mirror.
fn data_scene(name: &str) -> Option<bool> {
    let [plain, mirror] = DATA_SCENES;
    match name {
        n if n == plain => Some(false),
        n if n == mirror => Some(true),
        _ => None,
    }
}

/// The directory holding the shared meshes (bunny, teapot, Cornell OBJ, Sponza).
///
/// `$SUBCONE_DATA_DIR` when set. A relative value is taken relative to the
/// current directory when it exists there, else relative to the workspace root
/// (so `SUBCONE_DATA_DIR=../shared/data` means the same thing to the CLI run from
/// the workspace root and to tests, which cargo runs from the crate directory).
/// Unset, it is `shared/data` beside the workspace: `<workspace>/../shared/data`.
pub fn data_dir() -> PathBuf {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    match std::env::var_os("SUBCONE_DATA_DIR") {
        Some(dir) if !dir.is_empty() => {
            let dir = PathBuf::from(dir);
            if dir.is_absolute() || dir.is_dir() {
                dir
            } else {
                workspace.join(dir)
            }
        }
        _ => workspace.join("../shared/data"),
    }
}

fn load_err(path: &Path, reason: impl Into<String>) -> SceneError {
    SceneError::Load {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

fn scene_name(path: &Path) -> String {
    path.file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("mesh")
        .to_string()
}

enum Format {
    Obj,
    Gltf,
}

fn format_of(path: &Path) -> Result<Format, SceneError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("obj") => Ok(Format::Obj),
        Some("gltf") | Some("glb") => Ok(Format::Gltf),
        _ => Err(SceneError::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// Run a parser, turning a panic inside it into a load error.
fn guarded<T>(path: &Path, f: impl FnOnce() -> Result<T, SceneError>) -> Result<T, SceneError> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown cause".into());
            Err(load_err(path, format!("the parser failed: {what}")))
        }
    }
}

/// Load the triangles and materials of a `.obj`, `.gltf` or `.glb` file.
///
/// OBJ faces are triangulated (as fans); the MTL's diffuse colour `Kd` (and
/// emission `Ke`) become materials, and faces without a material get one grey
/// default. glTF meshes of the default scene (or of the first scene, or every
/// mesh when there is no scene) are placed by their nodes' world transforms,
/// normals by the inverse transpose; a material's base colour factor is its
/// albedo. Point and line primitives are skipped; strips and fans are
/// triangulated. Textures are not read.
///
/// The mesh is [sanitized](TriangleMesh::sanitize): the returned [`Sanitized`]
/// counts the NaN/Inf and zero-area triangles dropped.
///
/// Errors: [`SceneError::UnknownFormat`] for other extensions,
/// [`SceneError::Load`] for a file that cannot be read or parsed or that has no
/// triangle, [`SceneError::Empty`] when every triangle was dropped.
pub fn load_mesh_file(path: &Path) -> Result<(TriangleMesh, Vec<Material>, Sanitized), SceneError> {
    format_of(path)?;
    let meta = std::fs::metadata(path).map_err(|e| load_err(path, e.to_string()))?;
    if !meta.is_file() {
        return Err(load_err(path, "not a regular file"));
    }
    let bytes = std::fs::read(path).map_err(|e| load_err(path, e.to_string()))?;
    load_mesh_bytes(path, &bytes)
}

/// [`load_mesh_file`] on the contents of a file already in memory.
///
/// `path` is not read: its extension names the format and its directory is
/// where an OBJ's `mtllib` and a `.gltf`'s relative buffer URIs are looked up.
/// Same results and errors as [`load_mesh_file`] on a file holding `bytes`.
pub fn load_mesh_bytes(
    path: &Path,
    bytes: &[u8],
) -> Result<(TriangleMesh, Vec<Material>, Sanitized), SceneError> {
    let format = format_of(path)?;
    if bytes.is_empty() {
        return Err(load_err(path, "the file is empty"));
    }
    let (mut mesh, materials) = guarded(path, || match format {
        Format::Obj => read_obj(path, bytes),
        Format::Gltf => read_gltf(path, bytes),
    })?;
    if mesh.is_empty() {
        return Err(load_err(
            path,
            "the file contains no triangles (is it really a mesh file of this format?)",
        ));
    }
    let read = mesh.len();
    let dropped = mesh.sanitize();
    if mesh.is_empty() {
        return Err(SceneError::Empty {
            name: scene_name(path),
            detail: format!(": all {read} triangle(s) were dropped ({dropped})"),
        });
    }
    Ok((mesh, materials, dropped))
}

fn tobj_material(m: &tobj::Material) -> Material {
    let finite3 = |c: Option<[f32; 3]>| {
        c.map(Vec3::from_array)
            .filter(|c| c.is_finite())
            .map(|c| c.max(Vec3::ZERO))
    };
    let name = if m.name.is_empty() { "mtl" } else { &m.name };
    let mut mat = Material::diffuse(
        name,
        finite3(m.diffuse)
            .map(|c| c.min(Vec3::ONE))
            .unwrap_or(DEFAULT_ALBEDO),
    );
    if let Some(e) = finite3(m.emissive) {
        mat.emission = e;
    }
    mat
}

/// An MTL file with every colour statement (`Ka`, `Kd`, `Ks`, `Ke`) given
/// three components, which `tobj` requires (it panics on fewer): one value
/// `r` means `r r r`, as the MTL format defines; a statement with two or no
/// values is removed (the colour stays unset). Other lines are unchanged.
fn mtl_colours_completed(text: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(text.len() + 16);
    for (i, line) in text.split(|&b| b == b'\n').enumerate() {
        if i > 0 {
            out.push(b'\n');
        }
        // `tobj` splits lines on `\n` and words as `str::split_whitespace`.
        let words: Vec<&str> = match std::str::from_utf8(line) {
            Ok(l) => l.split_whitespace().collect(),
            Err(_) => Vec::new(),
        };
        match words.as_slice() {
            [key @ ("Ka" | "Kd" | "Ks" | "Ke"), r] => {
                out.extend_from_slice(format!("{key} {r} {r} {r}").as_bytes());
            }
            ["Ka" | "Kd" | "Ks" | "Ke"] | ["Ka" | "Kd" | "Ks" | "Ke", _, _] => {}
            _ => out.extend_from_slice(line),
        }
    }
    out
}

/// Check what `tobj` does not: that every index of a face, line or point
/// statement is non-zero, at most the file's length, and (when negative,
/// i.e. relative) no further back than the vertices, texture coordinates or
/// normals defined above it. `tobj` computes `3·i` or `count + i` for them
/// unchecked and overflows (a panic with overflow checks, else a wrong
/// vertex). Lines are split and parsed as `tobj` does; lines it rejects itself
/// are left to it.
fn obj_indices_in_range(bytes: &[u8]) -> Result<(), String> {
    // Vertices, texture coordinates, normals defined so far.
    let mut counts = [0usize; 3];
    for (n, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let Ok(line) = std::str::from_utf8(line) else {
            continue;
        };
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some("f" | "l" | "p") => {
                for vertex in words {
                    for (k, part) in vertex.split('/').enumerate().take(3) {
                        let Ok(i) = part.parse::<isize>() else {
                            continue;
                        };
                        let ok = if i < 0 {
                            i.unsigned_abs() <= counts[k]
                        } else {
                            i > 0 && i.unsigned_abs() <= bytes.len()
                        };
                        if !ok {
                            let what = ["vertex", "texture coordinate", "normal"][k];
                            return Err(format!(
                                "line {}: {what} index {i} is out of range",
                                n + 1
                            ));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

fn read_obj(path: &Path, bytes: &[u8]) -> Result<(TriangleMesh, Vec<Material>), SceneError> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    if let Err(reason) = obj_indices_in_range(bytes) {
        return Err(load_err(path, reason));
    }
    // As `tobj::load_obj` does: the MTL file is looked up beside the OBJ.
    let base = path.parent().unwrap_or(Path::new(""));
    let mut reader = bytes;
    let loaded = tobj::load_obj_buf(&mut reader, &options, |mtl| {
        let text = std::fs::read(base.join(mtl)).map_err(|_| tobj::LoadError::OpenFileFailed)?;
        tobj::load_mtl_buf(&mut mtl_colours_completed(&text).as_slice())
    });
    let (models, mtl) = loaded.map_err(|e| match e {
        tobj::LoadError::OpenFileFailed => load_err(path, "cannot open the file"),
        tobj::LoadError::ReadError => {
            load_err(path, "read error (is it a text OBJ file in UTF-8?)")
        }
        e => load_err(path, format!("malformed OBJ: {e}")),
    })?;
    // A missing or broken .mtl is not fatal: the faces get the default material.
    let mut materials: Vec<Material> = mtl
        .map(|ms| ms.iter().map(tobj_material).collect())
        .unwrap_or_default();
    let known = materials.len();
    let default = known as u32;
    let mut needs_default = false;

    let mut mesh = TriangleMesh::default();
    for model in &models {
        let m = &model.mesh;
        let material = match m.material_id {
            Some(i) if i < known => i as u32,
            _ => {
                needs_default = true;
                default
            }
        };
        let position = |i: u32| -> Option<Vec3> {
            let i = i as usize * 3;
            m.positions
                .get(i..i + 3)
                .map(|p| Vec3::new(p[0], p[1], p[2]))
        };
        let has_normals = !m.normals.is_empty() && m.normal_indices.len() == m.indices.len();
        let has_uvs = !m.texcoords.is_empty() && m.texcoord_indices.len() == m.indices.len();
        for (f, tri) in m.indices.chunks_exact(3).enumerate() {
            let (Some(a), Some(b), Some(c)) =
                (position(tri[0]), position(tri[1]), position(tri[2]))
            else {
                return Err(load_err(
                    path,
                    "a face refers to a vertex that does not exist",
                ));
            };
            let v = [a, b, c];
            let geo = (b - a).cross(c - a).unit_or_zero();
            let mut n = [geo; 3];
            if has_normals {
                for (k, nk) in n.iter_mut().enumerate() {
                    let i = m.normal_indices[3 * f + k] as usize * 3;
                    if let Some(p) = m.normals.get(i..i + 3) {
                        *nk = Vec3::new(p[0], p[1], p[2]);
                    }
                }
            }
            let mut uv = [Vec2::ZERO; 3];
            if has_uvs {
                for (k, uk) in uv.iter_mut().enumerate() {
                    let i = m.texcoord_indices[3 * f + k] as usize * 2;
                    if let Some(p) = m.texcoords.get(i..i + 2) {
                        *uk = Vec2::new(p[0], p[1]);
                    }
                }
            }
            mesh.push(v, n, uv, material);
        }
    }
    if needs_default || materials.is_empty() {
        materials.push(Material::diffuse("default", DEFAULT_ALBEDO));
    }
    Ok((mesh, materials))
}

/// Parse a `.gltf` or `.glb` into its document and GLB blob. The checks here
/// come before `gltf`'s own: its GLB reader trusts the declared length (it
/// allocates it, and underflows below 12), and its validation indexes the
/// accessor a POSITION attribute names without a bounds check.
fn parse_gltf(path: &Path, bytes: &[u8]) -> Result<(gltf::Document, Option<Vec<u8>>), SceneError> {
    let (json, blob): (&[u8], Option<Vec<u8>>);
    let glb;
    if bytes.starts_with(b"glTF") {
        let declared = bytes
            .get(8..12)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
        match declared {
            None => return Err(load_err(path, "the GLB header is truncated")),
            Some(n) if n < 20 || n > bytes.len() => {
                return Err(load_err(
                    path,
                    format!(
                        "the GLB header declares {n} bytes but the file has {}",
                        bytes.len()
                    ),
                ))
            }
            Some(_) => {}
        }
        glb = gltf::binary::Glb::from_slice(bytes)
            .map_err(|e| load_err(path, format!("malformed GLB: {e}")))?;
        json = &glb.json;
        blob = glb.bin.as_ref().map(|b| b.to_vec());
    } else {
        json = bytes;
        blob = None;
    }
    let root: gltf::json::Root = gltf::json::deserialize::from_slice(json)
        .map_err(|e| load_err(path, format!("malformed glTF JSON: {e}")))?;
    for (i, buffer) in root.buffers.iter().enumerate() {
        // `gltf` percent-decodes relative URIs and unwraps the UTF-8 result.
        if let Some(uri) = buffer.uri.as_deref().filter(|u| !u.contains(':')) {
            if std::str::from_utf8(&percent_decoded(uri.as_bytes())).is_err() {
                return Err(load_err(
                    path,
                    format!(
                        "invalid glTF: the URI of buffer {i} is not UTF-8 once percent-decoded"
                    ),
                ));
            }
        }
    }
    for (i, mesh) in root.meshes.iter().enumerate() {
        for prim in &mesh.primitives {
            let bad = prim
                .attributes
                .values()
                .chain(prim.indices.iter())
                .find(|a| a.value() >= root.accessors.len());
            if let Some(a) = bad {
                return Err(load_err(
                    path,
                    format!(
                        "invalid glTF: mesh {i} uses accessor {}, which does not exist",
                        a.value()
                    ),
                ));
            }
        }
    }
    let doc = gltf::Document::from_json(root)
        .map_err(|e| load_err(path, format!("invalid glTF: {e}")))?;
    Ok((doc, blob))
}

/// `%XX` (two hex digits) decoded to the byte `XX`, everything else kept, as
/// `gltf` decodes relative buffer URIs (with the `urlencoding` crate).
fn percent_decoded(uri: &[u8]) -> Vec<u8> {
    let hex = |b: u8| (b as char).to_digit(16).map(|d| d as u8);
    let mut out = Vec::with_capacity(uri.len());
    let mut i = 0;
    while i < uri.len() {
        if uri[i] == b'%' {
            if let (Some(h), Some(l)) = (
                uri.get(i + 1).copied().and_then(hex),
                uri.get(i + 2).copied().and_then(hex),
            ) {
                out.push(h << 4 | l);
                i += 3;
                continue;
            }
        }
        out.push(uri[i]);
        i += 1;
    }
    out
}

fn read_gltf(path: &Path, bytes: &[u8]) -> Result<(TriangleMesh, Vec<Material>), SceneError> {
    let (doc, blob) = parse_gltf(path, bytes)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let buffers = gltf::import_buffers(&doc, Some(base), blob)
        .map_err(|e| load_err(path, format!("cannot read the glTF buffers: {e}")))?;
    let doc = &doc;

    let mut materials: Vec<Material> = doc
        .materials()
        .map(|m| {
            let c = Vec3::from_slice(&m.pbr_metallic_roughness().base_color_factor()[..3]);
            let e = Vec3::from_array(m.emissive_factor());
            let name = match m.index() {
                Some(i) => format!("material {i}"),
                None => "default".into(),
            };
            let mut mat = Material::diffuse(
                &name,
                if c.is_finite() {
                    c.clamp(Vec3::ZERO, Vec3::ONE)
                } else {
                    DEFAULT_ALBEDO
                },
            );
            if e.is_finite() {
                mat.emission = e.max(Vec3::ZERO);
            }
            mat
        })
        .collect();
    let default = materials.len() as u32;
    materials.push(Material::diffuse("default", DEFAULT_ALBEDO));

    let mut mesh = TriangleMesh::default();
    let mut ctx = GltfCtx {
        path,
        buffers: &buffers,
        default_material: default,
        mesh: &mut mesh,
        visits: 0,
    };
    let scene = doc.default_scene().or_else(|| doc.scenes().next());
    match scene {
        Some(scene) => {
            for node in scene.nodes() {
                ctx.node(&node, Mat4::IDENTITY, 0)?;
            }
        }
        None => {
            for m in doc.meshes() {
                ctx.mesh(&m, Mat4::IDENTITY)?;
            }
        }
    }
    Ok((mesh, materials))
}

/// Deepest node hierarchy followed, and most node visits (guards against
/// cyclic or exponentially shared hierarchies in malformed files).
const MAX_NODE_DEPTH: usize = 256;
const MAX_NODE_VISITS: usize = 1 << 20;

struct GltfCtx<'a> {
    path: &'a Path,
    buffers: &'a [gltf::buffer::Data],
    default_material: u32,
    mesh: &'a mut TriangleMesh,
    visits: usize,
}

/// Most elements an accessor may have (bounds the arithmetic `gltf` does).
const MAX_ELEMENTS: usize = 1 << 28;

/// Whether a buffer view lies inside its (loaded) buffer with a sane stride.
fn view_ok(v: &gltf::buffer::View<'_>, buffers: &[gltf::buffer::Data]) -> bool {
    let len = buffers.get(v.buffer().index()).map_or(0, |d| d.0.len());
    v.offset()
        .checked_add(v.length())
        .is_some_and(|end| end <= len)
        && v.stride().is_none_or(|s| s <= 256)
}

/// Whether `gltf` can read accessor `a` as `dims` without panicking: a known
/// shape, a bounded non-zero count, views inside their buffers. (Data that
/// still does not fit makes its reader return `None`.)
fn accessor_ok(
    a: &gltf::Accessor<'_>,
    dims: gltf::accessor::Dimensions,
    types: &[gltf::accessor::DataType],
    buffers: &[gltf::buffer::Data],
) -> bool {
    let count_ok = |n: usize| (1..=MAX_ELEMENTS).contains(&n);
    let sparse_ok = a.sparse().is_none_or(|s| {
        count_ok(s.count())
            && s.count() <= a.count()
            && s.indices().offset() <= u32::MAX as usize
            && s.values().offset() <= u32::MAX as usize
            && view_ok(&s.indices().view(), buffers)
            && view_ok(&s.values().view(), buffers)
    });
    a.dimensions() == dims
        && types.contains(&a.data_type())
        && count_ok(a.count())
        && a.offset() <= u32::MAX as usize
        && (a.view().is_some() || a.sparse().is_some())
        && a.view().is_none_or(|v| view_ok(&v, buffers))
        && sparse_ok
}

impl GltfCtx<'_> {
    fn node(
        &mut self,
        node: &gltf::Node<'_>,
        parent: Mat4,
        depth: usize,
    ) -> Result<(), SceneError> {
        self.visits += 1;
        if depth > MAX_NODE_DEPTH || self.visits > MAX_NODE_VISITS {
            return Err(load_err(
                self.path,
                "the node hierarchy is too deep or cyclic",
            ));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(m) = node.mesh() {
            self.mesh(&m, world)?;
        }
        for child in node.children() {
            self.node(&child, world, depth + 1)?;
        }
        Ok(())
    }

    fn mesh(&mut self, m: &gltf::Mesh<'_>, world: Mat4) -> Result<(), SceneError> {
        use gltf::accessor::{DataType, Dimensions};
        use gltf::mesh::Mode;

        let linear = Mat3::from_mat4(world);
        let det = linear.determinant();
        // Normals by the inverse transpose; a singular transform flattens the
        // mesh, whose triangles sanitize then drops.
        let normal_m = if det.abs() > f32::MIN_POSITIVE && det.is_finite() {
            linear.inverse().transpose()
        } else {
            linear
        };
        let flip = det < 0.0;
        for prim in m.primitives() {
            let mode = prim.mode();
            if !matches!(
                mode,
                Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
            ) {
                continue;
            }
            let Some(pos_acc) = prim.get(&gltf::Semantic::Positions) else {
                continue;
            };
            let buffers = self.buffers;
            if !accessor_ok(&pos_acc, Dimensions::Vec3, &[DataType::F32], buffers) {
                return Err(load_err(
                    self.path,
                    "POSITION must be a non-empty VEC3 float accessor inside its buffer",
                ));
            }
            // Unusable normals or uvs are ignored (geometric normals, zero uvs).
            let normals_ok = prim
                .get(&gltf::Semantic::Normals)
                .is_some_and(|a| accessor_ok(&a, Dimensions::Vec3, &[DataType::F32], buffers));
            let uvs_ok = prim.get(&gltf::Semantic::TexCoords(0)).is_some_and(|a| {
                accessor_ok(
                    &a,
                    Dimensions::Vec2,
                    &[DataType::U8, DataType::U16, DataType::F32],
                    buffers,
                )
            });
            let indices_ok = prim.indices().is_none_or(|a| {
                accessor_ok(
                    &a,
                    Dimensions::Scalar,
                    &[DataType::U8, DataType::U16, DataType::U32],
                    buffers,
                )
            });
            if !indices_ok {
                return Err(load_err(
                    self.path,
                    "indices must be a non-empty SCALAR unsigned-integer accessor inside its buffer",
                ));
            }
            let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
            let positions: Vec<Vec3> = reader
                .read_positions()
                .ok_or_else(|| load_err(self.path, "POSITION data lies outside its buffer"))?
                .map(|p| world.transform_point3(Vec3::from_array(p)))
                .collect();
            let normals: Option<Vec<Vec3>> = if normals_ok {
                reader.read_normals().map(|it| {
                    it.map(|n| normal_m.mul_vec3(Vec3::from_array(n)).unit_or_zero())
                        .collect()
                })
            } else {
                None
            };
            let uvs: Option<Vec<Vec2>> = if uvs_ok {
                reader
                    .read_tex_coords(0)
                    .map(|it| it.into_f32().map(Vec2::from_array).collect())
            } else {
                None
            };
            let indices: Vec<u32> = match reader.read_indices() {
                Some(it) => it.into_u32().collect(),
                None if prim.indices().is_some() => {
                    return Err(load_err(self.path, "index data lies outside its buffer"))
                }
                None => (0..positions.len() as u32).collect(),
            };
            let tris = triangles(mode, &indices);
            let material = prim
                .material()
                .index()
                .map_or(self.default_material, |i| i as u32);
            let attributes = (normals.as_deref(), uvs.as_deref());
            self.push_triangles(tris, &positions, attributes, material, flip)?;
        }
        Ok(())
    }

    /// Triangles `tris` of a primitive's vertices (`positions`, in world
    /// space; their `normals` and `uvs` where usable) added to the mesh with
    /// `material`, their winding reversed when the transform mirrors
    /// (`flip`). A vertex without a normal takes the triangle's geometric
    /// normal, one without a uv zero; an index past the vertices is an
    /// error.
    fn push_triangles(
        &mut self,
        tris: Vec<[u32; 3]>,
        positions: &[Vec3],
        (normals, uvs): (Option<&[Vec3]>, Option<&[Vec2]>),
        material: u32,
        flip: bool,
    ) -> Result<(), SceneError> {
        for t in tris {
            let t = if flip { [t[0], t[2], t[1]] } else { t };
            let get = |i: u32| positions.get(i as usize).copied();
            let (Some(a), Some(b), Some(c)) = (get(t[0]), get(t[1]), get(t[2])) else {
                return Err(load_err(
                    self.path,
                    "an index refers to a vertex that does not exist",
                ));
            };
            let geo = (b - a).cross(c - a).unit_or_zero();
            let n = match normals {
                Some(ns) => t.map(|i| ns.get(i as usize).copied().unwrap_or(geo)),
                None => [geo; 3],
            };
            let uv = match uvs {
                Some(us) => t.map(|i| us.get(i as usize).copied().unwrap_or(Vec2::ZERO)),
                None => [Vec2::ZERO; 3],
            };
            self.mesh.push([a, b, c], n, uv, material);
        }
        Ok(())
    }
}

/// The triangles of a primitive's `indices` in `mode` (triangles, a strip
/// with every other triangle's winding restored, or a fan).
fn triangles(mode: gltf::mesh::Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    use gltf::mesh::Mode;
    match mode {
        Mode::Triangles => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        Mode::TriangleStrip => indices
            .windows(3)
            .enumerate()
            .map(|(i, t)| {
                if i % 2 == 0 {
                    [t[0], t[1], t[2]]
                } else {
                    [t[1], t[0], t[2]]
                }
            })
            .collect(),
        _ => (2..indices.len())
            .map(|i| [indices[0], indices[i - 1], indices[i]])
            .collect(),
    }
}

/// Bounds of a non-empty mesh as `(centre, radius of the bounding sphere)`,
/// with the radius at least a tiny positive value.
fn bounding_sphere(mesh: &TriangleMesh) -> (Vec3, f32) {
    let (lo, hi) = mesh.bounds().unwrap_or((Vec3::ZERO, Vec3::ZERO));
    let centre = 0.5 * (lo + hi);
    let r = 0.5 * (hi - lo).norm();
    (centre, r.max(1e-6 * centre.abs().max_element()).max(1e-30))
}

/// A camera framing `mesh` from the `+z` side, slightly above, with a 50° field
/// of view, far enough that the bounding sphere fits the image height.
pub fn framing_camera(mesh: &TriangleMesh) -> Result<Camera, SceneError> {
    let (centre, r) = bounding_sphere(mesh);
    let fov = 50f32.to_radians();
    let distance = 1.1 * r / (0.5 * fov).sin();
    let dir = Vec3::new(0.0, 0.35, 1.0).unit();
    Camera::look_at(centre + distance * dir, centre, Vec3::Y, fov)
}

/// A scene from a file.
///
/// - An SDF scene file (a name ending in `.sdf.ron`, see [`crate::file`]):
///   the scene it describes.
/// - A mesh file (see [`load_mesh_file`]): its triangles and materials, a
///   camera framing its bounds ([`framing_camera`]) and one point light above
///   and in front of it, bright enough to light it (irradiance about 3 at the
///   model's centre whatever its size).
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    if is_sdf_file(path) {
        return Scene::sdf(load_sdf_scene(path)?);
    }
    let (mesh, materials, _dropped) = load_mesh_file(path)?;
    scene_from_mesh(path, mesh, materials)
}

/// [`load_scene`] on the contents of a file already in memory; `path` as in
/// [`load_mesh_bytes`] (not read; it also names the scene).
pub fn load_scene_bytes(path: &Path, bytes: &[u8]) -> Result<Scene, SceneError> {
    if is_sdf_file(path) {
        let file = path.display().to_string();
        let text = std::str::from_utf8(bytes)
            .map_err(|e| load_err(path, format!("not UTF-8 text ({e})")))?;
        return Scene::sdf(parse_sdf_scene(text, &file)?);
    }
    let (mesh, materials, _dropped) = load_mesh_bytes(path, bytes)?;
    scene_from_mesh(path, mesh, materials)
}

fn scene_from_mesh(
    path: &Path,
    mesh: TriangleMesh,
    materials: Vec<Material>,
) -> Result<Scene, SceneError> {
    let camera = framing_camera(&mesh)?;
    let (centre, r) = bounding_sphere(&mesh);
    let offset = Vec3::new(0.6, 2.0, 1.2) * r;
    let light = Light::Point {
        position: centre + offset,
        intensity: Vec3::splat(3.0 * offset.length_squared()),
    };
    if !light.is_finite() {
        return Err(load_err(
            path,
            "the model is too large to light (bounds overflow f32)",
        ));
    }
    Scene::triangles(&scene_name(path), mesh, materials, vec![light], camera)
}

/// Height above the lowest upward-facing point within which an upward-facing
/// triangle of Sponza counts as floor.
const SPONZA_FLOOR_BAND: f32 = 0.05;

/// Marko Dabrovic's Sponza atrium, the scene of the SRAA-for-ray-tracing paper,
/// from `data_dir/sponza/sponza_dabrovic.obj` (66,454 triangles, one of them
/// degenerate and dropped; no materials: warm stone, [`SPONZA_STONE`]).
///
/// The camera stands near the `-x` end of the atrium at about a quarter of its
/// height, looking along it (`+x`) with a 60° field of view. A sun (irradiance
/// 3) from high above, behind the camera and tilted across the atrium, lights
/// the floor and one arcade and makes its columns cast hard shadows on the
/// floor; the other side is in shadow, lit by the ambient term only. With `reflective_floor`, the floor (faces
/// whose normal is nearly `+y` within 5 cm of the lowest upward-facing
/// point; the file's lowest point is the bottom of a downward-facing outer shell) is a mirror of
/// reflectance [`SPONZA_FLOOR_REFLECTANCE`] over the stone.
pub fn sponza(data_dir: &Path, reflective_floor: bool) -> Result<Scene, SceneError> {
    let path = data_dir.join(SPONZA_PATH);
    let (mut mesh, _materials, _dropped) = load_mesh_file(&path)?;
    let (lo, hi) = mesh.bounds().unwrap_or((Vec3::ZERO, Vec3::ZERO));
    let up_facing = |v: &[Vec3; 3]| (v[1] - v[0]).cross(v[2] - v[0]).unit_or_zero().y > 0.99;
    // The file's lowest point is the bottom of an outer shell (y ≈ -0.91) that
    // faces down; the floor is the lowest upward-facing surface (y ≈ 0.09).
    let floor_y = mesh
        .positions
        .iter()
        .filter(|v| up_facing(v))
        .map(|v| v[0].y.min(v[1].y).min(v[2].y))
        .fold(f32::INFINITY, f32::min);
    let floor_y = if floor_y.is_finite() { floor_y } else { lo.y };
    let mut materials = vec![Material::diffuse("stone", SPONZA_STONE)];
    for m in &mut mesh.materials {
        *m = 0;
    }
    if reflective_floor {
        materials.push(Material::mirror(
            "floor",
            SPONZA_STONE,
            SPONZA_FLOOR_REFLECTANCE,
        ));
        for (i, v) in mesh.positions.iter().enumerate() {
            if up_facing(v) && v.iter().all(|p| p.y <= floor_y + SPONZA_FLOOR_BAND) {
                mesh.materials[i] = 1;
            }
        }
    }
    let size = hi - lo;
    let height = hi.y - floor_y;
    let centre = 0.5 * (lo + hi);
    // Sponza is long in x: stand near the -x end (just in front of the end
    // loggia, whose arcade is at 0.17 of the length), a quarter of the way up.
    let eye = Vec3::new(lo.x + 0.2 * size.x, floor_y + 0.25 * height, centre.z);
    let target = Vec3::new(hi.x - 0.1 * size.x, floor_y + 0.15 * height, centre.z);
    let camera = Camera::look_at(eye, target, Vec3::Y, 60f32.to_radians())?;
    // The sun stands high behind the camera and a little to the +z side: the
    // courtyard floor, the -z arcade and the far end wall are lit, and the -z
    // columns throw hard shadows across the aisle floor. (The courtyard is
    // about 6.4 m wide and 15.6 m deep: a lower sun leaves the floor in shadow.)
    let sun = Light::Directional {
        direction: Vec3::new(-0.35, 1.0, 0.22).unit(),
        irradiance: Vec3::new(1.0, 0.95, 0.85) * 3.0,
    };
    let [plain, mirror] = DATA_SCENES;
    let name = if reflective_floor { mirror } else { plain };
    // A weaker fill from the other side, so the +z arcade (in the sun's shadow)
    // shows its edges and casts shadows of its own instead of a flat ambient grey.
    let fill = Light::Directional {
        direction: Vec3::new(0.1, 1.0, -0.3).unit(),
        irradiance: Vec3::new(0.75, 0.8, 0.95) * 2.0,
    };
    let mut s = Scene::triangles(name, mesh, materials, vec![sun, fill], camera)?;
    s.background = Vec3::new(0.55, 0.7, 0.9);
    s.ambient = Vec3::new(0.08, 0.085, 0.1);
    Ok(s)
}

/// A scene named on a command line: a built-in scene
/// ([`builtin::TRIANGLE_SCENES`]), `sponza` or `sponza-mirror` (loaded from
/// [`data_dir`]), or a path to a `.obj`, `.gltf`, `.glb` or `.sdf.ron` file.
pub fn scene_from_arg(arg: &str) -> Result<Scene, SceneError> {
    // The name alone decides: nothing is built to test it.
    if let Some(entry) = builtin::find(arg) {
        return entry.build();
    }
    if let Some(reflective_floor) = data_scene(arg) {
        return sponza(&data_dir(), reflective_floor);
    }
    let path = Path::new(arg);
    if is_sdf_file(path) {
        return load_scene(path);
    }
    let has_mesh_ext = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "obj" | "gltf" | "glb"));
    if has_mesh_ext || path.exists() {
        return load_scene(path);
    }
    let mut known: Vec<&str> = builtin::names().collect();
    known.extend(DATA_SCENES);
    Err(SceneError::UnknownScene {
        name: arg.into(),
        known: format!(
            "{}; or a path to a .obj, .gltf, .glb or .sdf.ron file",
            known.join(", ")
        ),
    })
}
