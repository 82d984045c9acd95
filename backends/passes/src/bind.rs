//! Bindings declared once, for the passes and for any wgpu program.
//!
//! A [`Group`] lists the bindings of one bind group in binding order
//! (buffers: uniform, read-only or read-write storage; sampled textures;
//! write-only storage textures), and from that one list come both the WGSL
//! declarations ([`Group::declarations`], `@group(g) @binding(i) var…`) and
//! the wgpu layout ([`Group::layout`]), so a binding number, a type or an
//! access mode cannot drift between the shader and the pipeline. A shader
//! written against a `Group` holds no `@binding` line of its own.
//! [`Bindings`] is a `Group` together with the resources it binds (a
//! program that owns its buffers, such as a renderer's frame); it also
//! makes the bind group ([`Bindings::bind_group`]). [`pipeline_layout`]
//! and [`compute_pipeline`] compile a compute pipeline over groups.
//!
//! Every pass of this crate declares its group 0 here; `subcone-wgpu`
//! declares every group of its compute and raster programs here too, so
//! there is one binding layer between the two. The module is public so
//! that a host can declare its own group (e.g. the `@group(1)` a
//! [`crate::CtssPass`] host binds) the same way.
//!
//! Besides, the crate-private checks of the host's views and
//! `PassPipeline`, what every pass records through: its compiled
//! pipeline, uniform slots and cached bind groups.

use std::borrow::Cow;

/// The host's wgpu types, named once. The passes take these from the host
/// and no other module of the crate names an item of wgpu (the test
/// `tests/wgpu_in_one_module.rs` fails when one does), and every wgpu call
/// is made here, so a wgpu upgrade touches this module (and `Cargo.toml`).
pub(crate) use wgpu::{
    BindGroup, BindGroupLayout, Buffer, BufferUsages, CommandEncoder, ComputePassTimestampWrites,
    Device, Queue, TextureDimension, TextureFormat, TextureSampleType, TextureUsages, TextureView,
    TextureViewDimension,
};

use crate::PassError;

/// How a shader accesses a buffer binding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BufferAccess {
    /// `var<uniform>`.
    Uniform,
    /// `var<storage, read>`.
    Read,
    /// `var<storage, read_write>`.
    ReadWrite,
}

#[derive(Clone, Debug)]
struct Decl {
    name: Cow<'static, str>,
    /// The address space after `var` (`<uniform>`, `<storage, read>`…),
    /// empty for a texture.
    space: &'static str,
    /// The WGSL type.
    wgsl_type: String,
    ty: wgpu::BindingType,
    /// The size of a uniform bound at a dynamic offset (a pass's
    /// [`UniformRing`]); `None` for every other binding.
    ring: Option<u64>,
}

/// One binding of a [`Group`], described without wgpu types
/// ([`Group::entries`]): the row of a pass's resource table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BindingEntry {
    /// `@group`: the descriptor set (Vulkan) or register space (D3D12).
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// The variable's name in the shader.
    pub name: String,
    /// Its WGSL type (`array<vec4<f32>>`, `texture_2d<f32>`…).
    pub wgsl_type: String,
    /// What the host binds there.
    pub kind: BindingKind,
}

/// What a host binds at a [`BindingEntry`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BindingKind {
    /// A uniform buffer of at least `size` bytes (`None`: the shader's
    /// struct says). wgpu binds a pass's uniforms at a dynamic offset into
    /// a ring of slots; a host may bind each frame's buffer whole.
    Uniform {
        /// Bytes the shader reads.
        size: Option<u64>,
    },
    /// A storage buffer.
    Storage {
        /// Whether the shader only reads it.
        read_only: bool,
    },
    /// A sampled texture read with `textureLoad` (texel fetch, no sampler).
    Texture {
        /// `"float"`, `"depth"`, `"uint"` or `"sint"`.
        sample: &'static str,
        /// An array of 2D layers rather than one 2D image.
        array: bool,
        /// Multisampled (read by sample index).
        multisampled: bool,
    },
    /// A write-only 2D storage image.
    StorageTexture {
        /// The texel format, as WGSL spells it (`rgba16float`…).
        format: &'static str,
    },
}

