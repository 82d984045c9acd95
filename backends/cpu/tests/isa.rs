//! Every instruction-set path renders the same frames as the baseline path,
//! bit for bit: triangle scenes with the SRAA family, SDF scenes with CTSS.

use subcone_cpu::isa::Isa;
use subcone_cpu::CpuBackend;
use subcone_scene::builtin::builtin;
use subcone_scene::{Backend, Method, RenderSettings};

const W: u32 = 48;
const H: u32 = 32;

/// The colour buffer's bits.
fn render_bits(isa: Isa, scene: &str, method: &str) -> Vec<u32> {
    let scene = builtin(scene).unwrap_or_else(|e| panic!("{scene}: {e}"));
    let method: Method = method.parse().expect("a method name");
    CpuBackend::new()
        .with_isa(isa)
        .render(&scene, &scene.camera, &method, &RenderSettings::new(W, H))
        .unwrap_or_else(|e| panic!("{} {method} on {isa}: {e}", scene.name))
        .color
        .iter()
        .flat_map(|c| c.to_array().map(f32::to_bits))
        .collect()
}

/// One test per scene: every method, every supported path against baseline.
macro_rules! same_bits_on_every_path {
    ($($test:ident: $scene:literal, [$($method:literal),+];)+) => {$(
        #[test]
        fn $test() {
            for method in [$($method),+] {
                let baseline = render_bits(Isa::Baseline, $scene, method);
                for isa in Isa::supported() {
                    let frame = render_bits(isa, $scene, method);
                    let differing = frame.iter().zip(&baseline).filter(|(a, b)| a != b).count();
                    assert!(
                        differing == 0,
                        "{} {method} on {isa}: {differing} of {} channels differ from baseline",
                        $scene,
                        frame.len()
                    );
                }
            }
        }
    )+};
}

same_bits_on_every_path! {
    cornell: "cornell", ["noaa", "ssaa2", "ssaa4", "sraa", "sraa-rt", "noaa-hybrid", "ssaa2-hybrid", "ssaa4-hybrid", "sraa-rt-hybrid"];
    checker: "checker", ["noaa", "ssaa4", "sraa", "sraa-rt", "sraa-hybrid", "sraa-rt-paper+mat-hybrid"];
    primitives: "primitives", ["noaa", "ssaa4", "ctss"];
    random_box: "random-box", ["noaa", "ssaa4", "ctss"];
}

/// `Isa`'s names and its fallback to a supported path.
mod names {
    use super::*;

    #[test]
    fn names_round_trip_and_fallback_is_supported() {
        for i in Isa::ALL {
            assert_eq!(i.name().parse::<Isa>(), Ok(i));
            assert!(i.or_supported().is_supported());
            assert!(i.or_supported() <= i);
            // The nesting `or_supported` relies on.
            assert_eq!(
                i.or_supported(),
                Isa::ALL
                    .into_iter()
                    .rev()
                    .filter(|j| *j <= i)
                    .find(|j| j.is_supported())
                    .unwrap()
            );
        }
        assert!("sse9".parse::<Isa>().is_err());
        assert!(Isa::supported().contains(&Isa::Baseline));
        assert_eq!(Isa::supported().last(), Some(&Isa::detected()));
    }
}

/// The BVH traversal itself, ray by ray, compiled for every path (inside
/// `Isa::run`, as the renderer calls it) against baseline: the same hit, the
/// same distance bits and the same occlusion answers. A random triangle soup
/// (many overlapping boxes per node), rays from inside and outside its
/// bounds, and the directions that stress a slab test: axis-aligned, with
/// zero and negative-zero components, components at and around
/// `f32::EPSILON` (the cut-off of the ray's `safe_inverse`), huge and tiny
/// ones.
mod traversal {
    use glam::{Vec2, Vec3};
    use subcone_cpu::isa::Isa;
    use subcone_cpu::SceneBvh;
    use subcone_scene::TriangleMesh;

