//! Semi-transparent SDF materials (CTSS §5.3) on the `glass` scene: CTSS with
//! the `K` masks against SSAA16 with alpha blending, and a half-opaque pane
//! that shows both what it is and what lies behind it.
mod common;

use common::render;
use subcone_cpu::CpuBackend;
use subcone_scene::{builtin::builtin, Backend, Frame, Method, RenderSettings, Scene};

const W: u32 = 64;
const H: u32 = 36;
/// The pane's material in the `glass` scene.
const PANE: usize = 4;

fn mean_abs_error(a: &Frame, b: &Frame) -> f64 {
    let sum: f64 = a
        .color
        .iter()
        .zip(&b.color)
        .map(|(x, y)| ((*x - *y).abs().element_sum() / 3.0) as f64)
        .sum();
    sum / a.color.len() as f64
}

fn with_pane_alpha(scene: &Scene, alpha: f32) -> Scene {
    let mut s = scene.clone();
    s.materials[PANE].alpha = alpha;
    s
}

/// CTSS on the glass scene is close to SSAA16 (mean absolute error per
/// channel, linear radiance, below 0.01 at 64×36; measured 0.0058) and closer
/// than NoAA (0.0062).
#[test]
fn ctss_on_glass_is_close_to_ssaa16() {
    let scene = builtin("glass").unwrap();
    assert!(scene.has_translucency());
    let reference = render(&scene, "ssaa16", W, H);
    let ctss = render(&scene, "ctss", W, H);
    let noaa = render(&scene, "noaa", W, H);
    let (e_ctss, e_noaa) = (
        mean_abs_error(&ctss, &reference),
        mean_abs_error(&noaa, &reference),
    );
    println!("glass {W}x{H}: mean abs error vs ssaa16: ctss {e_ctss:.4}, noaa {e_noaa:.4}");
    assert!(e_ctss < 0.01, "ctss error {e_ctss}");
    assert!(e_ctss < e_noaa, "ctss {e_ctss} is not below noaa {e_noaa}");
    for f in [&ctss, &reference, &noaa] {
        assert!(f
            .color
            .iter()
            .all(|c| c.is_finite() && c.min_element() >= 0.0));
    }
}

/// Where the half-opaque pane covers a pixel, the pixel lies strictly between
/// the same method's image with the pane opaque (the front colour) and with
/// the pane removed (alpha 0, the back colour), near their mean: it shows
/// both. Checked inside the pane (the pixel and its eight neighbours all see
/// front and back differ by 0.1 in some channel), for CTSS, SSAA+CTSS, NoAA
/// and the SSAA reference.
#[test]
fn half_opaque_pane_shows_front_and_back() {
    let scene = builtin("glass").unwrap();
    assert_eq!(scene.materials[PANE].alpha, 0.5);
    let (w, h) = (W as i32, H as i32);
    // CTSS-R is left out: it stops at a hard hit and renormalises partial
    // masks (eq. 6) where the pane is opaque or absent, but fills the stopping
    // mask where it is not, so edges behind the pane mix with other weights in
    // the three images and the per-channel share is not the pane's alone.
    for (method, lo, hi) in [
        ("ctss", 0.4, 0.6),
        ("ssaa16", 0.4, 0.6),
        ("ssaa4+ctss", 0.4, 0.6),
        ("noaa", 0.4, 0.6),
    ] {
        let front = render(&with_pane_alpha(&scene, 1.0), method, W, H);
        let back = render(&with_pane_alpha(&scene, 0.0), method, W, H);
        let img = render(&scene, method, W, H);
        let differs = |x: i32, y: i32| {
            let i = (y * w + x) as usize;
            (front.color[i] - back.color[i]).abs().max_element() >= 0.1
        };
        let mut checked = 0;
        for y in 1..h - 1 {
            for x in 1..w - 1 {
                if !(-1..=1).all(|dy| (-1..=1).all(|dx| differs(x + dx, y + dy))) {
                    continue;
                }
                let i = (y * w + x) as usize;
                let (f, b, c) = (front.color[i], back.color[i], img.color[i]);
                // The share of the front colour in each channel where front
                // and back differ by 0.05 or more: alpha = 0.5.
                for k in 0..3 {
                    if (f[k] - b[k]).abs() < 0.05 {
                        continue;
                    }
                    let share = (c[k] - b[k]) / (f[k] - b[k]);
                    assert!(
                        share > lo && share < hi,
                        "{method}: pixel ({x}, {y}) {c} is not between front {f} and back {b} (channel {k}: share {share})"
                    );
                }
                checked += 1;
            }
        }
        assert!(
            checked >= 30,
            "{method}: only {checked} pane pixels checked"
        );
    }
}

