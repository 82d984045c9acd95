//! CTSS's transparency levels (section 5.3).

use subcone_kernels::transparency::{
    clamp_alpha, is_opaque, level_weight, remaining_after, TransparencyAccumulator,
};

use super::grids::SPECIALS;
use super::rng::{Rng, GENERATED};
use super::tolerance::*;
use super::words::{out, R, W};
use super::KernelVectors;
use super::NO_REFERENCE;

pub(super) const CLAMP_ALPHA: KernelVectors = KernelVectors {
    name: "clamp_alpha",
    inputs: "alpha:f32",
    outputs: "alpha_clamped:f32",
    tolerance: TOL_TRANSPARENCY_WEIGHT,
    tolerance_constant: "TOL_TRANSPARENCY_WEIGHT",
    non_finite: "alpha clamped to [0, 1]; NaN reads as 1 (opaque), so a broken opacity never lets hidden surfaces show through.",
    reference: NO_REFERENCE,
    eval: |w| out(&[clamp_alpha(R(w).f())]),
    generate: |rng| alphas(rng).into_iter().map(|a| W::default().f(a).0).collect(),
};

pub(super) const REMAINING_AFTER: KernelVectors = KernelVectors {
    name: "remaining_after",
    inputs: "r:u32 alpha:f32",
    outputs: "levels:u32",
    tolerance: TOL_EXACT,
    tolerance_constant: "TOL_EXACT",
    non_finite: "floor(r (1 - clamp_alpha(alpha)) + 1/2), in [0, r]: the transmittance levels a cell keeps. Domain: r <= K = 4 (5 is generated too), any alpha (NaN is opaque). Exact, except where r (1 - alpha) + 1/2 lies within TRANSPARENCY_NEAR (1e-6) of an integer (and not exactly on it in f32), where a fused multiply-add may round to the other level.",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let (k, a) = (r.u(), r.f());
        vec![remaining_after(k, a)]
    },
    generate: |rng| {
        alphas(rng)
            .into_iter()
            .enumerate()
            .map(|(i, a)| W::default().u(i as u32 % 6).f(a).0)
            .collect()
    },
};

pub(super) const IS_OPAQUE: KernelVectors = KernelVectors {
    name: "is_opaque",
    inputs: "alpha:f32",
    outputs: "opaque:bool",
    tolerance: TOL_EXACT,
    tolerance_constant: "TOL_EXACT",
    non_finite: "Whether a surface of opacity alpha leaves no transmittance in a clear cell: alpha > 0.875 for K = 4, and NaN (opaque).",
    reference: NO_REFERENCE,
    eval: |w| vec![is_opaque(R(w).f()) as u32],
    generate: |rng| alphas(rng).into_iter().map(|a| W::default().f(a).0).collect(),
};

pub(super) const LEVEL_WEIGHT: KernelVectors = KernelVectors {
    name: "level_weight",
    inputs: "gained:u32",
    outputs: "w:f32",
    tolerance: TOL_TRANSPARENCY_WEIGHT,
    tolerance_constant: "TOL_TRANSPARENCY_WEIGHT",
    non_finite: "min(gained, 32 K) / (32 K), K = 4: the weight of gained opacity levels summed over cells, at most 1. Total over u32.",
    reference: "exact: min(gained, 128)/128 (checked by tests/vectors.rs).",
    eval: |w| out(&[level_weight(R(w).u())]),
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..=160u32).map(|g| vec![g]).collect();
        v.extend((0..512).map(|_| vec![rng.bits()]));
        v.push(vec![u32::MAX]);
        v
    },
};

pub(super) const TRANSPARENCY_ACCUMULATOR: KernelVectors = KernelVectors {
    name: "transparency_accumulator",
    inputs: "mask0:u32 alpha0:f32 mask1:u32 alpha1:f32 mask2:u32 alpha2:f32 level_set_index:u32 bit:u32",
    outputs: "visible0:u32 gained0:u32 visible1:u32 gained1:u32 visible2:u32 gained2:u32 plane0:u32 plane1:u32 plane2:u32 plane3:u32 plane4:u32 plane5:u32 level:u32 is_binary:bool opaque:u32 total_levels:u32 level_set:u32 uncovered_weight:f32",
    tolerance: TOL_EXACT,
    tolerance_constant: "TOL_EXACT",
    non_finite: "CTSS section 5.3's K = 4 nested masks: from a clear pixel, add(mask_k, alpha_k) for k = 0..3 (each returning the cells whose level rose and the levels gained), then plane(0..6) (plane(k) = M_(k+1) for k < K, else 0), level(bit), is_binary, opaque (M_K), total_levels, level_set(level_set_index) and uncovered_weight (1 - total_levels/(32 K)). NaN alpha is opaque, alpha outside [0, 1] is clamped. Exact, except where some alpha puts r (1 - alpha) + 1/2 within TRANSPARENCY_NEAR (1e-6) of an integer for r in 1..=4 (and not exactly on it in f32), where a fused multiply-add may round to the other level; such records are at most 1 %.",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let adds = [(r.u(), r.f()), (r.u(), r.f()), (r.u(), r.f())];
        let (set, bit) = (r.u(), r.u());
        let mut acc = TransparencyAccumulator::new();
        let mut o = Vec::with_capacity(18);
        for (m, a) in adds {
            let (v, g) = acc.add(m, a);
            o.extend([v, g]);
        }
        o.extend((0..6).map(|k| acc.plane(k)));
        o.extend([
            acc.level(bit),
            acc.is_binary() as u32,
            acc.opaque(),
            acc.total_levels(),
            acc.level_set(set),
            acc.uncovered_weight().to_bits(),
        ]);
        o
    },
    generate: |rng| {
        let a = alphas(rng);
        (0..GENERATED)
            .map(|i| {
                let mut w = W::default();
                for k in 0..3 {
                    let m = match rng.below(4) {
                        0 => rng.bits(),
                        1 => u32::MAX,
                        2 => 0,
                        _ => ((1u64 << rng.below(32)) - 1) as u32,
                    };
                    w = w.u(m).f(a[(3 * i + k) % a.len()]);
                }
                w.u(rng.below(6)).u(rng.below(40)).0
            })
            .collect()
    },
};

/// Opacities as the conformance suite draws them: any, the quarter levels'
/// boundaries and specials, any bits.
fn alphas(rng: &mut Rng) -> Vec<f32> {
    let special = [
        0.0f32, 1.0, 0.5, 0.125, 0.375, 0.625, 0.875, 0.25, 0.75, 0.3, 0.7, -0.5, 1.5,
    ];
    let mut v: Vec<f32> = special.iter().chain(SPECIALS.iter()).copied().collect();
    for _ in 0..GENERATED {
        v.push(match rng.below(6) {
            0..=2 => rng.any_f32(0.0, 1.0),
            3..=4 => rng.pick(&special),
            _ => f32::from_bits(rng.bits()),
        });
    }
    v
}
