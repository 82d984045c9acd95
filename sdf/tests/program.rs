//! The flat SDF program ([`SdfProgram`]) against the tree it was compiled
//! from: every lane's `(safe, surface, material)` must equal
//! [`SdfNode::eval_split`] bit for bit, on every built-in SDF scene, on the
//! example scene files, and on a tree with every shape and operator.
//! The program is called through `eval_split_outlined`, `eval_split` compiled
//! once in the library, so this test does not compile the interpreter again.

use glam::{Quat, Vec3};
use subcone_scene::builtin::{sdf_builtin, SDF_SCENES, STIFF_SCENES};
use subcone_scene::sdf::{ScatterConfig, SdfNode, SplitDistance};
use subcone_sdf::program::{Points, SdfProgram, SplitLanes, LANES};

/// A small deterministic generator (no dependency, same points every run).
struct Rng(u64);
impl Rng {
    fn unit(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }
}

/// Each active lane of the program's `out` at `pts` is the tree's value
/// there, as `same` judges; returns how many lanes were compared.
fn assert_lanes(
    name: &str,
    tree: &SdfNode,
    pts: &Points,
    active: u8,
    out: &SplitLanes,
    same: impl Fn(&SplitDistance, &SplitDistance) -> bool,
) -> usize {
    let mut compared = 0;
    for k in (0..LANES).filter(|k| active & (1 << k) != 0) {
        compared += 1;
        let p = pts.get(k);
        let want = tree.eval_split(p);
        let got = out.get(k);
        assert!(
            same(&want, &got),
            "{name}: lane {k} at {p:?}: the tree gives {want:?}, the program {got:?}"
        );
    }
    compared
}

/// Compare the program with the tree at `n` packets of points: points
/// scattered over `lo..hi`, half of every packet clustered (as a packet of
/// neighbouring rays is), with random active masks.
fn check(name: &str, tree: &SdfNode, lo: Vec3, hi: Vec3, n: usize) {
    let program = SdfProgram::compile(tree);
    let mut scratch = program.scratch();
    let mut rng = Rng(0x5eed ^ name.len() as u64);
    let mut evaluated = 0;
    for i in 0..n {
        let mut pts = Points::default();
        let centre = lo + (hi - lo) * Vec3::new(rng.unit(), rng.unit(), rng.unit());
        for k in 0..LANES {
            let p = if k % 2 == 0 {
                centre + Vec3::new(rng.unit(), rng.unit(), rng.unit()) * 0.05
            } else {
                lo + (hi - lo) * Vec3::new(rng.unit(), rng.unit(), rng.unit())
            };
            pts.set(k, p);
        }
        let active = if i % 3 == 0 {
            0xff
        } else {
            (rng.unit() * 256.0) as u8 | 1
        };
        let out = program.eval_split_outlined(&pts, active, &mut scratch);
        evaluated += assert_lanes(name, tree, &pts, active, &out, |want, got| {
            want.safe.to_bits() == got.safe.to_bits()
                && want.surface.to_bits() == got.surface.to_bits()
                && want.material == got.material
        });
    }
    assert!(evaluated > n, "{name}: too few lanes compared");
}

#[test]
fn program_equals_tree_on_builtin_scenes() {
    for name in SDF_SCENES
        .iter()
        .chain(STIFF_SCENES.iter())
        .chain(["glass"].iter())
    {
        let scene = sdf_builtin(name).unwrap().unwrap();
        let b = scene.root.bounds();
        // The scene's bounds (clipped where unbounded) and the camera.
        let c = scene.camera.position;
        let lo = b.min.max(c - Vec3::splat(30.0)).min(c);
        let hi = b.max.min(c + Vec3::splat(30.0)).max(c);
        check(name, &scene.root, lo, hi, 3000);
    }
}

