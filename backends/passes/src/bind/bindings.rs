//! [`Bindings`]: a [`Group`] together with the resources it binds.

use std::borrow::Cow;

use super::group::{BufferAccess, Group};
use crate::PassError;

/// A resource bound by [`Bindings`] or cached by a pass (wgpu's handles
/// are reference counted: a clone is the same object).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) enum Resource {
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
