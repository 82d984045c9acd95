//! `SraaPass` against the kernels' CPU resolve (`sraa::Resolver`, what the
//! CPU backend runs) on the same synthetic inputs, for the input
//! conventions a host MSAA prepass does not exercise (`host_sraa` covers
//! 4x MSAA with hardware depth): four-layer arrays and the packed layout,
//! linear view depth, signed and `[0, 1]`-encoded normals, shading at
//! subsample 0 and at the centre, lights gated by shadow bits (eq. 2), the
//! albedo gate, secondary (mirror) hits reconstructed on their own geometry
//! (§3.3), a 5×5 neighbourhood, and the same roles in storage buffers
//! (`GeometryLayout::Buffers`, `encode_buffers`, what `subcone-wgpu`'s
//! SRAA-RT resolves from). Bound: every channel within 1e-4 of
//! the CPU's (the WGSL accumulates in compensated f32 where the Rust uses
//! f64, and the GPU's `exp` is not libm's; `[0, 1]` normals are decoded and
//! renormalised).

mod common;

#[allow(dead_code)]
#[path = "../examples/host_sraa.rs"]
mod host_sraa;

use glam::{Vec3, Vec4};
use subcone_kernels::sraa::{
    Geometry, Resolver, ShadedFrame, ShadedGroup, ShadedPosition, SraaParams, Subsamples,
    ALBEDO_TOLERANCE,
};
use subcone_passes::{
    CentreGeometry, DepthKind, GeometryLayout, NormalEncoding, Samples, SecondaryBuffers,
    SecondaryInputs, SraaBuffers, SraaInputs, SraaPass, SraaPassDesc, SubsampleGeometry,
};

const W: u32 = 12;
const H: u32 = 8;

/// A small deterministic generator (xorshift).
struct Rng(u32);

