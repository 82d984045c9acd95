//! `ConeStepper::advance_free_lanes` (the packets' free-space step) against
//! `advance_object` lane by lane: the same events and the same stepper state,
//! bit for bit, on random distance sequences through surfaces, NaNs, step
//! budgets and `t_max`, for CTSS, CTSS-R and the paper's variant.
use proptest::prelude::*;
use subcone_kernels::ctss::{ConeStepper, CtssParams, Event};

const N: usize = 8;

fn params(variant: u8, max_steps: u32) -> CtssParams {
    let p = CtssParams::new(0.01)
        .with_range(0.0, 40.0)
        .with_max_steps(max_steps);
    match variant % 3 {
        0 => p,
        1 => p.relaxed(true),
        _ => p.paper(true),
    }
}

/// A distance: mostly free space, some contact and inside, rarely NaN.
fn distance() -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => 0.0f32..3.0,
        3 => -0.2f32..0.2,
        1 => Just(f32::NAN),
    ]
}

proptest! {
    #[test]
    fn free_lanes_step_as_advance_object(
        variant in 0u8..3,
        max_steps in 1u32..64,
        steps in prop::collection::vec(
            (prop::array::uniform8(distance()), prop::array::uniform8(0.0f32..1.0), any::<u8>()),
            1..64,
        ),
    ) {
        let p = params(variant, max_steps);
        let mut scalar: [ConeStepper; N] = std::array::from_fn(|_| ConeStepper::new(&p));
        let mut lanes = scalar.clone();
        for (d, cap, active) in steps {
            // The safe step: a bound `≤ d` where `d` is positive.
            let step: [f32; N] = std::array::from_fn(|k| d[k] * cap[k]);
            let active = active as u32;
            let slow = ConeStepper::advance_free_lanes(&mut lanes, &d, &step, active);
            prop_assert_eq!(slow & !active, 0);
            for k in 0..N {
                if active & (1 << k) == 0 {
                    continue;
                }
                let want = scalar[k].advance_object(d[k], step[k], k as u32);
                if slow & (1 << k) != 0 {
                    let got = lanes[k].advance_object(d[k], step[k], k as u32);
                    prop_assert_eq!(format!("{got:?}"), format!("{want:?}"));
                } else {
                    prop_assert_eq!(want, Event::March, "lane {} was free", k);
                }
                prop_assert_eq!(format!("{:?}", lanes[k]), format!("{:?}", scalar[k]));
            }
        }
    }
}
