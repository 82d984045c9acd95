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

pub mod tolerance;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use subcone_kernels::aggregate::{sample_weight, Aggregate, Weighting};
use subcone_kernels::ao::{ao_direction, ao_fraction};
use subcone_kernels::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, cone_tan_theta,
    min_step, PixelFootprint,
};
use subcone_kernels::fxaa::{fxaa_encode, fxaa_pixel, FxaaParams};
use subcone_kernels::mask::{
    needs_normal, project_normal, visibility_mask, MaskPlacement, FARTHEST_CENTRE,
};
use subcone_kernels::sraa::{
    albedo_difference, bilateral_weight, material_gated_weight, reconstruction_weight,
    resolve_pixel, shadow_gated_weight, DepthMetric, Geometry, SraaParams, WeightForm,
    ALBEDO_TOLERANCE,
};
use subcone_kernels::transparency::{
    clamp_alpha, is_opaque, level_weight, remaining_after, TransparencyAccumulator,
};

pub use tolerance::Tol;
use tolerance::*;

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

/// A deterministic generator (SplitMix64): the same seed, the same cases, on
/// every machine.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in `[0, n)`.
    fn below(&mut self, n: u32) -> u32 {
        (self.next() % n as u64) as u32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        let x = lo + (hi - lo) * self.unit();
        if x < hi {
            x
        } else {
            lo
        }
    }

    fn bits(&mut self) -> u32 {
        self.next() as u32
    }

    /// Values from every part of f32, as the conformance suite draws them:
    /// two thirds uniform over `[lo, hi)` (the kernel's domain), a ninth a
    /// special value ([`SPECIALS`]), two ninths any bits at all.
    fn any_f32(&mut self, lo: f32, hi: f32) -> f32 {
        match self.below(9) {
            0..=5 => self.range(lo, hi),
            6 => SPECIALS[self.below(SPECIALS.len() as u32) as usize],
            _ => f32::from_bits(self.bits()),
        }
    }

    /// Signed, log-uniform over 1e-3..1e3, every fifth a special.
    fn awkward(&mut self) -> f32 {
        if self.below(5) == 0 {
            SPECIALS[self.below(SPECIALS.len() as u32) as usize]
        } else {
            (self.unit() * 2.0 - 1.0) * 10f32.powf(self.unit() * 6.0 - 3.0)
        }
    }

    /// Mostly unit vectors, a ninth any vector (non-finite included).
    fn unit_vec(&mut self) -> Vec3 {
        if self.below(9) < 8 {
            let v = Vec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            v.try_normalize().unwrap_or(Vec3::Z)
        } else {
            Vec3::new(
                self.any_f32(-2.0, 2.0),
                self.any_f32(-2.0, 2.0),
                self.any_f32(-2.0, 2.0),
            )
        }
    }

    fn colour(&mut self, hi: f32) -> Vec3 {
        Vec3::new(
            self.any_f32(0.0, hi),
            self.any_f32(0.0, hi),
            self.any_f32(0.0, hi),
        )
    }

    fn pick<T: Copy>(&mut self, v: &[T]) -> T {
        v[self.below(v.len() as u32) as usize]
    }
}

/// The special values every generator mixes in: signed zeros, subnormals
/// (the smallest, and 1e-40), the smallest normal, 1e±30, ±1, ½, ±`f32::MAX`,
/// ±∞ and NaN.
pub const SPECIALS: [f32; 18] = [
    0.0,
    -0.0,
    1.4e-45,
    -1.4e-45,
    1e-40,
    f32::MIN_POSITIVE,
    1e-30,
    -1e-30,
    0.5,
    1.0,
    -1.0,
    1e30,
    -1e30,
    f32::MAX,
    f32::MIN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
];

/// The depths of the weight grids (here and in the conformance suite): equal,
/// close and double, 0, a subnormal, near `f32::MAX`, ∞, NaN and a miss-like
/// 1e6.
pub const AWKWARD_DEPTHS: [f32; 9] = [
    1.0,
    1.05,
    2.0,
    0.0,
    1e-40,
    3e38,
    f32::INFINITY,
    f32::NAN,
    1e6,
];

/// The parameter sets of the weight grids: both weight forms, both depth
/// metrics, and sigmas so large that every exponent is ~0.
pub const AWKWARD_WEIGHT_PARAMS: [SraaParams; 4] = [
    SraaParams::PAPER,
    SraaParams::CHAJDAS,
    SraaParams::PAPER.with_depth_metric(DepthMetric::Absolute),
    SraaParams::new(
        1e20,
        1e20,
        1.0,
        WeightForm::Product,
        DepthMetric::Relative,
        1,
    ),
];

/// The normals of the ambient-occlusion grids (here and in the conformance
/// suite): the signed axes, signed and unsigned zero, NaN, ∞, huge and tiny
/// vectors, and one unit vector off the axes.
pub fn ao_grid_normals() -> [Vec3; 13] {
    [
        Vec3::X,
        -Vec3::X,
        Vec3::Y,
        -Vec3::Y,
        Vec3::Z,
        -Vec3::Z,
        Vec3::new(0.0, 0.0, -0.0),
        Vec3::ZERO,
        Vec3::NAN,
        Vec3::new(f32::INFINITY, 0.0, 1.0),
        Vec3::splat(f32::MAX),
        Vec3::splat(1e-30),
        Vec3::new(0.6, 0.0, -0.8),
    ]
}

/// The (index, count) pairs of the ambient-occlusion grids: a zero count,
/// the first index of one and the last of 4, 64 and 256, indices beyond
/// their count (`u32::MAX` among them).
pub const AO_GRID_INDICES: [(u32, u32); 7] = [
    (0, 0),
    (0, 1),
    (3, 4),
    (63, 64),
    (255, 256),
    (9, 4),
    (u32::MAX, 16),
];

/// Generated cases per kernel, before its fixed grids.
const GENERATED: usize = 1024;

/// Input words, built up.
#[derive(Default)]
struct W(Vec<u32>);

