//! `report.html`: the report as one interactive page beside `report.md`.
//!
//! At the top, report.md's first section (the report's answer), converted
//! from its Markdown here (`SECTIONS`) and laid out by the page to be seen
//! whole on the first screen (its tables in a small font, the picks with
//! its prose folded beside them, the fronts below; the font shrinks a step
//! at a time when longer cells would push the last row out of the window);
//! below the plots, its "Verdicts at a glance". Per scene, a viewer of any
//! two of its images, each labelled with its kind (render, FLIP map,
//! 1 − SSIM map), with a line on what they are (camera offset 0 at the
//! quality size, where the table's errors are means over the offsets): a
//! draggable split, one alone, or their difference (`|A − B|` or signed,
//! times a scale), zoom 1× to 16× by nearest neighbour, pan, a colour bar
//! with its range for each map shown and for the difference, and under the
//! cursor the pixel's coordinates, edge classes, A's and B's RGB and their
//! methods' FLIP and 1 − SSIM there; then the scene's results table (the
//! columns a reader needs, with the verdict cells of report.md's verdict
//! table and a mark on each Pareto front of report.md's answer, FLIP and
//! 1 − SSIM against time, every column behind a toggle), sortable by any
//! column, its motion animation and its plots.
//!
//! The page is one file that works from `file://` with no network: its
//! script and style are inline (`html/page.js`, `html/page.css`), the data is
//! an inline JSON block, and images and plots are linked by relative paths.
//! A page from `file://` may not read the pixels of an image it loads by
//! path, so the classes travel in the data (per scene, one byte per pixel,
//! bit `i` is class `i` of [`CLASSES`], base64), and each image's pixels in a
//! script beside it ([`PIXELS_DIR`]) that hands the page the PNG as a
//! `data:` URL, which it may read; the page loads the scripts of the layers
//! it shows only. The values under the cursor are decoded
//! from those PNGs: FLIP by inverting FLIP's colour map (256 colours, so
//! within 0.5/255 of the measured error), 1 − SSIM from its grey (within
//! 0.5/510; white is 0.5 or more).
//!
//! The page keeps its state in the URL fragment (`#scene=cornell&a=sraa&
//! b=reference&mode=split&split=0.5&zoom=8&x=40&y=30&highlight=shadow&
//! sort=flip_mean:desc`, with `mode=diff` or `mode=signed` and `scale=4`
//! for a difference, `raw=1` for every column) and reads it on load, so a
//! link opens any view. `selftest=1` makes the page work each of its controls
//! and mark the body `data-selftest="pass"`; it marks `data-ready="1"` once
//! set up and `data-error` on any error, for checks in a headless browser.
//! The page names the build that wrote it (`<meta name="subcone-code">` and
//! its header), which `scripts/report-screenshot` records beside the
//! screenshot it takes.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context as _, Result};
use serde_json::{json, Map, Value};

use crate::answer;
use crate::classes::{Metric, CLASSES};
use crate::context::Context;
use crate::motion::{self, CROP_ZOOM};
use crate::output::json_rows;
use crate::reference::{code_version, write_atomic};
use crate::{file_safe, Mode, ReportSummary, ResultRow};

/// The images every method row may have in its scene's directory, by
/// file-name prefix (`<prefix><method>.png`): the name of their group in
/// the layer lists, their kind (the page decodes a map's values by kind) and
/// the words every label of the kind ends with. Another kind of per-method
/// map is one more line.
const METHOD_LAYERS: [(&str, &str, &str, &str); 3] = [
    ("", "renders", "render", "render"),
    ("flip_", "FLIP maps", "flip", "FLIP map"),
    ("ssim_", "1 − SSIM maps", "ssim", "1 − SSIM map"),
];

/// The reference's file stem: the first layer, B by default.
const REFERENCE: &str = "reference";

/// The other images of a scene itself that the viewer offers, after the
/// methods': file stem and label.
const SCENE_LAYERS: [(&str, &str); 1] = [("edge_mask", "edge mask")];

/// 1 − SSIM at which the `ssim_<method>.png` grey saturates (white); see
/// `ssim::Ssim::image`.
const SSIM_WHITE: f64 = 0.5;

/// The sections of `report.md` the page shows, by heading: `None` is the
/// first `## ` section after the header (the report's answer), whatever it
/// is called. A heading here that `report.md` lacks is shown on the page as
/// missing (and fails the browser test), not left out silently.
const SECTIONS: [Option<&str>; 2] = [None, Some(VERDICTS)];