impl Rng {
    fn next(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }
    fn unit(&mut self) -> f32 {
        (self.next() >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// One synthetic frame: three surfaces (and misses) scattered over the
/// samples, so that every weight, gate and fallback is exercised.
struct Data {
    lights: usize,
    shaded: Vec<Geometry>,
    sub: Vec<[Geometry; 4]>,
    colors: Vec<Vec3>,
    shaded_shadow: Vec<u32>,
    sub_shadow: Vec<[u32; 4]>,
    shaded_albedo: Vec<Vec3>,
    sub_albedo: Vec<[Vec3; 4]>,
    /// Secondary hits (NaN depth: no mirror), when the case has them.
    secondary: bool,
    shaded2: Vec<Geometry>,
    sub2: Vec<[Geometry; 4]>,
    shaded_shadow2: Vec<u32>,
    sub_shadow2: Vec<[u32; 4]>,
}

fn data(seed: u32, lights: usize, shaded_on_subsample: bool, secondary: bool) -> Data {
    let mut r = Rng(seed);
    let normals = [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.6, 0.0, 0.8),
        Vec3::new(0.0, -0.8, 0.6),
    ];
    let albedos = [
        Vec3::new(0.8, 0.2, 0.2),
        Vec3::new(0.8, 0.25, 0.2),
        Vec3::new(0.1, 0.5, 0.9),
    ];
    let n = (W * H) as usize;
    let geo = |r: &mut Rng, x: u32| -> (Geometry, Vec3) {
        let s = r.next() % 4;
        if s == 3 {
            return (Geometry::MISS, Vec3::ZERO);
        }
        let depth = 1.0 + s as f32 + 0.05 * x as f32 + 0.01 * r.unit();
        (
            Geometry::new(normals[s as usize], depth),
            albedos[s as usize],
        )
    };
    let mut d = Data {
        lights,
        shaded: Vec::new(),
        sub: Vec::new(),
        colors: Vec::new(),
        shaded_shadow: Vec::new(),
        sub_shadow: Vec::new(),
        shaded_albedo: Vec::new(),
        sub_albedo: Vec::new(),
        secondary,
        shaded2: Vec::new(),
        sub2: Vec::new(),
        shaded_shadow2: Vec::new(),
        sub_shadow2: Vec::new(),
    };
    // A secondary hit: none (no mirror), a miss, or one of the surfaces at
    // a path length of 3 to 6.
    let geo2 = |r: &mut Rng| -> Geometry {
        match r.next() % 6 {
            0 | 1 => Geometry::new(Vec3::ZERO, f32::NAN),
            2 => Geometry::MISS,
            s => Geometry::new(normals[s as usize - 3], 3.0 + s as f32 + r.unit()),
        }
    };
    for j in 0..n {
        let x = j as u32 % W;
        let mut sub = [Geometry::MISS; 4];
        let mut sub_albedo = [Vec3::ZERO; 4];
        for k in 0..4 {
            (sub[k], sub_albedo[k]) = geo(&mut r, x);
        }
        let mut sub_shadow = [0u32; 4];
        for s in &mut sub_shadow {
            *s = r.next() % (1 << lights);
        }
        let (mut g, mut a) = geo(&mut r, x);
        let mut shadow = r.next() % (1 << lights);
        if shaded_on_subsample {
            (g, a, shadow) = (sub[0], sub_albedo[0], sub_shadow[0]);
        }
        d.shaded.push(g);
        d.sub.push(sub);
        d.sub_shadow.push(sub_shadow);
        d.sub_albedo.push(sub_albedo);
        d.shaded_shadow.push(shadow);
        d.shaded_albedo.push(a);
        let mut sub2 = [Geometry::MISS; 4];
        let mut sub_shadow2 = [0u32; 4];
        for k in 0..4 {
            sub2[k] = geo2(&mut r);
            sub_shadow2[k] = r.next() % (1 << lights);
        }
        let mut g2 = geo2(&mut r);
        let mut shadow2 = r.next() % (1 << lights);
        if shaded_on_subsample {
            (g2, shadow2) = (sub2[0], sub_shadow2[0]);
        }
        d.shaded2.push(g2);
        d.sub2.push(sub2);
        d.shaded_shadow2.push(shadow2);
        d.sub_shadow2.push(sub_shadow2);
        let groups = if secondary { 2 } else { 1 };
        for _ in 0..(1 + lights) * groups {
            d.colors.push(
                Vec3::new(r.unit(), r.unit(), r.unit())
                    * if g.depth.is_finite() { 1.0 } else { 0.2 },
            );
        }
    }
    d
}

/// The CPU backend's resolve of `d`.
fn cpu(d: &Data, params: &SraaParams, gate: bool) -> Vec<Vec3> {
    let gates: Vec<Option<u8>> = (0..=d.lights)
        .map(|i| i.checked_sub(1).map(|l| l as u8))
        .collect();
    let resolver = Resolver::new(params, &gates, ALBEDO_TOLERANCE);
    let frame = ShadedFrame {
        width: W,
        height: H,
        colors: &d.colors,
        layers: (1 + d.lights) * if d.secondary { 2 } else { 1 },
        albedo: if gate { &d.shaded_albedo } else { &[] },
        primary: ShadedGroup {
            geometry: &d.shaded,
            shadow: &d.shaded_shadow,
            first_layer: 0,
        },
        secondary: d.secondary.then_some(ShadedGroup {
            geometry: &d.shaded2,
            shadow: &d.shaded_shadow2,
            first_layer: 1 + d.lights,
        }),
    };
    (0..W * H)
        .map(|j| {
            let i = j as usize;
            let subs = Subsamples {
                geometry: d.sub[i],
                shadow: d.sub_shadow[i],
                albedo: gate.then_some(d.sub_albedo[i]),
            };
            let subs2 = Subsamples {
                geometry: d.sub2[i],
                shadow: d.sub_shadow2[i],
                albedo: None,
            };
            resolver.resolve(&frame, j % W, j / W, &subs, d.secondary.then_some(&subs2))
        })
        .collect()
}

struct Case {
    name: &'static str,
    geometry: GeometryLayout,
    normal: NormalEncoding,
    params: SraaParams,
    lights: usize,
    gate: bool,
    secondary: bool,
}

/// A one-sample `W × H` array of `layers` layers of `format` holding
/// `texel(pixel, layer)`.
fn upload<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    format: wgpu::TextureFormat,
    layers: usize,
    texel: impl Fn(usize, usize) -> T,
) -> wgpu::TextureView {
    let t = host_sraa::host::texture(
        device,
        "input",
        (W, H, layers as u32),
        1,
        format,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    let texel_size = format.block_copy_size(None).expect("colour format");
    queue.write_texture(
        t.as_image_copy(),
        &layered(layers, texel),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(W * texel_size),
            rows_per_image: Some(H),
        },
        t.size(),
    );
    // The whole texture: 2D for one layer, a 2D array for more.
    t.create_view(&Default::default())
}

/// Layer-major texels of `f(pixel, layer)`.
fn layered<T: bytemuck::Pod>(layers: usize, f: impl Fn(usize, usize) -> T) -> Vec<u8> {
    let mut v = Vec::new();
    for l in 0..layers {
        for j in 0..(W * H) as usize {
            v.push(f(j, l));
        }
    }
    bytemuck::cast_slice(&v).to_vec()
}

/// A storage buffer holding `data` (and readable back, for the output).
fn storage<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    data: &[T],
) -> wgpu::Buffer {
    let bytes: &[u8] = bytemuck::cast_slice(data);
    let b = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("input"),
        size: (bytes.len() as u64).max(16),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    queue.write_buffer(&b, 0, bytes);
    b
}

