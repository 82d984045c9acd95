//! Every technique on every combination of scene features: the planner must
//! leave out exactly what the scene does not need.
use subcone_kernels::passes::{required_passes, Passes, SceneFeatures, Technique};

/// All 16 combinations of the feature flags.
fn all_features() -> impl Iterator<Item = SceneFeatures> {
    (0..16u32).map(SceneFeatures::from_bits_truncate)
}

/// The expected passes, written out per technique (not derived from the same code).
fn expected(t: Technique, f: SceneFeatures) -> Option<Passes> {
    let lights = f.contains(SceneFeatures::HAS_LIGHTS);
    let refl = f.contains(SceneFeatures::HAS_REFLECTIONS);
    let sdf = f.contains(SceneFeatures::IS_SDF);
    let opt = |on: bool, p: Passes| if on { p } else { Passes::empty() };
    let shade = Passes::SHADING
        | opt(lights, Passes::SHADOW)
        | opt(refl, Passes::SECONDARY)
        | opt(lights && refl, Passes::SECONDARY_SHADOW);
    Some(match t {
        Technique::NoAa => Passes::PRIMARY | shade,
        Technique::Fxaa => Passes::PRIMARY | shade | Passes::POST_PROCESS,
        Technique::Ssaa => Passes::PRIMARY | Passes::SUPERSAMPLE | shade,
        Technique::Sraa if !sdf => {
            Passes::PRIMARY
                | Passes::SUBPIXEL_GEOMETRY
                | Passes::RECONSTRUCTION
                | Passes::RESOLVE
                | shade
        }
        Technique::SraaRt => {
            Passes::PRIMARY
                | Passes::SUBPIXEL_GEOMETRY
                | Passes::RECONSTRUCTION
                | Passes::RESOLVE
                | shade
                | opt(lights, Passes::SUBPIXEL_SHADOW)
                | opt(
                    refl,
                    Passes::SUBPIXEL_SECONDARY_GEOMETRY | Passes::SECONDARY_RECONSTRUCTION,
                )
        }
        Technique::Ctss | Technique::CtssR if sdf => Passes::CONE_TRACE | shade,
        Technique::SsaaCtss if sdf => Passes::CONE_TRACE | Passes::SUPERSAMPLE | shade,
        _ => return None,
    })
}

#[test]
fn every_technique_on_every_feature_combination() {
    let mut checked = 0;
    for t in Technique::ALL {
        for f in all_features() {
            let got = required_passes(t, f);
            match expected(t, f) {
                Some(want) => assert_eq!(got, Ok(want), "{t:?} on {f:?}"),
                None => assert!(
                    got.is_err(),
                    "{t:?} on {f:?} should be unsupported, got {got:?}"
                ),
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 8 * 16);
}

#[test]
fn unneeded_passes_are_left_out() {
    let shadow = Passes::SHADOW | Passes::SUBPIXEL_SHADOW | Passes::SECONDARY_SHADOW;
    let secondary = Passes::SECONDARY
        | Passes::SECONDARY_SHADOW
        | Passes::SUBPIXEL_SECONDARY_GEOMETRY
        | Passes::SECONDARY_RECONSTRUCTION;
    for t in Technique::ALL {
        for f in all_features() {
            let Ok(p) = required_passes(t, f) else {
                continue;
            };
            if !f.contains(SceneFeatures::HAS_LIGHTS) {
                assert!(
                    !p.intersects(shadow),
                    "{t:?} on {f:?} runs a shadow pass: {p:?}"
                );
            }
            if !f.contains(SceneFeatures::HAS_REFLECTIONS) {
                assert!(
                    !p.intersects(secondary),
                    "{t:?} on {f:?} runs a secondary pass: {p:?}"
                );
            }
            // Textures never change the passes.
            assert_eq!(required_passes(t, f ^ SceneFeatures::HAS_TEXTURES), Ok(p));
        }
    }
}

#[test]
fn unsupported_combinations_explain_themselves() {
    let e = required_passes(Technique::Ctss, SceneFeatures::empty()).unwrap_err();
    assert!(e.to_string().contains("signed distance field"), "{e}");
    let e = required_passes(Technique::Sraa, SceneFeatures::IS_SDF).unwrap_err();
    assert!(e.to_string().contains("triangle"), "{e}");
    // SRAA-RT samples by ray casting: it runs on SDFs (sphere traced), with
    // its shadow passes only where there are lights.
    let p = required_passes(Technique::SraaRt, SceneFeatures::IS_SDF).unwrap();
    assert!(p.contains(Passes::SUBPIXEL_GEOMETRY | Passes::RECONSTRUCTION));
    assert!(!p.intersects(Passes::SHADOW | Passes::SUBPIXEL_SHADOW));
}

/// SRAA-RT's shading layers follow the planned passes: per-light layers only
/// with a shadow pass, secondary layers only with secondary reconstruction;
/// every other technique reconstructs the one final colour.
#[test]
fn layer_layout_follows_the_passes() {
    use subcone_kernels::passes::LayerLayout;
    let all = Passes::SHADOW | Passes::SECONDARY_RECONSTRUCTION;
    let rt = LayerLayout::new(Technique::SraaRt, all, 2);
    assert_eq!((rt.len(), rt.secondary_base()), (6, 3));
    assert_eq!(
        LayerLayout::new(Technique::SraaRt, Passes::SHADOW, 2).len(),
        3
    );
    assert_eq!(
        LayerLayout::new(Technique::SraaRt, Passes::SECONDARY_RECONSTRUCTION, 2).len(),
        2
    );
    assert_eq!(
        LayerLayout::new(Technique::SraaRt, Passes::empty(), 2).len(),
        1
    );
    let plain = LayerLayout::new(Technique::Sraa, all, 2);
    assert!(plain.single);
    assert_eq!((plain.len(), plain.lights, plain.secondary), (1, 0, false));
}
