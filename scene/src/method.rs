//! Antialiasing methods: a kernel [`Technique`] with its parameters.

use std::fmt;
use std::str::FromStr;

use subcone_kernels::passes::Technique;
use subcone_kernels::sraa::SraaParams;

/// The methods of the default comparison, by the names [`Method`] parses
/// and prints, in table order: the one list the report, the CLI's help and
/// the backend contract's checks read. Every other accepted name is an
/// `ssaaN`/`ssaaN+ctss` with another `N`, a `-delayed` variant of a CTSS
/// method, or a `-paper` variant of one (`ctss-r-paper`,
/// `ctss+edges-paper`, `ssaa4+ctss-paper`, `ctss-delayed-paper`).
pub const METHOD_NAMES: [&str; 18] = [
    "noaa",
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
    "ctss",
    "ctss-paper",
    "ctss-delayed",
    "ctss+edges",
    "ctss-r",
    "ssaa4+ctss",
    "fxaa",
];

/// Sample counts `ssaaN` accepts: squares, so the grid is regular.
pub const SSAA_COUNTS: [u32; 5] = [4, 9, 16, 64, 256];

/// A method: the technique and the parameters that do not decide passes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Method {
    /// What decides the passes.
    pub technique: Technique,
    /// Samples per pixel side for SSAA (`ssaa16` → 4); 1 otherwise.
    pub ssaa_side: u32,
    /// SRAA weight parameters.
    pub sraa: SraaParams,
    /// CTSS cone coverage multiplier (§5.1): 1 is the paper's cone through
    /// the pixel's corners. The CTSS methods default to
    /// [`CONE_COVERAGE`](subcone_kernels::ctss::CONE_COVERAGE), their
    /// `-paper` variants to 1.
    pub cone_coverage: f32,
    /// CTSS: the paper's hit groups, masks and cone
    /// ([`CtssParams::paper`](subcone_kernels::ctss::CtssParams::paper),
    /// `cone_coverage` 1); named with a `-paper` suffix (`ctss-paper`).
    pub ctss_paper: bool,
    /// CTSS visibility threshold k (§5.1).
    pub visibility_k: u32,
    /// Delayed shading (CTSS §5.1, a variant the authors name but did not
    /// implement): trace every cone's coverage first, recording its hit-group
    /// samples, then shade the recorded samples in a batch; otherwise each
    /// sample is shaded as soon as its group closes (ASAP). The image is the
    /// same (eq. 6 adds the same terms in the same order); only the order of
    /// the work changes. Only the cone-traced techniques read it; named with a
    /// `-delayed` suffix (`ctss-delayed`).
    pub delayed_shading: bool,
    /// CTSS: subdivide hit groups at internal edges (§5.3, `ctss+edges`).
    pub split_groups: bool,
    /// SRAA and SRAA-RT: gate the reconstruction by albedo as well
    /// (`sraa+mat`, `sraa-rt+mat`; `subcone_kernels::sraa::material_gated_weight`),
    /// so edges between differently coloured patches of one surface (§4.1,
    /// Fig. 6) are resolved. Adds an albedo per shaded sample and per
    /// geometric subsample; only changes the image where albedo varies
    /// (textures, patterned or several materials). Ignored by other techniques.
    pub material_aware: bool,
}

impl Method {
    /// A method with default parameters.
    pub fn new(technique: Technique) -> Self {
        let ssaa_side = match technique {
            Technique::Ssaa => 4,
            Technique::SsaaCtss => 2,
            _ => 1,
        };
        Method {
            technique,
            ssaa_side,
            sraa: SraaParams::TUNED,
            cone_coverage: if technique.is_cone_traced() {
                subcone_kernels::ctss::CONE_COVERAGE
            } else {
                1.0
            },
            ctss_paper: false,
            visibility_k: 32,
            delayed_shading: false,
            split_groups: false,
            material_aware: false,
        }
    }

    /// `ssaaN` on a regular `side × side` grid, so `N = side²`:
    /// `Method::ssaa_grid(4)` is `ssaa16`.
    pub fn ssaa_grid(side: u32) -> Self {
        Method {
            ssaa_side: side.max(1),
            ..Method::new(Technique::Ssaa)
        }
    }

    /// `technique` with the paper's SRAA preset ([`SraaParams::PAPER`]):
    /// `sraa-paper`, `sraa-rt-paper`.
    pub fn paper(technique: Technique) -> Self {
        Method {
            sraa: SraaParams::PAPER,
            ..Method::new(technique)
        }
    }

    /// The paper's CTSS ([`ctss_paper`](Self::ctss_paper), coverage 1) of a
    /// cone-traced method; other methods unchanged.
    pub fn ctss_paper(self) -> Self {
        if !self.technique.is_cone_traced() {
            return self;
        }
        Method {
            ctss_paper: true,
            cone_coverage: 1.0,
            ..self
        }
    }

    /// `sraa+mat` or `sraa-rt+mat`: `technique` with the material gate.
    pub fn material_aware(technique: Technique) -> Self {
        Method {
            material_aware: technique.is_subpixel_reconstruction(),
            ..Method::new(technique)
        }
    }

    /// Whether the SRAA reconstruction is gated by albedo (`+mat`).
    pub fn gates_material(&self) -> bool {
        self.material_aware && self.technique.is_subpixel_reconstruction()
    }

