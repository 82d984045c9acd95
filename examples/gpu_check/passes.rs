//! `gpu_check passes FILE --sizes WxH,WxH --runs N`: each pass of
//! `subcone-passes` alone (SraaPass, CtssPass, FxaaPass, TaaPass) on the
//! adapter the wgpu backend opens, at each size: one warm-up, then `runs`
//! submissions of the pass alone, each waited for and timed as the backend
//! times its passes (trusted GPU timestamps, else the wall clock from
//! submission to completion, and which of the two, recorded beside them).

use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use glam::Vec3;
use serde_json::{json, Value};
use subcone_kernels::ctss::CtssParams;
use subcone_kernels::sraa::SraaParams;
use subcone_passes::{
    CtssCamera, CtssFrame, CtssPass, CtssPassDesc, FxaaInput, FxaaPass, FxaaPassDesc, SraaInputs,
    SraaPass, SraaPassDesc, SubsampleGeometry, TaaInputs, TaaPass, TaaPassDesc,
};
use subcone_wgpu::GpuContext;

/// A sphere in front of the camera, shaded by its normal: CtssPass's field.
const FIELD_WGSL: &str = "
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let d = length(p - vec3<f32>(0.0, 0.0, 5.0)) - 1.0;
    return vec3<f32>(d, d, 0.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.5) + 0.5 * n;
}
";

const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

fn texture(
    ctx: &GpuContext,
    label: &str,
    (w, h): (u32, u32),
    samples: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::TextureView {
    ctx.device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

/// A `Rgba16Float` input holding a checkerboard of 7-pixel cells (edges for
/// FXAA and TAA to find), or a zero `Rg16Float` velocity.
fn pattern(ctx: &GpuContext, label: &str, (w, h): (u32, u32), velocity: bool) -> wgpu::TextureView {
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let format = if velocity {
        wgpu::TextureFormat::Rg16Float
    } else {
        COLOR
    };
    let t = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    });
    let channels = if velocity { 2 } else { 4 };
    let data: Vec<u16> = (0..w * h)
        .flat_map(|i| {
            let on = ((i % w) / 7 + (i / w) / 7) % 2 == 1;
            let v = if velocity {
                0.0
            } else if on {
                0.9
            } else {
                0.1
            };
            let px = [v, v, v, 1.0];
            px.into_iter()
                .take(channels)
                .map(|x: f32| half_bits(x))
                .collect::<Vec<_>>()
        })
        .collect();
    ctx.queue.write_texture(
        t.as_image_copy(),
        bytemuck::cast_slice(&data),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(w * 2 * channels as u32),
            rows_per_image: Some(h),
        },
        t.size(),
    );
    t.create_view(&Default::default())
}

/// The binary16 bits of `x`, for the exact values the pattern uses (0, 0.1,
/// 0.9, 1; rounded toward zero, which is all a timing input needs).
fn half_bits(x: f32) -> u16 {
    if x == 0.0 {
        return 0;
    }
    let b = x.to_bits();
    let exp = ((b >> 23) & 0xff) as i32 - 127 + 15;
    ((exp as u32) << 10 | (b >> 13) & 0x3ff) as u16
}

/// Clear the MSAA depth and normal targets (a flat surface facing the
/// camera) as a host's prepass would leave them.
fn clear_prepass(ctx: &GpuContext, depth: &wgpu::TextureView, normal: &wgpu::TextureView) {
    let mut enc = ctx.device.create_command_encoder(&Default::default());
    {
        let _pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("prepass clear"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: normal,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: 0.0,
                        g: 0.0,
                        b: -1.0,
                        a: 0.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.5),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
    }
    ctx.queue.submit([enc.finish()]);
}

/// One pass, ready to encode at one size.
type Encode<'a> = Box<
    dyn Fn(&mut wgpu::CommandEncoder, Option<wgpu::ComputePassTimestampWrites<'_>>) -> Result<()>
        + 'a,
>;

/// Time `encode` alone: one warm-up, then `runs` submissions, each timed
/// as the wgpu backend times its passes (`GpuContext::timed_pass`: trusted
/// GPU timestamps, else the wall clock from submission to completion). The
/// times in ms and how they were taken.
fn time(ctx: &GpuContext, runs: u32, encode: &Encode<'_>) -> Result<(Vec<f64>, String)> {
    let mut timings = Vec::new();
    let mut encoded = Ok(());
    for _ in 0..=runs {
        ctx.timed_pass("pass", &mut timings, |enc| {
            if encoded.is_ok() {
                encoded = encode(enc, None);
            }
        })
        .map_err(|e| anyhow!("{e}"))?;
    }
    encoded?;
    let ms = timings[1..]
        .iter()
        .map(|t| t.time.as_secs_f64() * 1e3)
        .collect();
    let source = timings
        .last()
        .map_or(String::new(), |t| t.source.to_string());
    Ok((ms, source))
}

fn median(v: &[f64]) -> Value {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).map_or(Value::Null, |&m| m.into())
}

