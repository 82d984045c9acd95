//! Plots (PNG and SVG through plotters) and labelled image panels.
//!
//! Text is drawn with DejaVu Sans, embedded in the binary and registered with
//! plotters' `ab_glyph` font backend, so no system font or fontconfig is used.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use anyhow::{anyhow, Context, Result};
use plotters::coord::ranged1d::AsRangedCoord;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use subcone_kernels::passes::Technique;
use subcone_scene::Method;

use crate::classes::{ClassError, CLASSES};
use crate::{file_safe, ResultRow};
use subcone_metrics::Rgb8;

/// DejaVu Sans (licence: `assets/fonts/DejaVuSans-LICENSE.txt`).
pub static FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// The family name plots use.
pub const FAMILY: &str = "sans-serif";

/// Register the embedded font for [`FAMILY`] (once per process).
pub fn register_fonts() -> Result<()> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        [FontStyle::Normal, FontStyle::Bold]
            .into_iter()
            .all(|s| register_font(FAMILY, s, FONT).is_ok())
    });
    if ok {
        Ok(())
    } else {
        Err(anyhow!(
            "the embedded DejaVu Sans font could not be registered"
        ))
    }
}

fn pe<E: std::fmt::Debug>(what: &str) -> impl FnOnce(E) -> anyhow::Error + '_ {
    move |e| anyhow!("{what}: {e:?}")
}

/// Plot size in pixels.
pub const PLOT_SIZE: (u32, u32) = (960, 640);

/// A line chart over two `f64` axes, as the report's line plots build it.
pub type LineChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// One method's line through `pts` in its colour ([`method_colour`]), a dot
/// of radius `dot` at each point, and its legend entry. A `-hybrid`
/// method's line is dashed, in its traced twin's colour, so that the two
/// read as one method with two primary visibilities.
pub fn method_line<DB: DrawingBackend>(
    chart: &mut LineChart<'_, DB>,
    method: &str,
    pts: &[(f64, f64)],
    dot: u32,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let pe = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plot of {method}: {e:?}");
    let c = method_colour(method);
    let hybrid = method.parse::<Method>().is_ok_and(|m| m.is_hybrid());
    if hybrid {
        chart
            .draw_series(DashedLineSeries::new(
                pts.to_vec(),
                12,
                8,
                c.stroke_width(3),
            ))
            .map_err(pe)?
            .label(method)
            .legend(move |(x, y)| {
                plotters::element::DashedPathElement::new(
                    vec![(x, y), (x + 20, y)],
                    6,
                    4,
                    c.stroke_width(3),
                )
            });
    } else {
        chart
            .draw_series(LineSeries::new(pts.to_vec(), c.stroke_width(3)))
            .map_err(pe)?
            .label(method)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3)));
    }
    chart
        .draw_series(pts.iter().map(|&p| Circle::new(p, dot, c.filled())))
        .map_err(pe)?;
    Ok(())
}

/// The plot colour of a method of the default comparison (sRGB), so every
/// plot agrees; `None` for other methods (the plots pick one from a palette).
fn plot_colour(method: &Method) -> Option<[u8; 3]> {
    let s = method.supersamples();
    if method.is_temporal() {
        // A lighter shade of the single-frame method's colour (TAA: cyan).
        return match method.single_frame().technique() {
            _ if method.is_paper() || method.gates_material() => None,
            Technique::NoAa => Some([23, 190, 207]),
            Technique::SraaRt => Some([255, 152, 150]),
            Technique::Ctss => Some([152, 223, 138]),
            _ => None,
        };
    }
    Some(
        match (
            method.technique(),
            method.is_paper(),
            method.gates_material(),
        ) {
            (_, true, _) | (_, _, true) => return None,
            (Technique::NoAa, ..) => [90, 90, 90],
            (Technique::Ssaa, ..) if s == 4 => [31, 119, 180],
            (Technique::Ssaa, ..) if s == 16 => [23, 75, 140],
            (Technique::Sraa, ..) => [255, 127, 14],
            (Technique::SraaRt, ..) => [214, 39, 40],
            (Technique::Ctss, ..) if !method.delayed_shading() && !method.split_groups() => {
                [44, 160, 44]
            }
            (Technique::CtssR, ..) if !method.delayed_shading() => [148, 103, 189],
            (Technique::SsaaCtss, ..) if s == 4 && !method.delayed_shading() => [140, 86, 75],
            (Technique::Fxaa, ..) => [227, 119, 194],
            _ => return None,
        },
    )
}

