//! CTSS's visibility masks (eq. 7-8) and their aggregation (eq. 6).

use glam::Vec3;
use subcone_kernels::aggregate::{sample_weight, Aggregate, Weighting};
use subcone_kernels::mask::{
    needs_normal, project_normal, visibility_mask, MaskPlacement, FARTHEST_CENTRE,
};

use super::grids::SPECIALS;
use super::rng::special_pairs;
use super::rng::GENERATED;
use super::tolerance::*;
use super::words::{out, R, W};
use super::KernelVectors;
use super::NO_REFERENCE;

pub(super) const PROJECT_NORMAL: KernelVectors = KernelVectors {
    name: "project_normal",
    inputs: "normal:vec3 right:vec3 up:vec3",
    outputs: "n_p:vec2",
    tolerance: TOL_PROJECT_NORMAL,
    tolerance_constant: "TOL_PROJECT_NORMAL",
    non_finite: "(n.right, n.up) with n = normal/|normal|, normalised after scaling by the largest component (so no square overflows). Domain: any finite non-zero normal; right, up orthonormal. A zero, NaN or infinite normal returns (0, 0).",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        out(&project_normal(r.v3(), r.v3(), r.v3()).to_array())
    },
    generate: |rng| {
        let frame = |n: Vec3, r: Vec3| {
            let up = r.cross(n).try_normalize().unwrap_or(Vec3::Y);
            W::default().v(&n.to_array()).v(&r.to_array()).v(&up.to_array()).0
        };
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                let (n, r) = (rng.unit_vec(), rng.unit_vec());
                frame(n, r)
            })
            .collect();
        for (a, b) in special_pairs() {
            v.push(frame(Vec3::new(a, b, 0.5), Vec3::X));
        }
        v
    },
};

pub(super) const VISIBILITY_MASK: KernelVectors = KernelVectors {
    name: "visibility_mask",
    inputs: "omega:f32 n_p:vec2 placement:u32",
    outputs: "mask:u32",
    tolerance: TOL_EXACT,
    tolerance_constant: "TOL_EXACT",
    non_finite: "The 32-cell mask of the half-plane (eq. 7-8) for occlusion omega and projected normal n_p; placement 0 derived, 1 the authors' code, 2 the paper's eq. 8 (other codes read as 0). Domain: omega in [-1, 2], |n_p| <= 1. A fronto-parallel surface (n_p = (0, 0)) gives all 32 bits when omega >= 0.5 and 0 otherwise; a NaN omega gives 0; |n_p| > 1 is treated as 1. Exact, except that a cell whose centre lies within MASK_NEAR (1e-5) of the mask's line (computed in f64) may differ, in at most 1 % of masks (MASK_NEAR_ROWS_PER_100).",
    reference: "kernels/tests/f64_reference.rs rasterises the same line in f64 (cells may differ only within MASK_NEAR of it); not re-checked on these cases.",
    eval: |w| {
        let mut r = R(w);
        let (omega, np, p) = (r.f(), r.v2(), r.u());
        vec![visibility_mask(omega, np, MaskPlacement::from_u32(p))]
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..3 * GENERATED / 2)
            .map(|i| {
                let omega = if i % 50 == 0 {
                    rng.awkward()
                } else {
                    rng.unit() * 1.4 - 0.2
                };
                let a = rng.unit() * std::f32::consts::TAU;
                let len = if i % 3 == 0 { rng.unit() } else { 1.0 };
                W::default()
                    .f(omega)
                    .f(a.cos() * len)
                    .f(a.sin() * len)
                    .u(rng.below(3))
                    .0
            })
            .collect();
        for (k, s) in SPECIALS.iter().enumerate() {
            for np in [[0.0, 0.0], [0.6, 0.8], [*s, 0.5]] {
                for p in 0..3 {
                    v.push(W::default().f(*s).v(&np).u(p).0);
                    v.push(W::default().f(0.25 + k as f32 / 36.0).v(&np).u(p).0);
                }
            }
        }
        v
    },
};

