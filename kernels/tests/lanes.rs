//! The lane-parallel kernels of the frame resolver against their scalar
//! twins, bit for bit.
use glam::{Vec3, Vec4};
use proptest::prelude::*;
use subcone_kernels::sraa::{
    gaussian_sum_lanes, gaussian_sum_wide, neighbourhood, reconstruction_weight,
    weights_product_lanes, weights_product_wide, DepthMetric, Geometry, GeometryLanes,
    GeometryWide, Resolver, ShadedPosition, SraaParams, WeightForm, ALBEDO_TOLERANCE,
};

/// The scalar exponential the lanes reproduce: `sraa::gaussian_sum`.
fn gaussian_sum(s: f32) -> f32 {
    if s == 0.0 {
        1.0
    } else if s < 105.0 {
        libm::expf(-s)
    } else {
        0.0
    }
}

/// Every `stride`-th f32 bit pattern from 0 to `+∞`, and NaN, four at a time.
fn check_exp(stride: u32) {
    let end = f32::INFINITY.to_bits();
    let mut bits = 0u32;
    while bits <= end {
        let s = Vec4::from_array(core::array::from_fn(|l| {
            f32::from_bits((bits + l as u32 * (stride / 4).max(1)).min(end))
        }));
        let got = gaussian_sum_lanes(s).to_array();
        for l in 0..4 {
            let want = gaussian_sum(s[l]);
            assert_eq!(
                got[l].to_bits(),
                want.to_bits(),
                "s = {:e} ({:#x})",
                s[l],
                s[l].to_bits()
            );
        }
        bits = match bits.checked_add(stride) {
            Some(b) => b,
            None => break,
        };
    }
    let got = gaussian_sum_lanes(Vec4::new(f32::NAN, -0.0, 105.0, 103.97208)).to_array();
    assert_eq!(got[0], 0.0);
    assert_eq!(got[1], 1.0);
    assert_eq!(got[2], 0.0);
    assert_eq!(got[3].to_bits(), gaussian_sum(103.97208).to_bits());
}

#[test]
fn lanes_exp_is_libm_expf_at_a_stride() {
    // About 3·10⁵ values over [0, ∞], every binade, subnormal results included.
    check_exp(3571);
    // The subnormal-result range (k < −126) and the branch thresholds, densely.
    for (lo, hi) in [
        (87.0f32, 105.0f32),
        (0.3, 0.4),
        (1.0, 1.1),
        (5.9e-5, 6.2e-5),
    ] {
        let (a, b) = (lo.to_bits(), hi.to_bits());
        let mut bits = a;
        while bits < b {
            let s = Vec4::from_array(core::array::from_fn(|l| f32::from_bits(bits + l as u32)));
            let got = gaussian_sum_lanes(s).to_array();
            for l in 0..4 {
                assert_eq!(
                    got[l].to_bits(),
                    gaussian_sum(s[l]).to_bits(),
                    "s = {:e}",
                    s[l]
                );
            }
            bits += 4 * 13;
        }
    }
}

/// Every f32 from 0 to ∞: about 2·10⁹ values, minutes in release
/// (`cargo test --release -p subcone-kernels --test lanes -- --ignored`).
#[test]
#[ignore]
fn lanes_exp_is_libm_expf_everywhere() {
    check_exp(1);
}

#[test]
fn lanes_weights_are_the_scalar_weights() {
    let geometries = extreme_geometries();
    let params = extreme_params();
    let spatial = Vec4::new(0.0, 0.25, 10.0, 200.0);
    for p in &params {
        for quad in geometries.chunks(4).filter(|c| c.len() == 4) {
            let gi: [Geometry; 4] = core::array::from_fn(|l| quad[l]);
            let lanes = GeometryLanes::new(&gi);
            for gj in &geometries {
                let got = weights_product_lanes(p, &lanes, gj, spatial).to_array();
                for l in 0..4 {
                    // The spatial term as the scalar weight computes it from
                    // d² with σs: use σs = 1 so that d²/σs² is `spatial`.
                    let q = p.with_spatial(1.0);
                    let want = reconstruction_weight(&q, &gi[l], gj, spatial[l]);
                    assert_eq!(got[l].to_bits(), want.to_bits(), "{p:?} {:?} {gj:?}", gi[l]);
                }
            }
        }
    }
}

