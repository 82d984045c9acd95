//! The registry of antialiasing methods: for each kernel [`Technique`], its
//! name grammar, family, the edge classes it claims to antialias, its
//! modifiers, a one-line description and what a backend needs to run it.
//!
//! Everything that lists or names methods reads it: [`Method`](crate::method::Method)'s parser and
//! `Display`, [`METHOD_NAMES`] (the default comparison), the CLI's
//! `--method` help ([`method_help`]), the report's claims and plot families,
//! the conformance suite's families and the one support plan
//! ([`crate::backend::plan`]). A method name is written as a string literal
//! here and nowhere else. Adding a technique is one [`TechniqueInfo`] here,
//! its kernel, and each backend's pass (ARCHITECTURE.md, "Adding a method").
//!
//! ```
//! use subcone_scene::registry::{info, EdgeClass, Family};
//! use subcone_scene::Method;
//! use subcone_kernels::passes::Technique;
//!
//! let sraa_rt = info(Technique::SraaRt);
//! assert_eq!(sraa_rt.family, Family::Sraa);
//! assert!(sraa_rt.claims.contains(&EdgeClass::Shadow));
//! // A modifier adds its claims: the material gate claims texture edges.
//! let m: Method = "sraa-rt+mat".parse().unwrap();
//! assert!(m.claims().contains(&EdgeClass::Texture));
//! ```

use std::fmt;

use subcone_kernels::passes::Technique;

/// An edge class: what a pixel contains that aliases (the report's masks
/// classify each pixel into one).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EdgeClass {
    /// Different surfaces, or a surface and the background, inside the pixel.
    Silhouette,
    /// One continuous surface folds inside the pixel.
    Crease,
    /// Smooth geometry, but a light's visibility changes inside the pixel.
    Shadow,
    /// Smooth geometry, but the albedo changes inside the pixel.
    Texture,
    /// The pixel sees a mirror.
    Reflection,
    /// None of the above.
    Flat,
}

/// Every edge class, in column order.
pub const EDGE_CLASSES: [EdgeClass; 6] = [
    EdgeClass::Silhouette,
    EdgeClass::Crease,
    EdgeClass::Shadow,
    EdgeClass::Texture,
    EdgeClass::Reflection,
    EdgeClass::Flat,
];

impl EdgeClass {
    /// The name used in columns (`flip_<name>`, `px_<name>`) and the report.
    pub fn name(self) -> &'static str {
        match self {
            EdgeClass::Silhouette => "silhouette",
            EdgeClass::Crease => "crease",
            EdgeClass::Shadow => "shadow",
            EdgeClass::Texture => "texture",
            EdgeClass::Reflection => "reflection",
            EdgeClass::Flat => "flat",
        }
    }

    /// Index in [`EDGE_CLASSES`].
    pub fn index(self) -> usize {
        self as usize
    }
}

impl fmt::Display for EdgeClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A family of techniques: what plots colour alike and what the conformance
/// suite bounds together.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    /// One sample per pixel, nothing else (the baseline every method is
    /// judged against).
    NoAa,
    /// A regular grid of samples per pixel.
    Supersampling,
    /// Subpixel reconstruction (SRAA, SRAA-RT).
    Sraa,
    /// Cone-traced supersampling (CTSS, CTSS-R, SSAA+CTSS).
    Ctss,
    /// A filter over the finished NoAA image (FXAA; the report's SMAA and
    /// outside commands).
    PostProcess,
}

/// What a post-process claims: luminance edges of any origin, but not
/// what a mirror shows (it sees only the final image).
pub const POST_PROCESS_CLAIMS: &[EdgeClass] = &[
    EdgeClass::Silhouette,
    EdgeClass::Crease,
    EdgeClass::Shadow,
    EdgeClass::Texture,
];

/// What supersampling claims: every edge class.
pub(crate) const SUPERSAMPLING_CLAIMS: &[EdgeClass] = &[
    EdgeClass::Silhouette,
    EdgeClass::Crease,
    EdgeClass::Shadow,
    EdgeClass::Texture,
    EdgeClass::Reflection,
];

