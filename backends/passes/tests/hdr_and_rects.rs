//! HDR and sub-rectangles in the passes:
//! - `SraaPass` with `ResolveSpace::ToneMapped` (Karis 2014's weights)
//!   against the kernels' CPU resolve (`sraa::Resolver::with_resolve_space`)
//!   on a small frame with HDR highlights, within 1e-4 relative (the WGSL
//!   sums in f32 where the Rust sums in f64, and the GPU's `exp` is not
//!   libm's), and the exposure's typed refusal;
//! - `SraaPass::encode_rect` on a rect of larger textures against
//!   `SraaPass::encode` on textures of the rect's size holding the same
//!   inputs (bit for bit), with the pixels outside the rect untouched, and
//!   the rect's typed refusals;
//! - `FxaaPass`'s refusal of a float input it would clip
//!   (`PassError::HdrInput`), and its unorm path giving the bits of the
//!   float path on the same values.

mod common;

#[allow(dead_code)]
#[path = "../examples/host_sraa.rs"]
mod host_sraa;

use glam::Vec3;
use subcone_kernels::sraa::{
    Geometry, ResolveSpace, Resolver, ShadedFrame, ShadedGroup, SraaParams, Subsamples,
    ALBEDO_TOLERANCE,
};
use subcone_passes::{
    CentreGeometry, DepthKind, FxaaInput, FxaaPass, FxaaPassDesc, GeometryLayout, PassError, Rect,
    Samples, SraaInputs, SraaPass, SraaPassDesc, SubsampleGeometry,
};

/// A deterministic hash of a pixel, a layer and a role.
fn hash(x: u32, y: u32, layer: u32, role: u32) -> u32 {
    let mut h = x.wrapping_mul(0x9e37_79b1) ^ y.wrapping_mul(0x85eb_ca77);
    h ^= layer.wrapping_mul(0xc2b2_ae3d) ^ role.wrapping_mul(0x27d4_eb2f);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2c1b_3c6d);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297a_2d39);
    h ^ (h >> 15)
}

fn unit(x: u32, y: u32, layer: u32, role: u32) -> f32 {
    (hash(x, y, layer, role) >> 8) as f32 / (1u32 << 24) as f32
}

/// The geometry at pixel `(x, y)`, sample `layer` (0–3 the subsamples, 4
/// the centre): three surfaces and misses, as a function of the pixel's
/// place in the whole texture (so a rect's inputs are the same values).
fn geometry(x: u32, y: u32, layer: u32) -> Geometry {
    let normals = [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.6, 0.0, 0.8),
        Vec3::new(0.0, -0.8, 0.6),
    ];
    let s = hash(x, y, layer, 1) % 4;
    if s == 3 {
        return Geometry::MISS;
    }
    let depth = 1.0 + s as f32 + 0.05 * x as f32 + 0.01 * unit(x, y, layer, 2);
    Geometry::new(normals[s as usize], depth)
}

/// Colour layer `layer` of pixel `(x, y)`: LDR, with one pixel in eight a
/// highlight 100× brighter.
fn color(x: u32, y: u32, layer: u32) -> Vec3 {
    let c = Vec3::new(
        unit(x, y, layer, 3),
        unit(x, y, layer, 4),
        unit(x, y, layer, 5),
    );
    if hash(x, y, layer, 6) % 8 == 0 {
        c * 100.0
    } else {
        c
    }
}

/// The shadow bit (light 0) of pixel `(x, y)`, sample `layer` (4: centre).
fn shadow(x: u32, y: u32, layer: u32) -> u32 {
    hash(x, y, layer, 7) % 2
}

/// The inputs of one light, layers layout, linear view depth, signed
/// normals, shaded at the centre (`SraaParams::TUNED`), as textures of
/// `size` whose pixel `(x, y)` holds the values of pixel `origin + (x, y)`.
struct Textures {
    sub_depth: wgpu::TextureView,
    sub_normal: wgpu::TextureView,
    centre_depth: wgpu::TextureView,
    centre_normal: wgpu::TextureView,
    color: wgpu::TextureView,
    shaded_shadow: wgpu::TextureView,
    sub_shadow: wgpu::TextureView,
}