fn every_operator() -> SdfNode {
    let s = |x: Result<SdfNode, _>| x.unwrap();
    let shapes = vec![
        s(SdfNode::sphere(0.8)),
        s(SdfNode::cuboid(Vec3::new(0.6, 0.4, 0.5))),
        s(SdfNode::round_box(Vec3::splat(0.6), 0.1)),
        s(SdfNode::box_frame(Vec3::splat(0.6), 0.1)),
        s(SdfNode::torus(0.6, 0.2)),
        s(SdfNode::link(0.3, 0.35, 0.12)),
        s(SdfNode::capsule(0.4, 0.3)),
        s(SdfNode::cylinder(0.5, 0.6)),
        s(SdfNode::rounded_cylinder(0.6, 0.5, 0.1)),
        s(SdfNode::capped_cone(0.6, 0.6, 0.2)),
        s(SdfNode::octahedron(0.8)),
        s(SdfNode::hex_prism(0.5, 0.6)),
        s(SdfNode::ellipsoid(Vec3::new(0.8, 0.4, 0.6))),
    ];
    let placed: Vec<SdfNode> = shapes
        .into_iter()
        .enumerate()
        .map(|(i, n)| {
            let at = Vec3::new((i % 5) as f32 * 2.0 - 4.0, 1.0, (i / 5) as f32 * 2.0 - 2.0);
            s(s(n.rotate(Quat::from_rotation_y(0.3 * i as f32))).translate(at))
                .with_material(i as u32)
        })
        .collect();
    let ops = vec![
        s(SdfNode::intersection(vec![
            s(SdfNode::sphere(1.0)),
            s(SdfNode::cuboid(Vec3::splat(0.8))),
        ])),
        s(SdfNode::smooth_union(
            0.3,
            vec![
                s(SdfNode::sphere(0.5)),
                s(s(SdfNode::torus(0.7, 0.2)).translate(Vec3::Y * 0.3)),
            ],
        )),
        s(s(SdfNode::cuboid(Vec3::splat(0.7))).subtract(s(SdfNode::sphere(0.85)))),
        s(
            s(s(SdfNode::sphere(0.3)).translate(Vec3::new(0.5, 0.2, 0.4)))
                .mirror([true, false, true]),
        ),
        s(s(SdfNode::sphere(0.2)).repeat(Vec3::new(1.0, 0.0, 1.0))),
        s(
            s(s(SdfNode::cuboid(Vec3::new(0.2, 0.3, 0.1))).rotate(Quat::from_rotation_z(0.4)))
                .repeat_limited(Vec3::splat(0.9), [-2, -2, -2], [2, 2, 2]),
        ),
        s(s(SdfNode::cuboid(Vec3::splat(0.5))).round(0.1)),
        s(s(SdfNode::sphere(0.6)).onion(0.05)),
        s(s(SdfNode::sphere(0.6)).scale_distance(0.5)),
        s(s(SdfNode::sphere(0.6)).displace(0.05, 8.0)),
        s(s(SdfNode::torus(0.5, 0.15)).bounded(0.2)),
        s(s(SdfNode::cuboid(Vec3::splat(0.5))).scale(1.7)),
        s(SdfNode::scatter(
            ScatterConfig::new(Vec3::splat(1.0), [-2, 0, -2], [2, 1, 2], 7),
            vec![
                s(SdfNode::cuboid(Vec3::splat(0.4))),
                s(SdfNode::torus(0.3, 0.1)),
            ],
        )),
    ];
    let placed_ops: Vec<SdfNode> = ops
        .into_iter()
        .enumerate()
        .map(|(i, n)| {
            let at = Vec3::new((i % 5) as f32 * 3.0 - 6.0, 1.0, (i / 5) as f32 * 3.0 + 4.0);
            s(n.translate(at)).with_material(20 + i as u32)
        })
        .collect();
    let mut all = vec![s(SdfNode::plane(Vec3::Y, 0.0))];
    all.extend(placed);
    all.push(s(SdfNode::union(placed_ops)));
    s(SdfNode::union(all))
}

#[test]
fn program_equals_tree_on_every_shape_and_operator() {
    let tree = every_operator();
    check(
        "every operator",
        &tree,
        Vec3::new(-9.0, -1.0, -5.0),
        Vec3::new(9.0, 4.0, 14.0),
        20000,
    );
    let program = SdfProgram::compile(&tree);
    assert!(
        program.has_tree_fallback(),
        "displacement is evaluated through the tree"
    );
}

#[test]
fn non_finite_points_do_not_panic() {
    let tree = every_operator();
    let program = SdfProgram::compile(&tree);
    let mut scratch = program.scratch();
    let mut pts = Points::default();
    let bad = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        -f32::MAX,
        0.0,
        -0.0,
        1e30,
    ];
    for k in 0..LANES {
        pts.set(
            k,
            Vec3::new(bad[k], bad[(k + 3) % LANES], bad[(k + 5) % LANES]),
        );
    }
    let out = program.eval_split_outlined(&pts, 0xff, &mut scratch);
    assert_lanes(
        "every operator",
        &tree,
        &pts,
        0xff,
        &out,
        SplitDistance::same_bits,
    );
}
