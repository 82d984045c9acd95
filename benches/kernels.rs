//! Per-call cost of every kernel of `subcone-kernels`.
//!
//! The cheap kernels run over [`N`] precomputed, varied inputs per iteration and
//! report `Throughput::Elements(N)`, so criterion's throughput is kernel calls
//! per second and `time / N` is the cost of one call. Inputs go through
//! `black_box` and every result is stored to an output buffer that is itself
//! `black_box`ed, so nothing is constant-folded and no call is dropped; no
//! result feeds the next call, so the figure is throughput, not latency.
//!
//! The SRAA inputs come from a small ray-cast scene (a sphere over a floor, in
//! front of a wall, under the sky, with the sphere's shadow on the floor): half
//! of the pixels are drawn from the whole image, half from pixels whose 3×3
//! neighbourhood straddles a depth, normal, shadow or sky edge.
//!
//! The CTSS group traces one pixel of a unit sphere per iteration, for a ray
//! through its centre (full occlusion), a ray grazing its silhouette (partial
//! coverage) and a miss, with CTSS (`ctss::trace`) and with the NoAA baseline
//! (`ctss::sphere_trace`, and the same plus the one shading call a NoAA pixel
//! makes on a hit).
//!
//! Run with `cargo bench --bench kernels`.

use std::time::Duration;

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::{Vec2, Vec3};
use subcone::aggregate::Aggregate;
use subcone::cone::{
    advance, backtrace_cone_entry, backtrace_hard_hit, cone_occlusion, cone_radius, cone_tan_theta,
    PixelFootprint,
};
use subcone::ctss::{cross_section_frame, sphere_trace, trace, CtssParams, StopReason};
use subcone::mask::{
    mask_weight, project_normal, visibility_mask, MaskPlacement, VisibilityAccumulator,
};
use subcone::sraa::{
    bilateral_weight, neighbourhood, reconstruct, resolve_pixel, shadow_gated_weight, Geometry,
    Resolver, ShadedFrame, ShadedGroup, ShadedSample, SraaParams, Subsamples, ALBEDO_TOLERANCE,
    SHADED_SUBSAMPLE, SUBPIXEL_OFFSETS,
};

/// Inputs per iteration of the cheap kernels.
const N: usize = 1024;

/// A 1080p, 60° vertical field of view camera: the per-pixel cone of the benches.
fn pixel_tan_theta() -> f32 {
    cone_tan_theta(60f32.to_radians(), 1080, 1.0, PixelFootprint::Circumscribed)
}

// ---------------------------------------------------------------------------
// Deterministic inputs
// ---------------------------------------------------------------------------

/// Knuth's MMIX linear congruential generator: deterministic, dependency-free.
struct Lcg(u64);

impl Lcg {
    fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u32(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 32) as u32
    }

    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Uniform in `[lo, hi)`.
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `0..n`.
    fn below(&mut self, n: usize) -> usize {
        ((self.next_u32() as u64 * n as u64) >> 32) as usize
    }

    /// A random unit vector (rejection sampling in the unit ball).
    fn unit_vec3(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l2 = v.length_squared();
            if l2 > 1e-4 && l2 <= 1.0 {
                return v / l2.sqrt();
            }
        }
    }

    fn color(&mut self) -> Vec3 {
        Vec3::new(self.unit(), self.unit(), self.unit())
    }
}

/// What a primary ray of the SRAA scene sees.
#[derive(Clone, Copy)]
struct Hit {
    geometry: Geometry,
    color: Vec3,
    shadowed: bool,
}

/// A sphere on a floor in front of a wall, seen by a pinhole camera at the origin
/// looking down +z, lit by one directional light.
struct SraaScene {
    width: usize,
    height: usize,
    tan_half_fov: f32,
    centre: Vec3,
    radius: f32,
    floor_y: f32,
    wall_z: f32,
    light: Vec3,
}

impl SraaScene {
    fn new() -> Self {
        Self {
            width: 96,
            height: 96,
            tan_half_fov: 30f32.to_radians().tan(),
            centre: Vec3::new(0.3, -0.2, 6.0),
            radius: 1.3,
            floor_y: -1.5,
            wall_z: 11.0,
            light: Vec3::new(0.5, 1.0, -0.3).normalize(),
        }
    }