impl BindingKind {
    fn of(ty: &wgpu::BindingType) -> Self {
        match *ty {
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                min_binding_size,
                ..
            } => BindingKind::Uniform {
                size: min_binding_size.map(|s| s.get()),
            },
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                ..
            } => BindingKind::Storage { read_only },
            wgpu::BindingType::Texture {
                sample_type,
                view_dimension,
                multisampled,
            } => BindingKind::Texture {
                sample: match sample_type {
                    wgpu::TextureSampleType::Float { .. } => "float",
                    wgpu::TextureSampleType::Depth => "depth",
                    wgpu::TextureSampleType::Uint => "uint",
                    wgpu::TextureSampleType::Sint => "sint",
                },
                array: view_dimension == wgpu::TextureViewDimension::D2Array,
                multisampled,
            },
            wgpu::BindingType::StorageTexture { format, .. } => BindingKind::StorageTexture {
                // A group only holds storage textures of a named format
                // (`Group::storage_texture` refuses the others).
                format: storage_format_name(format).unwrap_or("unknown"),
            },
            // Groups declare none of these (no `Group` method adds them).
            _ => BindingKind::Uniform { size: None },
        }
    }
}

/// The bindings of one bind group, in binding order: binding `i` is the
/// `i`-th added. Declarations only; [`Bindings`] adds the resources.
#[derive(Clone, Debug)]
pub struct Group {
    index: u32,
    visibility: wgpu::ShaderStages,
    list: Vec<Decl>,
}

impl Default for Group {
    /// An empty group 0 of a compute shader.
    fn default() -> Self {
        Group::new(0)
    }
}

/// WGSL's spelling of the texture type of `sample_type`, `view_dimension`
/// and `multisampled`: `texture_2d<f32>`, `texture_depth_2d_array`,
/// `texture_multisampled_2d<u32>`… (2D and 2D-array views; other
/// dimensions are not bound by subcone's programs).
fn texture_type(
    sample_type: wgpu::TextureSampleType,
    view_dimension: wgpu::TextureViewDimension,
    multisampled: bool,
) -> String {
    let array = view_dimension == wgpu::TextureViewDimension::D2Array;
    let scalar = match sample_type {
        wgpu::TextureSampleType::Depth => {
            return match (multisampled, array) {
                (true, _) => "texture_depth_multisampled_2d".into(),
                (false, true) => "texture_depth_2d_array".into(),
                (false, false) => "texture_depth_2d".into(),
            }
        }
        wgpu::TextureSampleType::Float { .. } => "f32",
        wgpu::TextureSampleType::Uint => "u32",
        wgpu::TextureSampleType::Sint => "i32",
    };
    match (multisampled, array) {
        (true, _) => format!("texture_multisampled_2d<{scalar}>"),
        (false, true) => format!("texture_2d_array<{scalar}>"),
        (false, false) => format!("texture_2d<{scalar}>"),
    }
}

impl Group {
    /// An empty group `index` (the `@group` of its declarations) of a
    /// compute shader.
    pub fn new(index: u32) -> Self {
        Self::visible_in(index, wgpu::ShaderStages::COMPUTE)
    }

    /// An empty group `index` visible to `stages` (a raster program's
    /// group is read by its vertex and fragment stages).
    pub fn visible_in(index: u32, stages: wgpu::ShaderStages) -> Self {
        Group {
            index,
            visibility: stages,
            list: Vec::new(),
        }
    }

    /// The group's index, `@group(index)`.
    pub fn index(&self) -> u32 {
        self.index
    }

    /// Bindings declared so far.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether nothing is declared.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Whether a binding named `name` is declared.
    pub fn contains(&self, name: &str) -> bool {
        self.list.iter().any(|d| d.name == name)
    }

