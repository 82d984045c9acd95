//! What [`Resolver::resolve`](super::Resolver::resolve) reads of a pixel's
//! 3×3 neighbourhood before any weight: which slots are in the image
//! ([`Hood`]), and which layers can change a subsample's sum of layers
//! ([`LayerScan`]), either scanned slot by slot or, inside the image, read
//! from per-pixel [`LayerFlags`] computed once per frame (each shaded sample
//! belongs to nine neighbourhoods: the flags look at its colours once, not
//! nine times).

use glam::{Vec3, Vec3A};

use super::{ShadedFrame, ShadedGroup, MAX_LAYERS, SLOTS};

/// One shaded sample's layers of one group, summarised for every
/// neighbourhood it belongs to ([`LayerFlags::fill`]). Bit `i` of each field
/// is about layer `i` of the group (at most [`MAX_LAYERS`] = 16).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LayerFlags {
    /// Layer `i`'s colour is finite.
    pub finite: u16,
    /// Layer `i`'s colour is finite and not exactly black.
    pub live: u16,
    /// Layer `i`'s colour and that of the pixel to the right are both finite
    /// and equal as values (−0 = +0); clear in the last column.
    pub same_right: u16,
    /// The same against the pixel below; clear in the last row.
    pub same_below: u16,
}

impl LayerFlags {
    /// The flags of layers `0..layers` of `group` (at most [`MAX_LAYERS`])
    /// for pixels `first..first + out.len()` of `frame` (row-major), into
    /// `out`, one per pixel: a band of rows at a time, so that threads can
    /// share a frame. Entries past the frame's last pixel are left alone;
    /// colours missing from a short `frame.colors` read as black, as the
    /// resolver reads them.
    ///
    /// Not `#[inline]`, unlike the resolver: it runs once per region, and a
    /// copy inlined into an instruction-set path's resolve measured slower
    /// (old and new binaries alternating) than this one function.
    pub fn fill(
        frame: &ShadedFrame,
        group: &ShadedGroup,
        layers: usize,
        first: usize,
        out: &mut [LayerFlags],
    ) {
        let n = layers.min(MAX_LAYERS);
        let (w, h) = (frame.width as usize, frame.height as usize);
        let colour = |j: usize, i: usize| {
            Vec3A::from(color_at(frame, j * frame.layers + group.first_layer + i))
        };
        let pixels = (w * h).saturating_sub(first);
        for (j, f) in (first..).zip(out.iter_mut().take(pixels)) {
            let (x, y) = (j % w, j / w);
            let mut flags = LayerFlags::default();
            for i in 0..n {
                let c = colour(j, i);
                if !c.is_finite_mask().all() {
                    continue;
                }
                flags.finite |= 1 << i;
                if c.cmpne(Vec3A::ZERO).any() {
                    flags.live |= 1 << i;
                }
                // A NaN compares unequal: `same` needs both finite.
                if x + 1 < w && c.cmpeq(colour(j + 1, i)).all() {
                    flags.same_right |= 1 << i;
                }
                if y + 1 < h && c.cmpeq(colour(j + w, i)).all() {
                    flags.same_below |= 1 << i;
                }
            }
            *f = flags;
        }
    }
}

/// The [`LayerFlags`] of a frame's groups, for
/// [`Resolver::resolve_flagged`](super::Resolver::resolve_flagged): one per
/// pixel of the frame, row-major, each filled for the resolver's layers
/// ([`Resolver::layer_flags`](super::Resolver::layer_flags)). A slice of any
/// other length is not read (the neighbourhood is scanned instead).
#[derive(Clone, Copy, Debug, Default)]
pub struct FrameFlags<'a> {
    /// The primary group's.
    pub primary: &'a [LayerFlags],
    /// The secondary group's (empty without one).
    pub secondary: &'a [LayerFlags],
}

