//! The SDF scene model: exact distances, bounds, tags, validation, built-in
//! scenes, precision far away, repetition and normals.

use std::f32::consts::FRAC_PI_2;

use glam::{Quat, Vec3};
use subcone_kernels::passes::SceneFeatures;
use subcone_scene::builtin::{sdf_builtin, SDF_SCENES, STIFF_SCENES};
use subcone_scene::sdf::{
    Exactness, ScatterConfig, SdfError, SdfNode, SdfScene, Shape, FAR_ORIGIN_SHIFT, MAX_DEPTH,
};
use subcone_scene::{Camera, Material};

/// A minimal f64 vector for references (the workspace's glam has no f64 types).
#[derive(Clone, Copy, Debug)]
struct D3([f64; 3]);

impl D3 {
    const ZERO: D3 = D3([0.0; 3]);
    fn new(x: f64, y: f64, z: f64) -> D3 {
        D3([x, y, z])
    }
    fn splat(v: f64) -> D3 {
        D3([v; 3])
    }
    fn map2(self, o: D3, f: impl Fn(f64, f64) -> f64) -> D3 {
        D3(std::array::from_fn(|k| f(self.0[k], o.0[k])))
    }
    fn abs(self) -> D3 {
        D3(self.0.map(f64::abs))
    }
    fn max(self, o: D3) -> D3 {
        self.map2(o, f64::max)
    }
    fn max_element(self) -> f64 {
        self.0[0].max(self.0[1]).max(self.0[2])
    }
    fn length_squared(self) -> f64 {
        self.0.iter().map(|v| v * v).sum()
    }
    fn length(self) -> f64 {
        self.length_squared().sqrt()
    }
    fn as_vec3(self) -> Vec3 {
        Vec3::new(self.0[0] as f32, self.0[1] as f32, self.0[2] as f32)
    }
}

impl std::ops::Sub for D3 {
    type Output = D3;
    fn sub(self, o: D3) -> D3 {
        self.map2(o, |a, b| a - b)
    }
}

impl std::ops::Add for D3 {
    type Output = D3;
    fn add(self, o: D3) -> D3 {
        self.map2(o, |a, b| a + b)
    }
}

impl std::ops::Mul for D3 {
    type Output = D3;
    fn mul(self, o: D3) -> D3 {
        self.map2(o, |a, b| a * b)
    }
}

impl std::ops::Div for D3 {
    type Output = D3;
    fn div(self, o: D3) -> D3 {
        self.map2(o, |a, b| a / b)
    }
}

fn d3(v: Vec3) -> D3 {
    D3::new(v.x as f64, v.y as f64, v.z as f64)
}

/// xorshift64*, so the tests need no extra dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }
    fn vec(&mut self, r: f32) -> Vec3 {
        Vec3::new(self.range(-r, r), self.range(-r, r), self.range(-r, r))
    }
}

fn exact_primitives() -> Vec<(&'static str, SdfNode)> {
    vec![
        ("sphere", SdfNode::sphere(0.8).unwrap()),
        ("box", SdfNode::cuboid(Vec3::new(0.5, 0.8, 0.3)).unwrap()),
        (
            "round box",
            SdfNode::round_box(Vec3::new(0.6, 0.5, 0.7), 0.2).unwrap(),
        ),
        (
            "box frame",
            SdfNode::box_frame(Vec3::new(0.6, 0.5, 0.7), 0.1).unwrap(),
        ),
        ("torus", SdfNode::torus(0.7, 0.2).unwrap()),
        ("link", SdfNode::link(0.3, 0.4, 0.1).unwrap()),
        ("capsule", SdfNode::capsule(0.5, 0.3).unwrap()),
        ("cylinder", SdfNode::cylinder(0.4, 0.6).unwrap()),
        (
            "rounded cylinder",
            SdfNode::rounded_cylinder(0.5, 0.6, 0.15).unwrap(),
        ),
        ("capped cone", SdfNode::capped_cone(0.6, 0.7, 0.2).unwrap()),
        (
            "inverted capped cone",
            SdfNode::capped_cone(0.5, 0.1, 0.6).unwrap(),
        ),
        ("octahedron", SdfNode::octahedron(0.9).unwrap()),
        ("hex prism", SdfNode::hex_prism(0.5, 0.7).unwrap()),
        (
            "plane",
            SdfNode::plane(Vec3::new(0.3, 1.0, -0.2), 0.4).unwrap(),
        ),
    ]
}

fn gradient(node: &SdfNode, p: Vec3, h: f32) -> Vec3 {
    let f = |q: Vec3| node.distance(q) as f64;
    let g = |a: Vec3| ((f(p + a * h) - f(p - a * h)) / (2.0 * h as f64)) as f32;
    Vec3::new(g(Vec3::X), g(Vec3::Y), g(Vec3::Z))
}

// ------------------------------------------------------------- exactness

#[test]
fn sphere_and_box_match_analytic_distances() {
    let mut rng = Rng(1);
    let sphere = SdfNode::sphere(1.3).unwrap();
    let half = D3::new(0.5, 1.0, 0.25);
    let cube = SdfNode::cuboid(half.as_vec3()).unwrap();
    for _ in 0..5000 {
        let p = rng.vec(4.0);
        let pd = d3(p);
        let ds = pd.length() - 1.3;
        assert!((sphere.distance(p) as f64 - ds).abs() < 1e-5, "{p}");
        // Box: outside, the distance to the clamped point; inside, minus the
        // distance to the nearest face.
        let q = pd.abs() - half;
        let db = if q.max_element() > 0.0 {
            q.max(D3::ZERO).length()
        } else {
            q.max_element()
        };
        assert!((cube.distance(p) as f64 - db).abs() < 1e-5, "{p}");
    }
}

