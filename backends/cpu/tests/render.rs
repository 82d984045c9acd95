//! The CPU backend on the built-in Cornell box: determinism, convergence of
//! SSAA, SRAA-RT against SRAA where the paper says it wins, and passes left out.
use subcone_cpu::CpuBackend;
use subcone_kernels::passes::Passes;
use subcone_scene::{builtin::builtin, Backend, Frame, Method, RenderSettings, Scene};

fn render(b: &CpuBackend, scene: &Scene, method: &str, size: u32) -> Frame {
    let m: Method = method.parse().unwrap();
    b.render(scene, &scene.camera, &m, &RenderSettings::new(size, size))
        .unwrap()
}

/// Whether no buffer of `f` has `part` in its name: the passes that would
/// use it allocated nothing.
fn no_buffer_named(f: &Frame, part: &str) -> bool {
    f.stats.buffers.iter().all(|(name, _)| !name.contains(part))
}

/// Mean absolute error of the 8-bit sRGB images a user would look at, in
/// `[0, 1]`, over the pixel rectangle `[x0, x1) × [y0, y1)`.
fn crop_error(a: &Frame, b: &Frame, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> f64 {
    let (sa, sb) = (a.to_srgb8(), b.to_srgb8());
    let mut sum = 0.0;
    let mut n = 0;
    for y in y0..y1 {
        for x in x0..x1 {
            let i = 3 * (y * a.width + x) as usize;
            for c in 0..3 {
                sum += (sa[i + c] as f64 - sb[i + c] as f64).abs() / 255.0;
                n += 1;
            }
        }
    }
    sum / n as f64
}

fn whole(f: &Frame) -> (u32, u32, u32, u32) {
    (0, 0, f.width, f.height)
}

#[test]
fn every_method_renders_cornell_deterministically() {
    let scene = builtin("cornell").unwrap();
    let b = CpuBackend::new();
    for m in ["noaa", "ssaa4", "ssaa16", "sraa", "sraa-rt"] {
        let a = render(&b, &scene, m, 40);
        let c = render(&b, &scene, m, 40);
        assert!(
            a.color.iter().all(|c| c.is_finite()),
            "{m}: non-finite pixel"
        );
        assert_eq!(a.color, c.color, "{m} is not deterministic");
        assert!(a.color.iter().any(|c| c.x > 0.5), "{m}: the image is dark");
    }
}

#[test]
fn ssaa_converges_to_the_reference() {
    let scene = builtin("cornell").unwrap();
    let b = CpuBackend::new();
    let reference = render(&b, &scene, "ssaa256", 64);
    let noaa = crop_error(
        &render(&b, &scene, "noaa", 64),
        &reference,
        whole(&reference),
    );
    let ssaa4 = crop_error(
        &render(&b, &scene, "ssaa4", 64),
        &reference,
        whole(&reference),
    );
    let ssaa16 = crop_error(
        &render(&b, &scene, "ssaa16", 64),
        &reference,
        whole(&reference),
    );
    println!("[cornell 64x64 vs ssaa256] mean |Δ| sRGB: noaa {noaa:.5}, ssaa4 {ssaa4:.5}, ssaa16 {ssaa16:.5}");
    assert!(
        ssaa16 < ssaa4 && ssaa4 < noaa,
        "SSAA does not converge: {noaa} {ssaa4} {ssaa16}"
    );
}

/// The paper's claim (§3.2–3.3, Fig. 4–5): with subpixel shadow rays and
/// secondary geometry, SRAA-RT resolves shadow edges and reflections that
/// primary-geometry SRAA blurs.
#[test]
fn sraa_rt_beats_sraa_on_shadow_edges_and_reflections() {
    let scene = builtin("cornell").unwrap();
    let b = CpuBackend::new();
    let size = 128;
    let reference = render(&b, &scene, "ssaa256", size);
    let sraa = render(&b, &scene, "sraa", size);
    let rt = render(&b, &scene, "sraa-rt", size);
    // Crops at 128×128 (pixels): the short block's shadow on the floor (no
    // geometric edge inside), and the inside of the mirror sphere (reflected
    // edges and the reflected floor shadow, away from its silhouette).
    let crops = [
        ("shadow edge", (96, 114, 124, 127)),
        ("reflection", (26, 86, 50, 110)),
    ];
    for (name, crop) in crops {
        let e_sraa = crop_error(&sraa, &reference, crop);
        let e_rt = crop_error(&rt, &reference, crop);
        println!("[cornell {size}x{size} {name} crop {crop:?}] mean |Δ| sRGB vs ssaa256: sraa {e_sraa:.5}, sraa-rt {e_rt:.5}");
        assert!(
            e_rt < e_sraa,
            "{name}: sraa-rt {e_rt} is not below sraa {e_sraa}"
        );
    }
}

/// Leave out what a scene does not need: no mirror, no secondary pass and no
/// secondary buffer, and forcing those passes on changes nothing.
#[test]
fn cornell_without_mirror_runs_no_secondary_pass() {
    let plain = builtin("cornell-nomirror").unwrap();
    let b = CpuBackend::new();
    let m: Method = "sraa-rt".parse().unwrap();
    let s = RenderSettings::new(48, 48);
    let lean = b.render(&plain, &plain.camera, &m, &s).unwrap();
    let secondary = Passes::SECONDARY
        | Passes::SECONDARY_SHADOW
        | Passes::SUBPIXEL_SECONDARY_GEOMETRY
        | Passes::SECONDARY_RECONSTRUCTION;
    assert!(
        !lean.stats.passes.intersects(secondary),
        "{:?}",
        lean.stats.passes
    );
    assert!(
        no_buffer_named(&lean, "secondary"),
        "{:?}",
        lean.stats.buffers
    );
    assert_eq!(lean.stats.rays.secondary, 0);
    let forced = b
        .render(
            &plain,
            &plain.camera,
            &m,
            &RenderSettings {
                force_passes: secondary,
                ..s
            },
        )
        .unwrap();
    assert!(forced.stats.passes.contains(secondary));
    assert!(forced.stats.buffer_bytes() > lean.stats.buffer_bytes());
    assert_eq!(
        lean.color, forced.color,
        "forcing the secondary passes on changed the image"
    );
    println!(
        "[cornell-nomirror 48x48 sraa-rt] buffers {} bytes lean, {} bytes with secondary passes forced",
        lean.stats.buffer_bytes(),
        forced.stats.buffer_bytes()
    );
    // And the mirror scene does run them.
    let mirror = builtin("cornell").unwrap();
    let f = b.render(&mirror, &mirror.camera, &m, &s).unwrap();
    assert!(f.stats.passes.contains(secondary));
}

/// A scene without lights runs no shadow pass.
#[test]
fn scene_without_lights_runs_no_shadow_pass() {
    let mut dark = builtin("cornell").unwrap();
    dark.lights.clear();
    dark.touch();
    let b = CpuBackend::new();
    for m in ["noaa", "sraa", "sraa-rt"] {
        let f = render(&b, &dark, m, 32);
        assert!(
            !f.stats
                .passes
                .intersects(Passes::SHADOW | Passes::SUBPIXEL_SHADOW | Passes::SECONDARY_SHADOW),
            "{m}"
        );
        assert_eq!(f.stats.rays.shadow, 0, "{m}");
        assert!(no_buffer_named(&f, "shadow"), "{m}: {:?}", f.stats.buffers);
    }
}

#[test]
fn bad_settings_are_errors_not_panics() {
    let scene = builtin("cornell").unwrap();
    let b = CpuBackend::new();
    let m: Method = "sraa-rt".parse().unwrap();
    for (w, h) in [(0, 0), (0, 10), (100_000, 100_000), (16_385, 1)] {
        let e = b
            .render(&scene, &scene.camera, &m, &RenderSettings::new(w, h))
            .unwrap_err();
        assert!(e.to_string().contains("resolution"), "{e}");
    }
    let mut cam = scene.camera;
    cam.fov_y = 0.0;
    let e = b
        .render(&scene, &cam, &m, &RenderSettings::new(8, 8))
        .unwrap_err();
    assert!(e.to_string().contains("field of view"), "{e}");
    let e = b
        .render(
            &scene,
            &scene.camera,
            &"ctss".parse().unwrap(),
            &RenderSettings::new(8, 8),
        )
        .unwrap_err();
    assert!(e.to_string().contains("signed distance field"), "{e}");
}

/// Adaptive subpixel shadow rays (`render::shadow_agreement`).
mod adaptive_shadows {
    use glam::Vec3;
    use subcone_cpu::{shadow_agreement, CpuBackend};
    use subcone_scene::{builtin::builtin, Backend, Method, RenderSettings};

    /// 3×3 image, one light, layers `[base, light 0]`.
    fn agreement(bits: [u32; 9], lit: [f32; 9]) -> (u32, u32) {
        let values: Vec<Vec3> = lit
            .iter()
            .flat_map(|&v| [Vec3::ONE, Vec3::splat(v)])
            .collect();
        shadow_agreement(&bits, &values, 2, 0, 1, 1, 1, 1, 3, 3)
    }

    #[test]
    fn agreement_skips_only_where_the_neighbourhood_agrees() {
        // All lit: inherit "lit", no ray.
        assert_eq!(agreement([0; 9], [0.5; 9]), (0, 0));
        // All shadowed (black layer): inherit "shadowed", no ray.
        assert_eq!(agreement([1; 9], [0.0; 9]), (0, 1));
        // Disagreement with light reaching some neighbours: cast.
        let mut bits = [0; 9];
        bits[4] = 1;
        let mut lit = [0.5; 9];
        lit[4] = 0.0;
        assert_eq!(agreement(bits, lit), (1, 0));
        // Disagreement, but the light's layer is black everywhere (grazing
        // light): the gate cannot change the image, no ray.
        assert_eq!(agreement(bits, [0.0; 9]), (0, 0));
        // A corner pixel reads only its 2×2 neighbourhood.
        let values = vec![Vec3::ONE; 18];
        let mut bits = [0u32; 9];
        bits[8] = 1;
        assert_eq!(
            shadow_agreement(&bits, &values, 2, 0, 1, 0, 0, 1, 3, 3),
            (0, 0)
        );
        assert_eq!(
            shadow_agreement(&bits, &values, 2, 0, 1, 2, 2, 1, 3, 3),
            (1, 0)
        );
    }

    /// The adaptive subpixel shadow rays against the exhaustive ones on the
    /// Cornell box (one light, a mirror): far fewer shadow rays, the same
    /// image but for a few pixels inside shadows that no shaded sample sees.
    #[test]
    fn adaptive_subpixel_shadows_match_exhaustive_ones() {
        let scene = builtin("cornell").unwrap();
        let method: Method = "sraa-rt".parse().unwrap();
        let s = RenderSettings::new(96, 96);
        let adaptive = CpuBackend::new()
            .render(&scene, &scene.camera, &method, &s)
            .unwrap();
        let full = CpuBackend::new()
            .with_exhaustive_subpixel_shadows(true)
            .render(&scene, &scene.camera, &method, &s)
            .unwrap();
        let (a, f) = (adaptive.stats.rays, full.stats.rays);
        assert_eq!(a.primary, f.primary);
        assert_eq!(a.geometry, f.geometry);
        assert_eq!(a.secondary, f.secondary);
        // The exhaustive pass casts about 3 subpixel shadow rays per pixel for
        // its one light; the adaptive one keeps well under half of them.
        assert!(
            (a.shadow as f64) < 0.6 * f.shadow as f64,
            "shadow rays: adaptive {} vs exhaustive {}",
            a.shadow,
            f.shadow
        );
        let diffs: Vec<f32> = adaptive
            .color
            .iter()
            .zip(&full.color)
            .map(|(p, q)| (*p - *q).abs().max_element())
            .collect();
        let differing = diffs.iter().filter(|&&d| d > 0.0).count();
        let mean = diffs.iter().sum::<f32>() / diffs.len() as f32;
        // Measured: a handful of pixels on 96×96, mean difference ~1e-4.
        assert!(
            differing <= diffs.len() / 100,
            "{differing} of {} pixels differ",
            diffs.len()
        );
        assert!(mean < 1e-3, "mean difference {mean}");
    }
}
