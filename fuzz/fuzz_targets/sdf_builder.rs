//! An arbitrary program of `SdfNode` builder calls (every primitive, every
//! operator, with raw f32 parameters including NaN, ±∞ and huge values), then
//! `SdfScene::new` / `Scene::sdf` and evaluations at arbitrary points.
//!
//! Asserted for every input: no panic; invalid parameters are `SdfError`
//! values; `depth() ≤ MAX_DEPTH`; the material `eval` returns is one of
//! `materials_used()` and at most `max_material()`, at any point (NaN too);
//! `normal`, `normal_central` and `normal_surface` are finite unit vectors at
//! any point and step; a scene accepts exactly the trees whose materials
//! exist, and `Scene::sdf` accepts every scene `SdfScene::new` built; the
//! tree's compiled program (`sdf::program`) gives `eval_split`'s values bit
//! for bit (NaN payloads aside) in every lane, at any point, with any lanes
//! active.
//!
//! Asserted inside the documented domain of `SdfNode` ("for finite `p`, with
//! `|p|` and every size well inside f32 range, say below 10¹⁸"): `eval` and
//! the split's step are finite, its surface distance finite or +∞ (no object
//! evaluated: a scatter's empty cell), and the split's step never exceeds
//! its surface distance; a point outside the bounding box is outside the
//! surface; an exact tree is 1-Lipschitz. The harness decides "inside the
//! domain" conservatively from every parameter the program used: the sum of
//! all lengths times every magnification and demagnification (scales, cell
//! folds, ellipsoid radii, scatter sizes, distance factors, frequencies) must
//! stay below 10¹⁵.
#![no_main]

use arbitrary::Arbitrary;
use glam::{Quat, Vec3};
use libfuzzer_sys::fuzz_target;
use subcone_scene::sdf::{Exactness, ScatterConfig, SdfError, SdfNode, SdfScene, MAX_DEPTH};
use subcone_scene::{Camera, Light, Material, Scene};

/// A parameter: raw bits, a tame value (`i / 256`), or a special value.
#[derive(Arbitrary, Debug, Clone, Copy)]
enum P {
    Raw(f32),
    Tame(i16),
    Special(u8),
}

const SPECIAL: [f32; 14] = [
    0.0,
    -0.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    1e30,
    -1e30,
    f32::MAX,
    f32::MIN_POSITIVE,
    1e-30,
    1.0,
    -1.0,
    0.5,
    1e-45,
];

impl P {
    fn get(self) -> f32 {
        match self {
            P::Raw(x) => x,
            P::Tame(i) => i as f32 / 256.0,
            P::Special(k) => SPECIAL[k as usize % SPECIAL.len()],
        }
    }
}

fn v3(p: [P; 3]) -> Vec3 {
    Vec3::new(p[0].get(), p[1].get(), p[2].get())
}

fn quat(p: [P; 4]) -> Quat {
    Quat::from_xyzw(p[0].get(), p[1].get(), p[2].get(), p[3].get())
}

#[derive(Arbitrary, Debug)]
enum ShapeArgs {
    Sphere(P),
    Cuboid([P; 3]),
    RoundBox([P; 3], P),
    BoxFrame([P; 3], P),
    Torus(P, P),
    Link(P, P, P),
    Capsule(P, P),
    Cylinder(P, P),
    RoundedCylinder(P, P, P),
    CappedCone(P, P, P),
    Octahedron(P),
    HexPrism(P, P),
    Ellipsoid([P; 3]),
    Plane([P; 3], P),
}

#[derive(Arbitrary, Debug)]
struct Scatter {
    origin: [P; 3],
    cell: [P; 3],
    lo: [i8; 3],
    span: [u8; 3],
    seed: u64,
    fill: P,
    margin: P,
    min_size: P,
    max_size: P,
    rotate: bool,
    jitter: bool,
    palette: Vec<u8>,
    templates: u8,
}

#[derive(Arbitrary, Debug)]
enum Op {
    Shape(ShapeArgs),
    Union(u8),
    Intersection(u8),
    SmoothUnion(P, u8),
    Subtract,
    Translate([P; 3]),
    Rotate([P; 4]),
    Scale(P),
    Transform([P; 3], [P; 4], P),
    Mirror([bool; 3]),
    Repeat([P; 3]),
    RepeatLimited([P; 3], [i32; 3], [i32; 3]),
    Round(P),
    Onion(P),
    ScaleDistance(P),
    Displace(P, P),
    Bounded(P),
    Scatter(Scatter),
    Material(u8),
    Dup,
}

