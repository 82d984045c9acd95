//! Test support (feature `test-util`): the one way tests run WGSL on the GPU,
//! and the one rule for what a test does without an adapter.
//!
//! Every kernel of `subcone-kernels` has a WGSL twin; the kernel conformance
//! suite (`tests/conformance_kernels.rs` at the workspace root) runs each
//! twin through [`run_wgsl`] and compares it with the Rust kernel. Keeping one
//! harness means one set of buffer layouts, one error path (the device's error
//! scopes, so a shader that fails to compile is an `Err`, not a panic) and one
//! place to change when wgpu changes.

use crate::compute::{self, Allocate, Program};
use crate::context::{err, GpuContext};
use crate::WgpuBackend;
use bytemuck::Pod;
use subcone_passes::bind::{Bindings, BufferAccess};
use subcone_scene::RenderError;
use wgpu::util::DeviceExt;

/// The backend on the shared device, or `None` when there is no adapter and
/// `SUBCONE_REQUIRE_GPU` is unset (the test then skips, printing why, so
/// machines without a GPU still run the rest of the suite). With
/// `SUBCONE_REQUIRE_GPU` set, as CI sets it, no adapter panics: a GPU test
/// must never pass by skipping where a GPU is expected.
///
/// `what` names the test or part that skips, for the message.
pub fn gpu_or_skip(what: &str) -> Option<WgpuBackend> {
    subcone_scene::conformance::or_skip(what, WgpuBackend::new())
}

/// A read-only storage buffer besides the records, declared by the harness
/// as `var<storage, read> {name}: {wgsl_type};` (e.g. a generated SDF's
/// `sdf_data` scatter table).
#[derive(Clone, Copy, Debug)]
pub struct Table<'a> {
    /// The WGSL variable name.
    pub name: &'a str,
    /// Its WGSL type, e.g. `array<vec4<f32>>`.
    pub wgsl_type: &'a str,
    /// Its contents.
    pub bytes: &'a [u8],
}

/// One compute kernel under test: WGSL run once per input record.
#[derive(Clone, Copy, Debug)]
pub struct Kernel<'a> {
    /// The WGSL the body calls: kernel sources (e.g. `subcone_kernels::
    /// cone::WGSL`). The harness puts the prelude, `subcone_kernels::wgsl::
    /// PARAMS`, before them, as every shader of this backend has it.
    pub library: &'a str,
    /// WGSL statements run once per record. They read the record through
    /// `f(k)` (its word `k` as `f32`), `u(k)` (as `u32`) and `v3(k)` (words
    /// `k..k + 3` as `vec3<f32>`), and write the record's output words
    /// `out[o + j]` (`u32`; write floats with `bitcast<u32>`) for
    /// `j < out_words`. `i` is the record's index.
    pub body: &'a str,
    /// Words (4 bytes) per input record.
    pub in_words: usize,
    /// Words per output record.
    pub out_words: usize,
    /// Extra read-only buffers the library reads.
    pub tables: &'a [Table<'a>],
}

/// Run `kernel` on every record of `input` in one compute dispatch on `ctx`
/// and return the outputs, `out_words` per record, as `O`s (whose size must
/// divide the output).
///
/// The input is any plain-old-data slice whose size is a whole number of
/// records. Errors (never panics) on no records, a record count one dispatch
/// cannot hold, WGSL that does not compile or validate, and any GPU failure:
/// the work runs inside the context's error scopes ([`GpuContext::scoped`])
/// and is waited for with its timeout ([`GpuContext::wait`]).
pub fn run_wgsl<I: Pod, O: Pod>(
    ctx: &GpuContext,
    kernel: &Kernel<'_>,
    input: &[I],
) -> Result<Vec<O>, RenderError> {
    let bytes: &[u8] = bytemuck::cast_slice(input);
    let record_bytes = kernel.in_words * 4;
    if record_bytes == 0 || bytes.is_empty() || bytes.len() % record_bytes != 0 {
        return Err(err(format!(
            "run_wgsl: {} input bytes are not a positive number of {}-word records",
            bytes.len(),
            kernel.in_words
        )));
    }
    let n = bytes.len() / record_bytes;
    let out_bytes = (n * kernel.out_words * 4) as u64;
    let unit = std::mem::size_of::<O>() as u64;
    if out_bytes == 0 || unit == 0 || out_bytes % unit != 0 {
        return Err(err(format!(
            "run_wgsl: {out_bytes} output bytes are not a whole number of {unit}-byte values"
        )));
    }
    let groups = n.div_ceil(64);
    if groups as u64 > ctx.device.limits().max_compute_workgroups_per_dimension as u64 {
        return Err(err(format!(
            "run_wgsl: {n} records are too many for one dispatch"
        )));
    }
    ctx.check_buffer_size("run_wgsl inputs", bytes.len() as u64)?;
    ctx.check_buffer_size("run_wgsl outputs", out_bytes)?;
    // The names are the harness's own (`run_wgsl_*`) or the body's
    // documented ones (`f`, `u`, `v3`, `out`, `i`, `o`).
    let mut b = Bindings::new(0);
    storage_init(
        &mut b,
        ctx,
        "run_wgsl inputs",
        "run_wgsl_in".into(),
        "array<u32>",
        BufferAccess::Read,
        bytes,
    )?;
    b.storage(ctx, "run_wgsl outputs", "out", "array<u32>", out_bytes)?;
    for t in kernel.tables {
        storage_init(
            &mut b,
            ctx,
            "run_wgsl table",
            t.name.to_string().into(),
            t.wgsl_type,
            BufferAccess::Read,
            t.bytes,
        )?;
    }
    let entry = format!(
        "\nvar<private> run_wgsl_base: u32;\n\
         fn f(k: u32) -> f32 {{ return bitcast<f32>(run_wgsl_in[run_wgsl_base + k]); }}\n\
         fn u(k: u32) -> u32 {{ return run_wgsl_in[run_wgsl_base + k]; }}\n\
         fn v3(k: u32) -> vec3<f32> {{ return vec3<f32>(f(k), f(k + 1u), f(k + 2u)); }}\n\
         @compute @workgroup_size(64)\n\
         fn run_wgsl_main(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
             let i = gid.x;\n\
             if i >= {n}u {{ return; }}\n\
             run_wgsl_base = i * {in_words}u;\n\
             let o = i * {out_words}u;\n\
             {body}\n\
         }}\n",
        in_words = kernel.in_words,
        out_words = kernel.out_words,
        body = kernel.body,
    );
    let mut program = Program::new(ctx, "run_wgsl", &[kernel.library, &entry], &[&b])?;
    let pipeline = program.pipeline("run_wgsl_main")?;
    ctx.timed_pass("run_wgsl", &mut Vec::new(), |enc| {
        program.dispatch(enc, &pipeline, (groups as u32, 1))
    })?;
    compute::read(ctx, b.get("out")?, (out_bytes / unit) as usize)
}

/// A storage buffer holding `contents`, bound in `b` as `var: ty` with
/// `access` and accounted as `name` (the harness's inputs and tables).
fn storage_init(
    b: &mut Bindings,
    ctx: &GpuContext,
    name: &'static str,
    var: std::borrow::Cow<'static, str>,
    ty: &str,
    access: BufferAccess,
    contents: &[u8],
) -> Result<(), RenderError> {
    ctx.check_buffer_size(name, contents.len() as u64)?;
    let buffer = ctx.scoped(name, || {
        ctx.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(name),
                contents,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            })
    })?;
    b.account(name, contents.len());
    b.buffer(var, ty, access, &buffer);
    Ok(())
}
