//! The golden vectors (`subcone vectors`): written twice, byte for byte the
//! same; every file in the documented line layout and valid JSON; every case
//! the Rust kernel's output, bit for bit (NaN as NaN); the special values
//! present; and, where an f64 reference exists, every in-domain case within
//! its bound of it.

use std::collections::BTreeSet;

use subcone::vectors::tolerance::{ulps, Tol};
use subcone::vectors::{parse_case_line, write_all, KernelVectors, Type, KERNELS};

fn f(w: u32) -> f32 {
    f32::from_bits(w)
}

/// Output words agree: equal bits, or both NaN.
fn same(ty: Type, a: u32, b: u32) -> bool {
    a == b || (ty == Type::F32 && f(a).is_nan() && f(b).is_nan())
}

#[test]
fn vectors_are_deterministic_and_match_the_kernels() {
    let a = tempfile::tempdir().expect("temp dir");
    let b = tempfile::tempdir().expect("temp dir");
    let written = write_all(a.path()).expect("write");
    write_all(b.path()).expect("write again");
    assert_eq!(written.len(), KERNELS.len());
    let names: BTreeSet<_> = KERNELS.iter().map(|k| k.name).collect();
    assert_eq!(names.len(), KERNELS.len(), "kernel names are unique");
    let mut total = 0;
    for k in KERNELS {
        let first = std::fs::read(a.path().join(k.file_name())).expect("read");
        let second = std::fs::read(b.path().join(k.file_name())).expect("read");
        assert!(first == second, "{}: two runs differ", k.name);
        total += first.len();
        check_file(k, &String::from_utf8(first).expect("UTF-8"));
    }
    println!("{} files, {total} bytes", KERNELS.len());
    assert!(total < 8 << 20, "the whole set stays modest: {total} bytes");
}

fn check_file(k: &KernelVectors, text: &str) {
    let name = k.name;
    // Valid JSON, with the header the kernel states.
    let json: serde_json::Value = serde_json::from_str(text).expect("valid JSON");
    assert_eq!(json["kernel"], name);
    let count = json["count"].as_u64().expect("count") as usize;
    assert_eq!(json["cases"].as_array().expect("cases").len(), count);
    let tol = &json["tolerance"];
    let (kind, value) = (tol["kind"].as_str().expect("kind"), &tol["value"]);
    assert_eq!(kind, k.tolerance.kind(), "{name}");
    match k.tolerance {
        Tol::Ulps(u) => assert_eq!(value.as_u64(), Some(u as u64), "{name}"),
        Tol::Abs(v) | Tol::Rel(v) => assert_eq!(value.as_f64().map(|x| x as f32), Some(v)),
    }
    assert_eq!(tol["constant"], k.tolerance_constant);
    for key in ["non_finite", "reference"] {
        assert!(
            json[key].as_str().is_some_and(|s| !s.is_empty()),
            "{name}: {key}"
        );
    }
    let (inputs, outputs) = (k.inputs(), k.outputs());
    for (side, fields) in [("in", &inputs), ("out", &outputs)] {
        let sig = json["signature"][side].as_array().expect("signature");
        assert_eq!(sig.len(), fields.len(), "{name}: signature {side}");
        for (s, f) in sig.iter().zip(fields.iter()) {
            assert_eq!(s["name"], f.name.as_str());
            assert_eq!(s["type"], f.ty.name());
        }
    }

    // The line layout a C reader relies on.
    let lines: Vec<&str> = text.lines().collect();
    let keys = [
        "\"kernel\": ",
        "\"signature\": ",
        "\"tolerance\": ",
        "\"non_finite\": ",
        "\"reference\": ",
        "\"count\": ",
    ];
    assert_eq!(lines[0], "{", "{name}");
    for (i, key) in keys.iter().enumerate() {
        assert!(lines[i + 1].starts_with(key), "{name}: line {}", i + 2);
    }
    assert_eq!(lines[7], "\"cases\": [", "{name}");
    assert_eq!(lines.len(), 8 + count + 2, "{name}: one case per line");
    assert_eq!(&lines[8 + count..], ["]", "}"], "{name}");

    let mut specials = Specials::default();
    let reference = reference(name);
    let mut worst = 0.0f64;
    let mut checked = 0;
    for (n, line) in lines[8..8 + count].iter().enumerate() {
        assert_eq!(line.ends_with(','), n + 1 < count, "{name}: commas");
        assert!(line.starts_with("{\"in\": ["), "{name}: {line}");
        let (input, output) = parse_case_line(line).expect("case line");
        assert_eq!(input.len(), inputs.len(), "{name}: {line}");
        assert_eq!(output.len(), outputs.len(), "{name}: {line}");
        // Each value in its type's spelling.
        let values = line
            .split(['[', ']'])
            .filter(|s| s.contains(|c: char| c.is_ascii_digit()));
        for (value, field) in values
            .flat_map(|s| s.split(", "))
            .zip(inputs.iter().chain(outputs.iter()))
        {
            match field.ty {
                Type::F32 => assert!(
                    value.len() == 12 && value.starts_with("\"0x"),
                    "{name}: {value}"
                ),
                Type::U32 => assert!(value.parse::<u32>().is_ok(), "{name}: {value}"),
                Type::Bool => assert!(value == "0" || value == "1", "{name}: {value}"),
            }
        }
        for (w, field) in input.iter().zip(&inputs) {
            if field.ty == Type::F32 {
                specials.see(f(*w));
            }
        }
        // The Rust kernel, bit for bit (NaN as NaN).
        let rust = (k.eval)(&input);
        for ((a, b), field) in rust.iter().zip(&output).zip(&outputs) {
            assert!(
                same(field.ty, *a, *b),
                "{name}: case {n} ({line}): the kernel gives {a:#010x} for {}",
                field.name
            );
        }
        // The f64 reference, on its domain.
        if let Some((bound, r)) = &reference {
            if let Some(want) = r(&input) {
                checked += 1;
                for (have, want) in output.iter().zip(want) {
                    let e = bound.error(want as f32, f(*have));
                    worst = worst.max(e);
                    assert!(
                        e <= bound.limit(),
                        "{name}: case {n} ({line}): {} against f64 {want:e}: error {e:e} over {bound:?}",
                        f(*have)
                    );
                }
            }
        }
    }
    if reference.is_some() {
        assert!(
            checked >= 100,
            "{name}: {checked} cases on the reference's domain"
        );
        println!("{name}: {count} cases, {checked} within {worst:e} of f64");
    }
    if inputs.iter().any(|f| f.ty == Type::F32) {
        specials.assert_all(name);
    }
}

