//! A pass's uniforms: a ring of slots per uniform in one buffer, bound at a
//! dynamic offset, that grows rather than overwrite a slot an encode not
//! yet submitted still reads.
//!
//! # Why slots, and when one may be rewritten
//!
//! `encode` writes a pass's uniforms with `Queue::write_buffer`, which takes
//! effect at the host's next `Queue::submit`, *before* any command of that
//! submission runs. So two encodes of one submission that bind the same
//! slot both read whichever value was written last: every distinct value of
//! a submission needs a slot of its own. (A ring of a fixed
//! [`UNIFORM_SLOTS`] that overwrote its least recently used slot made a
//! 17th CTSS viewport of one submission silently draw an earlier viewport
//! with its own camera and rect.)
//!
//! A slot is *pending* while an encode that binds it may not have been
//! submitted; a pending slot is never rewritten. It stops being pending
//!
//! - when the host says so: the pass's `end_submission` (every encode made
//!   so far has been submitted), the explicit, deterministic way; or
//! - when the command buffer of every encode that binds it has finished on
//!   the GPU: each encode registers `CommandEncoder::on_submitted_work_done`
//!   on the host's encoder, which wgpu calls from the host's own
//!   `Device::poll` or `Queue::submit` once the work ran. This is late (the
//!   hazard ends at submission, not at completion) and depends on the host
//!   polling, so it is only the safety net that keeps a host that never
//!   calls `end_submission` correct and bounded; it is never early, so it is
//!   never wrong.
//!
//! An encode reuses a slot that holds an equal value (pending or not, no
//! write), else rewrites the least recently used slot that is not pending,
//! else doubles the ring (a new buffer, and the pass's cached bind groups
//! are made again), up to [`MAX_UNIFORM_SLOTS`]; past that it is refused
//! with [`PassError::UniformSlotsExhausted`](crate::PassError), before
//! anything is written or recorded. Growing rather than refusing at
//! [`UNIFORM_SLOTS`] keeps a host that legitimately encodes many distinct
//! values in one submission (viewports, split screens, tiles) correct; the
//! bound keeps a host that leaks pending slots (it never submits, or drops
//! encoders unsubmitted without calling `end_submission`) from growing the
//! ring without end, and tells it so as a typed error.

use std::sync::{Arc, Mutex, MutexGuard};

/// Uniform slots per uniform of a pass when it is built: how many distinct
/// values of one uniform (a frame's size, camera, projection…) a pass holds
/// before its ring grows.
///
/// A host whose submissions each hold at most this many distinct values of
/// each uniform (and that submits and polls, or calls the pass's
/// `end_submission`) never makes the ring grow, so after its first frame
/// `encode` allocates nothing. More in one submission is correct too: the
/// ring doubles, up to [`MAX_UNIFORM_SLOTS`].
pub const UNIFORM_SLOTS: usize = 16;

/// Most uniform slots per uniform of a pass: the most distinct values of one
/// uniform that may wait for their submission at once.
///
/// The bound is what makes a forgotten submission a typed error
/// ([`PassError::UniformSlotsExhausted`](crate::PassError)) rather than a
/// ring that grows without end: 4096 slots of a 256-byte stride are 1 MiB
/// per uniform. The device's `max_buffer_size` may lower it.
pub const MAX_UNIFORM_SLOTS: usize = 4096;

/// One slot of a ring: the bytes last written to it, when it was last
/// bound, and how many encodes binding it may still be unsubmitted.
#[derive(Default)]
struct Slot {
    value: Option<Vec<u8>>,
    used: u64,
    pending: u32,
}

/// The slots of one ring. `generation` changes when the slots' pending
/// counts are reset (the host ended a submission), so a late work-done
/// callback of an older generation releases nothing.
struct RingSlots {
    slots: Vec<Slot>,
    generation: u64,
}

impl RingSlots {
    fn new(count: usize, generation: u64) -> Self {
        RingSlots {
            slots: (0..count).map(|_| Slot::default()).collect(),
            generation,
        }
    }
}

/// Where one encode's value of one uniform goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Placement {
    /// A slot that already holds the value: bind it, write nothing.
    Held(usize),
    /// A slot that is not pending: write the value into it.
    Write(usize),
    /// No slot is free: grow the ring to this many slots (a new buffer),
    /// then write the value into the first new slot. The old slots keep
    /// their index and pending count: the encodes that bind them read the
    /// old buffer, and their slots are taken again only once released.
    Grow(usize),
}

