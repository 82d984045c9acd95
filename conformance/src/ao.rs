//! Ambient occlusion on SDF scenes: every backend's occluded frames against
//! the CPU's, and against the CPU's `ssaa64` frame with the same occlusion.

use std::sync::{Arc, OnceLock};

use subcone_scene::builtin::builtin;
use subcone_scene::{Backend, Frame, Method, RenderSettings, Scene};

use crate::named::{CTSS, NOAA, SRAA_RT};
use crate::{
    cached_reference, check_invariants, family, flip, save_failure, ReferenceCache,
    FRAME_TOLERANCE, H, REFERENCE_METHOD, W,
};

/// The SDF scenes of the ambient-occlusion case ([`check_ambient_occlusion`]):
/// open ground with objects standing on it, and a closed court with walls,
/// steps and a fountain.
pub const AO_SCENES: [&str; 2] = ["primitives", "sdf-atrium"];

/// The methods of the ambient-occlusion case: no antialiasing, SRAA-RT
/// (which reconstructs the occluded ambient term from its shaded samples)
/// and CTSS (which shades, and occludes, once per hit group).
pub const AO_METHODS: [Method; 3] = [NOAA, SRAA_RT, CTSS];

/// Occlusion rays per shaded point in the ambient-occlusion case: few, so
/// that the `ssaa64` reference (64 shaded samples per pixel, each with its
/// rays) stays quick, and enough that the ambient term takes several levels.
pub const AO_RAYS: u32 = 4;

/// The `ssaa64` reference of `scene` with [`AO_RAYS`] occlusion rays, on the
/// CPU backend (rendered once per scene and kept).
pub fn ao_reference_frame(scene: &Scene) -> Arc<Frame> {
    static CACHE: ReferenceCache = OnceLock::new();
    let settings = RenderSettings {
        ao_rays: AO_RAYS,
        ..RenderSettings::new(W, H)
    };
    cached_reference(&CACHE, scene, &settings, " with AO")
}

/// Ambient occlusion ([`RenderSettings::ao_rays`]) on SDF scenes: every
/// [`AO_METHODS`] frame of every [`AO_SCENES`] scene with [`AO_RAYS`] rays
/// casts occlusion rays, is darker than the same method without them
/// (occlusion only ever removes ambient light), keeps the frame invariants,
/// agrees with the CPU backend's frame within [`FRAME_TOLERANCE`] (the
/// occlusion rays are sphere traced with the shadow rays' march on both), and
/// is within its family's [`REFERENCE_BOUNDS`](crate::REFERENCE_BOUNDS) mean of the CPU's `ssaa64`
/// frame with the same occlusion ([`ao_reference_frame`]): the bounds hold
/// with occlusion as without, as it changes the shading, not the edges the
/// methods antialias.
pub fn check_ambient_occlusion(backend: &dyn Backend) {
    let name = backend.name();
    let cpu = subcone_cpu::CpuBackend::new();
    let settings = RenderSettings {
        ao_rays: AO_RAYS,
        ..RenderSettings::new(W, H)
    };
    let mut failures = Vec::new();
    for scene_name in AO_SCENES {
        let scene = builtin(scene_name).expect("built-in scene");
        let reference = ao_reference_frame(&scene);
        for method in AO_METHODS {
            let m = method.to_string();
            let frame = backend
                .render(&scene, &scene.camera, &method, &settings)
                .unwrap_or_else(|e| panic!("{name}: {scene_name} {m} with AO: {e}"));
            check_invariants(name, &scene, &method, &frame);
            assert!(
                frame.stats.rays.ao > 0,
                "{name}: {scene_name} {m}: no occlusion rays counted"
            );
            let plain = backend
                .render(&scene, &scene.camera, &method, &RenderSettings::new(W, H))
                .unwrap_or_else(|e| panic!("{name}: {scene_name} {m}: {e}"));
            let sum = |f: &Frame| f.color.iter().map(|c| c.element_sum() as f64).sum::<f64>();
            assert!(
                sum(&frame) < sum(&plain),
                "{name}: {scene_name} {m}: occlusion did not darken the frame"
            );
            let expected = cpu
                .render(&scene, &scene.camera, &method, &settings)
                .unwrap_or_else(|e| panic!("cpu reference: {scene_name} {m} with AO: {e}"));
            let f = flip(&expected, &frame);
            let t = FRAME_TOLERANCE;
            let label = format!("{m}+ao{AO_RAYS}");
            if f.mean > t.mean || f.p99() > t.p99 {
                let stem = save_failure(name, scene_name, &label, "cpu", &expected, &frame, &f);
                failures.push(format!(
                    "{scene_name} {label} against the cpu backend: FLIP mean {:.5} (limit {}), p99 {:.4} (limit {}); images in {stem}-*.png",
                    f.mean, t.mean, f.p99(), t.p99
                ));
            }
            let r = flip(&reference, &frame);
            let fam = family(&method);
            if r.mean > fam.mean {
                let stem = save_failure(
                    name,
                    scene_name,
                    &label,
                    &REFERENCE_METHOD.to_string(),
                    &reference,
                    &frame,
                    &r,
                );
                failures.push(format!(
                    "{scene_name} {label} against {REFERENCE_METHOD} with AO: FLIP mean {:.5} (limit {} for the {} family: {}); images in {stem}-*.png",
                    r.mean, fam.mean, fam.name(), fam.why
                ));
            }
            println!(
                "{name:>5} {scene_name:>16} {label:>12}: vs cpu FLIP mean {:.5} (≤ {}), p99 {:.4} (≤ {}); vs {REFERENCE_METHOD}+ao{AO_RAYS} mean {:.5} (≤ {}); {} occlusion rays",
                f.mean, t.mean, f.p99(), t.p99, r.mean, fam.mean, frame.stats.rays.ao
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
