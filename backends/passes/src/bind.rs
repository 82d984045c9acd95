//! One bind group declared once: the WGSL declarations and the wgpu layout
//! come from the same list, so a binding number cannot drift between them
//! (the rule of `subcone-wgpu`'s `compute::Bindings`, for textures).
//! Shared checks of the host's textures, and what every pass records
//! through: its compiled pipeline ([`PassPipeline`]) and uniform buffers.

use crate::PassError;

struct Decl {
    name: &'static str,
    wgsl: String,
    ty: wgpu::BindingType,
}

/// The bindings of group 0 of one pass, in binding order.
#[derive(Default)]
pub(crate) struct Group {
    list: Vec<Decl>,
}

impl Group {
    fn push(&mut self, name: &'static str, wgsl: String, ty: wgpu::BindingType) {
        self.list.push(Decl { name, wgsl, ty });
    }

    /// `var<uniform> name: ty`.
    pub(crate) fn uniform(&mut self, name: &'static str, ty: &str) {
        self.push(
            name,
            format!("var<uniform> {name}: {ty};"),
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
        );
    }

    /// A sampled texture `var name: ty`, read with `textureLoad`.
    pub(crate) fn texture(
        &mut self,
        name: &'static str,
        ty: &str,
        sample_type: wgpu::TextureSampleType,
        view_dimension: wgpu::TextureViewDimension,
        multisampled: bool,
    ) {
        self.push(
            name,
            format!("var {name}: {ty};"),
            wgpu::BindingType::Texture {
                sample_type,
                view_dimension,
                multisampled,
            },
        );
    }

    /// A write-only storage texture of `format`.
    pub(crate) fn storage_texture(&mut self, name: &'static str, format: wgpu::TextureFormat) {
        let f = storage_format_name(format).unwrap_or("rgba32float");
        self.push(
            name,
            format!("var {name}: texture_storage_2d<{f}, write>;"),
            wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
        );
    }

    /// The WGSL declarations, `@group(0) @binding(i)` in list order.
    pub(crate) fn declarations(&self) -> String {
        self.list
            .iter()
            .enumerate()
            .map(|(i, d)| format!("@group(0) @binding({i}) {}\n", d.wgsl))
            .collect()
    }

    /// The bind group layout, visible to compute shaders.
    pub(crate) fn layout(&self, device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
        let entries: Vec<_> = self
            .list
            .iter()
            .enumerate()
            .map(|(i, d)| wgpu::BindGroupLayoutEntry {
                binding: i as u32,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: d.ty,
                count: None,
            })
            .collect();
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &entries,
        })
    }

    /// The bind group of `resources`, by name; every declared binding must
    /// be given exactly once.
    pub(crate) fn bind_group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        label: &str,
        resources: &[(&'static str, wgpu::BindingResource<'_>)],
    ) -> Result<wgpu::BindGroup, PassError> {
        let mut entries = Vec::with_capacity(self.list.len());
        for (i, d) in self.list.iter().enumerate() {
            let r = resources
                .iter()
                .find(|(n, _)| *n == d.name)
                .ok_or(PassError::Missing(d.name))?;
            entries.push(wgpu::BindGroupEntry {
                binding: i as u32,
                resource: r.1.clone(),
            });
        }
        if let Some((n, _)) = resources
            .iter()
            .find(|(n, _)| !self.list.iter().any(|d| d.name == *n))
        {
            return Err(PassError::Unexpected(n));
        }
        Ok(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &entries,
        }))
    }
}

/// The WGSL name of a storage texture format the passes write, or `None`
/// for a format they cannot write.
pub(crate) fn storage_format_name(format: wgpu::TextureFormat) -> Option<&'static str> {
    match format {
        wgpu::TextureFormat::Rgba8Unorm => Some("rgba8unorm"),
        wgpu::TextureFormat::Rgba16Float => Some("rgba16float"),
        wgpu::TextureFormat::Rgba32Float => Some("rgba32float"),
        _ => None,
    }
}

/// The output formats the passes write: `Rgba8Unorm`, `Rgba16Float`,
/// `Rgba32Float` (storage textures of core WebGPU).
pub(crate) const OUTPUT_FORMATS: &str = "Rgba8Unorm, Rgba16Float or Rgba32Float";

/// Refuse an output format the passes cannot write.
pub(crate) fn check_output_format(format: wgpu::TextureFormat) -> Result<(), PassError> {
    match storage_format_name(format) {
        Some(_) => Ok(()),
        None => Err(PassError::Format {
            what: "output",
            found: format,
            expected: OUTPUT_FORMATS,
        }),
    }
}

/// What a host texture must be for one role.
pub(crate) struct Expect {
    pub(crate) what: &'static str,
    pub(crate) size: (u32, u32),
    pub(crate) samples: u32,
    /// Exact array layer count.
    pub(crate) layers: u32,
    pub(crate) usage: wgpu::TextureUsages,
}

