//! The one way this backend runs WGSL: shader assembly, one pipeline
//! cache, dispatch and read-back, over the bindings of
//! `subcone_passes::bind`, the binding layer the passes use too.
//!
//! A GPU pass is one `.rs` beside one `.wgsl`. The `.wgsl` holds the pass's
//! structs, functions and entry points and no `@binding` line. The `.rs`
//! lists what the pass binds in a [`Bindings`] (buffers allocated through
//! [`Allocate`], inside the context's error scopes), which writes both the
//! WGSL declarations (`@group(g) @binding(i) var…`) and the bind group from
//! the same list, so a binding number cannot drift between the two. A
//! [`Program`] assembles the shader ([`PRELUDE`], the pass's sources, the
//! declarations), compiles it once per device and source (cached under a
//! [`ComputePipelineKey`]), and dispatches its entry points with every group bound.
//! Work runs inside the context's error scopes, so a shader that fails to
//! validate is a [`RenderError`], never a panic.
//!
//! Triangles (`triangles/`), SDF scenes (`sdf/`), their AOV passes, FXAA
//! (`post/`) and the kernel test harness (`test_util`) all go through here;
//! the raster pass declares its bind group through [`Bindings`] too.

use std::sync::Arc;

use bytemuck::Pod;
use subcone_scene::RenderError;
use wgpu::util::DeviceExt;

use crate::context::{err, CacheKey, GpuContext};
use subcone_passes::bind::{self, Bindings, BufferAccess};

/// What every shader starts with: the kernels' shared structs and the one
/// WGSL spelling of infinity and of the NaN and finiteness tests
/// (`subcone_inf`, `subcone_is_nan`, `subcone_is_finite`).
pub(crate) const PRELUDE: &str = subcone_kernels::wgsl::PARAMS;

/// A compute pipeline's cache key: the program's whole assembled source
/// (prelude, sources and binding declarations) and the entry point.
#[derive(Clone, PartialEq, Eq, Hash)]
pub(crate) struct ComputePipelineKey {
    source: Arc<str>,
    entry: &'static str,
}

impl CacheKey for ComputePipelineKey {
    type Value = wgpu::ComputePipeline;
}

/// What this backend adds to [`Bindings`]: buffers allocated inside the
/// context's error scopes (an allocation the device refuses is a
/// [`RenderError`]) and accounted in the bindings (for `FrameStats`), and
/// a bound buffer looked up as a `Result`.
pub(crate) trait Allocate {
    /// A uniform `var: ty` holding `value`.
    fn uniform<T: Pod>(
        &mut self,
        ctx: &GpuContext,
        var: &'static str,
        ty: &str,
        value: &T,
    ) -> Result<(), RenderError>;

    /// A zeroed read-write storage buffer of `bytes` (at least 16), bound as
    /// `var: ty` and accounted as `name`. It can be copied to and from.
    fn storage(
        &mut self,
        ctx: &GpuContext,
        name: &'static str,
        var: &'static str,
        ty: &str,
        bytes: u64,
    ) -> Result<(), RenderError>;

    /// The buffer bound as `var`.
    fn get(&self, var: &str) -> Result<&wgpu::Buffer, RenderError>;
}

impl Allocate for Bindings {
    fn uniform<T: Pod>(
        &mut self,
        ctx: &GpuContext,
        var: &'static str,
        ty: &str,
        value: &T,
    ) -> Result<(), RenderError> {
        let b = ctx.scoped(var, || {
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(var),
                    contents: bytemuck::bytes_of(value),
                    usage: wgpu::BufferUsages::UNIFORM,
                })
        })?;
        self.buffer(var, ty, BufferAccess::Uniform, &b);
        Ok(())
    }

    fn storage(
        &mut self,
        ctx: &GpuContext,
        name: &'static str,
        var: &'static str,
        ty: &str,
        bytes: u64,
    ) -> Result<(), RenderError> {
        ctx.check_buffer_size(name, bytes)?;
        let b = ctx.scoped(name, || {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(name),
                size: bytes.max(16),
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        })?;
        self.account(name, bytes as usize);
        self.buffer(var, ty, BufferAccess::ReadWrite, &b);
        Ok(())
    }

    fn get(&self, var: &str) -> Result<&wgpu::Buffer, RenderError> {
        self.buffer_named(var)
            .ok_or_else(|| err(format!("no buffer `{var}` is bound")))
    }
}

/// How this backend's programs read a sampled texture: `f32` texels with
/// `textureLoad`, never filtered.
pub(crate) const FLOAT: wgpu::TextureSampleType =
    wgpu::TextureSampleType::Float { filterable: false };

