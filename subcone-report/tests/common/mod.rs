//! What the quality tests share: a scene judged as the quick report judges
//! it, on the CPU backend.

use subcone_cpu::CpuBackend;
use subcone_metrics::{self as metrics, Rgb8};
use subcone_report::classes::{self, ClassError, ClassMasks};
use subcone_scene::{Backend, Frame, Method, RenderSettings, Scene};

/// `method` on `scene` at `settings`, on the CPU backend.
pub fn render(scene: &Scene, method: &str, settings: &RenderSettings) -> Frame {
    let method: Method = method.parse().expect("method");
    CpuBackend::new()
        .render(scene, &scene.camera, &method, settings)
        .expect("render")
}

/// A scene at one size with its `ssaa64` reference and its edge classes
/// (from NoAA's AOVs at [`classes::SUBSAMPLES`]² sub-samples per pixel), as
/// the quick report computes them.
pub struct Judged<'a> {
    scene: &'a Scene,
    settings: RenderSettings,
    reference: Rgb8,
    masks: ClassMasks,
}

impl<'a> Judged<'a> {
    /// Render the reference and the classes of `scene` at `w × h`.
    pub fn new(scene: &'a Scene, w: u32, h: u32) -> Self {
        let settings = RenderSettings::new(w, h);
        let reference = Rgb8::from_frame(&render(scene, "ssaa64", &settings)).unwrap();
        let side = classes::SUBSAMPLES;
        let mut sub = RenderSettings::new(w * side, h * side);
        sub.aovs = true;
        let masks = classes::classify(&render(scene, "noaa", &sub), side).unwrap();
        Judged {
            scene,
            settings,
            reference,
            masks,
        }
    }

    /// The same judgement with FLIP's near-edge band `radius` pixels wide
    /// ([`ClassMasks::with_flip_band`]). Only some of the tests that share
    /// this module call it.
    #[allow(dead_code)]
    pub fn with_flip_band(&self, radius: u32) -> Judged<'a> {
        Judged {
            scene: self.scene,
            settings: self.settings,
            reference: self.reference.clone(),
            masks: self.masks.with_flip_band(radius),
        }
    }

    /// The whole-image mean FLIP of `method` against the reference, and its
    /// FLIP per class.
    pub fn measure(&self, method: &str) -> (f64, ClassError) {
        let image = Rgb8::from_frame(&render(self.scene, method, &self.settings)).unwrap();
        let f = metrics::flip(&self.reference, &image).unwrap();
        (
            f.mean,
            ClassError::measure(&f.map, &self.masks, classes::Metric::Flip),
        )
    }
}
