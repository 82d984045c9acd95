//! SDF scenes in text files (`.sdf.ron`): read, validate, write.
//!
//! A file describes a whole [`SdfScene`]: the tree of primitives and
//! operators, materials, lights, the camera and the tracing limits. `subcone
//! render --scene PATH` and `subcone report --scene PATH` read any file whose
//! name ends in [`SDF_FILE_SUFFIX`]; `subcone scene --export NAME -o FILE`
//! writes every built-in SDF scene in the format, and reading it back renders
//! the same image, bit for bit.
//!
//! ```
//! use subcone_load::file::{parse_sdf_scene, write_sdf_scene};
//!
//! let text = r#"
//! // A ball on a checkered floor, lit by the sun.
//! SdfScene(
//!     camera: (position: (0, 1.5, -5), target: (0, 0.7, 0), fov_degrees: 40),
//!     materials: [
//!         (name: "floor", albedo: Checker(a: (0.8, 0.8, 0.8), b: (0.2, 0.2, 0.2), size: 1)),
//!         (name: "ball", albedo: Solid((0.8, 0.2, 0.1))),
//!     ],
//!     lights: [Directional(direction: (0.4, 1, -0.3), irradiance: (3, 3, 3))],
//!     root: Union([
//!         Plane(normal: (0, 1, 0)),
//!         Transform(translate: (0, 1, 0), child: Sphere(radius: 1, material: 1)),
//!     ]),
//! )
//! "#;
//! let scene = parse_sdf_scene(text, "ball.sdf.ron").unwrap();
//! assert_eq!(scene.name, "ball");
//! assert_eq!(scene.root.eval(glam::Vec3::new(0.0, 3.0, 0.0)), (1.0, 1));
//!
//! // Written out and read back, it is the same scene.
//! let again = parse_sdf_scene(&write_sdf_scene(&scene).unwrap(), "ball.sdf.ron").unwrap();
//! assert_eq!(format!("{again:?}"), format!("{scene:?}"));
//!
//! // A bad value is named by its line and its path in the file.
//! let bad = text.replace("radius: 1,", "radius: -1,");
//! let e = parse_sdf_scene(&bad, "ball.sdf.ron").unwrap_err();
//! // Line 12, column 78: where the sphere's node ends.
//! assert_eq!(e.to_string(), "ball.sdf.ron:12:78: root.Union[1].Transform.child: \
//!     sphere: radius must not be negative, got -1");
//! ```
//!
//! # Why RON
//!
//! The format is [RON](https://github.com/ron-rs/ron) (Rusty Object Notation),
//! through serde. An SDF scene is a tree of typed nodes, each with named
//! parameters: RON writes that as it is, `Transform(translate: (0, 1, 0),
//! child: Sphere(radius: 1))`, where JSON needs a tag field in every object and
//! TOML cannot nest a tree without tables of tables. RON also has comments and
//! trailing commas, and its parser reports the line and column of an error.
//!
//! # The format
//!
//! Vectors and colours are tuples `(x, y, z)`; numbers may be written without
//! a decimal point. `NaN` and `inf` parse, and are refused where a finite
//! value is needed. Every field not marked *required* may be omitted.
//!
//! **`SdfScene(...)`**, the file (the name `SdfScene` may be left out):
//!
//! | field | meaning | default |
//! |---|---|---|
//! | `version` | format version, 1 | 1 |
//! | `name` | for messages and reports | the file name without `.sdf.ron` |
//! | `camera` | required, see below | |
//! | `materials` | a list; nodes name them by index | one grey diffuse material |
//! | `lights` | a list | none (no shadow rays) |
//! | `background` | colour of rays that miss | `(0.05, 0.05, 0.06)` |
//! | `ambient` | ambient light | `(0.03, 0.03, 0.03)` |
//! | `max_distance` | where rays leave the scene | 100 |
//! | `max_steps` | step budget per ray | 512 |
//! | `root` | required: the tree | |
//!
//! **Camera** `(position: (..), target: (..), up: (..), fov_degrees: ..)`: a
//! pinhole at `position` looking at `target`, `up` roughly up (default `(0, 1,
//! 0)`), vertical field of view `fov_degrees` (default 45) or `fov_radians`.
//! Instead of `target`, `forward` gives the view direction (exported files
//! give `forward` and `up` exactly).
//!
//! **Material** `(name: "..", albedo: .., mirror: 0, emission: (0, 0, 0),
//! alpha: 1)`, see [`Material`](subcone_scene::Material): `albedo` is `Solid((r, g,
//! b))` (default grey 0.7), `Checker(a: (..), b: (..), size: ..)` or
//! `Patches(palette: [(..), ..], size: ..)`, both on the world `x`/`z`
//! plane; `mirror` (reflectance) and `alpha` (opacity, CTSS §5.3) are in `[0,
//! 1]`. Textures are not part of the format.
//!
//! **Light** `Point(position: (..), intensity: (..))` or
//! `Directional(direction: (..), irradiance: (..))`, `direction` pointing
//! towards the light (normalised when it is not unit).
//!
//! **Nodes**, one per [`SdfNode`](subcone_scene::sdf::SdfNode) constructor, with its parameters under the
//! same names (see each constructor for the ranges it accepts):
//!
//! | node | fields |
//! |---|---|
//! | `Sphere` | `radius` |
//! | `Box` | `half` (half extents) |
//! | `RoundBox` | `half`, `radius` |
//! | `BoxFrame` | `half`, `thickness` |
//! | `Torus` | `major`, `minor` |
//! | `Link` | `half_length`, `major`, `minor` |
//! | `Capsule` | `half_height`, `radius` |
//! | `Cylinder` | `radius`, `half_height` |
//! | `RoundedCylinder` | `radius`, `half_height`, `rounding` |
//! | `CappedCone` | `half_height`, `bottom`, `top` |
//! | `Octahedron` | `size` |
//! | `HexPrism` | `apothem`, `half_height` |
//! | `Ellipsoid` | `radii` |
//! | `Plane` | `normal`, `offset` (default 0): the half-space `dot(p, normal) + offset ≤ 0` |
//! | `Union([..])`, `Intersection([..])` | the children |
//! | `SmoothUnion` | `k`, `children: [..]` |
//! | `Subtract` | `from`, `remove` |
//! | `Transform` | `translate` (default 0), `rotate`, `scale` (default 1), `child`: scale, then rotate, then translate |
//! | `Mirror` | `axes: [X, Z]`, `child` |
//! | `Repeat` | `period`, `lo` and `hi` (integer cell limits, both or neither; neither repeats forever), `child` |
//! | `Round` | `radius`, `child` |
//! | `Onion` | `thickness`, `child` |
//! | `ScaleDistance` | `factor`, `child` |
//! | `Displace` | `amplitude`, `frequency`, `child` |
//! | `Bounded` | `pad`, `child` |
//! | `Scatter` | `cell`, `lo`, `hi`, `templates: [..]`; `origin` (0), `seed` (0), `fill` (1), `margin` (5 % of the smallest cell side), `min_size` (0.5), `max_size` (1), `rotate` (true), `jitter` (true), `palette` (none): see [`ScatterConfig`](subcone_scene::sdf::ScatterConfig) |
//! | `Material` | `index`, `child`: every object below takes material `index` |
//!
//! Every primitive also takes `material` (an index into `materials`, default
//! 0). `rotate` is `Quat(x, y, z, w)` or `AxisAngle(axis: (..), degrees: ..)`.
//!
//! # Errors
//!
//! Reading never panics and never returns part of a scene. A file that does
//! not parse (a wrong type, an unknown node or field, a missing field) is
//! reported by the parser's line and column and the path to the value, like
//! `root.Union[2].Transform.child.Sphere.radius`. A node whose values its
//! constructor refuses (NaN, a negative radius, nesting deeper than
//! [`MAX_DEPTH`](subcone_scene::sdf::MAX_DEPTH), …) is reported at the line where the
//! node ends, with its path and the constructor's [`SdfError`] message.
//! Camera, material and light errors name their path (`materials[1].alpha`).
//! Files nested deeper than [`MAX_NESTING`] brackets are refused before they
//! are read, so no file can exhaust the stack.