/// Every pass at `size`, as JSON rows.
fn at_size(ctx: &GpuContext, size: (u32, u32), runs: u32) -> Result<Vec<Value>> {
    let read = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
    let store = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
    let depth = texture(
        ctx,
        "msaa depth",
        size,
        4,
        wgpu::TextureFormat::Depth32Float,
        read,
    );
    let normal = texture(ctx, "msaa normal", size, 4, COLOR, read);
    clear_prepass(ctx, &depth, &normal);
    let colour = pattern(ctx, "shaded colour", size, false);
    let history = pattern(ctx, "history", size, false);
    let velocity = pattern(ctx, "velocity", size, true);
    let out = texture(ctx, "output", size, 1, COLOR, store);
    let d = &ctx.device;
    let pe = |what: &str, e: subcone_passes::PassError| anyhow!("{what}: {e}");
    // The paper's preset shades one of the four MSAA samples, so the pass
    // needs no centre geometry beside the prepass (the tuned preset shades
    // the pixel centre and would).
    let sraa = SraaPass::new(d, &SraaPassDesc::msaa().with_params(SraaParams::PAPER))
        .map_err(|e| pe("SraaPass", e))?;
    let ctss =
        CtssPass::new(d, FIELD_WGSL, &CtssPassDesc::default()).map_err(|e| pe("CtssPass", e))?;
    let fxaa = FxaaPass::new(
        d,
        &FxaaPassDesc::default().with_input(FxaaInput::ToneMapped),
    )
    .map_err(|e| pe("FxaaPass", e))?;
    let taa = TaaPass::new(d, &TaaPassDesc::default()).map_err(|e| pe("TaaPass", e))?;
    let q = &ctx.queue;
    let fov = 0.8;
    let passes: Vec<(&str, Encode<'_>)> = vec![
        (
            "SraaPass",
            Box::new(|enc, ts| {
                let inputs = SraaInputs {
                    geometry: SubsampleGeometry::Separate {
                        depth: &depth,
                        normal: &normal,
                    },
                    // Reversed Z, infinite far plane, near 0.05.
                    projection: [
                        [1.0, 0.0, 0.0, 0.0],
                        [0.0, 1.0, 0.0, 0.0],
                        [0.0, 0.0, 0.0, -1.0],
                        [0.0, 0.0, 0.05, 0.0],
                    ],
                    centre: None,
                    color: &colour,
                    shadows: None,
                    albedo: None,
                    secondary: None,
                    output: &out,
                };
                sraa.encode(d, q, enc, &inputs, ts)
                    .map_err(|e| pe("SraaPass", e))
            }),
        ),
        (
            "CtssPass",
            Box::new(|enc, ts| {
                let frame = CtssFrame {
                    camera: CtssCamera::new(Vec3::ZERO, Vec3::Z, Vec3::Y, fov).into(),
                    params: CtssParams::new(subcone_kernels::cone::cone_tan_theta(
                        fov,
                        size.1,
                        subcone_kernels::ctss::CONE_COVERAGE,
                        subcone_kernels::cone::PixelFootprint::Circumscribed,
                    ))
                    .with_range(0.0, 100.0)
                    .with_max_steps(128),
                    background: Vec3::new(0.1, 0.2, 0.3),
                    host_group: None,
                    output: &out,
                    depth: None,
                    rect: None,
                };
                ctss.encode(d, q, enc, &frame, ts)
                    .map_err(|e| pe("CtssPass", e))
            }),
        ),
        (
            "FxaaPass",
            Box::new(|enc, ts| {
                fxaa.encode(d, q, enc, &colour, &out, ts)
                    .map_err(|e| pe("FxaaPass", e))
            }),
        ),
        (
            "TaaPass",
            Box::new(|enc, ts| {
                let inputs = TaaInputs::new(&colour, &velocity, &history, 4);
                taa.encode(d, q, enc, &inputs, &out, ts)
                    .map_err(|e| pe("TaaPass", e))
            }),
        ),
    ];
    let mut rows = Vec::new();
    for (name, encode) in &passes {
        let (ms, timed_by) =
            time(ctx, runs, encode).with_context(|| format!("{name} at {size:?}"))?;
        println!(
            "{name:>9} at {}x{}: median {} ms ({timed_by})",
            size.0,
            size.1,
            median(&ms)
        );
        rows.push(json!({
            "pass": name, "width": size.0, "height": size.1, "runs": runs,
            "ms_median": median(&ms), "ms": ms, "timed_by": timed_by,
        }));
    }
    Ok(rows)
}

/// The `passes` step: every pass at every size, written as JSON to `path`.
pub fn run(path: &Path, sizes: &[(u32, u32)], runs: u32) -> Result<()> {
    if runs == 0 {
        bail!("--runs must be at least 1");
    }
    let ctx = GpuContext::new().map_err(|e| anyhow!("{e}"))?;
    let mut rows = Vec::new();
    for &size in sizes {
        ctx.check_texture_size(size.0, size.1)
            .map_err(|e| anyhow!("{e}"))?;
        rows.extend(at_size(&ctx, size, runs)?);
    }
    let value = json!({
        "adapter": ctx.info.name,
        "device_type": format!("{:?}", ctx.info.device_type),
        "software": ctx.info.device_type == wgpu::DeviceType::Cpu,
        "timestamps_trusted": ctx.timestamps,
        "rows": rows,
    });
    std::fs::write(path, serde_json::to_string_pretty(&value)? + "\n")
        .with_context(|| format!("writing {}", path.display()))
}