#[test]
fn transforms_are_exact() {
    // Scale, rotate, translate a unit sphere: the distance of a sphere of
    // radius s at c.
    let node = SdfNode::sphere(1.0)
        .unwrap()
        .scale(2.5)
        .unwrap()
        .rotate(Quat::from_rotation_y(0.7))
        .unwrap()
        .translate(Vec3::new(1.0, -2.0, 3.0))
        .unwrap();
    assert!(node.is_exact());
    let mut rng = Rng(2);
    for _ in 0..1000 {
        let p = rng.vec(8.0);
        let want = (p - Vec3::new(1.0, -2.0, 3.0)).length() - 2.5;
        assert!((node.distance(p) - want).abs() < 2e-5, "{p}");
    }
    // A rotated box matches the box evaluated in its own frame.
    let r = Quat::from_euler(glam::EulerRot::XYZ, 0.3, -0.8, 1.2);
    let half = Vec3::new(0.3, 0.6, 0.9);
    let b = SdfNode::cuboid(half)
        .unwrap()
        .rotate(r)
        .unwrap()
        .translate(Vec3::X)
        .unwrap();
    let local = Shape::Box { half };
    for _ in 0..1000 {
        let p = rng.vec(3.0);
        let want = local.distance(r.inverse() * (p - Vec3::X));
        assert!((b.distance(p) - want).abs() < 2e-5);
    }
}

#[test]
fn exact_primitives_have_unit_gradient_outside() {
    let mut rng = Rng(3);
    for (name, node) in exact_primitives() {
        assert!(node.is_exact(), "{name}");
        let mut checked = 0;
        let mut good = 0;
        while checked < 2000 {
            let p = rng.vec(2.5);
            if node.distance(p) < 0.02 {
                continue;
            }
            checked += 1;
            let g = gradient(&node, p, 1e-3).length();
            // Lipschitz 1 everywhere; unit almost everywhere (not on the
            // exterior medial axis, e.g. the axis of a torus).
            assert!(g < 1.01, "{name}: |∇f| = {g} at {p}");
            if (g - 1.0).abs() < 0.01 {
                good += 1;
            }
        }
        assert!(good >= 1980, "{name}: only {good}/2000 unit gradients");
    }
}

/// Exact distance to an ellipsoid from outside: the Lagrange condition
/// `Σ (p_i r_i / (r_i² + t))² = 1`, solved by bisection in f64.
fn ellipsoid_distance(p: D3, r: D3) -> f64 {
    let g = |t: f64| {
        let q = p * r / (r * r + D3::splat(t));
        q.length_squared() - 1.0
    };
    let (mut lo, mut hi) = (0.0, 1e3);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = 0.5 * (lo + hi);
    let x = p * r * r / (r * r + D3::splat(t));
    (p - x).length()
}

#[test]
fn ellipsoid_is_a_bound() {
    let mut rng = Rng(5);
    for radii in [
        Vec3::new(1.0, 0.5, 0.7),
        Vec3::new(1.5, 0.05, 0.8),
        Vec3::new(0.2, 2.0, 0.2),
    ] {
        let e = SdfNode::ellipsoid(radii).unwrap();
        assert_eq!(e.exactness(), Exactness::Bound);
        let mut n = 0;
        while n < 3000 {
            let p = rng.vec(2.0 * radii.max_element());
            let k0 = (p / radii).length();
            if k0 <= 1.0 {
                continue;
            }
            n += 1;
            let truth = ellipsoid_distance(d3(p), d3(radii));
            let d = e.distance(p) as f64;
            assert!(
                d <= truth + 1e-5 * (1.0 + truth),
                "{radii}: {d} > {truth} at {p}"
            );
            assert!(d > 0.0);
        }
        // Inside it is negative, and at the centre the smallest semi-axis.
        assert_eq!(e.distance(Vec3::ZERO), -radii.min_element());
    }
}

#[test]
fn exactness_tags() {
    let s = || SdfNode::sphere(1.0).unwrap();
    let b = || SdfNode::cuboid(Vec3::ONE).unwrap();
    let e = || SdfNode::ellipsoid(Vec3::new(1.0, 2.0, 0.5)).unwrap();
    for (_, node) in exact_primitives() {
        assert_eq!(node.exactness(), Exactness::Exact);
        assert!(node.is_conservative());
    }
    assert!(!e().is_exact());
    assert!(e().is_conservative());
    let union = SdfNode::union(vec![s(), b().translate(Vec3::X * 3.0).unwrap()]).unwrap();
    assert!(union.is_exact(), "union of exact is tagged exact (outside)");
    assert_eq!(
        SdfNode::union(vec![s(), e()]).unwrap().exactness(),
        Exactness::Bound
    );
    assert_eq!(s().subtract(b()).unwrap().exactness(), Exactness::Bound);
    assert_eq!(
        SdfNode::intersection(vec![s(), b()]).unwrap().exactness(),
        Exactness::Bound
    );
    assert_eq!(
        SdfNode::smooth_union(0.3, vec![s(), b()])
            .unwrap()
            .exactness(),
        Exactness::Bound
    );
    // Repetition: symmetric child exact, asymmetric child bound.
    let rep = s().repeat(Vec3::new(3.0, 0.0, 3.0)).unwrap();
    assert!(rep.is_exact());
    assert_eq!(rep.object_count(), None);
    let off = s()
        .translate(Vec3::new(0.3, 0.0, 0.0))
        .unwrap()
        .repeat(Vec3::new(3.0, 0.0, 3.0))
        .unwrap();
    assert_eq!(off.exactness(), Exactness::Bound);
    // Translation along a non-repeated axis keeps the symmetry that matters.
    let lifted = s()
        .translate(Vec3::Y * 2.0)
        .unwrap()
        .repeat_limited(Vec3::new(3.0, 0.0, 0.0), [-2, 0, 0], [2, 0, 0])
        .unwrap();
    assert!(lifted.is_exact());
    assert_eq!(lifted.object_count(), Some(5));
    // Mirror of a confined child is exact.
    let m = s()
        .translate(Vec3::X * 2.0)
        .unwrap()
        .mirror([true, false, false])
        .unwrap();
    assert!(m.is_exact());
    assert_eq!(m.object_count(), Some(2));
    // Non-Eikonal scaling: never exact; conservative only below 1.
    let slow = s().scale_distance(0.2).unwrap();
    assert_eq!(slow.exactness(), Exactness::NonEikonal);
    assert!(slow.is_conservative());
    let fast = s().scale_distance(5.0).unwrap();
    assert_eq!(fast.exactness(), Exactness::NonEikonal);
    assert!(!fast.is_conservative());
    assert!(!s().displace(0.1, 8.0).unwrap().is_conservative());
    assert!(s().scale_distance(1.0).unwrap().is_exact());
    // Onion: exact for a primitive, bound for a union.
    assert!(s().onion(0.1).unwrap().is_exact());
    assert!(!union.clone().onion(0.1).unwrap().is_exact());
    assert!(s().round(0.1).unwrap().is_exact());
    assert_eq!(union.bounded(0.5).unwrap().exactness(), Exactness::Bound);
}

