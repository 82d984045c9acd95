//! The methods the report's sections single out (the SRAA Table 1 sweep,
//! the ambient-occlusion sweep, the cost targets, the verdict lines), as
//! typed methods: their names come from the registry
//! ([`subcone_scene::registry`]) through `Display`, never from a literal.
//!
//! The `-hybrid` methods (primary visibility rasterised, SRAA §3.1 and
//! §4.2) are built by [`hybrid`] in functions: the modifier is checked at
//! run time ([`Method::with_hybrid`]).

use subcone_kernels::passes::Technique;
use subcone_scene::method::Preset;
use subcone_scene::Method;

/// One sample per pixel: the baseline of every ratio and verdict.
pub const NOAA: Method = Method::new(Technique::NoAa);
/// Two samples per pixel, the 2×2 grid's diagonal: the SSAA between NoAA
/// and `ssaa4`, so that SRAA has an SSAA neighbour on either side in error.
pub const SSAA2: Method = Method::SSAA2;
/// 2×2 supersampling.
pub const SSAA4: Method = Method::ssaa_grid(2);
/// 4×4 supersampling (SRAA's comparison, Fig. 3).
pub const SSAA16: Method = Method::ssaa_grid(4);
/// Plain SRAA.
pub const SRAA: Method = Method::new(Technique::Sraa);
/// SRAA for ray tracing.
pub const SRAA_RT: Method = Method::new(Technique::SraaRt);
/// CTSS.
pub const CTSS: Method = Method::new(Technique::Ctss);
/// CTSS-R.
pub const CTSS_R: Method = Method::new(Technique::CtssR);
/// 2×2 supersampling with CTSS per sample.
pub const SSAA4_CTSS: Method = Method::new(Technique::SsaaCtss);
/// Temporal antialiasing (NoAA under TAA).
pub const TAA: Method = Method::temporal(Technique::NoAa);
/// SRAA for ray tracing under TAA.
pub const SRAA_RT_TAA: Method = Method::temporal(Technique::SraaRt);
/// CTSS under TAA.
pub const CTSS_TAA: Method = Method::temporal(Technique::Ctss);
/// FXAA on the NoAA frame.
pub const FXAA: Method = Method::new(Technique::Fxaa);

/// `method` with rasterised primary visibility (`-hybrid`). Panics for a
/// method the modifier does not apply to: every caller passes one of
/// [`hybrid_bases`].
pub fn hybrid(method: Method) -> Method {
    method
        .with_hybrid()
        .unwrap_or_else(|e| panic!("{method} has no hybrid: {e}"))
}

/// `noaa-hybrid`: NoAA with its primary visibility rasterised.
pub fn noaa_hybrid() -> Method {
    hybrid(NOAA)
}

/// `ssaa2-hybrid`.
pub fn ssaa2_hybrid() -> Method {
    hybrid(SSAA2)
}

/// `ssaa4-hybrid`.
pub fn ssaa4_hybrid() -> Method {
    hybrid(SSAA4)
}

/// `ssaa16-hybrid`: the paper's 16x SSAA baseline of Fig. 3, rasterised.
pub fn ssaa16_hybrid() -> Method {
    hybrid(SSAA16)
}

/// `sraa-rt-hybrid`: SRAA as its paper runs it (§3.1, §4.2, Fig. 3), the
/// shaded sample and the geometric subsamples rasterised.
pub fn sraa_rt_hybrid() -> Method {
    hybrid(SRAA_RT)
}

/// A method with the paper's preset (`-paper`).
fn paper(method: Method) -> Method {
    method
        .with_preset(Preset::Paper)
        .unwrap_or_else(|e| panic!("{method} has no paper preset: {e}"))
}

/// The traced methods of the default comparison that have a `-hybrid`
/// twin there, in table order: the rows the report sets side by side
/// (traced against hybrid, per triangle scene).
pub fn hybrid_bases() -> [Method; 9] {
    [
        NOAA,
        SSAA2,
        SSAA4,
        SSAA16,
        SRAA,
        SRAA_RT,
        paper(SRAA),
        paper(SRAA_RT),
        FXAA,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names the report's sections and `results.csv` rows used before
    /// the registry: renaming a method is a change to the report's format.
    #[test]
    fn names_are_the_reports() {
        let names = [
            (NOAA, "noaa"),
            (SSAA2, "ssaa2"),
            (SSAA4, "ssaa4"),
            (SSAA16, "ssaa16"),
            (SRAA, "sraa"),
            (SRAA_RT, "sraa-rt"),
            (CTSS, "ctss"),
            (CTSS_R, "ctss-r"),
            (SSAA4_CTSS, "ssaa4+ctss"),
            (TAA, "taa"),
            (SRAA_RT_TAA, "sraa-rt+taa"),
            (CTSS_TAA, "ctss+taa"),
            (FXAA, "fxaa"),
            (noaa_hybrid(), "noaa-hybrid"),
            (ssaa4_hybrid(), "ssaa4-hybrid"),
            (ssaa16_hybrid(), "ssaa16-hybrid"),
            (sraa_rt_hybrid(), "sraa-rt-hybrid"),
        ];
        for (m, name) in names {
            assert_eq!(m.to_string(), name);
            assert_eq!(name.parse::<Method>().unwrap(), m);
        }
    }

    /// Every base's hybrid is a method of the default comparison, and so
    /// is the base: the traced-against-hybrid table has both rows.
    #[test]
    fn every_hybrid_base_has_its_hybrid_in_the_default_comparison() {
        let names = subcone_scene::method::METHOD_NAMES;
        for m in hybrid_bases() {
            assert!(!m.is_hybrid());
            assert!(names.contains(&m.to_string().as_str()), "{m}");
            let h = hybrid(m);
            assert!(h.is_hybrid() && h.traced() == m);
            assert!(names.contains(&h.to_string().as_str()), "{h}");
        }
        // And no hybrid of the default comparison is left out.
        let hybrids = names
            .iter()
            .filter(|n| n.parse::<Method>().unwrap().is_hybrid())
            .count();
        assert_eq!(hybrids, hybrid_bases().len());
    }
}
