//! The methods the suite's cases single out, as typed methods: their names
//! come from the registry ([`subcone_scene::registry`]) through `Display`,
//! never from a literal. The default comparison, which the per-scene cases
//! run ([`crate::methods_for`]), is the registry's list,
//! [`default_methods`].
//!
//! The modifiers checked at run time (`-delayed`, `+edges`) are applied in
//! functions ([`delayed`], [`split_groups`]).

use subcone_kernels::passes::Technique;
use subcone_scene::method::METHOD_NAMES;
use subcone_scene::Method;

/// One sample per pixel.
pub const NOAA: Method = Method::new(Technique::NoAa);
/// 2×2 supersampling.
pub const SSAA4: Method = Method::ssaa_grid(2);
/// 4×4 supersampling.
pub const SSAA16: Method = Method::ssaa_grid(4);
/// 8×8 supersampling: the suite's high-sample reference
/// ([`REFERENCE_METHOD`](crate::REFERENCE_METHOD)).
pub const SSAA64: Method = Method::ssaa_grid(8);
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
/// FXAA on the NoAA frame.
pub const FXAA: Method = Method::new(Technique::Fxaa);

/// `method` with delayed shading (`-delayed`). Panics for a method the
/// modifier does not apply to: every caller passes a cone-traced one.
pub fn delayed(method: Method) -> Method {
    method
        .with_delayed_shading()
        .unwrap_or_else(|e| panic!("{method} has no delayed shading: {e}"))
}

/// `method` with its hit groups split at internal edges (`+edges`). Panics
/// for a method the modifier does not apply to: every caller passes CTSS.
pub fn split_groups(method: Method) -> Method {
    method
        .with_split_groups()
        .unwrap_or_else(|e| panic!("{method} does not split its hit groups: {e}"))
}

/// The default comparison, [`METHOD_NAMES`], as typed methods, in its order.
/// Panics on a name that does not parse: the registry's own tests hold that
/// every one does.
pub fn default_methods() -> Vec<Method> {
    METHOD_NAMES
        .iter()
        .map(|n| {
            n.parse()
                .unwrap_or_else(|e| panic!("METHOD_NAMES lists {n}: {e}"))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names the suite's cases, messages and failure images used
    /// before the methods were typed: the same cases run under the same
    /// names.
    #[test]
    fn names_are_the_suites() {
        let names = [
            (NOAA, "noaa"),
            (SSAA4, "ssaa4"),
            (SSAA16, "ssaa16"),
            (SSAA64, "ssaa64"),
            (SRAA, "sraa"),
            (SRAA_RT, "sraa-rt"),
            (CTSS, "ctss"),
            (CTSS_R, "ctss-r"),
            (SSAA4_CTSS, "ssaa4+ctss"),
            (FXAA, "fxaa"),
            (delayed(CTSS), "ctss-delayed"),
            (delayed(CTSS_R), "ctss-r-delayed"),
            (delayed(SSAA4_CTSS), "ssaa4+ctss-delayed"),
            (split_groups(CTSS), "ctss+edges"),
        ];
        for (m, name) in names {
            assert_eq!(m.to_string(), name);
            assert_eq!(name.parse::<Method>().expect(name), m);
        }
        let listed: Vec<String> = default_methods().iter().map(Method::to_string).collect();
        assert_eq!(listed, METHOD_NAMES);
    }
}