/// Which special values a file's f32 inputs include.
#[derive(Default)]
struct Specials {
    zero: bool,
    neg_zero: bool,
    subnormal: bool,
    inf: bool,
    neg_inf: bool,
    nan: bool,
    huge: bool,
    tiny: bool,
}

impl Specials {
    fn see(&mut self, x: f32) {
        self.zero |= x.to_bits() == 0;
        self.neg_zero |= x.to_bits() == 0x8000_0000;
        self.subnormal |= x.is_subnormal();
        self.inf |= x == f32::INFINITY;
        self.neg_inf |= x == f32::NEG_INFINITY;
        self.nan |= x.is_nan();
        self.huge |= x.is_finite() && x.abs() >= 1e30;
        self.tiny |= x.is_normal() && x.abs() <= 1e-30;
    }

    fn assert_all(&self, name: &str) {
        let seen = [
            ("0", self.zero),
            ("-0", self.neg_zero),
            ("a subnormal", self.subnormal),
            ("+inf", self.inf),
            ("-inf", self.neg_inf),
            ("NaN", self.nan),
            ("|x| >= 1e30", self.huge),
            ("|x| <= 1e-30", self.tiny),
        ];
        for (what, ok) in seen {
            assert!(ok, "{name}: no input is {what}");
        }
    }
}

/// An f64 reference on its domain: the bound, and the expected outputs for
/// an input (`None` off the domain).
type Reference = (Tol, fn(&[u32]) -> Option<Vec<f64>>);

fn fs(w: &[u32]) -> Vec<f64> {
    w.iter().map(|&x| f(x) as f64).collect()
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0 && x as f32 >= f32::MIN_POSITIVE
}

