//! The quick report end to end: every method on every built-in paper scene at
//! 96x64, into a temporary directory.

use std::path::Path;
use std::time::Instant;

use subcone_report::{self as report, ReportArgs};

const REQUIRED: [&str; 16] = [
    "scene",
    "method",
    "backend",
    "width",
    "height",
    "runs",
    "ms_median",
    "ms_min",
    "ms_max",
    "ratio_to_noaa",
    "flip_mean",
    "psnr_db",
    "edge_flip_mean",
    "samples_per_pixel",
    "rays_per_pixel",
    "buffer_mib",
];

fn csv_rows(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).expect("results.csv");
    let mut lines = text.lines();
    let header = split_csv(lines.next().expect("header"));
    let rows = lines.map(split_csv).collect();
    (header, rows)
}

/// One CSV line into fields: quoted fields may hold commas and doubled
/// quotes (the adapter names do), no field holds a line break.
fn split_csv(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                fields.last_mut().unwrap().push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(String::new()),
            (c, _) => fields.last_mut().unwrap().push(c),
        }
    }
    fields
}

const CLASSES: [&str; 6] = [
    "silhouette",
    "crease",
    "shadow",
    "texture",
    "reflection",
    "flat",
];

/// The claims table of the report, restated: the classes each method claims.
fn claimed(method: &str) -> Vec<&'static str> {
    // A hybrid claims what its traced method claims: only the way its
    // primary samples find their triangles differs.
    let method = method.strip_suffix("-hybrid").unwrap_or(method);
    let base = method.strip_suffix("-delayed").unwrap_or(method);
    let (base, mat) = match base.strip_suffix("+mat") {
        Some(b) => (b, true),
        None => (base, false),
    };
    let base = base.strip_suffix("-paper").unwrap_or(base);
    let mut c = match base {
        "sraa" => vec!["silhouette", "crease"],
        "sraa-rt" => vec!["silhouette", "crease", "shadow", "reflection"],
        "ctss" | "ctss-r" => vec!["silhouette"],
        "ctss+edges" => vec!["silhouette", "crease"],
        // The post-process rows: FXAA, SMAA and the box filter of
        // `examples/box_filter.rs`.
        "fxaa" | "smaa" | "box" => vec!["silhouette", "crease", "shadow", "texture"],
        b if b.starts_with("ssaa") => CLASSES[..5].to_vec(),
        _ => vec![],
    };
    if mat && !c.contains(&"texture") {
        c.push("texture");
    }
    c
}

/// The verdict a class gets from its paired per-offset errors `pairs`
/// (the method's, NoAA's) and its fewest pixels, restated from the rules
/// section: too few pixels under 64; else, per offset, a win or a loss
/// (`call`), and the class beats (wins everywhere) or loses (loses
/// everywhere); on one side of NoAA at every offset, it leans that way
/// (a call at some offset) or ties on that side (none); otherwise it ties
/// (no call anywhere) or is a tie within noise. Flat never "leans better"
/// (a better flat offset holds).
fn outcome(
    pairs: &[(f64, f64)],
    px: u64,
    flat: bool,
    call: impl Fn(f64, f64) -> Option<bool>,
) -> &'static str {
    let calls: Vec<Option<bool>> = pairs.iter().map(|&(a, n)| call(a, n)).collect();
    let no_call = calls.iter().all(|c| c.is_none());
    if px < 64 {
        "few"
    } else if calls.iter().all(|c| *c == Some(true)) {
        "win"
    } else if calls.iter().all(|c| *c == Some(false)) {
        "loss"
    } else if !flat && pairs.iter().all(|&(a, n)| a < n) {
        if no_call {
            "tie-better"
        } else {
            "better"
        }
    } else if pairs.iter().all(|&(a, n)| a > n) {
        if no_call {
            "tie-worse"
        } else {
            "worse"
        }
    } else if no_call {
        "tie"
    } else {
        "noise"
    }
}

