//! `report.html` in a real browser: a small quick report (two scenes, three
//! methods) opened in headless Chromium, put into a state by its URL
//! fragment; the screenshot's pixels and the dumped DOM are checked against
//! the report's own images, rows, edge classes and error maps (the values
//! under the cursor, the difference modes and their colour bars), its
//! report.md sections, its Pareto fronts and its motion animation; and at a
//! laptop's window, the answer whole on the first screen, with the report's
//! own cells and with longer ones.
//!
//! Apart from the browser, a check that the committed screenshot
//! `docs/quick/report-html.png` is of the committed page: the build recorded
//! beside it (`docs/quick/report-html.build`, written by
//! `scripts/report-screenshot`) is the page's.
//!
//! Without a browser the test skips with a message, unless
//! `SUBCONE_REQUIRE_BROWSER=1` (CI), where it fails. `SUBCONE_BROWSER` names
//! the browser binary; by default the first of `chromium`,
//! `chromium-browser` and `google-chrome` on the `PATH`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use image::RgbImage;
use subcone_report::{self as report, ReportArgs, ReportSummary};

/// Browser window size in CSS pixels (and screenshot pixels: scale 1): tall
/// enough for the viewer below report.md's first section.
const WINDOW: (u32, u32) = (1100, 1400);
/// A laptop's window, in which the answer (every pick, every front) must be
/// seen whole without scrolling.
const LAPTOP: (u32, u32) = (1280, 800);
/// Largest difference per 8-bit channel between a screenshot pixel and the
/// image pixel it shows: the page draws the PNG unscaled in colour (sRGB
/// profile forced) and by nearest neighbour, so any difference is the
/// browser's rounding.
const TOLERANCE: i32 = 2;
/// The scene the checks look at and the zoom they use.
const SCENE: &str = "cornell";
const ZOOM: u32 = 8;

/// Virtual time the page gets to load and decode its images' pixels (the
/// `data:` URLs of `images/<scene>/pixels/<image>.js`) before a dump or
/// screenshot.
const SETTLE_MS: u32 = 5000;

fn settle() -> String {
    format!("--virtual-time-budget={SETTLE_MS}")
}

/// FLIP maps draw an error `e` as colour `round(255 e)` of the colour map:
/// a decoded value is within half a step of the error.
const FLIP_STEP: f64 = 1.0 / 255.0;
/// 1 − SSIM maps draw `d` as grey `round(255 · 2d)` (white from 0.5 on).
const SSIM_STEP: f64 = 1.0 / 510.0;
/// The page prints values to 4 decimals.
const PRINTED: f64 = 0.5e-4;

fn find_browser() -> Option<PathBuf> {
    if let Some(b) = std::env::var_os("SUBCONE_BROWSER") {
        return Some(PathBuf::from(b));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).find_map(|dir| {
        ["chromium", "chromium-browser", "google-chrome"]
            .iter()
            .map(|n| dir.join(n))
            .find(|p| p.is_file())
    })
}

/// The browser, driven by its command line, one process per page load.
struct Browser {
    bin: PathBuf,
    /// The page, as a `file://` URL without fragment.
    page: String,
    /// Scratch directory: the browser profile and the screenshots.
    tmp: PathBuf,
    /// Window size.
    window: (u32, u32),
}