/// A fixed colour per method, so every plot agrees: `plot_colour` for the
/// default comparison,
/// [`SMAA_COLOUR`] for the SMAA row, a palette colour picked by the name's
/// hash for any other.
pub fn method_colour(method: &str) -> RGBColor {
    let registered = method
        .parse::<subcone_scene::Method>()
        .ok()
        .and_then(|m| plot_colour(&m));
    if let Some([r, g, b]) = registered {
        return RGBColor(r, g, b);
    }
    if method == crate::SMAA {
        return SMAA_COLOUR;
    }
    let h = method
        .bytes()
        .fold(7u32, |a, b| a.wrapping_mul(31).wrapping_add(b as u32));
    let c = Palette99::pick(h as usize % 99).to_rgba();
    RGBColor(c.0, c.1, c.2)
}

/// The SMAA row's colour.
pub const SMAA_COLOUR: RGBColor = RGBColor(188, 189, 34);

/// A fixed colour per pass name (column-safe).
pub fn pass_colour(pass: &str, i: usize) -> RGBColor {
    match pass {
        "shading" => RGBColor(31, 119, 180),
        "geometry" => RGBColor(255, 127, 14),
        "antialiasing" => RGBColor(44, 160, 44),
        "sphere_tracing" => RGBColor(148, 103, 189),
        "cone_tracing" => RGBColor(214, 39, 40),
        "other" => RGBColor(200, 200, 200),
        _ => {
            let c = Palette99::pick(i + 10).to_rgba();
            RGBColor(c.0, c.1, c.2)
        }
    }
}

/// How many backends `rows` come from (labels name the backend when more
/// than one).
fn backend_count(rows: &[&ResultRow]) -> usize {
    let mut b: Vec<&str> = rows.iter().map(|r| r.backend.as_str()).collect();
    b.sort();
    b.dedup();
    b.len()
}

fn label(r: &ResultRow, backends: usize) -> String {
    if backends > 1 {
        format!("{} ({})", r.method, r.backend)
    } else {
        r.method.to_string()
    }
}

/// A point of the error-against-time plot: the row, its median time per
/// frame (ms) and its mean FLIP.
type TimedPoint<'r> = (&'r ResultRow, f64, f64);

/// The error-against-time chart: a log-scale time axis against a linear
/// error axis.
type ErrorTimeChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, RangedCoordf64>>;

/// Names the error-against-time plot in errors.
const ERROR_TIME: &str = "error-against-time plot";

/// The error-against-time plot of `scene`: each row's mean FLIP against its
/// median time, labelled, over the staircase of the Pareto front.
fn draw_error_time<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    scene: &str,
    rows: &[&ResultRow],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let e = ERROR_TIME;
    root.fill(&WHITE).map_err(pe(e))?;
    let left_out = crate::answer::exclusions(rows);
    let pts = error_time_points(rows, &left_out);
    let backends = backend_count(rows);
    let size = (PLOT_SIZE.1 / 32) as i32;
    let mut chart = error_time_chart(root, scene, &pts, size)?;
    let front: Vec<(f64, f64)> =
        crate::answer::front(rows, &left_out, crate::classes::Metric::Flip)
            .iter()
            .map(|p| (p.ms, p.error))
            .collect();
    draw_front_staircase(&mut chart, &front)?;
    draw_error_time_points(&mut chart, &pts, &front, &left_out, backends, size - 4)?;
    legend(&mut chart, SeriesLabelPosition::UpperRight, size - 4, e)?;
    root.present().map_err(pe(e))?;
    Ok(())
}

/// The rows the error-against-time plot draws, with their time and error.
/// A row repeating another's image adds no point (the other's label names
/// it); a row timed on another device is kept, to be drawn hollow, off the
/// front.
fn error_time_points<'r>(
    rows: &[&'r ResultRow],
    left_out: &[crate::answer::Excluded],
) -> Vec<TimedPoint<'r>> {
    rows.iter()
        .filter(|r| {
            !matches!(
                crate::answer::excluded(left_out, r).map(|e| &e.why),
                Some(crate::answer::Why::SameImage { .. })
            )
        })
        .filter_map(|r| {
            let f = r.flip_mean?;
            (r.ms_median.is_finite() && r.ms_median > 0.0 && f.is_finite()).then_some((
                *r,
                r.ms_median,
                f,
            ))
        })
        .collect()
}

