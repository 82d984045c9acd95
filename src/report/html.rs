//! `report.html`: the report as one interactive page beside `report.md`.
//!
//! Per scene, a viewer of any two of its images (a draggable split or one
//! alone, zoom 1× to 16× by nearest neighbour, pan, and the coordinates and
//! edge classes of the pixel under the cursor), the scene's results table,
//! sortable by any column, and its plots.
//!
//! The page is one file that works from `file://` with no network: its
//! script and style are inline (`html/page.js`, `html/page.css`), the data is
//! an inline JSON block, and images and plots are linked by relative paths.
//! Nothing reads an image's pixels (a page from `file://` may not), so the
//! classes travel in the data: per scene, one byte per pixel (bit `i` is
//! class `i` of [`CLASSES`]), base64.
//!
//! The page keeps its state in the URL fragment (`#scene=cornell&a=sraa&
//! b=reference&mode=split&split=0.5&zoom=8&x=40&y=30&highlight=shadow&
//! sort=flip_mean:desc`) and reads it on load, so a link opens any view.
//! `selftest=1` makes the page work each of its controls and mark the body
//! `data-selftest="pass"`; it marks `data-ready="1"` once set up and
//! `data-error` on any error, for checks in a headless browser.

use std::path::Path;

use serde_json::{json, Value};

use super::classes::CLASSES;
use super::output::{json_rows, Context};
use super::{file_safe, Mode, ReportSummary, ResultRow};

/// The images every method row may have in its scene's directory, by
/// file-name prefix (`<prefix><method>.png`), with the name of their group
/// in the layer lists. Another kind of per-method map is one more line.
const METHOD_LAYERS: [(&str, &str); 3] = [
    ("", "images"),
    ("flip_", "FLIP maps"),
    ("ssim_", "1 − SSIM maps"),
];

/// The reference's file stem: the first layer, B by default.
const REFERENCE: &str = "reference";

/// The other images of a scene itself that the viewer offers, after the
/// methods': file stem and label.
const SCENE_LAYERS: [(&str, &str); 1] = [("edge_mask", "edge mask")];

/// Columns of `results.json` left out of the page's tables: the scene (one
/// table per scene) and what is the same on every row of a scene or is
/// detail of another column (pixel counts per class, time ranges).
const HIDDEN_COLUMNS: [&str; 13] = [
    "scene",
    "width",
    "height",
    "runs",
    "ms_min",
    "ms_max",
    "ratio_min",
    "ratio_max",
    "quality_width",
    "quality_height",
    "reference",
    "post_process",
    "buffer_mib",
];

/// The page's template, style and script.
const TEMPLATE: &str = include_str!("html/page.html");
const STYLE: &str = include_str!("html/page.css");
const SCRIPT: &str = include_str!("html/page.js");

/// `report.html` of a run.
pub fn page(s: &ReportSummary, ctx: &Context) -> String {
    // `<` escaped as `\u003c` keeps `</script>` in any string from ending the
    // data block; JSON reads it back unchanged.
    let data = data(s, ctx).to_string().replace('<', "\\u003c");
    TEMPLATE
        .replace("/*STYLE*/", STYLE.trim_end())
        .replace("/*SCRIPT*/", SCRIPT.trim_end())
        .replace("/*DATA*/", &data)
}

/// Everything the page shows, as its script reads it.
fn data(s: &ReportSummary, ctx: &Context) -> Value {
    let (columns, rows) = json_rows(&s.rows);
    let columns: Vec<&String> = columns
        .iter()
        .filter(|c| !HIDDEN_COLUMNS.contains(&c.as_str()))
        .filter(|c| !c.starts_with("px_"))
        .collect();
    let first_backend = ctx.backends.first().map(String::as_str).unwrap_or("");
    let scene_names: Vec<&str> = ctx.scenes.iter().map(|sc| sc.name.as_str()).collect();
    let scenes: Vec<Value> = ctx
        .scenes
        .iter()
        .filter(|sc| s.rows.iter().any(|r| r.scene == sc.name))
        .map(|sc| {
            let scene_rows: Vec<&ResultRow> =
                s.rows.iter().filter(|r| r.scene == sc.name).collect();
            let (width, height) = sc.quality_size.unwrap_or(sc.timing_size);
            let masks = s.classes.iter().find(|c| c.scene == sc.name);
            json!({
                "name": sc.name,
                "width": width,
                "height": height,
                "layers": layers(&s.out_dir, &sc.name, &scene_rows, first_backend),
                "classes": masks.map(|c| base64(&c.masks.bits())),
                "rows": s.rows.iter().zip(&rows)
                    .filter(|(r, _)| r.scene == sc.name)
                    .map(|(_, v)| v)
                    .collect::<Vec<_>>(),
                "plots": plots(s, |scene| scene == Some(sc.name.as_str()), &scene_names),
            })
        })
        .collect();
    json!({
        "run": run_line(ctx),
        "columns": columns,
        "classes": CLASSES.iter().map(|c| c.name()).collect::<Vec<_>>(),
        "scenes": scenes,
        "plots": plots(s, |scene| scene.is_none(), &scene_names),
    })
}

