//! Ambient occlusion's directions and fraction.

use subcone_kernels::ao::{ao_direction, ao_fraction};

use super::grids::{ao_grid_normals, AO_GRID_INDICES};
use super::rng::GENERATED;
use super::tolerance::*;
use super::words::{out, R, W};
use super::KernelVectors;
use super::NO_REFERENCE;

pub(super) const AO_DIRECTION: KernelVectors = KernelVectors {
    name: "ao_direction",
    inputs: "n:vec3 i:u32 count:u32",
    outputs: "dir:vec3",
    tolerance: TOL_AO_DIRECTION,
    tolerance_constant: "TOL_AO_DIRECTION",
    non_finite: "Direction i of count (cosine-weighted, stratified) around the normal n, in tangent_frame(n). A zero or non-finite n is treated as +Z; count = 0 gives the normal; i is clamped to count - 1. The result is always finite.",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let (n, i, c) = (r.v3(), r.u(), r.u());
        out(&ao_direction(n, i, c).to_array())
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                W::default()
                    .v(&rng.unit_vec().to_array())
                    .u(rng.below(300))
                    .u(rng.below(300))
                    .0
            })
            .collect();
        for n in ao_grid_normals() {
            for (i, c) in AO_GRID_INDICES {
                v.push(W::default().v(&n.to_array()).u(i).u(c).0);
            }
        }
        v
    },
};

pub(super) const AO_FRACTION: KernelVectors = KernelVectors {
    name: "ao_fraction",
    inputs: "unoccluded:u32 count:u32",
    outputs: "fraction:f32",
    tolerance: TOL_AO_FRACTION,
    tolerance_constant: "TOL_AO_FRACTION",
    non_finite: "unoccluded / count in [0, 1]. Domain: unoccluded <= count. count = 0 gives exactly 1; unoccluded > count is clamped to 1.",
    reference: "f64: min(unoccluded, count) / count (1 for count = 0), correctly rounded (checked by tests/vectors.rs).",
    eval: |w| {
        let mut r = R(w);
        out(&[ao_fraction(r.u(), r.u())])
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| {
                let c = rng.below(300);
                W::default().u(rng.below(c + 2)).u(c).0
            })
            .collect();
        for (i, c) in [
            (0, 0),
            (1, 0),
            (0, 1),
            (1, 1),
            (2, 1),
            (u32::MAX, u32::MAX),
            (1, 3),
            (1 << 24, 1 << 24),
            ((1 << 24) - 1, 1 << 24),
        ] {
            v.push(W::default().u(i).u(c).0);
        }
        v
    },
};
