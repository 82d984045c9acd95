//! The one way this backend runs WGSL: shader assembly, bindings declared
//! once, one pipeline cache, dispatch and read-back.
//!
//! A GPU pass is one `.rs` beside one `.wgsl`. The `.wgsl` holds the pass's
//! structs, functions and entry points and no `@binding` line. The `.rs`
//! lists what the pass binds in a [`Bindings`], which writes both the WGSL
//! declarations (`@group(g) @binding(i) var…`) and the bind group from the
//! same list, so a binding number cannot drift between the two. A
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

/// How a shader reads a binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Access {
    /// `var<uniform>`.
    Uniform,
    /// `var<storage, read>`.
    Read,
    /// `var<storage, read_write>`.
    ReadWrite,
    /// A `texture_2d_array<f32>`, read with `textureLoad` (not filtered).
    Texture,
    /// A `texture_2d<f32>`, read with `textureLoad` (not filtered).
    Texture2d,
    /// A write-only `texture_storage_2d` of this format.
    StorageTexture(wgpu::TextureFormat),
}

enum Resource {
    Buffer(wgpu::Buffer),
    Texture(wgpu::TextureView),
}

struct Binding {
    var: String,
    ty: String,
    access: Access,
    resource: Resource,
}

/// One bind group, declared once: binding `i` is the `i`-th entry added.
/// [`Bindings::declarations`] is its WGSL, [`Bindings::layout`] and
/// [`Bindings::bind_group`] its wgpu objects.
pub(crate) struct Bindings {
    group: u32,
    visibility: wgpu::ShaderStages,
    list: Vec<Binding>,
    /// The buffers this group allocated, by name and bytes (for `FrameStats`).
    pub(crate) stats: Vec<(&'static str, usize)>,
}

impl Bindings {
    /// An empty group `group` of a compute shader.
    pub(crate) fn new(group: u32) -> Self {
        Self::visible_in(group, wgpu::ShaderStages::COMPUTE)
    }

    /// An empty group `group` visible to `stages` (the raster pass's group
    /// is read by its vertex and fragment stages).
    pub(crate) fn visible_in(group: u32, stages: wgpu::ShaderStages) -> Self {
        Bindings {
            group,
            visibility: stages,
            list: Vec::new(),
            stats: Vec::new(),
        }
    }

    fn push(&mut self, var: &str, ty: &str, access: Access, resource: Resource) {
        self.list.push(Binding {
            var: var.to_string(),
            ty: ty.to_string(),
            access,
            resource,
        });
    }

    /// Bind an existing buffer (shared by the caller, e.g. a cached scene's)
    /// as `var: ty`.
    pub(crate) fn buffer(&mut self, var: &str, ty: &str, access: Access, b: &wgpu::Buffer) {
        self.push(var, ty, access, Resource::Buffer(b.clone()));
    }

    /// A uniform `var: ty` holding `value`.
    pub(crate) fn uniform<T: Pod>(
        &mut self,
        ctx: &GpuContext,
        var: &str,
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
        self.push(var, ty, Access::Uniform, Resource::Buffer(b));
        Ok(())
    }

    /// A zeroed read-write storage buffer of `bytes` (at least 16), bound as
    /// `var: ty` and reported as `name`. It can be copied to and from.
    pub(crate) fn storage(
        &mut self,
        ctx: &GpuContext,
        name: &'static str,
        var: &str,
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
        self.stats.push((name, bytes as usize));
        self.push(var, ty, Access::ReadWrite, Resource::Buffer(b));
        Ok(())
    }

