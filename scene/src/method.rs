//! Antialiasing methods: a kernel [`Technique`], its preset and its
//! modifiers, built only in combinations that mean something.
//!
//! A [`Method`] is parsed from and displayed as the names of the
//! [`registry`] (`sraa-rt-paper+mat`, `ctss-delayed`,
//! `ssaa4+ctss`); built in code, every modifier is a method that checks it
//! applies and returns a typed [`MethodError`] where it does not. Settings
//! that belong to the method (cone coverage, visibility k) are checked the
//! same way, so the CLI and a library caller get the same checks.
//!
//! ```
//! use subcone_kernels::passes::Technique;
//! use subcone_scene::method::{Method, MethodError, Preset};
//!
//! let m = Method::new(Technique::SraaRt).with_preset(Preset::Paper)?.with_material_gate()?;
//! assert_eq!(m.to_string(), "sraa-rt-paper+mat");
//! assert_eq!("sraa-rt-paper+mat".parse::<Method>()?, m);
//! // A combination that means nothing is refused.
//! assert!(matches!(
//!     Method::new(Technique::NoAa).with_material_gate(),
//!     Err(MethodError::Modifier { .. })
//! ));
//! assert!(Method::new(Technique::Ctss).with_visibility_k(0).is_err());
//! # Ok::<(), MethodError>(())
//! ```

use std::fmt;
use std::str::FromStr;

use subcone_kernels::ctss::CtssParams;
use subcone_kernels::passes::Technique;
use subcone_kernels::sraa::SraaParams;

use crate::camera::Camera;

use crate::registry::{
    self, info, EdgeClass, CTSS_SUFFIX, DELAYED, EDGES, HYBRID, MATERIAL_GATE, PAPER, SSAA_PREFIX,
    TAA, TAA_SUFFIX,
};
pub use crate::registry::{METHOD_NAMES, SSAA_COUNTS, SSAA_DIAGONAL};

/// Which parameters a method runs with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Preset {
    /// This project's tuned parameters ([`SraaParams::TUNED`], the CTSS
    /// defaults of [`subcone_kernels::ctss`]).
    #[default]
    Tuned,
    /// The paper's: [`SraaParams::PAPER`] for the SRAA family, the paper's
    /// hit groups, masks and cone
    /// ([`CtssParams::paper`](subcone_kernels::ctss::CtssParams::paper),
    /// cone coverage 1) for the CTSS family. Named with a `-paper` suffix.
    Paper,
}

/// A method that cannot be built: an unknown name, a modifier that does not
/// apply to the technique, or a setting outside its domain.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MethodError {
    /// The name does not parse.
    #[error("unknown method {0:?}: expected {grammar}", grammar = registry::grammar())]
    Unknown(String),
    /// A modifier does not apply to the method.
    #[error("{method} cannot take {modifier}: {why}")]
    Modifier {
        /// The method as built so far.
        method: String,
        /// The modifier (`+mat`, `-delayed`, …).
        modifier: &'static str,
        /// Why not.
        why: &'static str,
    },
    /// A cone coverage that is not positive and finite.
    #[error("cone coverage {0} must be positive and finite")]
    ConeCoverage(f32),
    /// A visibility threshold outside `1..=32`.
    #[error("visibility k {0} must be in 1..=32")]
    VisibilityK(u32),
    /// A sample count `ssaaN` does not accept.
    #[error("{0} samples per pixel: expected one of 4, 9, 16, 64, 256")]
    Samples(u32),
}

/// The error of [`Method::from_str`] (kept under its old name).
pub type ParseMethodError = MethodError;

/// A method: the technique, its preset, its modifiers and its settings.
/// Fields are private: every value was built through a check.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Method {
    technique: Technique,
    preset: Preset,
    /// Samples per pixel side (SSAA, SSAA+CTSS); 1 otherwise.
    side: u32,
    material_gate: bool,
    delayed_shading: bool,
    split_groups: bool,
    cone_coverage: f32,
    visibility_k: u32,
    temporal: bool,
    hybrid: bool,
    /// `ssaa2`: of the 2×2 grid (`side` 2), only the diagonal samples.
    diagonal: bool,
}