    /// Nearest positive hit of the ray `o + s·d` with the sphere.
    fn hit_sphere(&self, o: Vec3, d: Vec3) -> Option<f32> {
        let oc = o - self.centre;
        let b = oc.dot(d);
        let c = oc.length_squared() - self.radius * self.radius;
        let disc = b * b - c;
        if disc < 0.0 {
            return None;
        }
        let s = disc.sqrt();
        [-b - s, -b + s].into_iter().find(|&t| t > 1e-4)
    }

    /// Primary ray through pixel `(x, y)` at subpixel `offset` (y grows downwards).
    fn shoot(&self, x: usize, y: usize, offset: Vec2) -> Hit {
        let aspect = self.width as f32 / self.height as f32;
        let sx = ((x as f32 + 0.5 + offset.x) / self.width as f32 * 2.0 - 1.0)
            * aspect
            * self.tan_half_fov;
        let sy = (1.0 - (y as f32 + 0.5 + offset.y) / self.height as f32 * 2.0) * self.tan_half_fov;
        let d = Vec3::new(sx, sy, 1.0).normalize();

        let mut best: Option<(f32, Vec3, Vec3)> = None; // (t, normal, albedo)
        let mut consider = |t: f32, n: Vec3, albedo: Vec3| {
            if t > 0.0 && best.is_none_or(|(bt, _, _)| t < bt) {
                best = Some((t, n, albedo));
            }
        };
        if let Some(t) = self.hit_sphere(Vec3::ZERO, d) {
            let n = (t * d - self.centre) / self.radius;
            consider(t, n, Vec3::new(0.8, 0.3, 0.2));
        }
        if d.y < 0.0 {
            consider(self.floor_y / d.y, Vec3::Y, Vec3::splat(0.7));
        }
        consider(self.wall_z / d.z, Vec3::NEG_Z, Vec3::new(0.3, 0.5, 0.8));

        match best {
            Some((t, n, albedo)) if t * d.z < self.wall_z * 1.5 => {
                let p = t * d;
                let facing = n.dot(self.light);
                let shadowed = facing <= 0.0 || self.hit_sphere(p + 1e-3 * n, self.light).is_some();
                let direct = if shadowed { 0.0 } else { facing };
                Hit {
                    geometry: Geometry::new(n, t * d.z),
                    color: albedo * (0.1 + direct),
                    shadowed,
                }
            }
            _ => Hit {
                geometry: Geometry::MISS,
                color: Vec3::new(0.5, 0.7, 1.0),
                shadowed: false,
            },
        }
    }
}

/// One reconstruction problem: a geometric subsample and its 3×3 shaded neighbours.
#[derive(Clone, Copy)]
struct ReconstructInput {
    target: Geometry,
    target_shadow: bool,
    neighbours: [ShadedSample; 9],
}

/// Inputs of `sraa::neighbourhood`: a pixel of a 1080p image and a subsample.
#[derive(Clone, Copy)]
struct PixelInput {
    x: u32,
    y: u32,
    sub: usize,
}

const IMAGE: (u32, u32) = (1920, 1080);

/// [`N`] pixels, one in eight on the image border (a clipped neighbourhood).
fn pixel_inputs() -> Vec<PixelInput> {
    let (w, h) = IMAGE;
    let mut rng = Lcg::new(0x5eed_0009);
    (0..N)
        .map(|i| {
            let mut x = rng.below(w as usize) as u32;
            let mut y = rng.below(h as usize) as u32;
            if i % 8 == 0 {
                match rng.below(4) {
                    0 => x = 0,
                    1 => x = w - 1,
                    2 => y = 0,
                    _ => y = h - 1,
                }
            }
            PixelInput {
                x,
                y,
                sub: rng.below(4),
            }
        })
        .collect()
}

/// The SRAA scene as an SRAA-RT frame of one light: per pixel the shaded
/// sample at the centre (the default preset's) split into two layers, base and
/// the light's direct part (black in shadow), its shadow bit, and the four
/// subsamples' geometry and shadow bits.
struct ResolveFrame {
    width: u32,
    height: u32,
    geometry: Vec<Geometry>,
    shadow: Vec<u32>,
    colors: Vec<Vec3>,
    subsamples: Vec<Subsamples>,
}

