//! TAA (`subcone_kernels::taa`): its invariants as proptests (1,000 cases
//! each), and the stiff inputs a history must survive.
use glam::{Vec2, Vec3};
use proptest::prelude::*;
use subcone_kernels::taa::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 1000,
        ..ProptestConfig::default()
    }
}

const N: u32 = 6;

/// Linear colours, mostly in the display range, some HDR.
fn colour() -> impl Strategy<Value = Vec3> {
    prop_oneof![
        4 => (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0).prop_map(|(r, g, b)| Vec3::new(r, g, b)),
        1 => (0.0f32..=1000.0).prop_map(Vec3::splat),
    ]
}

/// Any f32 bits, NaN and infinities included.
fn any_f32() -> impl Strategy<Value = f32> {
    any::<u32>().prop_map(f32::from_bits)
}

fn any_colour() -> impl Strategy<Value = Vec3> {
    (any_f32(), any_f32(), any_f32()).prop_map(|(r, g, b)| Vec3::new(r, g, b))
}

fn image(c: impl Strategy<Value = Vec3>) -> impl Strategy<Value = Vec<Vec3>> {
    proptest::collection::vec(c, (N * N) as usize)
}

fn fetch(img: &[Vec3]) -> impl Fn(i32, i32) -> Vec3 + '_ {
    move |x, y| {
        assert!(
            (0..N as i32).contains(&x) && (0..N as i32).contains(&y),
            "fetch out of the image"
        );
        img[(y as u32 * N + x as u32) as usize]
    }
}

fn params(frames: u32) -> TaaParams {
    TaaParams::new((N, N)).with_history_frames(frames)
}