/// The heading of the table of verdicts the results table takes its verdict
/// column from (a cell per method, backend, metric and scene).
const VERDICTS: &str = "Verdicts at a glance";

/// The columns of the page's results table (the rest stays in the raw
/// table behind a toggle and in `results.csv`): key in the row's data, and
/// title. `pareto_<metric>` ([`FRONTS`]) and `verdict_<metric>` are the
/// page's own.
const SUMMARY_COLUMNS: [(&str, &str); 12] = [
    ("method", "method"),
    ("backend", "backend"),
    ("ms_median", "ms"),
    ("ratio_to_noaa", "× NoAA"),
    ("flip_mean", "FLIP"),
    ("ssim_mean", "SSIM"),
    ("edge_flip_mean", "edge FLIP"),
    ("pareto_flip", "FLIP front (ms, FLIP)"),
    ("pareto_ssim", "SSIM front (ms, 1 − SSIM)"),
    ("verdict_flip", "verdict, FLIP"),
    ("verdict_ssim", "verdict, SSIM"),
    ("timed_by", "timed by"),
];

/// The Pareto fronts the results table marks, those of report.md's answer:
/// per metric, the column (in [`SUMMARY_COLUMNS`]) and the mark of a method
/// on the front, which names the metric so that either column reads alone.
const FRONTS: [(Metric, &str, &str); 2] = [
    (Metric::Flip, "pareto_flip", "◆ FLIP"),
    (Metric::Ssim, "pareto_ssim", "◆ SSIM"),
];

/// Columns of `results.json` left out of the page's raw table: the scene (one
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

/// The directory beside a scene's images whose scripts carry their pixels
/// for the page's readout and difference mode, one per image
/// (`images/<scene>/pixels/<stem>.js`).
pub const PIXELS_DIR: &str = "pixels";

/// Write `report.html` of a run, and per scene its images' pixels
/// ([`PIXELS_DIR`]); `md` is the run's `report.md`, whose `SECTIONS` the
/// page shows.
pub fn write(s: &ReportSummary, ctx: &Context, md: &str) -> Result<()> {
    let first_backend = ctx.backends.first().map(String::as_str).unwrap_or("");
    for sc in &ctx.scenes {
        let rows: Vec<&ResultRow> = s.rows.iter().filter(|r| r.scene == sc.name).collect();
        let ids: Vec<String> = layers(&s.out_dir, &sc.name, &rows, first_backend, &ctx.reference)
            .iter()
            .filter(|l| l["kind"] != "mask")
            .filter_map(|l| l["id"].as_str().map(String::from))
            .collect();
        pixel_files(&s.out_dir, &sc.name, &ids)?;
    }
    write_atomic(&s.report_html, page(s, ctx, md).as_bytes())
}

/// `report.html` of a run.
pub fn page(s: &ReportSummary, ctx: &Context, md: &str) -> String {
    // `<` escaped as `\u003c` keeps `</script>` in any string from ending the
    // data block; JSON reads it back unchanged.
    let data = data(s, ctx, md).to_string().replace('<', "\\u003c");
    TEMPLATE
        .replace("/*STYLE*/", STYLE.trim_end())
        .replace("/*SCRIPT*/", SCRIPT.trim_end())
        .replace("/*CODE*/", &escape(&code_version()))
        .replace("/*DATA*/", &data)
}

/// `images/<scene>/pixels/<stem>.js` for each of the scene's viewer layers
/// (`ids`, their file stems: renders, maps, the reference): a script that
/// hands the page the layer's PNG as a `data:` URL,
/// `subconePixels("<scene>", "<stem>", "data:image/png;base64,…")`. A page
/// opened from `file://` may not read the pixels of an image it loads by
/// path, but it may run a script beside it and read the pixels of a
/// `data:` image; the bytes are the PNG file's own, so the values the page
/// shows are decoded from the very images it displays.
fn pixel_files(out: &Path, scene: &str, ids: &[String]) -> Result<()> {
    if ids.is_empty() {
        return Ok(());
    }
    let dir = out.join("images").join(scene);
    let to = dir.join(PIXELS_DIR);
    std::fs::create_dir_all(&to).with_context(|| format!("cannot create {}", to.display()))?;
    for id in ids {
        let p = dir.join(format!("{id}.png"));
        let bytes = std::fs::read(&p).with_context(|| format!("cannot read {}", p.display()))?;
        let js = format!(
            "subconePixels({}, {}, \"data:image/png;base64,{}\");\n",
            Value::String(scene.to_string()),
            Value::String(id.clone()),
            base64(&bytes)
        );
        write_atomic(&to.join(format!("{id}.js")), js.as_bytes())?;
    }
    Ok(())
}