#[derive(Arbitrary, Debug)]
struct Input {
    ops: Vec<Op>,
    points: Vec<[P; 3]>,
    step: P,
    materials: u8,
    eye: [P; 3],
    target: [P; 3],
    fov: P,
    light: Option<([P; 3], [P; 3])>,
}

/// Most builder calls run per input, nodes alive at once (a `Dup` of a
/// union doubles it), and points evaluated.
const MAX_OPS: usize = 64;
const MAX_NODES: usize = 4096;
const MAX_POINTS: usize = 16;
/// The domain bound (see the module docs).
const DOMAIN: f64 = 1e15;

/// The harness's conservative magnitude bookkeeping, in f64.
struct Domain {
    /// Sum of every length used.
    lengths: f64,
    /// Product of every magnification (≥ 1).
    up: f64,
    /// Product of every demagnification (≥ 1).
    down: f64,
}

impl Domain {
    fn length(&mut self, v: f32) {
        self.lengths += (v as f64).abs();
    }
    fn lengths(&mut self, v: Vec3) {
        for c in v.to_array() {
            self.length(c);
        }
    }
    /// A factor that multiplies lengths (or the point) by `f`.
    fn factor(&mut self, f: f32) {
        let f = (f as f64).abs();
        if f > 1.0 {
            self.up *= f;
        } else if f > 0.0 {
            self.down /= f;
        } else if f.is_nan() || f == 0.0 {
            self.down = f64::INFINITY;
        }
    }
    /// Whether `p` lies inside the domain.
    fn contains(&self, p: Vec3) -> Option<f64> {
        let m = (self.lengths + p.abs().max_element() as f64 + 1.0) * self.up * self.down;
        (p.is_finite() && m.is_finite() && m < DOMAIN).then_some(m)
    }
}

struct Item {
    node: SdfNode,
    /// Nodes in the tree (an estimate: union flattening keeps it exact enough).
    size: usize,
}

fn shape(a: &ShapeArgs, dom: &mut Domain) -> Result<SdfNode, SdfError> {
    match *a {
        ShapeArgs::Sphere(r) => {
            dom.length(r.get());
            SdfNode::sphere(r.get())
        }
        ShapeArgs::Cuboid(h) => {
            dom.lengths(v3(h));
            SdfNode::cuboid(v3(h))
        }
        ShapeArgs::RoundBox(h, r) => {
            dom.lengths(v3(h));
            dom.length(r.get());
            SdfNode::round_box(v3(h), r.get())
        }
        ShapeArgs::BoxFrame(h, t) => {
            dom.lengths(v3(h));
            dom.length(t.get());
            SdfNode::box_frame(v3(h), t.get())
        }
        ShapeArgs::Torus(a, b) => {
            dom.length(a.get());
            dom.length(b.get());
            SdfNode::torus(a.get(), b.get())
        }
        ShapeArgs::Link(a, b, c) => {
            dom.lengths(v3([a, b, c]));
            SdfNode::link(a.get(), b.get(), c.get())
        }
        ShapeArgs::Capsule(a, b) => {
            dom.length(a.get());
            dom.length(b.get());
            SdfNode::capsule(a.get(), b.get())
        }
        ShapeArgs::Cylinder(a, b) => {
            dom.length(a.get());
            dom.length(b.get());
            SdfNode::cylinder(a.get(), b.get())
        }
        ShapeArgs::RoundedCylinder(a, b, c) => {
            dom.lengths(v3([a, b, c]));
            SdfNode::rounded_cylinder(a.get(), b.get(), c.get())
        }
        ShapeArgs::CappedCone(a, b, c) => {
            dom.lengths(v3([a, b, c]));
            SdfNode::capped_cone(a.get(), b.get(), c.get())
        }
        ShapeArgs::Octahedron(s) => {
            dom.length(s.get());
            SdfNode::octahedron(s.get())
        }
        ShapeArgs::HexPrism(a, b) => {
            dom.length(a.get());
            dom.length(b.get());
            SdfNode::hex_prism(a.get(), b.get())
        }
        ShapeArgs::Ellipsoid(r) => {
            let r = v3(r);
            dom.lengths(r);
            // `p / r²` is evaluated.
            let m = r.abs().min_element();
            dom.factor(m);
            dom.factor(m);
            SdfNode::ellipsoid(r)
        }
        ShapeArgs::Plane(n, o) => {
            dom.length(o.get());
            SdfNode::plane(v3(n), o.get())
        }
    }
}

