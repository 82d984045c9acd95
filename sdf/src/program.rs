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

use glam::{Quat, Vec3, Vec4};

use subcone_scene::sdf::lane::Lane;
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

#[macro_use]
mod lanes;

use lanes::{aabb_distance, round_cell, shape_distance, F8, M8, V3, W8};

mod compile;
mod scatter;

use compile::{compile, MASKS, POINTS, VALUES, WALLS};
use scatter::{cull, scatter_lanes};

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