/// Everything the page shows, as its script reads it.
fn data(s: &ReportSummary, ctx: &Context, md: &str) -> Value {
    let (columns, rows) = json_rows(&s.rows);
    let columns: Vec<&String> = columns
        .iter()
        .filter(|c| !HIDDEN_COLUMNS.contains(&c.as_str()))
        .filter(|c| !c.starts_with("px_"))
        .collect();
    let first_backend = ctx.backends.first().map(String::as_str).unwrap_or("");
    let scene_names: Vec<&str> = ctx.scenes.iter().map(|sc| sc.name.as_str()).collect();
    let (sections, missing) = sections(md);
    let verdicts = section_of(md, VERDICTS).and_then(|v| markdown_table(&v));
    let mut metrics: Vec<String> = Vec::new();
    let left_out = answer::exclusions(&s.rows.iter().collect::<Vec<_>>());
    let scenes: Vec<Value> = ctx
        .scenes
        .iter()
        .filter(|sc| s.rows.iter().any(|r| r.scene == sc.name))
        .map(|sc| {
            let scene_rows: Vec<&ResultRow> =
                s.rows.iter().filter(|r| r.scene == sc.name).collect();
            let (width, height) = sc.quality_size.unwrap_or(sc.timing_size);
            let masks = s.classes.iter().find(|c| c.scene == sc.name);
            // The answer section's fronts: per backend and metric, without
            // the rows it leaves out (timed on another device, a repeated
            // image).
            let front = |r: &ResultRow, metric: Metric| {
                let same_backend: Vec<&ResultRow> = scene_rows
                    .iter()
                    .copied()
                    .filter(|x| x.backend == r.backend)
                    .collect();
                answer::front(&same_backend, &left_out, metric)
            };
            let rows: Vec<Value> = s
                .rows
                .iter()
                .zip(&rows)
                .filter(|(r, _)| r.scene == sc.name)
                .map(|(r, v)| {
                    let mut v = v.clone();
                    for (metric, column, mark) in FRONTS {
                        let on_front = front(r, metric).iter().any(|p| p.method == r.method);
                        v[column] = if on_front { json!(mark) } else { Value::Null };
                    }
                    if let Some(t) = &verdicts {
                        for (metric, cell) in
                            t.verdicts(&r.method.to_string(), &r.backend, &sc.name)
                        {
                            if !metrics.contains(&metric) {
                                metrics.push(metric.clone());
                            }
                            v[format!("verdict_{}", metric.to_lowercase())] = json!(cell);
                        }
                    }
                    v
                })
                .collect();
            let dir = s.out_dir.join("images").join(sc.name.as_str());
            json!({
                "name": sc.name,
                "width": width,
                "height": height,
                "layers": layers(&s.out_dir, &sc.name, &scene_rows, first_backend, &ctx.reference),
                "pixels": dir.join(PIXELS_DIR).is_dir()
                    .then(|| format!("images/{}/{PIXELS_DIR}/", sc.name)),
                "classes": masks.map(|c| base64(&c.masks.bits())),
                "rows": rows,
                "plots": plots(s, |scene| scene == Some(sc.name.as_str()), &scene_names),
                "motion": motion_crop(s, &sc.name),
            })
        })
        .collect();
    let summary: Vec<Value> = SUMMARY_COLUMNS.iter().map(|(k, t)| json!([k, t])).collect();
    json!({
        "run": run_line(ctx),
        "code": code_version(),
        "columns": columns,
        "summary_columns": summary,
        "html_columns": metrics.iter().map(|m| format!("verdict_{}", m.to_lowercase())).collect::<Vec<_>>(),
        "classes": CLASSES.iter().map(|c| c.name()).collect::<Vec<_>>(),
        "scenes": scenes,
        "plots": plots(s, |scene| scene.is_none(), &scene_names),
        "sections": sections,
        "missing_sections": missing,
        "flip_lut": flip_lut(),
        "ssim_white": SSIM_WHITE,
    })
}