/// Take the top `n` items (at least one; `None` when the stack is empty).
fn pop_n(stack: &mut Vec<Item>, n: u8) -> Option<(Vec<SdfNode>, usize)> {
    if stack.is_empty() {
        return None;
    }
    let n = (n as usize % 4 + 1).min(stack.len());
    let items = stack.split_off(stack.len() - n);
    let size = items.iter().map(|i| i.size).sum::<usize>() + 1;
    Some((items.into_iter().map(|i| i.node).collect(), size))
}

fn run(op: &Op, stack: &mut Vec<Item>, dom: &mut Domain) -> Result<(), SdfError> {
    let unary = |stack: &mut Vec<Item>,
                 f: &mut dyn FnMut(SdfNode) -> Result<SdfNode, SdfError>|
     -> Result<(), SdfError> {
        if let Some(it) = stack.pop() {
            let node = f(it.node)?;
            stack.push(Item {
                node,
                size: it.size + 1,
            });
        }
        Ok(())
    };
    match op {
        Op::Shape(a) => {
            let node = shape(a, dom)?;
            stack.push(Item { node, size: 1 });
        }
        Op::Union(n) | Op::Intersection(n) | Op::SmoothUnion(_, n) => {
            let Some((children, size)) = pop_n(stack, *n) else {
                return Ok(());
            };
            let node = match op {
                Op::Union(_) => SdfNode::union(children)?,
                Op::Intersection(_) => SdfNode::intersection(children)?,
                Op::SmoothUnion(k, _) => {
                    dom.length(k.get());
                    SdfNode::smooth_union(k.get(), children)?
                }
                _ => unreachable!(),
            };
            stack.push(Item { node, size });
        }
        Op::Subtract => {
            if stack.len() >= 2 {
                let b = stack.pop().unwrap();
                let a = stack.pop().unwrap();
                let node = a.node.subtract(b.node)?;
                stack.push(Item {
                    node,
                    size: a.size + b.size + 1,
                });
            }
        }
        Op::Translate(t) => {
            dom.lengths(v3(*t));
            unary(stack, &mut |n| n.translate(v3(*t)))?;
        }
        Op::Rotate(q) => unary(stack, &mut |n| n.rotate(quat(*q)))?,
        Op::Scale(s) => {
            dom.factor(s.get());
            unary(stack, &mut |n| n.scale(s.get()))?;
        }
        Op::Transform(t, q, s) => {
            dom.lengths(v3(*t));
            dom.factor(s.get());
            unary(stack, &mut |n| n.transform(v3(*t), quat(*q), s.get()))?;
        }
        Op::Mirror(axes) => unary(stack, &mut |n| n.mirror(*axes))?,
        Op::Repeat(c) => {
            dom.lengths(v3(*c));
            // The cell fold maps `p` to at most `|p| + period`: 2× is generous.
            dom.factor(2.0);
            unary(stack, &mut |n| n.repeat(v3(*c)))?;
        }
        Op::RepeatLimited(c, lo, hi) => {
            // Instances sit at up to `period · max(|lo|, |hi|)`.
            let reach = Vec3::from_array(std::array::from_fn(|k| {
                (lo[k] as f32).abs().max((hi[k] as f32).abs()) + 1.0
            }));
            dom.lengths(v3(*c) * reach);
            dom.factor(2.0);
            unary(stack, &mut |n| n.repeat_limited(v3(*c), *lo, *hi))?;
        }
        Op::Round(r) => {
            dom.length(r.get());
            unary(stack, &mut |n| n.round(r.get()))?;
        }
        Op::Onion(t) => {
            dom.length(t.get());
            unary(stack, &mut |n| n.onion(t.get()))?;
        }
        Op::ScaleDistance(f) => {
            dom.factor(f.get());
            unary(stack, &mut |n| n.scale_distance(f.get()))?;
        }
        Op::Displace(a, f) => {
            dom.length(a.get());
            dom.factor(f.get().max(1.0));
            unary(stack, &mut |n| n.displace(a.get(), f.get()))?;
        }
        Op::Bounded(pad) => {
            dom.length(pad.get());
            unary(stack, &mut |n| n.bounded(pad.get()))?;
        }
        Op::Scatter(s) => {
            let Some((templates, size)) = pop_n(stack, s.templates) else {
                return Ok(());
            };
            let lo = s.lo.map(|v| v as i32);
            let hi = std::array::from_fn(|k| lo[k] + (s.span[k] % 8) as i32);
            let cell = v3(s.cell);
            let config = ScatterConfig {
                origin: v3(s.origin),
                cell,
                lo,
                hi,
                seed: s.seed,
                fill: s.fill.get(),
                margin: s.margin.get(),
                min_size: s.min_size.get(),
                max_size: s.max_size.get(),
                rotate: s.rotate,
                jitter: s.jitter,
                palette: s.palette.iter().map(|&m| m as u32 % 8).collect(),
            };
            dom.lengths(config.origin);
            dom.lengths(cell * 136.0);
            dom.length(config.margin);
            // An object of radius `u·R` from a template of radius `r_t`:
            // scaled by `u·R / r_t`, evaluated at `(p − c) · r_t / (u·R)`.
            let r = 0.5 * cell.abs().min_element() - config.margin.abs();
            let u = config.min_size.abs();
            for t in &templates {
                let rt = t.bounds().radius_about_origin();
                dom.factor(u * r / rt);
                dom.factor(r / rt);
                dom.length(rt);
            }
            let node = SdfNode::scatter(config, templates)?;
            stack.push(Item { node, size });
        }
        Op::Material(m) => unary(stack, &mut |n| Ok(n.with_material(*m as u32 % 8)))?,
        Op::Dup => {
            if let Some(top) = stack.last() {
                if top.size <= MAX_NODES / 2 && stack.len() < 16 {
                    let node = top.node.clone();
                    let size = top.size;
                    stack.push(Item { node, size });
                }
            }
        }
    }
    Ok(())
}