/// The modifiers a method name may carry, and what each does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Modifiers {
    /// `ssaaN…`: a sample count N from [`SSAA_COUNTS`].
    pub samples: bool,
    /// `-paper`: the paper's preset instead of the tuned one.
    pub paper: bool,
    /// `+mat`: the SRAA material gate (claims texture edges).
    pub material_gate: bool,
    /// `-delayed`: CTSS delayed shading.
    pub delayed: bool,
    /// `+edges`: CTSS hit-group subdivision at internal edges (claims creases).
    pub edges: bool,
    /// `+taa`: the method under temporal antialiasing
    /// ([`crate::temporal`]); NoAA under it is `taa`.
    pub temporal: bool,
    /// `-hybrid`: primary visibility (every primary sample and SRAA
    /// subsample) rasterised instead of traced, on triangle scenes (SRAA
    /// §3.1, §4.2).
    pub hybrid: bool,
}

impl Modifiers {
    /// No modifier.
    pub const NONE: Modifiers = Modifiers {
        samples: false,
        paper: false,
        material_gate: false,
        delayed: false,
        edges: false,
        temporal: false,
        hybrid: false,
    };
}

/// What a backend needs, beyond tracing the scene's geometry, to run a
/// technique ([`crate::backend::Capabilities`] says what it has).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Needs {
    /// On SDF scenes: sphere-traced subpixel geometry and its reconstruction
    /// (SRAA-RT).
    pub sdf_subpixel_geometry: bool,
    /// On SDF scenes: several samples per pixel side
    /// ([`crate::backend::Capabilities::max_sdf_side_samples`] bounds them).
    pub sdf_supersampling: bool,
}

impl Needs {
    /// Nothing beyond tracing the scene's geometry.
    pub const NONE: Needs = Needs {
        sdf_subpixel_geometry: false,
        sdf_supersampling: false,
    };
}

/// One technique in the registry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TechniqueInfo {
    /// The kernels' technique.
    pub technique: Technique,
    /// The name without modifiers; `ssaa` and `ssaa+ctss` take their sample
    /// count after `ssaa` (`ssaa16`, `ssaa4+ctss`).
    pub name: &'static str,
    /// The name's grammar, as help and errors state it.
    pub grammar: &'static str,
    /// Its family.
    pub family: Family,
    /// The edge classes it claims to antialias, before modifiers.
    pub claims: &'static [EdgeClass],
    /// The modifiers its names may carry.
    pub modifiers: Modifiers,
    /// Whether it carries opacity through semi-transparent SDF materials
    /// (CTSS §5.3's `K` masks, or alpha blending along each sample's ray).
    pub carries_opacity: bool,
    /// What a backend needs to run it.
    pub needs: Needs,
    /// Where its `+taa` sequence puts each frame's sample (for a technique
    /// without the temporal modifier, what it would be).
    pub taa_jitter: TaaJitter,
    /// One line for help and the report.
    pub description: &'static str,
}

/// How a `+taa` sequence jitters its frames ([`Taa::jitter`](crate::temporal::Taa::jitter)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TaaJitter {
    /// The Halton (2, 3) point of the frame's phase
    /// ([`subcone_kernels::taa::jitter`]).
    Halton,
    /// The shaded sample on geometric subsample `t mod 4` of SRAA's rotated
    /// grid ([`subcone_kernels::taa::subsample_rotation`]), as SMAA T2x
    /// rotates its subsample indices.
    SubsampleRotation,
}

/// Sample counts of the regular grids `ssaaN` and `ssaaN+ctss` accept:
/// squares.
pub const SSAA_COUNTS: [u32; 5] = [4, 9, 16, 64, 256];

/// The one count `ssaaN` also accepts that is not a square: `ssaa2`, the
/// diagonal of the 2×2 grid ([`Method::SSAA2`](crate::Method::SSAA2)).
pub const SSAA_DIAGONAL: u32 = 2;