impl Method {
    /// `technique` with the tuned preset and no modifier. `ssaa` gets 16
    /// samples (`ssaa16`), `ssaa+ctss` 4 (`ssaa4+ctss`); cone-traced
    /// techniques the tuned cone coverage
    /// ([`CONE_COVERAGE`](subcone_kernels::ctss::CONE_COVERAGE)).
    pub const fn new(technique: Technique) -> Self {
        let side = match technique {
            Technique::Ssaa => 4,
            Technique::SsaaCtss => 2,
            _ => 1,
        };
        Method {
            technique,
            preset: Preset::Tuned,
            side,
            material_gate: false,
            delayed_shading: false,
            split_groups: false,
            cone_coverage: if technique.is_cone_traced() {
                subcone_kernels::ctss::CONE_COVERAGE
            } else {
                1.0
            },
            visibility_k: 32,
            temporal: false,
            hybrid: false,
            diagonal: false,
        }
    }

    /// `technique` with the tuned preset under temporal antialiasing
    /// (`taa` for NoAA, `sraa-rt+taa`, `ctss+taa`), as a constant;
    /// [`Method::with_taa`] checks at run time. Panics (at compile time in a
    /// `const`) for a technique without `+taa`.
    pub const fn temporal(technique: Technique) -> Self {
        // The registry's `Modifiers::temporal`, spelled out for a `const`
        // (`temporal_agrees_with_the_registry` checks the two agree).
        match technique {
            Technique::NoAa | Technique::SraaRt | Technique::Ctss => Method {
                temporal: true,
                ..Method::new(technique)
            },
            _ => panic!("only noaa, sraa-rt and ctss run under TAA"),
        }
    }

    /// `ssaaN` on a regular `side × side` grid, so `N = side²`:
    /// `Method::ssaa_grid(4)` is `ssaa16`. Any side of at least 1 (a side
    /// whose square is not in [`SSAA_COUNTS`] prints a name that does not
    /// parse back); [`Method::ssaa`] takes a named count.
    pub const fn ssaa_grid(side: u32) -> Self {
        Method {
            side: if side == 0 { 1 } else { side },
            ..Method::new(Technique::Ssaa)
        }
    }

    /// `ssaaN`, `N` one of [`SSAA_COUNTS`], or 2 ([`Method::SSAA2`]).
    pub fn ssaa(samples: u32) -> Result<Self, MethodError> {
        if samples == SSAA_DIAGONAL {
            return Ok(Method::SSAA2);
        }
        Ok(Method::ssaa_grid(side_of(samples)?))
    }

    /// `ssaa2`: two samples per pixel on the diagonal of the 2×2 grid, at
    /// (¼, ¼) and (¾, ¾) of the pixel, box-filtered (the 2-sample rotated
    /// grid of 2× MSAA, Direct3D's standard pattern), so that the SSAA
    /// family has a member between NoAA and `ssaa4` in cost and error.
    /// Triangle scenes only: on SDF scenes, and on a backend without it
    /// ([`Capabilities::diagonal_ssaa`](crate::backend::Capabilities::diagonal_ssaa)),
    /// it is refused, never rendered as its 2×2 grid.
    pub const SSAA2: Method = Method {
        side: 2,
        diagonal: true,
        ..Method::new(Technique::Ssaa)
    };

    /// Whether the supersampling takes only the diagonal of its
    /// `side × side` grid ([`Method::SSAA2`]).
    pub const fn ssaa_diagonal(&self) -> bool {
        self.diagonal
    }

    /// `ssaaN+ctss`, `N` one of [`SSAA_COUNTS`].
    pub fn ssaa_ctss(samples: u32) -> Result<Self, MethodError> {
        Ok(Method {
            side: side_of(samples)?,
            ..Method::new(Technique::SsaaCtss)
        })
    }