/// The error-against-time chart's caption, axes and mesh on `root`, its
/// ranges wide enough for `pts` (a log-scale margin of 1.6× either side in
/// time, 20 % above the largest error).
fn error_time_chart<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    scene: &str,
    pts: &[TimedPoint<'_>],
    size: i32,
) -> Result<ErrorTimeChart<'a, DB>>
where
    DB::ErrorType: 'static,
{
    let e = ERROR_TIME;
    let tmin = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let tmax = pts.iter().map(|p| p.1).fold(0.0, f64::max);
    let fmax = pts.iter().map(|p| p.2).fold(0.0, f64::max);
    let (x0, x1) = if pts.is_empty() {
        (1.0, 10.0)
    } else {
        (tmin / 1.6, tmax * 1.6)
    };
    let y1 = if fmax > 0.0 { fmax * 1.2 } else { 0.1 };
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("{scene}: mean FLIP against median time"),
            (FAMILY, size + 4),
        )
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), 0.0..y1)
        .map_err(pe(e))?;
    chart
        .configure_mesh()
        .x_desc("median time per frame (ms, log scale)")
        .y_desc("mean FLIP against the reference")
        .label_style((FAMILY, size - 4))
        .axis_desc_style((FAMILY, size - 2))
        .x_label_formatter(&|v| format_ms(*v))
        .draw()
        .map_err(pe(e))?;
    Ok(chart)
}

/// The Pareto front (time, error) as a staircase, with its legend entry;
/// nothing for a front of fewer than two points.
fn draw_front_staircase<DB: DrawingBackend>(
    chart: &mut ErrorTimeChart<'_, DB>,
    front: &[(f64, f64)],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    if front.len() > 1 {
        // A staircase: no method is better than the front between its points.
        let mut stairs = Vec::new();
        for w in front.windows(2) {
            stairs.push(w[0]);
            stairs.push((w[1].0, w[0].1));
        }
        stairs.extend(front.last().copied());
        chart
            .draw_series(LineSeries::new(stairs, BLACK.mix(0.6).stroke_width(2)))
            .map_err(pe(ERROR_TIME))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    }
    Ok(())
}

/// The label of a point: the method (and backend when there are several),
/// the rows sharing its image, and a dagger when it was timed on another
/// device.
fn error_time_label(
    r: &ResultRow,
    backends: usize,
    left_out: &[crate::answer::Excluded],
) -> String {
    let mut text = label(r, backends);
    let twins = crate::answer::same_image_twins(left_out, r);
    if !twins.is_empty() {
        let twins: Vec<String> = twins.iter().map(|t| t.to_string()).collect();
        text = format!("{text} (= {})", twins.join(", "));
    }
    if crate::answer::excluded(left_out, r).is_some() {
        text = format!("{text} † other device");
    }
    text
}

/// Where a `w × h` label goes beside its point at (`px`, `py`): the offset of
/// the first of four places (then one higher up) whose box does not collide
/// with one in `placed`, else the first; the chosen box joins `placed`.
fn place_label(
    placed: &mut Vec<(i32, i32, i32, i32)>,
    px: i32,
    py: i32,
    w: i32,
    h: i32,
) -> (i32, i32) {
    let candidates = [
        (9, -h - 2),
        (9, 4),
        (-w - 9, -h - 2),
        (-w - 9, 4),
        (9, -2 * h - 6),
    ];
    let collides = |dx: i32, dy: i32| {
        let (x0, y0) = (px + dx, py + dy);
        placed
            .iter()
            .any(|&(a, b, c, d)| x0 < c && a < x0 + w && y0 < d && b < y0 + h)
    };
    let (dx, dy) = candidates
        .iter()
        .copied()
        .find(|&(dx, dy)| !collides(dx, dy))
        .unwrap_or(candidates[0]);
    placed.push((px + dx, py + dy, px + dx + w, py + dy + h));
    (dx, dy)
}