/// `gaussian_sum_wide` at 16 lanes (and at 5, a width that is no power of
/// two) against `gaussian_sum`, bit for bit, for every f32 in `bits`.
fn check_exp_wide(bits: impl Iterator<Item = u32>) {
    let mut chunk = [0.0f32; 16];
    let mut n = 0;
    let flush = |chunk: &[f32; 16], n: usize| {
        let got = gaussian_sum_wide(chunk);
        let first: &[f32; 5] = chunk[..5].try_into().unwrap();
        let got5 = gaussian_sum_wide(first);
        for l in 0..n {
            let want = gaussian_sum(chunk[l]).to_bits();
            assert_eq!(
                got[l].to_bits(),
                want,
                "s = {:e} ({:#x})",
                chunk[l],
                chunk[l].to_bits()
            );
            if l < 5 {
                assert_eq!(got5[l].to_bits(), want, "s = {:e} (5 lanes)", chunk[l]);
            }
        }
    };
    for b in bits {
        chunk[n] = f32::from_bits(b);
        n += 1;
        if n == 16 {
            flush(&chunk, n);
            n = 0;
        }
    }
    flush(&chunk, n);
}

/// The f32s `±radius` ulps around `s`, within `[0, +∞]`.
fn around(s: f32, radius: u32) -> impl Iterator<Item = u32> {
    let b = s.to_bits();
    b.saturating_sub(radius)..=(b + radius).min(f32::INFINITY.to_bits())
}

#[test]
fn wide_exp_is_libm_expf_at_a_stride() {
    // Every 997th f32 of [0, ∞] (about 2·10⁶, every binade).
    check_exp_wide((0..=f32::INFINITY.to_bits()).step_by(997));
    // Densely around every branch threshold: |x| ≤ 2⁻¹⁴, 0.5 ln 2, 1.5 ln 2,
    // k = −126 (the pre-scale), libm's underflow, 105.
    for t in [
        f32::from_bits(0x3900_0000),
        f32::from_bits(0x3eb1_7218),
        f32::from_bits(0x3f85_1592),
        126.5 * core::f32::consts::LN_2,
        f32::from_bits(0x42cf_f1b5),
        105.0,
    ] {
        check_exp_wide(around(t, 20_000));
    }
    // Around every step of k, where the truncation of x/ln 2 − 0.5 moves.
    for k in 1..=151 {
        check_exp_wide(around((k as f32 + 0.5) * core::f32::consts::LN_2, 2_000));
    }
    // The subnormal results (s in [87, 105)) at a small stride, and the
    // subnormal and tiny inputs.
    check_exp_wide((87.0f32.to_bits()..105.0f32.to_bits()).step_by(7));
    check_exp_wide(0..200_000);
}

#[test]
fn wide_exp_ends_and_out_of_domain() {
    let nan = f32::NAN;
    let s = [
        0.0,
        -0.0,
        f32::INFINITY,
        nan,
        -nan,
        f32::from_bits(0x7fc0_1234),
        f32::from_bits(0xff80_0001),
        f32::MAX,
        105.0,
        1e30,
        // Outside the domain (negative): 1 − s.
        -1.0,
        -1e-3,
        -100.0,
        f32::NEG_INFINITY,
        f32::MIN,
        1e-45,
    ];
    let got = gaussian_sum_wide(&s);
    let want = [
        1.0,
        1.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        2.0,
        1.0 - -1e-3,
        101.0,
        f32::INFINITY,
        f32::MAX,
        1.0,
    ];
    for l in 0..16 {
        assert_eq!(got[l].to_bits(), want[l].to_bits(), "s = {:e}", s[l]);
    }
    // The four-lane form agrees.
    for c in s.chunks_exact(4) {
        let v = gaussian_sum_lanes(Vec4::from_slice(c)).to_array();
        let w = gaussian_sum_wide::<4>(c.try_into().unwrap());
        assert_eq!(v.map(f32::to_bits), w.map(f32::to_bits));
    }
}

