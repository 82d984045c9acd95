//! Packets of rays against one ray at a time: the SDF renderer traces NoAA,
//! SSAA, the CTSS family and SRAA-RT's shading and geometry passes eight
//! rays at a time through the scene's compiled program; with no program it traces each ray alone through the tree. The
//! frames must be equal bit for bit (colour, samples per pixel and the
//! counters), on every paper scene, the stiff scenes and glass.

use subcone_cpu::sphere::SdfView;
use subcone_kernels::passes::{required_passes, Passes};
use subcone_scene::builtin::{SDF_SCENES, STIFF_SCENES};
use subcone_scene::{builtin::builtin, Frame, Method, RenderSettings};

fn frames(name: &str, method: &str, w: u32, h: u32) -> (Frame, Frame) {
    let scene = builtin(name).unwrap();
    let m: Method = method.parse().unwrap();
    let mut s = RenderSettings::new(w, h);
    s.aovs = true;
    // The scene's own passes (SRAA-RT's subpixel shadows among them).
    let passes = required_passes(m.technique(), scene.features()).unwrap();
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
        packets.render(&m, &s, passes).unwrap(),
        one_by_one.render(&m, &s, passes).unwrap(),
    )
}

fn bits(f: &Frame) -> Vec<u32> {
    f.color
        .iter()
        .flat_map(|c| c.to_array().map(f32::to_bits))
        .collect()
}

/// The centre AOVs (view depth, normal, albedo, light visibility, mirror),
/// bit for bit; they are taken in packets too.
fn aov_bits(f: &Frame) -> Vec<u32> {
    let v3 = |v: &Option<Vec<glam::Vec3>>| -> Vec<u32> {
        let v = v.as_ref().expect("AOVs were asked for");
        v.iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .collect()
    };
    let f1 = |v: &Option<Vec<f32>>| -> Vec<u32> {
        let v = v.as_ref().expect("AOVs were asked for");
        v.iter().map(|x| x.to_bits()).collect()
    };
    let mut out = f1(&f.depth);
    out.extend(v3(&f.normal));
    out.extend(v3(&f.albedo));
    out.extend(f.light_visibility.as_ref().expect("AOVs were asked for"));
    out.extend(f1(&f.mirror));
    out
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
            "ctss+edges",
            "sraa-rt",
            "sraa-rt-paper",
        ] {
            let (a, b) = frames(name, method, 40, 24);
            assert!(bits(&a) == bits(&b), "{name} {method}: the colours differ");
            assert!(
                aov_bits(&a) == aov_bits(&b),
                "{name} {method}: the AOVs differ"
            );
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

/// SRAA-RT with every subsample's shadow rays cast (not only where the
/// shaded samples around disagree): the packets cast the same rays.
#[test]
fn packets_cast_every_subpixel_shadow_ray_single_rays_cast() {
    for name in SDF_SCENES {
        let scene = builtin(name).unwrap();
        let m: Method = "sraa-rt".parse().unwrap();
        let s = RenderSettings::new(40, 24);
        let passes = required_passes(m.technique(), scene.features()).unwrap();
        let exhaustive = |program: bool| {
            let mut v = SdfView::of_scene(&scene, &scene.camera).unwrap();
            v.exhaustive_subpixel_shadows = true;
            if !program {
                v.program = None;
            }
            v.render(&m, &s, passes).unwrap()
        };
        let (a, b) = (exhaustive(true), exhaustive(false));
        assert!(bits(&a) == bits(&b), "{name}: the colours differ");
        assert_eq!(
            (a.stats.sdf_evaluations, a.stats.rays.shadow),
            (b.stats.sdf_evaluations, b.stats.rays.shadow),
            "{name}: the counters differ"
        );
        assert!(
            !scene.lights.is_empty() || a.stats.rays.shadow == 0,
            "{name}: shadow rays without lights"
        );
    }
}

/// Plain SRAA has no sphere-traced path: the view says so as a value (the
/// plan refuses it before any backend renders), rather than rendering it as
/// another technique.
#[test]
fn a_technique_without_a_sphere_traced_path_is_an_error() {
    let scene = builtin("primitives").unwrap();
    let view = SdfView::of_scene(&scene, &scene.camera).unwrap();
    let m: Method = "sraa".parse().unwrap();
    let passes = Passes::PRIMARY | Passes::SHADING;
    let err = view
        .render(&m, &RenderSettings::new(8, 8), passes)
        .unwrap_err();
    assert!(err.to_string().contains("no sphere-traced path"), "{err}");
}
