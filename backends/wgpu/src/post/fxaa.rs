//! FXAA 3.11 (`subcone_kernels::fxaa`, preset 12) on the GPU through
//! [`subcone_passes::FxaaPass`], the pass a host renderer runs: the frame's
//! colour buffer (`array<vec4<f32>>`, linear RGB) is copied into the pass's
//! input texture, filtered into its output texture and copied into a new
//! buffer (`fxaa.wgsl`), timed together as the pass `"post-process"`. The
//! input buffer is left untouched; the filtered frame is a new buffer for
//! the caller to read back.

use std::sync::Arc;

use subcone_kernels::fxaa::FxaaParams;
use subcone_passes::{FxaaInput, FxaaPass, FxaaPassDesc};
use subcone_scene::{PassTiming, RenderError};

use crate::compute::{self, Allocate, Program};
use crate::context::{err, CacheKey, GpuContext};
use subcone_passes::bind::{Bindings, BufferAccess};

pub(crate) const FXAA_WGSL: &str = include_str!("fxaa.wgsl");
const WORKGROUP: u32 = 8;
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The filtered frame and the buffers and textures a pass allocated, by
/// name and bytes.
type Filtered = (wgpu::Buffer, Vec<(&'static str, usize)>);

/// The FXAA pass's cache key: the bits of its parameters, the one input
/// of its descriptor ([`pass`] fixes the rest).
#[derive(PartialEq, Eq, Hash)]
struct FxaaPassKey([u32; size_of::<FxaaParams>() / 4]);

impl CacheKey for FxaaPassKey {
    type Value = FxaaPass;
}

/// The pass on this device for `params`, compiled once per device and
/// parameters.
fn pass(ctx: &GpuContext, params: &FxaaParams) -> Result<Arc<FxaaPass>, RenderError> {
    let key = FxaaPassKey(bytemuck::cast(*params));
    ctx.cached_or_insert(key, |_| {
        // The frame is FXAA's display-referred input (the kernel clamps
        // it to [0, 1], as the CPU's post-process does).
        let desc = FxaaPassDesc::default()
            .with_input(FxaaInput::ToneMapped)
            .with_params(*params)
            .with_output_format(FORMAT);
        ctx.scoped("fxaa", || FxaaPass::new(&ctx.device, &desc))?
            .map_err(|e| err(format!("FXAA: {e}")))
    })
}

/// FXAA of the `width`×`height` frame in `color` (16 bytes per pixel, needs
/// `STORAGE`): the filtered frame (`STORAGE | COPY_SRC`, same layout) and the
/// buffers and textures the pass allocated, by name. Pushes the pass's
/// timing onto `timings`.
pub(crate) fn run(
    ctx: &GpuContext,
    color: &wgpu::Buffer,
    width: u32,
    height: u32,
    params: &FxaaParams,
    timings: &mut Vec<PassTiming>,
) -> Result<Filtered, RenderError> {
    let px_bytes = width as u64 * height as u64 * 16;
    if color.size() < px_bytes {
        return Err(err(format!(
            "FXAA: the colour buffer holds {} bytes, {width}x{height} needs {px_bytes}",
            color.size()
        )));
    }
    let groups = compute::workgroups(ctx, "FXAA", width, height, WORKGROUP)?;
    let fxaa = pass(ctx, params)?;
    let texture = |label: &'static str| {
        ctx.frame_texture(
            label,
            (width, height),
            FORMAT,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::STORAGE_BINDING,
        )
    };
    let (input, output) = ctx.scoped("post-process textures", || {
        (
            texture("post-process input"),
            texture("post-process output"),
        )
    })?;
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    let (input, output) = (view(&input), view(&output));
    let mut b = Bindings::new(0);
    b.buffer("fxaa_src", "array<vec4<f32>>", BufferAccess::Read, color);
    b.storage_texture("fxaa_in", FORMAT, &input)
        .map_err(crate::compute::bind_err)?;
    b.texture(
        "fxaa_out",
        crate::compute::FLOAT,
        wgpu::TextureViewDimension::D2,
        false,
        &output,
    );
    b.storage(
        ctx,
        "post-process output buffer",
        "fxaa_dst",
        "array<vec4<f32>>",
        px_bytes,
    )?;
    let mut program = Program::new(ctx, "fxaa copies", &[FXAA_WGSL], &[&b])?;
    let to_texture = program.pipeline("fxaa_to_texture_main")?;
    let from_texture = program.pipeline("fxaa_from_texture_main")?;
    let mut encoded = Ok(());
    ctx.timed_pass("post-process", timings, |enc| {
        // Three compute passes: the pass boundaries order the copy in, the
        // filter and the copy out.
        program.dispatch(enc, &to_texture, groups);
        encoded = fxaa.encode(&ctx.device, &ctx.queue, enc, &input, &output, None);
        // The textures are this frame's: the shared pass need not keep them
        // (the encoder holds what it recorded).
        fxaa.release_views();
        program.dispatch(enc, &from_texture, groups);
    })?;
    encoded.map_err(|e| err(format!("FXAA: {e}")))?;
    let mut stats = b.accounts().to_vec();
    stats.push(("post-process input", px_bytes as usize));
    stats.push(("post-process output", px_bytes as usize));
    Ok((b.get("fxaa_dst")?.clone(), stats))
}
