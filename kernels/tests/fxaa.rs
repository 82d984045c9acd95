//! FXAA 3.11 (`subcone_kernels::fxaa`): its invariants as proptests (2,000
//! cases each) and what it is for, measured on analytic edges.
use glam::{Vec3, Vec4};
use proptest::prelude::*;
use subcone_kernels::fxaa::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 2000,
        ..ProptestConfig::default()
    }
}

const N: i32 = 6;

/// A clamped fetch over the encoded pixels of an `N`×`N` linear image.
fn fetch_of(img: &[Vec3]) -> impl Fn(i32, i32) -> Vec4 + '_ {
    move |x, y| fxaa_encode(img[(y.clamp(0, N - 1) * N + x.clamp(0, N - 1)) as usize])
}

/// Linear colours, mostly in the display range, some above it (HDR).
fn colour() -> impl Strategy<Value = Vec3> {
    prop_oneof![
        4 => (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0).prop_map(|(r, g, b)| Vec3::new(r, g, b)),
        1 => (0.0f32..=8.0).prop_map(Vec3::splat),
        1 => prop_oneof![Just(Vec3::ZERO), Just(Vec3::ONE)],
    ]
}

/// Any f32 bits, NaN and infinities included.
fn any_colour() -> impl Strategy<Value = Vec3> {
    (any::<u32>(), any::<u32>(), any::<u32>())
        .prop_map(|(r, g, b)| Vec3::new(f32::from_bits(r), f32::from_bits(g), f32::from_bits(b)))
}

/// Parameters over FXAA's documented ranges.
fn params() -> impl Strategy<Value = FxaaParams> {
    prop_oneof![
        Just(FxaaParams::QUALITY),
        (0.0f32..=1.0, 0.063f32..=0.333, 0.0312f32..=0.0833).prop_map(|(s, t, m)| FxaaParams {
            subpix: s,
            edge_threshold: t,
            edge_threshold_min: m,
            _pad: 0.0,
        }),
    ]
}

proptest! {
    #![proptest_config(config())]

    /// The output is the centre or a blend of the centre with one direct
    /// neighbour (the final tap moves at most one pixel along one axis): per
    /// channel it lies between the minimum and maximum of the centre and its
    /// four neighbours, and so within the 3×3 neighbourhood's range.
    #[test]
    fn output_stays_within_the_cross_neighbourhood(
        img in prop::collection::vec(colour(), (N * N) as usize),
        x in 0..N, y in 0..N, p in params(),
    ) {
        let f = fetch_of(&img);
        let out = fxaa_pixel(&f, x, y, &p);
        let cross = [f(x, y), f(x - 1, y), f(x + 1, y), f(x, y - 1), f(x, y + 1)];
        let lo = cross.iter().fold(Vec3::splat(f32::MAX), |a, c| a.min(c.truncate()));
        let hi = cross.iter().fold(Vec3::splat(f32::MIN), |a, c| a.max(c.truncate()));
        prop_assert!(out.cmpge(lo - 1e-6).all() && out.cmple(hi + 1e-6).all(),
            "{out} outside [{lo}, {hi}]");
    }

    /// A flat image is returned unchanged, whatever the parameters.
    #[test]
    fn flat_images_are_unchanged(c in colour(), x in 0..N, y in 0..N, p in params()) {
        let img = vec![c; (N * N) as usize];
        let f = fetch_of(&img);
        prop_assert_eq!(fxaa_pixel(&f, x, y, &p), f(x, y).truncate());
    }

    /// Garbage in (NaN, ±∞, any bits, any parameters), no garbage out: the
    /// output is finite and in [0, 1].
    #[test]
    fn any_input_gives_a_display_colour(
        img in prop::collection::vec(any_colour(), (N * N) as usize),
        x in 0..N, y in 0..N,
        s in any::<u32>(), t in any::<u32>(), m in any::<u32>(),
    ) {
        let p = FxaaParams {
            subpix: f32::from_bits(s),
            edge_threshold: f32::from_bits(t),
            edge_threshold_min: f32::from_bits(m),
            _pad: 0.0,
        };
        let f = fetch_of(&img);
        // The raw fetch may even return NaN: the kernel cleans it.
        let raw = |x: i32, y: i32| {
            let v = f(x, y);
            if (x + y) % 3 == 0 { Vec4::NAN } else { v }
        };
        for out in [fxaa_pixel(&f, x, y, &p), fxaa_pixel(&raw, x, y, &FxaaParams::QUALITY)] {
            prop_assert!(out.is_finite() && out.cmpge(Vec3::ZERO).all() && out.cmple(Vec3::ONE).all(),
                "{out}");
        }
        let d = fxaa_decode(fxaa_pixel(&f, x, y, &p));
        prop_assert!(d.is_finite() && d.cmpge(Vec3::ZERO).all() && d.cmple(Vec3::ONE).all());
    }

    /// Encoding is the display's: clamped, sRGB, 8 bits, with the Rec. 601
    /// luma of the stored colour; decoding inverts it up to the 8-bit step.
    #[test]
    fn encode_and_decode_invert_on_the_display_range(c in colour()) {
        let e = fxaa_encode(c);
        for v in e.to_array() {
            prop_assert!(((v * 255.0).round() - v * 255.0).abs() < 1e-3, "{e}");
        }
        prop_assert!((e.w - e.truncate().dot(LUMA_WEIGHTS)).abs() <= 0.5 / 255.0 + 1e-6);
        let back = fxaa_decode(e.truncate());
        let want = c.clamp(Vec3::ZERO, Vec3::ONE);
        prop_assert!((back - want).abs().max_element() < 5e-3, "{c} -> {back}");
    }
}

