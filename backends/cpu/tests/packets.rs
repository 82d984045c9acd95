//! Packets of rays against one ray at a time: the SDF renderer traces NoAA,
//! SSAA and the CTSS family eight rays at a time through the scene's compiled
//! program; with no program it traces each ray alone through the tree. The
//! frames must be equal bit for bit (colour, samples per pixel and the
//! counters), on every paper scene, the stiff scenes and glass.

use subcone_cpu::sphere::SdfView;
use subcone_kernels::passes::Passes;
use subcone_scene::sdf::{SDF_SCENES, STIFF_SCENES};
use subcone_scene::{builtin::builtin, Frame, Method, RenderSettings};

fn frames(name: &str, method: &str, w: u32, h: u32) -> (Frame, Frame) {
    let scene = builtin(name).unwrap();
    let m: Method = method.parse().unwrap();
    let mut s = RenderSettings::new(w, h);
    s.aovs = true;
    let passes = Passes::PRIMARY | Passes::SHADING | Passes::SHADOW;
    let packets = SdfView::of_scene(&scene, &scene.camera).unwrap();
    assert!(
        packets.program.is_some(),
        "{name}: the view compiles the tree"
    );
    let one_by_one = SdfView {
        program: None,
        ..SdfView::of_scene(&scene, &scene.camera).unwrap()
    };
    (
        packets.render(&m, &s, passes),
        one_by_one.render(&m, &s, passes),
    )
}

fn bits(f: &Frame) -> Vec<u32> {
    f.color
        .iter()
        .flat_map(|c| c.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn packets_render_what_single_rays_render() {
    let scenes = SDF_SCENES.iter().chain(STIFF_SCENES.iter());
    for name in scenes {
        for method in [
            "noaa",
            "ssaa4",
            "ctss",
            "ctss-r",
            "ctss-delayed",
            "ssaa4+ctss",
        ] {
            let (a, b) = frames(name, method, 40, 24);
            assert!(bits(&a) == bits(&b), "{name} {method}: the colours differ");
            assert_eq!(a.samples_per_pixel, b.samples_per_pixel, "{name} {method}");
            let (sa, sb) = (&a.stats, &b.stats);
            assert_eq!(
                (
                    sa.sdf_evaluations,
                    sa.shaded_samples,
                    sa.multi_sample_pixels,
                    sa.rays.shadow
                ),
                (
                    sb.sdf_evaluations,
                    sb.shaded_samples,
                    sb.multi_sample_pixels,
                    sb.rays.shadow
                ),
                "{name} {method}: the counters differ"
            );
        }
    }
}