/// `shaded` and `subsamples` as an input of a role the case has (`on`).
fn samples<R>(on: bool, shaded: R, subsamples: R) -> Option<Samples<R>> {
    on.then_some(Samples { shaded, subsamples })
}

/// The pass on buffers (`GeometryLayout::Buffers`): every role as the
/// kernels' structs, the geometry as it is (secondary misses and "no
/// mirror" as `Geometry` holds them).
fn gpu_buffers(device: &wgpu::Device, queue: &wgpu::Queue, d: &Data, c: &Case) -> Vec<Vec3> {
    let flat = |v: &[[Geometry; 4]]| -> Vec<Geometry> { v.iter().flatten().copied().collect() };
    let v4 = |a: &Vec3| -> [f32; 4] { Vec4::from((*a, 0.0)).into() };
    let words = |v: &[[u32; 4]]| -> Vec<u32> { v.iter().flatten().copied().collect() };
    let shaded = storage(device, queue, &d.shaded);
    let sub = storage(device, queue, &flat(&d.sub));
    let color: Vec<[f32; 4]> = d.colors.iter().map(v4).collect();
    let color = storage(device, queue, &color);
    let shaded_shadow = storage(device, queue, &d.shaded_shadow);
    let sub_shadow = storage(device, queue, &words(&d.sub_shadow));
    let shaded_albedo: Vec<[f32; 4]> = d.shaded_albedo.iter().map(v4).collect();
    let shaded_albedo = storage(device, queue, &shaded_albedo);
    let sub_albedo: Vec<[f32; 4]> = d.sub_albedo.iter().flatten().map(v4).collect();
    let sub_albedo = storage(device, queue, &sub_albedo);
    let shaded2 = storage(device, queue, &d.shaded2);
    let sub2 = storage(device, queue, &flat(&d.sub2));
    let shaded_shadow2 = storage(device, queue, &d.shaded_shadow2);
    let sub_shadow2 = storage(device, queue, &words(&d.sub_shadow2));
    let output = storage(device, queue, &vec![[0.0f32; 4]; (W * H) as usize]);
    let pass = SraaPass::new(
        device,
        &SraaPassDesc::buffers(c.params)
            .with_lights(c.lights as u32)
            .with_secondary(c.secondary)
            .with_albedo_gate(c.gate),
    )
    .expect("pass");
    let mut enc = device.create_command_encoder(&Default::default());
    let lit = c.lights > 0;
    pass.encode_buffers(
        device,
        queue,
        &mut enc,
        &SraaBuffers {
            size: (W, H),
            geometry: Samples {
                shaded: &shaded,
                subsamples: &sub,
            },
            color: &color,
            shadows: samples(lit, &shaded_shadow, &sub_shadow),
            albedo: samples(c.gate, &shaded_albedo, &sub_albedo),
            secondary: c.secondary.then_some(SecondaryBuffers {
                geometry: Samples {
                    shaded: &shaded2,
                    subsamples: &sub2,
                },
                shadows: samples(lit, &shaded_shadow2, &sub_shadow2),
            }),
            output: &output,
        },
        None,
    )
    .unwrap_or_else(|e| panic!("{}: {e}", c.name));
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read-back"),
        size: output.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    enc.copy_buffer_to_buffer(&output, 0, &staging, 0, output.size());
    queue.submit([enc.finish()]);
    let bytes = host_sraa::host::read_buffer(device, &staging).expect("read-back");
    let px: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
    px.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect()
}

