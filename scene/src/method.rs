//! Antialiasing methods: a kernel [`Technique`] with its parameters.

use std::fmt;
use std::str::FromStr;

use subcone_kernels::passes::Technique;
use subcone_kernels::sraa::SraaParams;

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
    /// CTSS cone coverage multiplier (§5.1).
    pub cone_coverage: f32,
    /// CTSS visibility threshold k (§5.1).
    pub visibility_k: u32,
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
            sraa: SraaParams::PAPER,
            cone_coverage: 1.0,
            visibility_k: 32,
        }
    }

    /// `ssaaN` with `N = side²`.
    pub fn ssaa(side: u32) -> Self {
        Method {
            ssaa_side: side.max(1),
            ..Method::new(Technique::Ssaa)
        }
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
        match self.technique {
            Technique::NoAa => write!(f, "noaa"),
            Technique::Ssaa => write!(f, "ssaa{}", self.supersamples()),
            Technique::Sraa => write!(f, "sraa"),
            Technique::SraaRt => write!(f, "sraa-rt"),
            Technique::Ctss => write!(f, "ctss"),
            Technique::CtssR => write!(f, "ctss-r"),
            Technique::SsaaCtss => write!(f, "ssaa{}+ctss", self.supersamples()),
            Technique::Fxaa => write!(f, "fxaa"),
        }
    }
}

/// A method name that does not parse.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown method {0:?}: expected noaa, ssaaN (N in 4, 9, 16, 64, 256), sraa, sraa-rt, ctss, ctss-r, ssaaN+ctss or fxaa")]
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
        Ok(match lower.as_str() {
            "noaa" => Method::new(Technique::NoAa),
            "sraa" => Method::new(Technique::Sraa),
            "sraa-rt" => Method::new(Technique::SraaRt),
            "ctss" => Method::new(Technique::Ctss),
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
                        Method::ssaa(parse_ssaa(rest).ok_or_else(err)?)
                    }
                } else {
                    return Err(err());
                }
            }
        })
    }
}