/// Opacity out of range is clamped and NaN is opaque: a NaN pane renders as
/// the opaque pane, an alpha of 7 too, an alpha of −1 as no pane.
#[test]
fn out_of_range_alpha_is_clamped() {
    let scene = builtin("glass").unwrap();
    let opaque = render(&with_pane_alpha(&scene, 1.0), "ctss", W, H);
    let none = render(&with_pane_alpha(&scene, 0.0), "ctss", W, H);
    assert_eq!(
        render(&with_pane_alpha(&scene, f32::NAN), "ctss", W, H).color,
        opaque.color
    );
    assert_eq!(
        render(&with_pane_alpha(&scene, 7.0), "ctss", W, H).color,
        opaque.color
    );
    assert_eq!(
        render(&with_pane_alpha(&scene, -1.0), "ctss", W, H).color,
        none.color
    );
}

/// Triangle scenes refuse semi-transparent materials instead of drawing them
/// opaque.
#[test]
fn triangle_scenes_refuse_translucency() {
    let mut scene = builtin("cornell").unwrap();
    scene.materials[0].alpha = 0.5;
    let r = CpuBackend::new().render(
        &scene,
        &scene.camera,
        &Method::new(subcone_kernels::passes::Technique::NoAa),
        &RenderSettings::new(8, 8),
    );
    assert!(r.is_err());
}

/// Methods whose paths do not carry opacity refuse a semi-transparent scene
/// with an error that names what does render it, instead of drawing it opaque.
#[test]
fn methods_without_opacity_refuse_glass() {
    let scene = builtin("glass").expect("built-in scene");
    for m in ["sraa-rt", "ctss-delayed", "ctss+edges"] {
        let method: Method = m.parse().expect("method name");
        let err = CpuBackend::new()
            .render(&scene, &scene.camera, &method, &RenderSettings::new(16, 12))
            .expect_err(m)
            .to_string();
        assert!(
            err.contains("semi-transparent") && err.contains("ctss"),
            "{m}: {err}"
        );
    }
}

/// The semi-transparent path against the opaque one (`sphere::translucent`).
mod translucent_path {
    use subcone_kernels::passes::{required_passes, Technique};
    use subcone_scene::builtin::builtin;
    use subcone_scene::builtin::{SDF_SCENES, STIFF_SCENES};
    use subcone_scene::{Method, RenderSettings};

    use subcone_cpu::sphere::SdfView;

    /// The semi-transparent path with every opacity 1 is the opaque renderer,
    /// bit for bit, on every built-in SDF scene and every SDF method.
    #[test]
    fn opaque_scenes_render_identically_on_the_translucent_path() {
        let methods = [
            Method::new(Technique::NoAa),
            Method::ssaa_grid(2),
            Method::new(Technique::Ctss),
            Method::new(Technique::CtssR),
            "ssaa4+ctss".parse().unwrap(),
        ];
        for name in SDF_SCENES.iter().chain(STIFF_SCENES.iter()) {
            let scene = builtin(name).unwrap();
            assert!(!scene.has_translucency(), "{name}");
            let view = SdfView::of_scene(&scene, &scene.camera).expect("an SDF scene");
            let s = RenderSettings::new(32, 18);
            for m in &methods {
                let passes = required_passes(m.technique(), scene.features()).unwrap();
                let a = view.render_with(m, &s, passes, false).unwrap();
                let b = view.render_with(m, &s, passes, true).unwrap();
                let same =
                    a.color.iter().zip(&b.color).all(|(x, y)| {
                        x.to_array().map(f32::to_bits) == y.to_array().map(f32::to_bits)
                    });
                assert!(same, "{name} {m}: the translucent path changed the image");
                assert_eq!(a.stats.shaded_samples, b.stats.shaded_samples, "{name} {m}");
            }
        }
    }
}
