//! An SDF tree compiled into a flat program, evaluated for
//! [`LANES`] points at once.
//!
//! [`SdfNode::eval_split`] walks the tree node by node, one point at a time.
//! [`SdfProgram::compile`] flattens the tree once into a list of instructions
//! over a small stack machine, so that an evaluation is one loop; the loop
//! runs eight points (a packet of rays) through every instruction together,
//! each arithmetic step one lane-wise operation that the compiler turns into
//! SIMD instructions (8-wide under AVX2, two 4-wide halves on baseline SSE2).
//!
//! **Bit for bit the tree's values.** Every lane computes exactly the
//! operations [`SdfNode::eval_split`] computes for its point, in the same order:
//! the same glam formulas written out lane-wise (`length` as
//! `√((x·x + y·y) + z·z)`, the SSE2 quaternion rotation, glam's compare-based
//! `min`/`max` of vectors against Rust's NaN-ignoring `f32::min`/`max` of
//! scalars), and the same bound culling: a union child is evaluated for the
//! lanes whose best distance so far its bounding sphere does not exceed, and
//! skipped (for all lanes at once) when no lane needs it. Skipping a subtree
//! is exact: the tree skips it for that point too. What no lane-wise formula
//! covers (displacement's `sin`) is evaluated per lane through the tree.
//! `tests/program.rs` compares the two on every shape and operator.
//!
//! ```
//! use glam::Vec3;
//! use subcone_scene::sdf::SdfNode;
//! use subcone_sdf::program::{Points, SdfProgram, LANES};
//!
//! let tree = SdfNode::union(vec![
//!     SdfNode::sphere(1.0).unwrap(),
//!     SdfNode::cuboid(Vec3::splat(0.5)).unwrap().translate(Vec3::X * 3.0).unwrap(),
//! ])
//! .unwrap();
//! let program = SdfProgram::compile(&tree);
//! let mut scratch = program.scratch();
//! let mut points = Points::default();
//! for k in 0..LANES {
//!     points.set(k, Vec3::new(k as f32, 0.25, 0.0));
//! }
//! let out = program.eval_split(&points, 0xff, &mut scratch);
//! for k in 0..LANES {
//!     let one = tree.eval_split(points.get(k));
//!     assert_eq!(out.safe[k].to_bits(), one.safe.to_bits());
//!     assert_eq!(out.surface[k].to_bits(), one.surface.to_bits());
//!     assert_eq!(out.material[k], one.material);
//! }
//! ```

use core::ops::{Add, Div, Mul, Neg, Sub};

use glam::{Quat, Vec3, Vec4};

use subcone_scene::sdf::lane::{self, Lane};
use subcone_scene::sdf::{Aabb, Instance, Op, Scatter, SdfNode, Shape, SplitDistance};

/// Points evaluated together: the width of a packet.
pub const LANES: usize = 8;

/// A set of active lanes, bit `k` for lane `k`.
pub type LaneMask = u8;

/// [`LANES`] points, one per lane, as coordinate arrays.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Points {
    /// x of each lane.
    pub x: [f32; LANES],
    /// y of each lane.
    pub y: [f32; LANES],
    /// z of each lane.
    pub z: [f32; LANES],
}

impl Points {
    /// Lane `k`'s point. Panics if `k ≥ LANES`.
    #[inline(always)]
    pub fn get(&self, k: usize) -> Vec3 {
        Vec3::new(self.x[k], self.y[k], self.z[k])
    }

    /// Sets lane `k`'s point. Panics if `k ≥ LANES`.
    #[inline(always)]
    pub fn set(&mut self, k: usize, p: Vec3) {
        self.x[k] = p.x;
        self.y[k] = p.y;
        self.z[k] = p.z;
    }
}

/// [`SplitDistance`] for each lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SplitLanes {
    /// The safe step of each lane.
    pub safe: [f32; LANES],
    /// The surface distance of each lane.
    pub surface: [f32; LANES],
    /// The material of each lane.
    pub material: [u32; LANES],
}

impl SplitLanes {
    /// Lane `k` as a [`SplitDistance`]. Panics if `k ≥ LANES`.
    #[inline(always)]
    pub fn get(&self, k: usize) -> SplitDistance {
        SplitDistance {
            safe: self.safe[k],
            surface: self.surface[k],
            material: self.material[k],
        }
    }
}

// ------------------------------------------------------------------ lanes

/// `[e(0), e(1), …, e(7)]`: an expression per lane, written out. Not a loop
/// (`for` or `core::array::from_fn`): the interpreter inlines thousands of
/// lane-wise operations, and as loops each was a loop for LLVM's loop passes
/// to rotate and unroll before vectorising, a cost that grew with the
/// interpreter's size (loop rotation alone was two thirds of the CPU
/// backend's build). Written out, the eight operations are straight-line code
/// that the SLP vectoriser packs into one vector operation, as the unrolled
/// loops were: the same operations lane by lane, so the same bits.
macro_rules! each_lane {
    (|$k:pat_param| $e:expr) => {{
        const _: () = assert!(LANES == 8);
        [
            {
                let $k = 0usize;
                $e
            },
            {
                let $k = 1usize;
                $e
            },
            {
                let $k = 2usize;
                $e
            },
            {
                let $k = 3usize;
                $e
            },
            {
                let $k = 4usize;
                $e
            },
            {
                let $k = 5usize;
                $e
            },
            {
                let $k = 6usize;
                $e
            },
            {
                let $k = 7usize;
                $e
            },
        ]
    }};
}

/// [`lanewise!`] as a loop, for the operations with a branch per lane
/// (glam's `min`/`max`, `clamp`, the cell rounding): the few of them cost
/// the build little, and as loops they run fewer instructions than written
/// out (measured on the AVX2 path: `primitives` 1 % fewer in all).
macro_rules! lanewise_loop {
    ($a:expr, |$k:ident| $e:expr) => {{
        let mut r = [0.0f32; LANES];
        for $k in 0..LANES {
            r[$k] = $e;
        }
        F8(r)
    }};
}

macro_rules! lanewise {
    ($a:expr, |$k:ident| $e:expr) => {{
        F8(each_lane!(|$k| $e))
    }};
}

#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
struct F8([f32; LANES]);

/// A lane mask.
type M8 = W8;

/// A lane mask as the vector units hold one: each lane all ones or all
/// zeros. The hot union instructions use it; `[bool; 8]` masks make LLVM
/// pack and unpack bytes at every step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(32))]
struct W8([u32; LANES]);