/// FLIP's magma colour map, the one `flip_<method>.png` is drawn with: 256
/// colours as one hex string (`rrggbb` each). A FLIP error `e` is drawn as
/// colour `round(255 e)`, so the page decodes a map pixel to its colour's
/// index over 255, within ±0.5/255 of the error.
fn flip_lut() -> String {
    let mut out = String::with_capacity(256 * 6);
    for b in subcone_metrics::magma_lut().into_iter().flatten() {
        let _ = write!(out, "{b:02x}");
    }
    out
}

/// The motion animation of a scene, when the report made one: its path and
/// a caption naming its tiles.
fn motion_crop(s: &ReportSummary, scene: &str) -> Option<Value> {
    let file = format!("images/{}/motion.png", file_safe(scene));
    if !s.out_dir.join(&file).is_file() {
        return None;
    }
    let m = &s.motion;
    let (_, c) = m.crops.iter().find(|(sc, _)| sc == scene)?;
    let mut names: Vec<&str> = m
        .rows
        .iter()
        .filter(|r| r.scene == scene)
        .map(|r| r.method.as_str())
        .collect();
    names.push(REFERENCE);
    Some(json!({
        "src": file,
        "zoom": CROP_ZOOM,
        "caption": format!(
            "{scene} in motion: the {side}×{side} window at ({x}, {y}) where NoAA is least \
    stable, {CROP_ZOOM}× zoomed; left to right {names}; frames 1 to {n} and back \
    ({fps} per second), each tile named above it and the frame's number below.",
            side = c.side,
            x = c.x,
            y = c.y,
            names = names.join(", "),
            n = m.frames,
            fps = motion::ANIMATION_FPS,
        ),
    }))
}

/// One line on the run: mode, backends, reference, version.
fn run_line(ctx: &Context) -> String {
    let errors = if ctx.mode == Mode::TimingOnly {
        "no errors (timing only)".to_string()
    } else {
        format!("errors against {}", ctx.reference)
    };
    format!(
        "Mode {}, {}; {}; code {}. Everything is in report.md; every column in results.csv.",
        ctx.mode.name(),
        ctx.backend_descriptions.join(", "),
        errors,
        code_version()
    )
}