/// Each point as a dot in its method's colour (larger on the front, hollow
/// when timed on another device) with its label beside it.
fn draw_error_time_points<DB: DrawingBackend>(
    chart: &mut ErrorTimeChart<'_, DB>,
    pts: &[TimedPoint<'_>],
    front: &[(f64, f64)],
    left_out: &[crate::answer::Excluded],
    backends: usize,
    font_px: i32,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    // Labels go beside their point, at the first of four places that does not
    // collide with a label already placed (boxes estimated from the font size).
    let mut placed: Vec<(i32, i32, i32, i32)> = Vec::new();
    for (r, t, f) in pts {
        let c = method_colour(&r.method.to_string());
        let on_front = front.iter().any(|p| p.0 == *t && p.1 == *f);
        let other_device = crate::answer::excluded(left_out, r).is_some();
        let text = error_time_label(r, backends, left_out);
        let (px, py) = chart.backend_coord(&(*t, *f));
        let w = (text.chars().count() as i32 * font_px * 6) / 10 + 2;
        let h = font_px + 2;
        let (dx, dy) = place_label(&mut placed, px, py, w, h);
        chart
            .draw_series(std::iter::once(
                EmptyElement::at((*t, *f))
                    + Circle::new(
                        (0, 0),
                        if on_front { 7 } else { 5 },
                        if other_device {
                            c.stroke_width(2)
                        } else {
                            c.filled()
                        },
                    )
                    + Text::new(text, (dx, dy), (FAMILY, font_px).into_font().color(&c)),
            ))
            .map_err(pe(ERROR_TIME))?;
    }
    Ok(())
}

/// `12.3` → `"12"`, `0.5` → `"0.5"`: short tick labels.
fn format_ms(v: f64) -> String {
    if v >= 10.0 {
        format!("{v:.0}")
    } else if v >= 1.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

fn draw_passes<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    scene: &str,
    rows: &[&ResultRow],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let e = "pass-time plot";
    root.fill(&WHITE).map_err(pe(e))?;
    let backends = backend_count(rows);
    // Segments per bar: the passes in run order, then what no pass covers.
    let bars: Vec<(String, Vec<(String, f64)>)> = rows
        .iter()
        .map(|r| {
            let mut segs = r.pass_ms.clone();
            let covered: f64 = segs.iter().map(|s| s.1).sum();
            if r.ms_median - covered > 0.02 * r.ms_median {
                segs.push(("other".into(), r.ms_median - covered));
            }
            (label(r, backends), segs)
        })
        .collect();
    let mut passes: Vec<String> = Vec::new();
    for (_, segs) in &bars {
        for (p, _) in segs {
            if !passes.contains(p) && p != "other" {
                passes.push(p.clone());
            }
        }
    }
    if bars.iter().any(|b| b.1.iter().any(|s| s.0 == "other")) {
        passes.push("other".into());
    }
    let ymax = bars
        .iter()
        .map(|b| b.1.iter().map(|s| s.1).sum::<f64>())
        .fold(0.0, f64::max);
    let n = bars.len().max(1) as u32;
    let size = (PLOT_SIZE.1 / 32) as i32;
    let names: Vec<String> = bars.iter().map(|b| b.0.clone()).collect();
    let caption = format!("{scene}: median time per pass");
    let mut chart = bar_chart(root, caption, (0..n - 1).into_segmented(), ymax, e)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(n as usize)
        .x_label_formatter(&|v| match v {
            SegmentValue::CenterOf(i) => names.get(*i as usize).cloned().unwrap_or_default(),
            _ => String::new(),
        })
        .y_desc("median time (ms)")
        .label_style((FAMILY, size - 5))
        .axis_desc_style((FAMILY, size - 2))
        .draw()
        .map_err(pe(e))?;
    for (pi, pass) in passes.iter().enumerate() {
        let c = pass_colour(pass, pi);
        let mut rects = Vec::new();
        for (bi, (_, segs)) in bars.iter().enumerate() {
            let mut y0 = 0.0;
            for (p, ms) in segs {
                if p == pass {
                    let mut r = Rectangle::new(
                        [
                            (SegmentValue::Exact(bi as u32), y0),
                            (SegmentValue::Exact(bi as u32 + 1), y0 + ms),
                        ],
                        c.filled(),
                    );
                    r.set_margin(0, 0, 12, 12);
                    rects.push(r);
                }
                y0 += ms;
            }
        }
        let name = pass.replace('_', " ");
        chart
            .draw_series(rects)
            .map_err(pe(e))?
            .label(name)
            .legend(swatch(c));
    }
    legend(&mut chart, SeriesLabelPosition::UpperLeft, size - 4, e)?;
    root.present().map_err(pe(e))?;
    Ok(())
}

/// The legend of a chart, in the plots' one style (`e` names the plot in
/// errors).
pub fn legend<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
    font_size: i32,
    e: &str,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font((FAMILY, font_size))
        .draw()
        .map_err(pe(e))
}

