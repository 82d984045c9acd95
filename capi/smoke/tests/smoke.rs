//! The C smoke test: `c/smoke.c`, compiled against `include/subcone.h` by the
//! system C compiler, calls every exported function; here its results are
//! compared with the Rust kernels on the same inputs, bit for bit (the C ABI
//! runs the same code), and its bad-input calls must all have returned their
//! documented error codes. The README's C example runs too.

use glam::{Vec2, Vec3};
use subcone_capi::SubconeVec3;
use subcone_capi_smoke::{subcone_readme_example, subcone_smoke_run, SmokeOutputs};
use subcone_kernels::aggregate::{sample_weight, Weighting};
use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, cone_tan_theta,
    PixelFootprint,
};
use subcone_kernels::ctss::{trace_field, CtssParams, FieldSample, SplitRay};
use subcone_kernels::mask::{project_normal, visibility_mask, MaskPlacement};
use subcone_kernels::sraa::{
    albedo_difference, bilateral_weight, reconstruction_weight, resolve_pixel, shadow_gated_weight,
    Geometry, Resolver, ShadedFrame, ShadedGroup, SraaParams, Subsamples, ALBEDO_TOLERANCE,
};

fn v(c: SubconeVec3) -> Vec3 {
    Vec3::new(c.x, c.y, c.z)
}

/// Bitwise, so that NaN equals NaN and −0 differs from 0.
fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits()
}

fn same3(a: Vec3, b: Vec3) -> bool {
    same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z)
}

#[test]
fn the_c_smoke_test_matches_the_kernels_and_gets_every_error_code() {
    let mut o = SmokeOutputs::default();
    let mut log = vec![0u8; 4096];
    // SAFETY: `o` and `log` are valid for the call; the C code writes within them.
    let failures = unsafe { subcone_smoke_run(&mut o, log.as_mut_ptr().cast(), log.len()) };
    let log = String::from_utf8_lossy(&log[..log.iter().position(|&b| b == 0).unwrap_or(0)]);
    assert_eq!(failures, 0, "the C smoke test's failures:\n{log}");

    let p = SraaParams::TUNED;
    let gi = Geometry {
        normal: Vec3::Z,
        depth: 2.0,
    };
    let gj = Geometry {
        normal: Vec3::new(0.6, 0.0, 0.8),
        depth: 2.1,
    };
    assert_eq!(o.version, subcone_capi::subcone_version());
    assert!(same(o.bilateral, bilateral_weight(&p, &gi, &gj)));
    assert!(o.bilateral > 0.0 && o.bilateral < 1.0, "{}", o.bilateral);
    assert!(same(
        o.shadow_same,
        shadow_gated_weight(&p, &gi, &gj, true, true)
    ));
    assert!(same(o.shadow_differ, 0.0));
    assert!(same(
        o.reconstruction,
        reconstruction_weight(&p, &gi, &gj, 0.5)
    ));
    let a = albedo_difference(Vec3::new(0.2, 0.4, 0.6), Vec3::new(0.3, 0.1, 0.6));
    assert!(same(o.albedo, a));
    let four = [Vec3::X, Vec3::Y, Vec3::Z, Vec3::ONE];
    assert!(same3(v(o.resolved), resolve_pixel(&four)));

    let tan = cone_tan_theta(0.8, 720, 0.6, PixelFootprint::Circumscribed);
    assert!(same(o.tan_theta, tan));
    let rc = cone_radius(3.0, tan);
    assert!(same(o.radius, rc));
    assert!(same(o.occlusion, cone_occlusion(0.001, rc)));
    assert!(same(o.advanced, advance(3.0, 0.001, 0.5, rc)));
    assert!(same(o.entry, backtrace_cone_entry(3.0, tan)));
    assert!(same(o.hard_hit, backtrace_hard_hit(2.9, 0.05, 3.0)));
    let n = project_normal(Vec3::new(0.3, 0.4, 0.5), Vec3::X, Vec3::Y);
    assert!(same(o.projected[0], n.x) && same(o.projected[1], n.y));
    let m = visibility_mask(0.3, Vec2::new(0.6, 0.8), MaskPlacement::Derived);
    assert_eq!(o.mask, m);
    assert!(m != 0 && m != u32::MAX);
    assert!(same(
        o.sample_weight,
        sample_weight(0xFFFF, Weighting::Visibility, 0.0)
    ));

    // The 3×2 frame of smoke.c, through the kernels' resolver.
    let mut colors = Vec::new();
    let (mut geometry, mut sub, mut shadow, mut subshadow) = (vec![], vec![], vec![], vec![]);
    for j in 0..6 {
        let r = (j + 1) as f32 * 0.1;
        colors.push(Vec3::new(r, 0.0, 0.25));
        colors.push(Vec3::new(r, 0.5, 0.25));
        let depth = 2.0 + (j % 3) as f32 * 0.5;
        geometry.push(Geometry {
            normal: Vec3::Z,
            depth,
        });
        shadow.push((j % 2) as u32);
        sub.push(std::array::from_fn::<_, 4, _>(|k| Geometry {
            normal: Vec3::Z,
            depth: depth + k as f32 * 0.01,
        }));
        subshadow.push(std::array::from_fn::<_, 4, _>(|k| ((j + k) % 2) as u32));
    }
    let gates = [None, Some(0)];
    let resolver = Resolver::new(&p, &gates, ALBEDO_TOLERANCE);
    let frame = ShadedFrame {
        width: 3,
        height: 2,
        colors: &colors,
        layers: 2,
        albedo: &[],
        primary: ShadedGroup {
            geometry: &geometry,
            shadow: &shadow,
            first_layer: 0,
        },
        secondary: None,
    };
    for j in 0..6 {
        let s = Subsamples {
            geometry: sub[j],
            shadow: subshadow[j],
            albedo: None,
        };
        let want = resolver.resolve(&frame, (j % 3) as u32, (j / 3) as u32, &s, None);
        assert!(
            same3(v(o.sraa[j]), want),
            "pixel {j}: {:?} {want}",
            o.sraa[j]
        );
    }

    // The CTSS trace of smoke.c: a unit sphere at z = 5, the ray along its edge.
    let dir = Vec3::new(0.204_124_1, 0.0, 1.0).normalize();
    let ray = SplitRay::new(Vec3::ZERO, dir, Vec3::Y);
    struct Sphere;
    impl subcone_kernels::ctss::ConeField for Sphere {
        fn sample(&mut self, p: Vec3) -> FieldSample {
            let d = (p - Vec3::new(0.0, 0.0, 5.0)).length() - 1.0;
            FieldSample {
                distance: d,
                step: d,
                object: 3,
            }
        }
    }
    let r = trace_field(
        &CtssParams::new(tan),
        &ray,
        &mut Sphere,
        |_, n, _| n * 0.5 + Vec3::splat(0.5),
        Vec3::new(0.1, 0.2, 0.3),
    );
    assert!(same3(v(o.ctss.color), r.color), "{:?} {:?}", o.ctss, r);
    assert_eq!(
        (o.ctss.samples, o.ctss.steps, o.ctss.coverage),
        (r.samples, r.steps, r.coverage)
    );
    // The pixel is partly sphere, partly background.
    assert!(r.coverage != 0 && r.coverage != u32::MAX, "{r:?}");
}

