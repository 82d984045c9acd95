//! SRAA weights (eq. 1–2), reconstruction and resolve on arbitrary input.
#![no_main]

mod common;

use arbitrary::{Arbitrary, Unstructured};
use common::{finite_nonneg, unit, v3, Hull};
use glam::Vec3;
use libfuzzer_sys::fuzz_target;
use subcone_kernels::sraa::{
    bilateral_weight, reconstruct, reconstruction_weight, resolve_pixel, shadow_gated_weight,
    DepthMetric, Geometry, ShadedSample, SraaParams, WeightForm, NEGLIGIBLE_WEIGHT,
};

#[derive(Arbitrary, Debug)]
enum ParamsChoice {
    Paper,
    Chajdas,
    /// Finite non-negative sigmas (the documented domain), any form and metric.
    Custom {
        sigma_z: f32,
        sigma_n: f32,
        scale: f32,
        chajdas: bool,
        absolute: bool,
        radius: u16,
    },
    /// Anything at all, including NaN/negative sigmas and unknown codes: only the
    /// range checks apply.
    Raw(AnyParams),
}

/// Parameters with any fields (padding 0).
#[derive(Debug)]
struct AnyParams(SraaParams);

impl<'a> Arbitrary<'a> for AnyParams {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(Self(SraaParams {
            sigma_z: u.arbitrary()?,
            sigma_n: u.arbitrary()?,
            scale: u.arbitrary()?,
            packed: u.arbitrary()?,
            sigma_s: u.arbitrary()?,
            shading: u.arbitrary()?,
            _pad: [0; 2],
        }))
    }
}

#[derive(Arbitrary, Debug, Clone, Copy)]
struct RawGeom {
    normal: [f32; 3],
    depth: f32,
}

impl RawGeom {
    fn geometry(self) -> Geometry {
        Geometry::new(v3(self.normal), self.depth)
    }
}

#[derive(Arbitrary, Debug)]
struct RawSample {
    geom: RawGeom,
    color: [f32; 3],
    shadowed: bool,
    distance2: f32,
}

#[derive(Arbitrary, Debug)]
struct Input {
    params: ParamsChoice,
    gi: RawGeom,
    gj: RawGeom,
    si: bool,
    sj: bool,
    target_shadow: Option<bool>,
    neighbours: Vec<RawSample>,
    subsamples: [[f32; 3]; 4],
}

fn params(choice: &ParamsChoice) -> (SraaParams, bool) {
    match *choice {
        ParamsChoice::Paper => (SraaParams::PAPER, true),
        ParamsChoice::Chajdas => (SraaParams::CHAJDAS, true),
        ParamsChoice::Custom {
            sigma_z,
            sigma_n,
            scale,
            chajdas,
            absolute,
            radius,
        } => (
            SraaParams::new(
                finite_nonneg(sigma_z),
                finite_nonneg(sigma_n),
                finite_nonneg(scale),
                if chajdas {
                    WeightForm::ChajdasMax
                } else {
                    WeightForm::Product
                },
                if absolute {
                    DepthMetric::Absolute
                } else {
                    DepthMetric::Relative
                },
                radius,
            ),
            true,
        ),
        ParamsChoice::Raw(AnyParams(raw)) => (raw, false),
    }
}

fn check_weight(p: &SraaParams, gi: &Geometry, gj: &Geometry, si: bool, sj: bool) -> f32 {
    let w = bilateral_weight(p, gi, gj);
    assert!(
        (0.0..=1.0).contains(&w),
        "bilateral_weight({p:?}, {gi:?}, {gj:?}) = {w} not in [0, 1]"
    );
    let g = shadow_gated_weight(p, gi, gj, si, sj);
    assert!(
        (0.0..=1.0).contains(&g),
        "shadow_gated_weight = {g} not in [0, 1]"
    );
    // The spatial term only lowers the weight, and at distance 0 is eq. 1.
    for d2 in [0.0f32, 0.25, 2.0, f32::INFINITY, f32::NAN] {
        let r = reconstruction_weight(p, gi, gj, d2);
        assert!(
            (0.0..=w).contains(&r) || (d2 == 0.0 && r.to_bits() == w.to_bits()),
            "reconstruction_weight(d² = {d2}) = {r} not in [0, eq. 1's {w}]"
        );
    }
    assert_eq!(reconstruction_weight(p, gi, gj, 0.0).to_bits(), w.to_bits());
    if si != sj {
        assert!(g == 0.0, "shadow gate {g} != 0 across a shadow edge");
    } else {
        assert!(
            g.to_bits() == w.to_bits(),
            "shadow gate {g} != bilateral weight {w} with equal states"
        );
    }
    w
}