/// Every technique, in [`Technique::ALL`] order.
pub const TECHNIQUES: [TechniqueInfo; 8] = [
    TechniqueInfo {
        technique: Technique::NoAa,
        name: "noaa",
        grammar: "noaa",
        family: Family::NoAa,
        claims: &[],
        modifiers: Modifiers {
            hybrid: true,
            temporal: true,
            ..Modifiers::NONE
        },
        carries_opacity: true,
        needs: Needs::NONE,
        taa_jitter: TaaJitter::Halton,
        description: "one ray through each pixel centre: no antialiasing",
    },
    TechniqueInfo {
        technique: Technique::Ssaa,
        name: "ssaa",
        grammar: "ssaaN (N in 2, 4, 9, 16, 64, 256; ssaa2 on triangle scenes)",
        family: Family::Supersampling,
        claims: SUPERSAMPLING_CLAIMS,
        modifiers: Modifiers {
            hybrid: true,
            samples: true,
            ..Modifiers::NONE
        },
        carries_opacity: true,
        needs: Needs {
            sdf_supersampling: true,
            ..Needs::NONE
        },
        taa_jitter: TaaJitter::Halton,
        description: "N shaded samples per pixel on a regular grid (ssaa2: the 2×2 grid's diagonal), box-filtered",
    },
    TechniqueInfo {
        technique: Technique::Sraa,
        name: "sraa",
        grammar: "sraa",
        family: Family::Sraa,
        claims: &[EdgeClass::Silhouette, EdgeClass::Crease],
        modifiers: Modifiers {
            hybrid: true,
            paper: true,
            material_gate: true,
            ..Modifiers::NONE
        },
        carries_opacity: false,
        needs: Needs::NONE,
        taa_jitter: TaaJitter::Halton,
        description: "subpixel reconstruction (Chajdas et al.): one shaded sample, four geometric subsamples, eq. 1",
    },
    TechniqueInfo {
        technique: Technique::SraaRt,
        name: "sraa-rt",
        grammar: "sraa-rt",
        family: Family::Sraa,
        claims: &[
            EdgeClass::Silhouette,
            EdgeClass::Crease,
            EdgeClass::Shadow,
            EdgeClass::Reflection,
        ],
        modifiers: Modifiers {
            hybrid: true,
            paper: true,
            material_gate: true,
            temporal: true,
            ..Modifiers::NONE
        },
        carries_opacity: false,
        needs: Needs {
            sdf_subpixel_geometry: true,
            ..Needs::NONE
        },
        taa_jitter: TaaJitter::SubsampleRotation,
        description: "SRAA for ray tracing: plus shadow-gated weights (eq. 2) and secondary shading on secondary geometry (§3.3)",
    },
    TechniqueInfo {
        technique: Technique::Ctss,
        name: "ctss",
        grammar: "ctss, ctss+edges",
        family: Family::Ctss,
        claims: &[EdgeClass::Silhouette],
        modifiers: Modifiers {
            paper: true,
            delayed: true,
            edges: true,
            temporal: true,
            ..Modifiers::NONE
        },
        carries_opacity: true,
        needs: Needs::NONE,
        taa_jitter: TaaJitter::Halton,
        description: "cone-traced supersampling: hit groups and a 32-bit visibility mask, traced to full occlusion",
    },
    TechniqueInfo {
        technique: Technique::CtssR,
        name: "ctss-r",
        grammar: "ctss-r",
        family: Family::Ctss,
        claims: &[EdgeClass::Silhouette],
        modifiers: Modifiers {
            paper: true,
            delayed: true,
            ..Modifiers::NONE
        },
        carries_opacity: true,
        needs: Needs::NONE,
        taa_jitter: TaaJitter::Halton,
        description: "CTSS-R: cone tracing that stops at the first hard hit",
    },
    TechniqueInfo {
        technique: Technique::SsaaCtss,
        name: "ssaa+ctss",
        grammar: "ssaaN+ctss",
        family: Family::Ctss,
        claims: SUPERSAMPLING_CLAIMS,
        modifiers: Modifiers {
            samples: true,
            paper: true,
            delayed: true,
            ..Modifiers::NONE
        },
        carries_opacity: true,
        needs: Needs {
            sdf_supersampling: true,
            ..Needs::NONE
        },
        taa_jitter: TaaJitter::Halton,
        description: "N×N supersampling with a cone traced per sample (CTSS §4.2)",
    },
    TechniqueInfo {
        technique: Technique::Fxaa,
        name: "fxaa",
        grammar: "fxaa",
        family: Family::PostProcess,
        claims: POST_PROCESS_CLAIMS,
        modifiers: Modifiers {
            hybrid: true,
            ..Modifiers::NONE
        },
        carries_opacity: true,
        needs: Needs::NONE,
        taa_jitter: TaaJitter::Halton,
        description: "FXAA 3.11 over the NoAA frame (the post-process baseline)",
    },
];

