//! `report.html` in a real browser: a small quick report (two scenes, three
//! methods) opened in headless Chromium, put into a state by its URL
//! fragment; the screenshot's pixels and the dumped DOM are checked against
//! the report's own images, rows and edge classes.
//!
//! Without a browser the test skips with a message, unless
//! `SUBCONE_REQUIRE_BROWSER=1` (CI), where it fails. `SUBCONE_BROWSER` names
//! the browser binary; by default the first of `chromium`,
//! `chromium-browser` and `google-chrome` on the `PATH`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use image::RgbImage;
use subcone::report::{self, ReportArgs, ReportSummary};

/// Browser window size in CSS pixels (and screenshot pixels: scale 1).
const WINDOW: (u32, u32) = (1100, 900);
/// Largest difference per 8-bit channel between a screenshot pixel and the
/// image pixel it shows: the page draws the PNG unscaled in colour (sRGB
/// profile forced) and by nearest neighbour, so any difference is the
/// browser's rounding.
const TOLERANCE: i32 = 2;
/// The scene the checks look at and the zoom they use.
const SCENE: &str = "cornell";
const ZOOM: u32 = 8;

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
        .arg(format!("--window-size={},{}", WINDOW.0, WINDOW.1))
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
        let out = self.run(&["--dump-dom".into()], fragment);
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
        let path = self.tmp.join(name);
        self.run(&[format!("--screenshot={}", path.display())], fragment);
        let img = image::open(&path)
            .unwrap_or_else(|e| panic!("screenshot {}: {e}", path.display()))
            .to_rgb8();
        assert_eq!(img.dimensions(), WINDOW, "screenshot size");
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
        "{what}: the screenshot shows {got:?}, the PNG has {want:?} (tolerance {TOLERANCE})"
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
        let tbody = &dom[dom.find("<tbody").expect("a table body")..];
        let tbody = &tbody[..tbody.find("</tbody>").unwrap()];
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