    fn refuse(&self, modifier: &'static str, why: &'static str) -> MethodError {
        MethodError::Modifier {
            method: self.to_string(),
            modifier,
            why,
        }
    }

    /// The same method with `preset`. The paper's preset exists for the SRAA
    /// and CTSS families; it sets a cone-traced method's coverage to the
    /// paper's 1.
    pub fn with_preset(self, preset: Preset) -> Result<Self, MethodError> {
        if preset == Preset::Paper {
            if !info(self.technique).modifiers.paper {
                return Err(
                    self.refuse(PAPER, "only SRAA and CTSS methods have the paper's preset")
                );
            }
            if self.preset == Preset::Paper {
                return Err(self.refuse(PAPER, "it is already the paper's preset"));
            }
        }
        let cone_coverage = match (preset, self.technique.is_cone_traced()) {
            (Preset::Paper, true) => 1.0,
            (Preset::Tuned, true) if self.preset == Preset::Paper => {
                subcone_kernels::ctss::CONE_COVERAGE
            }
            _ => self.cone_coverage,
        };
        Ok(Method {
            preset,
            cone_coverage,
            ..self
        })
    }

    /// The SRAA material gate (`+mat`,
    /// `subcone_kernels::sraa::material_gated_weight`): edges between
    /// differently coloured patches of one surface (§4.1, Fig. 6) are
    /// resolved too. SRAA and SRAA-RT only.
    pub fn with_material_gate(self) -> Result<Self, MethodError> {
        if !info(self.technique).modifiers.material_gate {
            return Err(self.refuse(
                MATERIAL_GATE,
                "the material gate gates SRAA's reconstruction",
            ));
        }
        Ok(Method {
            material_gate: true,
            ..self
        })
    }

    /// Delayed shading (`-delayed`, CTSS §5.1, a variant the authors name but
    /// did not implement): every cone's coverage is traced first, recording
    /// its hit-group samples, then the recorded samples are shaded in a
    /// batch. The image is the same (eq. 6 adds the same terms in the same
    /// order); only the order of the work changes. Cone-traced methods
    /// without hit-group subdivision.
    pub fn with_delayed_shading(self) -> Result<Self, MethodError> {
        if !info(self.technique).modifiers.delayed {
            return Err(self.refuse(DELAYED, "delayed shading orders the work of cone tracing"));
        }
        if self.split_groups {
            // Delayed shading records one sample per hit group; split groups
            // shade several.
            return Err(self.refuse(DELAYED, "split hit groups shade several samples per group"));
        }
        Ok(Method {
            delayed_shading: true,
            ..self
        })
    }

    /// Hit-group subdivision at internal edges (`ctss+edges`, CTSS §5.3).
    /// CTSS only, without delayed shading.
    pub fn with_split_groups(self) -> Result<Self, MethodError> {
        if !info(self.technique).modifiers.edges {
            return Err(self.refuse(EDGES, "only ctss subdivides its hit groups"));
        }
        if self.delayed_shading {
            return Err(self.refuse(EDGES, "delayed shading records one sample per hit group"));
        }
        Ok(Method {
            split_groups: true,
            ..self
        })
    }

    /// The cone coverage multiplier (CTSS §5.1): 1 is the paper's cone
    /// through the pixel's corners. Positive and finite; cone-traced methods
    /// only.
    pub fn with_cone_coverage(self, coverage: f32) -> Result<Self, MethodError> {
        if !self.technique.is_cone_traced() {
            return Err(self.refuse("a cone coverage", "only cone-traced methods trace cones"));
        }
        if !(coverage > 0.0 && coverage.is_finite()) {
            return Err(MethodError::ConeCoverage(coverage));
        }
        Ok(Method {
            cone_coverage: coverage,
            ..self
        })
    }