fn resolve_frame() -> ResolveFrame {
    let scene = SraaScene::new();
    let (w, h) = (scene.width, scene.height);
    let shaded: Vec<Hit> = (0..w * h)
        .map(|i| scene.shoot(i % w, i / w, SraaParams::TUNED.shaded_offset()))
        .collect();
    let colors = shaded
        .iter()
        .flat_map(|s| {
            let direct = if s.shadowed {
                Vec3::ZERO
            } else {
                0.7 * s.color
            };
            [0.3 * s.color, direct]
        })
        .collect();
    let subsamples = (0..w * h)
        .map(|i| {
            let hits: [Hit; 4] =
                core::array::from_fn(|k| scene.shoot(i % w, i / w, SUBPIXEL_OFFSETS[k]));
            Subsamples {
                geometry: hits.map(|h| h.geometry),
                shadow: hits.map(|h| h.shadowed as u32),
                albedo: None,
            }
        })
        .collect();
    ResolveFrame {
        width: w as u32,
        height: h as u32,
        geometry: shaded.iter().map(|s| s.geometry).collect(),
        shadow: shaded.iter().map(|s| s.shadowed as u32).collect(),
        colors,
        subsamples,
    }
}

/// Whether two samples would be told apart by an edge-aware filter.
fn is_edge(a: &Hit, b: &Hit) -> bool {
    let (za, zb) = (a.geometry.depth, b.geometry.depth);
    if za.is_infinite() || zb.is_infinite() {
        return za != zb;
    }
    (za - zb).abs() > 0.02 * za.min(zb)
        || a.geometry.normal.dot(b.geometry.normal) < 0.95
        || a.shadowed != b.shadowed
}

/// [`N`] neighbourhoods of the SRAA scene: half from anywhere, half from edges.
fn sraa_inputs() -> Vec<ReconstructInput> {
    let scene = SraaScene::new();
    let (w, h) = (scene.width, scene.height);
    let shaded: Vec<Hit> = (0..w * h)
        .map(|i| scene.shoot(i % w, i / w, SUBPIXEL_OFFSETS[SHADED_SUBSAMPLE]))
        .collect();
    let at = |x: usize, y: usize| &shaded[y * w + x];

    // Interior pixels, and those of them whose 3×3 neighbourhood crosses an edge.
    let interior: Vec<(usize, usize)> = (1..h - 1)
        .flat_map(|y| (1..w - 1).map(move |x| (x, y)))
        .collect();
    let edges: Vec<(usize, usize)> = interior
        .iter()
        .copied()
        .filter(|&(x, y)| (0..9).any(|k| is_edge(at(x, y), at(x + k % 3 - 1, y + k / 3 - 1))))
        .collect();
    assert!(edges.len() > N / 8, "the scene has too few edge pixels");

    let mut rng = Lcg::new(0x5eed_0001);
    (0..N)
        .map(|i| {
            let (x, y) = if i % 2 == 0 {
                interior[rng.below(interior.len())]
            } else {
                edges[rng.below(edges.len())]
            };
            let sub = rng.below(4);
            let target = scene.shoot(x, y, SUBPIXEL_OFFSETS[sub]);
            // The 3×3 gather a backend does, with the crate's own distances.
            let mut pixels = neighbourhood(
                x as u32,
                y as u32,
                sub,
                SraaParams::PAPER.shaded_offset(),
                1,
                w as u32,
                h as u32,
            );
            let neighbours = core::array::from_fn(|_| {
                let q = pixels.next().expect("an interior pixel has 9 neighbours");
                let s = at(q.x as usize, q.y as usize);
                ShadedSample {
                    geometry: s.geometry,
                    color: s.color,
                    shadowed: s.shadowed,
                    distance2: q.distance2,
                }
            });
            assert!(pixels.next().is_none());
            ReconstructInput {
                target: target.geometry,
                target_shadow: target.shadowed,
                neighbours,
            }
        })
        .collect()
}

/// A pair of samples for the weights: a target and one of its neighbours.
#[derive(Clone, Copy)]
struct WeightPair {
    gi: Geometry,
    gj: Geometry,
    si: bool,
    sj: bool,
}