impl W8 {
    /// The lanes of `bits`.
    #[inline(always)]
    fn of_bits(bits: LaneMask) -> W8 {
        W8(each_lane!(|k| {
            0u32.wrapping_sub(((bits >> k) & 1) as u32)
        }))
    }
    /// Lane-wise `cond`.
    #[inline(always)]
    fn from_fn(cond: impl Fn(usize) -> bool) -> W8 {
        W8(each_lane!(|k| 0u32.wrapping_sub(cond(k) as u32)))
    }
    #[inline(always)]
    fn and(self, o: W8) -> W8 {
        W8(each_lane!(|k| self.0[k] & o.0[k]))
    }
    #[inline(always)]
    fn and_not(self, o: W8) -> W8 {
        W8(each_lane!(|k| self.0[k] & !o.0[k]))
    }
    /// Whether any lane is set.
    #[inline(always)]
    fn any(self) -> bool {
        let w = self.0;
        ((w[0] | w[1]) | (w[2] | w[3])) | ((w[4] | w[5]) | (w[6] | w[7])) != 0
    }
    /// The lanes as bits.
    #[inline(always)]
    fn bits(self) -> LaneMask {
        let w = self.0;
        let bit = |k: usize| ((w[k] & 1) as LaneMask) << k;
        ((bit(0) | bit(1)) | (bit(2) | bit(3))) | ((bit(4) | bit(5)) | (bit(6) | bit(7)))
    }
    /// `a` in the set lanes, `b` elsewhere, bit for bit.
    #[inline(always)]
    fn select(self, a: F8, b: F8) -> F8 {
        F8(each_lane!(|k| {
            f32::from_bits((a.0[k].to_bits() & self.0[k]) | (b.0[k].to_bits() & !self.0[k]))
        }))
    }
    /// [`select`](W8::select) for materials.
    #[inline(always)]
    fn select_u(self, a: [u32; LANES], b: [u32; LANES]) -> [u32; LANES] {
        each_lane!(|k| (a[k] & self.0[k]) | (b[k] & !self.0[k]))
    }
}

impl F8 {
    /// glam's vector `min`: `if a < b { a } else { b }`.
    #[inline(always)]
    fn gmin(self, o: F8) -> F8 {
        lanewise_loop!(self, |k| if self.0[k] < o.0[k] {
            self.0[k]
        } else {
            o.0[k]
        })
    }
    #[inline(always)]
    fn ge(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] >= o.0[k])
    }
}

macro_rules! binop {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F8 {
            type Output = F8;
            #[inline(always)]
            fn $f(self, o: F8) -> F8 {
                lanewise!(self, |k| self.0[k] $op o.0[k])
            }
        }
        impl $tr<f32> for F8 {
            type Output = F8;
            #[inline(always)]
            fn $f(self, o: f32) -> F8 {
                lanewise!(self, |k| self.0[k] $op o)
            }
        }
        impl $tr<F8> for f32 {
            type Output = F8;
            #[inline(always)]
            fn $f(self, o: F8) -> F8 {
                lanewise!(o, |k| self $op o.0[k])
            }
        }
    };
}
binop!(Add, add, +);
binop!(Sub, sub, -);
binop!(Mul, mul, *);
binop!(Div, div, /);

impl Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        lanewise!(self, |k| -self.0[k])
    }
}

/// The primitives' operations ([`subcone_scene::sdf::lane`]) on eight lanes:
/// each the `f32` operation of [`Lane for f32`](lane::Lane), lane by lane.
impl Lane for F8 {
    type Mask = M8;
    #[inline(always)]
    fn splat(v: f32) -> F8 {
        F8([v; LANES])
    }
    /// Rust's `f32::min` (NaN-ignoring), lane-wise.
    #[inline(always)]
    fn min(self, o: F8) -> F8 {
        lanewise!(self, |k| self.0[k].min(o.0[k]))
    }
    /// Rust's `f32::max`, lane-wise.
    #[inline(always)]
    fn max(self, o: F8) -> F8 {
        lanewise!(self, |k| self.0[k].max(o.0[k]))
    }
    /// glam's vector `max`: `if a > b { a } else { b }`.
    #[inline(always)]
    fn gmax(self, o: F8) -> F8 {
        lanewise_loop!(self, |k| if self.0[k] > o.0[k] {
            self.0[k]
        } else {
            o.0[k]
        })
    }
    /// Rust's `f32::clamp`.
    #[inline(always)]
    fn clamp(self, lo: F8, hi: F8) -> F8 {
        lanewise_loop!(self, |k| {
            let mut v = self.0[k];
            if v < lo.0[k] {
                v = lo.0[k];
            }
            if v > hi.0[k] {
                v = hi.0[k];
            }
            v
        })
    }
    #[inline(always)]
    fn abs(self) -> F8 {
        lanewise!(self, |k| self.0[k].abs())
    }
    #[inline(always)]
    fn sqrt(self) -> F8 {
        lanewise!(self, |k| self.0[k].sqrt())
    }
    #[inline(always)]
    fn lt(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] < o.0[k])
    }
    #[inline(always)]
    fn gt(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] > o.0[k])
    }
    #[inline(always)]
    fn eq(self, o: F8) -> M8 {
        W8::from_fn(|k| self.0[k] == o.0[k])
    }
    #[inline(always)]
    fn is_finite(self) -> M8 {
        W8::from_fn(|k| self.0[k].is_finite())
    }
    #[inline(always)]
    fn and(a: M8, b: M8) -> M8 {
        a.and(b)
    }
    #[inline(always)]
    fn or(a: M8, b: M8) -> M8 {
        W8(each_lane!(|k| a.0[k] | b.0[k]))
    }
    #[inline(always)]
    fn select(m: M8, a: F8, b: F8) -> F8 {
        m.select(a, b)
    }
}

/// Three coordinates of eight lanes, with glam's `Vec3` semantics.
#[derive(Clone, Copy, Debug, Default)]
struct V3 {
    x: F8,
    y: F8,
    z: F8,
}

