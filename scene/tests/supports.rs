//! `Backend::supports`: the default plan (the kernels' `required_passes`), the
//! typed reasons and their messages.

use subcone_kernels::passes::Technique;
use subcone_scene::builtin::{builtin, names};
use subcone_scene::{
    Backend, Camera, Frame, Method, RenderError, RenderSettings, Scene, Unsupported,
    UnsupportedReason,
};

/// A backend with no limits of its own: it keeps the default `supports`.
struct Plain;

impl Backend for Plain {
    fn name(&self) -> &'static str {
        "plain"
    }

    fn render(
        &self,
        scene: &Scene,
        _camera: &Camera,
        method: &Method,
        settings: &RenderSettings,
    ) -> Result<Frame, RenderError> {
        self.supports(scene, method)?;
        Ok(Frame::new(settings.width, settings.height))
    }
}

#[test]
fn default_supports_is_required_passes() {
    for name in names() {
        let scene = builtin(name).unwrap();
        for technique in Technique::ALL {
            let method = Method::new(technique);
            let expected =
                subcone_kernels::passes::required_passes(technique, scene.features()).err();
            match Plain.supports(&scene, &method) {
                Ok(()) => assert_eq!(expected, None, "{name} {method}"),
                Err(u) => {
                    assert_eq!(u.backend, "plain");
                    assert_eq!(u.scene, scene.name);
                    assert_eq!(u.method, method.to_string());
                    assert_eq!(
                        Some(u.reason),
                        expected.map(UnsupportedReason::Technique),
                        "{name} {method}"
                    );
                }
            }
        }
    }
}

#[test]
fn render_returns_the_planned_refusal() {
    let scene = builtin("cornell").unwrap();
    let method: Method = "ctss".parse().unwrap();
    let planned = Plain.supports(&scene, &method).unwrap_err();
    match Plain.render(&scene, &scene.camera, &method, &RenderSettings::new(4, 4)) {
        Err(RenderError::NotSupported(u)) => assert_eq!(u, planned),
        other => panic!("{other:?}"),
    }
    let message = RenderError::from(planned).to_string();
    assert_eq!(
        message,
        "the plain backend cannot render scene \"cornell\" with ctss: \
         cone tracing needs a signed distance field"
    );
}

#[test]
fn every_reason_reads_as_a_sentence() {
    let scene = builtin("primitives").unwrap();
    let method: Method = "ctss+edges".parse().unwrap();
    let cases = [
        (
            UnsupportedReason::SdfReflections,
            "mirror reflections in SDF scenes are not implemented",
        ),
        (
            UnsupportedReason::MaterialGateOnSdf,
            "the material gate (+mat) is not implemented on SDF scenes",
        ),
        (
            UnsupportedReason::Translucency {
                what: "sraa-rt".into(),
                instead: "ctss renders them".into(),
            },
            "sraa-rt is not implemented for semi-transparent materials (alpha < 1); ctss renders them",
        ),
        (
            UnsupportedReason::CpuOnly {
                what: "ctss+edges",
                why: "no WGSL twin",
            },
            "ctss+edges runs on the CPU backend only (no WGSL twin)",
        ),
        (
            UnsupportedReason::TooManyLights { lights: 9, max: 8 },
            "9 lights; at most 8 are supported",
        ),
        (
            UnsupportedReason::TooManySamples { side: 65, max: 64 },
            "65x65 samples per pixel; at most 64x64 are supported",
        ),
    ];
    for (reason, needle) in cases {
        let u = Unsupported::new("gpu", &scene, &method, reason);
        let text = u.to_string();
        assert!(
            text.starts_with(
                "the gpu backend cannot render scene \"primitives\" with ctss+edges: "
            ),
            "{text}"
        );
        assert!(text.contains(needle), "{text}");
        let e: Box<dyn std::error::Error> = Box::new(u);
        assert_eq!(e.to_string(), text);
    }
}