proptest! {
    #![proptest_config(config())]

    /// Whatever the inputs (NaN, infinities, any velocity, any parameters),
    /// the result is finite and non-negative, and no fetch leaves the image.
    #[test]
    fn any_input_gives_a_finite_colour(
        cur in image(any_colour()),
        hist in image(any_colour()),
        (x, y) in (-3i32..9, -3i32..9),
        v in (any_f32(), any_f32()),
        (e, w, g) in (any_f32(), any_f32(), any_f32()),
        frames in 0u32..40,
    ) {
        let p = TaaParams {
            exposure: e,
            min_current_weight: w,
            clip_gamma: g,
            ..params(frames)
        };
        let out = resolve_pixel(&fetch(&cur), &fetch(&hist), (x, y), Vec2::new(v.0, v.1), &p);
        prop_assert!(out.is_finite() && out.min_element() >= 0.0, "{out:?}");
    }

    /// Whatever the motion scale, the dilation code and the depths (NaN and
    /// infinities included), the motion used is one of the neighbourhood's
    /// vectors, no fetch leaves the image, and the resolve of it is finite
    /// and non-negative.
    #[test]
    fn any_dilation_and_scale_give_a_finite_colour(
        cur in image(colour()),
        hist in image(colour()),
        depth in proptest::collection::vec(any_f32(), (N * N) as usize),
        (x, y) in (-3i32..9, -3i32..9),
        scale in (any_f32(), any_f32()),
        code in 0u32..5,
        frames in 0u32..40,
    ) {
        let p = TaaParams {
            depth_dilation: code,
            motion_scale: [scale.0, scale.1],
            ..params(frames)
        };
        let motion = |x: i32, y: i32| {
            assert!((0..N as i32).contains(&x) && (0..N as i32).contains(&y), "motion fetch out of the image");
            Vec2::new(x as f32 * 0.7 - 2.0, y as f32 * -0.4 + 1.0)
        };
        let depth_at = |x: i32, y: i32| {
            assert!((0..N as i32).contains(&x) && (0..N as i32).contains(&y), "depth fetch out of the image");
            depth[(y as u32 * N + x as u32) as usize]
        };
        let v = dilated_motion(&motion, &depth_at, (x, y), &p);
        let (cx, cy) = (x.clamp(0, N as i32 - 1), y.clamp(0, N as i32 - 1));
        let from_neighbour = (-1..=1).any(|dy| (-1..=1).any(|dx| {
            motion((cx + dx).clamp(0, N as i32 - 1), (cy + dy).clamp(0, N as i32 - 1)) == v
        }));
        prop_assert!(from_neighbour, "{v:?} is no neighbour's vector");
        let out = resolve_pixel(&fetch(&cur), &fetch(&hist), (x, y), v, &p);
        prop_assert!(out.is_finite() && out.min_element() >= 0.0, "{out:?}");
    }

    /// A reset returns the current colour, whatever the history.
    #[test]
    fn a_reset_is_the_current_frame(cur in image(colour()), hist in image(colour()), x in 0i32..6, y in 0i32..6) {
        let out = resolve_pixel(&fetch(&cur), &fetch(&hist), (x, y), Vec2::ZERO, &params(0));
        prop_assert_eq!(out, cur[(y as u32 * N + x as u32) as usize]);
    }

    /// An image that does not change, over a history of the same image,
    /// stays itself (up to the tone map's rounding).
    #[test]
    fn a_still_image_is_a_fixed_point(img in image(colour()), x in 0i32..6, y in 0i32..6, frames in 1u32..64) {
        let out = resolve_pixel(&fetch(&img), &fetch(&img), (x, y), Vec2::ZERO, &params(frames));
        let want = img[(y as u32 * N + x as u32) as usize];
        prop_assert!((out - want).abs().max_element() <= 1e-4 * want.max_element().max(1.0), "{out:?} {want:?}");
    }

    /// The output lies between the clipped history and the current colour:
    /// within the hull of the neighbourhood and the history.
    #[test]
    fn the_result_is_bounded_by_its_inputs(cur in image(colour()), hist in image(colour()), x in 0i32..6, y in 0i32..6, frames in 1u32..64) {
        let out = resolve_pixel(&fetch(&cur), &fetch(&hist), (x, y), Vec2::ZERO, &params(frames));
        let hi = cur.iter().chain(&hist).fold(0.0f32, |m, c| m.max(c.max_element()));
        prop_assert!(out.max_element() <= hi * 1.001 + 1e-5, "{out:?} above {hi}");
    }

    /// Tone map and inverse, YCoCg and back: round trips.
    #[test]
    fn the_colour_transforms_round_trip(c in colour(), e in 0.01f32..100.0) {
        // Exposed lumas up to 1000: beyond, T(c) is within 2⁻¹⁰ of 1 and f32
        // keeps too few bits of 1 − luma for a 10⁻³ round trip.
        let e = e.min(1000.0 / c.max_element().max(1e-6));
        let t = tonemap(c, e);
        prop_assert!(luma(t) < 1.0);
        let back = tonemap_inverse(t, e);
        prop_assert!((back - c).abs().max_element() <= 1e-3 * c.max_element().max(1.0), "{back:?} {c:?}");
        let y = ycocg_to_rgb(rgb_to_ycocg(c));
        prop_assert!((y - c).abs().max_element() <= 1e-5 * c.max_element().max(1.0));
    }

    /// Clipping lands on the box (or inside it), on the segment toward the
    /// centre.
    #[test]
    fn clipping_lands_in_the_box(h in colour(), c in colour(), e in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0)) {
        let extent = Vec3::new(e.0, e.1, e.2);
        let out = clip_towards(h, c, extent);
        let inside = ((out - c).abs() - extent).max_element() <= 1e-4;
        prop_assert!(inside, "{out:?} outside {c:?} ± {extent:?}");
        if ((h - c).abs() - extent).max_element() <= 0.0 {
            prop_assert_eq!(out, h);
        }
    }

    /// The jitter stays inside the pixel; Halton coordinates are in [0, 1).
    #[test]
    fn the_jitter_stays_in_the_pixel(frame in any::<u32>(), phases in 0u32..1024) {
        let j = jitter(frame, phases);
        prop_assert!(j.x > -0.5 && j.x < 0.5 && j.y > -0.5 && j.y < 0.5, "{j:?}");
        let r = subsample_rotation(frame, Vec2::ZERO);
        prop_assert!(r.x.abs() < 0.5 && r.y.abs() < 0.5);
    }
}