/// The registry entry of `technique`.
pub fn info(technique: Technique) -> &'static TechniqueInfo {
    TECHNIQUES
        .iter()
        .find(|i| i.technique == technique)
        .unwrap_or(&TECHNIQUES[0])
}

/// The methods of the default comparison, by the names [`Method`](crate::method::Method) parses
/// and prints, in table order: the one list the report, the CLI's help and
/// the backend contract's checks read. Every other accepted name is an
/// `ssaaN`/`ssaaN+ctss` with another `N`, a `-hybrid` variant of another
/// triangle method (`sraa+mat-hybrid`), a `-delayed` variant of a CTSS
/// method, or a `-paper` variant of one (`ctss-r-paper`,
/// `ctss+edges-paper`, `ssaa4+ctss-paper`, `ctss-delayed-paper`).
pub const METHOD_NAMES: [&str; 28] = [
    "noaa",
    "ssaa2",
    "ssaa4",
    "ssaa16",
    "sraa",
    "sraa-rt",
    "sraa+mat",
    "sraa-rt+mat",
    "sraa-paper",
    "sraa-rt-paper",
    "sraa-paper+mat",
    "sraa-rt-paper+mat",
    "noaa-hybrid",
    "ssaa2-hybrid",
    "ssaa4-hybrid",
    "ssaa16-hybrid",
    "sraa-hybrid",
    "sraa-rt-hybrid",
    "sraa-paper-hybrid",
    "sraa-rt-paper-hybrid",
    "ctss",
    "ctss-paper",
    "ctss-delayed",
    "ctss+edges",
    "ctss-r",
    "ssaa4+ctss",
    "fxaa",
    "fxaa-hybrid",
];

/// Suffix of the paper's preset (`sraa-paper`, `ctss-paper`).
pub(crate) const PAPER: &str = "-paper";
/// Suffix of the SRAA material gate (`sraa+mat`).
pub(crate) const MATERIAL_GATE: &str = "+mat";
/// Suffix of CTSS delayed shading (`ctss-delayed`).
pub(crate) const DELAYED: &str = "-delayed";
/// Suffix of CTSS hit-group subdivision (`ctss+edges`).
pub(crate) const EDGES: &str = "+edges";
/// Suffix of rasterised primary visibility (`sraa-rt-hybrid`), before
/// `+taa`.
pub(crate) const HYBRID: &str = "-hybrid";
/// Suffix of a method under temporal antialiasing (`sraa-rt+taa`), always
/// last.
pub(crate) const TAA_SUFFIX: &str = "+taa";
/// NoAA under temporal antialiasing: plain TAA.
pub(crate) const TAA: &str = "taa";
/// Prefix of the supersampled names (`ssaa16`, `ssaa4+ctss`).
pub(crate) const SSAA_PREFIX: &str = "ssaa";
/// Suffix of cone tracing per supersample (`ssaa4+ctss`).
pub(crate) const CTSS_SUFFIX: &str = "+ctss";