/// Check `t` against `e`: 2D, size, samples, layers, usage (format is the
/// caller's).
pub(crate) fn check(t: &wgpu::Texture, e: &Expect) -> Result<(), PassError> {
    let found = (t.width(), t.height());
    if t.dimension() != wgpu::TextureDimension::D2 {
        return Err(PassError::Dimension {
            what: e.what,
            found: t.dimension(),
        });
    }
    if found != e.size {
        return Err(PassError::Size {
            what: e.what,
            expected: e.size,
            found,
        });
    }
    if t.sample_count() != e.samples {
        return Err(PassError::SampleCount {
            what: e.what,
            expected: e.samples,
            found: t.sample_count(),
        });
    }
    if t.depth_or_array_layers() != e.layers {
        return Err(PassError::Layers {
            what: e.what,
            expected: e.layers,
            found: t.depth_or_array_layers(),
        });
    }
    if !t.usage().contains(e.usage) {
        return Err(PassError::Usage {
            what: e.what,
            missing: e.usage - t.usage(),
        });
    }
    Ok(())
}

/// Check a pass's output texture: one-sample 2D, one layer, writable as a
/// storage texture, of the `format` the pass was built for (`expected` says
/// where that format was given). Its size is the frame's, returned.
pub(crate) fn check_output(
    output: &wgpu::Texture,
    format: wgpu::TextureFormat,
    expected: &'static str,
) -> Result<(u32, u32), PassError> {
    let size = (output.width(), output.height());
    check(
        output,
        &Expect {
            what: "output",
            size,
            samples: 1,
            layers: 1,
            usage: wgpu::TextureUsages::STORAGE_BINDING,
        },
    )?;
    if output.format() != format {
        return Err(PassError::Format {
            what: "output",
            found: output.format(),
            expected,
        });
    }
    Ok(size)
}

/// Refuse a texture `what` that `textureLoad` does not read as `f32`
/// ([`is_float_color`]).
pub(crate) fn check_float_color(what: &'static str, t: &wgpu::Texture) -> Result<(), PassError> {
    if is_float_color(t.format()) {
        Ok(())
    } else {
        Err(PassError::Format {
            what,
            found: t.format(),
            expected: "a float, unorm or snorm colour format",
        })
    }
}

/// Whether `format` is read as `f32` by `textureLoad` (a colour format with
/// a float, unorm or snorm sample type).
pub(crate) fn is_float_color(format: wgpu::TextureFormat) -> bool {
    !format.is_depth_stencil_format()
        && matches!(
            format.sample_type(None, None),
            Some(wgpu::TextureSampleType::Float { .. })
        )
}

/// A view of `t`: the whole texture as `dimension`, the depth aspect of a
/// depth format.
pub(crate) fn view(t: &wgpu::Texture, dimension: wgpu::TextureViewDimension) -> wgpu::TextureView {
    let aspect = if t.format().is_depth_stencil_format() {
        wgpu::TextureAspect::DepthOnly
    } else {
        wgpu::TextureAspect::All
    };
    t.create_view(&wgpu::TextureViewDescriptor {
        label: Some("subcone pass input"),
        dimension: Some(dimension),
        aspect,
        mip_level_count: Some(1),
        ..Default::default()
    })
}

/// Pixels per side of every pass's workgroup: `@workgroup_size(8, 8)` in
/// each pass's WGSL.
const WORKGROUP: u32 = 8;

/// The compiled side of one pass: its group 0, that group's layout and the
/// compute pipeline over it (and over the host's group 1, for a pass that
/// reads one). Built once by the pass's `new`; each frame's `encode` binds
/// its resources and dispatches one invocation per output pixel.
pub(crate) struct PassPipeline {
    label: &'static str,
    group: Group,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl PassPipeline {
    /// Compile `source`'s `entry` over `group` (group 0) and `host_layout`
    /// (group 1, when the host binds one). `source` is the whole shader,
    /// the group's declarations included. `label` names every object made.
    pub(crate) fn new(
        device: &wgpu::Device,
        label: &'static str,
        group: Group,
        source: String,
        host_layout: Option<&wgpu::BindGroupLayout>,
        entry: &str,
    ) -> Self {
        let layout = group.layout(device, label);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layouts = [Some(&layout), host_layout];
        let count = if host_layout.is_some() { 2 } else { 1 };
        let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &layouts[..count],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(&pl),
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        });
        PassPipeline {
            label,
            group,
            layout,
            pipeline,
        }
    }

    /// Record one compute pass over `size` pixels: group 0 of `resources`
    /// (by name, [`Group::bind_group`]), `host_group` as group 1. On an
    /// error nothing is recorded.
    pub(crate) fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        (width, height): (u32, u32),
        resources: &[(&'static str, wgpu::BindingResource<'_>)],
        host_group: Option<&wgpu::BindGroup>,
    ) -> Result<(), PassError> {
        let group = self
            .group
            .bind_group(device, &self.layout, self.label, resources)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.label),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        if let Some(h) = host_group {
            pass.set_bind_group(1, h, &[]);
        }
        pass.dispatch_workgroups(width.div_ceil(WORKGROUP), height.div_ceil(WORKGROUP), 1);
        Ok(())
    }
}

/// A uniform buffer holding `value`, made for one frame's bind group.
pub(crate) fn uniform_buffer<T: bytemuck::Pod>(
    device: &wgpu::Device,
    label: &str,
    value: &T,
) -> wgpu::Buffer {
    use wgpu::util::DeviceExt;
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::bytes_of(value),
        usage: wgpu::BufferUsages::UNIFORM,
    })
}
