//! The TAA resolve (`subcone_kernels::taa`: Karis 2014 with Salvi's variance
//! clipping) on the GPU through [`subcone_passes::TaaPass`], the pass a host
//! renderer runs: the frame's colours, velocities, depths (with
//! closest-depth dilation) and history are written into the pass's input
//! textures, resolved into its output and read back, timed as the pass
//! `"taa"`. What `subcone_scene::temporal::Taa` calls through
//! `Backend::resolve_taa`.

use std::sync::Arc;

use glam::Vec3;
use subcone_kernels::taa::{DepthDilation, ResolveSpace, TaaSettings};
use subcone_passes::{TaaInputs, TaaPass, TaaPassDesc};
use subcone_scene::history::TaaInput;
use subcone_scene::{PassTiming, RenderError};

use crate::context::{err, CacheKey, GpuContext};

const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const VELOCITY: wgpu::TextureFormat = wgpu::TextureFormat::Rg32Float;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// The TAA pass's cache key: the bits of the settings the resolve reads
/// (tone mapped, exposure, smallest current weight, clip γ, depth
/// dilation).
#[derive(PartialEq, Eq, Hash)]
struct TaaPassKey([u32; 5]);

impl CacheKey for TaaPassKey {
    type Value = TaaPass;
}

/// The pass on this device for `input`'s parameters, compiled once per
/// device and parameters.
fn pass(ctx: &GpuContext, input: &TaaInput<'_>) -> Result<Arc<TaaPass>, RenderError> {
    let p = &input.params;
    let key = TaaPassKey([
        p.tone_mapped,
        p.exposure.to_bits(),
        p.min_current_weight.to_bits(),
        p.clip_gamma.to_bits(),
        p.depth_dilation,
    ]);
    ctx.cached_or_insert(key, |_| {
        let space = if p.tone_mapped == 1 {
            ResolveSpace::ToneMapped {
                exposure: p.exposure,
            }
        } else {
            ResolveSpace::Linear
        };
        let settings = TaaSettings {
            space,
            min_current_weight: p.min_current_weight,
            clip_gamma: p.clip_gamma,
            depth_dilation: DepthDilation::from_code(p.depth_dilation),
            ..TaaSettings::default()
        };
        let desc = TaaPassDesc::default()
            .with_settings(settings)
            .with_output_format(COLOR);
        ctx.scoped("taa", || TaaPass::new(&ctx.device, &desc))?
            .map_err(|e| err(format!("TAA: {e}")))
    })
}

/// The resolve of `input` on the GPU: the resolved colours and the pass's
/// timing.
pub(crate) fn resolve(
    ctx: &GpuContext,
    input: &TaaInput<'_>,
) -> Result<(Vec<Vec3>, PassTiming), RenderError> {
    input.validate()?;
    let (w, h) = (input.params.width, input.params.height);
    ctx.check_texture_size(w, h)?;
    let taa = pass(ctx, input)?;
    let rgba = |c: &[Vec3]| -> Vec<f32> { c.iter().flat_map(|v| [v.x, v.y, v.z, 1.0]).collect() };
    let current = rgba(input.current);
    let history = if input.params.history_frames == 0 {
        vec![0.0; current.len()]
    } else {
        rgba(input.history)
    };
    let velocity: Vec<f32> = input.velocity.iter().flat_map(|v| [v.x, v.y]).collect();
    // A pass without dilation binds no depth (and the key keeps it apart
    // from one with).
    let depth = input.depth.filter(|_| input.dilation().is_on());
    let read = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let textures = ctx.scoped("taa textures", || {
        let upload = |label, format, data: &[f32], texel: u32| {
            let t = ctx.frame_texture(label, (w, h), format, read);
            ctx.queue.write_texture(
                t.as_image_copy(),
                bytemuck::cast_slice(data),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(w * texel),
                    rows_per_image: Some(h),
                },
                t.size(),
            );
            t
        };
        let textures = [
            upload("taa current", COLOR, &current, 16),
            upload("taa velocity", VELOCITY, &velocity, 8),
            upload("taa history", COLOR, &history, 16),
            ctx.frame_texture(
                "taa output",
                (w, h),
                COLOR,
                wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
            ),
        ];
        let depth = depth.map(|d| upload("taa depth", DEPTH, d, 4));
        (textures, depth)
    })?;
    let (textures, depth) = textures;
    let [current, velocity, history, output] =
        textures.map(|t| (t.create_view(&Default::default()), t));
    let depth = depth.map(|t| t.create_view(&Default::default()));
    let mut timings = Vec::new();
    let mut encoded = Ok(());
    ctx.timed_pass("taa", &mut timings, |enc| {
        let mut inputs = TaaInputs::new(
            &current.0,
            &velocity.0,
            &history.0,
            input.params.history_frames,
        )
        .with_motion_scale(input.params.motion_scale);
        if let Some(d) = &depth {
            inputs = inputs.with_depth(d);
        }
        encoded = taa.encode(&ctx.device, &ctx.queue, enc, &inputs, &output.0, None);
        // The textures are this frame's: the shared pass need not keep them.
        taa.release_views();
    })?;
    encoded.map_err(|e| err(format!("TAA: {e}")))?;
    // Rows of a texture-to-buffer copy are 256-byte aligned.
    let row = w * 16;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let colors = ctx.read_back(
        "taa read-back",
        padded as u64 * h as u64,
        |enc, staging| {
            enc.copy_texture_to_buffer(
                output.1.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: staging,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(padded),
                        rows_per_image: Some(h),
                    },
                },
                output.1.size(),
            )
        },
        |bytes| {
            bytes
                .chunks(padded as usize)
                .flat_map(|r| {
                    let px: &[[f32; 4]] = bytemuck::cast_slice(&r[..row as usize]);
                    px.iter()
                        .map(|c| Vec3::new(c[0], c[1], c[2]))
                        .collect::<Vec<_>>()
                })
                .collect::<Vec<Vec3>>()
        },
    )?;
    let timing = timings
        .pop()
        .ok_or_else(|| err("TAA: the pass was not timed"))?;
    Ok((colors, timing))
}