/// One pass over a group's colours in the 3×3 neighbourhood, before any
/// weight: which layers can change a subsample's sum of layers and which
/// reconstruct to one colour whatever the weights.
///
/// A layer without a colour that is finite and not exactly black anywhere
/// in the neighbourhood (`live` clear) reconstructs to black. A layer with
/// one colour, bit for bit, wherever it is finite (`varied` clear)
/// reconstructs to that colour: each product `w·C` is exact in f64 and the
/// normalised sum is within a few f64 ulps of `C`, which rounds back to `C`
/// in f32; the fallback is `C` too. So `varied` may be set where the layer is
/// in fact uniform (the weighted path gives the same bits, at a higher
/// cost): [`LayerScan::from_flags`] sets it unless all nine colours are
/// finite and equal. The uniform colour is read when needed
/// ([`LayerScan::uniform`]).
pub(super) struct LayerScan {
    /// Bit `i`: layer `i` has a finite colour that is not black.
    pub(super) live: u32,
    /// Bit `i`: layer `i`'s finite colours may not all be one colour.
    pub(super) varied: u32,
    /// Each slot's index, in `frame.colors`, of the group's first layer.
    pub(super) base: [usize; SLOTS],
    /// Bit `i` of a slot: its colour of layer `i` is finite.
    pub(super) finite: [u32; SLOTS],
}

impl LayerScan {
    /// The scan of layers `0..n` of `group` over `hood`: read from `flags`
    /// (one per pixel of the frame) when the whole neighbourhood is in the
    /// image and `flags` covers the frame, else slot by slot.
    #[inline(always)]
    pub(super) fn of(
        frame: &ShadedFrame,
        hood: &Hood,
        group: &ShadedGroup,
        n: usize,
        flags: &[LayerFlags],
    ) -> Self {
        if hood.valid == Hood::ALL && flags.len() == frame.width as usize * frame.height as usize {
            Self::from_flags(frame, hood, group, n, flags)
        } else {
            Self::new(frame, hood, group, n)
        }
    }

    /// The scan of layers `0..n` of `group` over the valid slots of `hood`.
    // Layer `i` indexes bit masks and the per-layer arrays alike.
    #[allow(clippy::needless_range_loop)]
    #[inline(always)]
    fn new(frame: &ShadedFrame, hood: &Hood, group: &ShadedGroup, n: usize) -> Self {
        let mut live = 0u32;
        let mut varied = 0u32;
        let mut seen = 0u32;
        let mut uniform = [Vec3A::ZERO; MAX_LAYERS];
        let mut base = [0usize; SLOTS];
        let mut finite = [0u32; SLOTS];
        for slot in hood.slots() {
            base[slot] = hood.index[slot] * frame.layers + group.first_layer;
            for i in 0..n {
                // In one vector register: three lanes compared at once.
                let c = Vec3A::from(color_at(frame, base[slot] + i));
                if c.is_finite_mask().all() {
                    finite[slot] |= 1 << i;
                    if c.cmpne(Vec3A::ZERO).any() {
                        live |= 1 << i;
                    }
                    if seen & (1 << i) == 0 {
                        seen |= 1 << i;
                        uniform[i] = c;
                    } else if c.cmpne(uniform[i]).any() {
                        // (−0 and +0 count as one colour: either adds
                        // nothing to a subsample's sum of layers.)
                        varied |= 1 << i;
                    }
                }
            }
        }
        Self {
            live,
            varied,
            base,
            finite,
        }
    }

    /// Layer `i`'s colour where `varied` is clear: the first finite one in
    /// slot order, as [`LayerScan::new`] compared the others with. (Read on
    /// demand: an array of [`MAX_LAYERS`] colours per scan costs more to
    /// fill and move than the few layers that are uniform.)
    #[inline(always)]
    pub(super) fn uniform(&self, frame: &ShadedFrame, i: usize) -> Vec3A {
        for slot in 0..SLOTS {
            if self.finite[slot] & (1 << i) != 0 {
                return Vec3A::from(color_at(frame, self.base[slot] + i));
            }
        }
        Vec3A::ZERO
    }

