//! Issue target for SRAA's default preset, checked where it is claimed: on
//! every built-in triangle scene, `sraa` and `sraa-rt` beat NoAA on every
//! edge class they claim and hold on flat pixels, by the report's own rules
//! (`report::classes::Verdict`: at most 0.95 × NoAA's FLIP on a claimed class,
//! at most 1.02 × on flat), and their whole-image FLIP is below NoAA's.
//!
//! The size is the quick report's (96×64) against a CPU `ssaa64` reference,
//! with the classes from 4×4 sub-samples per pixel, as the quick report
//! computes them. The preset was tuned on `cornell` and `checker`; `atrium`
//! (and the mesh scenes of the report) judge it.
//!
//! Flat is judged as the target was stated: beyond a 2 px near-edge band
//! ([`TARGET_BAND`]). The report now judges flat beyond FLIP's reach (10
//! px), where SRAA's reconstruction does not hold on cornell at this size:
//! a few more of the far flat pixels are one 8-bit code off the reference
//! than NoAA's. The test prints that verdict as a `finding:` line; the
//! report's verdicts show it.

/// The near-edge band the target "holds on flat" was stated with, px.
const TARGET_BAND: u32 = 2;

mod common;

use subcone_report::classes::Verdict;
use subcone_report::named::{SRAA, SRAA_RT};
use subcone_scene::builtin::{builtin, TRIANGLE_SCENES};

const W: u32 = 96;
const H: u32 = 64;

#[test]
fn default_sraa_beats_noaa_where_it_claims_on_every_triangle_scene() {
    let mut failures = Vec::new();
    for name in TRIANGLE_SCENES {
        let scene = builtin(name).expect("scene");
        let reach = common::Judged::new(&scene, W, H);
        let judged = reach.with_flip_band(TARGET_BAND);
        let measure = |method: &str| judged.measure(method);
        let (noaa_mean, noaa) = measure("noaa");
        let (_, noaa_reach) = reach.measure("noaa");
        for method in [SRAA, SRAA_RT] {
            let (mean, it) = measure(&method.to_string());
            let v = Verdict::judge(method, &it, &noaa);
            eprintln!(
                "{name}: {} (whole {mean:.4} vs NoAA {noaa_mean:.4})",
                v.line("cpu")
            );
            let (_, it_reach) = reach.measure(&method.to_string());
            let beyond = Verdict::judge(method, &it_reach, &noaa_reach);
            eprintln!(
                "finding: {name}, flat beyond FLIP's reach: {}",
                beyond.flat_word()
            );
            if !v.misses.is_empty() || !v.holds_on_flat() || mean >= noaa_mean {
                failures.push(format!("{name}: {}", v.line("cpu")));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