fn gpu(device: &wgpu::Device, queue: &wgpu::Queue, d: &Data, c: &Case) -> Vec<Vec3> {
    use wgpu::TextureFormat::{R32Float, R32Uint, Rgba32Float};
    if c.geometry == GeometryLayout::Buffers {
        return gpu_buffers(device, queue, d, c);
    }
    let linear = |g: &Geometry| if g.depth.is_finite() { g.depth } else { 0.0 };
    let normal = |g: &Geometry| -> [f32; 4] {
        let n = match c.normal {
            NormalEncoding::Signed => g.normal,
            NormalEncoding::Unsigned => g.normal * 0.5 + Vec3::splat(0.5),
        };
        n.extend(0.0).into()
    };
    let (sub_depth, sub_normal) = match c.geometry {
        GeometryLayout::Packed => {
            let texel = |j: usize, k: usize| -> [f32; 4] {
                let g = &d.sub[j][k];
                let w = if g.depth.is_finite() { g.depth } else { -1.0 };
                g.normal.extend(w).into()
            };
            (upload(device, queue, Rgba32Float, 4, texel), None)
        }
        _ => (
            upload(device, queue, R32Float, 4, |j, k| linear(&d.sub[j][k])),
            Some(upload(device, queue, Rgba32Float, 4, |j, k| {
                normal(&d.sub[j][k])
            })),
        ),
    };
    let geometry = match &sub_normal {
        Some(normal) => SubsampleGeometry::Separate {
            depth: &sub_depth,
            normal,
        },
        None => SubsampleGeometry::Packed(&sub_depth),
    };
    let centre = c.params.shaded_position() == ShadedPosition::Centre;
    let centre_depth = upload(device, queue, R32Float, 1, |j, _| linear(&d.shaded[j]));
    let centre_normal = upload(device, queue, Rgba32Float, 1, |j, _| normal(&d.shaded[j]));
    let layers = (1 + c.lights) * if c.secondary { 2 } else { 1 };
    let color = upload(device, queue, Rgba32Float, layers, |j, l| -> [f32; 4] {
        d.colors[j * layers + l].extend(0.0).into()
    });
    let shaded_shadow = upload(device, queue, R32Uint, 1, |j, _| d.shaded_shadow[j]);
    let sub_shadow = upload(device, queue, R32Uint, 4, |j, k| d.sub_shadow[j][k]);
    let v4 = |a: Vec3| -> [f32; 4] { Vec4::from((a, 0.0)).into() };
    let shaded_albedo = upload(device, queue, Rgba32Float, 1, |j, _| v4(d.shaded_albedo[j]));
    let sub_albedo = upload(device, queue, Rgba32Float, 4, |j, k| v4(d.sub_albedo[j][k]));
    // Secondary path length: negative for no mirror, 0 for a miss.
    let path = |g: &Geometry| {
        if g.depth.is_nan() {
            -1.0
        } else if g.depth.is_finite() {
            g.depth
        } else {
            0.0
        }
    };
    let sec_shaded_depth = upload(device, queue, R32Float, 1, |j, _| path(&d.shaded2[j]));
    let sec_shaded_normal = upload(device, queue, Rgba32Float, 1, |j, _| normal(&d.shaded2[j]));
    let sec_sub_depth = upload(device, queue, R32Float, 4, |j, k| path(&d.sub2[j][k]));
    let sec_sub_normal = upload(device, queue, Rgba32Float, 4, |j, k| normal(&d.sub2[j][k]));
    let sec_shaded_shadow = upload(device, queue, R32Uint, 1, |j, _| d.shaded_shadow2[j]);
    let sec_sub_shadow = upload(device, queue, R32Uint, 4, |j, k| d.sub_shadow2[j][k]);
    let output = host_sraa::host::texture(
        device,
        "output",
        (W, H, 1),
        1,
        Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
    );
    let output_view = output.create_view(&Default::default());
    let pass = SraaPass::new(
        device,
        &SraaPassDesc::msaa()
            .with_lights(c.lights as u32)
            .with_secondary(c.secondary)
            .with_albedo_gate(c.gate)
            .with_params(c.params)
            .with_geometry(c.geometry)
            .with_depth(DepthKind::LinearView)
            .with_normal(c.normal)
            .with_output_format(Rgba32Float),
    )
    .expect("pass");
    let mut enc = device.create_command_encoder(&Default::default());
    pass.encode(
        device,
        queue,
        &mut enc,
        &SraaInputs {
            geometry,
            // Linear view depth: no projection is read.
            projection: glam::Mat4::IDENTITY.to_cols_array_2d(),
            centre: centre.then_some(CentreGeometry {
                depth: &centre_depth,
                normal: &centre_normal,
            }),
            color: &color,
            shadows: samples(c.lights > 0, &shaded_shadow, &sub_shadow),
            albedo: samples(c.gate, &shaded_albedo, &sub_albedo),
            secondary: c.secondary.then_some(SecondaryInputs {
                shaded_depth: &sec_shaded_depth,
                shaded_normal: &sec_shaded_normal,
                subsample_depth: &sec_sub_depth,
                subsample_normal: &sec_sub_normal,
                shadows: samples(c.lights > 0, &sec_shaded_shadow, &sec_sub_shadow),
            }),
            output: &output_view,
        },
        None,
    )
    .unwrap_or_else(|e| panic!("{}: {e}", c.name));
    host_sraa::read_rgba32f(device, queue, enc, &output)
        .expect("read-back")
        .iter()
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect()
}