/// Every f32 from 0 to ∞ and every NaN, at 16 lanes: about 2.2·10⁹ values
/// (`cargo test --release -p subcone-kernels --test lanes -- --ignored`).
#[test]
#[ignore]
fn wide_exp_is_libm_expf_everywhere() {
    check_exp_wide(0..=f32::INFINITY.to_bits());
    check_exp_wide(f32::INFINITY.to_bits() + 1..=u32::MAX >> 1);
    check_exp_wide(f32::NEG_INFINITY.to_bits() + 1..=u32::MAX);
}

/// Targets and neighbours of extreme geometry: the unit axes and a few
/// normals (one with a NaN, one zero, one not unit, one infinite) by depths
/// (equal, near, far, 0, subnormal, ∞, NaN, near f32::MAX).
fn extreme_geometries() -> Vec<Geometry> {
    let normals = [
        Vec3::Z,
        Vec3::new(0.0, 0.6, 0.8),
        Vec3::new(0.6, 0.0, -0.8),
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 1e-4).normalize(),
        Vec3::ZERO,
        Vec3::new(3.0, -2.0, 0.5),
        Vec3::new(0.0, f32::INFINITY, 0.0),
    ];
    let depths = [
        1.0,
        1.0001,
        1.1,
        3.0,
        0.0,
        1e-40,
        f32::INFINITY,
        f32::NAN,
        3e38,
    ];
    normals
        .iter()
        .flat_map(|&n| depths.iter().map(move |&z| Geometry::new(n, z)))
        .collect()
}

fn extreme_params() -> [SraaParams; 6] {
    [
        SraaParams::TUNED,
        SraaParams::PAPER,
        SraaParams::PAPER.with_depth_metric(DepthMetric::Absolute),
        SraaParams {
            sigma_z: 0.0,
            ..SraaParams::TUNED
        },
        SraaParams {
            sigma_z: 1e30,
            sigma_n: 1e-30,
            ..SraaParams::TUNED
        },
        SraaParams::TUNED.with_spatial(1e-20),
    ]
}

/// `weights_product_wide` lane by lane against `reconstruction_weight` (with
/// σs = 1, so that `d²/σs²` is the lane's `spatial`).
fn check_wide_weights<const N: usize>(
    p: &SraaParams,
    gi: &[Geometry; N],
    gj: &[Geometry; N],
    spatial: &[f32; N],
) {
    let got = weights_product_wide(
        p,
        &GeometryWide::from_fn(|l| gi[l]),
        &GeometryWide::from_fn(|l| gj[l]),
        spatial,
    );
    let q = p.with_spatial(1.0).with_form(WeightForm::Product);
    for l in 0..N {
        let want = reconstruction_weight(&q, &gi[l], &gj[l], spatial[l]);
        assert_eq!(
            got[l].to_bits(),
            want.to_bits(),
            "{p:?} {:?} {:?} {}",
            gi[l],
            gj[l],
            spatial[l]
        );
    }
}

#[test]
fn wide_weights_are_the_scalar_weights() {
    let geometries = extreme_geometries();
    let spatial: [f32; 16] = core::array::from_fn(|l| {
        [0.0, 0.25, 10.0, 200.0, 1e-30, 87.5, f32::INFINITY, f32::NAN][l % 8]
    });
    for p in &extreme_params() {
        // Every (target, neighbour) pair of the set, 16 lanes at a time,
        // each lane its own pair.
        let pairs: Vec<(Geometry, Geometry)> = geometries
            .iter()
            .flat_map(|&a| geometries.iter().map(move |&b| (a, b)))
            .collect();
        for (c, chunk) in pairs.chunks(16).enumerate() {
            let gi = core::array::from_fn(|l| chunk[l % chunk.len()].0);
            let gj = core::array::from_fn(|l| chunk[l % chunk.len()].1);
            let sp: [f32; 16] = core::array::from_fn(|l| spatial[(l + c) % 16]);
            check_wide_weights::<16>(p, &gi, &gj, &sp);
            let first: [f32; 7] = core::array::from_fn(|l| sp[l]);
            let gi7 = core::array::from_fn(|l| gi[l]);
            let gj7 = core::array::from_fn(|l| gj[l]);
            check_wide_weights::<7>(p, &gi7, &gj7, &first);
        }
    }
}