#[test]
fn non_eikonal_gradients() {
    let mut rng = Rng(6);
    let slow = SdfNode::sphere(1.0).unwrap().scale_distance(0.2).unwrap();
    let fast = SdfNode::sphere(1.0).unwrap().scale_distance(5.0).unwrap();
    for _ in 0..200 {
        let p = rng.vec(3.0);
        if p.length() < 1.1 {
            continue;
        }
        assert!((gradient(&slow, p, 1e-3).length() - 0.2).abs() < 1e-3);
        assert!((gradient(&fast, p, 1e-3).length() - 5.0).abs() < 1e-2);
    }
}

// ------------------------------------------------------------ validation

#[test]
fn validation_errors() {
    assert!(matches!(
        SdfNode::sphere(f32::NAN),
        Err(SdfError::NonFinite { .. })
    ));
    assert!(matches!(
        SdfNode::sphere(f32::INFINITY),
        Err(SdfError::NonFinite { .. })
    ));
    assert!(matches!(
        SdfNode::sphere(-1.0),
        Err(SdfError::Negative { .. })
    ));
    assert!(matches!(
        SdfNode::cuboid(Vec3::new(1.0, -0.1, 1.0)),
        Err(SdfError::Negative { .. })
    ));
    assert!(matches!(
        SdfNode::cuboid(Vec3::new(1.0, f32::NAN, 1.0)),
        Err(SdfError::NonFinite { .. })
    ));
    assert!(SdfNode::round_box(Vec3::ONE, 1.5).is_err());
    assert!(SdfNode::ellipsoid(Vec3::new(1.0, 0.0, 1.0)).is_err());
    assert!(SdfNode::plane(Vec3::ZERO, 0.0).is_err());
    assert!(SdfNode::plane(Vec3::Y, f32::NAN).is_err());
    let s = || SdfNode::sphere(1.0).unwrap();
    assert!(matches!(s().scale(0.0), Err(SdfError::NonPositive { .. })));
    assert!(matches!(s().scale(-2.0), Err(SdfError::NonPositive { .. })));
    assert!(matches!(
        s().scale(f32::NAN),
        Err(SdfError::NonFinite { .. })
    ));
    assert!(s().translate(Vec3::new(f32::INFINITY, 0.0, 0.0)).is_err());
    assert!(s().rotate(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)).is_err());
    assert!(s()
        .rotate(Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0))
        .is_err());
    // A non-normalised quaternion is normalised.
    assert!(s().rotate(Quat::from_xyzw(0.0, 0.0, 0.0, 3.0)).is_ok());
    assert!(matches!(
        SdfNode::union(vec![]),
        Err(SdfError::Empty { .. })
    ));
    assert!(matches!(
        SdfNode::intersection(vec![]),
        Err(SdfError::Empty { .. })
    ));
    assert!(matches!(
        SdfNode::smooth_union(0.5, vec![]),
        Err(SdfError::Empty { .. })
    ));
    assert!(SdfNode::smooth_union(-0.5, vec![s()]).is_err());
    assert!(s().scale_distance(0.0).is_err());
    assert!(s().onion(-0.1).is_err());
    assert!(s().displace(f32::NAN, 1.0).is_err());
    // Repetition: overlapping cells, zero period, empty range.
    assert!(matches!(
        s().repeat(Vec3::new(1.5, 0.0, 0.0)),
        Err(SdfError::Overlap { .. })
    ));
    assert!(s().repeat(Vec3::ZERO).is_err());
    assert!(s().repeat(Vec3::new(-3.0, 0.0, 0.0)).is_err());
    assert!(s()
        .repeat_limited(Vec3::new(3.0, 0.0, 0.0), [2, 0, 0], [1, 0, 0])
        .is_err());
    assert!(SdfNode::plane(Vec3::X, 0.0)
        .unwrap()
        .repeat(Vec3::new(3.0, 0.0, 0.0))
        .is_err());
    // Mirror of a child crossing the plane.
    assert!(matches!(
        s().mirror([true, false, false]),
        Err(SdfError::Overlap { .. })
    ));
    // Bounded of an unbounded child.
    assert!(SdfNode::plane(Vec3::Y, 0.0).unwrap().bounded(1.0).is_err());
    // Depth limit: each round adds a level.
    let mut node = s();
    let mut err = None;
    for _ in 0..MAX_DEPTH + 5 {
        match node.clone().round(0.0) {
            Ok(n) => node = n,
            Err(e) => {
                err = Some(e);
                break;
            }
        }
    }
    assert!(matches!(err, Some(SdfError::TooDeep { .. })));
    assert_eq!(node.depth(), MAX_DEPTH);
    // Messages say what to fix.
    let msg = SdfNode::sphere(-1.0).unwrap_err().to_string();
    assert!(msg.contains("sphere") && msg.contains("radius"), "{msg}");
}

#[test]
fn scene_validation() {
    let cam = Camera::look_at(Vec3::Z * 5.0, Vec3::ZERO, Vec3::Y, 0.9).unwrap();
    let root = SdfNode::sphere(1.0).unwrap().with_material(3);
    let mats = vec![Material::diffuse("a", Vec3::ONE)];
    assert!(matches!(
        SdfScene::new("x", root.clone(), mats.clone(), vec![], cam),
        Err(SdfError::Material { index: 3, count: 1 })
    ));
    let ok = SdfScene::new(
        "x",
        root.clone().with_material(0),
        mats.clone(),
        vec![],
        cam,
    )
    .unwrap();
    assert_eq!(ok.name(), "x");
    assert!(ok.features().is_empty());
    let mut bad = ok.clone();
    bad.max_distance = f32::NAN;
    assert!(bad.validate().is_err());
    let mut bad = ok.clone();
    bad.max_steps = 0;
    assert!(bad.validate().is_err());
    let mut bad = ok;
    bad.camera.fov_y = 0.0;
    assert!(matches!(bad.validate(), Err(SdfError::Camera(_))));
}

