//! [`PassPipeline`], what every pass records through: its compiled
//! pipeline, uniform rings and cached bind groups.

use std::borrow::Cow;

use super::bindings::Resource;
use super::checks::check_timestamps;
use super::group::Group;
use super::pipeline::{compute_pipeline, pipeline_layout};
use super::uniform_ring::{Slot, UniformRing, UNIFORM_SLOTS};
use crate::PassError;

/// Pixels per side of every pass's workgroup: `@workgroup_size(8, 8)` in
/// each pass's WGSL.
pub(crate) const WORKGROUP: u32 = 8;

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