impl Browser {
    fn run(&self, extra: &[String], fragment: &str) -> std::process::Output {
        let profile = self.tmp.join("profile");
        let mut cmd = Command::new(&self.bin);
        cmd.args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--force-color-profile=srgb",
            "--force-device-scale-factor=1",
            "--hide-scrollbars",
            "--no-first-run",
            "--allow-file-access-from-files",
        ])
        .arg(format!("--window-size={},{}", self.window.0, self.window.1))
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(format!("{}#{fragment}", self.page));
        let out = cmd
            .output()
            .unwrap_or_else(|e| panic!("cannot run {}: {e}", self.bin.display()));
        assert!(
            out.status.success(),
            "{} failed on #{fragment}: {}\n{}",
            self.bin.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
        out
    }

    /// The page's DOM once loaded at `#fragment`, checked to have set
    /// itself up without an error.
    fn dom(&self, fragment: &str) -> String {
        self.dom_with(&[], fragment)
    }

    /// [`Browser::dom`] once the page's asynchronous work (decoding the
    /// images' pixels) has had [`SETTLE_MS`] of virtual time.
    fn dom_settled(&self, fragment: &str) -> String {
        self.dom_with(&[settle()], fragment)
    }

    fn dom_with(&self, extra: &[String], fragment: &str) -> String {
        let mut args = vec!["--dump-dom".to_string()];
        args.extend(extra.iter().cloned());
        let out = self.run(&args, fragment);
        let dom = String::from_utf8(out.stdout).expect("DOM is UTF-8");
        let body = tag(&dom, "<body");
        assert_eq!(
            attr(body, "data-error"),
            None,
            "the page reports an error at #{fragment}"
        );
        assert_eq!(
            attr(body, "data-ready").as_deref(),
            Some("1"),
            "the page did not finish setting up at #{fragment}: {body}"
        );
        dom
    }

    /// A screenshot of the page at `#fragment`.
    fn screenshot(&self, fragment: &str, name: &str) -> RgbImage {
        self.screenshot_with(&[], fragment, name)
    }

    fn screenshot_with(&self, extra: &[String], fragment: &str, name: &str) -> RgbImage {
        let path = self.tmp.join(name);
        let mut args = vec![format!("--screenshot={}", path.display())];
        args.extend(extra.iter().cloned());
        self.run(&args, fragment);
        let img = image::open(&path)
            .unwrap_or_else(|e| panic!("screenshot {}: {e}", path.display()))
            .to_rgb8();
        assert_eq!(img.dimensions(), self.window, "screenshot size");
        img
    }
}

/// The opening tag that starts with `start` (e.g. `<body`, or
/// `id="viewport"` anywhere in it).
fn tag<'a>(dom: &'a str, start: &str) -> &'a str {
    let at = dom
        .find(start)
        .unwrap_or_else(|| panic!("no {start} in the DOM"));
    let open = dom[..=at].rfind('<').unwrap();
    let close = at + dom[at..].find('>').unwrap();
    &dom[open..=close]
}

/// An attribute of a tag, unescaped.
fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let at = tag.find(&key)? + key.len();
    let end = at + tag[at..].find('"')?;
    Some(
        tag[at..end]
            .replace("&quot;", "\"")
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&amp;", "&"),
    )
}

/// The numbers of a space-separated attribute.
fn numbers(tag: &str, name: &str) -> Vec<i64> {
    attr(tag, name)
        .unwrap_or_else(|| panic!("no {name} in {tag}"))
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect()
}

/// The viewer's box on the page: left, top, width, height.
fn viewer_box(dom: &str) -> (u32, u32, u32, u32) {
    let b = numbers(tag(dom, "id=\"viewport\""), "data-box");
    (b[0] as u32, b[1] as u32, b[2] as u32, b[3] as u32)
}

fn png(out: &Path, file: &str) -> RgbImage {
    let p = out.join("images").join(SCENE).join(file);
    image::open(&p)
        .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
        .to_rgb8()
}

fn differ(a: [u8; 3], b: [u8; 3], by: i32) -> bool {
    a.iter()
        .zip(&b)
        .any(|(&p, &q)| (p as i32 - q as i32).abs() > by)
}

/// The screenshot at the centre of pixel `(x + k, y)` of the view centred on
/// pixel `(x, y)` at [`ZOOM`]: pixel `(x, y)` covers the `ZOOM × ZOOM` screen
/// pixels around the viewer's centre, its neighbours follow at `ZOOM` steps.
fn shown(shot: &RgbImage, bx: (u32, u32, u32, u32), k: i32) -> [u8; 3] {
    let sx = (bx.0 + bx.2 / 2) as i32 + k * ZOOM as i32;
    let sy = bx.1 + bx.3 / 2;
    shot.get_pixel(sx as u32, sy).0
}

fn check_colour(got: [u8; 3], want: [u8; 3], what: &str) {
    assert!(
        !differ(got, want, TOLERANCE),
        "{what}: the screenshot shows {got:?}, the PNGs give {want:?} (tolerance {TOLERANCE})"
    );
}

/// A file URL of `path`, with the characters a URL cannot hold escaped.
fn file_url(path: &Path) -> String {
    let mut url = String::from("file://");
    for b in path.to_str().expect("UTF-8 path").bytes() {
        if b.is_ascii_alphanumeric() || b"/-_.~".contains(&b) {
            url.push(b as char);
        } else {
            url.push_str(&format!("%{b:02X}"));
        }
    }
    url
}

