//! Golden vectors for ports of the kernels: `subcone vectors --out DIR`.
//!
//! A backend written outside Rust (an HLSL, GLSL, CUDA or Metal port of the
//! kernels, a C++ engine) cannot run the kernel conformance suite; it can
//! check itself against data. [`write_all`] writes, for every pure kernel of
//! [`subcone_kernels`] that a port implements, a few thousand input/output
//! cases, one JSON file per kernel (`<kernel>.json`, see [`KERNELS`]). The
//! outputs are the Rust kernels'. The inputs are generated from a fixed seed
//! (mostly each kernel's domain, and a share of anything at all: 0, −0,
//! subnormals, ±∞, NaN, 1e±30, `f32::MAX`), followed by fixed grids of
//! extremes; two runs write byte-identical files.
//!
//! # File format
//!
//! Each file is one JSON object, laid out so that a C program can read it
//! line by line without a JSON library:
//!
//! ```text
//! {
//! "kernel": "cone_radius",
//! "signature": {"in": [{"name": "t", "type": "f32"}, {"name": "tan_theta", "type": "f32"}], "out": [{"name": "r_c", "type": "f32"}]},
//! "tolerance": {"kind": "ulps", "value": 2, "constant": "TOL_CONE"},
//! "non_finite": "…prose…",
//! "reference": "…prose…",
//! "count": 3372,
//! "cases": [
//! {"in": ["0x3f800000", "0x3a83126f"], "out": ["0x3a83126f"]},
//! …
//! {"in": ["0x7fc00000", "0x00000000"], "out": ["0x00000000"]}
//! ]
//! }
//! ```
//!
//! - The header fields come first, in this order, one per line:
//!   - `kernel`: the Rust kernel's name (the WGSL twin is `subcone_<kernel>`);
//!   - `signature`: the inputs and the outputs, in case order, each with a
//!     name (vectors are spread over components, `n.x`, `n.y`, `n.z`) and a
//!     type: `f32`, `u32` or `bool`;
//!   - `tolerance`: how far a port's output may be from the file's:
//!     `kind` `ulps` (at most `value` ulps apart), `abs` (`|a − b| ≤ value`,
//!     or at most 4 ulps apart) or `rel` (`|a − b| ≤ value · max(1, |a|,
//!     |b|)`); for every kind two NaNs agree, and a subnormal against a port's
//!     0 agrees (GPUs may flush subnormals). Integer and boolean outputs are
//!     compared exactly. `constant` names the constant of [`tolerance`] that
//!     states it, with its reason; it is the kernel conformance suite's;
//!   - `non_finite`: the kernel's documented contract for non-finite and
//!     out-of-domain input, as prose;
//!   - `reference`: the f64 reference the outputs are checked against, with
//!     its bound, or why there is none;
//!   - `count`: the number of cases.
//! - Then the line `"cases": [`, then **exactly one case per line**:
//!   `{"in": [...], "out": [...]}`, values in signature order, separated by
//!   `", "`, each line but the last ending in `,`. Every `f32` is a JSON
//!   string holding its IEEE 754 bit pattern as `0x` and 8 lowercase hex
//!   digits (`"0x3f800000"` is 1.0), so NaN (with its payload), ±∞, −0 and
//!   subnormals survive exactly; `u32` values are plain JSON numbers, `bool`
//!   values the numbers 0 and 1.
//! - Then the lines `]` and `}`.
//!
//! A C reader can take the lines starting with `{"in"`, and read each value
//! with `strtoul(p, &end, 0)` after skipping to the next digit (the `0x`
//! strings parse as hexadecimal, the plain numbers as decimal).
//!
//! NaN outputs: a port's NaN matches any NaN; the bit pattern is the Rust
//! kernel's.

mod ao;
mod cone;
mod fxaa;
mod grids;
mod mask;
mod rng;
mod sraa;
pub mod tolerance;
mod transparency;
mod words;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub use grids::{
    ao_grid_normals, AO_GRID_INDICES, AWKWARD_DEPTHS, AWKWARD_WEIGHT_PARAMS, SPECIALS,
};
use rng::Rng;
pub use tolerance::Tol;

/// The type of one input or output of a case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Type {
    /// An `f32`, written as its bit pattern, `"0x3f800000"`.
    F32,
    /// A `u32`, written as a JSON number.
    U32,
    /// A `bool`, written as the JSON number 0 or 1.
    Bool,
}

