//! SRAA's weights (eq. 1-2), its material gate and its resolve.

use glam::Vec3;
use subcone_kernels::sraa::{
    albedo_difference, bilateral_weight, material_gated_weight, reconstruction_weight,
    resolve_pixel, shadow_gated_weight, DepthMetric, Geometry, SraaParams, WeightForm,
    ALBEDO_TOLERANCE,
};

use super::grids::{AWKWARD_DEPTHS, AWKWARD_WEIGHT_PARAMS, SPECIALS};
use super::rng::special_pairs;
use super::rng::{Rng, GENERATED};
use super::tolerance::*;
use super::words::{out, R, W};
use super::KernelVectors;

const GEOMETRY_SIG: &str =
    "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32";

/// SRAA parameters as the conformance suite draws them: the presets, and
/// random sigmas, forms and depth metrics.
fn sraa_params(rng: &mut Rng) -> SraaParams {
    match rng.below(13) {
        0..=2 => SraaParams::PAPER,
        3..=5 => SraaParams::TUNED,
        6..=7 => SraaParams::CHAJDAS,
        8..=9 => SraaParams {
            sigma_s: rng.any_f32(0.0, 2.0),
            shading: rng.below(3),
            ..SraaParams::TUNED
        },
        10 => SraaParams::CHAJDAS.with_spatial(rng.any_f32(0.0, 2.0)),
        _ => SraaParams::new(
            rng.any_f32(0.0, 40.0),
            rng.any_f32(0.0, 2.0),
            10.0,
            if rng.below(2) == 0 {
                WeightForm::Product
            } else {
                WeightForm::ChajdasMax
            },
            if rng.below(2) == 0 {
                DepthMetric::Relative
            } else {
                DepthMetric::Absolute
            },
            1,
        ),
    }
}

fn geometry(rng: &mut Rng) -> Geometry {
    Geometry::new(rng.unit_vec(), rng.any_f32(0.0, 100.0))
}

/// The conformance suite's grid of awkward geometry: normals (NaN, zero,
/// opposite) against depths (0, subnormal, 3e38, ∞, NaN, a miss-like 1e6),
/// over four parameter sets (both forms, both metrics, huge sigmas).
fn weight_grid() -> Vec<(SraaParams, Geometry, Geometry)> {
    let nan = f32::NAN;
    let normals = [
        (Vec3::Z, Vec3::Z),
        (Vec3::Z, Vec3::new(0.0, 0.6, 0.8)),
        (Vec3::Z, Vec3::X),
        (Vec3::Z, -Vec3::Z),
        (Vec3::new(nan, 0.0, 1.0), Vec3::Z),
        (Vec3::ZERO, Vec3::Z),
    ];
    let mut cases = Vec::new();
    for (na, nb) in normals {
        for za in AWKWARD_DEPTHS {
            for zb in AWKWARD_DEPTHS {
                let p = AWKWARD_WEIGHT_PARAMS[cases.len() % AWKWARD_WEIGHT_PARAMS.len()];
                cases.push((p, Geometry::new(na, za), Geometry::new(nb, zb)));
            }
        }
    }
    cases
}

/// Generated weight cases and the grid, each with an index for the extra
/// inputs.
fn weight_cases(rng: &mut Rng) -> Vec<(SraaParams, Geometry, Geometry)> {
    let mut cases: Vec<_> = (0..GENERATED)
        .map(|_| (sraa_params(rng), geometry(rng), geometry(rng)))
        .collect();
    cases.extend(weight_grid());
    cases
}

/// An albedo: mostly in `[0, 1]`, sometimes anything.
fn albedo(rng: &mut Rng) -> Vec3 {
    if rng.below(5) < 4 {
        Vec3::new(rng.unit(), rng.unit(), rng.unit())
    } else {
        rng.colour(1.0)
    }
}

/// A pair of albedos: equal, close (the difference straddles the default
/// tolerance) or independent.
fn albedo_pair(rng: &mut Rng) -> (Vec3, Vec3) {
    let a = albedo(rng);
    match rng.below(7) {
        0..=1 => (a, a),
        2..=4 => {
            let d = Vec3::new(
                rng.range(-0.2, 0.2),
                rng.range(-0.2, 0.2),
                rng.range(-0.2, 0.2),
            );
            (a, a + d)
        }
        _ => (a, albedo(rng)),
    }
}

