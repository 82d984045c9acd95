//! One bind group declared once: the WGSL declarations and the wgpu layout
//! come from the same list, so a binding number cannot drift between them
//! (the rule of `subcone-wgpu`'s `compute::Bindings`, for textures).
//! Shared checks of the host's views, and what every pass records
//! through: its compiled pipeline, uniform buffers and bind groups
//! ([`PassPipeline`]).

use crate::PassError;

struct Decl {
    name: &'static str,
    wgsl: String,
    ty: wgpu::BindingType,
    /// The size of a uniform's value; `None` for a texture.
    uniform: Option<u64>,
}

/// The bindings of group 0 of one pass, in binding order: uniforms (each
/// a [`UniformRing`]) and textures (the host's views).
#[derive(Default)]
pub(crate) struct Group {
    list: Vec<Decl>,
}

impl Group {
    fn push(&mut self, name: &'static str, wgsl: String, ty: wgpu::BindingType) {
        let uniform = match ty {
            wgpu::BindingType::Buffer {
                min_binding_size, ..
            } => min_binding_size.map(u64::from),
            _ => None,
        };
        self.list.push(Decl {
            name,
            wgsl,
            ty,
            uniform,
        });
    }

    /// `var<uniform> name: ty`, of `T`'s size: one slot of the pass's
    /// uniform ring ([`UniformRing`]), bound at a dynamic offset.
    pub(crate) fn uniform<T: bytemuck::Pod>(&mut self, name: &'static str, ty: &str) {
        self.push(
            name,
            format!("var<uniform> {name}: {ty};"),
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(size_of::<T>() as u64),
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

/// Check the texture of view `v` against `e`: 2D, size, samples, layers,
/// usage (format is the caller's). wgpu 30 exposes a view's texture
/// (`TextureView::texture`) but not the view's own range or dimension, so
/// those are the host's contract: a view of the whole texture (mip level 0).
pub(crate) fn check(v: &wgpu::TextureView, e: &Expect) -> Result<(), PassError> {
    let t = v.texture();
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
    output: &wgpu::TextureView,
    format: wgpu::TextureFormat,
    expected: &'static str,
) -> Result<(u32, u32), PassError> {
    let size = (output.texture().width(), output.texture().height());
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
    if output.texture().format() != format {
        return Err(PassError::Format {
            what: "output",
            found: output.texture().format(),
            expected,
        });
    }
    Ok(size)
}

/// Refuse a texture `what` that `textureLoad` does not read as `f32`
/// ([`is_float_color`]).
pub(crate) fn check_float_color(
    what: &'static str,
    v: &wgpu::TextureView,
) -> Result<(), PassError> {
    let format = v.texture().format();
    if is_float_color(format) {
        Ok(())
    } else {
        Err(PassError::Format {
            what,
            found: format,
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

/// Pixels per side of every pass's workgroup: `@workgroup_size(8, 8)` in
/// each pass's WGSL.
const WORKGROUP: u32 = 8;

/// Uniform slots per uniform of a pass: how many distinct values of one
/// uniform (a frame's size, camera, projection…) a pass can hold at once.
///
/// `encode` writes a pass's uniforms with `Queue::write_buffer`, which takes
/// effect at the host's next `Queue::submit`, before the submitted commands
/// run. So every `encode` of one submission must bind its own copy of a
/// value that differs: a pass keeps `UNIFORM_SLOTS` slots per uniform,
/// reuses the slot that already holds an equal value (no write), and
/// otherwise overwrites the least recently used one. Hence the contract:
/// **between two submissions, a pass may be encoded any number of times
/// with at most `UNIFORM_SLOTS` distinct values of each uniform**; a
/// repeated value takes no new slot. Beyond that, an earlier encode of the
/// same submission would read a later encode's value.
pub const UNIFORM_SLOTS: usize = 16;

/// Bind groups a pass keeps, one per distinct set of input views (least
/// recently used first out).
///
/// A bind group is keyed by the views it binds (`wgpu::TextureView` is
/// `Eq + Hash` by identity in wgpu 30), and holds a clone of each view, so a
/// cached entry keeps the host's views (and their textures) alive until it
/// is evicted or the pass is dropped or its `release_views` is called. A
/// host that cycles through more than `BIND_GROUP_CACHE` sets of views
/// creates one bind group per encode.
pub const BIND_GROUP_CACHE: usize = 8;

/// One slot of a [`UniformRing`]: the bytes last written to it and when it
/// was last bound.
#[derive(Default)]
struct Slot {
    value: Option<Vec<u8>>,
    used: u64,
}

/// One uniform of a pass: a buffer of [`UNIFORM_SLOTS`] slots made in the
/// pass's `new`, each at a multiple of the device's
/// `min_uniform_buffer_offset_alignment`.
struct UniformRing {
    buffer: wgpu::Buffer,
    /// Bytes of one value.
    size: u64,
    /// Bytes between slots.
    stride: u64,
}

/// A cached bind group: the views it binds, in group order.
struct CachedGroup {
    views: Vec<wgpu::TextureView>,
    group: wgpu::BindGroup,
    used: u64,
}

/// What `encode` updates: the slots' contents and the bind groups.
#[derive(Default)]
struct State {
    /// A counter of encodes, for least-recently-used choices.
    clock: u64,
    /// `slots[u][s]`: slot `s` of uniform `u`.
    slots: Vec<Vec<Slot>>,
    groups: Vec<CachedGroup>,
}

/// The compiled side of one pass: its group 0, that group's layout, the
/// compute pipeline over it (and over the host's group 1, for a pass that
/// reads one), its uniform buffers and its cache of bind groups. Built once
/// by the pass's `new`; each frame's `encode` writes its uniforms into
/// slots, binds its views (a cached bind group after the first frame) and
/// dispatches one invocation per output pixel, creating no GPU object for
/// views it has seen ([`UNIFORM_SLOTS`], [`BIND_GROUP_CACHE`]).
pub(crate) struct PassPipeline {
    label: &'static str,
    group: Group,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// One ring per uniform of `group`, in binding order.
    uniforms: Vec<UniformRing>,
    state: std::sync::Mutex<State>,
}

impl PassPipeline {
    /// Compile `source`'s `entry` over `group` (group 0) and `host_layout`
    /// (group 1, when the host binds one), and make the uniform buffers.
    /// `source` is the whole shader, the group's declarations included.
    /// `label` names every object made.
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
        let align = u64::from(device.limits().min_uniform_buffer_offset_alignment).max(1);
        let uniforms: Vec<UniformRing> = group
            .list
            .iter()
            .filter_map(|d| d.uniform)
            .map(|size| {
                let stride = size.div_ceil(align) * align;
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: stride * UNIFORM_SLOTS as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                UniformRing {
                    buffer,
                    size,
                    stride,
                }
            })
            .collect();
        let state = State {
            slots: uniforms
                .iter()
                .map(|_| (0..UNIFORM_SLOTS).map(|_| Slot::default()).collect())
                .collect(),
            ..State::default()
        };
        PassPipeline {
            label,
            group,
            layout,
            pipeline,
            uniforms,
            state: std::sync::Mutex::new(state),
        }
    }

    /// Drop every cached bind group, and with them the pass's clones of the
    /// host's views.
    pub(crate) fn release_views(&self) {
        self.lock().groups.clear();
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        // A panic while the lock was held left the state consistent (each
        // field is replaced whole), so a poisoned lock is used as it is.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Record one compute pass over `size` pixels: the uniforms' values
    /// `uniforms` (in binding order), the views `views` (by name, every
    /// declared texture exactly once), `host_group` as group 1 and the
    /// host's `timestamps`. Checks the names and the timestamps first: on
    /// an error nothing is recorded or written.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn encode(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        (width, height): (u32, u32),
        uniforms: &[&[u8]],
        views: &[(&'static str, &wgpu::TextureView)],
        host_group: Option<&wgpu::BindGroup>,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        // The views in binding order.
        let mut ordered: Vec<&wgpu::TextureView> = Vec::with_capacity(views.len());
        for d in self.group.list.iter().filter(|d| d.uniform.is_none()) {
            let (_, v) = views
                .iter()
                .find(|(n, _)| *n == d.name)
                .ok_or(PassError::Missing(d.name))?;
            ordered.push(v);
        }
        if let Some((n, _)) = views.iter().find(|(n, _)| {
            !self
                .group
                .list
                .iter()
                .any(|d| d.uniform.is_none() && d.name == *n)
        }) {
            return Err(PassError::Unexpected(n));
        }
        if uniforms.len() != self.uniforms.len()
            || uniforms
                .iter()
                .zip(&self.uniforms)
                .any(|(u, r)| u.len() as u64 != r.size)
        {
            return Err(PassError::Config(format!(
                "{}: uniforms do not match the pass's layout",
                self.label
            )));
        }
        if let Some(t) = &timestamps {
            check_timestamps(device, t)?;
        }
        let mut state = self.lock();
        state.clock += 1;
        let now = state.clock;
        let mut offsets = Vec::with_capacity(uniforms.len());
        for (u, (value, ring)) in uniforms.iter().zip(&self.uniforms).enumerate() {
            let slots = &mut state.slots[u];
            let held = slots
                .iter()
                .position(|s| s.value.as_deref() == Some(*value));
            let s = match held {
                Some(s) => s,
                None => {
                    let lru = (0..slots.len()).min_by_key(|&s| slots[s].used).unwrap_or(0);
                    queue.write_buffer(&ring.buffer, lru as u64 * ring.stride, value);
                    slots[lru].value = Some(value.to_vec());
                    lru
                }
            };
            slots[s].used = now;
            offsets.push((s as u64 * ring.stride) as u32);
        }
        let cached = state
            .groups
            .iter()
            .position(|g| g.views.iter().eq(ordered.iter().copied()));
        let index = match cached {
            Some(i) => i,
            None => {
                let group = self.bind_group(device, &ordered);
                let entry = CachedGroup {
                    views: ordered.iter().map(|v| (*v).clone()).collect(),
                    group,
                    used: now,
                };
                if state.groups.len() < BIND_GROUP_CACHE {
                    state.groups.push(entry);
                    state.groups.len() - 1
                } else {
                    let lru = (0..state.groups.len())
                        .min_by_key(|&i| state.groups[i].used)
                        .unwrap_or(0);
                    state.groups[lru] = entry;
                    lru
                }
            }
        };
        state.groups[index].used = now;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.label),
            timestamp_writes: timestamps,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &state.groups[index].group, &offsets);
        if let Some(h) = host_group {
            pass.set_bind_group(1, h, &[]);
        }
        pass.dispatch_workgroups(width.div_ceil(WORKGROUP), height.div_ceil(WORKGROUP), 1);
        Ok(())
    }

    /// The bind group of the uniform rings (one slot each, at a dynamic
    /// offset) and `views`, in binding order.
    fn bind_group(&self, device: &wgpu::Device, views: &[&wgpu::TextureView]) -> wgpu::BindGroup {
        let mut rings = self.uniforms.iter();
        let mut views = views.iter();
        let entries: Vec<wgpu::BindGroupEntry<'_>> = self
            .group
            .list
            .iter()
            .enumerate()
            .filter_map(|(i, d)| {
                let resource = if d.uniform.is_some() {
                    let r = rings.next()?;
                    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &r.buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(r.size),
                    })
                } else {
                    wgpu::BindingResource::TextureView(views.next()?)
                };
                Some(wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource,
                })
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.label),
            layout: &self.layout,
            entries: &entries,
        })
    }
}

/// Refuse timestamp writes the device cannot take: without
/// `Features::TIMESTAMP_QUERY`, into a query set of another type, or at an
/// index past its end.
fn check_timestamps(
    device: &wgpu::Device,
    t: &wgpu::ComputePassTimestampWrites<'_>,
) -> Result<(), PassError> {
    if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        return Err(PassError::Config(
            "timestamps: the device was opened without Features::TIMESTAMP_QUERY".into(),
        ));
    }
    if !matches!(t.query_set.ty(), wgpu::QueryType::Timestamp) {
        return Err(PassError::Config(
            "timestamps: the query set is not of QueryType::Timestamp".into(),
        ));
    }
    let count = t.query_set.count();
    for i in [t.beginning_of_pass_write_index, t.end_of_pass_write_index]
        .into_iter()
        .flatten()
    {
        if i >= count {
            return Err(PassError::Config(format!(
                "timestamps: index {i} is past the query set's {count} queries"
            )));
        }
    }
    Ok(())
}