/// The body of the results table (the page's other tables are report.md's).
fn results_body(dom: &str) -> &str {
    let table = &dom[dom.find("id=\"results-table\"").expect("the results table")..];
    let tbody = &table[table.find("<tbody").expect("a table body")..];
    &tbody[..tbody.find("</tbody>").unwrap()]
}

/// The text of the element with `id` (no nested tags).
fn text_of<'a>(dom: &'a str, id: &str) -> &'a str {
    let t = tag(dom, &format!("id=\"{id}\""));
    let at = dom.find(t).unwrap() + t.len();
    &dom[at..at + dom[at..].find('<').unwrap()]
}

/// The number an element shows (`≥ ` dropped).
fn shown_number(dom: &str, id: &str) -> f64 {
    let t = text_of(dom, id);
    t.trim_start_matches("≥ ")
        .parse()
        .unwrap_or_else(|e| panic!("#{id} shows {t:?}: {e}"))
}

/// FLIP's error for a colour of its colour map (the map the report draws
/// `flip_<method>.png` with): the colour's index over 255.
fn decode_flip(rgb: [u8; 3]) -> f64 {
    let k = subcone_metrics::magma_lut()
        .into_iter()
        .position(|c| c == rgb)
        .unwrap_or_else(|| panic!("{rgb:?} is not a colour of FLIP's colour map"));
    k as f64 / 255.0
}