    /// Declare `var<space> name: wgsl_type`, bound as `ty`.
    fn push(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        (space, wgsl_type): (&'static str, String),
        ty: wgpu::BindingType,
        ring: Option<u64>,
    ) {
        self.list.push(Decl {
            name: name.into(),
            space,
            wgsl_type,
            ty,
            ring,
        });
    }

    /// A whole buffer `var<…> name: ty` with `access`, of any size (no
    /// dynamic offset).
    pub fn buffer(&mut self, name: impl Into<Cow<'static, str>>, ty: &str, access: BufferAccess) {
        let (space, ty_) = match access {
            BufferAccess::Uniform => ("<uniform>", wgpu::BufferBindingType::Uniform),
            BufferAccess::Read => (
                "<storage, read>",
                wgpu::BufferBindingType::Storage { read_only: true },
            ),
            BufferAccess::ReadWrite => (
                "<storage, read_write>",
                wgpu::BufferBindingType::Storage { read_only: false },
            ),
        };
        self.push(
            name,
            (space, ty.to_owned()),
            wgpu::BindingType::Buffer {
                ty: ty_,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            None,
        );
    }

    /// `var<uniform> name: ty`, of `T`'s size: one slot of a pass's
    /// uniform ring ([`UniformRing`]), bound at a dynamic offset.
    pub(crate) fn ring_uniform<T: bytemuck::Pod>(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        ty: &str,
    ) {
        let size = size_of::<T>() as u64;
        self.push(
            name,
            ("<uniform>", ty.to_owned()),
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(size),
            },
            Some(size),
        );
    }

    /// A sampled texture `name`, read with `textureLoad`; its WGSL type
    /// follows from the arguments (`texture_2d_array<f32>` for a 2D array
    /// of floats, `texture_depth_multisampled_2d` for a multisampled depth
    /// texture…).
    pub fn texture(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        sample_type: wgpu::TextureSampleType,
        view_dimension: wgpu::TextureViewDimension,
        multisampled: bool,
    ) {
        let ty = texture_type(sample_type, view_dimension, multisampled);
        self.push(
            name,
            ("", ty),
            wgpu::BindingType::Texture {
                sample_type,
                view_dimension,
                multisampled,
            },
            None,
        );
    }

    /// A write-only 2D storage texture `name` of `format`; a
    /// [`PassError::Format`] for a format without a WGSL storage name here
    /// (`Rgba8Unorm`, `Rgba16Float`, `Rgba32Float`, `R32Float`, `R32Uint`).
    pub fn storage_texture(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        format: wgpu::TextureFormat,
    ) -> Result<(), PassError> {
        let f = storage_format_name(format).ok_or(PassError::Format {
            what: "storage texture",
            found: format,
            expected: STORAGE_FORMATS,
        })?;
        self.push(
            name,
            ("", format!("texture_storage_2d<{f}, write>")),
            wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
            None,
        );
        Ok(())
    }

    /// Refuse a group the device cannot bind: more storage buffers, sampled
    /// textures or storage textures than its limits per shader stage
    /// (`wgpu::Limits::max_storage_buffers_per_shader_stage` and its
    /// neighbours; WebGPU's defaults are 8, 16 and 4).
    pub fn check_limits(&self, device: &wgpu::Device) -> Result<(), PassError> {
        let limits = device.limits();
        let count = |f: fn(&wgpu::BindingType) -> bool| {
            self.list.iter().filter(|d| f(&d.ty)).count() as u32
        };
        let kinds = [
            (
                "storage buffers",
                count(|t| {
                    matches!(
                        t,
                        wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Storage { .. },
                            ..
                        }
                    )
                }),
                limits.max_storage_buffers_per_shader_stage,
            ),
            (
                "sampled textures",
                count(|t| matches!(t, wgpu::BindingType::Texture { .. })),
                limits.max_sampled_textures_per_shader_stage,
            ),
            (
                "storage textures",
                count(|t| matches!(t, wgpu::BindingType::StorageTexture { .. })),
                limits.max_storage_textures_per_shader_stage,
            ),
        ];
        match kinds.iter().find(|(_, n, max)| n > max) {
            Some((what, n, max)) => Err(PassError::Config(format!(
                "the configuration binds {n} {what}; the device allows {max} per shader stage \
                 (open it with the adapter's limits)"
            ))),
            None => Ok(()),
        }
    }

    /// The bindings as an engine without wgpu declares them, in binding
    /// order: what [`crate::standalone`]'s resource tables list.
    pub fn entries(&self) -> Vec<BindingEntry> {
        self.list
            .iter()
            .enumerate()
            .map(|(i, d)| BindingEntry {
                group: self.index,
                binding: i as u32,
                name: d.name.to_string(),
                wgsl_type: d.wgsl_type.clone(),
                kind: BindingKind::of(&d.ty),
            })
            .collect()
    }

    /// The WGSL declarations, `@group(index) @binding(i) var…;` in list
    /// order, one line each.
    pub fn declarations(&self) -> String {
        self.list
            .iter()
            .enumerate()
            .map(|(i, d)| {
                format!(
                    "@group({}) @binding({i}) var{} {}: {};\n",
                    self.index, d.space, d.name, d.wgsl_type
                )
            })
            .collect()
    }