impl V3 {
    #[inline(always)]
    fn new(x: F8, y: F8, z: F8) -> V3 {
        V3 { x, y, z }
    }
    #[inline(always)]
    fn splat(v: Vec3) -> V3 {
        V3::new(F8::splat(v.x), F8::splat(v.y), F8::splat(v.z))
    }
    #[inline(always)]
    fn sub(self, o: V3) -> V3 {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
    #[inline(always)]
    fn mul(self, o: V3) -> V3 {
        V3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }
    #[inline(always)]
    fn scale(self, s: F8) -> V3 {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
    #[inline(always)]
    fn dot(self, o: V3) -> F8 {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }
    #[inline(always)]
    fn length(self) -> F8 {
        self.dot(self).sqrt()
    }
    /// glam's `max`.
    #[inline(always)]
    fn gmax(self, o: V3) -> V3 {
        V3::new(self.x.gmax(o.x), self.y.gmax(o.y), self.z.gmax(o.z))
    }
    /// glam's `max(Vec3::ZERO)`.
    #[inline(always)]
    fn pos(self) -> V3 {
        self.gmax(V3::splat(Vec3::ZERO))
    }
    /// glam's `Quat * Vec3` (SSE2): `v(w² − b·b) + b(2 v·b) + (b × v)(2w)`.
    #[inline(always)]
    fn rotate(self, q: Quat) -> V3 {
        self.rotate_lanes([
            F8::splat(q.x),
            F8::splat(q.y),
            F8::splat(q.z),
            F8::splat(q.w),
        ])
    }
    /// [`V3::rotate`] by a different quaternion per lane.
    #[inline(always)]
    fn rotate_lanes(self, q: [F8; 4]) -> V3 {
        let [bx, by, bz, w] = q;
        let b2 = (bx * bx + by * by) + bz * bz;
        let ww = w * w - b2;
        let vb2 = ((self.x * bx + self.y * by) + self.z * bz) * 2.0;
        let w2 = w * 2.0;
        // b × v, as glam's SSE2 `cross` forms it.
        let cx = by * self.z - self.y * bz;
        let cy = bz * self.x - self.z * bx;
        let cz = bx * self.y - self.x * by;
        V3::new(
            (self.x * ww + bx * vb2) + cx * w2,
            (self.y * ww + by * vb2) + cy * w2,
            (self.z * ww + bz * vb2) + cz * w2,
        )
    }
}

// ------------------------------------------------------------------ shapes

/// `Shape::distance`, lane-wise: the one definition of the primitives
/// ([`subcone_scene::sdf::lane`]), on eight lanes.
#[inline(always)]
fn shape_distance(shape: &Shape, p: V3) -> F8 {
    lane::shape_distance(shape, p.x, p.y, p.z)
}

/// `Aabb::distance`, lane-wise.
#[inline(always)]
fn aabb_distance(b: &Aabb, p: V3) -> F8 {
    V3::splat(b.min)
        .sub(p)
        .gmax(p.sub(V3::splat(b.max)))
        .pos()
        .length()
}

/// `round_cell` (`⌊x + ½⌋` through a truncation to `i64`), lane-wise and
/// bit for bit, with `floor` (one instruction from SSE4.1 on): below `2²³`
/// in magnitude the two agree but for the sign of a zero; from there on every
/// `f32` is an integer, which the scalar form returns as is up to its `i64`
/// saturation at `±2⁶³`; NaN gives 0 in both.
#[inline(always)]
fn round_cell(x: F8) -> F8 {
    const BIG: f32 = 8_388_608.0; // 2²³
    const SAT: f32 = 9_223_372_036_854_775_808.0; // 2⁶³
    lanewise_loop!(x, |k| {
        let f = x.0[k] + 0.5;
        // Below 2²³ the truncation then the step down is `floor`, but for
        // `−0`, which the truncation makes `+0` (and `+ 0.0` too).
        let small = f.floor() + 0.0;
        let large = f.clamp(-SAT, SAT);
        if f.abs() < BIG {
            small
        } else if f.is_nan() {
            0.0
        } else {
            large
        }
    })
}

// ------------------------------------------------------------------ program

/// One instruction of an [`SdfProgram`]. Values live on a stack of
/// `(safe, surface, material)` lanes; in the tree's `eval` mode (below an
/// operator that does not split its distance) `safe` and `surface` are equal.
#[derive(Clone, Debug)]
enum Inst<'a> {
    /// A shape, or a transformed shape: one instruction for the commonest
    /// subtree.
    Leaf(Leaf),
    /// A union's child that is a [`Leaf`]: cull, evaluate and fold in one
    /// instruction.
    UnionLeaf {
        sphere: Vec4,
        leaf: Leaf,
        split: bool,
    },
    /// Push `(p − translation)·inv_scale`, rotated by `inv_rotation` if any.
    PushTransform {
        translation: Vec3,
        inv_scale: f32,
        inv_rotation: Option<Quat>,
    },
    /// Pop the point; scale the top value by `scale`.
    PopTransform { scale: f32 },
    /// Push the point with the `axes` mirrored (`|p_k|`).
    PushMirror { axes: [bool; 3] },
    /// Pop the point.
    PopPoint,
    /// Push a repetition cell's point; keep its wall distance.
    PushRepeat {
        period: Vec3,
        lo: Vec3,
        hi: Vec3,
        guard: bool,
    },
    /// Pop the cell point and its walls; cap the top value: the safe step by
    /// `wall + margin` (`split`), or the distance as `eval` does.
    PopRepeat { margin: f32, split: bool },
    /// Push a union's accumulator.
    UnionBegin { material: u32 },
    /// Cull the next child (ending at its `UnionMerge`, `skip` instructions
    /// on) by its bounding sphere against the accumulator.
    UnionChild {
        sphere: Vec4,
        skip: u32,
        split: bool,
    },
    /// Fold the child on top into the accumulator below it, in its lanes.
    UnionMerge { split: bool },
    /// Close a split union: `safe = min(safe, surface)`.
    UnionEnd { split: bool },
    /// Push an intersection's accumulator.
    IntersectionBegin { material: u32 },
    /// Fold the child on top in: the larger distance wins.
    IntersectionMerge,
    /// Fold the child on top into the smooth union below it (`first`: it is
    /// the first child and becomes the accumulator).
    SmoothMerge { k: f32, first: bool },
    /// Pop `b`, then `a`: push `a` where `a ≥ −b`, else `−b`.
    SubtractMerge,
    /// `d − radius`.
    Round { radius: f32 },
    /// `|d| − thickness`.
    Onion { thickness: f32 },
    /// `d·factor`.
    ScaleDistance { factor: f32 },
    /// `bounded`, eval mode: push the box distance; cull the child (ending
    /// at its `BoundedMerge`, `skip` on) in the lanes farther than `pad`.
    BoundedBegin {
        bounds: Aabb,
        pad: f32,
        material: u32,
        skip: u32,
    },
    /// Fold the child on top into the lanes that needed it.
    BoundedMerge,
    /// `bounded`, split mode: keep the box distance for after the child.
    BoundedSplitBegin { bounds: Aabb },
    /// Combine the child's split values with the box distance kept.
    BoundedSplitEnd { pad: f32 },
    /// A scatter: the cell's instance of a template, per lane.
    Scatter {
        scatter: &'a Scatter,
        templates: Vec<SdfProgram<'a>>,
        split: bool,
    },
    /// What has no lane-wise form: the tree, lane by lane.
    Tree { node: &'a SdfNode, split: bool },
}

/// A shape in its own frame: `scale · shape((p − translation)·inv_scale`,
/// rotated by `inv_rotation`).
#[derive(Clone, Copy, Debug)]
struct Leaf {
    shape: Shape,
    material: u32,
    transform: Option<LeafTransform>,
}

#[derive(Clone, Copy, Debug)]
struct LeafTransform {
    translation: Vec3,
    inv_scale: f32,
    inv_rotation: Option<Quat>,
    scale: f32,
}

impl Leaf {
    /// The node as a leaf, if it is a shape or a transformed shape.
    fn of(node: &SdfNode) -> Option<Leaf> {
        match node.op() {
            Op::Shape { shape, material } => Some(Leaf {
                shape: *shape,
                material: *material,
                transform: None,
            }),
            Op::Transform(t) => match t.child.op() {
                Op::Shape { shape, material } => Some(Leaf {
                    shape: *shape,
                    material: *material,
                    transform: Some(LeafTransform {
                        translation: t.translation,
                        inv_scale: t.inv_scale,
                        inv_rotation: t.rotated.then_some(t.inv_rotation),
                        scale: t.scale,
                    }),
                }),
                _ => None,
            },
            _ => None,
        }
    }

    /// The distance at `p`: the transform's then the shape's operations, as
    /// the tree does them.
    ///
    /// The shape's distance is written once, after the transform (not once
    /// per case): every primitive is compiled into the interpreter once per
    /// call of this function, and the copies of every primitive on eight
    /// lanes are most of what LLVM spends on an interpreter.
    #[inline(always)]
    fn distance(&self, p: &V3) -> F8 {
        let q = match &self.transform {
            None => *p,
            Some(t) => {
                let mut q = p
                    .sub(V3::splat(t.translation))
                    .scale(F8::splat(t.inv_scale));
                if let Some(r) = t.inv_rotation {
                    q = q.rotate(r);
                }
                q
            }
        };
        let d = shape_distance(&self.shape, q);
        match &self.transform {
            None => d,
            Some(t) => d * t.scale,
        }
    }
}

/// An SDF tree as a flat program: see the [module](self) docs. Borrows the
/// tree (scatter tables and per-lane fallbacks are read from it).
#[derive(Clone, Debug)]
pub struct SdfProgram<'a> {
    code: Vec<Inst<'a>>,
    /// Deepest value, point, mask and wall stacks the code uses.
    depth: [usize; 4],
    /// Whether any instruction evaluates lane by lane through the tree.
    tree_fallback: bool,
}

/// Working stacks of one [`SdfProgram`] evaluation, reused from one packet to
/// the next ([`SdfProgram::scratch`]).
#[derive(Clone, Debug)]
pub struct Scratch {
    values: Vec<Value>,
    points: Vec<V3>,
    masks: Vec<W8>,
    walls: Vec<F8>,
    nested: Option<Box<Scratch>>,
}

#[derive(Clone, Copy, Debug, Default)]
struct Value {
    safe: F8,
    surf: F8,
    mat: [u32; LANES],
}

impl Value {
    #[inline(always)]
    fn both(d: F8, mat: [u32; LANES]) -> Value {
        Value {
            safe: d,
            surf: d,
            mat,
        }
    }
    #[inline(always)]
    fn select(m: M8, a: Value, b: Value) -> Value {
        Value {
            safe: F8::select(m, a.safe, b.safe),
            surf: F8::select(m, a.surf, b.surf),
            mat: m.select_u(a.mat, b.mat),
        }
    }
}

struct Compiler<'a> {
    code: Vec<Inst<'a>>,
    /// Current and deepest stack depths: values, points, masks, walls.
    now: [usize; 4],
    max: [usize; 4],
    nested: bool,
    tree_fallback: bool,
}