    /// The scan of a neighbourhood wholly inside the image, from the
    /// per-pixel flags: `live` and `finite` as [`LayerScan::new`] finds them;
    /// `varied` clear only for the layers whose nine colours are all finite
    /// and equal (each row equal along it, the left column down it), with
    /// the first slot's colour, as [`LayerScan::new`] takes it.
    #[inline(always)]
    fn from_flags(
        frame: &ShadedFrame,
        hood: &Hood,
        group: &ShadedGroup,
        n: usize,
        flags: &[LayerFlags],
    ) -> Self {
        let mut live = 0u32;
        let mut base = [0usize; SLOTS];
        let mut finite = [0u32; SLOTS];
        let mut f = [LayerFlags::default(); SLOTS];
        for slot in 0..SLOTS {
            let j = hood.index[slot];
            f[slot] = flags[j];
            base[slot] = j * frame.layers + group.first_layer;
            finite[slot] = f[slot].finite as u32;
            live |= f[slot].live as u32;
        }
        let same = f[0].same_right
            & f[1].same_right
            & f[3].same_right
            & f[4].same_right
            & f[6].same_right
            & f[7].same_right
            & f[0].same_below
            & f[3].same_below;
        let layers = if n >= 32 { u32::MAX } else { (1u32 << n) - 1 };
        let varied = layers & !(same as u32);
        Self {
            live,
            varied,
            base,
            finite,
        }
    }
}

/// The in-image part of a pixel's 3×3 neighbourhood: a bit per slot
/// (row-major) and each slot's pixel index.
pub(super) struct Hood {
    pub(super) valid: u32,
    pub(super) index: [usize; SLOTS],
}

impl Hood {
    /// Every slot in the image.
    pub(super) const ALL: u32 = (1 << SLOTS) - 1;

    #[inline(always)]
    pub(super) fn new(frame: &ShadedFrame, x: u32, y: u32) -> Self {
        let (w, h) = (frame.width as usize, frame.height as usize);
        let (xu, yu) = (x as usize, y as usize);
        if xu >= 1 && yu >= 1 && xu + 1 < w && yu + 1 < h {
            // Inside: the nine indices around the pixel's, no test per slot.
            let j = yu * w + xu;
            return Self {
                valid: Self::ALL,
                index: [
                    j - w - 1,
                    j - w,
                    j - w + 1,
                    j - 1,
                    j,
                    j + 1,
                    j + w - 1,
                    j + w,
                    j + w + 1,
                ],
            };
        }
        let mut valid = 0;
        let mut index = [0; SLOTS];
        for (slot, i) in index.iter_mut().enumerate() {
            let px = x as i64 + (slot % 3) as i64 - 1;
            let py = y as i64 + (slot / 3) as i64 - 1;
            if px >= 0 && py >= 0 && px < frame.width as i64 && py < frame.height as i64 {
                valid |= 1 << slot;
                *i = py as usize * frame.width as usize + px as usize;
            }
        }
        Self { valid, index }
    }

    /// The valid slots in row-major order (that of [`neighbourhood`](crate::sraa::neighbourhood)).
    pub(super) fn slots(&self) -> impl Iterator<Item = usize> {
        slots(self.valid)
    }
}

/// Colour `i` of the frame's flat layer array; black past its end.
#[inline]
pub(super) fn color_at(frame: &ShadedFrame, i: usize) -> Vec3 {
    frame.colors.get(i).copied().unwrap_or(Vec3::ZERO)
}

/// The slots set in `mask`, in increasing (row-major) order.
#[inline]
pub(super) fn slots(mut mask: u32) -> impl Iterator<Item = usize> {
    core::iter::from_fn(move || {
        if mask == 0 {
            return None;
        }
        let slot = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        Some(slot)
    })
}