pub(super) const NEEDS_NORMAL: KernelVectors = KernelVectors {
    name: "needs_normal",
    inputs: "omega:f32 placement:u32",
    outputs: "needs:bool",
    tolerance: TOL_EXACT,
    tolerance_constant: "TOL_EXACT",
    non_finite: "Whether visibility_mask depends on the projected normal at this occlusion: for placements 0 and 1, false when |1 - 2 omega| >= FARTHEST_CENTRE (the mask is then empty or full for every normal); always true for placement 2; false for a NaN omega. Exact, except where |1 - 2 omega| lies within NEEDS_NORMAL_NEAR (1e-5) of FARTHEST_CENTRE, where one rounding decides.",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let (omega, p) = (r.f(), r.u());
        vec![needs_normal(omega, MaskPlacement::from_u32(p)) as u32]
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| W::default().f(rng.any_f32(-0.2, 1.2)).u(rng.below(3)).0)
            .collect();
        // Around the thresholds, ω = (1 ± FARTHEST_CENTRE)/2.
        for sign in [-1.0f32, 1.0] {
            let edge = (1.0 + sign * FARTHEST_CENTRE) * 0.5;
            for k in -8i32..=8 {
                let omega = edge + k as f32 * 1e-3;
                for p in 0..3 {
                    v.push(W::default().f(omega).u(p).0);
                }
            }
        }
        for s in SPECIALS {
            for p in 0..3 {
                v.push(W::default().f(s).u(p).0);
            }
        }
        v
    },
};

pub(super) const SAMPLE_WEIGHT: KernelVectors = KernelVectors {
    name: "sample_weight",
    inputs: "visible:u32 weighting:u32 min_weight:f32",
    outputs: "w:f32",
    tolerance: TOL_SAMPLE_WEIGHT,
    tolerance_constant: "TOL_SAMPLE_WEIGHT",
    non_finite: "weighting 1 (uniform): 1. Otherwise (0, and unknown codes): max(bitCount(visible)/32, min(min_weight, 1)) when min_weight > 0, else bitCount(visible)/32. Domain: min_weight in [0, 1]; NaN reads as 0.",
    reference: "exact: bitCount(visible)/32, or the clamped floor, or 1 (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        let (m, k, min_w) = (r.u(), r.u(), r.f());
        out(&[sample_weight(m, Weighting::from_u32(k), min_w)])
    },
    generate: |rng| {
        let floors = [0.0f32, 0.01];
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                let min_w = if rng.below(2) == 0 {
                    rng.pick(&floors)
                } else {
                    rng.any_f32(0.0, 1.0)
                };
                W::default().u(rng.bits()).u(rng.below(3)).f(min_w).0
            })
            .collect();
        for b in 0..=32u32 {
            let m = if b == 32 { u32::MAX } else { (1u32 << b) - 1 };
            for min_w in [0.0, 0.01, f32::NAN, 2.0, -1.0] {
                v.push(W::default().u(m).u(0).f(min_w).0);
            }
        }
        v
    },
};

pub(super) const AGGREGATE_RESOLVE: KernelVectors = KernelVectors {
    name: "aggregate_resolve",
    inputs: "mask0:u32 c0:vec3 mask1:u32 c1:vec3 mask2:u32 c2:vec3 mask3:u32 c3:vec3 background:vec3 bg_weight:f32 weighting:u32 min_weight:f32",
    outputs: "c:vec3",
    tolerance: TOL_AGGREGATE,
    tolerance_constant: "TOL_AGGREGATE",
    non_finite: "Eq. 6: for k = 0..4, w_k = sample_weight(mask_k, weighting, min_weight) and Aggregate::add(w_k, c_k); then Aggregate::resolve(background, bg_weight) = (sum w_k c_k + bg_weight * background) / (sum w_k + bg_weight). add clamps w to [0, 1] (NaN as 0) and skips a non-finite colour (which still counts as a sample). With no weight (or a total below NEGLIGIBLE_WEIGHT) the last finite colour is returned, or the background, or black; if the weighted sum overflows, the last colour too. The result lies in the convex hull of the colours and the background. The tolerance holds on radiances (finite, non-negative components below 1e30); outside, a port must return a finite colour.",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let samples = [
            (r.u(), r.v3()),
            (r.u(), r.v3()),
            (r.u(), r.v3()),
            (r.u(), r.v3()),
        ];
        let (bg, bgw, k, min_w) = (r.v3(), r.f(), r.u(), r.f());
        let mut agg = Aggregate::new();
        for (m, c) in samples {
            agg.add(sample_weight(m, Weighting::from_u32(k), min_w), c);
        }
        out(&agg.resolve(bg, bgw).to_array())
    },
    generate: |rng| {
        (0..GENERATED)
            .map(|_| {
                let mut w = W::default();
                for _ in 0..4 {
                    let m = match rng.below(4) {
                        0 => 0,
                        1 => u32::MAX,
                        _ => rng.bits(),
                    };
                    w = w.u(m).v(&rng.colour(4.0).to_array());
                }
                let min_w = if rng.below(2) == 0 { 0.0 } else { 0.01 };
                w.v(&rng.colour(4.0).to_array())
                    .f(rng.any_f32(0.0, 1.0))
                    .u(rng.below(2))
                    .f(min_w)
                    .0
            })
            .collect()
    },
};