impl Type {
    /// The name in a file's `signature`.
    pub fn name(self) -> &'static str {
        match self {
            Type::F32 => "f32",
            Type::U32 => "u32",
            Type::Bool => "bool",
        }
    }
}

/// One named input or output.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Field {
    /// Its name (`n.x` for a vector's component).
    pub name: String,
    /// Its type.
    pub ty: Type,
}

/// Fields from a compact spec, `"t:f32 n:vec3 count:u32 si:bool"`: `vec2`
/// and `vec3` spread over components `.x`, `.y`, `.z` (and `vec4` `.w`);
/// `p:vec3*49` is `p0:vec3 p1:vec3 … p48:vec3`.
fn fields(spec: &str) -> Vec<Field> {
    let mut out = Vec::new();
    for item in spec.split_whitespace() {
        let (name, ty) = item.split_once(':').expect("name:type");
        if let Some((ty, n)) = ty.split_once('*') {
            let n: usize = n.parse().expect("repeat count");
            for k in 0..n {
                out.extend(fields(&format!("{name}{k}:{ty}")));
            }
            continue;
        }
        let field = |name: String, ty| Field { name, ty };
        match ty {
            "f32" => out.push(field(name.into(), Type::F32)),
            "u32" => out.push(field(name.into(), Type::U32)),
            "bool" => out.push(field(name.into(), Type::Bool)),
            "vec2" | "vec3" | "vec4" => {
                let n = ty[3..].parse::<usize>().expect("vector size");
                for c in &["x", "y", "z", "w"][..n] {
                    out.push(field(format!("{name}.{c}"), Type::F32));
                }
            }
            _ => panic!("unknown type {ty}"),
        }
    }
    out
}

/// One kernel's vectors: its signature, tolerance, contract, and how its
/// cases are generated and evaluated.
pub struct KernelVectors {
    /// The Rust kernel's name; the file is `<name>.json`.
    pub name: &'static str,
    /// The compact signature of the inputs (see the module docs).
    inputs: &'static str,
    /// The compact signature of the outputs.
    outputs: &'static str,
    /// The tolerance a port is held to.
    pub tolerance: Tol,
    /// The name of the [`tolerance`] constant that states it.
    pub tolerance_constant: &'static str,
    /// The kernel's contract for non-finite and out-of-domain input.
    pub non_finite: &'static str,
    /// The f64 reference, or why there is none.
    pub reference: &'static str,
    /// The Rust kernel on one case's input words (f32 bits, u32, bool as
    /// 0/1), returning its output words.
    pub eval: fn(&[u32]) -> Vec<u32>,
    /// The inputs, from a seeded generator.
    generate: fn(&mut Rng) -> Vec<Vec<u32>>,
}

impl KernelVectors {
    /// The inputs, in case order.
    pub fn inputs(&self) -> Vec<Field> {
        fields(self.inputs)
    }

    /// The outputs, in case order.
    pub fn outputs(&self) -> Vec<Field> {
        fields(self.outputs)
    }

    /// The file name, `<kernel>.json`.
    pub fn file_name(&self) -> String {
        format!("{}.json", self.name)
    }