/// Every non-NoAA row with class errors has a verdict line per metric in
/// report.md whose words follow from the per-offset errors in
/// `results.json` (`errors_at`), paired with NoAA's by offset, by the rules
/// section restated here: at one offset a claimed class is won when the
/// error is at most 0.95 × NoAA's and lost when at least 1/0.95 × (under
/// SSIM also by at least the 0.0015 floor either way); flat holds at an
/// offset when at most 1.02 × NoAA's (or, under SSIM, higher by less than
/// the floor). FLIP's fields are `flip_<class>`, SSIM's `dssim_<class>`
/// (1 − SSIM). The whole-image and class columns are the means over the
/// offsets.
fn check_verdicts(results: &serde_json::Value, md: &str) {
    let rows = results.as_array().unwrap();
    let get = |r: &serde_json::Value, k: &str| r[k].as_f64();
    let mut checked = 0;
    let mut words = std::collections::BTreeMap::<&str, usize>::new();
    for r in rows {
        let (scene, method, backend) = (
            r["scene"].as_str().unwrap(),
            r["method"].as_str().unwrap(),
            r["backend"].as_str().unwrap(),
        );
        let Some(at) = r["errors_at"].as_array() else {
            continue;
        };
        assert_eq!(
            at.len(),
            4,
            "{scene} {method}: the quick report measures 4 offsets"
        );
        assert_eq!(r["offsets"].as_u64(), Some(4));
        // The means over the offsets are the columns.
        let mean = |k: &str| at.iter().map(|e| e[k].as_f64().unwrap()).sum::<f64>() / 4.0;
        assert!((mean("flip") - get(r, "flip_mean").unwrap()).abs() < 1e-9);
        assert!((mean("ssim") - get(r, "ssim_mean").unwrap()).abs() < 1e-9);
        if method == "noaa" {
            continue;
        }
        let noaa = rows
            .iter()
            .find(|n| n["scene"] == scene && n["method"] == "noaa" && n["backend"] == backend)
            .unwrap_or_else(|| panic!("{scene}: no noaa row on {backend}"));
        let noaa_at = noaa["errors_at"].as_array().unwrap();
        // The verdict lines of this scene's section.
        let section = md
            .split("\n## ")
            .find(|s| s.starts_with(&format!("{scene}\n")))
            .unwrap_or_else(|| panic!("no section for {scene}"));
        for (metric, column, floor) in [("FLIP", "flip", 0.0), ("SSIM", "dssim", 0.0015)] {
            let prefix = format!("- **{method}** ({backend}, {metric}): ");
            let line = section
                .lines()
                .find(|l| l.starts_with(&prefix))
                .unwrap_or_else(|| {
                    panic!("{scene}: no {metric} verdict line for {method} on {backend}")
                });
            let parts: Vec<&str> = line
                .trim_start_matches(&prefix)
                .trim_end_matches('.')
                .split("; ")
                .collect();
            // The classes a part lists after `head`, e.g. "beats NoAA on ".
            let listed = |head: &str| -> Vec<String> {
                let mut v: Vec<String> = parts
                    .iter()
                    .filter_map(|p| p.strip_prefix(head))
                    .flat_map(|p| p.split("), "))
                    .map(|c| c.split(' ').next().unwrap().to_string())
                    .collect();
                v.sort();
                v
            };
            let lost: Vec<String> = {
                let mut v: Vec<String> = parts
                    .iter()
                    .filter_map(|p| p.strip_prefix("loses by "))
                    .map(|p| {
                        let (_, rest) = p.split_once(" on ").unwrap();
                        rest.split(' ').next().unwrap().to_string()
                    })
                    .collect();
                v.sort();
                v
            };
            let pairs = |c: &str| -> (Vec<(f64, f64)>, u64) {
                let key = format!("{column}_{c}");
                // Flat is each metric's own (beyond its reach).
                let pk = if c == "flat" && metric == "SSIM" {
                    "px_ssim_flat".to_string()
                } else {
                    format!("px_{c}")
                };
                let pairs = at
                    .iter()
                    .zip(noaa_at)
                    .filter_map(|(a, n)| Some((a[&key].as_f64()?, n[&key].as_f64()?)))
                    .collect();
                let px = at
                    .iter()
                    .zip(noaa_at)
                    .map(|(a, n)| a[&pk].as_u64().unwrap().min(n[&pk].as_u64().unwrap()))
                    .min()
                    .unwrap();
                (pairs, px)
            };
            let mut expect: std::collections::BTreeMap<&str, Vec<String>> = Default::default();
            for c in claimed(method) {
                let (p, px) = pairs(c);
                if p.is_empty() {
                    continue;
                }
                let o = outcome(&p, px, false, |a, n| {
                    if a <= 0.95 * n && n - a >= floor {
                        Some(true)
                    } else if a >= n / 0.95 && a - n >= floor && a > n {
                        Some(false)
                    } else {
                        None
                    }
                });
                expect.entry(o).or_default().push(c.to_string());
                *words.entry(o).or_default() += 1;
            }
            for (o, head) in [
                ("win", "beats NoAA on "),
                (
                    "better",
                    "better than NoAA at every offset, not always by the margin, on ",
                ),
                (
                    "tie-better",
                    "ties (consistently better, within the margin) on ",
                ),
                ("tie", "ties NoAA on "),
                (
                    "tie-worse",
                    "ties (consistently worse, within the margin) on ",
                ),
                (
                    "worse",
                    "worse than NoAA at every offset, not always by the margin, on ",
                ),
                ("noise", "tie (within noise) on "),
                ("few", "too few pixels for a verdict on "),
            ] {
                let mut e = expect.get(o).cloned().unwrap_or_default();
                e.sort();
                assert_eq!(listed(head), e, "{o}: {line}");
            }
            let mut e = expect.get("loss").cloned().unwrap_or_default();
            e.sort();
            assert_eq!(lost, e, "losses: {line}");
            let (p, px) = pairs("flat");
            if !p.is_empty() {
                let o = outcome(&p, px, true, |a, n| Some(a <= 1.02 * n || a - n < floor));
                let word = match o {
                    "win" => "flat: holds",
                    "loss" => "flat: loses by ",
                    "few" => "flat: too few pixels",
                    "worse" => "flat: worse at every offset, not always by the margin",
                    _ => "flat: tie (within noise)",
                };
                assert!(line.contains(word), "{word}: {line}");
            }
            assert!(!line.contains("does not beat"), "{line}");
            checked += 1;
        }
    }
    assert!(checked > 40, "only {checked} verdict lines checked");
    println!("class verdicts re-derived: {words:?}");
}

