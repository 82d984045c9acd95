//! Method names: every CLI word parses and round-trips through Display; bad
//! words give an error that lists the valid ones.

use subcone_kernels::passes::Technique;
use subcone_scene::method::ParseMethodError;
use subcone_scene::Method;

const WORDS: [&str; 20] = [
    "noaa",
    "ssaa2",
    "ssaa2-hybrid",
    "ssaa4",
    "ssaa9",
    "ssaa16",
    "ssaa64",
    "ssaa256",
    "sraa",
    "sraa-rt",
    "sraa+mat",
    "sraa-rt+mat",
    "ctss",
    "ctss+edges",
    "ctss-r",
    "ssaa4+ctss",
    "ctss-delayed",
    "ctss-r-delayed",
    "ssaa4+ctss-delayed",
    "fxaa",
];

#[test]
fn every_word_parses_and_round_trips() {
    for word in WORDS {
        let m: Method = word.parse().unwrap_or_else(|e| panic!("{word}: {e}"));
        assert_eq!(m.to_string(), word);
        let again: Method = m.to_string().parse().unwrap();
        assert_eq!(again, m);
    }
}

#[test]
fn parsed_methods_have_the_right_technique_and_samples() {
    let cases = [
        ("noaa", Technique::NoAa, 1),
        ("ssaa2", Technique::Ssaa, 2),
        ("ssaa4", Technique::Ssaa, 4),
        ("ssaa9", Technique::Ssaa, 9),
        ("ssaa16", Technique::Ssaa, 16),
        ("ssaa64", Technique::Ssaa, 64),
        ("ssaa256", Technique::Ssaa, 256),
        ("sraa", Technique::Sraa, 1),
        ("sraa-rt", Technique::SraaRt, 1),
        ("sraa+mat", Technique::Sraa, 1),
        ("sraa-rt+mat", Technique::SraaRt, 1),
        ("ctss", Technique::Ctss, 1),
        ("ctss+edges", Technique::Ctss, 1),
        ("ctss-r", Technique::CtssR, 1),
        ("ssaa4+ctss", Technique::SsaaCtss, 4),
        ("ssaa16+ctss", Technique::SsaaCtss, 16),
        ("fxaa", Technique::Fxaa, 1),
    ];
    for (word, technique, samples) in cases {
        let m: Method = word.parse().unwrap();
        assert_eq!(m.technique(), technique, "{word}");
        assert_eq!(m.supersamples(), samples, "{word}");
    }
    // Delayed shading is a flag on the cone-traced techniques.
    let d: Method = "ctss-delayed".parse().unwrap();
    assert_eq!(d.technique(), Technique::Ctss);
    assert!(d.delayed_shading());
    assert!(!"ctss".parse::<Method>().unwrap().delayed_shading());
    assert_ne!(d, "ctss".parse::<Method>().unwrap());
    // Only the `+mat` words gate by albedo.
    for (word, gated) in [("sraa", false), ("sraa+mat", true), ("sraa-rt+mat", true)] {
        let m: Method = word.parse().unwrap();
        assert_eq!(m.gates_material(), gated, "{word}");
    }
    // Case and surrounding blanks are forgiven.
    assert_eq!(
        "  SRAA-RT ".parse::<Method>().unwrap().to_string(),
        "sraa-rt"
    );
}

#[test]
fn bad_words_list_the_valid_ones() {
    for bad in [
        "ssaa5",
        "",
        "foo",
        "ssaa",
        "ssaa0",
        "ssaa-4",
        "ssaa5+ctss",
        "ctss+ssaa4",
        "sraa rt",
        "noaa-delayed",
        "sraa-rt-delayed",
        "ctss+edges-delayed",
        "ctss-delayed-delayed",
        "-delayed",
        "noaa+mat",
        "ctss+mat",
        "sraa-rt+mat-delayed",
    ] {
        let err: ParseMethodError = bad.parse::<Method>().unwrap_err();
        assert_eq!(err, ParseMethodError::Unknown(bad.to_string()));
        let msg = err.to_string();
        assert!(msg.contains(&format!("{bad:?}")), "{msg}");
        // Every word without a sample count or a modifier suffix by name, the
        // sample-count words by their pattern.
        let fixed = WORDS
            .into_iter()
            .filter(|w| !w.starts_with("ssaa") && !w.ends_with("-delayed"));
        for valid in fixed.chain(["ssaaN", "4, 9, 16, 64, 256", "ssaaN+ctss"]) {
            assert!(msg.contains(valid), "{bad:?}: {msg} lacks {valid}");
        }
    }
}

/// `ctss+edges` is CTSS with hit group subdivision (§5.3); no other word
/// turns it on.
#[test]
fn only_ctss_edges_splits_groups() {
    for word in WORDS {
        let m: Method = word.parse().unwrap();
        assert_eq!(m.split_groups(), word == "ctss+edges", "{word}");
    }
}

#[test]
fn ssaa2_is_the_diagonal_of_the_2x2_grid_on_triangle_scenes_only() {
    use subcone_scene::backend::{plan, Capabilities};
    use subcone_scene::builtin::builtin;
    use subcone_scene::UnsupportedReason;
    let m: Method = "ssaa2".parse().unwrap();
    assert_eq!(m, Method::SSAA2);
    assert_eq!(
        (m.ssaa_side(), m.supersamples(), m.ssaa_diagonal()),
        (2, 2, true)
    );
    assert!(!Method::ssaa(4).unwrap().ssaa_diagonal());
    // No 2-sample cone tracing per supersample.
    assert!("ssaa2+ctss".parse::<Method>().is_err());
    let caps = |diagonal_ssaa| Capabilities {
        backend: "test",
        max_lights_triangles: None,
        max_lights_sdf: None,
        sdf_subpixel_geometry: Ok(()),
        max_sdf_side_samples: None,
        raster_primary: Ok(()),
        diagonal_ssaa,
    };
    let cornell = builtin("cornell").unwrap();
    assert!(plan(&cornell, &m, &caps(Ok(()))).is_ok());
    // A backend without it refuses, rather than render the 2×2 grid.
    let e = plan(&cornell, &m, &caps(Err("no diagonal"))).unwrap_err();
    assert!(
        matches!(
            e.reason,
            UnsupportedReason::CpuOnly {
                why: "no diagonal",
                ..
            }
        ),
        "{e}"
    );
    // SDF scenes refuse it on any backend.
    let primitives = builtin("primitives").unwrap();
    let e = plan(&primitives, &m, &caps(Ok(()))).unwrap_err();
    assert_eq!(e.reason, UnsupportedReason::DiagonalSsaaOnSdf);
}