/// A one-sample texture of `size` and `layers` layers of `format`, texel
/// `(x, y)` of layer `l` holding `f(x, y, l)`.
fn upload<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    (w, h): (u32, u32),
    format: wgpu::TextureFormat,
    layers: u32,
    f: impl Fn(u32, u32, u32) -> T,
) -> wgpu::TextureView {
    let t = host_sraa::host::texture(
        device,
        "input",
        (w, h, layers),
        1,
        format,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    let mut texels = Vec::new();
    for l in 0..layers {
        for y in 0..h {
            for x in 0..w {
                texels.push(f(x, y, l));
            }
        }
    }
    let texel = format.block_copy_size(None).expect("colour format");
    queue.write_texture(
        t.as_image_copy(),
        bytemuck::cast_slice(&texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(w * texel),
            rows_per_image: Some(h),
        },
        t.size(),
    );
    t.create_view(&Default::default())
}

impl Textures {
    fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        size: (u32, u32),
        origin: (u32, u32),
    ) -> Self {
        use wgpu::TextureFormat::{R32Float, R32Uint, Rgba32Float};
        let at = |x: u32, y: u32| (x + origin.0, y + origin.1);
        let depth = |g: Geometry| if g.depth.is_finite() { g.depth } else { 0.0 };
        let normal = |g: Geometry| -> [f32; 4] { g.normal.extend(0.0).into() };
        let g = |x, y, l| {
            let (x, y) = at(x, y);
            geometry(x, y, l)
        };
        Textures {
            sub_depth: upload(device, queue, size, R32Float, 4, |x, y, k| {
                depth(g(x, y, k))
            }),
            sub_normal: upload(device, queue, size, Rgba32Float, 4, |x, y, k| {
                normal(g(x, y, k))
            }),
            centre_depth: upload(device, queue, size, R32Float, 1, |x, y, _| {
                depth(g(x, y, 4))
            }),
            centre_normal: upload(device, queue, size, Rgba32Float, 1, |x, y, _| {
                normal(g(x, y, 4))
            }),
            color: upload(device, queue, size, Rgba32Float, 2, |x, y, l| -> [f32; 4] {
                let (x, y) = at(x, y);
                color(x, y, l).extend(0.0).into()
            }),
            shaded_shadow: upload(device, queue, size, R32Uint, 1, |x, y, _| {
                let (x, y) = at(x, y);
                shadow(x, y, 4)
            }),
            sub_shadow: upload(device, queue, size, R32Uint, 4, |x, y, k| {
                let (x, y) = at(x, y);
                shadow(x, y, k)
            }),
        }
    }

    fn inputs<'a>(&'a self, output: &'a wgpu::TextureView) -> SraaInputs<'a> {
        SraaInputs {
            geometry: SubsampleGeometry::Separate {
                depth: &self.sub_depth,
                normal: &self.sub_normal,
            },
            projection: glam::Mat4::IDENTITY.to_cols_array_2d(),
            centre: Some(CentreGeometry {
                depth: &self.centre_depth,
                normal: &self.centre_normal,
            }),
            color: &self.color,
            shadows: Some(Samples {
                shaded: &self.shaded_shadow,
                subsamples: &self.sub_shadow,
            }),
            albedo: None,
            secondary: None,
            output,
        }
    }
}

/// The pass's configuration for [`Textures`]: one light, layers, linear
/// view depth, `SraaParams::TUNED`, writing `Rgba32Float`, resolving in
/// `resolve`.
fn desc(resolve: ResolveSpace) -> SraaPassDesc {
    SraaPassDesc::msaa()
        .with_lights(1)
        .with_params(SraaParams::TUNED)
        .with_geometry(GeometryLayout::Layers)
        .with_depth(DepthKind::LinearView)
        .with_output_format(wgpu::TextureFormat::Rgba32Float)
        .with_resolve(resolve)
}

/// An `Rgba32Float` output of `size` whose every texel is `fill`.
fn output(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    (w, h): (u32, u32),
    fill: [f32; 4],
) -> wgpu::Texture {
    let t = host_sraa::host::texture(
        device,
        "output",
        (w, h, 1),
        1,
        wgpu::TextureFormat::Rgba32Float,
        wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST,
    );
    let texels = vec![fill; (w * h) as usize];
    queue.write_texture(
        t.as_image_copy(),
        bytemuck::cast_slice(&texels),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(w * 16),
            rows_per_image: Some(h),
        },
        t.size(),
    );
    t
}