fn unit(n: Vec3) -> bool {
    n.is_finite() && (n.length() - 1.0).abs() < 1e-4
}

fn check_tree(node: &SdfNode, input: &Input, dom: &Domain) {
    assert!(node.depth() <= MAX_DEPTH, "depth {}", node.depth());
    let used = node.materials_used();
    assert!(!used.is_empty(), "a tree without materials");
    assert_eq!(used.last().copied(), Some(node.max_material()), "{used:?}");
    let _ = (
        node.exactness(),
        node.is_conservative(),
        node.object_count(),
    );
    let bounds = node.bounds();
    let h = input.step.get();
    let points: Vec<Vec3> = input
        .points
        .iter()
        .take(MAX_POINTS)
        .map(|p| v3(*p))
        .collect();
    check_program(node, &points);
    for (i, &p) in points.iter().enumerate() {
        let (d, m) = node.eval(p);
        assert!(used.contains(&m), "eval({p}) material {m} not in {used:?}");
        let subcone_scene::sdf::SplitDistance {
            safe,
            surface,
            material: m2,
        } = node.eval_split(p);
        assert!(
            used.contains(&m2),
            "eval_split({p}) material {m2} not in {used:?}"
        );
        for n in [
            node.normal(p, h),
            node.normal_central(p, h),
            node.normal_surface(p, h),
        ] {
            assert!(unit(n), "normal at {p} with step {h}: {n}");
        }
        let Some(mag) = dom.contains(p) else {
            continue;
        };
        assert!(
            d.is_finite(),
            "eval({p}) = {d} inside the domain (magnitude {mag:e})"
        );
        // The surface distance is +∞ where no object is evaluated (a
        // scatter's empty cell, `SplitDistance::surface`), never NaN or −∞.
        assert!(
            safe.is_finite() && (surface.is_finite() || surface == f32::INFINITY),
            "eval_split({p}) = ({safe}, {surface}) inside the domain"
        );
        // Rounding: a few ulps of the largest magnitude involved.
        let tol = (mag * 1e-5) as f32;
        assert!(
            safe <= surface + tol,
            "eval_split({p}): step {safe} > surface {surface}"
        );
        if bounds.is_finite() && bounds.min.cmple(bounds.max).all() {
            let outside = bounds.distance(p);
            assert!(
                outside <= tol || d > -tol,
                "{p} is {outside} outside the bounds {bounds:?} but eval = {d}"
            );
        }
        if node.exactness() == Exactness::Exact {
            // 1-Lipschitz, against the next point and a point nearby.
            let near = p + 1e-3 * Vec3::new(1.0, -0.5, 0.25) * (1.0 + p.abs().max_element());
            let next = points.get(i + 1).copied().unwrap_or(near);
            for q in [near, next] {
                let Some(mag_q) = dom.contains(q) else {
                    continue;
                };
                let dq = node.eval(q).0;
                let tol = (mag.max(mag_q) * 1e-5) as f32;
                assert!(
                    (d - dq).abs() <= p.distance(q) * 1.0001 + tol,
                    "exact tree not 1-Lipschitz: f({p}) = {d}, f({q}) = {dq}, |p - q| = {}",
                    p.distance(q)
                );
            }
        }
    }
}

