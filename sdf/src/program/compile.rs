//! [`SdfProgram::compile`]'s compiler: the tree walked once into the
//! program's instructions, with the stack depths they reach.

use super::*;

struct Compiler<'a> {
    code: Vec<Inst<'a>>,
    /// Current and deepest stack depths: values, points, masks, walls.
    now: [usize; 4],
    max: [usize; 4],
    nested: bool,
    tree_fallback: bool,
}

pub(super) const VALUES: usize = 0;
pub(super) const POINTS: usize = 1;
pub(super) const MASKS: usize = 2;
pub(super) const WALLS: usize = 3;

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

pub(super) fn compile(root: &SdfNode, split: bool, nested: bool) -> SdfProgram<'_> {
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