/// The images of a scene the viewer offers, those on disk only: the
/// reference, each row's images of [`METHOD_LAYERS`] kind by kind, the edge
/// mask. A layer's id is its file stem; its label names the image and its
/// kind; a render names its maps (`maps`), a map the render it is of
/// (`of`), so the page can read every value of a pixel from either.
fn layers(
    out: &Path,
    scene: &str,
    rows: &[&ResultRow],
    first_backend: &str,
    reference: &str,
) -> Vec<Value> {
    let dir = out.join("images").join(scene);
    let on_disk = |stem: &str| dir.join(format!("{stem}.png")).is_file();
    let layer = |stem: &str, label: String, kind: &str, group: &str| {
        json!({
            "id": stem, "label": label, "kind": kind, "group": group,
            "src": format!("images/{scene}/{stem}.png"),
        })
    };
    let mut out: Vec<Value> = Vec::new();
    if on_disk(REFERENCE) {
        out.push(layer(
            REFERENCE,
            format!("reference ({reference}) · render"),
            "reference",
            "scene",
        ));
    }
    let stem_of = |prefix: &str, r: &ResultRow| {
        if r.backend == first_backend {
            format!("{prefix}{}", file_safe(&r.method.to_string()))
        } else {
            format!(
                "{prefix}{}-{}",
                file_safe(&r.method.to_string()),
                file_safe(&r.backend)
            )
        }
    };
    for (prefix, group, kind, words) in METHOD_LAYERS {
        for r in rows.iter().filter(|r| r.flip_mean.is_some()) {
            let stem = stem_of(prefix, r);
            if !on_disk(&stem) {
                continue;
            }
            let name = if r.backend == first_backend {
                r.method.to_string()
            } else {
                format!("{} ({})", r.method, r.backend)
            };
            let mut l = layer(&stem, format!("{name} · {words}"), kind, group);
            let maps: Map<String, Value> = METHOD_LAYERS
                .iter()
                .filter(|(p, ..)| !p.is_empty())
                .map(|(p, _, k, _)| (k.to_string(), json!(stem_of(p, r))))
                .filter(|(_, v)| on_disk(v.as_str().unwrap_or("")))
                .collect();
            l["maps"] = Value::Object(maps);
            l["of"] = json!(stem_of("", r));
            out.push(l);
        }
    }
    for (stem, label) in SCENE_LAYERS {
        if on_disk(stem) {
            out.push(layer(stem, label.to_string(), "mask", "scene"));
        }
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

/// The sections of `md` the page shows ([`SECTIONS`]), as HTML: heading and
/// body each; and the headings asked for that `md` lacks.
fn sections(md: &str) -> (Vec<Value>, Vec<String>) {
    let mut shown: Vec<Value> = Vec::new();
    let mut missing = Vec::new();
    let mut seen: Vec<String> = Vec::new();
    for want in SECTIONS {
        let found = match want {
            None => split_sections(md).into_iter().next(),
            Some(h) => split_sections(md).into_iter().find(|(head, _)| head == h),
        };
        match found {
            Some((head, body)) if !seen.contains(&head) => {
                shown.push(json!({ "heading": head, "html": markdown_html(&body) }));
                seen.push(head);
            }
            Some(_) => {}
            None => missing.push(want.unwrap_or("the first section").to_string()),
        }
    }
    (shown, missing)
}

/// The `## ` sections of `md` (outside code fences): heading and body.
fn split_sections(md: &str) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = Vec::new();
    let mut fence = false;
    for line in md.lines() {
        if line.starts_with("```") {
            fence = !fence;
        }
        match line.strip_prefix("## ") {
            Some(h) if !fence => out.push((h.trim().to_string(), String::new())),
            _ => {
                if let Some((_, body)) = out.last_mut() {
                    body.push_str(line);
                    body.push('\n');
                }
            }
        }
    }
    out
}

/// The body of the section of `md` headed `heading`.
fn section_of(md: &str, heading: &str) -> Option<String> {
    split_sections(md)
        .into_iter()
        .find(|(h, _)| h == heading)
        .map(|(_, b)| b)
}

/// A Markdown table: its header cells and rows of cells, as written.
#[derive(Debug, PartialEq)]
struct Table {
    head: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// From the verdict table ([`VERDICTS`]), the cells of `method` on
    /// `backend` in column `scene`, one per metric (the `metric` column), as
    /// HTML. Empty when the table has no such columns or row.
    fn verdicts(&self, method: &str, backend: &str, scene: &str) -> Vec<(String, String)> {
        let col = |name: &str| self.head.iter().position(|h| h == name);
        let (Some(m), Some(b), Some(k), Some(c)) =
            (col("method"), col("backend"), col("metric"), col(scene))
        else {
            return Vec::new();
        };
        self.rows
            .iter()
            .filter(|r| {
                r.get(m).is_some_and(|v| v == method) && r.get(b).is_some_and(|v| v == backend)
            })
            .filter_map(|r| Some((r.get(k)?.clone(), inline_html(r.get(c)?))))
            .collect()
    }
}

/// The cells of a table row `| a | b |`.
fn table_cells(line: &str) -> Vec<String> {
    let t = line.trim();
    let t = t.strip_prefix('|').unwrap_or(t);
    let t = t.strip_suffix('|').unwrap_or(t);
    t.split('|').map(|c| c.trim().to_string()).collect()
}

/// Whether `line` is a table's alignment row (`|---|--:|`).
fn is_rule(line: &str) -> bool {
    let cells = table_cells(line);
    !cells.is_empty()
        && cells
            .iter()
            .all(|c| !c.is_empty() && c.chars().all(|ch| matches!(ch, '-' | ':')))
}

/// The first table in `md`.
fn markdown_table(md: &str) -> Option<Table> {
    let lines: Vec<&str> = md.lines().collect();
    let at = lines
        .windows(2)
        .position(|w| w[0].trim_start().starts_with('|') && is_rule(w[1]))?;
    Some(Table {
        head: table_cells(lines[at]),
        rows: lines[at + 2..]
            .iter()
            .take_while(|l| l.trim_start().starts_with('|'))
            .map(|l| table_cells(l))
            .collect(),
    })
}

/// `report.md`'s Markdown, as far as the report writes it, to HTML:
/// `###`+ headings, paragraphs, `- ` lists, tables (with their columns'
/// alignment) and inline code, bold, italics, links and images.
fn markdown_html(md: &str) -> String {
    let mut html = String::new();
    let lines: Vec<&str> = md.lines().collect();
    let mut i = 0;
    let mut para: Vec<&str> = Vec::new();
    let flush = |para: &mut Vec<&str>, html: &mut String| {
        if !para.is_empty() {
            let _ = writeln!(html, "<p>{}</p>", inline_html(&para.join(" ")));
            para.clear();
        }
    };
    while i < lines.len() {
        let line = lines[i];
        let t = line.trim();
        if t.is_empty() {
            flush(&mut para, &mut html);
            i += 1;
        } else if t.starts_with('#') {
            flush(&mut para, &mut html);
            let level = t.chars().take_while(|&c| c == '#').count().clamp(3, 6);
            let _ = writeln!(
                html,
                "<h{level}>{}</h{level}>",
                inline_html(t.trim_start_matches('#').trim())
            );
            i += 1;
        } else if t.starts_with('|') && lines.get(i + 1).is_some_and(|l| is_rule(l)) {
            flush(&mut para, &mut html);
            let head = table_cells(t);
            let align: Vec<&str> = table_cells(lines[i + 1])
                .iter()
                .map(|c| match (c.starts_with(':'), c.ends_with(':')) {
                    (true, true) => " class=\"c\"",
                    (false, true) => " class=\"num\"",
                    _ => "",
                })
                .collect();
            html.push_str("<div class=\"table-wrap\"><table class=\"md\"><thead><tr>");
            for (k, h) in head.iter().enumerate() {
                let a = align.get(k).copied().unwrap_or("");
                let _ = write!(html, "<th{a}>{}</th>", inline_html(h));
            }
            html.push_str("</tr></thead><tbody>\n");
            i += 2;
            while i < lines.len() && lines[i].trim_start().starts_with('|') {
                html.push_str("<tr>");
                for (k, c) in table_cells(lines[i]).iter().enumerate() {
                    let a = align.get(k).copied().unwrap_or("");
                    let _ = write!(html, "<td{a}>{}</td>", inline_html(c));
                }
                html.push_str("</tr>\n");
                i += 1;
            }
            html.push_str("</tbody></table></div>\n");
        } else if let Some(item) = t.strip_prefix("- ") {
            flush(&mut para, &mut html);
            html.push_str("<ul>\n");
            let _ = writeln!(html, "<li>{}</li>", inline_html(item));
            i += 1;
            while let Some(item) = lines.get(i).and_then(|l| l.trim().strip_prefix("- ")) {
                let _ = writeln!(html, "<li>{}</li>", inline_html(item));
                i += 1;
            }
            html.push_str("</ul>\n");
        } else {
            para.push(t);
            i += 1;
        }
    }
    flush(&mut para, &mut html);
    html
}

/// HTML-escaped text.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One line of Markdown to HTML: `` `code` ``, `**bold**`, `*italics*`,
/// `[text](url)`, `![alt](src)`; everything else escaped.
fn inline_html(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    let mut bold = false;
    let mut em = false;
    while let Some(c) = rest.chars().next() {
        if c == '`' {
            if let Some(end) = rest[1..].find('`') {
                let _ = write!(out, "<code>{}</code>", escape(&rest[1..1 + end]));
                rest = &rest[end + 2..];
                continue;
            }
        }
        if let Some((alt, url, len)) = link(rest, "![") {
            let _ = write!(out, "<img src=\"{}\" alt=\"{}\">", escape(url), escape(alt));
            rest = &rest[len..];
            continue;
        }
        if let Some((text, url, len)) = link(rest, "[") {
            let _ = write!(out, "<a href=\"{}\">{}</a>", escape(url), inline_html(text));
            rest = &rest[len..];
            continue;
        }
        if rest.starts_with("**") {
            out.push_str(if bold { "</strong>" } else { "<strong>" });
            bold = !bold;
            rest = &rest[2..];
            continue;
        }
        // A `*` opens emphasis before a non-space and closes it after one
        // (`2 * 3` stays text).
        if c == '*' {
            let next = rest[1..].chars().next();
            if !em && next.is_some_and(|n| !n.is_whitespace()) && rest[1..].contains('*') {
                out.push_str("<em>");
                em = true;
                rest = &rest[1..];
                continue;
            }
            if em && !out.ends_with(char::is_whitespace) {
                out.push_str("</em>");
                em = false;
                rest = &rest[1..];
                continue;
            }
        }
        out.push_str(&escape(&rest[..c.len_utf8()]));
        rest = &rest[c.len_utf8()..];
    }
    if em {
        out.push_str("</em>");
    }
    if bold {
        out.push_str("</strong>");
    }
    out
}

/// `open` text `](` url `)` at the start of `s`: text, url and the length.
fn link<'a>(s: &'a str, open: &str) -> Option<(&'a str, &'a str, usize)> {
    let body = s.strip_prefix(open)?;
    let close = body.find("](")?;
    let text = &body[..close];
    if text.contains('[') {
        return None;
    }
    let after = &body[close + 2..];
    let end = after.find(')')?;
    Some((text, &after[..end], open.len() + close + 2 + end + 1))
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

    const MD: &str = "# subcone report\n\nHeader *text*.\n\n## The answer\n\nUse **a** \
for `x` < 2 * y.\n\n| method | ms |\n|---|--:|\n| a | 1.5 |\n\n- one\n- two [link](r.md)\n\n\
## Verdicts at a glance\n\nIntro.\n\n| method | backend | metric | s1 | s2 |\n|---|---|---|--:|--:|\n\
| a | cpu | FLIP | 1/2 · holds | 2/2 · **loses** |\n| a | cpu | SSIM | 2/2 · holds | – |\n\n\
## Later\n\n```\n## not a heading\n```\n";

    #[test]
    fn sections_are_found_by_heading_and_a_missing_one_is_named() {
        let (shown, missing) = sections(MD);
        assert!(missing.is_empty(), "{missing:?}");
        let heads: Vec<&str> = shown
            .iter()
            .map(|s| s["heading"].as_str().unwrap())
            .collect();
        assert_eq!(heads, ["The answer", "Verdicts at a glance"]);
        let renamed = MD.replace("## Verdicts at a glance", "## Verdicts in short");
        let (shown, missing) = sections(&renamed);
        assert_eq!(shown.len(), 1);
        assert_eq!(missing, [VERDICTS]);
        // The fenced line is no section.
        assert_eq!(split_sections(MD).len(), 3);
    }

    #[test]
    fn markdown_converts_what_the_report_writes() {
        let html = markdown_html(&section_of(MD, "The answer").unwrap());
        assert!(
            html.contains("<p>Use <strong>a</strong> for <code>x</code> &lt; 2 * y.</p>"),
            "{html}"
        );
        assert!(
            html.contains("<th>method</th><th class=\"num\">ms</th>"),
            "{html}"
        );
        assert!(
            html.contains("<td>a</td><td class=\"num\">1.5</td>"),
            "{html}"
        );
        assert!(
            html.contains("<li>two <a href=\"r.md\">link</a></li>"),
            "{html}"
        );
        assert_eq!(
            inline_html("*FLIP* and ![x](i/a.png)"),
            "<em>FLIP</em> and <img src=\"i/a.png\" alt=\"x\">"
        );
        assert_eq!(inline_html("<b>"), "&lt;b&gt;");
    }

    #[test]
    fn the_verdict_column_is_the_verdict_tables_cell() {
        let t = markdown_table(&section_of(MD, VERDICTS).unwrap()).unwrap();
        assert_eq!(t.head, ["method", "backend", "metric", "s1", "s2"]);
        assert_eq!(
            t.verdicts("a", "cpu", "s2"),
            [
                (
                    "FLIP".to_string(),
                    "2/2 · <strong>loses</strong>".to_string()
                ),
                ("SSIM".to_string(), "–".to_string())
            ]
        );
        assert!(t.verdicts("a", "gpu", "s1").is_empty());
        assert!(t.verdicts("a", "cpu", "nowhere").is_empty());
    }

    #[test]
    fn the_flip_colour_map_has_256_distinct_colours() {
        // The page decodes a map pixel by its colour: two equal colours
        // would make two errors one.
        let lut = flip_lut();
        assert_eq!(lut.len(), 256 * 6);
        let mut colours: Vec<&str> = (0..256).map(|i| &lut[6 * i..6 * i + 6]).collect();
        colours.sort();
        colours.dedup();
        assert_eq!(colours.len(), 256);
    }

    #[test]
    fn the_template_has_every_slot_once() {
        for slot in ["/*STYLE*/", "/*SCRIPT*/", "/*DATA*/", "/*CODE*/"] {
            assert_eq!(TEMPLATE.matches(slot).count(), 1, "{slot}");
        }
        // No slot marker in what fills the others.
        for part in [STYLE, SCRIPT] {
            assert!(
                !part.contains("/*DATA*/")
                    && !part.contains("/*CODE*/")
                    && !part.contains("</script")
            );
        }
    }
}
