//! Eq. 6 aggregation with the background as a sample, and the sample weights.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{v3, Hull};
use glam::Vec3;
use libfuzzer_sys::fuzz_target;
use subcone_kernels::aggregate::{sample_weight, Aggregate, Weighting};
use subcone_kernels::mask::mask_weight;
use subcone_kernels::sraa::NEGLIGIBLE_WEIGHT;

#[derive(Arbitrary, Debug)]
struct Input {
    samples: Vec<(f32, [f32; 3])>,
    background: [f32; 3],
    bg_weight: f32,
    visible: u32,
    weighting: u32,
    min_weight: f32,
}

fuzz_target!(|x: Input| {
    // Sample weights.
    let vw = sample_weight(x.visible, Weighting::Visibility, x.min_weight);
    assert!(
        (0.0..=1.0).contains(&vw),
        "sample_weight({:#x}, Visibility, {}) = {vw}",
        x.visible,
        x.min_weight
    );
    assert!(vw >= mask_weight(x.visible));
    let clamped = if x.min_weight.is_finite() {
        x.min_weight.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let w = sample_weight(x.visible, Weighting::Visibility, clamped);
    assert!((0.0..=1.0).contains(&w) && w >= clamped && w >= mask_weight(x.visible));
    assert!(sample_weight(x.visible, Weighting::Uniform, x.min_weight) == 1.0);
    let any = sample_weight(x.visible, Weighting::from_u32(x.weighting), x.min_weight);
    assert!((0.0..=1.0).contains(&any));

    // Aggregation.
    let samples: Vec<(f32, Vec3)> = x.samples.iter().take(10).map(|&(w, c)| (w, v3(c))).collect();
    let background = v3(x.background);
    let mut agg = Aggregate::new();
    for &(w, c) in &samples {
        agg.add(w, c);
    }
    assert!(agg.samples() as usize == samples.len());

    // Replay the documented sums (accumulated in f64, as the kernel does):
    // non-finite colours are not added (but still count as samples), weights
    // are clamped to [0, 1] (NaN and negative read as 0), so Σw ≤ the number of
    // finite colours and never overflows.
    let mut wsum = 0.0f64;
    let mut added = 0usize;
    let mut last = None;
    let mut hull = Hull::new();
    for &(w, c) in &samples {
        if !c.is_finite() {
            continue;
        }
        wsum += if w > 0.0 { w.min(1.0) as f64 } else { 0.0 };
        added += 1;
        last = Some(c);
        hull.add(c);
    }
    assert!(
        agg.weight() >= 0.0 && agg.weight() <= added as f32 && agg.weight().to_bits() == (wsum as f32).to_bits(),
        "weight sum {} (replayed {wsum}, {added} finite colours) of {samples:?}",
        agg.weight()
    );
    if background.is_finite() {
        hull.add(background);
    }
    // The fallback: the last surface's colour, else the background, else black.
    let fallback = last.unwrap_or(if background.is_finite() {
        background
    } else {
        Vec3::ZERO
    });

    // The given background weight, then a full occlusion (0), full weight, and
    // out-of-domain weights.
    for bw in [x.bg_weight, 0.0, 1.0, f32::NAN, f32::INFINITY] {
        let c = agg.resolve(background, bw);
        assert!(
            c.is_finite(),
            "resolve = {c:?} is not finite ({samples:?}, {background:?}, {bw})"
        );
        let bgw = if bw > 0.0 && background.is_finite() {
            bw.min(1.0)
        } else {
            0.0
        };
        let total = wsum + bgw as f64;
        // A negligible total (Σw·C may have lost its precision to underflow)
        // falls back.
        if !(total >= NEGLIGIBLE_WEIGHT as f64) {
            assert!(
                c == fallback,
                "resolve = {c:?} with negligible total weight {total:e}, expected the fallback \
                 {fallback:?} ({samples:?}, {background:?}, bg weight {bw})"
            );
        }
        if hull.is_empty() {
            assert!(c == Vec3::ZERO, "resolve = {c:?} with nothing finite");
        } else {
            assert!(
                hull.contains(c),
                "resolve = {c:?} outside the hull {hull:?} of {samples:?} and {background:?} \
                 (bg weight {bw}, total weight {total:e})"
            );
        }
    }
});