fn nonempty(path: &Path) {
    let len = std::fs::metadata(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .len();
    assert!(len > 0, "{} is empty", path.display());
}

/// The 3×3 box filter of `subcone-report/examples/box_filter.rs`: `cargo test` builds the
/// examples before it runs any test; a narrower run builds it here.
fn box_filter() -> std::path::PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().parent().unwrap().join("examples");
    let bin = dir.join(format!("box_filter{}", std::env::consts::EXE_SUFFIX));
    if !bin.exists() {
        let status = std::process::Command::new(env!("CARGO"))
            .args(["build", "-p", "subcone-report", "--example", "box_filter"])
            .status()
            .expect("cargo build -p subcone-report --example box_filter");
        assert!(status.success());
    }
    assert!(bin.exists(), "{} was not built", bin.display());
    bin
}

/// `--post-process box=…`, the path quoted for the shell-like split.
fn box_post_process() -> String {
    format!("box='{}' {{color}} {{output}}", box_filter().display())
}

#[test]
fn quick_report_on_every_paper_scene() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let args = ReportArgs {
        quick: true,
        out: out.clone(),
        post_processes: vec![box_post_process()],
        ..Default::default()
    };
    // The SMAA rows need an adapter: without one that part skips, saying so.
    let gpu = subcone_wgpu::test_util::gpu_or_skip("the SMAA rows").is_some();
    let start = Instant::now();
    let summary = report::run(&args).expect("quick report");
    println!(
        "quick report: {:.1} s\n{summary}",
        start.elapsed().as_secs_f64()
    );

    // "Where SRAA pays" runs in the default (full) report and with
    // --sraa-sweep, never in the quick report.
    assert!(!summary.ao_sweep.ran && summary.ao_sweep.rows.is_empty());
    let md_text = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(!md_text.contains("## Where SRAA pays"));

    // Every paper scene that loads has rows; the triangle scenes always load.
    let (loaded, _) = report::paper_scenes();
    assert!(loaded.len() >= 3, "cornell, checker and atrium must load");
    for (name, _) in &loaded {
        assert!(
            summary.rows.iter().any(|r| &r.scene == name),
            "no results for scene {name}"
        );
    }

    // results.csv: required columns, a pass column, one row per result.
    let (header, rows) = csv_rows(&out.join("results.csv"));
    for c in REQUIRED {
        assert!(
            header.iter().any(|h| h == c),
            "results.csv lacks column {c}"
        );
    }
    assert!(
        header
            .iter()
            .any(|h| h.starts_with("ms_") && h != "ms_median" && h != "ms_min" && h != "ms_max"),
        "results.csv has no per-pass column: {header:?}"
    );
    assert_eq!(rows.len(), summary.rows.len());
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (scene, method, flip) = (col("scene"), col("method"), col("flip_mean"));
    for r in &rows {
        assert_eq!(r.len(), header.len(), "ragged row {r:?}");
    }

    // FLIP falls from NoAA to SSAA16 on every scene (as written in the CSV).
    for (name, _) in &loaded {
        let get = |m: &str| -> f64 {
            rows.iter()
                .find(|r| &r[scene] == name && r[method] == m)
                .unwrap_or_else(|| panic!("no {m} row for {name}"))[flip]
                .parse()
                .unwrap_or_else(|_| panic!("no FLIP for {m} on {name}"))
        };
        let (noaa, ssaa16) = (get("noaa"), get("ssaa16"));
        // The post-process baselines have their rows on every scene: SMAA
        // wherever a GPU adapter exists, and always in CI; the outside
        // command's everywhere.
        get("fxaa");
        let boxed = get("box");
        assert!((0.0..1.0).contains(&boxed), "{name}: box FLIP {boxed}");
        if gpu {
            let smaa = get("smaa");
            assert!((0.0..1.0).contains(&smaa), "{name}: smaa FLIP {smaa}");
        }
        assert!(
            ssaa16 < noaa,
            "{name}: FLIP of ssaa16 ({ssaa16}) is not below noaa's ({noaa})"
        );
    }

    // Methods that do not apply are listed as skipped in report.md.
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    // The answer comes first: its heading, its picks and every scene's
    // fronts within the first 40 lines.
    let head: Vec<&str> = md.lines().take(40).collect();
    assert!(
        head.contains(&"## The answer: what to use at each cost"),
        "{head:#?}"
    );
    for (name, _) in &loaded {
        assert!(
            head.iter()
                .any(|l| l.starts_with(&format!("| {name} | cpu | "))),
            "no front of {name} in the first 40 lines"
        );
    }
    assert!(md.contains("## Skipped"));
    assert!(md.contains("cone tracing needs a signed distance field"));
    assert!(md.contains("SRAA for ray tracing, Table 1"));
    // Every performance target is stated with its figure, met or not.
    assert!(md.contains("## Performance targets"));
    for target in [
        "| ctss ≤ 1.20x NoAA",
        "| ctss-r ≤ 1.08x NoAA",
        "| sraa-rt ≤ 1/6 of ssaa16's time",
        "| primary rays ≥ 70.0% of raw traversal",
        "| shadow rays ≥ 70.0% of raw traversal",
        "| bilateral_weight (SRAA eq. 1) ≤ 5 ns per call",
        "| visibility_mask (CTSS eq. 7-8) ≤ 5 ns per call",
        "| ssaa16 / sraa-rt-hybrid time ≥ 6 (SRAA Fig. 3",
        "| antialiasing pass of sraa-rt ≤ 0.5x noaa's frame time | cpu | cornell",
        "| antialiasing pass of sraa-rt-hybrid ≤ 0.5x noaa's frame time | cpu | cornell",
        "| raster share of a sraa-rt-hybrid frame ≤ 15 % | cpu | atrium",
    ] {
        let line = md
            .lines()
            .find(|l| l.starts_with(target))
            .unwrap_or_else(|| panic!("no target line {target:?} in report.md"));
        // A ray-throughput figure may be "not judged" where raw traversal
        // is no bound (too few rays, or the pipeline outran it).
        assert!(
            line.ends_with("| met |")
                || line.ends_with("| **not met** |")
                || (target.contains("rays ≥") && line.contains("| not judged")),
            "{line}"
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(json["results"].as_array().unwrap().len(), rows.len());

    // Hybrid rows (triangle scenes, cpu): a raster pass and rasterised
    // samples; traced rows none. Each triangle scene sets the two side by
    // side, and the papers' section reads Fig. 3 both ways.
    let (raster_spp, ms_raster) = (col("raster_samples_per_pixel"), col("ms_raster"));
    let mut hybrids = 0;
    for r in rows.iter().filter(|r| r[col("backend")] == "cpu") {
        let spp: f64 = r[raster_spp].parse().unwrap();
        if r[method].ends_with("-hybrid") {
            hybrids += 1;
            assert!(spp > 0.0, "{r:?}");
            assert!(r[ms_raster].parse::<f64>().unwrap() > 0.0, "{r:?}");
        } else {
            assert_eq!(spp, 0.0, "{r:?}");
            assert!(r[ms_raster].is_empty(), "{r:?}");
        }
    }
    assert!(hybrids >= 3 * 8, "only {hybrids} hybrid rows");
    for name in ["cornell", "atrium"] {
        let section = md
            .split("\n## ")
            .find(|s| s.starts_with(&format!("{name}\n")))
            .unwrap();
        assert!(section.contains("**Traced against hybrid.**"), "{name}");
        assert!(section.contains("| sraa-rt | cpu | "), "{name}");
    }
    assert!(md.contains("### SRAA for ray tracing, Fig. 3: hybrid and traced"));
    assert!(md.contains("| rasteriser / raw |"));

    // Edge classes: three columns per class, counts that cover every pixel,
    // and verdict lines that apply the stated rules to the written numbers.
    for c in CLASSES {
        for col in [format!("flip_{c}"), format!("px_{c}"), format!("dssim_{c}")] {
            assert!(header.contains(&col), "results.csv lacks column {col}");
        }
    }
    assert!(md.contains("## Edge classes and the rules of judgement"));
    // The near-edge band: its columns, and pixels that leave flat for it
    // (every scene has edges, so some flat-looking pixel is within 2 px of
    // one), at every camera offset.
    for name in [
        "flip_near_edge",
        "px_near_edge",
        "dssim_near_edge",
        "flip_min",
        "flip_max",
    ] {
        assert!(
            header.iter().any(|h| h == name),
            "results.csv lacks column {name}"
        );
    }
    let band = col("px_near_edge");
    for r in rows.iter().filter(|r| !r[col("flip_mean")].is_empty()) {
        let px: u64 = r[band].parse().unwrap_or_else(|_| panic!("{r:?}"));
        assert!(px > 0, "no near-edge pixel: {r:?}");
        let (lo, hi): (f64, f64) = (
            r[col("flip_min")].parse().unwrap(),
            r[col("flip_max")].parse().unwrap(),
        );
        let mean: f64 = r[col("flip_mean")].parse().unwrap();
        assert!(lo <= mean && mean <= hi, "{r:?}");
    }
    // The band is as wide as each metric reaches, and each scene says how
    // much flat remains beyond it.
    assert!(md.contains(
        "| near edge | none of the above, but within the metric's reach of a pixel that is (Chebyshev distance): 10 px under FLIP"
    ));
    assert!(md.contains("Flat beyond the metrics' reach (what \"flat\" is judged on): "));
    // SSIM beside FLIP: a mean in (-1, 1) for every measured row (no method
    // matches the reference exactly at this size), its map beside FLIP's,
    // and each scene says where the two metrics' verdicts disagree.
    let ssim = col("ssim_mean");
    for r in rows.iter().filter(|r| !r[col("flip_mean")].is_empty()) {
        let v: f64 = r[ssim].parse().unwrap_or_else(|_| panic!("{r:?}"));
        assert!(v > -1.0 && v < 1.0, "{r:?}");
        let m = report::file_safe(&r[method]);
        if r[col("backend")] == "cpu" {
            nonempty(&out.join(format!("images/{}/ssim_{m}.png", r[scene])));
        }
    }
    // Motion, the quick version: every loaded scene followed over 4 frames
    // by noaa and ssaa4 at least, finite errors, an animation per scene.
    let motion = &json["motion"];
    assert_eq!(motion["frames"], 4);
    let mrows = motion["rows"].as_array().unwrap();
    for (name, _) in &loaded {
        for m in ["noaa", "ssaa4"] {
            let r = mrows
                .iter()
                .find(|r| r["scene"] == name.as_str() && r["method"] == m)
                .unwrap_or_else(|| panic!("no motion row for {m} on {name}"));
            assert_eq!(r["flip_per_frame"].as_array().unwrap().len(), 4);
            let flat = r["instability_flat"].as_f64().unwrap();
            assert!(flat.is_finite() && flat >= 0.0, "{r}");
            // The pixels it pools over: frames 2 to 4 of the scene's flat
            // class, the same for every method.
            let px = r["px_flat"].as_u64().unwrap();
            let (w, h) = (
                motion["width"].as_u64().unwrap(),
                motion["height"].as_u64().unwrap(),
            );
            assert!(px > 0 && px <= 3 * w * h, "{r}");
            let noaa = mrows
                .iter()
                .find(|n| n["scene"] == name.as_str() && n["method"] == "noaa")
                .unwrap();
            assert_eq!(r["px_flat"], noaa["px_flat"], "{r}");
        }
        let apng = std::fs::read(out.join(format!("images/{name}/motion.png"))).unwrap();
        assert!(
            apng.windows(4).any(|w| w == b"acTL"),
            "{name}: motion.png is not animated"
        );
    }
    assert!(md.contains("## Motion"));
    for sc in ["cornell", "primitives"] {
        let section = md
            .split("\n## ")
            .find(|s| s.starts_with(&format!("{sc}\n")))
            .unwrap();
        assert!(
            section.contains("Where FLIP and SSIM disagree, each with its computed cause:")
                || section.contains("FLIP and SSIM agree on every verdict of this scene."),
            "{sc}"
        );
        // Every disagreement has its cause line.
        if let Some((_, list)) = section.split_once("Where FLIP and SSIM disagree") {
            let list = list.split("\n\n").nth(1).unwrap_or("");
            let items = list
                .lines()
                .filter(|l| l.starts_with("  - ") && !l.starts_with("  - Near-edge band"))
                .count();
            let causes = list
                .lines()
                .filter(|l| l.starts_with("    Cause: "))
                .count();
            assert!(
                items > 0 && items == causes,
                "{sc}: {items} disagreements, {causes} causes"
            );
        }
        assert!(section.contains("1 − SSIM by edge class"), "{sc}");
    }
    let post = col("post_process");
    assert!(md.contains("box: the cpu NoAA frame post-processed by the command `'"));
    assert!(md.contains("its time is NoAA's plus the command's wall time"));
    for r in rows.iter().filter(|r| r[method] == "box") {
        assert!(r[post].starts_with("the command `"), "{r:?}");
        // Its time is NoAA's plus the command's, which is the pass `box`.
        let noaa = rows
            .iter()
            .find(|n| n[scene] == r[scene] && n[method] == "noaa")
            .unwrap();
        let ms = |row: &Vec<String>, c: &str| row[col(c)].parse::<f64>().unwrap();
        let sum = ms(noaa, "ms_median") + ms(r, "ms_box");
        assert!(
            (ms(r, "ms_median") - sum).abs() < 1e-3 * sum.max(1.0),
            "{r:?}"
        );
    }
    if gpu {
        assert!(md.contains(
            "smaa: the cpu NoAA frame post-processed by SMAA 1x (the `smaa` crate, quality High) on "
        ));
        assert!(rows
            .iter()
            .filter(|r| r[method] == "smaa")
            .all(|r| !r[post].is_empty()));
    } else {
        assert!(md.contains("no GPU adapter for the SMAA post-process"));
    }
    assert!(
        !md.contains("render failed") && summary.failures.is_empty(),
        "a quick report has no failed render"
    );
    check_verdicts(&json["results"], &md);

    // The interactive page (tests/report_html.rs opens it in a browser).
    nonempty(&out.join("report.html"));

    // Plots and images.
    for (name, _) in &loaded {
        for stem in ["flip_vs_time", "passes", "classes"] {
            for ext in ["png", "svg"] {
                nonempty(&out.join("plots").join(format!("{name}_{stem}.{ext}")));
            }
        }
        let img = out.join("images").join(name);
        for f in [
            "reference.png",
            "noaa.png",
            "ssaa16.png",
            "flip_noaa.png",
            "flip_ssaa16.png",
            "box.png",
            "flip_box.png",
            "crops_edge.png",
            "crops_shadow.png",
            "crops_reflection.png",
            "crops_overview.png",
        ] {
            nonempty(&img.join(f));
        }
        let png = image::open(img.join("noaa.png")).unwrap();
        assert_eq!((png.width(), png.height()), report::QUICK_SIZE);
    }

    // A second run reads every reference from the cache.
    let again = report::run(&ReportArgs {
        methods: vec!["noaa".into()],
        post_processes: Vec::new(),
        ..args
    })
    .expect("second quick report");
    assert_eq!(again.references_rendered, 0);
    // The paper scenes and the quick run's extra scenes (`glass`), one
    // reference per camera offset each.
    assert_eq!(
        again.references_cached,
        (loaded.len() + report::QUICK_EXTRA_SCENES.len()) * report::offsets::ERROR_OFFSETS.len()
    );
}

#[test]
fn bad_arguments_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let base = ReportArgs {
        quick: true,
        out: dir.path().join("r"),
        no_paper_scenes: true,
        scenes: vec!["cornell".into()],
        methods: vec!["noaa".into()],
        ..Default::default()
    };
    // Each case: one argument made bad, and what its error must name.
    type MakeBad = fn(&mut ReportArgs);
    let cases: [(MakeBad, &str); 6] = [
        (|a| a.backend = "cpu,vulkan9".into(), "vulkan9"),
        (|a| a.size = Some("0x10".into()), "--size"),
        (|a| a.methods = vec!["ssaa5".into()], "ssaa5"),
        (|a| a.runs = Some(0), "--runs"),
        (|a| a.scenes = vec!["no-such-scene".into()], "no-such-scene"),
        (|a| a.scenes = vec![], "--no-paper-scenes"),
    ];
    for (bad, named) in cases {
        let mut args = base.clone();
        bad(&mut args);
        let err = format!("{:#}", report::run(&args).unwrap_err());
        assert!(err.contains(named), "{named}: {err}");
    }
}

