//! The tone-mapped SRAA resolve (`sraa::resolve_pixel_tone_mapped`, Karis
//! 2014's weights `1 / (1 + luma(c · exposure))`) against the linear box
//! (`sraa::resolve_pixel`) and against the tone map it stands for,
//! `T(c) = c / (1 + luma(c))`: proptests of 2,000 cases each, and the
//! named edge cases.

use glam::Vec3;
use proptest::prelude::*;
use subcone_kernels::sraa::{
    resolve_pixel, resolve_pixel_tone_mapped, tone_map_weight, ResolveSpace, RESOLVE_LUMA,
};

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 2000,
        ..ProptestConfig::default()
    }
}

/// The reversible tone map of Karis 2014 after the exposure, in f64:
/// `T(e·c) = e·c / (1 + luma(e·c))`.
fn tone_map(c: Vec3, exposure: f32) -> [f64; 3] {
    let e = f64::from(exposure);
    let c = c.to_array().map(f64::from);
    let w = RESOLVE_LUMA.to_array().map(f64::from);
    let l = (c[0] * w[0] + c[1] * w[1] + c[2] * w[2]) * e;
    c.map(|x| x * e / (1.0 + l))
}

/// The mean of the subsamples' tone-mapped colours: what a box filter in
/// tone-mapped space shows.
fn tone_mapped_box(subs: &[Vec3; 4], exposure: f32) -> [f64; 3] {
    let mut m = [0.0; 3];
    for c in subs {
        for (m, t) in m.iter_mut().zip(tone_map(*c, exposure)) {
            *m += t / 4.0;
        }
    }
    m
}

/// The largest channel difference of two tone-mapped colours.
fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// An LDR colour: every channel in `[0, 1]`.
fn ldr() -> impl Strategy<Value = Vec3> {
    (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0).prop_map(|(r, g, b)| Vec3::new(r, g, b))
}

/// Exposures over four orders of magnitude.
fn exposure() -> impl Strategy<Value = f32> {
    (-2.0f32..2.0).prop_map(|e| 10f32.powf(e))
}

/// Any f32, the non-finite and subnormal ones included.
fn any_bits() -> impl Strategy<Value = f32> {
    any::<u32>().prop_map(f32::from_bits)
}

proptest! {
    #![proptest_config(config())]

    /// Subsamples of one luma weigh alike: the tone-mapped resolve is the
    /// linear box, up to the rounding of the box's f32 sum.
    #[test]
    fn equal_luma_is_the_linear_box(
        colors in [ldr(), ldr(), ldr(), ldr()],
        luma in 0.01f32..=1.0,
        e in exposure(),
    ) {
        let subs = colors.map(|c| {
            let l = c.dot(RESOLVE_LUMA);
            if l > 1e-3 { c * (luma / l) } else { Vec3::splat(luma) }
        });
        let want = resolve_pixel(&subs);
        let got = resolve_pixel_tone_mapped(&subs, e);
        let tol = 4.0 * f32::EPSILON * want.max_element().max(f32::MIN_POSITIVE);
        prop_assert!((got - want).abs().max_element() <= tol, "{got} vs {want}");
    }

    /// A pixel of one colour is returned unchanged, bit for bit, at any
    /// exposure in the domain.
    #[test]
    fn a_constant_pixel_is_unchanged(
        c in (any_bits(), any_bits(), any_bits()).prop_map(|(r, g, b)| Vec3::new(r, g, b)),
        e in exposure(),
    ) {
        prop_assume!(c.is_finite());
        let got = resolve_pixel_tone_mapped(&[c; 4], e);
        prop_assert_eq!(got.to_array().map(f32::to_bits), c.to_array().map(f32::to_bits));
    }

    /// Beside an HDR highlight (one subsample 100× a bright LDR colour), the
    /// tone-mapped resolve, tone mapped, is the box average of the
    /// tone-mapped subsamples (the identity Karis' weights stand for), and
    /// closer to it than the linear box, tone mapped, is.
    #[test]
    fn an_hdr_highlight_resolves_as_it_is_displayed(
        highlight in ldr(),
        rest in [ldr(), ldr(), ldr()],
        at in 0usize..4,
        e in exposure(),
    ) {
        prop_assume!(highlight.dot(RESOLVE_LUMA) > 0.1);
        let mut subs = [rest[0], rest[1], rest[2], rest[0]];
        subs[at] = highlight * 100.0;
        if at != 3 {
            subs[3] = rest[at];
        }
        let target = tone_mapped_box(&subs, e);
        let tone_mapped = distance(tone_map(resolve_pixel_tone_mapped(&subs, e), e), target);
        let linear = distance(tone_map(resolve_pixel(&subs), e), target);
        prop_assert!(tone_mapped <= 1e-5, "tone-mapped resolve off by {tone_mapped}");
        prop_assert!(tone_mapped < linear, "{tone_mapped} vs linear {linear}");
    }

    /// Any bits in, never NaN out; the result is finite whenever a subsample
    /// is, and black when none is (as the linear box).
    #[test]
    fn never_nan(
        bits in prop::array::uniform12(any_bits()),
        e in any_bits(),
    ) {
        let subs: [Vec3; 4] = core::array::from_fn(|k| Vec3::from_slice(&bits[3 * k..3 * k + 3]));
        let got = resolve_pixel_tone_mapped(&subs, e);
        prop_assert!(got.is_finite(), "{got}");
        if !subs.iter().any(|c| c.is_finite()) {
            prop_assert_eq!(got, Vec3::ZERO);
        }
        let w = tone_map_weight(subs[0], e);
        prop_assert!((0.0..=1.0).contains(&w), "{w}");
    }
}

