//! A pass's uniforms: [`UNIFORM_SLOTS`] slots per uniform in one buffer,
//! bound at a dynamic offset.

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

/// One slot of a [`UniformRing`]: the bytes last written to it and when it
/// was last bound.
#[derive(Default)]
pub(super) struct Slot {
    pub(super) value: Option<Vec<u8>>,
    pub(super) used: u64,
}

/// One uniform of a pass: a buffer of [`UNIFORM_SLOTS`] slots made in the
/// pass's `new`, each at a multiple of the device's
/// `min_uniform_buffer_offset_alignment`.
pub(super) struct UniformRing {
    pub(super) buffer: wgpu::Buffer,
    /// Bytes of one value.
    pub(super) size: u64,
    /// Bytes between slots.
    pub(super) stride: u64,
}
