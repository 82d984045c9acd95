//! The methods the report's sections single out (the SRAA Table 1 sweep,
//! the ambient-occlusion sweep, the cost targets, the verdict lines), as
//! typed methods: their names come from the registry
//! ([`subcone_scene::registry`]) through `Display`, never from a literal.

use subcone_kernels::passes::Technique;
use subcone_scene::Method;

/// One sample per pixel: the baseline of every ratio and verdict.
pub const NOAA: Method = Method::new(Technique::NoAa);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The names the report's sections and `results.csv` rows used before
    /// the registry: renaming a method is a change to the report's format.
    #[test]
    fn names_are_the_reports() {
        let names = [
            (NOAA, "noaa"),
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
        ];
        for (m, name) in names {
            assert_eq!(m.to_string(), name);
            assert_eq!(name.parse::<Method>().unwrap(), m);
        }
    }
}