const VALUES: usize = 0;
const POINTS: usize = 1;
const MASKS: usize = 2;
const WALLS: usize = 3;

impl<'a> Compiler<'a> {
    fn push(&mut self, stack: usize, n: isize) {
        self.now[stack] = (self.now[stack] as isize + n) as usize;
        self.max[stack] = self.max[stack].max(self.now[stack]);
    }

    /// Compile `node` as the tree's `split` (or, with `split` false, `eval`):
    /// leaves one value on the stack.
    fn node(&mut self, node: &'a SdfNode, split: bool) {
        if let Some(leaf) = Leaf::of(node) {
            self.leaf(leaf);
            return;
        }
        match node.op() {
            // Taken by `Leaf::of` above; kept for completeness.
            Op::Shape { shape, material } => self.leaf(Leaf {
                shape: *shape,
                material: *material,
                transform: None,
            }),
            Op::Transform(t) => self.transform(t, split),
            Op::Union { children, spheres } => {
                self.union(node.default_material(), children, spheres, split)
            }
            Op::Repeat(r) if split && r.guard => {
                self.repeat(r, true);
            }
            Op::Scatter(s) => self.scatter(node, s, split),
            Op::Bounded { pad, child } if split => self.bounded_split(*pad, child),
            // Below here: the tree's `eval` (split falls back to it).
            Op::Bounded { pad, child } => self.bounded(node.default_material(), *pad, child),
            Op::Repeat(r) => self.repeat(r, false),
            Op::Intersection(children) => self.intersection(node.default_material(), children),
            Op::SmoothUnion { k, children } => self.smooth_union(*k, children),
            Op::Subtract(ab) => self.subtract(&ab.0, &ab.1),
            Op::Mirror { axes, child } => self.mirror(*axes, child),
            Op::Round { radius, child } => {
                self.node(child, false);
                self.code.push(Inst::Round { radius: *radius });
            }
            Op::Onion { thickness, child } => {
                self.node(child, false);
                self.code.push(Inst::Onion {
                    thickness: *thickness,
                });
            }
            Op::ScaleDistance { factor, child } => {
                self.node(child, false);
                self.code.push(Inst::ScaleDistance { factor: *factor });
            }
            Op::Displace { .. } => self.tree(node, false),
        }
    }

    fn leaf(&mut self, leaf: Leaf) {
        self.code.push(Inst::Leaf(leaf));
        self.push(VALUES, 1);
    }

    fn transform(&mut self, t: &'a subcone_scene::sdf::Transform, split: bool) {
        self.code.push(Inst::PushTransform {
            translation: t.translation,
            inv_scale: t.inv_scale,
            inv_rotation: t.rotated.then_some(t.inv_rotation),
        });
        self.push(POINTS, 1);
        self.node(&t.child, split);
        self.code.push(Inst::PopTransform { scale: t.scale });
        self.push(POINTS, -1);
    }

    /// A union: leaf children as one instruction each, others between a
    /// cull that may skip them and a merge.
    fn union(&mut self, material: u32, children: &'a [SdfNode], spheres: &[Vec4], split: bool) {
        self.code.push(Inst::UnionBegin { material });
        self.push(VALUES, 1);
        for (c, s) in children.iter().zip(spheres) {
            if let Some(leaf) = Leaf::of(c) {
                self.code.push(Inst::UnionLeaf {
                    sphere: *s,
                    leaf,
                    split,
                });
                continue;
            }
            let at = self.code.len();
            self.code.push(Inst::UnionChild {
                sphere: *s,
                skip: 0,
                split,
            });
            self.push(MASKS, 1);
            self.node(c, split);
            self.code.push(Inst::UnionMerge { split });
            self.push(VALUES, -1);
            self.push(MASKS, -1);
            let skip = (self.code.len() - at) as u32;
            if let Inst::UnionChild { skip: s, .. } = &mut self.code[at] {
                *s = skip;
            }
        }
        self.code.push(Inst::UnionEnd { split });
    }

    /// A scatter with its templates compiled as nested programs; inside a
    /// template, through the tree.
    fn scatter(&mut self, node: &'a SdfNode, s: &'a Scatter, split: bool) {
        if self.nested {
            self.tree(node, split);
            return;
        }
        let templates = s
            .templates
            .iter()
            .map(|t| compile(t, false, true))
            .collect();
        self.code.push(Inst::Scatter {
            scatter: s,
            templates,
            split,
        });
        self.push(VALUES, 1);
    }