fn weight_pairs(hoods: &[ReconstructInput]) -> Vec<WeightPair> {
    let mut rng = Lcg::new(0x5eed_0002);
    hoods
        .iter()
        .map(|h| {
            let j = h.neighbours[rng.below(9)];
            WeightPair {
                gi: h.target,
                gj: j.geometry,
                si: h.target_shadow,
                sj: j.shadowed,
            }
        })
        .collect()
}

/// Cone inputs: depths along a 1080p pixel cone and SDF values around its radius.
#[derive(Clone, Copy)]
struct ConeInput {
    t: f32,
    d: f32,
    rc: f32,
    tan_theta: f32,
}

fn cone_inputs() -> Vec<ConeInput> {
    let tan = pixel_tan_theta();
    let mut rng = Lcg::new(0x5eed_0003);
    (0..N)
        .map(|i| {
            let t = rng.range(0.05, 100.0);
            // Coverage varies the cone from a quarter pixel to four pixels.
            let tan_theta = tan * rng.range(0.25, 4.0);
            let rc = cone_radius(t, tan_theta);
            let d = match i % 8 {
                // Free space: far from every surface.
                0 => rng.range(0.0, 10.0),
                // Inside, deeper than the cone (full occlusion).
                1 => -rng.range(1.0, 4.0) * rc,
                // Around the surface: miss, soft, hard.
                _ => rng.range(-1.0, 3.0) * rc,
            };
            ConeInput {
                t,
                d,
                rc,
                tan_theta,
            }
        })
        .collect()
}

/// Mask inputs: an occlusion and a projected normal.
#[derive(Clone, Copy)]
struct MaskInput {
    occlusion: f32,
    projected: Vec2,
}

/// Inputs of `project_normal`: a normal of any length and a cross-section frame.
#[derive(Clone, Copy)]
struct FrameInput {
    normal: Vec3,
    right: Vec3,
    up: Vec3,
}

fn frame_inputs() -> Vec<FrameInput> {
    let mut rng = Lcg::new(0x5eed_0004);
    (0..N)
        .map(|_| {
            let dir = (Vec3::Z + 0.6 * rng.unit_vec3()).normalize();
            let (right, up) = cross_section_frame(dir, Vec3::Y);
            let normal = rng.unit_vec3() * rng.range(0.5, 2.0);
            FrameInput { normal, right, up }
        })
        .collect()
}

fn mask_inputs(frames: &[FrameInput]) -> Vec<MaskInput> {
    let mut rng = Lcg::new(0x5eed_0005);
    frames
        .iter()
        .enumerate()
        .map(|(i, f)| MaskInput {
            occlusion: rng.range(-0.3, 1.3),
            // One in sixteen faces the ray (the fronto-parallel path).
            projected: if i % 16 == 0 {
                Vec2::ZERO
            } else {
                project_normal(f.normal, f.right, f.up)
            },
        })
        .collect()
}

/// One pixel's worth of CTSS samples: four masks, colours and a background.
#[derive(Clone, Copy)]
struct PixelSamples {
    masks: [u32; 4],
    colors: [Vec3; 4],
    background: Vec3,
}

fn pixel_samples(masks: &[MaskInput]) -> Vec<PixelSamples> {
    let mut rng = Lcg::new(0x5eed_0006);
    let mask_of = |m: &MaskInput| visibility_mask(m.occlusion, m.projected, MaskPlacement::Derived);
    (0..N)
        .map(|_| PixelSamples {
            masks: core::array::from_fn(|_| mask_of(&masks[rng.below(masks.len())])),
            colors: core::array::from_fn(|_| rng.color()),
            background: rng.color(),
        })
        .collect()
}

// ---------------------------------------------------------------------------
// Benches
// ---------------------------------------------------------------------------

/// Run `f` on each of `inputs` into `out`, with inputs and outputs opaque.
#[inline(always)]
fn map_into<I, O>(inputs: &[I], out: &mut [O], mut f: impl FnMut(&I) -> O) {
    for (o, x) in out.iter_mut().zip(black_box(inputs)) {
        *o = f(x);
    }
    black_box(out);
}

