//! One binding described without wgpu types ([`BindingEntry`],
//! [`BindingKind`]): what an engine without wgpu reads from a
//! [`Group`].
//!
//! [`Group`]: super::Group

use super::formats::storage_format_name;

/// One binding of a [`Group`], described without wgpu types
/// ([`Group::entries`]): the row of a pass's resource table.
///
/// [`Group`]: super::Group
/// [`Group::entries`]: super::Group::entries
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
    pub(super) fn of(ty: &wgpu::BindingType) -> Self {
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