    /// `bounded` in split mode: the child always, then the box distance.
    fn bounded_split(&mut self, pad: f32, child: &'a SdfNode) {
        self.code.push(Inst::BoundedSplitBegin {
            bounds: child.bounds(),
        });
        self.push(WALLS, 1);
        self.node(child, true);
        self.code.push(Inst::BoundedSplitEnd { pad });
        self.push(WALLS, -1);
    }

    /// `bounded` in eval mode: the box distance, and the child in the lanes
    /// near the box.
    fn bounded(&mut self, material: u32, pad: f32, child: &'a SdfNode) {
        let at = self.code.len();
        self.code.push(Inst::BoundedBegin {
            bounds: child.bounds(),
            pad,
            material,
            skip: 0,
        });
        self.push(VALUES, 1);
        self.push(MASKS, 1);
        self.node(child, false);
        self.code.push(Inst::BoundedMerge);
        self.push(VALUES, -1);
        self.push(MASKS, -1);
        let skip = (self.code.len() - at) as u32;
        if let Inst::BoundedBegin { skip: s, .. } = &mut self.code[at] {
            *s = skip;
        }
    }

    fn intersection(&mut self, material: u32, children: &'a [SdfNode]) {
        self.code.push(Inst::IntersectionBegin { material });
        self.push(VALUES, 1);
        for c in children {
            self.node(c, false);
            self.code.push(Inst::IntersectionMerge);
            self.push(VALUES, -1);
        }
    }

    fn smooth_union(&mut self, k: f32, children: &'a [SdfNode]) {
        for (i, c) in children.iter().enumerate() {
            self.node(c, false);
            self.code.push(Inst::SmoothMerge { k, first: i == 0 });
            if i > 0 {
                self.push(VALUES, -1);
            }
        }
    }

    fn subtract(&mut self, a: &'a SdfNode, b: &'a SdfNode) {
        self.node(a, false);
        self.node(b, false);
        self.code.push(Inst::SubtractMerge);
        self.push(VALUES, -1);
    }

    fn mirror(&mut self, axes: [bool; 3], child: &'a SdfNode) {
        self.code.push(Inst::PushMirror { axes });
        self.push(POINTS, 1);
        self.node(child, false);
        self.code.push(Inst::PopPoint);
        self.push(POINTS, -1);
    }

    fn repeat(&mut self, r: &'a subcone_scene::sdf::Repeat, split: bool) {
        self.code.push(Inst::PushRepeat {
            period: r.period,
            lo: r.lo,
            hi: r.hi,
            guard: r.guard,
        });
        self.push(POINTS, 1);
        self.push(WALLS, 1);
        self.node(&r.child, split);
        self.code.push(Inst::PopRepeat {
            margin: r.margin,
            split,
        });
        self.push(POINTS, -1);
        self.push(WALLS, -1);
    }

    fn tree(&mut self, node: &'a SdfNode, split: bool) {
        self.tree_fallback = true;
        self.code.push(Inst::Tree { node, split });
        self.push(VALUES, 1);
    }
}

fn compile(root: &SdfNode, split: bool, nested: bool) -> SdfProgram<'_> {
    let mut c = Compiler {
        code: Vec::new(),
        now: [0, 1, 1, 0],
        max: [0, 1, 1, 0],
        nested,
        tree_fallback: false,
    };
    c.node(root, split);
    SdfProgram {
        code: c.code,
        depth: c.max,
        tree_fallback: c.tree_fallback,
    }
}

// ------------------------------------------------------------------ steps

// The interpreter's steps: one per instruction ([`Inst`] says what each
// does), each expanded into `SdfProgram::run`'s loop. Macros, not functions:
// expanded, they are exactly the loop body the interpreter always had. As
// methods of a struct holding the stacks, or as functions taking them (always
// inlined either way), the same steps changed the register allocation around
// the loop's dispatch: a few more register moves at every instruction, and the
// `primitives` scene took 5 % more CPU time on the AVX-512 path.
//
// Each takes the scratch stacks `s`, the stack tops it reads or moves (`vs`
// values on the stack, `ps` the current point, `ms` the current lane mask,
// `ws` walls kept), then the instruction's fields. Those that may skip a
// subtree also take `pc`, and `continue` the loop themselves.

macro_rules! leaf {
    ($s:ident, $vs:ident, $ps:ident; $leaf:ident) => {{
        let d = $leaf.distance(&$s.points[$ps]);
        $s.values[$vs] = Value::both(d, [$leaf.material; LANES]);
        $vs += 1;
    }};
}

macro_rules! union_leaf {
    ($s:ident, $vs:ident, $ps:ident, $ms:ident; $sphere:ident, $leaf:ident, $split:ident) => {{
        let p = &$s.points[$ps];
        let acc = &mut $s.values[$vs - 1];
        let lanes = cull($sphere, p, acc, $s.masks[$ms], *$split);
        if lanes.any() {
            let d = $leaf.distance(p);
            if *$split {
                acc.safe = lanes.select(acc.safe.min(d), acc.safe);
            }
            let better = lanes.and(W8::from_fn(|k| d.0[k] < acc.surf.0[k]));
            acc.surf = better.select(d, acc.surf);
            acc.mat = better.select_u([$leaf.material; LANES], acc.mat);
            if !*$split {
                acc.safe = acc.surf;
            }
        }
    }};
}

macro_rules! push_transform {
    ($s:ident, $ps:ident; $translation:ident, $inv_scale:ident, $inv_rotation:ident) => {{
        let p = $s.points[$ps];
        let mut q = p
            .sub(V3::splat(*$translation))
            .scale(F8::splat(*$inv_scale));
        if let Some(r) = $inv_rotation {
            q = q.rotate(*r);
        }
        $ps += 1;
        $s.points[$ps] = q;
    }};
}

macro_rules! pop_transform {
    ($s:ident, $vs:ident, $ps:ident; $scale:ident) => {{
        $ps -= 1;
        let v = &mut $s.values[$vs - 1];
        v.safe = v.safe * *$scale;
        v.surf = v.surf * *$scale;
    }};
}

macro_rules! push_mirror {
    ($s:ident, $ps:ident; $axes:ident) => {{
        let p = $s.points[$ps];
        let mut q = p;
        if $axes[0] {
            q.x = q.x.abs();
        }
        if $axes[1] {
            q.y = q.y.abs();
        }
        if $axes[2] {
            q.z = q.z.abs();
        }
        $ps += 1;
        $s.points[$ps] = q;
    }};
}

/// `Repeat::cell`: the point in its cell and, with `guard`, the distance to
/// the walls that have a neighbouring cell (∞ otherwise).
macro_rules! push_repeat {
    ($s:ident, $ps:ident, $ws:ident; $period:ident, $lo:ident, $hi:ident, $guard:ident) => {{
        let p = $s.points[$ps];
        let mut q = [p.x, p.y, p.z];
        let mut wall = F8::splat(f32::INFINITY);
        for (k, qk) in q.iter_mut().enumerate() {
            let c = $period[k];
            if c > 0.0 {
                let i = round_cell(*qk / c).clamp(F8::splat($lo[k]), F8::splat($hi[k]));
                let pk = *qk;
                *qk = pk - c * i;
                if *$guard {
                    let below = i.lt(F8::splat($hi[k]));
                    wall = F8::select(below, wall.min(0.5 * c - *qk), wall);
                    let above = i.gt(F8::splat($lo[k]));
                    wall = F8::select(above, wall.min(0.5 * c + *qk), wall);
                }
            }
        }
        $ps += 1;
        $s.points[$ps] = V3::new(q[0], q[1], q[2]);
        $s.walls[$ws] = wall;
        $ws += 1;
    }};
}