/// One line on the run: mode, backends, reference, version.
fn run_line(ctx: &Context) -> String {
    let errors = if ctx.mode == Mode::TimingOnly {
        "no errors (timing only)".to_string()
    } else {
        format!("errors against {}", ctx.reference)
    };
    format!(
        "Mode {}, {}; {}; code {}. The tables and text are in report.md.",
        ctx.mode.name(),
        ctx.backend_descriptions.join(", "),
        errors,
        super::reference::code_version()
    )
}

/// The images of a scene the viewer offers, those on disk only: the
/// reference, each row's images of [`METHOD_LAYERS`] kind by kind, the edge
/// mask. A layer's id is its file stem.
fn layers(out: &Path, scene: &str, rows: &[&ResultRow], first_backend: &str) -> Vec<Value> {
    let dir = out.join("images").join(scene);
    let layer = |stem: String, label: String, kind: &str, group: &str| {
        let file = format!("{stem}.png");
        dir.join(&file).is_file().then(|| {
            json!({
                "id": stem, "label": label, "kind": kind, "group": group,
                "src": format!("images/{scene}/{file}"),
            })
        })
    };
    let mut out: Vec<Value> = Vec::new();
    out.extend(layer(REFERENCE.into(), REFERENCE.into(), "scene", "scene"));
    for (prefix, group) in METHOD_LAYERS {
        for r in rows.iter().filter(|r| r.flip_mean.is_some()) {
            let stem = if r.backend == first_backend {
                format!("{prefix}{}", file_safe(&r.method))
            } else {
                format!("{prefix}{}-{}", file_safe(&r.method), file_safe(&r.backend))
            };
            let label = if r.backend == first_backend {
                r.method.clone()
            } else {
                format!("{} ({})", r.method, r.backend)
            };
            let kind = if prefix.is_empty() { "image" } else { "map" };
            out.extend(layer(stem, label, kind, group));
        }
    }
    for (stem, label) in SCENE_LAYERS {
        out.extend(layer(stem.to_string(), label.to_string(), "scene", "scene"));
    }
    out
}

/// The plots whose scene (by the file-name prefix `<scene>_`, the longest
/// that matches, or none) passes `keep`: the SVG of each, the PNG where
/// there is no SVG.
fn plots(s: &ReportSummary, keep: impl Fn(Option<&str>) -> bool, scenes: &[&str]) -> Vec<Value> {
    let mut out = Vec::new();
    for p in &s.plots {
        let (Some(stem), Some(ext)) = (
            p.file_stem().and_then(|n| n.to_str()),
            p.extension().and_then(|e| e.to_str()),
        ) else {
            continue;
        };
        let svg_too = s.plots.contains(&p.with_extension("svg"));
        if !(ext == "svg" || ext == "png" && !svg_too) {
            continue;
        }
        let scene = scenes
            .iter()
            .filter(|sc| stem.starts_with(&format!("{sc}_")))
            .max_by_key(|sc| sc.len())
            .copied();
        if !keep(scene) {
            continue;
        }
        let rel = p.strip_prefix(&s.out_dir).unwrap_or(p);
        let src: Vec<String> = rel
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        let title = scene
            .map(|sc| stem[sc.len() + 1..].replace('_', " "))
            .unwrap_or_else(|| stem.replace('_', " "));
        out.push(json!({ "src": src.join("/"), "title": title }));
    }
    out
}

/// Standard base64 with padding, as the page's `atob` reads it.
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_standard_alphabet_and_padding() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
        assert_eq!(base64(&[0xff, 0xfe, 0x00, 0x3f]), "//4APw==");
    }

    #[test]
    fn the_template_has_every_slot_once() {
        for slot in ["/*STYLE*/", "/*SCRIPT*/", "/*DATA*/"] {
            assert_eq!(TEMPLATE.matches(slot).count(), 1, "{slot}");
        }
        // No slot marker in what fills the others.
        for part in [STYLE, SCRIPT] {
            assert!(!part.contains("/*DATA*/") && !part.contains("</script"));
        }
    }
}
