//! [`Group`]: the declarations of one bind group, from which come both the
//! WGSL declarations and the wgpu layout and bind group.

use std::borrow::Cow;

use super::entry::{BindingEntry, BindingKind};
use super::formats::{storage_format_name, STORAGE_FORMATS};
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
pub(super) struct Decl {
    pub(super) name: Cow<'static, str>,
    /// The address space after `var` (`<uniform>`, `<storage, read>`…),
    /// empty for a texture.
    space: &'static str,
    /// The WGSL type.
    wgsl_type: String,
    ty: wgpu::BindingType,
    /// The size of a uniform bound at a dynamic offset (a pass's
    /// [`UniformRing`]); `None` for every other binding.
    ///
    /// [`UniformRing`]: super::uniform_ring::UniformRing
    pub(super) ring: Option<u64>,
}

/// The bindings of one bind group, in binding order: binding `i` is the
/// `i`-th added. Declarations only; [`Bindings`] adds the resources.
///
/// [`Bindings`]: super::Bindings
#[derive(Clone, Debug)]
pub struct Group {
    index: u32,
    visibility: wgpu::ShaderStages,
    pub(super) list: Vec<Decl>,
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
    ///
    /// [`UniformRing`]: super::uniform_ring::UniformRing
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