    /// The visibility threshold k (CTSS §5.1): the trace stops once `k` of
    /// the mask's 32 bits are covered. In `1..=32`; cone-traced methods only.
    pub fn with_visibility_k(self, k: u32) -> Result<Self, MethodError> {
        if !self.technique.is_cone_traced() {
            return Err(self.refuse(
                "a visibility k",
                "only cone-traced methods have a visibility mask",
            ));
        }
        if !(1..=32).contains(&k) {
            return Err(MethodError::VisibilityK(k));
        }
        Ok(Method {
            visibility_k: k,
            ..self
        })
    }

    /// The method under temporal antialiasing (`+taa`,
    /// [`crate::temporal`]): each frame jittered, accumulated into a
    /// history by `subcone_kernels::taa`. NoAA, SRAA-RT and CTSS.
    pub fn with_taa(self) -> Result<Self, MethodError> {
        if !info(self.technique).modifiers.temporal {
            return Err(self.refuse(TAA_SUFFIX, "only noaa, sraa-rt and ctss run under TAA"));
        }
        if self.temporal {
            return Err(self.refuse(TAA_SUFFIX, "it already runs under TAA"));
        }
        Ok(Method {
            temporal: true,
            ..self
        })
    }

    /// The method with rasterised primary visibility (`-hybrid`, SRAA §3.1
    /// and §4.2): on triangle scenes every primary sample (the pixel
    /// centre, SSAA's grid, SRAA's shaded sample and subsamples) finds its
    /// triangle by rasterisation, and the hit on it is the tracer's; shadow,
    /// reflection and ambient-occlusion rays stay rays. SDF scenes have no
    /// triangles to rasterise: a backend traces them as the method without
    /// it. NoAA, SSAA, SRAA, SRAA-RT and FXAA.
    pub fn with_hybrid(self) -> Result<Self, MethodError> {
        if !info(self.technique).modifiers.hybrid {
            return Err(self.refuse(
                HYBRID,
                "only the triangle methods (noaa, ssaaN, sraa, sraa-rt, fxaa) rasterise",
            ));
        }
        if self.hybrid {
            return Err(self.refuse(HYBRID, "it is already hybrid"));
        }
        Ok(Method {
            hybrid: true,
            ..self
        })
    }

    /// Whether primary visibility is rasterised (`-hybrid`).
    pub const fn is_hybrid(&self) -> bool {
        self.hybrid
    }

    /// The method with its primary visibility traced: itself without
    /// `-hybrid`.
    pub const fn traced(&self) -> Self {
        Method {
            hybrid: false,
            ..*self
        }
    }

    /// Whether the method runs under temporal antialiasing (`+taa`): it
    /// renders a sequence ([`crate::temporal::Taa`]), not one frame.
    pub const fn is_temporal(&self) -> bool {
        self.temporal
    }

    /// The method one frame of its sequence renders: itself without `+taa`.
    pub const fn single_frame(&self) -> Self {
        Method {
            temporal: false,
            ..*self
        }
    }

    /// What decides the passes.
    pub const fn technique(&self) -> Technique {
        self.technique
    }

    /// The preset.
    pub const fn preset(&self) -> Preset {
        self.preset
    }

    /// Whether this is the paper's preset (`-paper`).
    pub fn is_paper(&self) -> bool {
        self.preset == Preset::Paper
    }

    /// The SRAA weight parameters of the preset.
    pub fn sraa(&self) -> SraaParams {
        match self.preset {
            Preset::Tuned => SraaParams::TUNED,
            Preset::Paper => SraaParams::PAPER,
        }
    }

    /// CTSS: the paper's hit groups, masks and cone
    /// ([`CtssParams::paper`](subcone_kernels::ctss::CtssParams::paper)).
    pub fn ctss_paper(&self) -> bool {
        self.technique.is_cone_traced() && self.is_paper()
    }

    /// Samples per pixel side (`ssaa16` → 4); 1 without supersampling.
    pub const fn ssaa_side(&self) -> u32 {
        self.side
    }

    /// Samples per pixel of the supersampling (1 without supersampling):
    /// the grid's, or its diagonal's ([`Method::SSAA2`]).
    pub const fn supersamples(&self) -> u32 {
        if self.diagonal {
            self.side
        } else {
            self.side * self.side
        }
    }

