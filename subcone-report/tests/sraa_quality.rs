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
        let judged = common::Judged::new(&scene, W, H);
        let measure = |method: &str| judged.measure(method);
        let (noaa_mean, noaa) = measure("noaa");
        for method in [SRAA, SRAA_RT] {
            let (mean, it) = measure(&method.to_string());
            let v = Verdict::judge(method, &it, &noaa);
            eprintln!(
                "{name}: {} (whole {mean:.4} vs NoAA {noaa_mean:.4})",
                v.line("cpu")
            );
            if !v.misses.is_empty() || !v.holds_on_flat() || mean >= noaa_mean {
                failures.push(format!("{name}: {}", v.line("cpu")));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