#[test]
fn timing_only_writes_no_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t");
    let s = report::run(&ReportArgs {
        timing_only: true,
        out: out.clone(),
        no_paper_scenes: true,
        scenes: vec!["cornell".into()],
        methods: vec!["noaa".into(), "sraa-rt".into()],
        size: Some("64x48".into()),
        runs: Some(1),
        ..Default::default()
    })
    .unwrap();
    assert_eq!(s.rows.len(), 2);
    assert!(s.rows.iter().all(|r| r.flip_mean.is_none()));
    assert!(s.rows.iter().all(|r| (r.width, r.height) == (64, 48)));
    assert_eq!(s.references_rendered + s.references_cached, 0);
    let sraa = s
        .rows
        .iter()
        .find(|r| r.method.to_string() == "sraa-rt")
        .unwrap();
    assert!(sraa.pass("geometry").is_some() && sraa.pass("antialiasing").is_some());
    nonempty(&out.join("plots/cornell_passes.svg"));
    assert!(!out.join("plots/cornell_flip_vs_time.png").exists());
    assert!(!out.join("cache").exists());
}

/// `--backend cpu,wgpu` puts both backends in one table: every method that
/// applies has a row per backend, with a time and an error, and the report
/// names the adapter.
#[test]
fn report_with_both_backends() {
    if subcone_wgpu::test_util::gpu_or_skip("report_with_both_backends").is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let summary = report::run(&ReportArgs {
        quick: true,
        no_paper_scenes: true,
        scenes: vec!["cornell".into(), "primitives".into()],
        methods: vec!["noaa".into(), "sraa".into(), "ctss".into()],
        backend: "cpu,wgpu".into(),
        size: Some("48x32".into()),
        out: out.clone(),
        ..Default::default()
    })
    .expect("report on both backends");
    for (scene, method) in [
        ("cornell", "noaa"),
        ("cornell", "sraa"),
        ("primitives", "ctss"),
    ] {
        for backend in ["cpu", "wgpu"] {
            let row = summary
                .rows
                .iter()
                .find(|r| {
                    r.scene == scene && r.method.to_string() == method && r.backend == backend
                })
                .unwrap_or_else(|| panic!("no {backend} row for {scene} {method}"));
            assert!(row.ms_median > 0.0, "{backend} {scene} {method}: no time");
            assert!(
                row.flip_mean.is_some_and(|f| (0.0..1.0).contains(&f)),
                "{backend} {scene} {method}: no error"
            );
        }
    }
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("wgpu on "), "the report names the adapter");
}