/// A geometry of any f32 bits in places: unit normals, misses, NaN, zero,
/// subnormal and huge depths, non-unit and infinite normals.
fn any_geometry() -> impl Strategy<Value = Geometry> {
    let component = prop_oneof![
        4 => -1.0f32..=1.0,
        1 => any::<f32>(),
        1 => Just(0.0f32),
    ];
    let depth = prop_oneof![
        4 => (-3.0f32..9.0).prop_map(|e| 10f32.powf(e)),
        1 => Just(f32::INFINITY),
        1 => any::<f32>(),
        1 => Just(0.0f32),
        1 => (0u32..0x0080_0000).prop_map(f32::from_bits),
    ];
    (component.clone(), component.clone(), component, depth).prop_map(|(x, y, z, d)| {
        let n = Vec3::new(x, y, z);
        let n = if n.is_finite() { n.normalize_or(n) } else { n };
        Geometry::new(n, d)
    })
}

fn any_params() -> impl Strategy<Value = SraaParams> {
    (
        prop_oneof![0.0f32..100.0, any::<f32>()],
        prop_oneof![0.0f32..10.0, any::<f32>()],
        any::<bool>(),
    )
        .prop_map(|(sz, sn, absolute)| {
            let metric = if absolute {
                DepthMetric::Absolute
            } else {
                DepthMetric::Relative
            };
            SraaParams {
                sigma_z: sz,
                sigma_n: sn,
                ..SraaParams::TUNED.with_depth_metric(metric)
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Random pairs, one per lane, of any geometry and parameters: the wide
    /// weights are the scalar weights bit for bit.
    #[test]
    fn wide_weights_equal_scalar_on_random_geometry(
        p in any_params(),
        gi in prop::array::uniform16(any_geometry()),
        gj in prop::array::uniform16(any_geometry()),
        spatial in prop::array::uniform16(prop_oneof![0.0f32..120.0, any::<f32>().prop_map(f32::abs)]),
    ) {
        check_wide_weights::<16>(&p, &gi, &gj, &spatial);
    }

    /// The resolver's 36 weights of a pixel are `reconstruction_weight` at
    /// the distances `neighbourhood` gives, for either shaded position and
    /// any σs, bit for bit.
    #[test]
    fn resolver_weights_are_the_scalar_weights(
        p in any_params(),
        sigma_s in prop_oneof![0.0f32..2.0, Just(0.0), Just(1e-20), any::<f32>()],
        centre in any::<bool>(),
        targets in prop::array::uniform4(any_geometry()),
        hood in prop::array::uniform9(any_geometry()),
        near in prop::array::uniform4(0usize..10),
    ) {
        let position = if centre { ShadedPosition::Centre } else { ShadedPosition::Subsample };
        let p = p.with_spatial(sigma_s).with_shaded_position(position);
        // Some targets take a neighbour's geometry, so that weights are often 1.
        let mut targets = targets;
        for k in 0..4 {
            if near[k] < 9 {
                targets[k] = hood[near[k]];
            }
        }
        let resolver = Resolver::new(&p, &[None], ALBEDO_TOLERANCE);
        let got = resolver.weights_product(&targets, &hood);
        for k in 0..4 {
            for (slot, np) in neighbourhood(1, 1, k, p.shaded_offset(), 1, 3, 3).enumerate() {
                let want = reconstruction_weight(&p, &targets[k], &hood[slot], np.distance2);
                prop_assert_eq!(got[slot][k].to_bits(), want.to_bits(),
                    "slot {} subsample {}: {:?} {:?}", slot, k, targets[k], hood[slot]);
            }
        }
    }
}