/// A bar chart's axes on `root`, in the bar plots' one layout: `caption`
/// above, `x` along the bottom, 0 to 1.15 × `ymax` up (`e` names the plot in
/// errors).
fn bar_chart<'a, DB: DrawingBackend, X: AsRangedCoord>(
    root: &'a DrawingArea<DB, Shift>,
    caption: String,
    x: X,
    ymax: f64,
    e: &str,
) -> Result<ChartContext<'a, DB, Cartesian2d<X::CoordDescType, RangedCoordf64>>>
where
    DB::ErrorType: 'static,
{
    let size = (PLOT_SIZE.1 / 32) as i32;
    ChartBuilder::on(root)
        .caption(caption, (FAMILY, size + 4))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(x, 0.0..(ymax * 1.15).max(1e-3))
        .map_err(pe(e))
}

/// A bar series' mark in the legend: a filled square of its colour.
fn swatch(c: RGBColor) -> impl Fn((i32, i32)) -> Rectangle<(i32, i32)> {
    move |(x, y)| Rectangle::new([(x, y - 6), (x + 14, y + 6)], c.filled())
}

/// FLIP by edge class: one group of bars per class, one bar per method.
fn draw_classes<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    scene: &str,
    rows: &[&ResultRow],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let e = "edge-class plot";
    root.fill(&WHITE).map_err(pe(e))?;
    let backends = backend_count(rows);
    let bars: Vec<(String, String, ClassError)> = rows
        .iter()
        .filter_map(|r| {
            r.classes
                .map(|k| (label(r, backends), r.method.to_string(), k))
        })
        .collect();
    let ymax = bars
        .iter()
        .flat_map(|b| b.2.mean.iter().flatten().copied())
        .fold(0.0, f64::max);
    let size = (PLOT_SIZE.1 / 32) as i32;
    let n = CLASSES.len();
    let px = bars.first().map(|b| b.2.px).unwrap_or_default();
    let caption = format!("{scene}: FLIP by edge class");
    let mut chart = bar_chart(root, caption, 0.0..n as f64, ymax, e)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(2 * n + 1)
        .x_label_formatter(&|v| {
            let i = (v - 0.5).round();
            if (v - 0.5 - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < n {
                let c = CLASSES[i as usize];
                format!("{c} ({} px)", px[c.index()])
            } else {
                String::new()
            }
        })
        .y_desc("mean FLIP over the class's pixels")
        .label_style((FAMILY, size - 6))
        .axis_desc_style((FAMILY, size - 2))
        .draw()
        .map_err(pe(e))?;
    let k = bars.len().max(1) as f64;
    let width = 0.8 / k;
    for (bi, (name, method, flips)) in bars.iter().enumerate() {
        let c = method_colour(method);
        let rects: Vec<_> = CLASSES
            .iter()
            .filter_map(|cl| {
                let v = flips.mean[cl.index()]?;
                let x0 = cl.index() as f64 + 0.1 + bi as f64 * width;
                Some(Rectangle::new([(x0, 0.0), (x0 + width, v)], c.filled()))
            })
            .collect();
        chart
            .draw_series(rects)
            .map_err(pe(e))?
            .label(name.clone())
            .legend(swatch(c));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight, size - 6, e)?;
    root.present().map_err(pe(e))?;
    Ok(())
}

#[derive(Clone, Copy)]
enum Kind {
    ErrorTime,
    Passes,
    Classes,
}

fn draw<DB: DrawingBackend>(
    kind: Kind,
    root: &DrawingArea<DB, Shift>,
    scene: &str,
    rows: &[&ResultRow],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    match kind {
        Kind::ErrorTime => draw_error_time(root, scene, rows),
        Kind::Passes => draw_passes(root, scene, rows),
        Kind::Classes => draw_classes(root, scene, rows),
    }
}

/// A chart that draws itself on any plotters backend, so that
/// [`save_chart`] can write it as PNG and as SVG from one description.
pub trait Chart {
    /// Draw on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static;
}