/// The class names of pixel `(x, y)` of the scene, from the summary.
fn classes_at(summary: &ReportSummary, x: u32, y: u32) -> String {
    let c = summary
        .classes
        .iter()
        .find(|c| c.scene == SCENE)
        .expect("classes of the scene");
    let i = (y * c.masks.width + x) as usize;
    report::classes::CLASSES
        .iter()
        .filter(|k| c.masks.mask(**k)[i])
        .map(|k| k.name())
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn report_page_in_a_browser() {
    let required = std::env::var("SUBCONE_REQUIRE_BROWSER").is_ok_and(|v| v == "1");
    let Some(bin) = find_browser() else {
        assert!(
            !required,
            "SUBCONE_REQUIRE_BROWSER=1 but no browser: install chromium or set SUBCONE_BROWSER"
        );
        subcone_scene::conformance::print_skipped(
            subcone_scene::conformance::SKIP_NO_BROWSER,
            "no chromium on the PATH; set SUBCONE_REQUIRE_BROWSER=1 to fail instead",
        );
        return;
    };
    let start = Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let summary = report::run(&ReportArgs {
        quick: true,
        no_paper_scenes: true,
        scenes: vec![SCENE.into(), "checker".into()],
        methods: vec!["noaa".into(), "sraa".into(), "ssaa4".into()],
        no_sweep: true,
        out: out.clone(),
        ..Default::default()
    })
    .expect("quick report");
    assert_eq!(summary.report_html, out.join("report.html"));
    let report_s = start.elapsed().as_secs_f64();
    let browser = Browser {
        bin,
        page: file_url(&summary.report_html),
        tmp: dir.path().join("browser"),
        window: WINDOW,
    };
    let (width, height) = report::QUICK_SIZE;

    // (1) One method alone, zoomed on a pixel where it differs from the
    // reference and NoAA: the viewer's centre shows that pixel of its PNG.
    let (sraa, reference, noaa) = (
        png(&out, "sraa.png"),
        png(&out, "reference.png"),
        png(&out, "noaa.png"),
    );
    let (x, y) = (8..height - 8)
        .flat_map(|y| (8..width - 8).map(move |x| (x, y)))
        .find(|&(x, y)| {
            let p = sraa.get_pixel(x, y).0;
            differ(p, reference.get_pixel(x, y).0, 6) && differ(p, noaa.get_pixel(x, y).0, 6)
        })
        .expect("a pixel where sraa differs from the reference and noaa");
    let fragment = format!("scene={SCENE}&a=sraa&b=reference&mode=a&zoom={ZOOM}&x={x}&y={y}");
    let dom = browser.dom(&fragment);
    let body = tag(&dom, "<body");
    assert_eq!(
        attr(body, "data-state").unwrap(),
        format!("scene={SCENE}&a=sraa&b=reference&mode=a&split=0.5&zoom={ZOOM}&x={x}&y={y}"),
        "the page reads its state from the fragment and writes it back"
    );
    let info = tag(&dom, "id=\"pixel-info\"");
    assert_eq!(attr(info, "data-x"), Some(x.to_string()));
    assert_eq!(attr(info, "data-y"), Some(y.to_string()));
    assert_eq!(
        attr(info, "data-classes").unwrap(),
        classes_at(&summary, x, y),
        "the edge classes of the centre pixel"
    );
    let bx = viewer_box(&dom);
    let shot = browser.screenshot(&fragment, "method.png");
    let want = sraa.get_pixel(x, y).0;
    for (dx, dy) in [(0, 0), (-3, -3), (3, 3), (-3, 3), (3, -3)] {
        let sx = (bx.0 + bx.2 / 2) as i32 + dx;
        let sy = (bx.1 + bx.3 / 2) as i32 + dy;
        let got = shot.get_pixel(sx as u32, sy as u32).0;
        check_colour(
            got,
            want,
            &format!("sraa pixel ({x}, {y}) at screen ({sx}, {sy})"),
        );
    }

    // (2) The split at the middle, NoAA (A) against its FLIP map (B): a
    // quarter of the viewer in from the left shows A, from the right B, on
    // a row where A and B differ at both places.
    let flip = png(&out, "flip_noaa.png");
    let k = (bx.2 / 4 / ZOOM) as i32;
    let cx = width / 2;
    let (left, right) = (cx - k as u32, cx + k as u32);
    let row = (0..height)
        .find(|&y| {
            differ(noaa.get_pixel(left, y).0, flip.get_pixel(left, y).0, 6)
                && differ(noaa.get_pixel(right, y).0, flip.get_pixel(right, y).0, 6)
        })
        .expect("a row where NoAA and its FLIP map differ");
    let fragment =
        format!("scene={SCENE}&a=noaa&b=flip_noaa&mode=split&split=0.5&zoom={ZOOM}&x={cx}&y={row}");
    let shot = browser.screenshot(&fragment, "split.png");
    check_colour(
        shown(&shot, bx, -k),
        noaa.get_pixel(left, row).0,
        &format!("left of the split, layer A (noaa) at ({left}, {row})"),
    );
    check_colour(
        shown(&shot, bx, k),
        flip.get_pixel(right, row).0,
        &format!("right of the split, layer B (flip_noaa) at ({right}, {row})"),
    );

    // (3) Sorting from the fragment: the table's rows in the column's order,
    // missing values last, ties in the results' order.
    for (col, desc) in [("flip_mean", true), ("ms_median", false)] {
        let dir = if desc { "desc" } else { "asc" };
        let dom = browser.dom(&format!("scene={SCENE}&sort={col}:{dir}"));
        let tbody = results_body(&dom);
        let shown: Vec<String> = tbody
            .split("<tr ")
            .skip(1)
            .map(|tr| attr(&format!(" {tr}"), "data-key").expect("row key"))
            .collect();
        let mut rows: Vec<&report::ResultRow> =
            summary.rows.iter().filter(|r| r.scene == SCENE).collect();
        let value = |r: &report::ResultRow| match col {
            "flip_mean" => r.flip_mean,
            _ => Some(r.ms_median),
        };
        rows.sort_by(|a, b| match (value(a), value(b)) {
            (Some(p), Some(q)) if desc => q.total_cmp(&p),
            (Some(p), Some(q)) => p.total_cmp(&q),
            (p, q) => p.is_none().cmp(&q.is_none()),
        });
        let want: Vec<String> = rows
            .iter()
            .map(|r| format!("{}/{}", r.method, r.backend))
            .collect();
        assert!(want.len() >= 3, "too few rows to check the order");
        assert_eq!(shown, want, "rows sorted by {col}:{dir}");
    }

    // (5) The values under the cursor: A's and B's RGB from their PNGs; the
    // FLIP and 1 − SSIM shown equal the maps' decoded values (to the printed
    // digits), which are within the maps' quantisation of the errors the
    // report measured.
    let fragment = format!("scene={SCENE}&a=sraa&b=reference&mode=a&zoom={ZOOM}&x={x}&y={y}");
    let dom = browser.dom_settled(&fragment);
    let values = tag(&dom, "id=\"values\"");
    assert_eq!(
        attr(values, "data-state").as_deref(),
        Some("ready"),
        "the values of ({x}, {y}) are not shown: {values}"
    );
    let rgb = |p: [u8; 3]| format!("{} {} {}", p[0], p[1], p[2]);
    assert_eq!(
        attr(values, "data-rgb-a"),
        Some(rgb(sraa.get_pixel(x, y).0)),
        "A's RGB"
    );
    assert_eq!(
        text_of(&dom, "rgb-a"),
        rgb(sraa.get_pixel(x, y).0),
        "A's RGB on screen"
    );
    assert_eq!(
        text_of(&dom, "rgb-b"),
        rgb(reference.get_pixel(x, y).0),
        "B's RGB on screen"
    );
    let flip_png = png(&out, "flip_sraa.png");
    let decoded = decode_flip(flip_png.get_pixel(x, y).0);
    let on_screen = shown_number(&dom, "flip-a");
    assert!(
        (on_screen - decoded).abs() <= PRINTED + 1e-9,
        "FLIP at ({x}, {y}): the page shows {on_screen}, flip_sraa.png decodes to {decoded}"
    );
    let to_rgb8 = |i: &RgbImage| subcone_metrics::Rgb8 {
        width,
        height,
        data: i.as_raw().clone(),
    };
    let measured = subcone_metrics::flip(&to_rgb8(&reference), &to_rgb8(&sraa))
        .unwrap()
        .map[(y * width + x) as usize] as f64;
    assert!(
        (decoded - measured).abs() <= FLIP_STEP / 2.0 + 1e-6,
        "FLIP at ({x}, {y}): decoded {decoded}, measured {measured}"
    );
    let grey = png(&out, "ssim_sraa.png").get_pixel(x, y).0[0];
    let ssim_decoded = f64::from(grey) * SSIM_STEP;
    let on_screen = shown_number(&dom, "ssim-a");
    assert!(
        (on_screen - ssim_decoded).abs() <= PRINTED + 1e-9,
        "1 − SSIM at ({x}, {y}): the page shows {on_screen}, ssim_sraa.png decodes to {ssim_decoded}"
    );
    let dssim = 1.0
        - subcone_metrics::ssim::ssim(&to_rgb8(&reference), &to_rgb8(&sraa))
            .unwrap()
            .map[(y * width + x) as usize] as f64;
    if dssim < 0.5 {
        assert!(
            (ssim_decoded - dssim).abs() <= SSIM_STEP / 2.0 + 1e-6,
            "1 − SSIM at ({x}, {y}): decoded {ssim_decoded}, measured {dssim}"
        );
    }
    // The line on what the images are: offset 0 at the quality size, where
    // the table's errors are means over the offsets.
    let n = summary
        .rows
        .iter()
        .find(|r| r.scene == SCENE && r.method.to_string() == "sraa")
        .expect("the sraa row")
        .errors_at
        .len();
    let note = text_of(&dom, "images-note");
    assert_eq!(
        attr(tag(&dom, "id=\"images-note\""), "data-offsets"),
        Some(n.to_string()),
        "the offsets the errors are means over"
    );
    assert!(
        note.starts_with(&format!(
            "Images: camera offset 0 (the scene's camera) at the quality size, {width}×{height}; "
        )) && (n < 2 || note.contains(&format!("means over {n} camera offsets"))),
        "{note}"
    );
    // Every label names the kind of image; a FLIP map and a 1 − SSIM map
    // side by side show both colour bars, a render none.
    assert!(text_of(&dom, "label-a").ends_with("sraa · render"));
    for kind in [
        "sraa · render",
        "sraa · FLIP map",
        "sraa · 1 − SSIM map",
        "· render</option>",
    ] {
        assert!(dom.contains(kind), "no {kind:?} in the layer lists");
    }
    assert_eq!(
        attr(tag(&dom, "id=\"bars\""), "data-shown").as_deref(),
        Some("")
    );
    let dom = browser.dom(&format!("scene={SCENE}&a=flip_sraa&b=ssim_sraa&mode=split"));
    assert_eq!(
        attr(tag(&dom, "id=\"bars\""), "data-shown").as_deref(),
        Some("flip ssim"),
        "colour bars of a FLIP and a 1 − SSIM map"
    );

    // (6) The difference modes at scale 4: the viewer's centre shows
    // 4 |A − B|, and 128 + 4 (A − B) / 2, of the PNGs' pixel, per channel,
    // with the colour bar of that scaling: black to white over 0 to 255 / 4
    // levels, and −256 / 4 to 254 / 4.
    let (a, b) = (sraa.get_pixel(x, y).0, reference.get_pixel(x, y).0);
    let scale = 4;
    for (mode, f, scaling, ends) in [
        (
            "diff",
            (|d: i32, k: i32| k * d.abs()) as fn(i32, i32) -> i32,
            "|A − B| × 4",
            ["0", "≥ 63.75"],
        ),
        (
            "signed",
            |d: i32, k: i32| (128.0 + f64::from(k * d) / 2.0).round() as i32,
            "128 + 4 (A − B) / 2",
            ["≤ −64", "≥ +63.5"],
        ),
    ] {
        let want: [u8; 3] = std::array::from_fn(|c| {
            f(i32::from(a[c]) - i32::from(b[c]), scale).clamp(0, 255) as u8
        });
        let fragment = format!(
            "scene={SCENE}&a=sraa&b=reference&mode={mode}&scale={scale}&zoom={ZOOM}&x={x}&y={y}"
        );
        let dom = browser.dom_settled(&fragment);
        assert_eq!(
            attr(tag(&dom, "id=\"diff-canvas\""), "data-ready").as_deref(),
            Some("1"),
            "the {mode} mode draws no difference"
        );
        assert_eq!(
            attr(tag(&dom, "id=\"bars\""), "data-shown").as_deref(),
            Some(mode),
            "the colour bar of the {mode} mode"
        );
        let bar = tag(&dom, &format!("id=\"bar-{mode}\""));
        assert!(!bar.contains(" hidden"), "{bar}");
        let bar_html = &dom[dom.find(bar).unwrap()..];
        let bar_html = &bar_html[..bar_html.find("</div>").unwrap()];
        for (class, value) in ["bar-lo", "bar-hi"].into_iter().zip(ends) {
            assert!(
                bar_html.contains(&format!("<span class=\"{class}\">{value}</span>")),
                "the {mode} bar's {class} is not {value}: {bar_html}"
            );
        }
        assert!(
            bar_html.contains(scaling),
            "the {mode} bar names {scaling:?}: {bar_html}"
        );
        let shot = browser.screenshot_with(&[settle()], &fragment, &format!("{mode}.png"));
        check_colour(
            shown(&shot, bx, 0),
            want,
            &format!("{mode} ×{scale} of sraa {a:?} and reference {b:?} at ({x}, {y})"),
        );
    }

    // (7) The table: a mark on the methods of each of the scene's Pareto
    // fronts (FLIP and 1 − SSIM against time), a verdict cell for every
    // method but NoAA, and report.md's answer and verdict sections on the
    // page.
    let dom = browser.dom(&format!("scene={SCENE}"));
    let rows: Vec<&report::ResultRow> = summary.rows.iter().filter(|r| r.scene == SCENE).collect();
    // The answer section's fronts (one backend here), without the rows it
    // leaves out.
    let all: Vec<&report::ResultRow> = summary.rows.iter().collect();
    let left_out = report::answer::exclusions(&all);
    let fronts = [
        (report::classes::Metric::Flip, "pareto_flip", "◆ FLIP"),
        (report::classes::Metric::Ssim, "pareto_ssim", "◆ SSIM"),
    ]
    .map(|(metric, column, mark)| {
        (
            report::answer::front(&rows, &left_out, metric),
            column,
            mark,
        )
    });
    let tbody = results_body(&dom);
    for tr in tbody.split("<tr ").skip(1) {
        let key = attr(&format!(" {tr}"), "data-key").unwrap();
        let r = rows
            .iter()
            .find(|r| format!("{}/{}", r.method, r.backend) == key)
            .unwrap();
        for (front, column, mark) in &fronts {
            let on_front = front.iter().any(|p| p.method == r.method);
            assert_eq!(
                tr.contains(&format!("data-column=\"{column}\">{mark}<")),
                on_front,
                "{column} mark of {key}"
            );
        }
        let verdict = tr
            .split("data-column=\"verdict_flip\">")
            .nth(1)
            .map(|c| &c[..c.find("</td>").unwrap()])
            .unwrap_or("");
        assert_eq!(
            verdict.contains(" · "),
            r.method.to_string() != "noaa",
            "FLIP verdict of {key}: {verdict:?}"
        );
    }
    for (front, column, _) in &fronts {
        assert!(
            front.len() >= 2,
            "a {column} front of one point checks little"
        );
    }
    let body = tag(&dom, "<body");
    assert_eq!(
        attr(body, "data-missing-sections"),
        None,
        "sections missing"
    );
    let sections = attr(body, "data-sections").unwrap();
    assert!(
        sections.ends_with("|Verdicts at a glance") && !sections.starts_with('|'),
        "the answer and the verdicts: {sections}"
    );
    assert!(dom.contains("<section class=\"md\" data-heading=\"Verdicts at a glance\">"));
    if summary.motion.ran {
        let motion = tag(&dom, "id=\"motion\"");
        assert!(!motion.contains(" hidden"), "the motion section is hidden");
        assert!(text_of(&dom, "motion-caption").contains("left to right noaa"));
    }

    // (8) At a laptop's window, the answer whole without scrolling: the last
    // row of the picks and of the fronts (both columns, FLIP and SSIM)
    // within the window; on the report's page, and on one whose answer has
    // the quick report's number of rows (6 picks, 9 scenes' fronts) and
    // longer cells than it writes (`longer_cell`).
    let page = std::fs::read_to_string(&summary.report_html).unwrap();
    let long = out.join("report-long-answer.html");
    std::fs::write(&long, longer_answer(&page)).unwrap();
    for (file, rows) in [(&summary.report_html, None), (&long, Some((6, 9)))] {
        let laptop = Browser {
            bin: browser.bin.clone(),
            page: file_url(file),
            tmp: dir.path().join("laptop"),
            window: LAPTOP,
        };
        let dom = laptop.dom(&format!("scene={SCENE}"));
        let answer = &dom[dom.find("<div id=\"answer\"").expect("the answer")..];
        let answer = &answer[..answer
            .find("<nav id=\"scenes\"")
            .expect("the scene buttons")];
        assert_eq!(
            attr(tag(answer, "<div"), "data-fit").as_deref(),
            Some("1280 800"),
            "the answer is fitted to the window"
        );
        let tables: Vec<&str> = answer
            .match_indices("<table")
            .map(|(at, _)| &answer[at..])
            .collect();
        assert!(tables.len() >= 2, "the picks and the fronts");
        for (k, t) in tables.iter().enumerate() {
            let end = numbers(tag(t, "<table"), "data-last-row");
            assert!(
                end[0] <= i64::from(LAPTOP.0) && end[1] <= i64::from(LAPTOP.1),
                "{}: the last row of the answer's table {k} ends at {end:?}, out of the {LAPTOP:?} window",
                file.display()
            );
            if let (Some((picks, fronts)), 0..=1) = (rows, k) {
                let body = &t[..t.find("</table>").unwrap()];
                let n = body.matches("<tr>").count() - 1;
                assert_eq!(n, if k == 0 { picks } else { fronts }, "rows of table {k}");
            }
        }
        let fronts = &tables[1][..tables[1].find("</thead>").unwrap()];
        assert!(
            fronts.contains("FLIP front") && fronts.contains("SSIM front"),
            "the fronts of both metrics: {fronts}"
        );
        let name = format!(
            "laptop-{}.png",
            if rows.is_some() { "long" } else { "page" }
        );
        laptop.screenshot(&format!("scene={SCENE}"), &name);
    }

    // (4) Every control changes the view (the page's own self-test works
    // them as a user would), and a fragment of nonsense falls back to
    // defaults without an error.
    let dom = browser.dom(&format!("scene={SCENE}&selftest=1"));
    assert_eq!(
        attr(tag(&dom, "<body"), "data-selftest").as_deref(),
        Some("pass"),
        "the page's self-test did not pass"
    );
    let dom = browser.dom("scene=nowhere&a=nothing&zoom=99&split=7&sort=nope:up");
    let state = attr(tag(&dom, "<body"), "data-state").unwrap();
    assert!(
        state.contains("zoom=16") && state.contains("split=1") && !state.contains("sort="),
        "invalid values replaced or clamped: {state}"
    );
    println!(
        "report.html checked in {}: report {report_s:.1} s, browser {:.1} s",
        browser.bin.display(),
        start.elapsed().as_secs_f64() - report_s
    );
}

/// `page` with a longer answer: its first section's tables with at least as
/// many rows as the quick report's answer (6 picks, the fronts of 9
/// scenes; rows repeated) and longer cells ([`longer_cell`]).
fn longer_answer(page: &str) -> String {
    let open = "<script type=\"application/json\" id=\"report-data\">";
    let at = page.find(open).expect("the page's data") + open.len();
    let end = at + page[at..].find("</script>").unwrap();
    let mut data: serde_json::Value = serde_json::from_str(&page[at..end]).expect("JSON data");
    let html = data["sections"][0]["html"]
        .as_str()
        .expect("the answer")
        .to_string();
    let mut longer = String::new();
    let mut rest = html.as_str();
    for want in [6, 9] {
        let Some(from) = rest.find("<tbody>") else {
            break;
        };
        let from = from + "<tbody>".len();
        let to = rest.find("</tbody>").unwrap();
        longer.push_str(&rest[..from]);
        let rows: Vec<String> = rest[from..to]
            .split("</tr>")
            .filter(|r| r.contains("<tr>"))
            .map(|r| longer_row(r.trim()))
            .collect();
        for i in 0..want.max(rows.len()) {
            longer.push_str(&rows[i % rows.len()]);
            longer.push('\n');
        }
        longer.push_str("</tbody>");
        rest = &rest[to + "</tbody>".len()..];
    }
    longer.push_str(rest);
    data["sections"][0]["html"] = serde_json::Value::String(longer);
    let data = data.to_string().replace('<', "\\u003c");
    format!("{}{data}{}", &page[..at], &page[end..])
}

/// A table row `<tr><td>…</td>…` of the answer with each cell longer.
fn longer_row(row: &str) -> String {
    let mut out = String::new();
    let cells: Vec<&str> = row.split("</td>").collect();
    for (i, piece) in cells.iter().enumerate() {
        if i + 1 == cells.len() {
            out.push_str(piece);
            break;
        }
        let open = piece.rfind("<td").expect("a cell");
        let gt = open + piece[open..].find('>').unwrap() + 1;
        out.push_str(&piece[..gt]);
        out.push_str(&longer_cell(&piece[gt..]));
        out.push_str("</td>");
    }
    out.push_str("</tr>");
    out
}

/// A cell longer than the answer writes it: a front's steps (`… ms · …`)
/// each marked " (within noise)" and repeated to 450 characters and more
/// (the quick report's fronts have some 360 on average, 550 at most), a
/// pick (`name (…, n/m)` and what follows) with a further runner-up and
/// margin.
fn longer_cell(cell: &str) -> String {
    if cell.contains(" ms") {
        let steps: Vec<String> = cell
            .split(" → ")
            .map(|s| format!("{s} (within noise)"))
            .collect();
        let mut out: Vec<&str> = Vec::new();
        while out.iter().map(|s| s.chars().count() + 3).sum::<usize>() < 450 {
            out.push(&steps[out.len() % steps.len()]);
        }
        out.join(" → ")
    } else if cell.contains('(') && cell.contains('/') {
        format!("{cell}; runner-up ssaa4 (0.61, 2/3), margin 7 %, within noise")
    } else {
        cell.to_string()
    }
}

/// The committed screenshot is of the committed page: the build recorded
/// beside it by `scripts/report-screenshot` is the one `docs/quick/report.html`
/// names. Regenerating the quick report without the screenshot fails here.
#[test]
fn the_committed_screenshot_is_of_the_committed_page() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/quick");
    let page = std::fs::read_to_string(dir.join("report.html")).expect("docs/quick/report.html");
    let meta = tag(&page, "name=\"subcone-code\"");
    let code = attr(meta, "content").expect("the page names its build");
    let shot = std::fs::read_to_string(dir.join("report-html.build"))
        .expect("docs/quick/report-html.build: run scripts/report-screenshot");
    assert_eq!(
        shot.trim(),
        code,
        "docs/quick/report-html.png is of build {}, the page is of build {code}: run \
         scripts/report-screenshot",
        shot.trim()
    );
    assert!(dir.join("report-html.png").is_file());
}