/// The f64 references of the kernels that have one (each file's `reference`
/// field says which); the bounds are those the kernels meet against f64 in
/// kernels/tests/f64_reference.rs, or their conformance tolerance.
fn reference(kernel: &str) -> Option<Reference> {
    Some(match kernel {
        "cone_radius" | "min_step" => (Tol::Ulps(2), |w| {
            let x = fs(w);
            let p = x[0] * x[1];
            (positive(x[0]) && positive(x[1]) && positive(p) && p < f32::MAX as f64)
                .then(|| vec![p])
        }),
        "cone_occlusion" => (Tol::Abs(1e-6), |w| {
            let (d, rc) = (f(w[0]) as f64, f(w[1]) as f64);
            let ok = d.is_finite() && positive(rc) && rc < 1e30 && (d / rc).abs() <= 3.0;
            ok.then(|| vec![(1.0 - d / rc) / 2.0])
        }),
        "backtrace_cone_entry" => (Tol::Ulps(2), |w| {
            let (t, tan) = (f(w[0]) as f64, f(w[1]) as f64);
            (positive(t) && positive(tan) && t < 1e30 && tan < 1e30).then(|| vec![t / (1.0 + tan)])
        }),
        "backtrace_hard_hit" => (Tol::Ulps(2), |w| {
            let x = fs(w);
            let (t, d, ti) = (x[0], x[1], x[2]);
            let ok = x.iter().all(|v| v.abs() < 1e30) && t <= ti;
            ok.then(|| vec![(t + d).max(t).min(ti)])
        }),
        "albedo_difference" => (Tol::Abs(1e-6), |w| {
            let x = fs(w);
            if !x.iter().all(|v| v.is_finite() && *v <= 4.0) {
                return None;
            }
            let e = |v: f64| v.max(0.0).sqrt();
            Some(vec![(0..3)
                .map(|c| (e(x[c]) - e(x[c + 3])).abs())
                .fold(0.0, f64::max)])
        }),
        "resolve_pixel" => (Tol::Abs(1e-6), |w| {
            let x = fs(w);
            let ok = |c: &[f64]| c.iter().all(|v| v.is_finite());
            if !x.iter().all(|v| !v.is_finite() || v.abs() <= 4.0) {
                return None;
            }
            let finite: Vec<&[f64]> = x.chunks(3).filter(|c| ok(c)).collect();
            if finite.is_empty() {
                return Some(vec![0.0; 3]);
            }
            let n = finite.len() as f64;
            Some(
                (0..3)
                    .map(|c| finite.iter().map(|s| s[c]).sum::<f64>() / n)
                    .collect(),
            )
        }),
        "cone_tan_theta" => (Tol::Ulps(4), |w| {
            let (fov, h, cov, fp) = (f(w[0]) as f64, w[1], f(w[2]) as f64, w[3]);
            let pi = std::f64::consts::PI;
            let ok = (1e-3..=pi - 1e-3).contains(&fov) && h > 0 && (1e-3..=1e3).contains(&cov);
            let r = match fp {
                0 => std::f64::consts::FRAC_1_SQRT_2,
                1 => 2.0 / (2.0 + std::f64::consts::SQRT_2),
                _ => 0.5,
            };
            let t = cov * r * 2.0 * (0.5 * fov).tan() / h as f64;
            (ok && positive(t)).then(|| vec![t])
        }),
        "ao_fraction" => (Tol::Ulps(1), |w| {
            let (i, c) = (w[0], w[1]);
            if c > 1 << 24 {
                return None;
            }
            Some(vec![if c == 0 {
                1.0
            } else {
                i.min(c) as f64 / c as f64
            }])
        }),
        "sample_weight" => (Tol::Ulps(0), |w| {
            let (m, k, min_w) = (w[0], w[1], f(w[2]));
            let base = m.count_ones() as f64 / 32.0;
            Some(vec![if k == 1 {
                1.0
            } else if min_w > 0.0 {
                base.max(min_w.min(1.0) as f64)
            } else {
                base
            }])
        }),
        "level_weight" => (Tol::Ulps(0), |w| Some(vec![w[0].min(128) as f64 / 128.0])),
        _ => return None,
    })
}

#[test]
fn f64_references_match_the_files_reference_fields() {
    for k in KERNELS {
        let has = reference(k.name).is_some();
        let says = k.reference.contains("checked by tests/vectors.rs");
        assert_eq!(has, says, "{}: reference field", k.name);
    }
}

#[test]
fn ulps_counts_adjacent_floats() {
    assert_eq!(ulps(1.0, 1.0f32.next_up()), 1);
    assert_eq!(ulps(-0.0, 0.0), 0);
    assert_eq!(ulps(f32::NAN, f32::NAN), 0);
}

#[test]
fn case_lines_parse() {
    let line = "{\"in\": [\"0x7fc00000\", 3, 1], \"out\": [\"0x80000000\"]},";
    assert_eq!(
        parse_case_line(line),
        Some((vec![0x7fc0_0000, 3, 1], vec![0x8000_0000]))
    );
    assert_eq!(parse_case_line("\"count\": 3,"), None);
}

#[test]
fn the_command_line_writes_the_same_files() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("vectors");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_subcone"))
        .args(["vectors", "--out"])
        .arg(&out)
        .output()
        .expect("run subcone vectors");
    assert!(status.status.success(), "{status:?}");
    let mut files: Vec<String> = std::fs::read_dir(&out)
        .expect("listing")
        .map(|e| e.expect("entry").file_name().into_string().expect("name"))
        .collect();
    files.sort();
    let mut want: Vec<String> = KERNELS.iter().map(|k| k.file_name()).collect();
    want.sort();
    assert_eq!(files, want);
    for k in KERNELS {
        let text = std::fs::read_to_string(out.join(k.file_name())).expect("read");
        assert!(text == k.render(), "{}: the CLI's file differs", k.name);
    }
}