fn bench_sraa(c: &mut Criterion) {
    let hoods = sraa_inputs();
    let pairs = weight_pairs(&hoods);
    let mut rng = Lcg::new(0x5eed_0007);
    let quads: Vec<[Vec3; 4]> = (0..N)
        .map(|_| core::array::from_fn(|_| rng.color()))
        .collect();

    let mut g = c.benchmark_group("sraa");
    g.throughput(Throughput::Elements(N as u64));

    let mut w = vec![0f32; N];
    for (name, preset) in [
        ("paper", SraaParams::PAPER),
        ("chajdas", SraaParams::CHAJDAS),
    ] {
        g.bench_function(BenchmarkId::new("bilateral_weight", name), |b| {
            let p = black_box(preset);
            b.iter(|| map_into(&pairs, &mut w, |q| bilateral_weight(&p, &q.gi, &q.gj)))
        });
    }
    g.bench_function("shadow_gated_weight", |b| {
        let p = black_box(SraaParams::PAPER);
        b.iter(|| {
            map_into(&pairs, &mut w, |q| {
                shadow_gated_weight(&p, &q.gi, &q.gj, q.si, q.sj)
            })
        })
    });

    // The gather alone: one call walks the (clipped) 3×3 neighbourhood.
    let pixels = pixel_inputs();
    g.bench_function("neighbourhood_3x3", |b| {
        let (width, height) = black_box(IMAGE);
        b.iter(|| {
            map_into(&pixels, &mut w, |q| {
                neighbourhood(
                    q.x,
                    q.y,
                    q.sub,
                    SraaParams::PAPER.shaded_offset(),
                    1,
                    width,
                    height,
                )
                .map(|n| n.distance2 + (n.x ^ n.y) as f32)
                .sum::<f32>()
            })
        })
    });

    let mut rec = vec![Vec3::ZERO; N];
    g.bench_function("reconstruct_3x3", |b| {
        let p = black_box(SraaParams::PAPER);
        b.iter(|| {
            map_into(&hoods, &mut rec, |h| {
                reconstruct(
                    &p,
                    &h.target,
                    Some(h.target_shadow),
                    h.neighbours.iter().copied(),
                )
                .color
            })
        })
    });
    g.bench_function("resolve_pixel", |b| {
        b.iter(|| map_into(&quads, &mut rec, resolve_pixel))
    });

    // The whole antialiasing pass of one SRAA-RT pixel (one light, default
    // preset): four subsamples, two layers, the 3×3 neighbourhood.
    let rf = resolve_frame();
    let gates = [None, Some(0u8)];
    let frame = ShadedFrame {
        width: rf.width,
        height: rf.height,
        colors: &rf.colors,
        layers: 2,
        albedo: &[],
        primary: ShadedGroup {
            geometry: &rf.geometry,
            shadow: &rf.shadow,
            first_layer: 0,
        },
        secondary: None,
    };
    let mut rng = Lcg::new(0x5eed_000a);
    let resolve_pixels: Vec<(u32, u32)> = (0..N)
        .map(|_| {
            (
                rng.below(rf.width as usize) as u32,
                rng.below(rf.height as usize) as u32,
            )
        })
        .collect();
    g.bench_function("resolver_resolve_rt_1_light", |b| {
        let resolver = Resolver::new(&black_box(SraaParams::TUNED), &gates, ALBEDO_TOLERANCE);
        b.iter(|| {
            map_into(&resolve_pixels, &mut rec, |&(x, y)| {
                let i = (y * rf.width + x) as usize;
                resolver.resolve(&frame, x, y, &rf.subsamples[i], None)
            })
        })
    });
    g.finish();
}