/// A slot bound by one encode: (uniform, slot, generation), what its
/// work-done callback releases.
pub(super) type Held = (usize, usize, u64);

/// The slots of every uniform of a pass, shared with the work-done
/// callbacks of its encodes (plain data: wgpu objects stay in the pass).
#[derive(Default)]
pub(super) struct SlotTable {
    rings: Vec<RingSlots>,
    /// A counter of encodes, for least-recently-used choices.
    clock: u64,
}

/// [`SlotTable`] behind the lock its callbacks take.
pub(super) type SharedSlots = Arc<Mutex<SlotTable>>;

/// Lock `slots`. A panic while the lock was held left the table consistent
/// (every change is a whole field), so a poisoned lock is used as it is.
pub(super) fn lock(slots: &Mutex<SlotTable>) -> MutexGuard<'_, SlotTable> {
    slots.lock().unwrap_or_else(|e| e.into_inner())
}

impl SlotTable {
    /// A table of `rings` rings of [`UNIFORM_SLOTS`] slots each.
    pub(super) fn new(rings: usize) -> Self {
        SlotTable {
            rings: (0..rings)
                .map(|_| RingSlots::new(UNIFORM_SLOTS, 0))
                .collect(),
            clock: 0,
        }
    }

    /// Slots of ring `u` now.
    pub(super) fn len(&self, u: usize) -> usize {
        self.rings[u].slots.len()
    }

    /// Where `value` of uniform `u` would go, changing nothing; `None` when
    /// no slot is free and the ring already has `max` slots.
    pub(super) fn place(&self, u: usize, value: &[u8], max: usize) -> Option<Placement> {
        let slots = &self.rings[u].slots;
        if let Some(s) = slots.iter().position(|s| s.value.as_deref() == Some(value)) {
            return Some(Placement::Held(s));
        }
        if let Some(s) = (0..slots.len())
            .filter(|&s| slots[s].pending == 0)
            .min_by_key(|&s| slots[s].used)
        {
            return Some(Placement::Write(s));
        }
        (slots.len() < max).then(|| Placement::Grow((2 * slots.len()).min(max)))
    }

    /// Start one encode: advance the clock.
    pub(super) fn tick(&mut self) {
        self.clock += 1;
    }

    /// Apply `placement` of `value` of uniform `u` (from [`Self::place`],
    /// with nothing changed in between): the slot now holds `value`, is
    /// pending for one more encode and was used now. The slot bound.
    pub(super) fn bind(&mut self, u: usize, placement: Placement, value: &[u8]) -> Held {
        let ring = &mut self.rings[u];
        let s = match placement {
            Placement::Held(s) => s,
            Placement::Write(s) => {
                ring.slots[s].value = Some(value.to_vec());
                s
            }
            Placement::Grow(count) => {
                // The new buffer holds none of the old values.
                for slot in &mut ring.slots {
                    slot.value = None;
                }
                let first = ring.slots.len();
                ring.slots.resize_with(count, Slot::default);
                ring.slots[first].value = Some(value.to_vec());
                first
            }
        };
        let slot = &mut ring.slots[s];
        slot.used = self.clock;
        slot.pending += 1;
        (u, s, ring.generation)
    }

    /// Release the slots `held` bound by one encode whose work has run (a
    /// slot of an older generation was released already).
    pub(super) fn release(&mut self, held: &[Held]) {
        for &(u, s, generation) in held {
            if let Some(ring) = self.rings.get_mut(u) {
                if ring.generation == generation {
                    if let Some(slot) = ring.slots.get_mut(s) {
                        slot.pending = slot.pending.saturating_sub(1);
                    }
                }
            }
        }
    }

    /// The host submitted every encode made so far: no slot is pending.
    pub(super) fn end_submission(&mut self) {
        for ring in &mut self.rings {
            ring.generation += 1;
            for slot in &mut ring.slots {
                slot.pending = 0;
            }
        }
    }
}

