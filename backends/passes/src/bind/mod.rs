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
//!
//! # The module's rules
//!
//! - wgpu is named here and nowhere else in the crate: every other module
//!   takes the host's wgpu types from this module's re-exports and calls
//!   wgpu through it (the test `tests/wgpu_in_one_module.rs` holds every
//!   file outside `src/bind/` to that).
//! - One file per concern, each reached through this module's re-exports
//!   (the paths `subcone_passes::bind::Group`, `bind::Rect`… do not name
//!   the files), and the files depend one way, from the pass's pipeline
//!   down to the formats:
//!   - `formats.rs`: the storage formats a group declares and the output
//!     formats a pass writes;
//!   - `entry.rs`: [`BindingEntry`] and [`BindingKind`], a binding without
//!     wgpu types;
//!   - `group.rs`: [`Group`] and [`BufferAccess`], the declarations (WGSL
//!     and wgpu layout from one list);
//!   - `bindings.rs`: [`Bindings`], a group with its resources;
//!   - `pipeline.rs`: [`pipeline_layout`] and [`compute_pipeline`];
//!   - `rect.rs`: [`Rect`], the pixels a pass reads and writes;
//!   - `checks.rs`: the checks of the host's views, buffers, timestamps
//!     and required inputs;
//!   - `uniform_ring.rs`: a pass's uniform slots ([`UNIFORM_SLOTS`],
//!     [`MAX_UNIFORM_SLOTS`]), and when one may be rewritten;
//!   - `pass_pipeline.rs`: `PassPipeline`, its cache of bind groups
//!     ([`BIND_GROUP_CACHE`]) and the resources it binds.

mod bindings;
mod checks;
mod entry;
mod formats;
mod group;
mod pass_pipeline;
mod pipeline;
mod rect;
mod uniform_ring;

/// The host's wgpu types, named once. The passes take these from the host
/// and no other module of the crate names an item of wgpu (the test
/// `tests/wgpu_in_one_module.rs` fails when one does), and every wgpu call
/// is made here, so a wgpu upgrade touches this module (and `Cargo.toml`).
pub(crate) use wgpu::{
    BindGroup, BindGroupLayout, Buffer, BufferUsages, CommandEncoder, ComputePassTimestampWrites,
    Device, Queue, TextureDimension, TextureFormat, TextureSampleType, TextureUsages, TextureView,
    TextureViewDimension,
};

pub use bindings::Bindings;
pub(crate) use checks::{
    check, check_buffer, check_float_color, check_output, check_output_region, check_region,
    is_float_color, required, Expect,
};
pub use entry::{BindingEntry, BindingKind};
pub(crate) use formats::check_output_format;
pub use group::{BufferAccess, Group};
pub use pass_pipeline::BIND_GROUP_CACHE;
pub(crate) use pass_pipeline::{Bound, PassPipeline, WORKGROUP};
pub use pipeline::{compute_pipeline, pipeline_layout};
pub use rect::Rect;
pub use uniform_ring::{MAX_UNIFORM_SLOTS, UNIFORM_SLOTS};