#[test]
fn sraa_pass_matches_the_cpu_resolver_in_every_convention() {
    // The adapter's limits: the buffer form with lights, mirrors and the
    // albedo gate binds 12 storage buffers (WebGPU's default allows 8).
    let Some((device, queue)) = common::device_or_skip(
        "resolve conventions",
        host_sraa::host::open_device_with_adapter_limits,
    ) else {
        return;
    };
    let cases = [
        Case {
            name: "layers, signed, paper, 2 lights, albedo gate",
            geometry: GeometryLayout::Layers,
            normal: NormalEncoding::Signed,
            params: SraaParams::PAPER,
            lights: 2,
            gate: true,
            secondary: false,
        },
        Case {
            name: "layers, unsigned, tuned",
            geometry: GeometryLayout::Layers,
            normal: NormalEncoding::Unsigned,
            params: SraaParams::TUNED,
            lights: 0,
            gate: false,
            secondary: false,
        },
        Case {
            name: "packed, tuned, 3 lights, albedo gate",
            geometry: GeometryLayout::Packed,
            normal: NormalEncoding::Signed,
            params: SraaParams::TUNED,
            lights: 3,
            gate: true,
            secondary: false,
        },
        Case {
            name: "layers, signed, tuned, radius 2",
            geometry: GeometryLayout::Layers,
            normal: NormalEncoding::Signed,
            params: SraaParams::TUNED.with_radius(2),
            lights: 1,
            gate: false,
            secondary: false,
        },
        Case {
            name: "layers, signed, paper, 2 lights, secondary",
            geometry: GeometryLayout::Layers,
            normal: NormalEncoding::Signed,
            params: SraaParams::PAPER,
            lights: 2,
            gate: true,
            secondary: true,
        },
        Case {
            name: "buffers, paper, 2 lights, albedo gate, secondary",
            geometry: GeometryLayout::Buffers,
            normal: NormalEncoding::Signed,
            params: SraaParams::PAPER,
            lights: 2,
            gate: true,
            secondary: true,
        },
        Case {
            name: "buffers, tuned, 1 light",
            geometry: GeometryLayout::Buffers,
            normal: NormalEncoding::Signed,
            params: SraaParams::TUNED,
            lights: 1,
            gate: false,
            secondary: false,
        },
        Case {
            name: "packed, tuned, secondary",
            geometry: GeometryLayout::Packed,
            normal: NormalEncoding::Signed,
            params: SraaParams::TUNED,
            lights: 0,
            gate: false,
            secondary: true,
        },
    ];
    for (i, c) in cases.iter().enumerate() {
        let on_subsample = c.params.shaded_position() == ShadedPosition::Subsample;
        let d = data(
            0x9e37_79b9 ^ (i as u32 * 7919 + 1),
            c.lights,
            on_subsample,
            c.secondary,
        );
        let want = cpu(&d, &c.params, c.gate);
        let got = gpu(&device, &queue, &d, c);
        let worst = want
            .iter()
            .zip(&got)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0f32, f32::max);
        // The inputs are not trivial: neighbouring pixels' results differ.
        let spread = want
            .iter()
            .map(|c| (*c - want[0]).abs().max_element())
            .fold(0.0f32, f32::max);
        eprintln!("{}: largest channel difference {worst:e}", c.name);
        assert!(spread > 0.1, "{}: a flat frame", c.name);
        assert!(
            worst.is_finite() && worst <= 1e-4,
            "{}: GPU and CPU differ by {worst}",
            c.name
        );
    }
}