    /// A small deterministic generator (xorshift), so the test needs no
    /// dependency and fails the same way every run.
    struct Rng(u64);
    impl Rng {
        fn unit(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 40) as f32 / (1u64 << 24) as f32
        }
        fn signed(&mut self) -> f32 {
            2.0 * self.unit() - 1.0
        }
        fn vec(&mut self) -> Vec3 {
            Vec3::new(self.signed(), self.signed(), self.signed())
        }
    }

    fn soup(rng: &mut Rng) -> TriangleMesh {
        let mut mesh = TriangleMesh::default();
        for i in 0..3000 {
            let c = rng.vec() * 10.0;
            let size = if i % 10 == 0 { 4.0 } else { 1.0 };
            let v = [
                c + rng.vec() * size,
                c + rng.vec() * size,
                c + rng.vec() * size,
            ];
            mesh.push(v, [Vec3::Z; 3], [Vec2::ZERO; 3], 0);
        }
        mesh
    }

    fn directions(rng: &mut Rng) -> Vec<Vec3> {
        let e = f32::EPSILON;
        let mut d = vec![
            Vec3::X,
            -Vec3::X,
            Vec3::Y,
            -Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(1.0, 0.0, -0.0),
            Vec3::new(-0.0, -0.0, 1.0),
            Vec3::new(e, 1.0, -e),
            Vec3::new(e * 1.0001, -1.0, e * 0.9999),
            Vec3::new(-e * 1.0001, 1e-30, 1.0),
            Vec3::new(1e-20, -1e-38, 1.0),
            Vec3::new(1e30, 1.0, -1e30),
            Vec3::new(0.0, 0.0, 0.0),
        ];
        for _ in 0..4000 {
            let mut v = rng.vec();
            // Now and then a component flushed to (signed) zero or epsilon.
            match (rng.unit() * 8.0) as u32 {
                0 => v.x = 0.0,
                1 => v.y = -0.0,
                2 => v.z = e,
                _ => {}
            }
            d.push(v.normalize_or(Vec3::X));
        }
        d
    }

    #[test]
    fn every_path_finds_the_same_hits() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mesh = soup(&mut rng);
        let bvh = SceneBvh::build(&mesh, |_| true);
        let dirs = directions(&mut rng);
        let mut hits = 0;
        for (i, d) in dirs.iter().enumerate() {
            // Alternately from inside the soup and from outside its bounds.
            let o = if i % 2 == 0 {
                rng.vec() * 8.0
            } else {
                rng.vec() * 5.0 - *d * 60.0
            };
            let query = |isa: Isa| {
                isa.run(
                    #[inline(always)]
                    || {
                        (
                            bvh.closest(o, *d, 0.0, f32::INFINITY),
                            bvh.raw_closest_t(o, *d).to_bits(),
                            bvh.occluded(o, *d, 0.0, 15.0),
                            bvh.raw_occluded(o, *d, 15.0),
                        )
                    },
                )
            };
            let base = query(Isa::Baseline);
            hits += usize::from(base.0.is_some());
            for isa in Isa::supported() {
                let got = query(isa);
                assert_eq!(got, base, "ray {i} from {o} along {d} on {isa}");
            }
        }
        // The soup is dense enough that most rays hit (a test of misses only
        // would compare little).
        assert!(hits > dirs.len() / 2, "{hits} of {} rays hit", dirs.len());
    }

    /// The pipeline's intersector is obvhs' (the same `t`, bit for bit, as
    /// the raw traversal), and its barycentrics weigh `v1` and `v2`: the
    /// point rebuilt from them lies on the ray.
    #[test]
    fn barycentrics_rebuild_the_hit_point() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mesh = soup(&mut rng);
        let bvh = SceneBvh::build(&mesh, |_| true);
        let mut hits = 0;
        for i in 0..4000 {
            let o = rng.vec() * 25.0;
            let d = (rng.vec() * 5.0 - o).normalize();
            let raw = bvh.raw_closest_t(o, d);
            let Some(hit) = bvh.closest(o, d, 0.0, f32::INFINITY) else {
                assert!(
                    raw.is_infinite(),
                    "ray {i}: obvhs hit at {raw}, the pipeline missed"
                );
                continue;
            };
            hits += 1;
            assert_eq!(hit.t.to_bits(), raw.to_bits(), "ray {i}");
            let [v0, v1, v2] = mesh.positions[hit.triangle as usize];
            let (b1, b2) = (hit.barycentrics.x, hit.barycentrics.y);
            assert!(
                b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0 + 1e-6,
                "ray {i}: {b1}, {b2}"
            );
            let rebuilt = (1.0 - b1 - b2) * v0 + b1 * v1 + b2 * v2;
            let p = o + hit.t * d;
            assert!(
                (rebuilt - p).length() <= 1e-4 * (1.0 + p.length()),
                "ray {i}: {rebuilt} from the barycentrics, {p} on the ray"
            );
        }
        assert!(
            hits > 2000,
            "only {hits} of 4000 rays hit: the test compares little"
        );
    }
}
