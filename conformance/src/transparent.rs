//! The semi-transparent scenes: every backend renders and refuses there
//! what the CPU backend does, and its frames match the CPU's.

use subcone_scene::builtin::builtin;
use subcone_scene::builtin::TRANSPARENT_SCENES;
use subcone_scene::{Backend, RenderError, RenderSettings, UnsupportedReason};

use crate::{check_invariants, flip, methods_for, save_failure, FRAME_TOLERANCE, H, W};

/// The scenes with semi-transparent materials ([`TRANSPARENT_SCENES`], CTSS
/// §5.3): a backend renders each method the CPU backend renders there, and
/// refuses, as planned and for the CPU's reason, each one the CPU refuses
/// (the paths that do not carry opacity: SRAA-RT, `ctss+edges`, delayed
/// shading, refused as [`UnsupportedReason::Translucency`] saying
/// "semi-transparent", never drawn opaque silently). Every frame keeps the
/// invariants and is compared with the CPU backend's frame within
/// [`FRAME_TOLERANCE`], as the opaque scenes are. (The `ssaa64` bounds of
/// [`REFERENCE_BOUNDS`](crate::REFERENCE_BOUNDS) were measured on the opaque scenes and are not
/// applied here.)
pub fn check_transparent(backend: &dyn Backend) {
    let name = backend.name();
    let cpu = subcone_cpu::CpuBackend::new();
    let settings = RenderSettings::new(W, H);
    let mut failures = Vec::new();
    for scene_name in TRANSPARENT_SCENES {
        let scene = builtin(scene_name).expect("built-in scene");
        assert!(scene.has_translucency(), "{scene_name}");
        let mut rendered = 0;
        for method in methods_for(&scene) {
            let m = method.to_string();
            let want = cpu.supports(&scene, &method);
            let plan = backend.supports(&scene, &method);
            let r = backend.render(&scene, &scene.camera, &method, &settings);
            match (want, plan, r) {
                (Ok(()), Ok(()), Ok(frame)) => {
                    rendered += 1;
                    check_invariants(name, &scene, &method, &frame);
                    let expected = cpu
                        .render(&scene, &scene.camera, &method, &settings)
                        .unwrap_or_else(|e| panic!("cpu reference: {scene_name} {m}: {e}"));
                    let f = flip(&expected, &frame);
                    let t = FRAME_TOLERANCE;
                    println!(
                        "{name:>5} {scene_name:>16} {m:>12}: vs cpu FLIP mean {:.5} (≤ {}), p99 {:.4} (≤ {})",
                        f.mean, t.mean, f.p99(), t.p99
                    );
                    if f.mean > t.mean || f.p99() > t.p99 {
                        let stem = save_failure(name, scene_name, &m, "cpu", &expected, &frame, &f);
                        failures.push(format!(
                            "{scene_name} {m} against the cpu backend: FLIP mean {:.5} (limit {}), p99 {:.4} (limit {}); images in {stem}-*.png",
                            f.mean, t.mean, f.p99(), t.p99
                        ));
                    }
                }
                (Err(cpu_refusal), Err(planned), Err(e)) => {
                    assert_eq!(
                        planned.reason, cpu_refusal.reason,
                        "{name}: {scene_name} {m}: refused otherwise than the cpu backend"
                    );
                    assert!(
                        matches!(&e, RenderError::NotSupported(u) if *u == planned),
                        "{name}: {scene_name} {m}: refused otherwise than planned: {e}"
                    );
                    if matches!(planned.reason, UnsupportedReason::Translucency { .. }) {
                        assert!(e.to_string().contains("semi-transparent"), "{name}: {e}");
                    }
                }
                (want, plan, r) => panic!(
                    "{name}: {scene_name} {m}: the cpu backend plans {want:?}, this backend {plan:?}, and render gave {:?}",
                    r.map(|_| "a frame")
                ),
            }
        }
        assert!(rendered > 0, "{name}: no method renders {scene_name}");
    }
    assert!(
        failures.is_empty(),
        "{name} fails on the semi-transparent scenes:\n{}",
        failures.join("\n")
    );
}