#[test]
fn scatter_validation() {
    let t = || vec![SdfNode::cuboid(Vec3::ONE).unwrap()];
    let base = ScatterConfig::new(Vec3::splat(2.0), [0, 0, 0], [3, 0, 3], 7);
    assert!(SdfNode::scatter(base.clone(), t()).is_ok());
    assert!(SdfNode::scatter(base.clone(), vec![]).is_err());
    let mut c = base.clone();
    c.fill = 0.0;
    assert!(SdfNode::scatter(c, t()).is_err(), "no object");
    let mut c = base.clone();
    c.cell.x = 0.0;
    assert!(SdfNode::scatter(c, t()).is_err());
    let mut c = base.clone();
    c.margin = 1.0;
    assert!(SdfNode::scatter(c, t()).is_err(), "margin fills the cell");
    let mut c = base.clone();
    c.lo = [i32::MIN, 0, 0];
    c.hi = [i32::MAX, 0, 0];
    assert!(SdfNode::scatter(c, t()).is_err(), "too many cells");
    let mut c = base.clone();
    c.min_size = 0.0;
    assert!(SdfNode::scatter(c, t()).is_err());
    let mut c = base;
    c.fill = f32::NAN;
    assert!(SdfNode::scatter(c.clone(), t()).is_err());
    c.fill = 1.0;
    assert!(SdfNode::scatter(c, vec![SdfNode::plane(Vec3::Y, 0.0).unwrap()]).is_err());
}

/// `eval_split` in a scatter's empty cell: no surface (`+∞`), a finite
/// step bound; a full scatter has a surface in every cell.
#[test]
fn an_empty_scatter_cell_has_no_surface_and_a_finite_step() {
    let t = || vec![SdfNode::cuboid(Vec3::splat(0.5)).unwrap()];
    let centres =
        || (0..8).flat_map(|x| (0..8).map(move |z| Vec3::new(2.0 * x as f32, 0.0, 2.0 * z as f32)));
    let mut sparse = ScatterConfig::new(Vec3::splat(2.0), [0, 0, 0], [7, 0, 7], 3);
    sparse.fill = 0.3;
    let node = SdfNode::scatter(sparse, t()).unwrap();
    let (mut empty, mut full) = (0, 0);
    for p in centres() {
        let s = node.eval_split(p);
        assert!(s.safe.is_finite() && s.safe <= s.surface, "{p}: {s:?}");
        assert_eq!(s.safe, node.eval(p).0, "{p}");
        if s.surface == f32::INFINITY {
            empty += 1;
        } else {
            assert!(s.surface.is_finite(), "{p}: {s:?}");
            full += 1;
        }
    }
    assert!(
        empty > 0 && full > 0,
        "{empty} empty and {full} occupied cells"
    );
    let dense = ScatterConfig::new(Vec3::splat(2.0), [0, 0, 0], [7, 0, 7], 3);
    let node = SdfNode::scatter(dense, t()).unwrap();
    for p in centres() {
        let s = node.eval_split(p);
        assert!(s.safe.is_finite() && s.surface.is_finite(), "{p}: {s:?}");
    }
}

#[test]
fn arbitrary_parameters_never_panic() {
    let mut rng = Rng(7);
    let specials = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        1e-30,
        1e30,
        f32::MAX,
        f32::MIN_POSITIVE,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ];
    let pick = |rng: &mut Rng| {
        if rng.unit() < 0.5 {
            specials[(rng.next() % specials.len() as u64) as usize]
        } else {
            rng.range(-3.0, 3.0)
        }
    };
    for _ in 0..3000 {
        let a = pick(&mut rng);
        let b = pick(&mut rng);
        let c = pick(&mut rng);
        let shape = match rng.next() % 14 {
            0 => Shape::Sphere { radius: a },
            1 => Shape::Box {
                half: Vec3::new(a, b, c),
            },
            2 => Shape::RoundBox {
                half: Vec3::new(a, b, b),
                radius: c,
            },
            3 => Shape::BoxFrame {
                half: Vec3::new(a, a, b),
                thickness: c,
            },
            4 => Shape::Torus { major: a, minor: b },
            5 => Shape::Link {
                half_length: a,
                major: b,
                minor: c,
            },
            6 => Shape::Capsule {
                half_height: a,
                radius: b,
            },
            7 => Shape::Cylinder {
                radius: a,
                half_height: b,
            },
            8 => Shape::RoundedCylinder {
                radius: a,
                half_height: b,
                rounding: c,
            },
            9 => Shape::CappedCone {
                half_height: a,
                bottom: b,
                top: c,
            },
            10 => Shape::Octahedron { size: a },
            11 => Shape::HexPrism {
                apothem: a,
                half_height: b,
            },
            12 => Shape::Ellipsoid {
                radii: Vec3::new(a, b, c),
            },
            _ => Shape::Plane {
                normal: Vec3::new(a, b, c),
                offset: a,
            },
        };
        let Ok(node) = SdfNode::shape(shape) else {
            continue;
        };
        let e = pick(&mut rng);
        let node = match rng.next() % 4 {
            0 => node.scale(e),
            1 => node.translate(Vec3::new(e, 0.0, 0.0)),
            2 => node.repeat(Vec3::new(e.abs(), 0.0, 0.0)),
            _ => node.rotate(Quat::from_xyzw(e, 1.0, 0.0, 0.0)),
        };
        let Ok(node) = node else { continue };
        // Sizes up to 1e30 (or scales down to 1e-30) overflow lengths: finite
        // results are promised for moderate sizes only.
        let moderate = [a, b, c, e]
            .iter()
            .all(|v| !v.is_finite() || (v.abs() < 1e6 && (v.abs() > 1e-6 || *v == 0.0)));
        for _ in 0..10 {
            let p = rng.vec(5.0);
            let (d, m) = node.eval(p);
            assert_eq!(m, 0);
            if moderate && node.bounds().min.is_finite() {
                assert!(!d.is_nan(), "{shape:?} at {p}: {d}");
            }
            let n = node.normal(p, 1e-3);
            assert!(n.is_finite());
        }
    }
}