impl W {
    fn f(mut self, x: f32) -> Self {
        self.0.push(x.to_bits());
        self
    }
    fn u(mut self, x: u32) -> Self {
        self.0.push(x);
        self
    }
    fn v(mut self, v: &[f32]) -> Self {
        self.0.extend(v.iter().map(|x| x.to_bits()));
        self
    }
    fn params(self, p: &SraaParams) -> Self {
        self.f(p.sigma_z)
            .f(p.sigma_n)
            .f(p.scale)
            .u(p.packed)
            .f(p.sigma_s)
            .u(p.shading)
    }
    fn geometry(self, g: &Geometry) -> Self {
        self.v(&g.normal.to_array()).f(g.depth)
    }
}

/// Input words, read back in order.
struct R<'a>(&'a [u32]);

impl R<'_> {
    fn u(&mut self) -> u32 {
        let (x, rest) = self.0.split_first().expect("input word");
        self.0 = rest;
        *x
    }
    fn f(&mut self) -> f32 {
        f32::from_bits(self.u())
    }
    fn b(&mut self) -> bool {
        self.u() != 0
    }
    fn v2(&mut self) -> Vec2 {
        Vec2::new(self.f(), self.f())
    }
    fn v3(&mut self) -> Vec3 {
        Vec3::new(self.f(), self.f(), self.f())
    }
    fn params(&mut self) -> SraaParams {
        SraaParams {
            sigma_z: self.f(),
            sigma_n: self.f(),
            scale: self.f(),
            packed: self.u(),
            sigma_s: self.f(),
            shading: self.u(),
            _pad: [0; 2],
        }
    }
    fn geometry(&mut self) -> Geometry {
        Geometry::new(self.v3(), self.f())
    }
}