/// The kernels' CPU resolve of the `(w, h)` frame of [`Textures`] at
/// origin 0, in `space`.
fn cpu(w: u32, h: u32, space: ResolveSpace) -> Vec<Vec3> {
    let n = (w * h) as usize;
    let px = |j: usize| (j as u32 % w, j as u32 / w);
    let shaded: Vec<Geometry> = (0..n).map(|j| geometry(px(j).0, px(j).1, 4)).collect();
    let shaded_shadow: Vec<u32> = (0..n).map(|j| shadow(px(j).0, px(j).1, 4)).collect();
    let colors: Vec<Vec3> = (0..n)
        .flat_map(|j| (0..2).map(move |l| color(px(j).0, px(j).1, l)))
        .collect();
    let gates = [None, Some(0)];
    let resolver =
        Resolver::new(&SraaParams::TUNED, &gates, ALBEDO_TOLERANCE).with_resolve_space(space);
    let frame = ShadedFrame {
        width: w,
        height: h,
        colors: &colors,
        layers: 2,
        albedo: &[],
        primary: ShadedGroup {
            geometry: &shaded,
            shadow: &shaded_shadow,
            first_layer: 0,
        },
        secondary: None,
    };
    (0..n)
        .map(|j| {
            let (x, y) = px(j);
            let subs = Subsamples {
                geometry: core::array::from_fn(|k| geometry(x, y, k as u32)),
                shadow: core::array::from_fn(|k| shadow(x, y, k as u32)),
                albedo: None,
            };
            resolver.resolve(&frame, x, y, &subs, None)
        })
        .collect()
}

fn rgb(p: &[f32; 4]) -> Vec3 {
    Vec3::new(p[0], p[1], p[2])
}

#[test]
fn tone_mapped_resolve_matches_the_cpu_resolver() {
    let Some((device, queue)) =
        common::device_or_skip("tone-mapped resolve", host_sraa::open_device)
    else {
        return;
    };
    let (w, h) = (12, 8);
    let space = ResolveSpace::ToneMapped { exposure: 0.5 };
    let textures = Textures::new(&device, &queue, (w, h), (0, 0));
    let out = output(&device, &queue, (w, h), [0.0; 4]);
    let view = out.create_view(&Default::default());
    let pass = SraaPass::new(&device, &desc(space)).expect("pass");
    let mut enc = device.create_command_encoder(&Default::default());
    pass.encode(&device, &queue, &mut enc, &textures.inputs(&view), None)
        .expect("encode");
    let got: Vec<Vec3> = host_sraa::read_rgba32f(&device, &queue, enc, &out)
        .expect("read-back")
        .iter()
        .map(rgb)
        .collect();
    let want = cpu(w, h, space);
    let linear = cpu(w, h, ResolveSpace::Linear);
    let mut worst = 0.0f32;
    for (g, c) in got.iter().zip(&want) {
        let err = (*g - *c).abs().max_element() / c.abs().max_element().max(1.0);
        worst = worst.max(err);
    }
    // The highlights make the two resolves differ, by much more than the bound.
    let apart = want
        .iter()
        .zip(&linear)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .fold(0.0f32, f32::max);
    eprintln!("tone-mapped resolve: GPU vs CPU, largest relative difference {worst:e}; tone-mapped vs linear {apart}");
    assert!(
        apart > 1.0,
        "the highlights do not change the resolve ({apart})"
    );
    assert!(
        worst.is_finite() && worst <= 1e-4,
        "GPU and CPU differ by {worst}"
    );
}

#[test]
fn an_exposure_outside_its_domain_is_refused() {
    let Some((device, _queue)) = common::device_or_skip("exposure", host_sraa::open_device) else {
        return;
    };
    for exposure in [0.0f32, -1.0, f32::NAN, f32::INFINITY] {
        let r = SraaPass::new(&device, &desc(ResolveSpace::ToneMapped { exposure }));
        assert_eq!(
            r.err(),
            Some(PassError::Exposure {
                found_bits: exposure.to_bits()
            })
        );
    }
}