/// Sixteen phases are sixteen distinct points spread over the pixel: their
/// mean is near its centre and every quadrant holds four.
#[test]
fn sixteen_phases_cover_the_pixel() {
    let pts: Vec<Vec2> = (0..16).map(|t| jitter(t, PHASES_FINE)).collect();
    for (i, a) in pts.iter().enumerate() {
        for b in &pts[i + 1..] {
            assert!((*a - *b).length() > 1e-3, "{a:?} repeats");
        }
    }
    let mean = pts.iter().copied().sum::<Vec2>() / 16.0;
    assert!(mean.length() < 0.05, "{mean:?}");
    for (sx, sy) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
        let n = pts
            .iter()
            .filter(|p| p.x * sx >= 0.0 && p.y * sy >= 0.0)
            .count();
        assert!((3..=5).contains(&n), "quadrant ({sx}, {sy}) holds {n}");
    }
    // The sequence repeats after its phases.
    assert_eq!(jitter(16, PHASES_FINE), jitter(0, PHASES_FINE));
    assert_eq!(jitter(8, PHASES_KARIS), jitter(0, PHASES_KARIS));
}

/// The history filter reproduces the history at pixel centres and is a
/// partition of unity, and a point off the image has no history.
#[test]
fn the_history_filter_interpolates() {
    for t in [0.0f32, 0.25, 0.5, 0.9] {
        let w = catmull_rom_weights(t);
        assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-6);
    }
    let img: Vec<Vec3> = (0..N * N).map(|i| Vec3::splat(i as f32)).collect();
    let f = fetch(&img);
    for (x, y) in [(0u32, 0u32), (2, 3), (5, 5)] {
        let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        assert_eq!(
            sample_history(&f, p, (N, N)),
            Some(img[(y * N + x) as usize])
        );
    }
    // A linear ramp is reproduced between centres too (Catmull-Rom is exact
    // on linear data away from the clamped border).
    let mid = sample_history(&f, Vec2::new(2.75, 2.5), (N, N)).unwrap();
    assert!((mid.x - (2.0 * N as f32 + 2.25)).abs() < 1e-4, "{mid:?}");
    for p in [
        Vec2::new(-0.1, 1.0),
        Vec2::new(1.0, 6.5),
        Vec2::splat(f32::NAN),
    ] {
        assert_eq!(sample_history(&f, p, (N, N)), None);
    }
}

/// A still camera accumulates: with the running mean, after 16 frames of a
/// pixel that alternates between two colours of one neighbourhood, the
/// (linear) history is their mean, the box filter (variance clipping keeps
/// it: the mean lies inside the neighbourhood's box).
#[test]
fn a_still_history_is_the_running_mean() {
    let a: Vec<Vec3> = (0..N * N)
        .map(|i| Vec3::splat(if i % 2 == 0 { 0.2 } else { 0.6 }))
        .collect();
    let b: Vec<Vec3> = (0..N * N)
        .map(|i| Vec3::splat(if i % 2 == 0 { 0.6 } else { 0.2 }))
        .collect();
    let mut hist = a.clone();
    for frame in 1..16u32 {
        let cur = if frame % 2 == 0 { &a } else { &b };
        hist = (0..N * N)
            .map(|i| {
                let (x, y) = ((i % N) as i32, (i / N) as i32);
                resolve_pixel(
                    &fetch(cur),
                    &fetch(&hist),
                    (x, y),
                    Vec2::ZERO,
                    &params(frame),
                )
            })
            .collect();
    }
    // Sixteen frames, eight of each: their mean, 0.4 (the linear resolve),
    // up to the early frames' clipping where the history leaves the box of
    // a corner's clamped neighbourhood.
    for c in &hist {
        assert!((c.x - 0.4).abs() < 0.01, "{c:?}");
    }
}

/// A history the current frame contradicts (a disocclusion: white history,
/// black neighbourhood) is clipped to the neighbourhood, not blended.
#[test]
fn a_contradicted_history_is_clipped() {
    let black = vec![Vec3::ZERO; (N * N) as usize];
    let white = vec![Vec3::ONE; (N * N) as usize];
    let out = resolve_pixel(
        &fetch(&black),
        &fetch(&white),
        (3, 3),
        Vec2::ZERO,
        &params(10),
    );
    assert_eq!(out, Vec3::ZERO);
    // Without clipping the blend would keep most of the white.
    let loose = TaaParams {
        clip_gamma: 1e30,
        ..params(10)
    };
    let kept = resolve_pixel(&fetch(&black), &fetch(&white), (3, 3), Vec2::ZERO, &loose);
    assert_eq!(kept, Vec3::ZERO, "a zero-variance box clips whatever γ");
}