    /// Samples per pixel of the supersampling grid (1 without supersampling).
    pub fn supersamples(&self) -> u32 {
        match self.technique {
            Technique::Ssaa | Technique::SsaaCtss => self.ssaa_side * self.ssaa_side,
            _ => 1,
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let delayed = self.delayed_shading && self.technique.is_cone_traced();
        let suffix = if delayed { "-delayed" } else { "" };
        match self.technique {
            Technique::NoAa => write!(f, "noaa"),
            Technique::Ssaa => write!(f, "ssaa{}", self.supersamples()),
            Technique::Sraa => write!(f, "sraa"),
            Technique::SraaRt => write!(f, "sraa-rt"),
            Technique::Ctss if self.split_groups => write!(f, "ctss+edges{suffix}"),
            Technique::Ctss => write!(f, "ctss{suffix}"),
            Technique::CtssR => write!(f, "ctss-r{suffix}"),
            Technique::SsaaCtss => write!(f, "ssaa{}+ctss{suffix}", self.supersamples()),
            Technique::Fxaa => write!(f, "fxaa"),
            // A technique added to the kernels before this crate names it.
            other => write!(f, "{}", format!("{other:?}").to_ascii_lowercase()),
        }?;
        if self.technique.is_cone_traced() && self.ctss_paper {
            write!(f, "-paper")?;
        }
        if self.technique.is_subpixel_reconstruction() && self.sraa == SraaParams::PAPER {
            write!(f, "-paper")?;
        }
        if self.gates_material() {
            write!(f, "+mat")?;
        }
        Ok(())
    }
}

/// A method name that does not parse.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown method {0:?}: expected noaa, ssaaN (N in 4, 9, 16, 64, 256), sraa, sraa-rt, sraa+mat, sraa-rt+mat, sraa-paper, sraa-rt-paper, sraa-paper+mat, sraa-rt-paper+mat, ctss, ctss+edges, ctss-r, ssaaN+ctss or fxaa; ctss, ctss-r and ssaaN+ctss optionally with -delayed; any of these CTSS names optionally with -paper last")]
pub struct ParseMethodError(pub String);

fn parse_ssaa(n: &str) -> Option<u32> {
    let n: u32 = n.parse().ok()?;
    SSAA_COUNTS.contains(&n).then(|| (n as f64).sqrt() as u32)
}

impl FromStr for Method {
    type Err = ParseMethodError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        let err = || ParseMethodError(s.to_string());
        // CTSS: any cone-traced name, then `-paper`.
        if let Some(base) = lower.strip_suffix("-paper") {
            if let Ok(m) = base.parse::<Method>() {
                if m.technique.is_cone_traced() && !m.ctss_paper {
                    return Ok(m.ctss_paper());
                }
            }
        }
        if let Some(base) = lower.strip_suffix("-delayed") {
            let m: Method = base.parse().map_err(|_| err())?;
            // Delayed shading records one sample per hit group; split groups
            // (`ctss+edges`) shade several, so the two do not combine.
            if !m.technique.is_cone_traced()
                || base.ends_with("-delayed")
                || m.split_groups
                || m.ctss_paper
            {
                return Err(err());
            }
            return Ok(Method {
                delayed_shading: true,
                ..m
            });
        }
        // SRAA: a base, then `-paper` (the paper's preset), then `+mat`.
        let (sraa_base, mat) = match lower.strip_suffix("+mat") {
            Some(b) => (b, true),
            None => (lower.as_str(), false),
        };
        let (sraa_base, paper) = match sraa_base.strip_suffix("-paper") {
            Some(b) => (b, true),
            None => (sraa_base, false),
        };
        let sraa = match sraa_base {
            "sraa" => Some(Technique::Sraa),
            "sraa-rt" => Some(Technique::SraaRt),
            _ => None,
        };
        if let Some(t) = sraa {
            let m = if mat {
                Method::material_aware(t)
            } else {
                Method::new(t)
            };
            return Ok(if paper {
                Method {
                    sraa: SraaParams::PAPER,
                    ..m
                }
            } else {
                m
            });
        }
        Ok(match lower.as_str() {
            "noaa" => Method::new(Technique::NoAa),
            "ctss" => Method::new(Technique::Ctss),
            "ctss+edges" => Method {
                split_groups: true,
                ..Method::new(Technique::Ctss)
            },
            "ctss-r" => Method::new(Technique::CtssR),
            "fxaa" => Method::new(Technique::Fxaa),
            other => {
                if let Some(rest) = other.strip_prefix("ssaa") {
                    if let Some(n) = rest.strip_suffix("+ctss") {
                        Method {
                            ssaa_side: parse_ssaa(n).ok_or_else(err)?,
                            ..Method::new(Technique::SsaaCtss)
                        }
                    } else {
                        Method::ssaa_grid(parse_ssaa(rest).ok_or_else(err)?)
                    }
                } else {
                    return Err(err());
                }
            }
        })
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
            assert!(m.ctss_paper && m.cone_coverage == 1.0, "{name}");
            assert_eq!(m.to_string(), name);
        }
        for bad in [
            "ctss-paper-paper",
            "noaa-paper",
            "fxaa-paper",
            "ctss-paper-delayed",
        ] {
            assert!(bad.parse::<Method>().is_err(), "{bad}");
        }
        let m: Method = "ctss".parse().unwrap();
        assert!(!m.ctss_paper && m.cone_coverage == subcone_kernels::ctss::CONE_COVERAGE);
        let mut sorted = METHOD_NAMES.to_vec();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), METHOD_NAMES.len(), "a name is listed twice");
    }
}