fn out(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

const GEOMETRY_SIG: &str =
    "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32";

/// SRAA parameters as the conformance suite draws them: the presets, and
/// random sigmas, forms and depth metrics.
fn sraa_params(rng: &mut Rng) -> SraaParams {
    match rng.below(13) {
        0..=2 => SraaParams::PAPER,
        3..=5 => SraaParams::TUNED,
        6..=7 => SraaParams::CHAJDAS,
        8..=9 => SraaParams {
            sigma_s: rng.any_f32(0.0, 2.0),
            shading: rng.below(3),
            ..SraaParams::TUNED
        },
        10 => SraaParams::CHAJDAS.with_spatial(rng.any_f32(0.0, 2.0)),
        _ => SraaParams::new(
            rng.any_f32(0.0, 40.0),
            rng.any_f32(0.0, 2.0),
            10.0,
            if rng.below(2) == 0 {
                WeightForm::Product
            } else {
                WeightForm::ChajdasMax
            },
            if rng.below(2) == 0 {
                DepthMetric::Relative
            } else {
                DepthMetric::Absolute
            },
            1,
        ),
    }
}

fn geometry(rng: &mut Rng) -> Geometry {
    Geometry::new(rng.unit_vec(), rng.any_f32(0.0, 100.0))
}

/// The conformance suite's grid of awkward geometry: normals (NaN, zero,
/// opposite) against depths (0, subnormal, 3e38, ∞, NaN, a miss-like 1e6),
/// over four parameter sets (both forms, both metrics, huge sigmas).
fn weight_grid() -> Vec<(SraaParams, Geometry, Geometry)> {
    let nan = f32::NAN;
    let normals = [
        (Vec3::Z, Vec3::Z),
        (Vec3::Z, Vec3::new(0.0, 0.6, 0.8)),
        (Vec3::Z, Vec3::X),
        (Vec3::Z, -Vec3::Z),
        (Vec3::new(nan, 0.0, 1.0), Vec3::Z),
        (Vec3::ZERO, Vec3::Z),
    ];
    let mut cases = Vec::new();
    for (na, nb) in normals {
        for za in AWKWARD_DEPTHS {
            for zb in AWKWARD_DEPTHS {
                let p = AWKWARD_WEIGHT_PARAMS[cases.len() % AWKWARD_WEIGHT_PARAMS.len()];
                cases.push((p, Geometry::new(na, za), Geometry::new(nb, zb)));
            }
        }
    }
    cases
}

/// Generated weight cases and the grid, each with an index for the extra
/// inputs.
fn weight_cases(rng: &mut Rng) -> Vec<(SraaParams, Geometry, Geometry)> {
    let mut cases: Vec<_> = (0..GENERATED)
        .map(|_| (sraa_params(rng), geometry(rng), geometry(rng)))
        .collect();
    cases.extend(weight_grid());
    cases
}

/// Every pair of [`SPECIALS`].
fn special_pairs() -> impl Iterator<Item = (f32, f32)> {
    SPECIALS
        .iter()
        .flat_map(|&a| SPECIALS.iter().map(move |&b| (a, b)))
}

/// An albedo: mostly in `[0, 1]`, sometimes anything.
fn albedo(rng: &mut Rng) -> Vec3 {
    if rng.below(5) < 4 {
        Vec3::new(rng.unit(), rng.unit(), rng.unit())
    } else {
        rng.colour(1.0)
    }
}

/// A pair of albedos: equal, close (the difference straddles the default
/// tolerance) or independent.
fn albedo_pair(rng: &mut Rng) -> (Vec3, Vec3) {
    let a = albedo(rng);
    match rng.below(7) {
        0..=1 => (a, a),
        2..=4 => {
            let d = Vec3::new(
                rng.range(-0.2, 0.2),
                rng.range(-0.2, 0.2),
                rng.range(-0.2, 0.2),
            );
            (a, a + d)
        }
        _ => (a, albedo(rng)),
    }
}

/// The non-finite contract of the SRAA weights.
const WEIGHT_NON_FINITE: &str = "Domain: unit normals, depths in [0, inf], finite non-negative parameters. Returns a value in [0, 1], never NaN. A NaN anywhere gives 0 (the neighbour is excluded, never blended); two misses (depth = +inf) give 1 whatever their normals; non-unit normals are accepted (the cosine is saturated to [0, 1]); weights that underflow are 0.";

const WEIGHT_REFERENCE: &str = "kernels/tests/f64_reference.rs: eq. 1 in f64 (SraaParams::PAPER and CHAJDAS presets, unit normals, depths 1e-3..1e6), within 2e-6 absolute; not re-checked on these cases.";

const NO_REFERENCE: &str =
    "none: no f64 reference; the outputs are the Rust kernel's, which tests/vectors.rs re-reads and compares bit for bit.";

/// Every kernel with golden vectors, in the order [`write_all`] writes them.
pub const KERNELS: &[KernelVectors] = &[
    KernelVectors {
        name: "bilateral_weight",
        inputs: GEOMETRY_SIG,
        outputs: "w:f32",
        tolerance: TOL_WEIGHT,
        tolerance_constant: "TOL_WEIGHT",
        non_finite: WEIGHT_NON_FINITE,
        reference: WEIGHT_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
            out(&[bilateral_weight(&p, &gi, &gj)])
        },
        generate: |rng| {
            weight_cases(rng)
                .iter()
                .map(|(p, gi, gj)| W::default().params(p).geometry(gi).geometry(gj).0)
                .collect()
        },
    },
    KernelVectors {
        name: "shadow_gated_weight",
        inputs: "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32 si:bool sj:bool",
        outputs: "w:f32",
        tolerance: TOL_WEIGHT,
        tolerance_constant: "TOL_WEIGHT",
        non_finite: "Exactly 0 when si != sj (the gate of eq. 2, whatever the other inputs); otherwise bilateral_weight's contract: domain unit normals, depths in [0, inf], finite non-negative parameters; a value in [0, 1], never NaN; a NaN anywhere gives 0; two misses (depth = +inf) give 1.",
        reference: WEIGHT_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
            let (si, sj) = (r.b(), r.b());
            out(&[shadow_gated_weight(&p, &gi, &gj, si, sj)])
        },
        generate: |rng| {
            weight_cases(rng)
                .iter()
                .map(|(p, gi, gj)| {
                    let (si, sj) = (rng.below(2), rng.below(2));
                    W::default().params(p).geometry(gi).geometry(gj).u(si).u(sj).0
                })
                .collect()
        },
    },
    KernelVectors {
        name: "reconstruction_weight",
        inputs: "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32 distance2:f32",
        outputs: "w:f32",
        tolerance: TOL_WEIGHT,
        tolerance_constant: "TOL_WEIGHT",
        non_finite: "bilateral_weight times exp(-distance2/sigma_s^2) when sigma_s > 0. Domain: bilateral_weight's, and distance2 >= 0. With the spatial term on, a NaN or infinite distance2 gives 0; with it off (sigma_s <= 0 or NaN), distance2 is ignored and the result is bilateral_weight's, bit for bit. Always in [0, 1], never NaN.",
        reference: WEIGHT_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
            out(&[reconstruction_weight(&p, &gi, &gj, r.f())])
        },
        generate: |rng| {
            let d2s = [0.0f32, 0.156_25, 0.39, 1.2, 4.5, 1e-30, 3e38, f32::INFINITY];
            weight_cases(rng)
                .iter()
                .map(|(p, gi, gj)| {
                    let d2 = if rng.below(2) == 0 {
                        rng.pick(&d2s)
                    } else {
                        rng.any_f32(0.0, 5.0)
                    };
                    W::default().params(p).geometry(gi).geometry(gj).f(d2).0
                })
                .collect()
        },
    },
    KernelVectors {
        name: "albedo_difference",
        inputs: "a:vec3 b:vec3",
        outputs: "d:f32",
        tolerance: TOL_ALBEDO_DIFFERENCE,
        tolerance_constant: "TOL_ALBEDO_DIFFERENCE",
        non_finite: "max_c |sqrt(a_c) - sqrt(b_c)|. Domain: finite components, nominally in [0, 1]; negative components count as 0, components above 1 are compared as they are. A NaN or infinite component in either albedo gives +inf. The tolerance holds on components in [0, 4]; beyond, where the difference cancels, only the class (infinite or not) is compared by the conformance suite.",
        reference: "f64: max_c |sqrt(max(a_c, 0)) - sqrt(max(b_c, 0))| on finite components in [0, 4], within TOL_ALBEDO_DIFFERENCE (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            out(&[albedo_difference(r.v3(), r.v3())])
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    let (a, b) = albedo_pair(rng);
                    W::default().v(&a.to_array()).v(&b.to_array()).0
                })
                .collect();
            v.extend(special_pairs().map(|(a, b)| {
                W::default().v(&[a, 0.5, 0.25]).v(&[b, 0.5, 0.25]).0
            }));
            v
        },
    },
    KernelVectors {
        name: "material_gated_weight",
        inputs: "sigma_z:f32 sigma_n:f32 scale:f32 packed:u32 sigma_s:f32 shading:u32 gi.normal:vec3 gi.depth:f32 gj.normal:vec3 gj.depth:f32 ai:vec3 aj:vec3 tolerance:f32",
        outputs: "w:f32",
        tolerance: TOL_WEIGHT,
        tolerance_constant: "TOL_WEIGHT",
        non_finite: "bilateral_weight when albedo_difference(ai, aj) <= tolerance and is finite, else exactly 0. A non-finite albedo, or a NaN or negative tolerance, gates (weight 0); the result is always in [0, 1], never NaN. The gate's decision is exact, except where the albedo difference lies within MATERIAL_GATE_NEAR (1e-5) of the tolerance, where a few ulps of sqrt decide.",
        reference: WEIGHT_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let (p, gi, gj) = (r.params(), r.geometry(), r.geometry());
            let (ai, aj, t) = (r.v3(), r.v3(), r.f());
            out(&[material_gated_weight(&p, &gi, &gj, ai, aj, t)])
        },
        generate: |rng| {
            weight_cases(rng)
                .iter()
                .map(|(p, gi, gj)| {
                    let (ai, aj) = albedo_pair(rng);
                    let t = if rng.below(4) < 3 {
                        ALBEDO_TOLERANCE
                    } else {
                        rng.any_f32(0.0, 1.0)
                    };
                    W::default()
                        .params(p)
                        .geometry(gi)
                        .geometry(gj)
                        .v(&ai.to_array())
                        .v(&aj.to_array())
                        .f(t)
                        .0
                })
                .collect()
        },
    },
    KernelVectors {
        name: "resolve_pixel",
        inputs: "c0:vec3 c1:vec3 c2:vec3 c3:vec3",
        outputs: "c:vec3",
        tolerance: TOL_RESOLVE,
        tolerance_constant: "TOL_RESOLVE",
        non_finite: "The mean of the four subsample colours, each scaled by 1/n before summing. Domain: finite colours. A subsample with any non-finite component is dropped and the others are averaged; with none finite, returns black (0, 0, 0). Colours above 1e37 may overflow the sum in a port's order and are outside the compared contract.",
        reference: "f64: the mean of the finite subsamples, on components in [0, 4], within TOL_RESOLVE (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            let c = [r.v3(), r.v3(), r.v3(), r.v3()];
            out(&resolve_pixel(&c).to_array())
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    let mut w = W::default();
                    for _ in 0..4 {
                        w = w.v(&rng.colour(4.0).to_array());
                    }
                    w.0
                })
                .collect();
            for (k, s) in SPECIALS.iter().enumerate() {
                // One special in one channel of one subsample, then in all.
                let mut c = [[0.25f32, 0.5, 0.75]; 4];
                c[k % 4][k % 3] = *s;
                v.push(c.iter().fold(W::default(), |w, c| w.v(c)).0);
                v.push(W::default().v(&[*s; 12]).0);
            }
            v
        },
    },
    KernelVectors {
        name: "cone_tan_theta",
        inputs: "fov_y:f32 height:u32 coverage:f32 footprint:u32",
        outputs: "tan_theta:f32",
        tolerance: TOL_CONE_TAN_THETA,
        tolerance_constant: "TOL_CONE_TAN_THETA",
        non_finite: "coverage * r * 2 tan(fov_y/2) / height, r the footprint's radius in pixels (footprint 0: circumscribed, 1/sqrt(2); 1: balanced, 2/(2 + sqrt(2)); 2: inscribed, 1/2; other codes are not generated). Domain: fov_y in (0, pi), height >= 1, coverage > 0, all finite. Outside it (and where the result is not finite) returns 0.",
        reference: "f64: coverage * r * 2 tan(fov_y/2) / height on the domain, within TOL_CONE_TAN_THETA (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            let (fov, h, cov) = (r.f(), r.u(), r.f());
            let fp = match r.u() {
                1 => PixelFootprint::Balanced,
                2 => PixelFootprint::Inscribed,
                _ => PixelFootprint::Circumscribed,
            };
            out(&[cone_tan_theta(fov, h, cov, fp)])
        },
        generate: |rng| {
            let heights = [0u32, 1, 2, 480, 512, 1080, 2160, u32::MAX];
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    let h = if rng.below(4) == 0 {
                        rng.pick(&heights)
                    } else {
                        1 + rng.below(8192)
                    };
                    W::default()
                        .f(rng.any_f32(0.0, 3.2))
                        .u(h)
                        .f(rng.any_f32(0.0, 4.0))
                        .u(rng.below(3))
                        .0
                })
                .collect();
            v.extend(special_pairs().map(|(a, b)| W::default().f(a).u(512).f(b).u(0).0));
            v
        },
    },
    KernelVectors {
        name: "cone_radius",
        inputs: "t:f32 tan_theta:f32",
        outputs: "r_c:f32",
        tolerance: TOL_CONE,
        tolerance_constant: "TOL_CONE",
        non_finite: "t * tan_theta when both are > 0, else 0. Domain: t >= 0, tan_theta >= 0. Negative, zero or NaN inputs give 0 (a point); +inf propagates (inf * tan_theta).",
        reference: "f64: t * tan_theta rounded once, for t, tan_theta > 0 finite, within TOL_CONE (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            out(&[cone_radius(r.f(), r.f())])
        },
        generate: |rng| cone_pairs(rng, (0.0, 1e3), (0.0, 0.01)),
    },
    KernelVectors {
        name: "cone_occlusion",
        inputs: "d:f32 r_c:f32",
        outputs: "omega:f32",
        tolerance: TOL_OCCLUSION,
        tolerance_constant: "TOL_OCCLUSION",
        non_finite: "(1 - d/r_c)/2, clamped to [-1, 2]. Domain: d finite, r_c > 0 finite. r_c <= 0 or NaN: the limit, -1 for d > 0, 2 for d < 0, 0.5 for d = 0; d = +inf gives -1, d = -inf gives 2, d = NaN gives -1; r_c = +inf with finite d gives 0.5. Never NaN or infinite.",
        reference: "f64: (1 - d/r_c)/2 for d/r_c in [-3, 3], r_c > 0 finite, within 1e-6 absolute, the f64 bound of kernels/tests/f64_reference.rs (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            out(&[cone_occlusion(r.f(), r.f())])
        },
        generate: |rng| cone_pairs(rng, (-1.0, 1.0), (0.0, 10.0)),
    },
    KernelVectors {
        name: "min_step",
        inputs: "alpha:f32 r_c:f32",
        outputs: "s_min:f32",
        tolerance: TOL_CONE,
        tolerance_constant: "TOL_CONE",
        non_finite: "alpha * r_c. Domain: alpha in (0, 1], r_c >= 0. NaN or negative products give 0.",
        reference: "f64: alpha * r_c rounded once, for positive finite inputs, within TOL_CONE (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            out(&[min_step(r.f(), r.f())])
        },
        generate: |rng| cone_pairs(rng, (0.0, 1.0), (0.0, 10.0)),
    },
    KernelVectors {
        name: "advance",
        inputs: "t:f32 d:f32 alpha:f32 r_c:f32",
        outputs: "t_next:f32",
        tolerance: TOL_CONE,
        tolerance_constant: "TOL_CONE",
        non_finite: "t + max(d, alpha * r_c), promoted to the next float above t when the sum rounds back to t. Domain: finite t >= 0. A NaN d steps by alpha * r_c (then by one ulp); the result is > t for every finite t, and +inf only when the step is.",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            out(&[advance(r.f(), r.f(), r.f(), r.f())])
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    W::default()
                        .f(rng.any_f32(0.0, 1e3))
                        .f(rng.any_f32(-1.0, 1.0))
                        .f(rng.any_f32(0.0, 1.0))
                        .f(rng.any_f32(0.0, 10.0))
                        .0
                })
                .collect();
            for _ in 0..512 {
                let t = rng.awkward();
                let d = rng.awkward();
                let rc = rng.awkward().abs();
                v.push(W::default().f(t).f(d).f(0.5).f(rc).0);
            }
            v.extend(special_pairs().map(|(t, d)| W::default().f(t).f(d).f(0.5).f(1e-3).0));
            v
        },
    },
    KernelVectors {
        name: "backtrace_cone_entry",
        inputs: "t_i:f32 tan_theta:f32",
        outputs: "t_s:f32",
        tolerance: TOL_CONE,
        tolerance_constant: "TOL_CONE",
        non_finite: "t_i / (1 + tan_theta) (eq. 9-10). Domain: t_i >= 0, tan_theta >= 0, finite. Returns a value in [0, t_i]; a NaN or negative tan_theta returns t_i, a NaN t_i returns 0.",
        reference: "f64: t_i / (1 + tan_theta) on the domain, within TOL_CONE (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            out(&[backtrace_cone_entry(r.f(), r.f())])
        },
        generate: |rng| cone_pairs(rng, (0.0, 1e3), (0.0, 0.01)),
    },
    KernelVectors {
        name: "backtrace_hard_hit",
        inputs: "t_prev:f32 d_prev:f32 t_i:f32",
        outputs: "t_s:f32",
        tolerance: TOL_CONE,
        tolerance_constant: "TOL_CONE",
        non_finite: "t_prev + d_prev (section 3.6), clamped to [t_prev, t_i]. Domain: t_prev <= t_i, d_prev >= 0. A non-Eikonal or negative d_prev cannot push the result past t_i or behind t_prev; a NaN d_prev returns t_prev.",
        reference: "f64: min(max(t_prev + d_prev, t_prev), t_i) rounded once, on finite inputs with t_prev <= t_i, within TOL_CONE (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            out(&[backtrace_hard_hit(r.f(), r.f(), r.f())])
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    let t = rng.any_f32(0.0, 1e3);
                    let d = rng.any_f32(-1.0, 1.0);
                    let rc = rng.any_f32(0.0, 10.0);
                    W::default().f(t).f(d).f(t + rc).0
                })
                .collect();
            for _ in 0..512 {
                let (t, d, ti) = (rng.awkward(), rng.awkward(), rng.awkward());
                v.push(W::default().f(t).f(d).f(ti).0);
            }
            v.extend(special_pairs().map(|(t, d)| W::default().f(t).f(d).f(1.0).0));
            v
        },
    },
    KernelVectors {
        name: "project_normal",
        inputs: "normal:vec3 right:vec3 up:vec3",
        outputs: "n_p:vec2",
        tolerance: TOL_PROJECT_NORMAL,
        tolerance_constant: "TOL_PROJECT_NORMAL",
        non_finite: "(n.right, n.up) with n = normal/|normal|, normalised after scaling by the largest component (so no square overflows). Domain: any finite non-zero normal; right, up orthonormal. A zero, NaN or infinite normal returns (0, 0).",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            out(&project_normal(r.v3(), r.v3(), r.v3()).to_array())
        },
        generate: |rng| {
            let frame = |n: Vec3, r: Vec3| {
                let up = r.cross(n).try_normalize().unwrap_or(Vec3::Y);
                W::default().v(&n.to_array()).v(&r.to_array()).v(&up.to_array()).0
            };
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    let (n, r) = (rng.unit_vec(), rng.unit_vec());
                    frame(n, r)
                })
                .collect();
            for (a, b) in special_pairs() {
                v.push(frame(Vec3::new(a, b, 0.5), Vec3::X));
            }
            v
        },
    },
    KernelVectors {
        name: "visibility_mask",
        inputs: "omega:f32 n_p:vec2 placement:u32",
        outputs: "mask:u32",
        tolerance: TOL_EXACT,
        tolerance_constant: "TOL_EXACT",
        non_finite: "The 32-cell mask of the half-plane (eq. 7-8) for occlusion omega and projected normal n_p; placement 0 derived, 1 the authors' code, 2 the paper's eq. 8 (other codes read as 0). Domain: omega in [-1, 2], |n_p| <= 1. A fronto-parallel surface (n_p = (0, 0)) gives all 32 bits when omega >= 0.5 and 0 otherwise; a NaN omega gives 0; |n_p| > 1 is treated as 1. Exact, except that a cell whose centre lies within MASK_NEAR (1e-5) of the mask's line (computed in f64) may differ, in at most 1 % of masks (MASK_NEAR_ROWS_PER_100).",
        reference: "kernels/tests/f64_reference.rs rasterises the same line in f64 (cells may differ only within MASK_NEAR of it); not re-checked on these cases.",
        eval: |w| {
            let mut r = R(w);
            let (omega, np, p) = (r.f(), r.v2(), r.u());
            vec![visibility_mask(omega, np, MaskPlacement::from_u32(p))]
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..3 * GENERATED / 2)
                .map(|i| {
                    let omega = if i % 50 == 0 {
                        rng.awkward()
                    } else {
                        rng.unit() * 1.4 - 0.2
                    };
                    let a = rng.unit() * std::f32::consts::TAU;
                    let len = if i % 3 == 0 { rng.unit() } else { 1.0 };
                    W::default()
                        .f(omega)
                        .f(a.cos() * len)
                        .f(a.sin() * len)
                        .u(rng.below(3))
                        .0
                })
                .collect();
            for (k, s) in SPECIALS.iter().enumerate() {
                for np in [[0.0, 0.0], [0.6, 0.8], [*s, 0.5]] {
                    for p in 0..3 {
                        v.push(W::default().f(*s).v(&np).u(p).0);
                        v.push(W::default().f(0.25 + k as f32 / 36.0).v(&np).u(p).0);
                    }
                }
            }
            v
        },
    },
    KernelVectors {
        name: "needs_normal",
        inputs: "omega:f32 placement:u32",
        outputs: "needs:bool",
        tolerance: TOL_EXACT,
        tolerance_constant: "TOL_EXACT",
        non_finite: "Whether visibility_mask depends on the projected normal at this occlusion: for placements 0 and 1, false when |1 - 2 omega| >= FARTHEST_CENTRE (the mask is then empty or full for every normal); always true for placement 2; false for a NaN omega. Exact, except where |1 - 2 omega| lies within NEEDS_NORMAL_NEAR (1e-5) of FARTHEST_CENTRE, where one rounding decides.",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let (omega, p) = (r.f(), r.u());
            vec![needs_normal(omega, MaskPlacement::from_u32(p)) as u32]
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| W::default().f(rng.any_f32(-0.2, 1.2)).u(rng.below(3)).0)
                .collect();
            // Around the thresholds, ω = (1 ± FARTHEST_CENTRE)/2.
            for sign in [-1.0f32, 1.0] {
                let edge = (1.0 + sign * FARTHEST_CENTRE) * 0.5;
                for k in -8i32..=8 {
                    let omega = edge + k as f32 * 1e-3;
                    for p in 0..3 {
                        v.push(W::default().f(omega).u(p).0);
                    }
                }
            }
            for s in SPECIALS {
                for p in 0..3 {
                    v.push(W::default().f(s).u(p).0);
                }
            }
            v
        },
    },
    KernelVectors {
        name: "sample_weight",
        inputs: "visible:u32 weighting:u32 min_weight:f32",
        outputs: "w:f32",
        tolerance: TOL_SAMPLE_WEIGHT,
        tolerance_constant: "TOL_SAMPLE_WEIGHT",
        non_finite: "weighting 1 (uniform): 1. Otherwise (0, and unknown codes): max(bitCount(visible)/32, min(min_weight, 1)) when min_weight > 0, else bitCount(visible)/32. Domain: min_weight in [0, 1]; NaN reads as 0.",
        reference: "exact: bitCount(visible)/32, or the clamped floor, or 1 (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            let (m, k, min_w) = (r.u(), r.u(), r.f());
            out(&[sample_weight(m, Weighting::from_u32(k), min_w)])
        },
        generate: |rng| {
            let floors = [0.0f32, 0.01];
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    let min_w = if rng.below(2) == 0 {
                        rng.pick(&floors)
                    } else {
                        rng.any_f32(0.0, 1.0)
                    };
                    W::default().u(rng.bits()).u(rng.below(3)).f(min_w).0
                })
                .collect();
            for b in 0..=32u32 {
                let m = if b == 32 { u32::MAX } else { (1u32 << b) - 1 };
                for min_w in [0.0, 0.01, f32::NAN, 2.0, -1.0] {
                    v.push(W::default().u(m).u(0).f(min_w).0);
                }
            }
            v
        },
    },
    KernelVectors {
        name: "aggregate_resolve",
        inputs: "mask0:u32 c0:vec3 mask1:u32 c1:vec3 mask2:u32 c2:vec3 mask3:u32 c3:vec3 background:vec3 bg_weight:f32 weighting:u32 min_weight:f32",
        outputs: "c:vec3",
        tolerance: TOL_AGGREGATE,
        tolerance_constant: "TOL_AGGREGATE",
        non_finite: "Eq. 6: for k = 0..4, w_k = sample_weight(mask_k, weighting, min_weight) and Aggregate::add(w_k, c_k); then Aggregate::resolve(background, bg_weight) = (sum w_k c_k + bg_weight * background) / (sum w_k + bg_weight). add clamps w to [0, 1] (NaN as 0) and skips a non-finite colour (which still counts as a sample). With no weight (or a total below NEGLIGIBLE_WEIGHT) the last finite colour is returned, or the background, or black; if the weighted sum overflows, the last colour too. The result lies in the convex hull of the colours and the background. The tolerance holds on radiances (finite, non-negative components below 1e30); outside, a port must return a finite colour.",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let samples = [
                (r.u(), r.v3()),
                (r.u(), r.v3()),
                (r.u(), r.v3()),
                (r.u(), r.v3()),
            ];
            let (bg, bgw, k, min_w) = (r.v3(), r.f(), r.u(), r.f());
            let mut agg = Aggregate::new();
            for (m, c) in samples {
                agg.add(sample_weight(m, Weighting::from_u32(k), min_w), c);
            }
            out(&agg.resolve(bg, bgw).to_array())
        },
        generate: |rng| {
            (0..GENERATED)
                .map(|_| {
                    let mut w = W::default();
                    for _ in 0..4 {
                        let m = match rng.below(4) {
                            0 => 0,
                            1 => u32::MAX,
                            _ => rng.bits(),
                        };
                        w = w.u(m).v(&rng.colour(4.0).to_array());
                    }
                    let min_w = if rng.below(2) == 0 { 0.0 } else { 0.01 };
                    w.v(&rng.colour(4.0).to_array())
                        .f(rng.any_f32(0.0, 1.0))
                        .u(rng.below(2))
                        .f(min_w)
                        .0
                })
                .collect()
        },
    },
    KernelVectors {
        name: "ao_direction",
        inputs: "n:vec3 i:u32 count:u32",
        outputs: "dir:vec3",
        tolerance: TOL_AO_DIRECTION,
        tolerance_constant: "TOL_AO_DIRECTION",
        non_finite: "Direction i of count (cosine-weighted, stratified) around the normal n, in tangent_frame(n). A zero or non-finite n is treated as +Z; count = 0 gives the normal; i is clamped to count - 1. The result is always finite.",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let (n, i, c) = (r.v3(), r.u(), r.u());
            out(&ao_direction(n, i, c).to_array())
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    W::default()
                        .v(&rng.unit_vec().to_array())
                        .u(rng.below(300))
                        .u(rng.below(300))
                        .0
                })
                .collect();
            for n in ao_grid_normals() {
                for (i, c) in AO_GRID_INDICES {
                    v.push(W::default().v(&n.to_array()).u(i).u(c).0);
                }
            }
            v
        },
    },
    KernelVectors {
        name: "ao_fraction",
        inputs: "unoccluded:u32 count:u32",
        outputs: "fraction:f32",
        tolerance: TOL_AO_FRACTION,
        tolerance_constant: "TOL_AO_FRACTION",
        non_finite: "unoccluded / count in [0, 1]. Domain: unoccluded <= count. count = 0 gives exactly 1; unoccluded > count is clamped to 1.",
        reference: "f64: min(unoccluded, count) / count (1 for count = 0), correctly rounded (checked by tests/vectors.rs).",
        eval: |w| {
            let mut r = R(w);
            out(&[ao_fraction(r.u(), r.u())])
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| {
                    let c = rng.below(300);
                    W::default().u(rng.below(c + 2)).u(c).0
                })
                .collect();
            for (i, c) in [
                (0, 0),
                (1, 0),
                (0, 1),
                (1, 1),
                (2, 1),
                (u32::MAX, u32::MAX),
                (1, 3),
                (1 << 24, 1 << 24),
                ((1 << 24) - 1, 1 << 24),
            ] {
                v.push(W::default().u(i).u(c).0);
            }
            v
        },
    },
    KernelVectors {
        name: "fxaa_encode",
        inputs: "linear:vec3",
        outputs: "texel:vec4",
        tolerance: TOL_FXAA_ENCODE,
        tolerance_constant: "TOL_FXAA_ENCODE",
        non_finite: "The linear colour clamped to [0, 1], sRGB-encoded, in xyz, its luma (0.299, 0.587, 0.114 of the stored colour) in w, each rounded to 8-bit levels. Total: NaN channels read as 0, +-inf clamp; the result is always in [0, 1]^4.",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            out(&fxaa_encode(r.v3()).to_array())
        },
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..GENERATED)
                .map(|_| W::default().v(&rng.colour(1.2).to_array()).0)
                .collect();
            for (a, b) in special_pairs() {
                v.push(W::default().v(&[a, b, 0.5]).0);
            }
            // Every 8-bit sRGB level's linear value.
            for l in 0..256u32 {
                let x = subcone_kernels::fxaa::srgb_to_linear(l as f32 / 255.0);
                v.push(W::default().v(&[x, x, x]).0);
            }
            v
        },
    },
    KernelVectors {
        name: "fxaa_pixel",
        inputs: "p:vec3*49 subpix:f32 edge_threshold:f32 edge_threshold_min:f32",
        outputs: "c:vec3",
        tolerance: TOL_FXAA_PIXEL,
        tolerance_constant: "TOL_FXAA_PIXEL",
        non_finite: "FXAA 3.11 quality (preset 12) on the centre pixel (3, 3) of a 7x7 patch of linear colours. The patch's 49 colours p0..p48 come rows first (row y, column x is p<7y + x>); each is encoded by fxaa_encode, and a fetch outside the patch is clamped to its edge. The output is in the sRGB space of the encoded input, always finite and in [0, 1]^3: the centre unchanged or a blend of the centre with one of its four direct neighbours. NaN and infinite inputs are cleaned by fxaa_encode (NaN as 0, clamped). Where an edge puts FXAA's end-of-edge test on its threshold, one ulp may pick another span: the conformance suite accepts a port's output there when it still lies between the centre and its direct neighbours (at most 1 % of patches).",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let px: Vec<Vec3> = (0..49).map(|_| r.v3()).collect();
            let p = FxaaParams {
                subpix: r.f(),
                edge_threshold: r.f(),
                edge_threshold_min: r.f(),
                _pad: 0.0,
            };
            let fetch = |x: i32, y: i32| fxaa_encode(px[(y.clamp(0, 6) * 7 + x.clamp(0, 6)) as usize]);
            out(&fxaa_pixel(&fetch, 3, 3, &p).to_array())
        },
        generate: |rng| {
            (0..256)
                .map(|_| {
                    let colour =
                        |rng: &mut Rng| Vec3::new(rng.unit(), rng.unit(), rng.unit());
                    let px: Vec<Vec3> = match rng.below(6) {
                        0..=1 => (0..49).map(|_| colour(rng)).collect(),
                        2..=4 => {
                            let (a, b) = (colour(rng), colour(rng));
                            let (nx, ny) = (rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
                            let c = rng.range(-3.0, 3.0);
                            (0..49)
                                .map(|i| {
                                    let (x, y) = ((i % 7) as f32 - 3.0, (i / 7) as f32 - 3.0);
                                    if nx * x + ny * y > c {
                                        a
                                    } else {
                                        b
                                    }
                                })
                                .collect()
                        }
                        _ => (0..49).map(|_| rng.colour(2.0)).collect(),
                    };
                    let p = if rng.below(4) < 3 {
                        FxaaParams::QUALITY
                    } else {
                        FxaaParams {
                            subpix: rng.range(0.0, 1.0),
                            edge_threshold: rng.range(0.063, 0.333),
                            edge_threshold_min: rng.range(0.0312, 0.0833),
                            _pad: 0.0,
                        }
                    };
                    let mut w = W::default();
                    for c in &px {
                        w = w.v(&c.to_array());
                    }
                    w.f(p.subpix)
                        .f(p.edge_threshold)
                        .f(p.edge_threshold_min)
                        .0
                })
                .collect()
        },
    },
    KernelVectors {
        name: "clamp_alpha",
        inputs: "alpha:f32",
        outputs: "alpha_clamped:f32",
        tolerance: TOL_TRANSPARENCY_WEIGHT,
        tolerance_constant: "TOL_TRANSPARENCY_WEIGHT",
        non_finite: "alpha clamped to [0, 1]; NaN reads as 1 (opaque), so a broken opacity never lets hidden surfaces show through.",
        reference: NO_REFERENCE,
        eval: |w| out(&[clamp_alpha(R(w).f())]),
        generate: |rng| alphas(rng).into_iter().map(|a| W::default().f(a).0).collect(),
    },
    KernelVectors {
        name: "remaining_after",
        inputs: "r:u32 alpha:f32",
        outputs: "levels:u32",
        tolerance: TOL_EXACT,
        tolerance_constant: "TOL_EXACT",
        non_finite: "floor(r (1 - clamp_alpha(alpha)) + 1/2), in [0, r]: the transmittance levels a cell keeps. Domain: r <= K = 4 (5 is generated too), any alpha (NaN is opaque). Exact, except where r (1 - alpha) + 1/2 lies within TRANSPARENCY_NEAR (1e-6) of an integer (and not exactly on it in f32), where a fused multiply-add may round to the other level.",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let (k, a) = (r.u(), r.f());
            vec![remaining_after(k, a)]
        },
        generate: |rng| {
            alphas(rng)
                .into_iter()
                .enumerate()
                .map(|(i, a)| W::default().u(i as u32 % 6).f(a).0)
                .collect()
        },
    },
    KernelVectors {
        name: "is_opaque",
        inputs: "alpha:f32",
        outputs: "opaque:bool",
        tolerance: TOL_EXACT,
        tolerance_constant: "TOL_EXACT",
        non_finite: "Whether a surface of opacity alpha leaves no transmittance in a clear cell: alpha > 0.875 for K = 4, and NaN (opaque).",
        reference: NO_REFERENCE,
        eval: |w| vec![is_opaque(R(w).f()) as u32],
        generate: |rng| alphas(rng).into_iter().map(|a| W::default().f(a).0).collect(),
    },
    KernelVectors {
        name: "level_weight",
        inputs: "gained:u32",
        outputs: "w:f32",
        tolerance: TOL_TRANSPARENCY_WEIGHT,
        tolerance_constant: "TOL_TRANSPARENCY_WEIGHT",
        non_finite: "min(gained, 32 K) / (32 K), K = 4: the weight of gained opacity levels summed over cells, at most 1. Total over u32.",
        reference: "exact: min(gained, 128)/128 (checked by tests/vectors.rs).",
        eval: |w| out(&[level_weight(R(w).u())]),
        generate: |rng| {
            let mut v: Vec<Vec<u32>> = (0..=160u32).map(|g| vec![g]).collect();
            v.extend((0..512).map(|_| vec![rng.bits()]));
            v.push(vec![u32::MAX]);
            v
        },
    },
    KernelVectors {
        name: "transparency_accumulator",
        inputs: "mask0:u32 alpha0:f32 mask1:u32 alpha1:f32 mask2:u32 alpha2:f32 level_set_index:u32 bit:u32",
        outputs: "visible0:u32 gained0:u32 visible1:u32 gained1:u32 visible2:u32 gained2:u32 plane0:u32 plane1:u32 plane2:u32 plane3:u32 plane4:u32 plane5:u32 level:u32 is_binary:bool opaque:u32 total_levels:u32 level_set:u32 uncovered_weight:f32",
        tolerance: TOL_EXACT,
        tolerance_constant: "TOL_EXACT",
        non_finite: "CTSS section 5.3's K = 4 nested masks: from a clear pixel, add(mask_k, alpha_k) for k = 0..3 (each returning the cells whose level rose and the levels gained), then plane(0..6) (plane(k) = M_(k+1) for k < K, else 0), level(bit), is_binary, opaque (M_K), total_levels, level_set(level_set_index) and uncovered_weight (1 - total_levels/(32 K)). NaN alpha is opaque, alpha outside [0, 1] is clamped. Exact, except where some alpha puts r (1 - alpha) + 1/2 within TRANSPARENCY_NEAR (1e-6) of an integer for r in 1..=4 (and not exactly on it in f32), where a fused multiply-add may round to the other level; such records are at most 1 %.",
        reference: NO_REFERENCE,
        eval: |w| {
            let mut r = R(w);
            let adds = [(r.u(), r.f()), (r.u(), r.f()), (r.u(), r.f())];
            let (set, bit) = (r.u(), r.u());
            let mut acc = TransparencyAccumulator::new();
            let mut o = Vec::with_capacity(18);
            for (m, a) in adds {
                let (v, g) = acc.add(m, a);
                o.extend([v, g]);
            }
            o.extend((0..6).map(|k| acc.plane(k)));
            o.extend([
                acc.level(bit),
                acc.is_binary() as u32,
                acc.opaque(),
                acc.total_levels(),
                acc.level_set(set),
                acc.uncovered_weight().to_bits(),
            ]);
            o
        },
        generate: |rng| {
            let a = alphas(rng);
            (0..GENERATED)
                .map(|i| {
                    let mut w = W::default();
                    for k in 0..3 {
                        let m = match rng.below(4) {
                            0 => rng.bits(),
                            1 => u32::MAX,
                            2 => 0,
                            _ => ((1u64 << rng.below(32)) - 1) as u32,
                        };
                        w = w.u(m).f(a[(3 * i + k) % a.len()]);
                    }
                    w.u(rng.below(6)).u(rng.below(40)).0
                })
                .collect()
        },
    },
];