#[test]
fn the_readme_c_example_runs() {
    // SAFETY: a C function without arguments.
    assert_eq!(unsafe { subcone_readme_example() }, 0);
}

/// README.md shows `c/readme_example.c` between its markers, as it is.
#[test]
fn the_readme_shows_the_c_example_as_it_is() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let c = std::fs::read_to_string(dir.join("c/readme_example.c")).unwrap();
    let start = c.find("/* README: begin */\n").unwrap() + "/* README: begin */\n".len();
    let end = c.find("/* README: end */").unwrap();
    let snippet = &c[start..end];
    let readme = std::fs::read_to_string(dir.join("../../README.md")).unwrap();
    assert!(
        readme.contains(snippet),
        "README.md does not show capi/smoke/c/readme_example.c as it is"
    );
}

/// Runs the C checker (`c/vectors.c`) on the vectors in `dir`: its failure
/// count, its tally and its log.
fn check_vectors(dir: &std::path::Path) -> (i32, subcone_capi_smoke::VectorTally, String) {
    let path = std::ffi::CString::new(dir.to_str().unwrap()).unwrap();
    let mut tally = subcone_capi_smoke::VectorTally::default();
    let mut log = vec![0u8; 1 << 16];
    // SAFETY: valid pointers for the call; the C code writes within them.
    let failures = unsafe {
        subcone_capi_smoke::subcone_smoke_vectors(
            path.as_ptr(),
            &mut tally,
            log.as_mut_ptr().cast(),
            log.len(),
        )
    };
    let end = log.iter().position(|&b| b == 0).unwrap_or(0);
    (failures, tally, String::from_utf8_lossy(&log[..end]).into())
}

/// The C checker reads the golden vectors, as `subcone vectors --out DIR`
/// writes them, and checks the C ABI against every case of the kernels it
/// exports, within each file's tolerance; where the ABI refuses a case's
/// parameters, the error code must be its answer.
#[test]
fn the_c_abi_passes_the_golden_vectors_from_c() {
    let dir = tempfile::tempdir().unwrap();
    subcone::vectors::write_all(dir.path()).unwrap();
    let (failures, tally, log) = check_vectors(dir.path());
    println!("{tally:?}");
    assert_eq!(failures, 0, "{tally:?}\n{log}");
    assert_eq!(tally.files, 14, "{tally:?}");
    assert!(tally.cases > 14 * 500, "{tally:?}");
    // The C ABI runs the Rust kernels: every accepted case is bit for bit.
    assert_eq!(tally.exact + tally.refused, tally.cases, "{tally:?}");
}

/// The C checker fails a case whose expected output is wrong.
#[test]
fn the_c_vector_checker_catches_a_wrong_output() {
    let dir = tempfile::tempdir().unwrap();
    subcone::vectors::write_all(dir.path()).unwrap();
    // Flip the first cone_radius case's output to 1.0.
    let file = dir.path().join("cone_radius.json");
    let text = std::fs::read_to_string(&file).unwrap();
    let line = text.lines().find(|l| l.starts_with("{\"in\"")).unwrap();
    let at = line.find("\"out\": [\"").unwrap() + "\"out\": [\"".len();
    let bad = format!("{}0x3f800000{}", &line[..at], &line[at + 10..]);
    assert_ne!(bad, line);
    std::fs::write(&file, text.replacen(line, &bad, 1)).unwrap();
    let (failures, tally, log) = check_vectors(dir.path());
    assert_eq!(failures, 1, "{tally:?}\n{log}");
    assert!(log.contains("cone_radius: outside the tolerance"), "{log}");
}