/// The non-finite contract of the SRAA weights.
const WEIGHT_NON_FINITE: &str = "Domain: unit normals, depths in [0, inf], finite non-negative parameters. Returns a value in [0, 1], never NaN. A NaN anywhere gives 0 (the neighbour is excluded, never blended); two misses (depth = +inf) give 1 whatever their normals; non-unit normals are accepted (the cosine is saturated to [0, 1]); weights that underflow are 0.";

const WEIGHT_REFERENCE: &str = "kernels/tests/f64_reference.rs: eq. 1 in f64 (SraaParams::PAPER and CHAJDAS presets, unit normals, depths 1e-3..1e6), within 2e-6 absolute; not re-checked on these cases.";

pub(super) const BILATERAL_WEIGHT: KernelVectors = KernelVectors {
    name: "bilateral_weight",
    inputs: GEOMETRY_SIG,
    outputs: "w:f32",
    tolerance: TOL_WEIGHT,
    tolerance_constant: "TOL_WEIGHT",
    non_finite: WEIGHT_NON_FINITE,
    reference: WEIGHT_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
        out(&[bilateral_weight(&p, &gi, &gj)])
    },
    generate: |rng| {
        weight_cases(rng)
            .iter()
            .map(|(p, gi, gj)| W::default().params(p).geometry(gi).geometry(gj).0)
            .collect()
    },
};

pub(super) const SHADOW_GATED_WEIGHT: KernelVectors = KernelVectors {
    name: "shadow_gated_weight",
    inputs: "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32 si:bool sj:bool",
    outputs: "w:f32",
    tolerance: TOL_WEIGHT,
    tolerance_constant: "TOL_WEIGHT",
    non_finite: "Exactly 0 when si != sj (the gate of eq. 2, whatever the other inputs); otherwise bilateral_weight's contract: domain unit normals, depths in [0, inf], finite non-negative parameters; a value in [0, 1], never NaN; a NaN anywhere gives 0; two misses (depth = +inf) give 1.",
    reference: WEIGHT_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
        let (si, sj) = (r.b(), r.b());
        out(&[shadow_gated_weight(&p, &gi, &gj, si, sj)])
    },
    generate: |rng| {
        weight_cases(rng)
            .iter()
            .map(|(p, gi, gj)| {
                let (si, sj) = (rng.below(2), rng.below(2));
                W::default().params(p).geometry(gi).geometry(gj).u(si).u(sj).0
            })
            .collect()
    },
};

pub(super) const RECONSTRUCTION_WEIGHT: KernelVectors = KernelVectors {
    name: "reconstruction_weight",
    inputs: "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32 distance2:f32",
    outputs: "w:f32",
    tolerance: TOL_WEIGHT,
    tolerance_constant: "TOL_WEIGHT",
    non_finite: "bilateral_weight times exp(-distance2/sigma_s^2) when sigma_s > 0. Domain: bilateral_weight's, and distance2 >= 0. With the spatial term on, a NaN or infinite distance2 gives 0; with it off (sigma_s <= 0 or NaN), distance2 is ignored and the result is bilateral_weight's, bit for bit. Always in [0, 1], never NaN.",
    reference: WEIGHT_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
        out(&[reconstruction_weight(&p, &gi, &gj, r.f())])
    },
    generate: |rng| {
        let d2s = [0.0f32, 0.156_25, 0.39, 1.2, 4.5, 1e-30, 3e38, f32::INFINITY];
        weight_cases(rng)
            .iter()
            .map(|(p, gi, gj)| {
                let d2 = if rng.below(2) == 0 {
                    rng.pick(&d2s)
                } else {
                    rng.any_f32(0.0, 5.0)
                };
                W::default().params(p).geometry(gi).geometry(gj).f(d2).0
            })
            .collect()
    },
};