/// One uniform of a pass: a buffer of slots (as many as its ring in the
/// [`SlotTable`]), each at a multiple of the device's
/// `min_uniform_buffer_offset_alignment`.
pub(super) struct UniformRing {
    pub(super) buffer: wgpu::Buffer,
    /// Bytes of one value.
    pub(super) size: u64,
    /// Bytes between slots.
    pub(super) stride: u64,
}

impl UniformRing {
    /// A ring of `slots` slots for values of `size` bytes, `stride` apart.
    pub(super) fn new(
        device: &wgpu::Device,
        label: &str,
        size: u64,
        stride: u64,
        slots: usize,
    ) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: stride * slots as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        UniformRing {
            buffer,
            size,
            stride,
        }
    }

    /// The most slots this ring may grow to on `device`:
    /// [`MAX_UNIFORM_SLOTS`], or fewer if the buffer would pass the device's
    /// `max_buffer_size` (never fewer than [`UNIFORM_SLOTS`], which `new`
    /// made).
    pub(super) fn max_slots(&self, device: &wgpu::Device) -> usize {
        let fit = device.limits().max_buffer_size / self.stride;
        MAX_UNIFORM_SLOTS
            .min(usize::try_from(fit).unwrap_or(usize::MAX))
            .max(UNIFORM_SLOTS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_equal_value_is_held_and_a_distinct_one_takes_a_free_slot() {
        let mut t = SlotTable::new(1);
        t.tick();
        assert_eq!(t.place(0, b"a", 64), Some(Placement::Write(0)));
        t.bind(0, Placement::Write(0), b"a");
        t.tick();
        assert_eq!(t.place(0, b"a", 64), Some(Placement::Held(0)));
        assert_eq!(t.place(0, b"b", 64), Some(Placement::Write(1)));
    }

    #[test]
    fn a_pending_slot_is_never_rewritten_and_the_ring_grows_to_its_bound() {
        let mut t = SlotTable::new(1);
        for i in 0..UNIFORM_SLOTS {
            t.tick();
            let v = [i as u8];
            let p = t.place(0, &v, 32).expect("a free slot");
            assert_eq!(p, Placement::Write(i));
            t.bind(0, p, &v);
        }
        assert_eq!(t.place(0, &[200], 32), Some(Placement::Grow(32)));
        assert_eq!(t.bind(0, Placement::Grow(32), &[200]).1, UNIFORM_SLOTS);
        assert_eq!(t.len(0), 32);
        // The old slots stay pending (their encodes read the old buffer),
        // and none holds its value in the new one.
        assert_eq!(t.place(0, &[0], 32), Some(Placement::Write(17)));
        for i in 17..32 {
            t.tick();
            let v = [100 + i as u8];
            assert_eq!(t.place(0, &v, 32), Some(Placement::Write(i)));
            t.bind(0, Placement::Write(i), &v);
        }
        assert_eq!(t.place(0, &[255], 32), None, "past the bound");
    }

    #[test]
    fn released_or_ended_slots_are_rewritten_and_releases_of_an_ended_submission_do_nothing() {
        let mut t = SlotTable::new(1);
        let mut held = Vec::new();
        for i in 0..UNIFORM_SLOTS {
            t.tick();
            let v = [i as u8];
            let p = t.place(0, &v, UNIFORM_SLOTS).expect("a free slot");
            held.push(t.bind(0, p, &v));
        }
        assert_eq!(t.place(0, &[99], UNIFORM_SLOTS), None);
        // The work of encode 3 ran: its slot, and only it, is free.
        t.release(&held[3..4]);
        assert_eq!(t.place(0, &[99], UNIFORM_SLOTS), Some(Placement::Write(3)));
        t.bind(0, Placement::Write(3), &[99]);
        assert_eq!(t.place(0, &[98], UNIFORM_SLOTS), None);
        // The host ended the submission: every slot is free, and callbacks
        // of the ended generation release nothing later.
        t.end_submission();
        assert!(matches!(
            t.place(0, &[98], UNIFORM_SLOTS),
            Some(Placement::Write(_))
        ));
        t.tick();
        let p = t.place(0, &[98], UNIFORM_SLOTS).unwrap();
        let new = t.bind(0, p, &[98]);
        t.release(&held);
        let Placement::Write(s) = p else {
            panic!("{p:?}")
        };
        assert_eq!(new.1, s);
        assert_eq!(t.rings[0].slots[s].pending, 1, "a stale release freed it");
    }
}