/// Opacities as the conformance suite draws them: any, the quarter levels'
/// boundaries and specials, any bits.
fn alphas(rng: &mut Rng) -> Vec<f32> {
    let special = [
        0.0f32, 1.0, 0.5, 0.125, 0.375, 0.625, 0.875, 0.25, 0.75, 0.3, 0.7, -0.5, 1.5,
    ];
    let mut v: Vec<f32> = special.iter().chain(SPECIALS.iter()).copied().collect();
    for _ in 0..GENERATED {
        v.push(match rng.below(6) {
            0..=2 => rng.any_f32(0.0, 1.0),
            3..=4 => rng.pick(&special),
            _ => f32::from_bits(rng.bits()),
        });
    }
    v
}

/// Two-input cone kernels: generated over the two domains, 512 awkward pairs
/// (signed, log-uniform, specials; the second non-negative), and every pair
/// of [`SPECIALS`].
fn cone_pairs(rng: &mut Rng, a: (f32, f32), b: (f32, f32)) -> Vec<Vec<u32>> {
    let mut v: Vec<Vec<u32>> = (0..GENERATED)
        .map(|_| {
            W::default()
                .f(rng.any_f32(a.0, a.1))
                .f(rng.any_f32(b.0, b.1))
                .0
        })
        .collect();
    for _ in 0..512 {
        let (x, y) = (rng.awkward(), rng.awkward().abs());
        v.push(W::default().f(x).f(y).0);
    }
    v.extend(special_pairs().map(|(x, y)| W::default().f(x).f(y).0));
    v
}