#[test]
fn a_rect_of_larger_textures_is_the_pass_on_the_rect() {
    let Some((device, queue)) = common::device_or_skip("sraa rect", host_sraa::open_device) else {
        return;
    };
    let big = (20, 14);
    let rect = Rect::new(5, 3, 9, 7);
    let fill = [7.0, -3.0, 0.25, 0.5];
    for space in [
        ResolveSpace::Linear,
        ResolveSpace::ToneMapped { exposure: 2.0 },
    ] {
        let pass = SraaPass::new(&device, &desc(space)).expect("pass");
        // The pass over textures of the rect's size holding the rect's values.
        let small = Textures::new(&device, &queue, rect.size(), (rect.x, rect.y));
        let small_out = output(&device, &queue, rect.size(), fill);
        let small_view = small_out.create_view(&Default::default());
        let mut enc = device.create_command_encoder(&Default::default());
        pass.encode(&device, &queue, &mut enc, &small.inputs(&small_view), None)
            .expect("encode");
        let want = host_sraa::read_rgba32f(&device, &queue, enc, &small_out).expect("read-back");
        // The pass over the rect of the large textures.
        let large = Textures::new(&device, &queue, big, (0, 0));
        let large_out = output(&device, &queue, big, fill);
        let large_view = large_out.create_view(&Default::default());
        let mut enc = device.create_command_encoder(&Default::default());
        pass.encode_rect(
            &device,
            &queue,
            &mut enc,
            &large.inputs(&large_view),
            rect,
            None,
        )
        .expect("encode_rect");
        let got = host_sraa::read_rgba32f(&device, &queue, enc, &large_out).expect("read-back");
        let mut inside = 0;
        for y in 0..big.1 {
            for x in 0..big.0 {
                let g = got[(y * big.0 + x) as usize].map(f32::to_bits);
                let (rx, ry) = (x.wrapping_sub(rect.x), y.wrapping_sub(rect.y));
                if rx < rect.width && ry < rect.height {
                    let w = want[(ry * rect.width + rx) as usize].map(f32::to_bits);
                    assert_eq!(g, w, "{space:?}: pixel ({x}, {y}) of the rect differs");
                    inside += 1;
                } else {
                    assert_eq!(
                        g,
                        fill.map(f32::to_bits),
                        "{space:?}: pixel ({x}, {y}) outside the rect was written"
                    );
                }
            }
        }
        assert_eq!(inside, rect.width * rect.height);
        // The rect clips the neighbourhood: pixels of the rect's edge differ
        // from the whole texture's resolve there.
        let mut enc = device.create_command_encoder(&Default::default());
        let whole_out = output(&device, &queue, big, fill);
        let whole_view = whole_out.create_view(&Default::default());
        pass.encode(&device, &queue, &mut enc, &large.inputs(&whole_view), None)
            .expect("encode");
        let whole = host_sraa::read_rgba32f(&device, &queue, enc, &whole_out).expect("read-back");
        let edge_differs = (0..rect.width).any(|rx| {
            let (x, y) = (rect.x + rx, rect.y);
            whole[(y * big.0 + x) as usize] != got[(y * big.0 + x) as usize]
        });
        assert!(
            edge_differs,
            "{space:?}: the rect's top row reads outside the rect"
        );
    }
}

