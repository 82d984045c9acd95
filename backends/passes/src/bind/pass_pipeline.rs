//! [`PassPipeline`], what every pass records through: its compiled
//! pipeline, uniform rings and cached bind groups.

use std::borrow::Cow;

use super::bindings::Resource;
use super::checks::check_timestamps;
use super::group::Group;
use super::pipeline::{compute_pipeline, pipeline_layout};
use super::uniform_ring::{self, Placement, SharedSlots, SlotTable, UniformRing, UNIFORM_SLOTS};
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

/// What `encode` updates besides the slot table: the uniform rings'
/// buffers (replaced when a ring grows) and the bind groups.
struct State {
    /// A counter of encodes, for the least recently used bind group.
    clock: u64,
    /// One ring per uniform of the group, in binding order.
    uniforms: Vec<UniformRing>,
    groups: Vec<CachedGroup>,
}

/// The compiled side of one pass: its group 0, that group's layout, the
/// compute pipeline over it (and over the host's group 1, for a pass that
/// reads one), its uniform buffers and its cache of bind groups. Built once
/// by the pass's `new`; each frame's `encode` writes its uniforms into
/// slots, binds its views (a cached bind group after the first frame) and
/// dispatches one invocation per output pixel, creating no GPU object for
/// views it has seen ([`UNIFORM_SLOTS`], [`BIND_GROUP_CACHE`]) unless a
/// submission holds more distinct uniform values than any before
/// (`uniform_ring.rs`: the ring grows).
pub(crate) struct PassPipeline {
    label: &'static str,
    group: Group,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// Bytes of each uniform of `group`, in binding order.
    sizes: Vec<u64>,
    /// Which slot holds what, shared with the encodes' work-done callbacks.
    /// Locked after `state`, and never while calling wgpu.
    slots: SharedSlots,
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
    /// device's limits ([`Group::check_limits`]) before creating anything,
    /// and a source that does not compile with [`PassError::Shader`]:
    /// the module and the pipeline are made inside an error scope of the
    /// pass's own, so naga's message comes back to the host as a value of
    /// its `new` rather than through its device's uncaptured-error handler
    /// (which sees nothing).
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
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pl = match host_layout {
            Some(host) => pipeline_layout(device, label, &[&layout, host]),
            None => pipeline_layout(device, label, &[&layout]),
        };
        let pipeline = compute_pipeline(device, label, &pl, &module, entry);
        // The scope holds the first error: the module's (naga's parser or
        // validator), else the pipeline's (e.g. a host group 1 layout the
        // shader does not match).
        if let Some(e) = ready(scope.pop()) {
            return Err(PassError::Shader {
                message: e.to_string().trim_end().to_owned(),
            });
        }
        let align = u64::from(device.limits().min_uniform_buffer_offset_alignment).max(1);
        let uniforms: Vec<UniformRing> = group
            .list
            .iter()
            .filter_map(|d| d.ring)
            .map(|size| {
                let stride = size.div_ceil(align) * align;
                UniformRing::new(device, label, size, stride, UNIFORM_SLOTS)
            })
            .collect();
        Ok(PassPipeline {
            label,
            group,
            layout,
            pipeline,
            sizes: uniforms.iter().map(|r| r.size).collect(),
            slots: std::sync::Arc::new(std::sync::Mutex::new(SlotTable::new(uniforms.len()))),
            state: std::sync::Mutex::new(State {
                clock: 0,
                uniforms,
                groups: Vec::new(),
            }),
        })
    }

    /// The host has submitted every command buffer encoded into so far: no
    /// uniform slot is read by an unsubmitted encode any more, so every slot
    /// may be rewritten (`uniform_ring.rs`).
    pub(crate) fn end_submission(&self) {
        uniform_ring::lock(&self.slots).end_submission();
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
        let ordered = self.in_binding_order(resources)?;
        if uniforms.len() != self.sizes.len()
            || uniforms
                .iter()
                .zip(&self.sizes)
                .any(|(u, &size)| u.len() as u64 != size)
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
        // Where each value goes, decided under the table's lock and applied
        // to it at once (so a work-done callback sees either all or none of
        // this encode's slots); the wgpu calls come after the lock.
        let (placements, held) = {
            let mut table = uniform_ring::lock(&self.slots);
            let mut placements = Vec::with_capacity(uniforms.len());
            for (u, value) in uniforms.iter().enumerate() {
                let max = state.uniforms[u].max_slots(device);
                let p = table
                    .place(u, value, max)
                    .ok_or(PassError::UniformSlotsExhausted {
                        pass: self.label,
                        slots: table.len(u),
                    })?;
                placements.push(p);
            }
            table.tick();
            let held: Vec<_> = placements
                .iter()
                .zip(uniforms)
                .enumerate()
                .map(|(u, (&p, value))| table.bind(u, p, value))
                .collect();
            (placements, held)
        };
        let mut offsets = Vec::with_capacity(uniforms.len());
        for (u, (placement, value)) in placements.iter().zip(uniforms).enumerate() {
            let s = held[u].1;
            if let Placement::Grow(count) = *placement {
                // Encodes already recorded keep the old buffer alive (wgpu
                // holds what a command buffer binds); the cached bind groups
                // bind it, so they go.
                let (size, stride) = (state.uniforms[u].size, state.uniforms[u].stride);
                state.uniforms[u] = UniformRing::new(device, self.label, size, stride, count);
                state.groups.clear();
            }
            let ring = &state.uniforms[u];
            if !matches!(placement, Placement::Held(_)) {
                queue.write_buffer(&ring.buffer, s as u64 * ring.stride, value);
            }
            offsets.push((s as u64 * ring.stride) as u32);
        }
        // The safety net for a host that never calls `end_submission`: the
        // slots are released once this command buffer has run.
        let slots = std::sync::Arc::clone(&self.slots);
        encoder.on_submitted_work_done(move || uniform_ring::lock(&slots).release(&held));
        state.clock += 1;
        let now = state.clock;
        let index = self.cached_group(device, &mut state, &ordered, now);
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

    /// The host's `resources` in binding order: every declared binding but
    /// the uniforms exactly once, by name; a missing or unexpected name is
    /// an error.
    fn in_binding_order<'r>(
        &self,
        resources: &[(&'static str, Bound<'r>)],
    ) -> Result<Vec<Bound<'r>>, PassError> {
        // The resources in binding order.
        let mut ordered: Vec<Bound<'r>> = Vec::with_capacity(resources.len());
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
        Ok(ordered)
    }

    /// The index in `state`'s cache of the bind group of `ordered` (the
    /// uniform rings as they are now): a cached one binding the same
    /// resources, or a new one in a free entry or the least recently used.
    fn cached_group(
        &self,
        device: &wgpu::Device,
        state: &mut State,
        ordered: &[Bound<'_>],
        now: u64,
    ) -> usize {
        let cached = state.groups.iter().position(|g| {
            g.resources.len() == ordered.len()
                && g.resources.iter().zip(ordered).all(|(a, b)| b.is(a))
        });
        match cached {
            Some(i) => i,
            None => {
                let group = self.bind_group(device, &state.uniforms, ordered);
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
        }
    }

    /// The bind group of the uniform rings (one slot each, at a dynamic
    /// offset) and `resources`, in binding order.
    fn bind_group(
        &self,
        device: &wgpu::Device,
        uniforms: &[UniformRing],
        resources: &[Bound<'_>],
    ) -> wgpu::BindGroup {
        let mut rings = uniforms.iter();
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

/// The output of `future`, polled on this thread with a waker that does
/// nothing, yielding while it is pending: the crate's one wait, for a
/// popped error scope, whose future wgpu's native backends return ready
/// (the errors were caught as the objects were made). A waker of our own
/// rather than an executor keeps the crate's dependencies to the kernels,
/// wgpu, bytemuck and glam (`tests/dependencies.rs`).
fn ready<F: std::future::Future>(future: F) -> F::Output {
    let mut future = std::pin::pin!(future);
    let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
    loop {
        if let std::task::Poll::Ready(out) = future.as_mut().poll(&mut cx) {
            return out;
        }
        std::thread::yield_now();
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
