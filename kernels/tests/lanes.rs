//! The lane-parallel kernels of the frame resolver against their scalar
//! twins, bit for bit.
use glam::{Vec3, Vec4};
use subcone_kernels::sraa::{
    gaussian_sum_lanes, reconstruction_weight, weights_product_lanes, DepthMetric, Geometry,
    GeometryLanes, SraaParams,
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
    let normals = [
        Vec3::Z,
        Vec3::new(0.0, 0.6, 0.8),
        Vec3::new(0.6, 0.0, -0.8),
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, 1.0, 1e-4).normalize(),
        Vec3::ZERO,
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
    let geometries: Vec<Geometry> = normals
        .iter()
        .flat_map(|&n| depths.iter().map(move |&z| Geometry::new(n, z)))
        .collect();
    let params = [
        SraaParams::TUNED,
        SraaParams::PAPER,
        SraaParams::PAPER.with_depth_metric(DepthMetric::Absolute),
        SraaParams {
            sigma_z: 0.0,
            ..SraaParams::TUNED
        },
        SraaParams::TUNED.with_spatial(1e-20),
    ];
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