macro_rules! pop_repeat {
    ($s:ident, $vs:ident, $ps:ident, $ws:ident; $margin:ident, $split:ident) => {{
        $ps -= 1;
        $ws -= 1;
        let g = $s.walls[$ws] + *$margin;
        let v = &mut $s.values[$vs - 1];
        if *$split {
            v.safe = v.safe.min(g);
        } else {
            let d = F8::select(g.lt(v.surf), g, v.surf);
            v.safe = d;
            v.surf = d;
        }
    }};
}

macro_rules! union_begin {
    ($s:ident, $vs:ident; $material:ident) => {{
        let inf = F8::splat(f32::INFINITY);
        $s.values[$vs] = Value {
            safe: inf,
            surf: inf,
            mat: [*$material; LANES],
        };
        $vs += 1;
    }};
}

/// Culls the next child: skips it (`$skip` on, past its merge) when no lane
/// needs it, else pushes the lanes that do as the current mask.
macro_rules! union_child {
    ($s:ident, $vs:ident, $ps:ident, $ms:ident, $pc:ident; $sphere:ident, $skip:ident, $split:ident) => {{
        let p = $s.points[$ps];
        let acc = &mut $s.values[$vs - 1];
        let needed = cull($sphere, &p, acc, $s.masks[$ms], *$split);
        if !needed.any() {
            $pc += *$skip as usize;
            continue;
        }
        $ms += 1;
        $s.masks[$ms] = needed;
    }};
}

macro_rules! union_merge {
    ($s:ident, $vs:ident, $ms:ident; $split:ident) => {{
        $vs -= 1;
        let c = $s.values[$vs];
        let lanes = $s.masks[$ms];
        $ms -= 1;
        let acc = &mut $s.values[$vs - 1];
        if *$split {
            acc.safe = lanes.select(acc.safe.min(c.safe), acc.safe);
        }
        let better = lanes.and(W8::from_fn(|k| c.surf.0[k] < acc.surf.0[k]));
        acc.surf = better.select(c.surf, acc.surf);
        acc.mat = better.select_u(c.mat, acc.mat);
        if !*$split {
            acc.safe = acc.surf;
        }
    }};
}

macro_rules! union_end {
    ($s:ident, $vs:ident; $split:ident) => {{
        let acc = &mut $s.values[$vs - 1];
        if *$split {
            acc.safe = acc.safe.min(acc.surf);
        } else {
            acc.safe = acc.surf;
        }
    }};
}

macro_rules! intersection_merge {
    ($s:ident, $vs:ident) => {{
        $vs -= 1;
        let c = $s.values[$vs];
        let acc = &mut $s.values[$vs - 1];
        *acc = Value::select(c.surf.gt(acc.surf), c, *acc);
    }};
}

macro_rules! smooth_merge {
    ($s:ident, $vs:ident; $k:ident, $first:ident) => {{
        if !*$first {
            $vs -= 1;
            let c = $s.values[$vs];
            let acc = &mut $s.values[$vs - 1];
            let k = *$k;
            let h = (k - (acc.surf - c.surf).abs()).max(F8::splat(0.0)) / k;
            let mat = c.surf.lt(acc.surf).select_u(c.mat, acc.mat);
            let d = acc.surf.min(c.surf) - 0.25 * k * h * h;
            *acc = Value::both(d, mat);
        }
    }};
}

macro_rules! subtract_merge {
    ($s:ident, $vs:ident) => {{
        $vs -= 1;
        let b = $s.values[$vs];
        let a = $s.values[$vs - 1];
        let nb = -b.surf;
        $s.values[$vs - 1] = Value::select(a.surf.ge(nb), a, Value::both(nb, b.mat));
    }};
}

/// Pushes the box distance; skips the child (`$skip` on, past its merge)
/// when no lane is near enough to need it, else pushes the lanes that do as
/// the current mask.
macro_rules! bounded_begin {
    ($s:ident, $vs:ident, $ps:ident, $ms:ident, $pc:ident; $bounds:ident, $pad:ident, $material:ident, $skip:ident) => {{
        let p = $s.points[$ps];
        let b = aabb_distance($bounds, p);
        $s.values[$vs] = Value::both(b, [*$material; LANES]);
        $vs += 1;
        let needed = $s.masks[$ms].and_not(W8::from_fn(|k| b.0[k] > *$pad));
        if !needed.any() {
            $pc += *$skip as usize;
            continue;
        }
        $ms += 1;
        $s.masks[$ms] = needed;
    }};
}

macro_rules! bounded_merge {
    ($s:ident, $vs:ident, $ms:ident) => {{
        $vs -= 1;
        let c = $s.values[$vs];
        let lanes = $s.masks[$ms];
        $ms -= 1;
        let acc = &mut $s.values[$vs - 1];
        *acc = Value::select(lanes, c, *acc);
    }};
}

macro_rules! bounded_split_end {
    ($s:ident, $vs:ident, $ws:ident; $pad:ident) => {{
        $ws -= 1;
        let b = $s.walls[$ws];
        let v = &mut $s.values[$vs - 1];
        let far = b.gt(F8::splat(*$pad));
        v.safe = F8::select(far, v.safe.max(b).min(v.surf), v.safe);
    }};
}

/// What has no lane-wise form: the tree, lane by lane.
macro_rules! tree {
    ($s:ident, $vs:ident, $ps:ident, $ms:ident; $node:ident, $split:ident) => {{
        let p = $s.points[$ps];
        let mut v = Value::default();
        let m = $s.masks[$ms].bits();
        for k in 0..LANES {
            if m & (1 << k) == 0 {
                continue;
            }
            let q = Vec3::new(p.x.0[k], p.y.0[k], p.z.0[k]);
            let (a, b, mat) = if *$split {
                let r = $node.eval_split(q);
                (r.safe, r.surface, r.material)
            } else {
                let (d, mat) = $node.eval(q);
                (d, d, mat)
            };
            v.safe.0[k] = a;
            v.surf.0[k] = b;
            v.mat[k] = mat;
        }
        $s.values[$vs] = v;
        $vs += 1;
    }};
}

macro_rules! scatter {
    ($s:ident, $vs:ident, $ps:ident, $ms:ident, $nested:ident; $scatter:ident, $templates:ident, $split:ident) => {{
        let p = $s.points[$ps];
        let v = if $nested {
            // Never compiled: nested scatters fall back to the tree.
            Value::default()
        } else {
            scatter_lanes(
                $scatter,
                $templates,
                p,
                $s.masks[$ms].bits(),
                &mut $s.nested,
                *$split,
            )
        };
        $s.values[$vs] = v;
        $vs += 1;
    }};
}

