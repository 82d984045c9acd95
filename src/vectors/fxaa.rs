//! FXAA's encode and its per-pixel filter.

use glam::Vec3;
use subcone_kernels::fxaa::{fxaa_encode, fxaa_pixel, FxaaParams};

use super::rng::special_pairs;
use super::rng::{Rng, GENERATED};
use super::tolerance::*;
use super::words::{out, R, W};
use super::KernelVectors;
use super::NO_REFERENCE;

pub(super) const FXAA_ENCODE: KernelVectors = KernelVectors {
    name: "fxaa_encode",
    inputs: "linear:vec3",
    outputs: "texel:vec4",
    tolerance: TOL_FXAA_ENCODE,
    tolerance_constant: "TOL_FXAA_ENCODE",
    non_finite: "The linear colour clamped to [0, 1], sRGB-encoded, in xyz, its luma (0.299, 0.587, 0.114 of the stored colour) in w, each rounded to 8-bit levels. Total: NaN channels read as 0, +-inf clamp; the result is always in [0, 1]^4.",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        out(&fxaa_encode(r.v3()).to_array())
    },
    generate: |rng| {
        let mut v: Vec<Vec<u32>> = (0..GENERATED)
            .map(|_| W::default().v(&rng.colour(1.2).to_array()).0)
            .collect();
        for (a, b) in special_pairs() {
            v.push(W::default().v(&[a, b, 0.5]).0);
        }
        // Every 8-bit sRGB level's linear value.
        for l in 0..256u32 {
            let x = subcone_kernels::fxaa::srgb_to_linear(l as f32 / 255.0);
            v.push(W::default().v(&[x, x, x]).0);
        }
        v
    },
};

pub(super) const FXAA_PIXEL: KernelVectors = KernelVectors {
    name: "fxaa_pixel",
    inputs: "p:vec3*49 subpix:f32 edge_threshold:f32 edge_threshold_min:f32",
    outputs: "c:vec3",
    tolerance: TOL_FXAA_PIXEL,
    tolerance_constant: "TOL_FXAA_PIXEL",
    non_finite: "FXAA 3.11 quality (preset 12) on the centre pixel (3, 3) of a 7x7 patch of linear colours. The patch's 49 colours p0..p48 come rows first (row y, column x is p<7y + x>); each is encoded by fxaa_encode, and a fetch outside the patch is clamped to its edge. The output is in the sRGB space of the encoded input, always finite and in [0, 1]^3: the centre unchanged or a blend of the centre with one of its four direct neighbours. NaN and infinite inputs are cleaned by fxaa_encode (NaN as 0, clamped). Where an edge puts FXAA's end-of-edge test on its threshold, one ulp may pick another span: the conformance suite accepts a port's output there when it still lies between the centre and its direct neighbours (at most 1 % of patches).",
    reference: NO_REFERENCE,
    eval: |w| {
        let mut r = R(w);
        let px: Vec<Vec3> = (0..49).map(|_| r.v3()).collect();
        let p = FxaaParams {
            subpix: r.f(),
            edge_threshold: r.f(),
            edge_threshold_min: r.f(),
            _pad: 0.0,
        };
        let fetch = |x: i32, y: i32| fxaa_encode(px[(y.clamp(0, 6) * 7 + x.clamp(0, 6)) as usize]);
        out(&fxaa_pixel(&fetch, 3, 3, &p).to_array())
    },
    generate: |rng| {
        (0..256)
            .map(|_| {
                let colour =
                    |rng: &mut Rng| Vec3::new(rng.unit(), rng.unit(), rng.unit());
                let px: Vec<Vec3> = match rng.below(6) {
                    0..=1 => (0..49).map(|_| colour(rng)).collect(),
                    2..=4 => {
                        let (a, b) = (colour(rng), colour(rng));
                        let (nx, ny) = (rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
                        let c = rng.range(-3.0, 3.0);
                        (0..49)
                            .map(|i| {
                                let (x, y) = ((i % 7) as f32 - 3.0, (i / 7) as f32 - 3.0);
                                if nx * x + ny * y > c {
                                    a
                                } else {
                                    b
                                }
                            })
                            .collect()
                    }
                    _ => (0..49).map(|_| rng.colour(2.0)).collect(),
                };
                let p = if rng.below(4) < 3 {
                    FxaaParams::QUALITY
                } else {
                    FxaaParams {
                        subpix: rng.range(0.0, 1.0),
                        edge_threshold: rng.range(0.063, 0.333),
                        edge_threshold_min: rng.range(0.0312, 0.0833),
                        _pad: 0.0,
                    }
                };
                let mut w = W::default();
                for c in &px {
                    w = w.v(&c.to_array());
                }
                w.f(p.subpix)
                    .f(p.edge_threshold)
                    .f(p.edge_threshold_min)
                    .0
            })
            .collect()
    },
};