/// The worked case of the tone-mapped resolve: three black subsamples and
/// one of radiance 100 at exposure 1. The linear box gives 25 (tone mapped,
/// 25/26 ≈ 0.96: the highlight fills the pixel); the tone-mapped resolve
/// gives 100/103, whose tone map is 0.25 = the mean of (100/101, 0, 0, 0)
/// after T.
#[test]
fn one_highlight_among_black() {
    let subs = [Vec3::splat(100.0), Vec3::ZERO, Vec3::ZERO, Vec3::ZERO];
    assert_eq!(resolve_pixel(&subs), Vec3::splat(25.0));
    let got = resolve_pixel_tone_mapped(&subs, 1.0);
    // w = 1/101 for the highlight (luma 100), 1 for each black subsample.
    let want = 100.0 / 101.0 / (3.0 + 1.0 / 101.0);
    assert!(
        (got - Vec3::splat(want)).abs().max_element() < 1e-6,
        "{got}"
    );
    let shown = tone_map(got, 1.0)[0];
    let box_shown = tone_mapped_box(&subs, 1.0)[0];
    assert!((shown - box_shown).abs() < 1e-6, "{shown} vs {box_shown}");
}

/// Outside the exposure's domain the resolve is the linear box; the weight
/// of a non-finite colour or exposure is 0, of an overflowing luma 0.
#[test]
fn out_of_domain_exposures_give_the_linear_box() {
    let subs = [
        Vec3::new(8.0, 0.5, 0.1),
        Vec3::ZERO,
        Vec3::new(0.2, 0.3, 0.4),
        Vec3::splat(1.0),
    ];
    for e in [0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(resolve_pixel_tone_mapped(&subs, e), resolve_pixel(&subs));
        assert!(!ResolveSpace::ToneMapped { exposure: e }.is_valid());
    }
    assert!(ResolveSpace::ToneMapped { exposure: 0.5 }.is_valid());
    assert!(ResolveSpace::Linear.is_valid());
    assert_eq!(ResolveSpace::default(), ResolveSpace::Linear);
    assert_eq!(tone_map_weight(Vec3::splat(f32::NAN), 1.0), 0.0);
    assert_eq!(tone_map_weight(Vec3::ONE, f32::INFINITY), 0.0);
    assert_eq!(tone_map_weight(Vec3::splat(f32::MAX), 1e10), 0.0);
    assert_eq!(tone_map_weight(Vec3::splat(-1.0), 1.0), 1.0);
    // Weights far below f32's normal range still weigh (f64): grey at
    // 1e30 beside three at 1e25, weights 1/(1 + c), is 4 / (1e-30 + 3e-25),
    // not the box's 2.5e29.
    let huge = [
        Vec3::splat(1e30),
        Vec3::splat(1e25),
        Vec3::splat(1e25),
        Vec3::splat(1e25),
    ];
    let got = resolve_pixel_tone_mapped(&huge, 1.0);
    let want = 4.0 / (1e-30 + 3e-25);
    assert!((f64::from(got.x) / want - 1.0).abs() < 1e-4, "{got}");
    // A non-finite subsample is dropped, as the box drops it.
    let with_nan = [Vec3::NAN, Vec3::ONE, Vec3::ONE, Vec3::ONE];
    assert_eq!(resolve_pixel_tone_mapped(&with_nan, 1.0), Vec3::ONE);
}

/// `ResolveSpace::resolve` dispatches to the two resolves, the linear one
/// bit for bit.
#[test]
fn resolve_space_dispatches() {
    let subs = [
        Vec3::new(0.1, 0.2, 0.3),
        Vec3::new(40.0, 30.0, 20.0),
        Vec3::new(0.7, 0.6, 0.5),
        Vec3::new(0.0, 0.9, 0.1),
    ];
    assert_eq!(ResolveSpace::Linear.resolve(&subs), resolve_pixel(&subs));
    assert_eq!(
        ResolveSpace::ToneMapped { exposure: 2.0 }.resolve(&subs),
        resolve_pixel_tone_mapped(&subs, 2.0)
    );
}