    /// The cone coverage (1 for methods that trace no cone).
    pub const fn cone_coverage(&self) -> f32 {
        self.cone_coverage
    }

    /// The visibility threshold k (32 for methods that trace no cone).
    pub const fn visibility_k(&self) -> u32 {
        self.visibility_k
    }

    /// Whether shading is delayed (`-delayed`).
    pub const fn delayed_shading(&self) -> bool {
        self.delayed_shading
    }

    /// Whether hit groups are subdivided at internal edges (`ctss+edges`).
    pub const fn split_groups(&self) -> bool {
        self.split_groups
    }

    /// Whether the SRAA reconstruction is gated by albedo (`+mat`).
    pub const fn gates_material(&self) -> bool {
        self.material_gate
    }

    /// `tan θ` of the cone of one of this method's samples in a frame
    /// `height` pixels high through `camera` (CTSS eq. 3, §3.1): the pixel's
    /// cone at the method's [`cone_coverage`](Self::cone_coverage), narrowed
    /// by the samples per side, so that each supersample's cone covers its
    /// own subpixel. The one place a coverage becomes `tan θ`.
    pub fn cone_tan_theta(&self, camera: &Camera, height: u32) -> f32 {
        camera.cone_tan_theta(height, self.cone_coverage) / self.side.max(1) as f32
    }

    /// The CTSS parameters of this method for a frame `height` pixels high
    /// through `camera`, marching `[0, max_distance]` in at most `max_steps`
    /// steps: [`cone_tan_theta`](Self::cone_tan_theta), CTSS-R's relaxed
    /// stop (§4), the visibility threshold, hit-group subdivision and the
    /// paper's behaviour. Every backend builds its
    /// [`CtssParams`] here (sphere tracing reads the same struct).
    pub fn ctss_params(
        &self,
        camera: &Camera,
        height: u32,
        max_distance: f32,
        max_steps: u32,
    ) -> CtssParams {
        CtssParams::new(self.cone_tan_theta(camera, height))
            .with_range(0.0, max_distance)
            .with_max_steps(max_steps)
            .relaxed(self.technique == Technique::CtssR)
            .with_visibility_k(self.visibility_k)
            .with_split_groups(self.split_groups)
            .paper(self.ctss_paper())
    }

    /// The edge classes the method claims to antialias: its technique's
    /// ([`registry::TechniqueInfo::claims`]), plus texture edges with the
    /// material gate and creases with hit-group subdivision.
    pub fn claims(&self) -> Vec<EdgeClass> {
        let mut c = info(self.technique).claims.to_vec();
        if self.material_gate {
            c.push(EdgeClass::Texture);
        }
        if self.split_groups {
            c.push(EdgeClass::Crease);
        }
        if self.temporal {
            // Accumulating jittered frames supersamples whatever the frame
            // shows.
            c.extend_from_slice(registry::SUPERSAMPLING_CLAIMS);
        }
        c.sort();
        c.dedup();
        c
    }
}

impl Default for Method {
    fn default() -> Self {
        Method::new(Technique::NoAa)
    }
}

fn side_of(samples: u32) -> Result<u32, MethodError> {
    if SSAA_COUNTS.contains(&samples) {
        Ok((samples as f64).sqrt() as u32)
    } else {
        Err(MethodError::Samples(samples))
    }
}

impl Method {
    /// The name, written as the registry spells it.
    fn write_name(&self, f: &mut impl fmt::Write) -> fmt::Result {
        let i = info(self.technique);
        if i.modifiers.samples {
            write!(f, "{SSAA_PREFIX}{}", self.supersamples())?;
            if self.technique == Technique::SsaaCtss {
                f.write_str(CTSS_SUFFIX)?;
            }
        } else if self.temporal && self.technique == Technique::NoAa {
            return f.write_str(TAA);
        } else {
            f.write_str(i.name)?;
        }
        if self.split_groups {
            f.write_str(EDGES)?;
        }
        if self.delayed_shading {
            f.write_str(DELAYED)?;
        }
        if self.is_paper() {
            f.write_str(PAPER)?;
        }
        if self.material_gate {
            f.write_str(MATERIAL_GATE)?;
        }
        if self.hybrid {
            f.write_str(HYBRID)?;
        }
        if self.temporal {
            f.write_str(TAA_SUFFIX)?;
        }
        Ok(())
    }
}