/// A bind-group declaration the device refused to take (a format without a
/// WGSL storage name), as a render error.
pub(crate) fn bind_err(e: subcone_passes::PassError) -> RenderError {
    err(format!("bindings: {e}"))
}

/// A compute shader with its bind groups: [`PRELUDE`], the pass's sources
/// and the declarations of its [`Bindings`], compiled lazily and at most
/// once per device and source.
pub(crate) struct Program<'a> {
    ctx: &'a GpuContext,
    label: &'static str,
    source: Arc<str>,
    module: Option<wgpu::ShaderModule>,
    layout: wgpu::PipelineLayout,
    groups: Vec<wgpu::BindGroup>,
}

impl<'a> Program<'a> {
    /// The program of `sources` (after the prelude) binding `groups`, whose
    /// group numbers must be 0, 1, … in order.
    pub(crate) fn new(
        ctx: &'a GpuContext,
        label: &'static str,
        sources: &[&str],
        groups: &[&Bindings],
    ) -> Result<Self, RenderError> {
        if let Some((i, g)) = groups
            .iter()
            .enumerate()
            .find(|(i, g)| g.group().index() != *i as u32)
        {
            return Err(err(format!(
                "{label}: bind group {i} is declared as group {}",
                g.group().index()
            )));
        }
        let mut source = String::from(PRELUDE);
        for s in sources {
            source.push_str(s);
        }
        for g in groups {
            source.push_str(&g.declarations());
        }
        let source: Arc<str> = source.into();
        ctx.scoped(label, || {
            let layouts: Vec<wgpu::BindGroupLayout> = groups
                .iter()
                .map(|g| g.layout(&ctx.device, label))
                .collect();
            let layout =
                bind::pipeline_layout(&ctx.device, label, &layouts.iter().collect::<Vec<_>>());
            let bound = groups
                .iter()
                .zip(&layouts)
                .map(|(g, l)| g.bind_group(&ctx.device, label, l))
                .collect();
            Program {
                ctx,
                label,
                source,
                module: None,
                layout,
                groups: bound,
            }
        })
    }

    /// The pipeline of entry point `entry`, compiled on first use per device.
    pub(crate) fn pipeline(
        &mut self,
        entry: &'static str,
    ) -> Result<Arc<wgpu::ComputePipeline>, RenderError> {
        let ctx = self.ctx;
        let key = ComputePipelineKey {
            source: self.source.clone(),
            entry,
        };
        ctx.cached_or_insert(key, |_| {
            if self.module.is_none() {
                let (label, source) = (self.label, &self.source);
                self.module = Some(ctx.scoped(label, || {
                    ctx.device
                        .create_shader_module(wgpu::ShaderModuleDescriptor {
                            label: Some(label),
                            source: wgpu::ShaderSource::Wgsl(source.as_ref().into()),
                        })
                })?);
            }
            let (module, layout) = (self.module.as_ref().expect("compiled above"), &self.layout);
            ctx.scoped(entry, || {
                bind::compute_pipeline(&ctx.device, entry, layout, module, entry)
            })
        })
    }

    /// Record one compute pass running `pipeline` over `workgroups`, with
    /// every group of this program bound.
    pub(crate) fn dispatch(
        &self,
        enc: &mut wgpu::CommandEncoder,
        pipeline: &wgpu::ComputePipeline,
        workgroups: (u32, u32),
    ) {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.label),
            timestamp_writes: None,
        });
        pass.set_pipeline(pipeline);
        for (i, g) in self.groups.iter().enumerate() {
            pass.set_bind_group(i as u32, g, &[]);
        }
        pass.dispatch_workgroups(workgroups.0, workgroups.1, 1);
    }
}

/// Workgroups of `size × size` invocations covering `width × height`, or an
/// error naming `what` when the device cannot dispatch that many.
pub(crate) fn workgroups(
    ctx: &GpuContext,
    what: &str,
    width: u32,
    height: u32,
    size: u32,
) -> Result<(u32, u32), RenderError> {
    let groups = (width.div_ceil(size), height.div_ceil(size));
    let max = ctx.device.limits().max_compute_workgroups_per_dimension;
    if groups.0 > max || groups.1 > max {
        return Err(err(format!(
            "{what}: {width}x{height} needs more than {max} workgroups per dimension"
        )));
    }
    Ok(groups)
}

/// The first `count` values of type `T` in `buffer` (which needs `COPY_SRC`).
pub(crate) fn read<T: Pod>(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
    count: usize,
) -> Result<Vec<T>, RenderError> {
    let bytes = ctx.read_buffer(buffer, 0, (count * std::mem::size_of::<T>()) as u64)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