/// A white half-plane on black, `above(x, y)` in continuous pixel
/// coordinates (pixel `(i, j)` covers `[i, i+1]×[j, j+1]`): the aliased
/// image (one sample at each centre), and the displayed coverage of a 32×32
/// supersampled reference, sRGB-encoded.
fn half_plane(w: i32, h: i32, above: impl Fn(f32, f32) -> bool) -> (Vec<Vec3>, Vec<f32>) {
    let mut aliased = Vec::new();
    let mut truth = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let (cx, cy) = (x as f32 + 0.5, y as f32 + 0.5);
            aliased.push(if above(cx, cy) { Vec3::ONE } else { Vec3::ZERO });
            let mut n = 0;
            for sy in 0..32 {
                for sx in 0..32 {
                    let (px, py) = (
                        x as f32 + (sx as f32 + 0.5) / 32.0,
                        y as f32 + (sy as f32 + 0.5) / 32.0,
                    );
                    n += above(px, py) as u32;
                }
            }
            truth.push(linear_to_srgb(n as f32 / 1024.0));
        }
    }
    (aliased, truth)
}

/// Mean absolute display error of the aliased image and of its FXAA, over the
/// pixels the edge crosses (the others are exact in both).
fn edge_errors(w: i32, h: i32, above: impl Fn(f32, f32) -> bool) -> (f32, f32, usize) {
    let (aliased, truth) = half_plane(w, h, above);
    let fetch =
        |x: i32, y: i32| fxaa_encode(aliased[(y.clamp(0, h - 1) * w + x.clamp(0, w - 1)) as usize]);
    let (mut e_alias, mut e_fxaa, mut n) = (0.0, 0.0, 0);
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            if truth[i] == 0.0 || truth[i] >= 1.0 - 1e-6 {
                continue;
            }
            e_alias += (fetch(x, y).x - truth[i]).abs();
            e_fxaa += (fxaa_pixel(&fetch, x, y, &FxaaParams::QUALITY).x - truth[i]).abs();
            n += 1;
        }
    }
    (e_alias / n as f32, e_fxaa / n as f32, n)
}

/// FXAA's purpose: on shallow and steep straight edges (its horizontal and
/// vertical spans) and on a 45° edge, the filtered image is closer to the
/// edge's true coverage than the aliased one.
#[test]
fn straight_edges_move_towards_their_coverage() {
    type Inside = Box<dyn Fn(f32, f32) -> bool>;
    let cases: [(&str, Inside); 4] = [
        ("shallow", Box::new(|x, y| y > 0.21 * x + 9.3)),
        ("steep", Box::new(|x, y| x > 0.27 * y + 11.1)),
        ("45°", Box::new(|x, y| y > x - 0.3)),
        ("shallow, white below", Box::new(|x, y| y < 0.13 * x + 20.6)),
    ];
    for (name, above) in cases {
        let (alias, fxaa, n) = edge_errors(40, 40, above);
        println!("{name}: {n} edge pixels, aliased error {alias:.4}, FXAA {fxaa:.4}");
        assert!(n > 20, "{name}: the edge crosses only {n} pixels");
        assert!(
            fxaa < 0.8 * alias,
            "{name}: FXAA error {fxaa} not clearly below the aliased {alias}"
        );
    }
}

/// An axis-aligned step is already the best one-sample image of itself; FXAA
/// changes it by no more than its sub-pixel term (subpix × (1/3 · 7/3 · 1/3)²
/// ≈ 0.05 of the step, from the shader's subpixC..subpixH).
#[test]
fn an_axis_aligned_step_is_barely_touched() {
    let img: Vec<Vec3> = (0..N * N)
        .map(|i| if i % N < 3 { Vec3::ZERO } else { Vec3::ONE })
        .collect();
    let f = fetch_of(&img);
    for y in 0..N {
        for x in 0..N {
            let out = fxaa_pixel(&f, x, y, &FxaaParams::QUALITY);
            let d = (out - f(x, y).truncate()).abs().max_element();
            assert!(d <= 0.06, "({x}, {y}) moved by {d}");
        }
    }
}

/// `edge_clamped` reads the pixel inside the image, the nearest edge pixel
/// outside it, and never panics: a zero size reads as 1, a short slice
/// reads black past its end.
#[test]
fn edge_clamped_reads_the_nearest_pixel_of_the_image() {
    let encoded: Vec<Vec4> = (0..12).map(|i| Vec4::splat(i as f32)).collect();
    let fetch = edge_clamped(&encoded, 4, 3);
    assert_eq!(fetch(1, 2), Vec4::splat(9.0));
    assert_eq!(fetch(-5, -5), Vec4::splat(0.0));
    assert_eq!(fetch(9, 1), Vec4::splat(7.0));
    assert_eq!(fetch(2, i32::MAX), Vec4::splat(10.0));
    assert_eq!(edge_clamped(&encoded, 0, 0)(3, 3), Vec4::splat(0.0));
    assert_eq!(edge_clamped(&encoded[..5], 4, 3)(3, 2), Vec4::ZERO);
}