#[test]
fn a_rect_outside_a_texture_is_refused() {
    let Some((device, queue)) = common::device_or_skip("sraa rect checks", host_sraa::open_device)
    else {
        return;
    };
    let pass = SraaPass::new(&device, &desc(ResolveSpace::Linear)).expect("pass");
    let textures = Textures::new(&device, &queue, (16, 10), (0, 0));
    let out = output(&device, &queue, (16, 10), [0.0; 4]);
    let view = out.create_view(&Default::default());
    let small_out = output(&device, &queue, (8, 8), [0.0; 4]);
    let small_view = small_out.create_view(&Default::default());
    let mut enc = device.create_command_encoder(&Default::default());
    let mut encode = |inputs: &SraaInputs<'_>, rect| {
        pass.encode_rect(&device, &queue, &mut enc, inputs, rect, None)
    };
    let inputs = textures.inputs(&view);
    assert_eq!(encode(&inputs, Rect::new(0, 0, 16, 10)), Ok(()));
    assert_eq!(encode(&inputs, Rect::new(4, 2, 12, 8)), Ok(()));
    for rect in [
        Rect::new(5, 2, 12, 8),
        Rect::new(0, 3, 16, 8),
        Rect::new(3, 3, 0, 4),
        Rect::new(u32::MAX, 0, 2, 2),
    ] {
        assert_eq!(
            encode(&inputs, rect),
            Err(PassError::Rect {
                what: "output",
                rect,
                size: (16, 10)
            })
        );
    }
    // The output holds the rect but an input does not.
    let rect = Rect::new(0, 0, 8, 8);
    assert_eq!(encode(&textures.inputs(&small_view), rect), Ok(()));
    let small = Textures::new(&device, &queue, (8, 6), (0, 0));
    assert_eq!(
        encode(&small.inputs(&view), rect),
        Err(PassError::Rect {
            what: "subsample depth",
            rect,
            size: (8, 6)
        })
    );
    // Without a rect, sizes must still match exactly.
    let mut enc = device.create_command_encoder(&Default::default());
    assert!(matches!(
        pass.encode(
            &device,
            &queue,
            &mut enc,
            &textures.inputs(&small_view),
            None
        ),
        Err(PassError::Size { .. })
    ));
}

#[test]
fn fxaa_refuses_hdr_input_and_keeps_its_ldr_path() {
    use wgpu::TextureFormat::{Rgba16Float, Rgba32Float, Rgba8Unorm};
    let Some((device, queue)) = common::device_or_skip("fxaa hdr", host_sraa::open_device) else {
        return;
    };
    let (w, h) = (16, 12);
    // A hard diagonal edge of two LDR colours, on 8-bit levels.
    let level = |x: u32, y: u32, c: u32| -> u8 {
        let inside = 2 * x > 3 * y;
        [[40u8, 200, 90], [230, 30, 160]][inside as usize][c as usize]
    };
    let unorm = upload(
        &device,
        &queue,
        (w, h),
        Rgba8Unorm,
        1,
        |x, y, _| -> [u8; 4] { [level(x, y, 0), level(x, y, 1), level(x, y, 2), 255] },
    );
    let float = upload(
        &device,
        &queue,
        (w, h),
        Rgba32Float,
        1,
        |x, y, _| -> [f32; 4] {
            [0, 1, 2, 3].map(|c| {
                if c == 3 {
                    1.0
                } else {
                    f32::from(level(x, y, c)) / 255.0
                }
            })
        },
    );
    let half = upload(&device, &queue, (w, h), Rgba16Float, 1, |_, _, _| [0u16; 4]);
    let run =
        |input: &wgpu::TextureView, desc: &FxaaPassDesc| -> Result<Vec<[f32; 4]>, PassError> {
            let pass = FxaaPass::new(&device, desc).expect("pass");
            let out = output(&device, &queue, (w, h), [0.0; 4]);
            let view = out.create_view(&Default::default());
            let mut enc = device.create_command_encoder(&Default::default());
            pass.encode(&device, &queue, &mut enc, input, &view, None)?;
            Ok(host_sraa::read_rgba32f(&device, &queue, enc, &out).expect("read-back"))
        };
    let ldr = FxaaPassDesc::default().with_output_format(Rgba32Float);
    for (input, format) in [(&float, Rgba32Float), (&half, Rgba16Float)] {
        assert_eq!(
            run(input, &ldr).err(),
            Some(PassError::HdrInput {
                what: "input",
                found: format
            })
        );
    }
    let from_unorm = run(&unorm, &ldr).expect("unorm input");
    let tone_mapped = ldr.with_input(FxaaInput::ToneMapped);
    let from_float = run(&float, &tone_mapped).expect("tone-mapped float input");
    assert_eq!(
        from_unorm
            .iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>(),
        from_float
            .iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>(),
        "the unorm and the float path differ on the same values"
    );
    // FXAA blended the edge: some pixel is neither of the two colours.
    let pure = |p: &[f32; 4]| {
        let s = host_sraa::host::to_srgb8(&[rgb(p)]);
        s == [40, 200, 90] || s == [230, 30, 160]
    };
    assert!(from_unorm.iter().any(|p| !pure(p)), "FXAA changed nothing");
}