pub(super) const ALBEDO_DIFFERENCE: KernelVectors = KernelVectors {
    name: "albedo_difference",
    inputs: "a:vec3 b:vec3",
    outputs: "d:f32",
    tolerance: TOL_ALBEDO_DIFFERENCE,
    tolerance_constant: "TOL_ALBEDO_DIFFERENCE",
    non_finite: "max_c |sqrt(a_c) - sqrt(b_c)|. Domain: finite components, nominally in [0, 1]; negative components count as 0, components above 1 are compared as they are. A NaN or infinite component in either albedo gives +inf. The tolerance holds on components in [0, 4]; beyond, where the difference cancels, only the class (infinite or not) is compared by the conformance suite.",
    reference: "f64: max_c |sqrt(max(a_c, 0)) - sqrt(max(b_c, 0))| on finite components in [0, 4], within TOL_ALBEDO_DIFFERENCE (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        out(&[albedo_difference(r.v3(), r.v3())])
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                let (a, b) = albedo_pair(rng);
                W::default().v(&a.to_array()).v(&b.to_array()).0
            })
            .collect();
        v.extend(special_pairs().map(|(a, b)| {
            W::default().v(&[a, 0.5, 0.25]).v(&[b, 0.5, 0.25]).0
        }));
        v
    },
};

pub(super) const MATERIAL_GATED_WEIGHT: KernelVectors = KernelVectors {
    name: "material_gated_weight",
    inputs: "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32 ai:vec3 aj:vec3 tolerance:f32",
    outputs: "w:f32",
    tolerance: TOL_WEIGHT,
    tolerance_constant: "TOL_WEIGHT",
    non_finite: "bilateral_weight when albedo_difference(ai, aj) <= tolerance and is finite, else exactly 0. A non-finite albedo, or a NaN or negative tolerance, gates (weight 0); the result is always in [0, 1], never NaN. The gate's decision is exact, except where the albedo difference lies within MATERIAL_GATE_NEAR (1e-5) of the tolerance, where a few ulps of sqrt decide.",
    reference: WEIGHT_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
        let (ai, aj, t) = (r.v3(), r.v3(), r.f());
        out(&[material_gated_weight(&p, &gi, &gj, ai, aj, t)])
    },
    generate: |rng| {
        weight_cases(rng)
            .iter()
            .map(|(p, gi, gj)| {
                let (ai, aj) = albedo_pair(rng);
                let t = if rng.below(4) < 3 {
                    ALBEDO_TOLERANCE
                } else {
                    rng.any_f32(0.0, 1.0)
                };
                W::default()
                    .params(p)
                    .geometry(gi)
                    .geometry(gj)
                    .v(&ai.to_array())
                    .v(&aj.to_array())
                    .f(t)
                    .0
            })
            .collect()
    },
};

pub(super) const RESOLVE_PIXEL: KernelVectors = KernelVectors {
    name: "resolve_pixel",
    inputs: "c0:vec3 c1:vec3 c2:vec3 c3:vec3",
    outputs: "c:vec3",
    tolerance: TOL_RESOLVE,
    tolerance_constant: "TOL_RESOLVE",
    non_finite: "The mean of the four subsample colours, each scaled by 1/n before summing. Domain: finite colours. A subsample with any non-finite component is dropped and the others are averaged; with none finite, returns black (0, 0, 0). Colours above 1e37 may overflow the sum in a port's order and are outside the compared contract.",
    reference: "f64: the mean of the finite subsamples, on components in [0, 4], within TOL_RESOLVE (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        let c = [r.v3(), r.v3(), r.v3(), r.v3()];
        out(&resolve_pixel(&c).to_array())
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                let mut w = W::default();
                for _ in 0..4 {
                    w = w.v(&rng.colour(4.0).to_array());
                }
                w.0
            })
            .collect();
        for (k, s) in SPECIALS.iter().enumerate() {
            // One special in one channel of one subsample, then in all.
            let mut c = [[0.25f32, 0.5, 0.75]; 4];
            c[k % 4][k % 3] = *s;
            v.push(c.iter().fold(W::default(), |w, c| w.v(c)).0);
            v.push(W::default().v(&[*s; 12]).0);
        }
        v
    },
};