/// `chart` as `<stem>.png` and `<stem>.svg` in `dir`, [`PLOT_SIZE`]
/// pixels; the paths written.
pub fn save_chart(dir: &Path, stem: &str, chart: &impl Chart) -> Result<Vec<PathBuf>> {
    let (w, h) = PLOT_SIZE;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        chart.draw(&root)?;
    }
    let png_path = dir.join(format!("{stem}.png"));
    crate::files::save_png(
        &png_path,
        &Rgb8 {
            width: w,
            height: h,
            data: buf,
        },
    )?;
    let mut svg_text = String::new();
    {
        let root = SVGBackend::with_string(&mut svg_text, (w, h)).into_drawing_area();
        chart.draw(&root)?;
    }
    let svg_path = dir.join(format!("{stem}.svg"));
    crate::reference::write_atomic(&svg_path, svg_text.as_bytes())?;
    Ok(vec![png_path, svg_path])
}

/// One of a scene's charts.
struct SceneChart<'a> {
    kind: Kind,
    scene: &'a str,
    rows: &'a [&'a ResultRow],
}

impl Chart for SceneChart<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        draw(self.kind, root, self.scene, self.rows)
    }
}

fn both(
    dir: &Path,
    stem: &str,
    scene: &str,
    rows: &[&ResultRow],
    kind: Kind,
) -> Result<Vec<PathBuf>> {
    save_chart(dir, stem, &SceneChart { kind, scene, rows })
}

/// The plots of a scene, as PNG and SVG in `dir`: `<scene>_flip_vs_time`
/// and `<scene>_classes` (FLIP by edge class; both only when errors were
/// measured) and `<scene>_passes`.
pub fn scene_plots(dir: &Path, scene: &str, rows: &[&ResultRow]) -> Result<Vec<PathBuf>> {
    if rows.is_empty() {
        return Ok(Vec::new());
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let stem = file_safe(scene);
    let mut out = Vec::new();
    if rows.iter().any(|r| r.flip_mean.is_some()) {
        out.extend(both(
            dir,
            &format!("{stem}_flip_vs_time"),
            scene,
            rows,
            Kind::ErrorTime,
        )?);
    }
    if rows.iter().any(|r| r.classes.is_some()) {
        out.extend(both(
            dir,
            &format!("{stem}_classes"),
            scene,
            rows,
            Kind::Classes,
        )?);
    }
    out.extend(both(
        dir,
        &format!("{stem}_passes"),
        scene,
        rows,
        Kind::Passes,
    )?);
    Ok(out)
}

/// Tiles side by side with a label above each, on white.
pub fn label_panel(tiles: &[(String, Rgb8)]) -> Result<Rgb8> {
    const GAP: u32 = 8;
    const LABEL: u32 = 28;
    let tw: u32 = tiles.iter().map(|t| t.1.width).sum::<u32>() + GAP * (tiles.len() as u32 + 1);
    let th: u32 = tiles.iter().map(|t| t.1.height).max().unwrap_or(0) + LABEL + GAP;
    let (w, h) = (tw.max(1), th.max(1));
    let mut data = vec![255u8; (w * h * 3) as usize];
    let mut x0 = GAP;
    for (_, img) in tiles {
        for y in 0..img.height {
            let src = (y * img.width * 3) as usize;
            let dst = (((LABEL + y) * w + x0) * 3) as usize;
            let len = (img.width * 3) as usize;
            data[dst..dst + len].copy_from_slice(&img.data[src..src + len]);
        }
        x0 += img.width + GAP;
    }
    {
        let root = BitMapBackend::with_buffer(&mut data, (w, h)).into_drawing_area();
        let mut x0 = GAP as i32;
        for (name, img) in tiles {
            let font = (FAMILY, 16).into_font().color(&BLACK);
            root.draw(&Text::new(name.clone(), (x0, 6), font))
                .map_err(pe("crop labels"))?;
            x0 += (img.width + GAP) as i32;
        }
        root.present().map_err(pe("crop labels"))?;
    }
    Ok(Rgb8 {
        width: w,
        height: h,
        data,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn font_registers() {
        register_fonts().unwrap();
        let panel = label_panel(&[(
            "noaa".into(),
            Rgb8 {
                width: 16,
                height: 16,
                data: vec![0; 16 * 16 * 3],
            },
        )])
        .unwrap();
        // Some label pixel is dark.
        assert!(panel.data[..(panel.width * 28 * 3) as usize]
            .iter()
            .any(|&v| v < 128));
    }
}