/// What the tone-mapped resolve is for: a still pixel whose jittered samples
/// alternate between a dark surface and an HDR highlight 100× brighter.
/// Displayed through the tone map, the tone-mapped resolve's pixel is the
/// mean of the displayed samples (what a viewer's eye averages), while the
/// linear resolve's is the tone map of the mean radiance, much brighter.
#[test]
fn the_tone_mapped_resolve_averages_what_is_displayed() {
    let dark = Vec3::splat(0.05);
    let bright = Vec3::splat(5.0);
    let exposure = 1.0;
    let run = |space: ResolveSpace| {
        let mut hist = vec![dark; (N * N) as usize];
        for frame in 1..16u32 {
            let v = if frame % 2 == 0 { dark } else { bright };
            // A neighbourhood holding both, as at an edge.
            let cur: Vec<Vec3> = (0..N * N)
                .map(|i| if i % 2 == 0 { v } else { dark + bright - v })
                .collect();
            let p = params(frame).with_space(space);
            hist = (0..N * N)
                .map(|i| {
                    resolve_pixel(
                        &fetch(&cur),
                        &fetch(&hist),
                        ((i % N) as i32, (i / N) as i32),
                        Vec2::ZERO,
                        &p,
                    )
                })
                .collect();
        }
        hist[14]
    };
    let shown = |c: Vec3| luma(tonemap(c, exposure));
    let displayed_mean = 0.5 * (shown(dark) + shown(bright));
    let tone = shown(run(ResolveSpace::ToneMapped { exposure }));
    let linear = shown(run(ResolveSpace::Linear));
    assert!(
        (tone - displayed_mean).abs() < 0.5 * (linear - displayed_mean).abs(),
        "displayed mean {displayed_mean}: tone-mapped resolve shows {tone}, linear {linear}"
    );
}

/// A moving frame: a history of 8×8 distinct colours and a current frame,
/// the pixel's motion `v` in pixels.
fn moving_case() -> (Vec<Vec3>, Vec<Vec3>, Vec<Vec2>) {
    let hist: Vec<Vec3> = (0..N * N)
        .map(|i| Vec3::new((i % 7) as f32 * 0.1, (i % 5) as f32 * 0.2, 0.3))
        .collect();
    let cur: Vec<Vec3> = (0..N * N)
        .map(|i| Vec3::new(0.2, (i % 3) as f32 * 0.3, (i % 4) as f32 * 0.25))
        .collect();
    let vel: Vec<Vec2> = (0..N * N)
        .map(|i| Vec2::new((i % 5) as f32 * 0.45 - 0.9, (i % 3) as f32 * 0.7 - 0.7))
        .collect();
    (cur, hist, vel)
}

/// The resolve of every pixel of `moving_case` with `params`, the motion
/// vectors `vel`.
fn resolve_all(cur: &[Vec3], hist: &[Vec3], vel: &[Vec2], p: &TaaParams) -> Vec<Vec3> {
    (0..N * N)
        .map(|i| {
            let (x, y) = ((i % N) as i32, (i / N) as i32);
            resolve_pixel(&fetch(cur), &fetch(hist), (x, y), vel[i as usize], p)
        })
        .collect()
}

/// Bevy's motion vectors (`MotionVectorPrepass`: UV units, the image is 1,
/// current minus previous, `+y` down) with `motion_scale = (width,
/// height)` resolve as the same motion in pixels with the default scale.
#[test]
fn bevy_motion_vectors_resolve_as_pixels() {
    let (cur, hist, px) = moving_case();
    let size = Vec2::new(N as f32, N as f32);
    let uv: Vec<Vec2> = px.iter().map(|v| *v / size).collect();
    let want = resolve_all(&cur, &hist, &px, &params(3));
    let bevy = params(3).with_motion_scale([N as f32, N as f32]);
    let got = resolve_all(&cur, &hist, &uv, &bevy);
    for (g, w) in got.iter().zip(&want) {
        assert!((*g - *w).abs().max_element() <= 1e-5, "{g:?} {w:?}");
    }
    // Unscaled, the same UV vectors are a different (near-still) motion.
    let wrong = resolve_all(&cur, &hist, &uv, &params(3));
    assert!(wrong
        .iter()
        .zip(&want)
        .any(|(a, b)| (*a - *b).abs().max_element() > 1e-3));
}