/// The buffer form checks its buffers before recording: a buffer too small
/// for the frame, one without `STORAGE`, a role the desc does not read and
/// a texture desc given buffers are each refused, as values.
#[test]
fn sraa_pass_buffers_are_checked() {
    use subcone_passes::PassError;
    let Some((device, queue)) = common::device_or_skip("buffer checks", host_sraa::open_device)
    else {
        return;
    };
    let n = (W * H) as usize;
    let geo = storage(&device, &queue, &vec![Geometry::MISS; n]);
    let sub = storage(&device, &queue, &vec![Geometry::MISS; 4 * n]);
    let small = storage(&device, &queue, &vec![Geometry::MISS; n - 1]);
    let color = storage(&device, &queue, &vec![[0.0f32; 4]; n]);
    let words = storage(&device, &queue, &vec![0u32; 4 * n]);
    let output = storage(&device, &queue, &vec![[0.0f32; 4]; n]);
    let unbindable = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: (n * 16) as u64,
        usage: wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let pass = SraaPass::new(&device, &SraaPassDesc::buffers(SraaParams::TUNED)).expect("pass");
    let geometry = Samples {
        shaded: &geo,
        subsamples: &sub,
    };
    let inputs = SraaBuffers {
        size: (W, H),
        geometry,
        color: &color,
        shadows: None,
        albedo: None,
        secondary: None,
        output: &output,
    };
    let mut enc = device.create_command_encoder(&Default::default());
    let mut encode = |i: &SraaBuffers<'_>| pass.encode_buffers(&device, &queue, &mut enc, i, None);
    assert_eq!(encode(&inputs), Ok(()));
    assert!(matches!(
        encode(&SraaBuffers {
            geometry: Samples {
                shaded: &small,
                ..geometry
            },
            ..inputs
        }),
        Err(PassError::BufferSize {
            what: "shaded geometry",
            ..
        })
    ));
    assert!(matches!(
        encode(&SraaBuffers {
            output: &unbindable,
            ..inputs
        }),
        Err(PassError::BufferUsage { what: "output", .. })
    ));
    assert_eq!(
        encode(&SraaBuffers {
            shadows: Some(Samples {
                shaded: &words,
                subsamples: &words,
            }),
            ..inputs
        }),
        Err(PassError::Unexpected("shadow buffers (0 lights)"))
    );
    let textures = SraaPass::new(&device, &SraaPassDesc::packed(SraaParams::TUNED)).expect("pass");
    // On a device of WebGPU's default limits (8 storage buffers per stage),
    // the 12 buffers of lights, mirrors and the albedo gate are refused.
    let full = SraaPassDesc::buffers(SraaParams::TUNED)
        .with_lights(2)
        .with_secondary(true)
        .with_albedo_gate(true);
    assert!(matches!(
        SraaPass::new(&device, &full),
        Err(PassError::Config(_))
    ));
    assert!(matches!(
        textures.encode_buffers(&device, &queue, &mut enc, &inputs, None),
        Err(PassError::Config(_))
    ));
}