mod build;
mod desc;
mod export;

use std::path::Path;

use build::Parsed;
use desc::{SceneDesc, FORMAT_VERSION};
use subcone_scene::sdf::{SdfError, SdfScene};
pub use subcone_scene::SdfFileError;

/// The end of an SDF scene file's name.
pub const SDF_FILE_SUFFIX: &str = ".sdf.ron";

/// The deepest bracket nesting a file may have: the tree's
/// [`MAX_DEPTH`](subcone_scene::sdf::MAX_DEPTH) levels at four brackets per level,
/// with room to spare for transforms, which merge.
pub const MAX_NESTING: usize = 512;

/// Whether `path` names an SDF scene file (ends in [`SDF_FILE_SUFFIX`], any
/// case).
pub fn is_sdf_file(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.to_ascii_lowercase().ends_with(SDF_FILE_SUFFIX))
}

/// The scene name a file gives when it names none: its file name without
/// [`SDF_FILE_SUFFIX`].
fn default_name(file: &str) -> String {
    let name = Path::new(file)
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or(file);
    let cut = name.len().saturating_sub(SDF_FILE_SUFFIX.len());
    match name.get(cut..) {
        Some(end) if end.eq_ignore_ascii_case(SDF_FILE_SUFFIX) && cut > 0 => name[..cut].into(),
        _ => name.into(),
    }
}

/// Refuses text nested deeper than [`MAX_NESTING`] brackets, naming the line;
/// strings and comments are skipped.
fn check_nesting(text: &str, file: &str) -> Result<(), SdfFileError> {
    let (mut depth, mut line, mut col) = (0usize, 1usize, 0usize);
    let mut chars = text.chars().peekable();
    let mut in_string = false;
    while let Some(c) = chars.next() {
        col += 1;
        if c == '\n' {
            line += 1;
            col = 0;
            continue;
        }
        if in_string {
            match c {
                '\\' => {
                    chars.next();
                    col += 1;
                }
                '"' => in_string = false,
                _ => {}
            }
            continue;
        }
        match c {
            '"' => in_string = true,
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        line += 1;
                        col = 0;
                        break;
                    }
                }
            }
            '(' | '[' | '{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(SdfFileError {
                        file: file.into(),
                        position: Some((line, col)),
                        path: String::new(),
                        reason: format!(
                            "nested deeper than {MAX_NESTING} brackets (a tree may be at most {} \
                             levels deep)",
                            subcone_scene::sdf::MAX_DEPTH
                        ),
                    });
                }
            }
            ')' | ']' | '}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
}