/// The compiled program against the tree, eight points at a time (the
/// points rotated through the lanes, every other lane inactive in odd
/// packets).
fn check_program(node: &SdfNode, points: &[Vec3]) {
    use subcone_sdf::program::{Points, SdfProgram, LANES};
    if points.is_empty() {
        return;
    }
    let program = SdfProgram::compile(node);
    let mut scratch = program.scratch();
    for start in 0..points.len() {
        let mut pts = Points::default();
        for k in 0..LANES {
            pts.set(k, points[(start + k) % points.len()]);
        }
        let active = if start % 2 == 0 { 0xff } else { 0x55 };
        let out = program.eval_split_outlined(&pts, active, &mut scratch);
        for k in (0..LANES).filter(|k| active & (1 << k) != 0) {
            let want = node.eval_split(pts.get(k));
            let got = out.get(k);
            assert!(
                got.same_bits(&want),
                "program at {}: {got:?}, tree: {want:?}",
                pts.get(k)
            );
        }
    }
}

fn check_scene(root: SdfNode, input: &Input) {
    let count = input.materials as usize % 10;
    let materials: Vec<Material> = (0..count)
        .map(|i| Material::diffuse(&format!("m{i}"), Vec3::splat(0.5)))
        .collect();
    let lights: Vec<Light> = input
        .light
        .iter()
        .map(|(p, c)| Light::Point {
            position: v3(*p),
            intensity: v3(*c),
        })
        .collect();
    let Ok(camera) = Camera::look_at(v3(input.eye), v3(input.target), Vec3::Y, input.fov.get())
    else {
        return;
    };
    let max = root.max_material() as usize;
    let lights_ok = lights.iter().all(Light::is_finite);
    match SdfScene::new("fuzz", root, materials, lights, camera) {
        Ok(scene) => {
            assert!(
                max < count.max(1),
                "material {max} accepted with {count} materials"
            );
            assert!(lights_ok, "a non-finite light accepted");
            let s = Scene::sdf(scene).expect("Scene::sdf refused a valid SdfScene");
            assert!(s.sdf_geometry().is_some());
            let _ = s.features();
        }
        Err(SdfError::Material { index, count: c }) => {
            assert_eq!(index as usize, max);
            assert!(max >= c, "material {max} refused with {c} materials");
        }
        Err(SdfError::Scene { .. }) => assert!(!lights_ok, "valid lights refused"),
        Err(e) => panic!("unexpected scene error: {e}"),
    }
}

fuzz_target!(|input: Input| {
    let mut stack: Vec<Item> = Vec::new();
    let mut dom = Domain {
        lengths: 0.0,
        up: 1.0,
        down: 1.0,
    };
    for op in input.ops.iter().take(MAX_OPS) {
        if let Err(e) = run(op, &mut stack, &mut dom) {
            // Errors are values with a message; the operands are consumed.
            assert!(!e.to_string().is_empty());
        }
        if stack.iter().map(|i| i.size).sum::<usize>() > MAX_NODES {
            break;
        }
    }
    let Some(top) = stack.pop() else {
        return;
    };
    check_tree(&top.node, &input, &dom);
    check_scene(top.node, &input);
});