/// The method's name; width and alignment pad it (`{:<12}`) as they pad a
/// string.
impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut name = String::new();
        self.write_name(&mut name)?;
        f.pad(&name)
    }
}

/// The technique and sample count of a name without modifiers.
fn parse_base(base: &str) -> Option<Method> {
    if let Some(rest) = base.strip_prefix(SSAA_PREFIX) {
        return match rest.strip_suffix(CTSS_SUFFIX) {
            Some(n) => Method::ssaa_ctss(n.parse().ok()?).ok(),
            None => Method::ssaa(rest.parse().ok()?).ok(),
        };
    }
    let (base, edges) = match base.strip_suffix(EDGES) {
        Some(b) => (b, true),
        None => (base, false),
    };
    let t = registry::TECHNIQUES
        .iter()
        .find(|t| !t.modifiers.samples && t.name == base)?;
    let m = Method::new(t.technique);
    if edges {
        m.with_split_groups().ok()
    } else {
        Some(m)
    }
}

impl FromStr for Method {
    type Err = MethodError;

    /// Parses the registry's grammar, case-insensitively and trimmed: a base
    /// name, then `-delayed`, then `-paper`, then `+mat`, then `+taa`, each
    /// where it applies (`ctss-delayed-paper`, `sraa-rt-paper+mat`,
    /// `sraa-rt+taa`); `taa` is NoAA under TAA.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        let unknown = || MethodError::Unknown(s.to_string());
        if lower == TAA {
            return Ok(Method::temporal(Technique::NoAa));
        }
        let (name, temporal) = match lower.strip_suffix(TAA_SUFFIX) {
            Some(r) if r != "noaa" => (r, true),
            _ => (lower.as_str(), false),
        };
        let (name, hybrid) = match name.strip_suffix(HYBRID) {
            Some(r) => (r, true),
            None => (name, false),
        };
        let (rest, mat) = match name.strip_suffix(MATERIAL_GATE) {
            Some(r) => (r, true),
            None => (name, false),
        };
        let (rest, paper) = match rest.strip_suffix(PAPER) {
            Some(r) => (r, true),
            None => (rest, false),
        };
        let (base, delayed) = match rest.strip_suffix(DELAYED) {
            Some(r) => (r, true),
            None => (rest, false),
        };
        let mut m = parse_base(base).ok_or_else(unknown)?;
        if delayed {
            m = m.with_delayed_shading().map_err(|_| unknown())?;
        }
        if paper {
            m = m.with_preset(Preset::Paper).map_err(|_| unknown())?;
        }
        if mat {
            m = m.with_material_gate().map_err(|_| unknown())?;
        }
        if hybrid {
            m = m.with_hybrid().map_err(|_| unknown())?;
        }
        if temporal {
            m = m.with_taa().map_err(|_| unknown())?;
        }
        Ok(m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_listed_name_parses_and_prints_back() {
        for name in METHOD_NAMES {
            let m: Method = name.parse().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(m.to_string(), name);
        }
        for name in [
            "ctss-r-paper",
            "ctss+edges-paper",
            "ssaa4+ctss-paper",
            "ctss-delayed-paper",
            "ctss-r-delayed-paper",
        ] {
            let m: Method = name.parse().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(m.ctss_paper() && m.cone_coverage() == 1.0, "{name}");
            assert_eq!(m.to_string(), name);
        }
        for name in [
            "noaa-hybrid",
            "ssaa16-hybrid",
            "sraa-rt-paper+mat-hybrid",
            "sraa-hybrid",
            "fxaa-hybrid",
            "sraa-rt-hybrid+taa",
        ] {
            let m: Method = name.parse().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(m.is_hybrid() && !m.traced().is_hybrid(), "{name}");
            assert_eq!(m.to_string(), name);
            assert_eq!(m.traced().with_hybrid(), Ok(m));
        }
        for bad in [
            "ctss-paper-paper",
            "noaa-paper",
            "fxaa-paper",
            "ctss-paper-delayed",
            "sraa+mat-paper",
            "sraa-rt+mat+mat",
            "ctss-r+edges",
            "ssaa4+ctss+edges",
            "ctss-hybrid",
            "noaa-hybrid-hybrid",
            "sraa-hybrid+mat",
            "sraa-rt+taa-hybrid",
        ] {
            assert!(bad.parse::<Method>().is_err(), "{bad}");
        }
        let m: Method = "ctss".parse().unwrap();
        assert!(!m.ctss_paper() && m.cone_coverage() == subcone_kernels::ctss::CONE_COVERAGE);
        let mut sorted = METHOD_NAMES.to_vec();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), METHOD_NAMES.len(), "a name is listed twice");
    }

    #[test]
    fn temporal_agrees_with_the_registry() {
        for t in Technique::ALL {
            let allowed = info(t).modifiers.temporal;
            assert_eq!(Method::new(t).with_taa().is_ok(), allowed, "{t:?}");
            if allowed {
                let m = Method::temporal(t);
                assert_eq!(Method::new(t).with_taa(), Ok(m));
                assert!(m.is_temporal() && !m.single_frame().is_temporal());
                assert_eq!(m.to_string().parse::<Method>(), Ok(m));
            }
        }
        assert_eq!(Method::temporal(Technique::NoAa).to_string(), "taa");
        assert_eq!(
            Method::temporal(Technique::SraaRt).to_string(),
            "sraa-rt+taa"
        );
        assert_eq!(Method::temporal(Technique::Ctss).to_string(), "ctss+taa");
        let m: Method = "sraa-rt-paper+mat+taa".parse().unwrap();
        assert!(m.is_temporal() && m.is_paper() && m.gates_material());
        assert_eq!(m.to_string(), "sraa-rt-paper+mat+taa");
        for bad in [
            "noaa+taa",
            "taa+taa",
            "ssaa4+taa",
            "fxaa+taa",
            "ctss+taa+taa",
            "sraa+taa",
        ] {
            assert!(bad.parse::<Method>().is_err(), "{bad}");
        }
        assert!(Method::temporal(Technique::Ctss)
            .claims()
            .contains(&EdgeClass::Shadow));
    }

    #[test]
    fn settings_are_checked_by_the_method() {
        let ctss = Method::new(Technique::Ctss);
        assert_eq!(ctss.with_cone_coverage(2.0).unwrap().cone_coverage(), 2.0);
        for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(matches!(
                ctss.with_cone_coverage(bad),
                Err(MethodError::ConeCoverage(_))
            ));
        }
        assert_eq!(ctss.with_visibility_k(16).unwrap().visibility_k(), 16);
        assert_eq!(ctss.with_visibility_k(0), Err(MethodError::VisibilityK(0)));
        assert_eq!(
            ctss.with_visibility_k(33),
            Err(MethodError::VisibilityK(33))
        );
        let noaa = Method::new(Technique::NoAa);
        assert!(matches!(
            noaa.with_cone_coverage(1.0),
            Err(MethodError::Modifier { .. })
        ));
        assert!(matches!(
            noaa.with_visibility_k(32),
            Err(MethodError::Modifier { .. })
        ));
        // The paper's preset resets the coverage to 1, the tuned one back.
        let paper = ctss.with_preset(Preset::Paper).unwrap();
        assert_eq!(paper.cone_coverage(), 1.0);
        assert_eq!(paper.with_preset(Preset::Tuned).unwrap(), ctss);
        assert_eq!(Method::ssaa(5), Err(MethodError::Samples(5)));
    }
}