impl<'a> SdfProgram<'a> {
    /// Compiles `root` for [`SdfNode::eval_split`]'s values.
    pub fn compile(root: &'a SdfNode) -> SdfProgram<'a> {
        compile(root, true, false)
    }

    /// Number of instructions.
    pub fn len(&self) -> usize {
        self.code.len()
    }

    /// Whether the program is empty (never, for a compiled tree).
    pub fn is_empty(&self) -> bool {
        self.code.is_empty()
    }

    /// Whether some subtree has no lane-wise form and is evaluated lane by
    /// lane through the tree (displacement, a scatter inside a scatter).
    pub fn has_tree_fallback(&self) -> bool {
        self.tree_fallback
    }

    /// Stacks sized for this program.
    pub fn scratch(&self) -> Scratch {
        let nested = self
            .code
            .iter()
            .filter_map(|i| match i {
                Inst::Scatter { templates, .. } => Some(templates),
                _ => None,
            })
            .flatten()
            .map(|t| t.depth)
            .reduce(|a, b| core::array::from_fn(|k| a[k].max(b[k])));
        let mut s = Scratch::with_depth(self.depth);
        s.nested = nested.map(|d| Box::new(Scratch::with_depth(d)));
        s
    }

    /// The tree's [`SdfNode::eval_split`] at each lane's point, bit for bit
    /// (a NaN may carry another payload).
    /// Lanes outside `active` hold unspecified values (they are computed
    /// where that is cheaper than not; nothing panics). `scratch` must come
    /// from this program's [`scratch`](Self::scratch); another program's
    /// may panic.
    #[inline(always)]
    pub fn eval_split(&self, p: &Points, active: LaneMask, scratch: &mut Scratch) -> SplitLanes {
        let v = self.run::<false>(V3::new(F8(p.x), F8(p.y), F8(p.z)), active, scratch);
        SplitLanes {
            safe: v.safe.0,
            surface: v.surf.0,
            material: v.mat,
        }
    }

    /// [`eval_split`](Self::eval_split) as one out-of-line function, compiled
    /// once in this crate: for callers off the hot path (tests, tools,
    /// fuzzing), each of which would otherwise compile the whole interpreter
    /// into itself at every call site. A hot loop calls `eval_split`, so that
    /// the interpreter is compiled into the loop, on its instruction set.
    #[inline(never)]
    pub fn eval_split_outlined(
        &self,
        p: &Points,
        active: LaneMask,
        scratch: &mut Scratch,
    ) -> SplitLanes {
        self.eval_split(p, active, scratch)
    }

    /// One point in lane 0: [`SdfNode::eval_split`] at `p`.
    pub fn eval_split_one(&self, p: Vec3, scratch: &mut Scratch) -> SplitDistance {
        let mut pts = Points::default();
        for k in 0..LANES {
            pts.set(k, p);
        }
        self.eval_split_outlined(&pts, 1, scratch).get(0)
    }

    /// The interpreter. `NESTED` programs (scatter templates) never contain
    /// a scatter, so the two instantiations do not recurse and both inline
    /// into the caller's loop.
    #[inline(always)]
    fn run<const NESTED: bool>(&self, p: V3, active: LaneMask, s: &mut Scratch) -> Value {
        let (mut vs, mut ps, mut ms, mut ws) = (0usize, 0usize, 0usize, 0usize);
        s.points[0] = p;
        s.masks[0] = W8::of_bits(active);
        let code = &self.code;
        let mut pc = 0;
        while pc < code.len() {
            match &code[pc] {
                Inst::Leaf(leaf) => leaf!(s, vs, ps; leaf),
                Inst::UnionLeaf {
                    sphere,
                    leaf,
                    split,
                } => union_leaf!(s, vs, ps, ms; sphere, leaf, split),
                Inst::PushTransform {
                    translation,
                    inv_scale,
                    inv_rotation,
                } => push_transform!(s, ps; translation, inv_scale, inv_rotation),
                Inst::PopTransform { scale } => pop_transform!(s, vs, ps; scale),
                Inst::PushMirror { axes } => push_mirror!(s, ps; axes),
                Inst::PopPoint => ps -= 1,
                Inst::PushRepeat {
                    period,
                    lo,
                    hi,
                    guard,
                } => push_repeat!(s, ps, ws; period, lo, hi, guard),
                Inst::PopRepeat { margin, split } => pop_repeat!(s, vs, ps, ws; margin, split),
                Inst::UnionBegin { material } => union_begin!(s, vs; material),
                Inst::UnionChild {
                    sphere,
                    skip,
                    split,
                } => union_child!(s, vs, ps, ms, pc; sphere, skip, split),
                Inst::UnionMerge { split } => union_merge!(s, vs, ms; split),
                Inst::UnionEnd { split } => union_end!(s, vs; split),
                Inst::IntersectionBegin { material } => {
                    s.values[vs] = Value::both(F8::splat(f32::NEG_INFINITY), [*material; LANES]);
                    vs += 1;
                }
                Inst::IntersectionMerge => intersection_merge!(s, vs),
                Inst::SmoothMerge { k, first } => smooth_merge!(s, vs; k, first),
                Inst::SubtractMerge => subtract_merge!(s, vs),
                Inst::Round { radius } => {
                    let v = &mut s.values[vs - 1];
                    *v = Value::both(v.surf - *radius, v.mat);
                }
                Inst::Onion { thickness } => {
                    let v = &mut s.values[vs - 1];
                    *v = Value::both(v.surf.abs() - *thickness, v.mat);
                }
                Inst::ScaleDistance { factor } => {
                    let v = &mut s.values[vs - 1];
                    *v = Value::both(v.surf * *factor, v.mat);
                }
                Inst::BoundedBegin {
                    bounds,
                    pad,
                    material,
                    skip,
                } => bounded_begin!(s, vs, ps, ms, pc; bounds, pad, material, skip),
                Inst::BoundedMerge => bounded_merge!(s, vs, ms),
                Inst::BoundedSplitBegin { bounds } => {
                    let p = s.points[ps];
                    s.walls[ws] = aabb_distance(bounds, p);
                    ws += 1;
                }
                Inst::BoundedSplitEnd { pad } => bounded_split_end!(s, vs, ws; pad),
                Inst::Scatter {
                    scatter,
                    templates,
                    split,
                } => scatter!(s, vs, ps, ms, NESTED; scatter, templates, split),
                Inst::Tree { node, split } => tree!(s, vs, ps, ms; node, split),
            }
            pc += 1;
        }
        s.values[0]
    }
}

/// A union's bound culling of one child against the accumulator `acc`, in
/// the `active` lanes: the lanes that must evaluate the child. A split union takes the skipped child's sphere distance
/// into its safe step, as the tree does.
#[inline(always)]
fn cull(sphere: &Vec4, p: &V3, acc: &mut Value, active: W8, split: bool) -> W8 {
    let c = V3::splat(sphere.truncate());
    let d2 = {
        let e = p.sub(c);
        e.dot(e)
    };
    let reach = acc.surf + sphere.w;
    // `&`, not `&&`: lane-wise masks without branches.
    let skipped = active.and(W8::from_fn(|k| {
        (reach.0[k] >= 0.0) & (d2.0[k] >= reach.0[k] * reach.0[k])
    }));
    if split && skipped.any() {
        let bound = d2.sqrt() - sphere.w;
        acc.safe = skipped.select(acc.safe.min(bound), acc.safe);
    }
    active.and_not(skipped)
}

/// `Scatter::split` (or its `eval` bound) lane-wise: each lane's cell and
/// instance, then each distinct template among the lanes that reach their
/// object, run once over those lanes.
#[inline(always)]
fn scatter_lanes(
    sc: &Scatter,
    templates: &[SdfProgram<'_>],
    p: V3,
    active: LaneMask,
    nested: &mut Option<Box<Scratch>>,
    split: bool,
) -> Value {
    let rel = p.sub(V3::splat(sc.origin));
    let f = rel.mul(V3::splat(sc.inv_cell));
    let f = V3::new(round_cell(f.x), round_cell(f.y), round_cell(f.z));
    // glam's `clamp`: `max(lo).min(hi)` by comparisons.
    let lo = V3::splat(sc.lo);
    let hi = V3::splat(sc.hi);
    let f = {
        let m = f.gmax(lo);
        V3::new(m.x.gmin(hi.x), m.y.gmin(hi.y), m.z.gmin(hi.z))
    };
    let q = rel.sub(f.mul(V3::splat(sc.cell)));
    let mut wall = F8::splat(f32::INFINITY);
    let (fa, qa) = ([f.x, f.y, f.z], [q.x, q.y, q.z]);
    for k in 0..3 {
        let below = fa[k].lt(F8::splat(sc.hi[k]));
        wall = F8::select(below, wall.min(0.5 * sc.cell[k] - qa[k]), wall);
        let above = fa[k].gt(F8::splat(sc.lo[k]));
        wall = F8::select(above, wall.min(0.5 * sc.cell[k] + qa[k]), wall);
    }
    let guard = wall + sc.margin;
    let i = f.sub(lo);

    // The cell's index: `i` is clamped to the grid (NaN to its first cell),
    // so every term is an integer below 2¹⁸ and exact in `f32`.
    let idx: [i32; LANES] = {
        let f = i.x + sc.dims[0] as f32 * (i.y + sc.dims[1] as f32 * i.z);
        each_lane!(|k| f.0[k] as i32)
    };
    // Gather each lane's instance: a lane with none (inactive, outside the
    // table, or an unknown template) reads `NONE`, whose zeros are what the
    // lanes without an instance carry. Each field is built lane by lane in
    // registers, not stored per lane and reloaded as a vector (which stalls
    // store forwarding).
    const EMPTY: u32 = u32::MAX;
    const NONE: Instance = Instance {
        template: EMPTY,
        material: EMPTY,
        inv_rotation: Quat::from_xyzw(0.0, 0.0, 0.0, 0.0),
        offset: Vec3::ZERO,
        scale: 0.0,
        inv_scale: 0.0,
        radius: 0.0,
    };
    let lookup = |k: usize| match sc.instances.get(idx[k] as usize) {
        Some(i) if (i.template as usize) < sc.templates.len() => i,
        _ => &NONE,
    };
    // Neighbouring rays are mostly in one cell: when every active lane is,
    // its instance is read once and broadcast (the same values in every
    // lane, so the same bits as the lane-by-lane gather).
    let lead = (active.trailing_zeros() as usize).min(LANES - 1);
    let shared = (0..LANES).all(|k| active & (1 << k) == 0 || idx[k] == idx[lead]);
    let one = shared.then(|| lookup(lead));
    let act = W8::of_bits(active);
    let inst: [&Instance; LANES] = each_lane!(|k| {
        if active & (1 << k) == 0 {
            &NONE
        } else if let Some(i) = one {
            i
        } else {
            lookup(k)
        }
    });
    let field = |f: fn(&Instance) -> f32| match one {
        Some(i) => act.select(F8::splat(f(i)), F8::splat(f(&NONE))),
        None => F8(each_lane!(|k| f(inst[k]))),
    };
    let off = [
        field(|i| i.offset.x),
        field(|i| i.offset.y),
        field(|i| i.offset.z),
    ];
    let rot = [
        field(|i| i.inv_rotation.x),
        field(|i| i.inv_rotation.y),
        field(|i| i.inv_rotation.z),
        field(|i| i.inv_rotation.w),
    ];
    let (radius, scale, inv_scale) = (
        field(|i| i.radius),
        field(|i| i.scale),
        field(|i| i.inv_scale),
    );
    let template: [u32; LANES] = each_lane!(|k| inst[k].template);
    let inst_mat: [u32; LANES] = each_lane!(|k| inst[k].material);
    let own: [u32; LANES] = each_lane!(|k| {
        if inst_mat[k] != EMPTY {
            inst_mat[k]
        } else {
            sc.default_material
        }
    });
    let local = q.sub(V3::new(off[0], off[1], off[2]));
    let sphere = local.length() - radius;
    let has = W8::from_fn(|k| template[k] != EMPTY);
    // No instance: `(guard, ∞, default)`; far from the object: its sphere.
    let mut out = Value {
        safe: guard,
        surf: F8::select(has, sphere, F8::splat(f32::INFINITY)),
        mat: own,
    };
    let reach = active & has.and_not(sphere.ge(guard)).bits();
    if reach != 0 {
        let tp = local.rotate_lanes(rot).scale(inv_scale);
        let scratch = nested.get_or_insert_with(|| {
            let d = templates
                .iter()
                .map(|t| t.depth)
                .fold([0; 4], |a, b| core::array::from_fn(|k| a[k].max(b[k])));
            Box::new(Scratch::with_depth(d))
        });
        let mut left = reach;
        while left != 0 {
            let first = left.trailing_zeros() as usize;
            let t = template[first];
            let mut lanes = 0u8;
            for (k, tk) in template.iter().enumerate() {
                if left & (1 << k) != 0 && *tk == t {
                    lanes |= 1 << k;
                }
            }
            left &= !lanes;
            let Some(prog) = templates.get(t as usize) else {
                continue;
            };
            let v = prog.run::<true>(tp, lanes, scratch);
            let d = v.surf * scale;
            let m = W8::from_fn(|k| inst_mat[k] == EMPTY).select_u(v.mat, inst_mat);
            let sel = W8::of_bits(lanes);
            out.safe = F8::select(sel, guard.min(d), out.safe);
            out.surf = F8::select(sel, d, out.surf);
            out.mat = sel.select_u(m, out.mat);
        }
    }
    if !split {
        // `eval`: the bound alone.
        out.surf = out.safe;
    }
    out
}

impl Scratch {
    fn with_depth(depth: [usize; 4]) -> Scratch {
        Scratch {
            values: vec![Value::default(); depth[VALUES] + 1],
            points: vec![V3::default(); depth[POINTS] + 1],
            masks: vec![W8::default(); depth[MASKS] + 1],
            walls: vec![F8::default(); depth[WALLS] + 1],
            nested: None,
        }
    }
}
