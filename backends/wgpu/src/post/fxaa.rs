//! FXAA 3.11 (`subcone_kernels::fxaa`, preset 12) on the GPU: two compute
//! passes over a frame's colour buffer (`array<vec4<f32>>`, linear RGB),
//! encode (clamp, sRGB, luma) then filter and decode, timed together as the
//! pass `"post-process"`. The input buffer is left untouched; the filtered
//! frame is a new buffer for the caller to read back.

use bytemuck::{Pod, Zeroable};
use subcone_kernels::fxaa::FxaaParams;
use subcone_scene::{PassTiming, RenderError};

use crate::compute::{self, Access, Bindings, Program};
use crate::context::{err, GpuContext};

pub(crate) const FXAA_WGSL: &str = include_str!("fxaa.wgsl");
const WORKGROUP: u32 = 8;

/// The frame's size; `FxaaFrame` in fxaa.wgsl (16 bytes).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub(crate) struct FxaaFrame {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) _pad: [u32; 2],
}

/// The filtered frame and the buffers a pass allocated, by name and bytes.
type Filtered = (wgpu::Buffer, Vec<(&'static str, usize)>);

/// FXAA of the `width`×`height` frame in `color` (16 bytes per pixel, needs
/// `STORAGE`): the filtered frame (`STORAGE | COPY_SRC`, same layout) and the
/// buffers the pass allocated, by name. Pushes the pass's timing onto
/// `timings`.
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
    let frame = FxaaFrame {
        width,
        height,
        _pad: [0; 2],
    };
    let mut b = Bindings::new(0);
    b.uniform(ctx, "fxaa_params", "subcone_FxaaParams", params)?;
    b.uniform(ctx, "fxaa_frame", "FxaaFrame", &frame)?;
    b.buffer("fxaa_src", "array<vec4<f32>>", Access::Read, color);
    b.storage(
        ctx,
        "post-process input",
        "fxaa_encoded",
        "array<vec4<f32>>",
        px_bytes,
    )?;
    b.storage(
        ctx,
        "post-process output",
        "fxaa_dst",
        "array<vec4<f32>>",
        px_bytes,
    )?;
    let mut program = Program::new(
        ctx,
        "fxaa",
        &[subcone_kernels::fxaa::WGSL, FXAA_WGSL],
        &[&b],
    )?;
    let encode = program.pipeline("fxaa_encode_main")?;
    let filter = program.pipeline("fxaa_main")?;
    ctx.timed_pass("post-process", timings, |enc| {
        // Two compute passes, so that every encoded pixel is written before
        // any is read (the pass boundary orders them).
        program.dispatch(enc, &encode, groups);
        program.dispatch(enc, &filter, groups);
    })?;
    Ok((b.get("fxaa_dst")?.clone(), b.stats))
}