// --------------------------------------------------------- built-in scenes

#[test]
fn every_builtin_builds_and_evaluates() {
    assert!(sdf_builtin("no-such-scene").is_none());
    let mut rng = Rng(8);
    for name in SDF_SCENES.iter().chain(STIFF_SCENES.iter()) {
        let scene = sdf_builtin(name)
            .unwrap()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(scene.name(), *name);
        scene.validate().unwrap();
        scene.camera.validate().unwrap();
        assert!(scene.camera.position.is_finite());
        let _ = scene.exactness();
        assert_eq!(scene.is_exact(), scene.exactness() == Exactness::Exact);
        assert!(scene.root.object_count().unwrap_or(u64::MAX) >= 1);
        assert!((scene.root.max_material() as usize) < scene.materials.len());
        // The camera is outside every object.
        assert!(scene.root.distance(scene.camera.position) > 0.0, "{name}");
        // Points around the camera and through the view.
        let reach = scene.max_distance.min(200.0);
        for i in 0..1000 {
            let p = if i % 2 == 0 {
                scene.camera.position + rng.vec(reach)
            } else {
                let (o, d) = scene.camera.ray(
                    glam::Vec2::new(rng.range(0.0, 1280.0), rng.range(0.0, 720.0)),
                    1280,
                    720,
                );
                o + d * rng.range(0.0, scene.max_distance)
            };
            let (d, m) = scene.root.eval(p);
            assert!(d.is_finite(), "{name}: {d} at {p}");
            assert!((m as usize) < scene.materials.len(), "{name}: material {m}");
            let n = scene.root.normal(p, 1e-3);
            assert!((n.length() - 1.0).abs() < 1e-4, "{name}: {n}");
        }
    }
}

#[test]
fn builtin_tags_and_lights() {
    let get = |n: &str| sdf_builtin(n).unwrap().unwrap();
    assert!(get("primitives").is_exact());
    assert_eq!(get("primitives").root.object_count(), Some(13));
    assert!(get("grazing").is_exact());
    assert!(get("far").is_exact());
    for n in [
        "random-box",
        "random-shape",
        "sdf-atrium",
        "sparse-shape",
        "thin",
    ] {
        assert_eq!(get(n).exactness(), Exactness::Bound, "{n}");
        assert!(get(n).root.is_conservative(), "{n}");
    }
    let ne = get("non-eikonal");
    assert_eq!(ne.exactness(), Exactness::NonEikonal);
    assert!(!ne.root.is_conservative());
    // Many objects in the random scenes, few in the sparse one.
    for n in ["random-box", "random-shape"] {
        let c = get(n).root.object_count().unwrap();
        assert!((1000..3000).contains(&c), "{n}: {c}");
    }
    assert!(get("sparse-shape").root.object_count().unwrap() <= 10);
    // Lights: everywhere but `thin`.
    for name in SDF_SCENES.iter().chain(STIFF_SCENES.iter()) {
        let s = get(name);
        assert_eq!(
            s.features().contains(SceneFeatures::HAS_LIGHTS),
            *name != "thin",
            "{name}"
        );
        assert!(!s.features().contains(SceneFeatures::HAS_REFLECTIONS));
    }
    assert!(get("thin").lights.is_empty());
    assert!(get("primitives")
        .features()
        .contains(SceneFeatures::HAS_TEXTURES));
}

#[test]
fn builtins_are_deterministic() {
    for name in SDF_SCENES.iter().chain(STIFF_SCENES.iter()) {
        let a = sdf_builtin(name).unwrap().unwrap();
        let b = sdf_builtin(name).unwrap().unwrap();
        let mut rng = Rng(9);
        for _ in 0..200 {
            let p = a.camera.position + rng.vec(20.0);
            assert_eq!(a.root.eval(p), b.root.eval(p));
        }
    }
}

#[test]
fn camera_rays_hit_something_in_the_paper_scenes() {
    // Sphere trace the centre pixel: every paper scene has geometry there,
    // except the sparse one, which is mostly sky.
    for name in SDF_SCENES {
        let s = sdf_builtin(name).unwrap().unwrap();
        let mut hits = 0;
        for j in 0..9 {
            for i in 0..16 {
                let px = glam::Vec2::new(40.0 + 80.0 * i as f32, 40.0 + 80.0 * j as f32);
                let (o, d) = s.camera.ray(px, 1280, 720);
                let mut t = 0.0;
                for _ in 0..s.max_steps {
                    let dist = s.root.distance(o + d * t);
                    if dist < 1e-3 * (1.0 + t) {
                        hits += 1;
                        break;
                    }
                    t += dist;
                    if t > s.max_distance {
                        break;
                    }
                }
            }
        }
        if name == "sparse-shape" {
            assert!((1..72).contains(&hits), "{name}: {hits}/144");
        } else {
            assert!(hits >= 60, "{name}: {hits}/144");
        }
    }
}

// ---------------------------------------------------------------- far