    /// The bind group layout.
    pub fn layout(&self, device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
        let entries: Vec<_> = self
            .list
            .iter()
            .enumerate()
            .map(|(i, d)| wgpu::BindGroupLayoutEntry {
                binding: i as u32,
                visibility: self.visibility,
                ty: d.ty,
                count: None,
            })
            .collect();
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &entries,
        })
    }

    /// The bind group of `resources` (one per binding, in binding order)
    /// for `layout` (from [`Group::layout`]).
    pub fn bind_group<'r>(
        &self,
        device: &wgpu::Device,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        resources: impl IntoIterator<Item = wgpu::BindingResource<'r>>,
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
            .into_iter()
            .enumerate()
            .map(|(i, resource)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource,
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &entries,
        })
    }
}

/// A resource bound by [`Bindings`] or cached by a pass (wgpu's handles
/// are reference counted: a clone is the same object).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum Resource {
    Buffer(wgpu::Buffer),
    Texture(wgpu::TextureView),
}

impl Resource {
    fn binding(&self) -> wgpu::BindingResource<'_> {
        match self {
            Resource::Buffer(b) => b.as_entire_binding(),
            Resource::Texture(v) => wgpu::BindingResource::TextureView(v),
        }
    }
}

/// A [`Group`] with the resources it binds, one per binding: what a
/// program that owns its buffers and textures (a renderer's frame) builds
/// once and binds as it is. It also keeps an account of the memory its
/// owner allocated for it ([`Bindings::account`]), by name, for a frame's
/// statistics.
#[derive(Clone, Debug)]
pub struct Bindings {
    group: Group,
    resources: Vec<Resource>,
    accounts: Vec<(&'static str, usize)>,
}

impl Bindings {
    /// Empty bindings of group `index` of a compute shader.
    pub fn new(index: u32) -> Self {
        Self::visible_in(index, wgpu::ShaderStages::COMPUTE)
    }

    /// Empty bindings of group `index` visible to `stages`.
    pub fn visible_in(index: u32, stages: wgpu::ShaderStages) -> Self {
        Bindings {
            group: Group::visible_in(index, stages),
            resources: Vec::new(),
            accounts: Vec::new(),
        }
    }

    /// The declarations.
    pub fn group(&self) -> &Group {
        &self.group
    }

    /// Bind `buffer` whole as `var<…> name: ty` ([`Group::buffer`]).
    pub fn buffer(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        ty: &str,
        access: BufferAccess,
        buffer: &wgpu::Buffer,
    ) {
        self.group.buffer(name, ty, access);
        self.resources.push(Resource::Buffer(buffer.clone()));
    }

    /// Bind `view` as the sampled texture `name` ([`Group::texture`]).
    pub fn texture(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        sample_type: wgpu::TextureSampleType,
        view_dimension: wgpu::TextureViewDimension,
        multisampled: bool,
        view: &wgpu::TextureView,
    ) {
        self.group
            .texture(name, sample_type, view_dimension, multisampled);
        self.resources.push(Resource::Texture(view.clone()));
    }

    /// Bind `view` as the write-only storage texture `name` of `format`
    /// ([`Group::storage_texture`]).
    pub fn storage_texture(
        &mut self,
        name: impl Into<Cow<'static, str>>,
        format: wgpu::TextureFormat,
        view: &wgpu::TextureView,
    ) -> Result<(), PassError> {
        self.group.storage_texture(name, format)?;
        self.resources.push(Resource::Texture(view.clone()));
        Ok(())
    }

    /// Record that `bytes` were allocated for `what`.
    pub fn account(&mut self, what: &'static str, bytes: usize) {
        self.accounts.push((what, bytes));
    }