/// A post-process command that fails, cannot start, writes the wrong thing
/// or hangs: an error naming the row and the scene; with `--keep-going`, a
/// line under Failures and no row.
#[test]
fn a_failing_post_process_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let run = |post: &str, keep_going: bool| {
        report::run(&ReportArgs {
            // The post-process fails on its warm-up, before any error is
            // measured: timing only, one round.
            quick: true,
            timing_only: true,
            size: Some("96x64".into()),
            runs: Some(1),
            no_paper_scenes: true,
            scenes: vec!["cornell".into()],
            methods: vec!["noaa".into()],
            out: dir.path().join("report"),
            post_processes: vec![post.into()],
            post_timeout: Some(2.0),
            keep_going,
            ..Default::default()
        })
    };
    let bin = box_filter();
    let bin = bin.display();
    // A PNG of another size, which the box filter copies (filtered) to the
    // output.
    let small = dir.path().join("small.png");
    image::RgbImage::new(5, 5).save(&small).unwrap();
    let small = small.display();
    let cases = [
        ("missing=/nonexistent/filter {color} {output}", "cannot run"),
        // The box filter's own error (one argument short): exit code 1, its
        // standard error quoted.
        (&*format!("nonzero='{bin}' {{color}}"), "usage: box_filter"),
        // Exits 0 without writing the output.
        (
            &*format!("silent='{bin}' {{color}} {{color}}"),
            "was not written",
        ),
        (
            &*format!("resized='{bin}' '{small}' {{output}}"),
            "is 5x5; expected the frame's 96x64",
        ),
    ];
    for (spec, why) in cases {
        let name = spec.split('=').next().unwrap();
        let e = format!("{:#}", run(spec, false).expect_err(spec));
        assert!(
            e.contains(&format!("cornell / {name} on cpu failed")),
            "{e}"
        );
        assert!(e.contains(why), "{spec}: {e}");
        let s = run(spec, true).expect(spec);
        assert!(
            s.rows.iter().all(|r| r.method.to_string() != name),
            "{spec}: a row"
        );
        assert_eq!(s.failures.len(), 1, "{spec}");
        assert!(s.failures[0].error.contains(why), "{}", s.failures[0].error);
        let md = std::fs::read_to_string(dir.path().join("report/report.md")).unwrap();
        assert!(md.contains("## Failures") && md.contains(why), "{spec}");
    }
    #[cfg(unix)]
    {
        // A file that is no PNG, and a hang.
        let unix = [
            ("depth=cp {depth} {output}", "not a PNG"),
            ("hang=sleep 30", "ran past the timeout of 2 s"),
        ];
        for (spec, why) in unix {
            let e = format!("{:#}", run(spec, false).expect_err(spec));
            assert!(e.contains(why), "{spec}: {e}");
        }
    }
}
