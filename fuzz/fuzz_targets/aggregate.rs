//! Eq. 6 aggregation with the background as a sample, and the sample weights.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{known_bug, product_underflows, v3, Hull, SUBNORMAL_ULP};
use glam::Vec3;
use libfuzzer_sys::fuzz_target;
use subcone_kernels::aggregate::{sample_weight, Aggregate, Weighting};
use subcone_kernels::mask::mask_weight;

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
    assert!(agg.weight() >= 0.0, "weight sum {}", agg.weight());
    let c = agg.resolve(background, x.bg_weight);
    assert!(c.is_finite(), "resolve = {c:?} is not finite ({samples:?}, {background:?}, {})", x.bg_weight);
    // The same aggregate after a full occlusion (bg weight 0), and with the
    // background at full weight.
    for bw in [0.0, 1.0, f32::NAN, f32::INFINITY] {
        assert!(agg.resolve(background, bw).is_finite());
    }

    let all_finite = samples.iter().all(|(w, c)| w.is_finite() && c.is_finite())
        && background.is_finite()
        && x.bg_weight.is_finite();
    if all_finite {
        let mut hull = Hull::new();
        for &(_, c) in &samples {
            hull.add(c);
        }
        hull.add(background);

        // Replay the kernel's sums to recognise the known bugs' inputs.
        let bgw = if x.bg_weight > 0.0 { x.bg_weight.min(1.0) } else { 0.0 };
        let mut wsum = 0.0f32;
        let mut underflow = false;
        for &(w, c) in &samples {
            let w = if w > 0.0 { w } else { 0.0 };
            wsum += w;
            underflow |= product_underflows(w, c);
        }
        underflow |= product_underflows(bgw, background);
        let total = wsum + bgw;
        // Known bug 4: Σw overflows to +∞ while Σw·C stays finite, so the quotient
        // is 0 (or tiny), wherever the colours are.
        let overflow = !total.is_finite();
        // Known bug 2 (as in sraa::reconstruct): w·C underflows while
        // Σw ≥ f32::MIN_POSITIVE.
        let extra = if total.is_finite() && total > 0.0 && known_bug(underflow) {
            (samples.len() + 1) as f64 * SUBNORMAL_ULP / total as f64
        } else {
            0.0
        };
        if !known_bug(overflow) {
            assert!(
                hull.contains(c, extra),
                "resolve = {c:?} outside the hull {hull:?} of {samples:?} and {background:?} (bg weight {})",
                x.bg_weight
            );
        }
    }
});