#[test]
fn far_scene_keeps_precision_camera_relative() {
    let s = sdf_builtin("far").unwrap().unwrap();
    assert_eq!(s.camera.position, Vec3::ZERO);
    assert!(FAR_ORIGIN_SHIFT.length() > 1e7);
    assert!(s.max_distance >= 1e7);
    // Approach each object from the camera: at a gap δ in front of the
    // surface the field reads δ, within a few ulps of |p|.
    // Points inside the sphere, the box and the torus's tube.
    let targets = [
        Vec3::new(-4.0e4, -4.0e3, -1.0e5),
        Vec3::new(3.5e5, 5.0e4, -1.0e6),
        Vec3::new(-1.5e6 + 6.0e5, 2.0e6, -1.0e7),
    ];
    for c in targets {
        assert!(s.root.distance(c) < 0.0, "{c}");
        let dir = c.normalize();
        // Find the surface along the ray by bisection on the field.
        let (mut lo, mut hi) = (0.0f32, c.length());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if s.root.distance(dir * mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let t_hit = lo;
        let ulp = (t_hit.abs() * f32::EPSILON).max(1e-3);
        for gap in [10.0f32, 100.0, 1000.0] {
            let t = t_hit - gap;
            let d = s.root.distance(dir * t);
            // Oblique incidence: the distance is at most the gap along the ray
            // and, for these convex-ish targets, at least a good share of it.
            assert!(d <= gap + 8.0 * ulp, "{c}: gap {gap}, d {d}, t {t_hit}");
            assert!(d > 0.2 * gap - 8.0 * ulp, "{c}: gap {gap}, d {d}");
        }
    }
    // The sphere: exact reference in f64 at points around it.
    let c = D3::new(-4.0e4, -4.0e3, -1.0e5);
    let mut rng = Rng(10);
    for _ in 0..1000 {
        let p = d3(c.as_vec3() + rng.vec(2.0e4));
        let want = (p - c).length() - 8.0e3;
        if want > 2.0e4 {
            continue;
        }
        let got = s.root.distance(p.as_vec3()) as f64;
        // Nearer objects (the ground) may win; never exceed the sphere's.
        assert!(got <= want + 0.05, "{got} vs {want}");
        if got < want - 0.05 {
            continue;
        }
        assert!((got - want).abs() <= 0.05, "{got} vs {want}");
    }
    // Normals at the far torus are unit and face the camera.
    let hit = Vec3::new(-1.5e6 + 6.0e5, 2.0e6, -1.0e7).normalize();
    let mut t = 0.0;
    for _ in 0..s.max_steps {
        let d = s.root.distance(hit * t);
        if d < 1e-4 * t {
            break;
        }
        t += d;
    }
    let n = s.root.normal(hit * t, 0.25 * t * 1e-3);
    assert!((n.length() - 1.0).abs() < 1e-4);
    assert!(n.dot(hit) < 0.0, "{n}");
}

// ----------------------------------------------------------- repetition

/// Brute force: the minimum over all instances of a repetition.
fn brute_repeat(child: &SdfNode, period: Vec3, lo: [i32; 3], hi: [i32; 3], p: Vec3) -> f32 {
    let mut best = f32::INFINITY;
    for x in lo[0]..=hi[0] {
        for y in lo[1]..=hi[1] {
            for z in lo[2]..=hi[2] {
                let c = period * Vec3::new(x as f32, y as f32, z as f32);
                best = best.min(child.distance(p - c));
            }
        }
    }
    best
}

#[test]
fn repetition_never_overestimates() {
    let mut rng = Rng(11);
    let period = Vec3::new(2.0, 0.0, 3.0);
    let (lo, hi) = ([-3, 0, -2], [3, 0, 2]);
    let children = [
        // Asymmetric: off-centre, rotated, a cone.
        SdfNode::capped_cone(0.7, 0.6, 0.1)
            .unwrap()
            .rotate(Quat::from_rotation_x(0.8))
            .unwrap()
            .translate(Vec3::new(0.2, 0.0, -0.4))
            .unwrap(),
        SdfNode::sphere(0.3)
            .unwrap()
            .translate(Vec3::new(0.6, 0.3, 1.1))
            .unwrap(),
        SdfNode::cuboid(Vec3::new(0.9, 0.2, 0.1))
            .unwrap()
            .rotate(Quat::from_rotation_y(0.3))
            .unwrap(),
        // Symmetric: exact.
        SdfNode::cuboid(Vec3::new(0.9, 0.5, 1.4)).unwrap(),
        SdfNode::torus(0.6, 0.2).unwrap(),
    ];
    for child in children {
        let rep = child.clone().repeat_limited(period, lo, hi).unwrap();
        let mut near = 0;
        let mut tries = 0;
        while tries < 200_000 && near < 300 {
            tries += 1;
            // Half the points anywhere, half within the grid.
            let p = if tries % 2 == 0 {
                rng.vec(9.0)
            } else {
                Vec3::new(
                    rng.range(-7.0, 7.0),
                    rng.range(-1.5, 1.5),
                    rng.range(-7.5, 7.5),
                )
            };
            let truth = brute_repeat(&child, period, lo, hi, p);
            let d = rep.distance(p);
            assert!(d <= truth + 1e-5, "{d} > {truth} at {p}");
            if rep.is_exact() {
                assert!((d - truth).abs() < 1e-5, "exact: {d} vs {truth} at {p}");
            }
            // Same sign: inside one instance iff inside the repetition.
            assert_eq!(d < 0.0, truth < 0.0, "{p}");
            // Within the margin (≥ 0.1 for these children) of an instance
            // the guard cannot win: the value is the instance's own.
            if truth.abs() < 0.1 {
                near += 1;
                assert!((d - truth).abs() < 1e-5, "near: {d} vs {truth} at {p}");
            }
        }
        assert!(near == 300, "{near} points near the surface");
    }
    // Infinite repetition against a wide brute force near the origin.
    let child = SdfNode::sphere(0.4)
        .unwrap()
        .translate(Vec3::new(0.5, 0.0, 0.0))
        .unwrap();
    let rep = child.clone().repeat(Vec3::new(2.0, 2.0, 0.0)).unwrap();
    assert_eq!(rep.exactness(), Exactness::Bound);
    for _ in 0..2000 {
        let p = rng.vec(6.0);
        let truth = brute_repeat(&child, Vec3::new(2.0, 2.0, 0.0), [-8, -8, 0], [8, 8, 0], p);
        assert!(rep.distance(p) <= truth + 1e-5);
    }
}

#[test]
fn scatter_is_a_bound_with_cells_visited_once() {
    // Against sphere tracing: stepping by the field from outside never
    // crosses into an object (the sign stays positive until a hit).
    let s = sdf_builtin("random-shape").unwrap().unwrap();
    let mut rng = Rng(12);
    for _ in 0..300 {
        let (o, d) = s.camera.ray(
            glam::Vec2::new(rng.range(0.0, 1280.0), rng.range(0.0, 720.0)),
            1280,
            720,
        );
        let mut t = 0.0;
        for _ in 0..2000 {
            let dist = s.root.distance(o + d * t);
            assert!(dist >= -1e-4, "stepped inside: {dist}");
            if dist < 1e-4 || t > s.max_distance {
                break;
            }
            t += dist;
        }
    }
}

// ----------------------------------------------------------------- normals

#[test]
fn normals_are_unit_and_agree() {
    let mut rng = Rng(13);
    let sphere = SdfNode::sphere(1.0).unwrap();
    for _ in 0..1000 {
        let dir = rng.vec(1.0).normalize_or(Vec3::Y);
        let p = dir * 1.0001;
        let n4 = sphere.normal(p, 1e-3);
        let n6 = sphere.normal_central(p, 1e-3);
        assert!((n4.length() - 1.0).abs() < 1e-5);
        assert!((n6.length() - 1.0).abs() < 1e-5);
        assert!(n4.dot(dir) > 0.9999, "{n4} vs {dir}");
        assert!(n6.dot(dir) > 0.9999, "{n6} vs {dir}");
    }
    for name in SDF_SCENES {
        let s = sdf_builtin(name).unwrap().unwrap();
        for _ in 0..500 {
            let p = s.camera.position + rng.vec(10.0);
            for n in [s.root.normal(p, 1e-3), s.root.normal_central(p, 1e-3)] {
                assert!((n.length() - 1.0).abs() < 1e-4, "{name}: {n}");
            }
        }
    }
    // Degenerate inputs: a zero step is floored; a NaN step too.
    let n = sphere.normal(Vec3::new(0.0, 1.0, 0.0), 0.0);
    assert!((n - Vec3::Y).length() < 1e-3, "{n}");
    assert!(sphere.normal(Vec3::X, f32::NAN).is_finite());
    // The centre of a box has no gradient: the fallback is +y.
    let flat = SdfNode::cuboid(Vec3::ONE).unwrap();
    assert_eq!(flat.normal(Vec3::ZERO, 1e-3), Vec3::Y);
}

#[test]
fn operators_combine_materials() {
    let a = SdfNode::sphere(1.0).unwrap().with_material(1);
    let b = SdfNode::sphere(1.0)
        .unwrap()
        .translate(Vec3::X * 3.0)
        .unwrap()
        .with_material(2);
    let u = SdfNode::union(vec![a.clone(), b.clone()]).unwrap();
    assert_eq!(u.eval(Vec3::new(-2.0, 0.0, 0.0)), (1.0, 1));
    assert_eq!(u.eval(Vec3::new(5.0, 0.0, 0.0)), (1.0, 2));
    assert_eq!(u.materials_used(), vec![1, 2]);
    let cut = SdfNode::cuboid(Vec3::ONE)
        .unwrap()
        .with_material(1)
        .subtract(SdfNode::sphere(0.5).unwrap().with_material(2))
        .unwrap();
    // Inside the carved hole the nearest surface is the sphere's.
    assert_eq!(cut.eval(Vec3::ZERO).1, 2);
    assert!((cut.distance(Vec3::ZERO) - 0.5).abs() < 1e-6);
    let sm = SdfNode::smooth_union(0.5, vec![a, b]).unwrap();
    // Between the spheres smin is below min.
    let mid = Vec3::new(1.5, 0.0, 0.0);
    assert!(sm.distance(mid) <= 0.5);
    assert!(sm.distance(mid) >= 0.5 - 0.125 - 1e-6);
    // Shared and nested unions flatten.
    let nested = SdfNode::union(vec![u.clone(), u]).unwrap();
    assert_eq!(nested.object_count(), Some(4));
    assert_eq!(nested.depth(), 3);
}

#[test]
fn rotated_cylinder_intersection_tags_and_bounds() {
    let x_bar = SdfNode::cylinder(0.2, 1.0)
        .unwrap()
        .rotate(Quat::from_rotation_z(FRAC_PI_2))
        .unwrap();
    let b = x_bar.bounds();
    assert!(b.max.x >= 1.0 && b.max.y >= 0.2 && b.max.y < 0.3);
    let i = SdfNode::intersection(vec![x_bar, SdfNode::sphere(0.5).unwrap()]).unwrap();
    assert!(i.bounds().max.x <= 0.5 + 1e-6);
}

#[test]
fn union_skipping_is_invisible_for_exact_children() {
    // The union skips children whose bounding sphere is no nearer than the
    // best value so far: for exact children the result equals the plain
    // minimum, inside and out.
    let mut rng = Rng(14);
    let children: Vec<SdfNode> = exact_primitives()
        .into_iter()
        .filter(|(n, _)| *n != "plane")
        .enumerate()
        .map(|(i, (_, node))| {
            node.rotate(Quat::from_rotation_y(i as f32))
                .unwrap()
                .translate(Vec3::new(
                    (i % 4) as f32 * 1.3 - 2.0,
                    0.0,
                    (i / 4) as f32 * 1.3 - 2.0,
                ))
                .unwrap()
                .with_material(i as u32)
        })
        .collect();
    let union = SdfNode::union(children.clone()).unwrap();
    assert!(union.is_exact());
    for _ in 0..20_000 {
        let p = rng.vec(5.0);
        let mut best = (f32::INFINITY, 0);
        for c in &children {
            let r = c.eval(p);
            if r.0 < best.0 {
                best = r;
            }
        }
        assert_eq!(union.eval(p), best, "{p}");
    }
    // With a bound (ellipsoid) child the result may exceed the plain minimum,
    // but never the true distance (the ellipsoid's exact distance here).
    let radii = Vec3::new(0.9, 0.2, 0.5);
    let e = SdfNode::ellipsoid(radii)
        .unwrap()
        .translate(Vec3::X * 3.0)
        .unwrap();
    let u = SdfNode::union(vec![SdfNode::sphere(0.5).unwrap(), e.clone()]).unwrap();
    for _ in 0..20_000 {
        let p = rng.vec(6.0);
        let q = p - Vec3::X * 3.0;
        if (q / radii).length() <= 1.0 || p.length() < 0.5 {
            continue;
        }
        let truth = (p.length() as f64 - 0.5).min(ellipsoid_distance(d3(q), d3(radii)));
        let d = u.distance(p) as f64;
        assert!(d <= truth + 1e-5, "{d} > {truth}");
        assert!(d >= (p.length() - 0.5).min(e.distance(p)) as f64 - 1e-6);
    }
}

/// Operators that lower the field (onion, round, displacement, smooth union)
/// over a capped step bound (a guarded repetition, a scatter grid, a bounded
/// node) are accepted up to the cap's margin, where the field stays positive
/// away from the grown instances, and refused beyond it, where the cap would
/// read as a surface on every cell wall.
#[test]
fn offsets_over_capped_fields_stay_within_the_margin() {
    // Off-centre spheres (asymmetric: guarded) in cells of 3 along x: the
    // sphere reaches x = 0.2 ± 1, a margin of 0.3.
    let cells = SdfNode::sphere(1.0)
        .unwrap()
        .translate(Vec3::new(0.2, 0.0, 0.0))
        .unwrap()
        .repeat_limited(Vec3::new(3.0, 0.0, 0.0), [-2, 0, 0], [2, 0, 0])
        .unwrap();
    let margin = 0.3;
    for thickness in [0.0, 0.1, 0.29] {
        let shell = cells.clone().onion(thickness).unwrap();
        let rounded = cells.clone().round(thickness).unwrap();
        let bounds = shell.bounds();
        // Next to a cell wall's plane (x = 1.5), far beside the row and
        // between two instances.
        for p in [
            Vec3::new(1.5, 50.0, 0.0),
            Vec3::new(1.5, 0.0, 40.0),
            Vec3::new(1.45, 0.0, 1.2),
        ] {
            assert!(shell.distance(p) > 0.0, "onion {thickness} at {p}");
            assert!(rounded.distance(p) > 0.0, "round {thickness} at {p}");
            let split = shell.eval_split(p);
            assert!(split.safe <= split.surface && split.safe > 0.0, "{p}");
        }
        assert!(bounds.distance(Vec3::new(1.5, 50.0, 0.0)) > 0.0);
    }
    // Scaled: the margin scales too.
    assert!(cells.clone().scale(2.0).unwrap().onion(0.59).is_ok());
    assert!(matches!(
        cells.clone().scale(2.0).unwrap().onion(0.61),
        Err(SdfError::Overlap { .. })
    ));
    // Beyond the margin, every lowering operator is refused.
    let over = margin + 0.01;
    assert!(matches!(
        cells.clone().onion(over),
        Err(SdfError::Overlap { .. })
    ));
    assert!(matches!(
        cells.clone().round(over),
        Err(SdfError::Overlap { .. })
    ));
    assert!(matches!(
        cells.clone().displace(over, 2.0),
        Err(SdfError::Overlap { .. })
    ));
    assert!(cells.clone().displace(over, 0.0).is_ok());
    assert!(matches!(
        SdfNode::smooth_union(
            4.0 * over,
            vec![cells.clone(), SdfNode::sphere(0.5).unwrap()]
        ),
        Err(SdfError::Overlap { .. })
    ));
    // Offsets accumulate: two rounds of 0.2 exceed 0.3.
    let once = cells.clone().round(0.2).unwrap();
    assert!(matches!(once.round(0.2), Err(SdfError::Overlap { .. })));
    // Through a union with an uncapped sibling the limit stays.
    let both = SdfNode::union(vec![
        cells.clone(),
        SdfNode::sphere(1.0)
            .unwrap()
            .translate(Vec3::new(0.0, 5.0, 0.0))
            .unwrap(),
    ])
    .unwrap();
    assert!(both.clone().onion(0.2).is_ok());
    assert!(both.onion(0.4).is_err());
    // Below the repetition a thick shell is fine: the repetition checks that
    // the grown instance fits its cell.
    assert!(SdfNode::sphere(1.0)
        .unwrap()
        .translate(Vec3::new(0.2, 0.0, 0.0))
        .unwrap()
        .onion(0.25)
        .unwrap()
        .repeat_limited(Vec3::new(3.0, 0.0, 0.0), [-2, 0, 0], [2, 0, 0])
        .is_ok());
    // A symmetric (exact, unguarded) repetition has no cap.
    let exact = SdfNode::sphere(1.0)
        .unwrap()
        .repeat_limited(Vec3::new(3.0, 0.0, 0.0), [-2, 0, 0], [2, 0, 0])
        .unwrap();
    assert!(exact.onion(2.0).is_ok());
    // A bounded node answers its box's distance beyond `pad`.
    let boxed = SdfNode::sphere(1.0).unwrap().bounded(0.5).unwrap();
    assert!(boxed.clone().onion(0.5).is_ok());
    assert!(matches!(boxed.onion(0.6), Err(SdfError::Overlap { .. })));
}

/// The field's size for ambient occlusion: the box of its bounded objects,
/// an infinite floor plane left out; the reach of its rays when nothing is
/// bounded; the radius a tenth of it.
#[test]
fn sdf_size_is_the_bounded_objects_box() {
    use subcone_scene::scene::SdfGeometry;
    let geometry = |root: SdfNode| SdfGeometry {
        root,
        max_distance: 80.0,
        max_steps: 64,
    };
    let sphere = SdfNode::sphere(1.0).unwrap();
    let alone = geometry(sphere.clone());
    // The box of a unit sphere: 2 × 2 × 2, diagonal 2√3 (bounds may be padded).
    let d = 2.0 * 3f32.sqrt();
    assert!(
        alone.size() >= d && alone.size() < d * 1.01,
        "{}",
        alone.size()
    );
    let floor = SdfNode::plane(Vec3::Y, 0.0).unwrap();
    let with_floor = geometry(SdfNode::union(vec![floor.clone(), sphere]).unwrap());
    assert_eq!(with_floor.size(), alone.size());
    assert_eq!(geometry(floor).size(), 80.0);
    assert_eq!(
        with_floor.ao_radius(),
        with_floor.size() * subcone_kernels::ao::AO_RADIUS_FRACTION
    );
}