/// Reads an SDF scene from `text`; `file` names it in errors and, when the
/// file gives no `name`, names the scene (see the [module docs](self) for
/// the format).
pub fn parse_sdf_scene(text: &str, file: &str) -> Result<SdfScene, SdfFileError> {
    check_nesting(text, file)?;
    let options = ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .with_recursion_limit(MAX_NESTING * 2);
    let spanned = |e: ron::error::SpannedError, path: String| SdfFileError {
        file: file.into(),
        position: Some((e.span.start.line, e.span.start.col)),
        path,
        reason: e.code.to_string(),
    };
    let mut de = ron::Deserializer::from_str_with_options(text, &options)
        .map_err(|e| spanned(e, String::new()))?;
    let desc = match serde_path_to_error::deserialize(&mut de) {
        Ok(d) => d,
        Err(e) => {
            let path = e.path().to_string();
            let path = if path == "." { String::new() } else { path };
            return Err(spanned(de.span_error(e.into_inner()), path));
        }
    };
    de.end()
        .map_err(|e| spanned(de.span_error(e), String::new()))?;
    let desc: SceneDesc<Parsed> = desc;
    scene(desc, file)
}

/// [`parse_sdf_scene`] on a file's contents.
pub fn load_sdf_scene(path: &Path) -> Result<SdfScene, SdfFileError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| SdfFileError::at(&file, "", format!("cannot read the file: {e}")))?;
    parse_sdf_scene(&text, &file)
}

fn scene(d: SceneDesc<Parsed>, file: &str) -> Result<SdfScene, SdfFileError> {
    if d.version != FORMAT_VERSION {
        return Err(SdfFileError::at(
            file,
            "version",
            format!(
                "format version {} is not one this build reads ({FORMAT_VERSION})",
                d.version
            ),
        ));
    }
    let camera = build::camera(&d.camera).map_err(|e| SdfFileError::at(file, "camera", e))?;
    let mut materials = Vec::with_capacity(d.materials.len());
    for (i, m) in d.materials.into_iter().enumerate() {
        materials.push(
            build::material(m, i)
                .map_err(|e| SdfFileError::at(file, format!("materials[{i}]"), e))?,
        );
    }
    let mut lights = Vec::with_capacity(d.lights.len());
    for (i, l) in d.lights.into_iter().enumerate() {
        lights
            .push(build::light(l).map_err(|e| SdfFileError::at(file, format!("lights[{i}]"), e))?);
    }
    let name = d.name.unwrap_or_else(|| default_name(file));
    let root = d.root.0;
    let count = materials.len().max(1);
    let culprit = (root.max_material() as usize >= count)
        .then(|| export::material_path(&root, count, "root"))
        .flatten();
    let mut s = SdfScene::new(&name, root, materials, lights, camera).map_err(|e| {
        let path = match &e {
            SdfError::Material { .. } => culprit.unwrap_or_else(|| "root".into()),
            _ => String::new(),
        };
        SdfFileError::at(file, path, e.to_string())
    })?;
    s.background = build::colour_field("background", d.background)
        .map_err(|e| SdfFileError::at(file, "background", e))?;
    s.ambient = build::colour_field("ambient", d.ambient)
        .map_err(|e| SdfFileError::at(file, "ambient", e))?;
    s.max_distance = d.max_distance;
    s.max_steps = d.max_steps;
    s.validate().map_err(|e| {
        let path = if !(d.max_distance.is_finite() && d.max_distance > 0.0) {
            "max_distance"
        } else if d.max_steps == 0 {
            "max_steps"
        } else {
            ""
        };
        SdfFileError::at(file, path, e.to_string())
    })?;
    Ok(s)
}

/// The scene in the format (see the [module docs](self)), pretty-printed.
/// Reading it back gives the same scene, bit for bit. Errors when the scene
/// uses what the format cannot describe (a textured material).
pub fn write_sdf_scene(scene: &SdfScene) -> Result<String, SdfFileError> {
    let desc = export::scene(scene).map_err(|e| SdfFileError::at(&scene.name, "", e))?;
    let config = ron::ser::PrettyConfig::new()
        .struct_names(true)
        .extensions(ron::extensions::Extensions::IMPLICIT_SOME)
        .indentor("    ".to_string());
    let body = ron::ser::to_string_pretty(&desc, config)
        .map_err(|e| SdfFileError::at(&scene.name, "", e.to_string()))?;
    Ok(format!(
        "// SDF scene {:?}, written by subcone {} (format version {FORMAT_VERSION}).\n{body}\n",
        scene.name,
        env!("CARGO_PKG_VERSION")
    ))
}
