//! [`Rect`]: the rectangle of pixels a pass reads and writes.

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
