//! Method names: every CLI word parses and round-trips through Display; bad
//! words give an error that lists the valid ones.

use subcone_kernels::passes::Technique;
use subcone_scene::method::ParseMethodError;
use subcone_scene::Method;

const WORDS: [&str; 12] = [
    "noaa",
    "ssaa4",
    "ssaa9",
    "ssaa16",
    "ssaa64",
    "ssaa256",
    "sraa",
    "sraa-rt",
    "ctss",
    "ctss-r",
    "ssaa4+ctss",
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
        ("ssaa4", Technique::Ssaa, 4),
        ("ssaa9", Technique::Ssaa, 9),
        ("ssaa16", Technique::Ssaa, 16),
        ("ssaa64", Technique::Ssaa, 64),
        ("ssaa256", Technique::Ssaa, 256),
        ("sraa", Technique::Sraa, 1),
        ("sraa-rt", Technique::SraaRt, 1),
        ("ctss", Technique::Ctss, 1),
        ("ctss-r", Technique::CtssR, 1),
        ("ssaa4+ctss", Technique::SsaaCtss, 4),
        ("ssaa16+ctss", Technique::SsaaCtss, 16),
        ("fxaa", Technique::Fxaa, 1),
    ];
    for (word, technique, samples) in cases {
        let m: Method = word.parse().unwrap();
        assert_eq!(m.technique, technique, "{word}");
        assert_eq!(m.supersamples(), samples, "{word}");
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
    ] {
        let err: ParseMethodError = bad.parse::<Method>().unwrap_err();
        assert_eq!(err.0, bad);
        let msg = err.to_string();
        assert!(msg.contains(&format!("{bad:?}")), "{msg}");
        for valid in [
            "noaa",
            "ssaaN",
            "4, 9, 16, 64, 256",
            "sraa",
            "sraa-rt",
            "ctss",
            "ctss-r",
            "ssaaN+ctss",
            "fxaa",
        ] {
            assert!(msg.contains(valid), "{bad:?}: {msg} lacks {valid}");
        }
    }
}