fn bench_cone(c: &mut Criterion) {
    let inputs = cone_inputs();
    let mut out = vec![0f32; N];
    let mut g = c.benchmark_group("cone");
    g.throughput(Throughput::Elements(N as u64));

    g.bench_function("cone_occlusion", |b| {
        b.iter(|| map_into(&inputs, &mut out, |x| cone_occlusion(x.d, x.rc)))
    });
    g.bench_function("advance", |b| {
        let alpha = black_box(0.5f32);
        b.iter(|| map_into(&inputs, &mut out, |x| advance(x.t, x.d, alpha, x.rc)))
    });
    g.bench_function("backtrace_cone_entry", |b| {
        b.iter(|| {
            map_into(&inputs, &mut out, |x| {
                backtrace_cone_entry(x.t, x.tan_theta)
            })
        })
    });
    g.bench_function("backtrace_hard_hit", |b| {
        // (t_prev, d_prev, t_i) of a step: t_i = t_prev + max(d_prev, α·R_c).
        b.iter(|| {
            map_into(&inputs, &mut out, |x| {
                backtrace_hard_hit(x.t, x.d, x.t + x.d.max(0.5 * x.rc))
            })
        })
    });
    g.finish();
}

fn bench_mask(c: &mut Criterion) {
    let frames = frame_inputs();
    let masks = mask_inputs(&frames);
    let mut rng = Lcg::new(0x5eed_0008);
    let raw_masks: Vec<u32> = (0..N).map(|_| rng.next_u32() & rng.next_u32()).collect();

    let mut g = c.benchmark_group("mask");
    g.throughput(Throughput::Elements(N as u64));

    let mut bits = vec![0u32; N];
    for (name, placement) in [
        ("derived", MaskPlacement::Derived),
        ("authors_code", MaskPlacement::AuthorsCode),
    ] {
        g.bench_function(BenchmarkId::new("visibility_mask", name), |b| {
            let placement = black_box(placement);
            b.iter(|| {
                map_into(&masks, &mut bits, |m| {
                    visibility_mask(m.occlusion, m.projected, placement)
                })
            })
        });
    }

    let mut np = vec![Vec2::ZERO; N];
    g.bench_function("project_normal", |b| {
        b.iter(|| {
            map_into(&frames, &mut np, |f| {
                project_normal(f.normal, f.right, f.up)
            })
        })
    });

    // Four masks per pixel, correlated in order as along a ray; N adds in all.
    g.bench_function("accumulator_add", |b| {
        b.iter(|| {
            let input = black_box(&raw_masks);
            for (o, m) in bits.chunks_exact_mut(4).zip(input.chunks_exact(4)) {
                let mut acc = VisibilityAccumulator::new();
                for (v, &mi) in o.iter_mut().zip(m) {
                    *v = acc.add(mi);
                }
            }
            black_box(&mut bits);
        })
    });
    g.finish();
}

fn bench_aggregate(c: &mut Criterion) {
    let frames = frame_inputs();
    let masks = mask_inputs(&frames);
    let pixels = pixel_samples(&masks);
    let mut out = vec![Vec3::ZERO; N];

    let mut g = c.benchmark_group("aggregate");
    // One element is one pixel: four correlated samples added, then resolved.
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("add4_resolve", |b| {
        b.iter(|| {
            map_into(&pixels, &mut out, |px| {
                let mut vis = VisibilityAccumulator::new();
                let mut agg = Aggregate::new();
                for (&m, &col) in px.masks.iter().zip(&px.colors) {
                    agg.add(mask_weight(vis.add(m)), col);
                }
                agg.resolve(px.background, vis.uncovered_weight())
            })
        })
    });
    g.finish();
}

/// The CTSS scene: a unit sphere 5 units down +z, seen from the origin.
struct SphereScene {
    centre: Vec3,
    radius: f32,
    light: Vec3,
    albedo: Vec3,
    background: Vec3,
}

/// A pixel ray of the CTSS group.
struct Ray {
    name: &'static str,
    dir: Vec3,
    right: Vec3,
    up: Vec3,
}

fn ctss_rays(scene: &SphereScene, tan_theta: f32) -> [Ray; 3] {
    let make = |name, dir: Vec3| {
        let dir = dir.normalize();
        let (right, up) = cross_section_frame(dir, Vec3::Y);
        Ray {
            name,
            dir,
            right,
            up,
        }
    };
    // The silhouette is where the ray passes at `radius` from the centre; pass
    // a quarter of the cone radius outside it, so the cone's cross-section is
    // partly inside the sphere (a soft hit, ω ≈ 0.375) but the ray never is.
    let dist = scene.centre.length();
    let t_tangent = (dist * dist - scene.radius * scene.radius).sqrt();
    let offset = scene.radius + 0.25 * cone_radius(t_tangent, tan_theta);
    let angle = (offset / dist).asin();
    [
        make("centre", scene.centre),
        make("graze", Vec3::new(angle.sin(), 0.0, angle.cos())),
        make("miss", Vec3::new(0.5, 0.3, 1.0)),
    ]
}