    /// The cases: input words and the Rust kernel's output words.
    pub fn cases(&self) -> Vec<(Vec<u32>, Vec<u32>)> {
        // One seed per kernel, from its name: adding a kernel does not move
        // another's cases.
        let seed = self.name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
        });
        let mut rng = Rng(seed);
        let inputs = (self.generate)(&mut rng);
        let n_in = self.inputs().len();
        inputs
            .into_iter()
            .map(|input| {
                assert_eq!(input.len(), n_in, "{}: input width", self.name);
                let out = (self.eval)(&input);
                (input, out)
            })
            .collect()
    }

    /// The whole file, in the layout of the module docs.
    pub fn render(&self) -> String {
        let (inputs, outputs) = (self.inputs(), self.outputs());
        let cases = self.cases();
        let sig = |fs: &[Field]| {
            fs.iter()
                .map(|f| {
                    format!(
                        "{{\"name\": {}, \"type\": \"{}\"}}",
                        json_str(&f.name),
                        f.ty.name()
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        let value = match self.tolerance {
            Tol::Ulps(u) => u.to_string(),
            Tol::Abs(v) | Tol::Rel(v) => format!("{v:e}"),
        };
        let mut s = String::new();
        s.push_str("{\n");
        let _ = writeln!(s, "\"kernel\": {},", json_str(self.name));
        let _ = writeln!(
            s,
            "\"signature\": {{\"in\": [{}], \"out\": [{}]}},",
            sig(&inputs),
            sig(&outputs)
        );
        let _ = writeln!(
            s,
            "\"tolerance\": {{\"kind\": \"{}\", \"value\": {value}, \"constant\": \"{}\"}},",
            self.tolerance.kind(),
            self.tolerance_constant
        );
        let _ = writeln!(s, "\"non_finite\": {},", json_str(self.non_finite));
        let _ = writeln!(s, "\"reference\": {},", json_str(self.reference));
        let _ = writeln!(s, "\"count\": {},", cases.len());
        s.push_str("\"cases\": [\n");
        let words = |fs: &[Field], w: &[u32]| {
            assert_eq!(fs.len(), w.len(), "{}: case width", self.name);
            fs.iter()
                .zip(w)
                .map(|(f, &x)| match f.ty {
                    Type::F32 => format!("\"0x{x:08x}\""),
                    Type::U32 | Type::Bool => x.to_string(),
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        for (k, (i, o)) in cases.iter().enumerate() {
            let comma = if k + 1 < cases.len() { "," } else { "" };
            let _ = writeln!(
                s,
                "{{\"in\": [{}], \"out\": [{}]}}{comma}",
                words(&inputs, i),
                words(&outputs, o)
            );
        }
        s.push_str("]\n}\n");
        s
    }
}

/// A JSON string literal.
fn json_str(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Parse one case line of a file (`{"in": [...], "out": [...]}`, with or
/// without its trailing comma) into input and output words: `"0x…"` strings
/// as bit patterns, numbers as they are. `None` for any other line.
pub fn parse_case_line(line: &str) -> Option<(Vec<u32>, Vec<u32>)> {
    let line = line.trim().trim_end_matches(',');
    let rest = line.strip_prefix("{\"in\": [")?;
    let (ins, rest) = rest.split_once("], \"out\": [")?;
    let outs = rest.strip_suffix("]}")?;
    let words = |s: &str| -> Option<Vec<u32>> {
        if s.is_empty() {
            return Some(Vec::new());
        }
        s.split(", ")
            .map(|v| match v.strip_prefix("\"0x") {
                Some(h) => u32::from_str_radix(h.strip_suffix('"')?, 16).ok(),
                None => v.parse().ok(),
            })
            .collect()
    };
    Some((words(ins)?, words(outs)?))
}

/// Write every kernel's file into `dir` (created if missing); the paths
/// written, in [`KERNELS`] order.
pub fn write_all(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    KERNELS
        .iter()
        .map(|k| {
            let path = dir.join(k.file_name());
            std::fs::write(&path, k.render())?;
            Ok(path)
        })
        .collect()
}

const NO_REFERENCE: &str =
    "none: no f64 reference; the outputs are the Rust kernel's, which tests/vectors.rs re-reads and compares bit for bit.";

/// Every kernel with golden vectors, in the order [`write_all`] writes them.
pub const KERNELS: &[KernelVectors] = &[
    sraa::BILATERAL_WEIGHT,
    sraa::SHADOW_GATED_WEIGHT,
    sraa::RECONSTRUCTION_WEIGHT,
    sraa::ALBEDO_DIFFERENCE,
    sraa::MATERIAL_GATED_WEIGHT,
    sraa::RESOLVE_PIXEL,
    cone::CONE_TAN_THETA,
    cone::CONE_RADIUS,
    cone::CONE_OCCLUSION,
    cone::MIN_STEP,
    cone::ADVANCE,
    cone::BACKTRACE_CONE_ENTRY,
    cone::BACKTRACE_HARD_HIT,
    mask::PROJECT_NORMAL,
    mask::VISIBILITY_MASK,
    mask::NEEDS_NORMAL,
    mask::SAMPLE_WEIGHT,
    mask::AGGREGATE_RESOLVE,
    ao::AO_DIRECTION,
    ao::AO_FRACTION,
    fxaa::FXAA_ENCODE,
    fxaa::FXAA_PIXEL,
    transparency::CLAMP_ALPHA,
    transparency::REMAINING_AFTER,
    transparency::IS_OPAQUE,
    transparency::LEVEL_WEIGHT,
    transparency::TRANSPARENCY_ACCUMULATOR,
];