/// FSR2's motion vectors (pixels, from the current frame's pixel to the
/// previous frame's position: previous minus current) with `motion_scale =
/// (−1, −1)` resolve bit for bit as the pixel vectors with the default.
#[test]
fn fsr2_motion_vectors_resolve_as_pixels() {
    let (cur, hist, px) = moving_case();
    let fsr2: Vec<Vec2> = px.iter().map(|v| -*v).collect();
    let want = resolve_all(&cur, &hist, &px, &params(3));
    let got = resolve_all(
        &cur,
        &hist,
        &fsr2,
        &params(3).with_motion_scale([-1.0, -1.0]),
    );
    assert_eq!(got, want);
    let wrong = resolve_all(&cur, &hist, &fsr2, &params(3));
    assert_ne!(wrong, want);
}

/// A zero or non-finite scale component reads as 1 (a zero-filled struct
/// reads pixels); any other is used as it is.
#[test]
fn the_motion_scale_domain() {
    let p = |s: [f32; 2]| TaaParams::new((N, N)).with_motion_scale(s).motion_scale();
    assert_eq!(TaaParams::new((N, N)).motion_scale(), Vec2::ONE);
    assert_eq!(p([0.0, f32::NAN]), Vec2::ONE);
    assert_eq!(p([f32::INFINITY, -0.0]), Vec2::ONE);
    assert_eq!(p([-1.0, 1920.0]), Vec2::new(-1.0, 1920.0));
}

/// Closest-depth dilation: a pixel beside a nearer one takes its vector
/// (in both depth orders); off, or with every neighbour farther, the
/// pixel keeps its own; off reads no depth at all.
#[test]
fn dilation_takes_the_nearest_vector() {
    let motion = |x: i32, y: i32| Vec2::new(x as f32, 10.0 * y as f32);
    // A far background (view depth 10) with one near pixel (2) at (3, 3),
    // and nothing hit (+∞) at (1, 1).
    let view = |x: i32, y: i32| match (x, y) {
        (3, 3) => 2.0,
        (1, 1) => f32::INFINITY,
        _ => 10.0,
    };
    let smallest = params(1).with_depth_dilation(DepthDilation::NearestSmallest);
    assert_eq!(
        dilated_motion(&motion, &view, (4, 4), &smallest),
        motion(3, 3)
    );
    assert_eq!(
        dilated_motion(&motion, &view, (2, 3), &smallest),
        motion(3, 3)
    );
    // Two away: its own.
    assert_eq!(
        dilated_motion(&motion, &view, (5, 5), &smallest),
        motion(5, 5)
    );
    // A tie keeps the pixel's own; +∞ is never nearest.
    assert_eq!(
        dilated_motion(&motion, &view, (0, 0), &smallest),
        motion(0, 0)
    );
    assert_eq!(
        dilated_motion(&motion, &view, (1, 1), &smallest),
        motion(0, 0)
    );
    // Reversed Z: 1 − view / 20, larger nearer, the same pick.
    let reversed = |x: i32, y: i32| 1.0 - view(x, y) / 20.0;
    let largest = params(1).with_depth_dilation(DepthDilation::NearestLargest);
    assert_eq!(
        dilated_motion(&motion, &reversed, (4, 4), &largest),
        motion(3, 3)
    );
    // Read in the other order, the near pixel is the farthest.
    assert_eq!(
        dilated_motion(&motion, &reversed, (4, 4), &smallest),
        motion(4, 4)
    );
    // Off (and unknown codes): the own vector, and the depth is not read.
    let unread = |_: i32, _: i32| -> f32 { panic!("depth read with dilation off") };
    for code in [0, 3, u32::MAX] {
        let p = TaaParams {
            depth_dilation: code,
            ..params(1)
        };
        assert_eq!(dilated_motion(&motion, &unread, (4, 4), &p), motion(4, 4));
    }
    // The codes round-trip.
    for d in [
        DepthDilation::Off,
        DepthDilation::NearestSmallest,
        DepthDilation::NearestLargest,
    ] {
        assert_eq!(DepthDilation::from_code(d.code()), d);
    }
}
