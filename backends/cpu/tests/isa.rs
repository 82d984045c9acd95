//! Every instruction-set path renders the same frames as the baseline path,
//! bit for bit: triangle scenes with the SRAA family, SDF scenes with CTSS.

use subcone_cpu::isa::Isa;
use subcone_cpu::CpuBackend;
use subcone_scene::builtin::builtin;
use subcone_scene::{Backend, Method, RenderSettings};

const W: u32 = 48;
const H: u32 = 32;

/// The colour buffer's bits.
fn render_bits(isa: Isa, scene: &str, method: &str) -> Vec<u32> {
    let scene = builtin(scene).unwrap_or_else(|e| panic!("{scene}: {e}"));
    let method: Method = method.parse().expect("a method name");
    CpuBackend::new()
        .with_isa(isa)
        .render(&scene, &scene.camera, &method, &RenderSettings::new(W, H))
        .unwrap_or_else(|e| panic!("{} {method} on {isa}: {e}", scene.name))
        .color
        .iter()
        .flat_map(|c| c.to_array().map(f32::to_bits))
        .collect()
}

/// One test per scene: every method, every supported path against baseline.
macro_rules! same_bits_on_every_path {
    ($($test:ident: $scene:literal, [$($method:literal),+];)+) => {$(
        #[test]
        fn $test() {
            for method in [$($method),+] {
                let baseline = render_bits(Isa::Baseline, $scene, method);
                for isa in Isa::supported() {
                    let frame = render_bits(isa, $scene, method);
                    let differing = frame.iter().zip(&baseline).filter(|(a, b)| a != b).count();
                    assert!(
                        differing == 0,
                        "{} {method} on {isa}: {differing} of {} channels differ from baseline",
                        $scene,
                        frame.len()
                    );
                }
            }
        }
    )+};
}

same_bits_on_every_path! {
    cornell: "cornell", ["noaa", "ssaa4", "sraa", "sraa-rt"];
    checker: "checker", ["noaa", "ssaa4", "sraa", "sraa-rt"];
    primitives: "primitives", ["noaa", "ssaa4", "ctss"];
    random_box: "random-box", ["noaa", "ssaa4", "ctss"];
}

/// `Isa`'s names and its fallback to a supported path.
mod names {
    use super::*;

    #[test]
    fn names_round_trip_and_fallback_is_supported() {
        for i in Isa::ALL {
            assert_eq!(i.name().parse::<Isa>(), Ok(i));
            assert!(i.or_supported().is_supported());
            assert!(i.or_supported() <= i);
            // The nesting `or_supported` relies on.
            assert_eq!(
                i.or_supported(),
                Isa::ALL
                    .into_iter()
                    .rev()
                    .filter(|j| *j <= i)
                    .find(|j| j.is_supported())
                    .unwrap()
            );
        }
        assert!("sse9".parse::<Isa>().is_err());
        assert!(Isa::supported().contains(&Isa::Baseline));
        assert_eq!(Isa::supported().last(), Some(&Isa::detected()));
    }
}