    /// A storage buffer holding `contents`, bound as `var: ty` with `access`
    /// and reported as `name`.
    #[cfg_attr(not(feature = "test-util"), allow(dead_code))]
    pub(crate) fn storage_init(
        &mut self,
        ctx: &GpuContext,
        name: &'static str,
        var: &str,
        ty: &str,
        access: Access,
        contents: &[u8],
    ) -> Result<(), RenderError> {
        ctx.check_buffer_size(name, contents.len() as u64)?;
        let b = ctx.scoped(name, || {
            ctx.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(name),
                    contents,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                })
        })?;
        self.stats.push((name, contents.len()));
        self.push(var, ty, access, Resource::Buffer(b));
        Ok(())
    }

    /// A texture array `var` (`texture_2d_array<f32>`).
    pub(crate) fn texture(&mut self, var: &str, view: wgpu::TextureView) {
        self.push(
            var,
            "texture_2d_array<f32>",
            Access::Texture,
            Resource::Texture(view),
        );
    }

    /// A 2D texture `var` (`texture_2d<f32>`).
    pub(crate) fn texture_2d(&mut self, var: &str, view: wgpu::TextureView) {
        self.push(
            var,
            "texture_2d<f32>",
            Access::Texture2d,
            Resource::Texture(view),
        );
    }

    /// A write-only 2D storage texture `var` of `format`, whose WGSL name is
    /// `wgsl_format` (e.g. `rgba32float`).
    pub(crate) fn storage_texture(
        &mut self,
        var: &str,
        format: wgpu::TextureFormat,
        wgsl_format: &str,
        view: wgpu::TextureView,
    ) {
        self.push(
            var,
            &format!("texture_storage_2d<{wgsl_format}, write>"),
            Access::StorageTexture(format),
            Resource::Texture(view),
        );
    }

    /// Whether `var` is bound.
    pub(crate) fn has(&self, var: &str) -> bool {
        self.list.iter().any(|b| b.var == var)
    }

    /// The buffer bound as `var`.
    pub(crate) fn get(&self, var: &str) -> Result<&wgpu::Buffer, RenderError> {
        self.list
            .iter()
            .find_map(|b| match &b.resource {
                Resource::Buffer(buf) if b.var == var => Some(buf),
                _ => None,
            })
            .ok_or_else(|| err(format!("no buffer `{var}` is bound")))
    }

    /// The WGSL declarations of the group, one line per binding.
    pub(crate) fn declarations(&self) -> String {
        let mut s = String::new();
        for (i, b) in self.list.iter().enumerate() {
            let space = match b.access {
                Access::Uniform => "<uniform>",
                Access::Read => "<storage, read>",
                Access::ReadWrite => "<storage, read_write>",
                Access::Texture | Access::Texture2d | Access::StorageTexture(_) => "",
            };
            s += &format!(
                "@group({}) @binding({i}) var{space} {}: {};\n",
                self.group, b.var, b.ty
            );
        }
        s
    }

    /// The group's layout.
    pub(crate) fn layout(&self, ctx: &GpuContext) -> wgpu::BindGroupLayout {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = self
            .list
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let buffer = |ty| wgpu::BindingType::Buffer {
                    ty,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                };
                wgpu::BindGroupLayoutEntry {
                    binding: i as u32,
                    visibility: self.visibility,
                    ty: match b.access {
                        Access::Uniform => buffer(wgpu::BufferBindingType::Uniform),
                        Access::Read => {
                            buffer(wgpu::BufferBindingType::Storage { read_only: true })
                        }
                        Access::ReadWrite => {
                            buffer(wgpu::BufferBindingType::Storage { read_only: false })
                        }
                        Access::Texture => wgpu::BindingType::Texture {
                            sample_type: wgpu::TextureSampleType::Float { filterable: false },
                            view_dimension: wgpu::TextureViewDimension::D2Array,
                            multisampled: false,
                        },
                        Access::Texture2d => wgpu::BindingType::Texture {
                            sample_type: wgpu::TextureSampleType::Float { filterable: false },
                            view_dimension: wgpu::TextureViewDimension::D2,
                            multisampled: false,
                        },
                        Access::StorageTexture(format) => wgpu::BindingType::StorageTexture {
                            access: wgpu::StorageTextureAccess::WriteOnly,
                            format,
                            view_dimension: wgpu::TextureViewDimension::D2,
                        },
                    },
                    count: None,
                }
            })
            .collect();
        ctx.device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: None,
                entries: &entries,
            })
    }

    /// The bind group of these bindings, for `layout` (from
    /// [`Bindings::layout`]).
    pub(crate) fn bind_group(
        &self,
        ctx: &GpuContext,
        layout: &wgpu::BindGroupLayout,
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = self
            .list
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: match &b.resource {
                    Resource::Buffer(buf) => buf.as_entire_binding(),
                    Resource::Texture(v) => wgpu::BindingResource::TextureView(v),
                },
            })
            .collect();
        ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout,
            entries: &entries,
        })
    }
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
            .find(|(i, g)| g.group != *i as u32)
        {
            return Err(err(format!(
                "{label}: bind group {i} is declared as group {}",
                g.group
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
            let layouts: Vec<wgpu::BindGroupLayout> =
                groups.iter().map(|g| g.layout(ctx)).collect();
            let layout = ctx
                .device
                .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some(label),
                    bind_group_layouts: &layouts.iter().map(Some).collect::<Vec<_>>(),
                    immediate_size: 0,
                });
            let bound = groups
                .iter()
                .zip(&layouts)
                .map(|(g, l)| g.bind_group(ctx, l))
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
        if let Some(p) = ctx.cached(&key) {
            return Ok(p);
        }
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
        let p = Arc::new(ctx.scoped(entry, || {
            ctx.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: Some(layout),
                    module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
        })?);
        ctx.cache_insert(key, p.clone());
        Ok(p)
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