    /// What was recorded with [`Bindings::account`], in order.
    pub fn accounts(&self) -> &[(&'static str, usize)] {
        &self.accounts
    }

    /// Whether a binding named `name` is declared.
    pub fn contains(&self, name: &str) -> bool {
        self.group.contains(name)
    }

    /// The buffer bound as `name`, if one is.
    pub fn buffer_named(&self, name: &str) -> Option<&wgpu::Buffer> {
        self.group
            .list
            .iter()
            .zip(&self.resources)
            .find_map(|(d, r)| match r {
                Resource::Buffer(b) if d.name == name => Some(b),
                _ => None,
            })
    }

    /// The WGSL declarations ([`Group::declarations`]).
    pub fn declarations(&self) -> String {
        self.group.declarations()
    }

    /// The bind group layout ([`Group::layout`]).
    pub fn layout(&self, device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
        self.group.layout(device, label)
    }

    /// The bind group of these resources for `layout` (from
    /// [`Bindings::layout`]).
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        label: &str,
        layout: &wgpu::BindGroupLayout,
    ) -> wgpu::BindGroup {
        self.group.bind_group(
            device,
            label,
            layout,
            self.resources.iter().map(Resource::binding),
        )
    }
}

/// The layout of a pipeline over `groups`, group `i` the `i`-th.
pub fn pipeline_layout(
    device: &wgpu::Device,
    label: &str,
    groups: &[&wgpu::BindGroupLayout],
) -> wgpu::PipelineLayout {
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().copied().map(Some).collect();
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    })
}

/// The compute pipeline of `module`'s entry point `entry` over `layout`.
pub fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    entry: &str,
) -> wgpu::ComputePipeline {
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// The formats [`Group::storage_texture`] declares.
const STORAGE_FORMATS: &str = "Rgba8Unorm, Rgba16Float, Rgba32Float, R32Float or R32Uint";

/// The WGSL name of a storage texture format [`Group::storage_texture`]
/// declares, or `None`.
fn storage_format_name(format: wgpu::TextureFormat) -> Option<&'static str> {
    match format {
        wgpu::TextureFormat::Rgba8Unorm => Some("rgba8unorm"),
        wgpu::TextureFormat::Rgba16Float => Some("rgba16float"),
        wgpu::TextureFormat::Rgba32Float => Some("rgba32float"),
        wgpu::TextureFormat::R32Float => Some("r32float"),
        wgpu::TextureFormat::R32Uint => Some("r32uint"),
        _ => None,
    }
}

/// Whether a pass's output may be of `format`: the formats a host's
/// output is written in ([`OUTPUT_FORMATS`]).
fn is_output_format(format: wgpu::TextureFormat) -> bool {
    matches!(
        format,
        wgpu::TextureFormat::Rgba8Unorm
            | wgpu::TextureFormat::Rgba16Float
            | wgpu::TextureFormat::Rgba32Float
    )
}

/// The output formats the passes write: `Rgba8Unorm`, `Rgba16Float`,
/// `Rgba32Float` (storage textures of core WebGPU).
pub(crate) const OUTPUT_FORMATS: &str = "Rgba8Unorm, Rgba16Float or Rgba32Float";

/// Refuse an output format the passes cannot write.
pub(crate) fn check_output_format(format: wgpu::TextureFormat) -> Result<(), PassError> {
    match is_output_format(format) {
        true => Ok(()),
        false => Err(PassError::Format {
            what: "output",
            found: format,
            expected: OUTPUT_FORMATS,
        }),
    }
}

/// A rectangle of pixels of a pass's textures: its top-left pixel
/// `(x, y)` (x right, y down, from the texture's top-left texel) and its
/// size, in pixels. A pass given a rect reads and writes its textures
/// there, at the same pixels of every texture (a viewport: dynamic
/// resolution, split screen), and leaves the output's other pixels as
/// they were.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rect {
    /// Column of the rect's top-left pixel.
    pub x: u32,
    /// Row of the rect's top-left pixel.
    pub y: u32,
    /// Width in pixels, `> 0`.
    pub width: u32,
    /// Height in pixels, `> 0`.
    pub height: u32,
}

impl Rect {
    /// The rect of `width × height` pixels whose top-left pixel is `(x, y)`.
    pub const fn new(x: u32, y: u32, width: u32, height: u32) -> Self {
        Rect {
            x,
            y,
            width,
            height,
        }
    }

    /// The whole of a texture of `(width, height)`: origin `(0, 0)`.
    pub const fn whole((width, height): (u32, u32)) -> Self {
        Rect::new(0, 0, width, height)
    }