fn bench_ctss(c: &mut Criterion) {
    let scene = SphereScene {
        centre: Vec3::new(0.0, 0.0, 5.0),
        radius: 1.0,
        light: Vec3::new(0.4, 0.8, -0.45).normalize(),
        albedo: Vec3::new(0.8, 0.6, 0.3),
        background: Vec3::new(0.1, 0.2, 0.4),
    };
    let params = CtssParams::new(pixel_tan_theta());
    let rays = ctss_rays(&scene, params.tan_theta);

    let sdf = |centre: Vec3, radius: f32| move |p: Vec3| (p - centre).length() - radius;
    let normal = |centre: Vec3| move |p: Vec3| (p - centre).normalize();
    let shade =
        |light: Vec3, albedo: Vec3| move |_p: Vec3, n: Vec3| albedo * (0.1 + n.dot(light).max(0.0));

    // Check once that each ray is the case it claims to be, and show its cost in
    // SDF evaluations (stderr, next to criterion's report).
    for r in &rays {
        let res = trace(
            &params,
            Vec3::ZERO,
            r.dir,
            r.right,
            r.up,
            sdf(scene.centre, scene.radius),
            normal(scene.centre),
            shade(scene.light, scene.albedo),
            scene.background,
        );
        let hit = sphere_trace(&params, Vec3::ZERO, r.dir, sdf(scene.centre, scene.radius));
        let bits = res.coverage.count_ones();
        match r.name {
            "centre" => assert!(res.stop == StopReason::FullOcclusion && hit.t.is_some()),
            "graze" => assert!(res.samples >= 1 && bits > 0 && bits < 32 && hit.t.is_none()),
            _ => assert!(res.samples == 0 && hit.t.is_none()),
        }
        eprintln!(
            "ctss {:>6}: CTSS {:>3} steps, {} samples, {:>2}/32 covered, {:?}; NoAA {:>3} steps, {:?}",
            r.name, res.steps, res.samples, bits, res.stop, hit.steps, hit.stop
        );
    }

    let mut g = c.benchmark_group("ctss");
    // One element is one pixel.
    g.throughput(Throughput::Elements(1));
    for r in &rays {
        g.bench_function(BenchmarkId::new("trace", r.name), |b| {
            b.iter(|| {
                let (centre, radius) = black_box((scene.centre, scene.radius));
                trace(
                    &params,
                    black_box(Vec3::ZERO),
                    black_box(r.dir),
                    black_box(r.right),
                    black_box(r.up),
                    sdf(centre, radius),
                    normal(centre),
                    shade(scene.light, scene.albedo),
                    scene.background,
                )
            })
        });
    }
    for r in &rays {
        g.bench_function(BenchmarkId::new("sphere_trace", r.name), |b| {
            b.iter(|| {
                let (centre, radius) = black_box((scene.centre, scene.radius));
                sphere_trace(
                    &params,
                    black_box(Vec3::ZERO),
                    black_box(r.dir),
                    sdf(centre, radius),
                )
            })
        });
    }
    // A whole NoAA pixel: the sphere trace plus the normal and shading of its hit.
    for r in &rays {
        g.bench_function(BenchmarkId::new("sphere_trace_shaded", r.name), |b| {
            b.iter(|| {
                let (centre, radius) = black_box((scene.centre, scene.radius));
                let origin = black_box(Vec3::ZERO);
                let dir = black_box(r.dir);
                let hit = sphere_trace(&params, origin, dir, sdf(centre, radius));
                match hit.t {
                    Some(t) => {
                        let p = origin + t * dir;
                        shade(scene.light, scene.albedo)(p, normal(centre)(p))
                    }
                    None => scene.background,
                }
            })
        });
    }
    g.finish();
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = kernels;
    config = config();
    targets = bench_sraa, bench_cone, bench_mask, bench_aggregate, bench_ctss
}
criterion_main!(kernels);