/// Every method name the parser accepts, as one sentence (for errors and
/// help): the grammars of [`TECHNIQUES`] and their modifiers.
pub fn grammar() -> String {
    let bases: Vec<&str> = TECHNIQUES.iter().map(|t| t.grammar).collect();
    // A technique's plain name: the first of its grammar's alternatives
    // (split at a comma outside brackets: `ssaaN (N in 2, 4, …)` is one).
    let plain = |t: &TechniqueInfo| {
        let mut depth = 0i32;
        let b = t.grammar.as_bytes();
        let cut = (0..b.len()).find(|&i| {
            match b[i] {
                b'(' => depth += 1,
                b')' => depth -= 1,
                _ => {}
            }
            depth == 0 && b[i] == b',' && b.get(i + 1) == Some(&b' ')
        });
        &t.grammar[..cut.unwrap_or(b.len())]
    };
    let with = |pick: fn(&Modifiers) -> bool, suffix: &str| -> Vec<String> {
        TECHNIQUES
            .iter()
            .filter(|t| pick(&t.modifiers))
            .map(|t| format!("{}{suffix}", plain(t)))
            .collect()
    };
    let gated = with(|m| m.material_gate, "");
    format!(
        "{}; the SRAA paper's preset {} and the material gate {}, both as {}{PAPER}{MATERIAL_GATE}; \
         {} optionally with {DELAYED} (not ctss{EDGES}); any of these CTSS names optionally with {PAPER} last; \
         rasterised primary visibility on triangle scenes as {HYBRID} after any of {} (before +taa); \
         temporal antialiasing as {TAA}, or {} after any other of their names",
        bases.join(", "),
        with(|m| m.material_gate, PAPER).join(", "),
        with(|m| m.material_gate, MATERIAL_GATE).join(", "),
        gated.first().map_or("", String::as_str),
        with(|m| m.delayed, "").join(", "),
        with(|m| m.hybrid, "").join(", "),
        with(|m| m.temporal && !m.samples, TAA_SUFFIX)
            .into_iter()
            .filter(|n| !n.starts_with("noaa"))
            .collect::<Vec<_>>()
            .join(", "),
    )
}

/// What [`UnsupportedReason::CpuOnly`](crate::UnsupportedReason::CpuOnly)
/// names when a backend lacks sphere-traced subpixel geometry
/// ([`Needs::sdf_subpixel_geometry`]); the CPU and wgpu backends have it.
pub const SDF_SUBPIXEL_GEOMETRY: &str = "sraa-rt on SDF scenes";

/// The method `subcone render` uses when none is named.
pub const DEFAULT_METHOD: &str = "sraa-rt";

/// The CLI's `--method` help: the grammar, the default comparison, then one
/// line per technique.
pub fn method_help() -> String {
    let mut s = format!(
        "The antialiasing method: {}.\n\nThe report's default comparison: {}.\n",
        grammar(),
        METHOD_NAMES.join(", ")
    );
    for t in &TECHNIQUES {
        s.push_str(&format!("\n{}: {}", t.grammar, t.description));
    }
    s
}

/// The SDF methods that render semi-transparent materials, for refusals:
/// the techniques that carry opacity, without their modifiers.
pub fn opacity_methods() -> String {
    let names: Vec<String> = TECHNIQUES
        .iter()
        .filter(|t| t.carries_opacity)
        .filter(|t| t.family != Family::PostProcess)
        // The first alternative, without its note: `ssaaN`, `ctss`.
        .filter_map(|t| t.grammar.split([',', ' ']).next())
        .map(str::to_string)
        .collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => names.join(""),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_entry_per_technique_in_order() {
        assert_eq!(TECHNIQUES.len(), Technique::ALL.len());
        for (i, t) in TECHNIQUES.iter().zip(Technique::ALL) {
            assert_eq!(i.technique, t);
            assert_eq!(info(t).technique, t);
        }
    }

    #[test]
    fn grammar_names_every_technique() {
        let g = grammar();
        for t in &TECHNIQUES {
            assert!(g.contains(t.grammar), "{g} lacks {}", t.grammar);
        }
    }
}