    /// `(width, height)`.
    pub const fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Whether the rect is not empty and lies inside a texture of
    /// `(width, height)` (its far edges included, without overflow).
    pub fn lies_inside(&self, (width, height): (u32, u32)) -> bool {
        let inside = |origin: u32, extent: u32, limit: u32| {
            extent > 0 && origin.checked_add(extent).is_some_and(|end| end <= limit)
        };
        inside(self.x, self.width, width) && inside(self.y, self.height, height)
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
    check_region(v, e, None)
}

/// [`check`], but with a `rect` the texture's size is not compared with
/// `e.size`: the rect must lie inside it ([`Rect::lies_inside`]), a
/// [`PassError::Rect`] otherwise.
pub(crate) fn check_region(
    v: &wgpu::TextureView,
    e: &Expect,
    rect: Option<&Rect>,
) -> Result<(), PassError> {
    let t = v.texture();
    let found = (t.width(), t.height());
    if t.dimension() != wgpu::TextureDimension::D2 {
        return Err(PassError::Dimension {
            what: e.what,
            found: t.dimension(),
        });
    }
    match rect {
        Some(r) if !r.lies_inside(found) => {
            return Err(PassError::Rect {
                what: e.what,
                rect: *r,
                size: found,
            })
        }
        Some(_) => {}
        None if found != e.size => {
            return Err(PassError::Size {
                what: e.what,
                expected: e.size,
                found,
            })
        }
        None => {}
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
    check_output_region(output, format, expected, None).map(|r| r.size())
}

/// [`check_output`] for a pass that writes `rect` of its output (the whole
/// texture for `None`): the rect must lie inside the output texture. The
/// rect of pixels to write, returned.
pub(crate) fn check_output_region(
    output: &wgpu::TextureView,
    format: wgpu::TextureFormat,
    expected: &'static str,
    rect: Option<&Rect>,
) -> Result<Rect, PassError> {
    let size = (output.texture().width(), output.texture().height());
    check_region(
        output,
        &Expect {
            what: "output",
            size,
            samples: 1,
            layers: 1,
            usage: wgpu::TextureUsages::STORAGE_BINDING,
        },
        rect,
    )?;
    if output.texture().format() != format {
        return Err(PassError::Format {
            what: "output",
            found: output.texture().format(),
            expected,
        });
    }
    Ok(rect.copied().unwrap_or(Rect::whole(size)))
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
pub(crate) const WORKGROUP: u32 = 8;

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

/// A cached bind group: the resources it binds besides the uniform rings,
/// in group order.
struct CachedGroup {
    resources: Vec<Resource>,
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

impl std::fmt::Debug for PassPipeline {
    /// The label: the GPU objects behind it print nothing useful.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PassPipeline")
            .field("label", &self.label)
            .finish_non_exhaustive()
    }
}

impl PassPipeline {
    /// Compile `source`'s `entry` over `group` (group 0) and `host_layout`
    /// (group 1, when the host binds one), and make the uniform buffers.
    /// `source` is the whole shader, the group's declarations included.
    /// `label` names every object made. Refuses a group beyond the
    /// device's limits ([`Group::check_limits`]) before creating anything.
    pub(crate) fn new(
        device: &wgpu::Device,
        label: &'static str,
        group: Group,
        source: String,
        host_layout: Option<&wgpu::BindGroupLayout>,
        entry: &str,
    ) -> Result<Self, PassError> {
        group.check_limits(device)?;
        let layout = group.layout(device, label);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pl = match host_layout {
            Some(host) => pipeline_layout(device, label, &[&layout, host]),
            None => pipeline_layout(device, label, &[&layout]),
        };
        let pipeline = compute_pipeline(device, label, &pl, &module, entry);
        let align = u64::from(device.limits().min_uniform_buffer_offset_alignment).max(1);
        let uniforms: Vec<UniformRing> = group
            .list
            .iter()
            .filter_map(|d| d.ring)
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
        Ok(PassPipeline {
            label,
            group,
            layout,
            pipeline,
            uniforms,
            state: std::sync::Mutex::new(state),
        })
    }

    /// Drop every cached bind group, and with them the pass's clones of the
    /// host's views and buffers.
    pub(crate) fn release_views(&self) {
        self.lock().groups.clear();
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        // A panic while the lock was held left the state consistent (each
        // field is replaced whole), so a poisoned lock is used as it is.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Record one compute pass over `size` pixels: the uniforms' values
    /// `uniforms` (in binding order), the host's `resources` (views and
    /// buffers by name, every declared binding but the uniforms exactly
    /// once), `host_group` as group 1 and the host's `timestamps`. Checks
    /// the names and the timestamps first: on an error nothing is recorded
    /// or written.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn encode(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        (width, height): (u32, u32),
        uniforms: &[&[u8]],
        resources: &[(&'static str, Bound<'_>)],
        host_group: Option<&wgpu::BindGroup>,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), PassError> {
        // The resources in binding order.
        let mut ordered: Vec<Bound<'_>> = Vec::with_capacity(resources.len());
        for d in self.group.list.iter().filter(|d| d.ring.is_none()) {
            let (_, r) = resources
                .iter()
                .find(|(n, _)| *n == d.name)
                .ok_or(match &d.name {
                    Cow::Borrowed(n) => PassError::Missing(n),
                    Cow::Owned(_) => PassError::Missing("an input"),
                })?;
            ordered.push(*r);
        }
        if let Some((n, _)) = resources.iter().find(|(n, _)| {
            !self
                .group
                .list
                .iter()
                .any(|d| d.ring.is_none() && d.name == *n)
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
        let cached = state.groups.iter().position(|g| {
            g.resources.len() == ordered.len()
                && g.resources.iter().zip(&ordered).all(|(a, b)| b.is(a))
        });
        let index = match cached {
            Some(i) => i,
            None => {
                let group = self.bind_group(device, &ordered);
                let entry = CachedGroup {
                    resources: ordered.iter().map(|b| b.to_resource()).collect(),
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
    /// offset) and `resources`, in binding order.
    fn bind_group(&self, device: &wgpu::Device, resources: &[Bound<'_>]) -> wgpu::BindGroup {
        let mut rings = self.uniforms.iter();
        let mut resources = resources.iter();
        let bound = self.group.list.iter().filter_map(|d| {
            if d.ring.is_some() {
                let r = rings.next()?;
                Some(wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &r.buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(r.size),
                }))
            } else {
                Some(match resources.next()? {
                    Bound::Texture(v) => wgpu::BindingResource::TextureView(v),
                    Bound::Buffer(b) => b.as_entire_binding(),
                })
            }
        });
        self.group
            .bind_group(device, self.label, &self.layout, bound)
    }
}

/// A host's resource for [`PassPipeline::encode`], borrowed.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Bound<'a> {
    Texture(&'a wgpu::TextureView),
    Buffer(&'a wgpu::Buffer),
}

impl<'a> From<&'a wgpu::TextureView> for Bound<'a> {
    fn from(view: &'a wgpu::TextureView) -> Self {
        Bound::Texture(view)
    }
}

impl<'a> From<&'a wgpu::Buffer> for Bound<'a> {
    fn from(buffer: &'a wgpu::Buffer) -> Self {
        Bound::Buffer(buffer)
    }
}

impl Bound<'_> {
    /// Whether this is the resource `r` (wgpu's handles compare by identity).
    fn is(&self, r: &Resource) -> bool {
        match (self, r) {
            (Bound::Texture(a), Resource::Texture(b)) => *a == b,
            (Bound::Buffer(a), Resource::Buffer(b)) => *a == b,
            _ => false,
        }
    }

    fn to_resource(self) -> Resource {
        match self {
            Bound::Texture(v) => Resource::Texture((*v).clone()),
            Bound::Buffer(b) => Resource::Buffer((*b).clone()),
        }
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

/// Check buffer `b` (`what`) holds `count` elements of `element` bytes and
/// can be bound as storage.
pub(crate) fn check_buffer(
    what: &'static str,
    b: &wgpu::Buffer,
    count: u64,
    element: u64,
) -> Result<(), PassError> {
    if !b.usage().contains(wgpu::BufferUsages::STORAGE) {
        return Err(PassError::BufferUsage {
            what,
            missing: wgpu::BufferUsages::STORAGE,
        });
    }
    let expected = count * element;
    if b.size() < expected {
        return Err(PassError::BufferSize {
            what,
            expected,
            found: b.size(),
        });
    }
    Ok(())
}

/// The input of an `Option` role: `Ok(Some)` when it is given and
/// required, `Ok(None)` when neither; when given and required disagree, a
/// [`PassError::Missing`] naming `missing` or a [`PassError::Unexpected`]
/// naming `unexpected`.
pub(crate) fn required<T>(
    given: Option<T>,
    required: bool,
    missing: &'static str,
    unexpected: &'static str,
) -> Result<Option<T>, PassError> {
    match (given, required) {
        (Some(_), false) => Err(PassError::Unexpected(unexpected)),
        (None, true) => Err(PassError::Missing(missing)),
        (given, _) => Ok(given),
    }
}