fuzz_target!(|input: Input| {
    let (p, in_domain) = params(&input.params);
    let gi = input.gi.geometry();
    let gj = input.gj.geometry();

    // Range and gate, for any input whatsoever.
    let wij = check_weight(&p, &gi, &gj, input.si, input.sj);
    let _ = check_weight(&p, &gj, &gi, input.sj, input.si);
    let _ = check_weight(&p, &gi, &gi, input.si, input.si);
    let _ = check_weight(&p, &Geometry::MISS, &gj, input.si, input.sj);

    // Identity and symmetry on the domain: finite non-negative parameters,
    // unit normals, non-NaN depths.
    if in_domain {
        if let (Some(ni), Some(nj)) = (unit(gi.normal), unit(gj.normal)) {
            let (zi, zj) = (gi.depth, gj.depth);
            let ui = Geometry::new(ni, zi);
            let uj = Geometry::new(nj, zj);
            if !zi.is_nan() {
                let wii = bilateral_weight(&p, &ui, &ui);
                // f32 normalisation can leave n·n = 1 − 2⁻²⁴ (or − 2⁻²³); the
                // kernel snaps cosines within NORMAL_COS_SNAP of 1 to 1.
                assert!(
                    wii == 1.0,
                    "w(i,i) = {wii} != 1 for {p:?}, {ui:?} (n·n = {})",
                    ni.dot(ni)
                );
            }
            if !zi.is_nan() && !zj.is_nan() {
                let a = bilateral_weight(&p, &ui, &uj);
                let b = bilateral_weight(&p, &uj, &ui);
                assert!(
                    a.to_bits() == b.to_bits(),
                    "w(i,j) = {a} != w(j,i) = {b} for {p:?}, {ui:?}, {uj:?}"
                );
            }
        }
    }
    let _ = wij;

    // Reconstruction over up to 9 neighbours (the 3×3 neighbourhood).
    let neighbours: Vec<ShadedSample> = input
        .neighbours
        .iter()
        .take(9)
        .map(|s| ShadedSample {
            geometry: s.geom.geometry(),
            color: v3(s.color),
            shadowed: s.shadowed,
            distance2: s.distance2,
        })
        .collect();
    let r = reconstruct(&p, &gi, input.target_shadow, neighbours.iter().copied());
    assert!(
        r.color.is_finite(),
        "reconstruct returned a non-finite colour {r:?}"
    );

    // Replay the kernel's sums over the finite neighbours, in the same order
    // and, as the kernel does, in f64: the fallback applies exactly when Σw is
    // below NEGLIGIBLE_WEIGHT or the quotient is not finite in f32.
    let mut hull = Hull::new();
    let mut wsum = 0.0f64;
    let mut sum = [0.0f64; 3];
    let mut nearest: Option<(f32, Vec3)> = None;
    for s in &neighbours {
        if !s.color.is_finite() {
            continue;
        }
        hull.add(s.color);
        let d2 = if s.distance2.is_nan() {
            f32::INFINITY
        } else {
            s.distance2
        };
        // Eq. 2's gate, then eq. 1 with the spatial term at the sample's
        // distance, as `reconstruct` weighs.
        let w = match input.target_shadow {
            Some(si) if si != s.shadowed => 0.0,
            _ => reconstruction_weight(&p, &gi, &s.geometry, d2),
        };
        for k in 0..3 {
            sum[k] += w as f64 * s.color[k] as f64;
        }
        wsum += w as f64;
        match nearest {
            Some((nd, _)) if !(d2 < nd) => {}
            _ => nearest = Some((d2, s.color)),
        }
    }
    let inv = 1.0 / wsum;
    let mean = Vec3::new(
        (sum[0] * inv) as f32,
        (sum[1] * inv) as f32,
        (sum[2] * inv) as f32,
    );
    let expect_fallback = !(wsum >= NEGLIGIBLE_WEIGHT as f64) || !mean.is_finite();
    assert!(
        r.fell_back == expect_fallback,
        "reconstruct {r:?}: fell_back should be {expect_fallback} (Σw = {wsum:e}, Σw·C = {sum:?})"
    );
    if r.fell_back {
        let expect = nearest.map_or(Vec3::ZERO, |(_, c)| c);
        assert!(
            r.color == expect && r.weight_sum == 0.0,
            "fallback {r:?} is not the nearest finite neighbour {expect:?}"
        );
    } else {
        assert!(
            r.weight_sum.to_bits() == (wsum as f32).to_bits() && wsum >= NEGLIGIBLE_WEIGHT as f64,
            "no fallback with weight sum {:e} (replayed {wsum:e})",
            r.weight_sum
        );
    }
    // Non-finite neighbours are excluded, so the result lies in the hull of the
    // finite ones (black with none).
    if hull.is_empty() {
        assert!(
            r.color == Vec3::ZERO && r.fell_back,
            "no usable neighbour: {r:?}"
        );
    } else {
        assert!(
            hull.contains(r.color),
            "reconstruct {r:?} outside the finite neighbours' hull {hull:?} (Σw = {wsum:e})"
        );
    }

    // The pixel resolve.
    let subs = input.subsamples.map(v3);
    let c = resolve_pixel(&subs);
    assert!(!c.is_nan(), "resolve_pixel({subs:?}) = {c:?} is NaN");
    let mut hull = Hull::new();
    for s in subs.iter().filter(|s| s.is_finite()) {
        hull.add(*s);
    }
    if hull.is_empty() {
        assert!(
            c == Vec3::ZERO,
            "resolve_pixel with no finite subsample: {c:?}"
        );
    } else {
        assert!(
            hull.contains(c),
            "resolve_pixel({subs:?}) = {c:?} outside the finite subsamples' hull"
        );
    }
});
