//! The reconstruction neighbourhood: the pixels whose shaded samples
//! reconstruct a subsample.

use glam::Vec2;

use super::SUBPIXEL_OFFSETS;

/// A pixel of a reconstruction neighbourhood, with the squared screen distance
/// from the target subsample to that pixel's shaded sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NeighbourPixel {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// Squared distance in pixels² (what [`ShadedSample::distance2`](super::ShadedSample::distance2) wants).
    pub distance2: f32,
}

/// The pixels whose shaded samples reconstruct subsample `sub` of pixel `(x, y)`:
/// the `(2r+1)²` pixels around it (the paper's "fixed radius"; `r = 1` is the 3×3
/// neighbourhood), clipped to a `width × height` image, in row-major order,
/// with each shaded sample's squared distance to the subsample. `shaded` is
/// where a pixel's shaded sample lies ([`SraaParams::shaded_offset`](super::SraaParams::shaded_offset)).
///
/// Domain: `sub < 4`, `(x, y)` inside the image. A `sub ≥ 4` (e.g.
/// [`SHADED_SAMPLE`](super::SHADED_SAMPLE)) is the shaded sample itself; a pixel outside the image
/// yields only the in-image part of its neighbourhood (possibly nothing).
pub fn neighbourhood(
    x: u32,
    y: u32,
    sub: usize,
    shaded: Vec2,
    radius: u32,
    width: u32,
    height: u32,
) -> Neighbourhood {
    let target = if sub < 4 {
        SUBPIXEL_OFFSETS[sub]
    } else {
        shaded
    };
    let offset = target - shaded;
    let x0 = x.saturating_sub(radius);
    let y0 = y.saturating_sub(radius);
    let x1 = x.saturating_add(radius).saturating_add(1).min(width);
    let y1 = y.saturating_add(radius).saturating_add(1).min(height);
    Neighbourhood {
        x,
        y,
        offset,
        x0,
        x1,
        y1,
        cx: x0,
        cy: y0,
    }
}

/// Iterator returned by [`neighbourhood`].
#[derive(Clone, Debug)]
pub struct Neighbourhood {
    x: u32,
    y: u32,
    /// Target subsample position minus the shaded sample position, within a pixel.
    offset: Vec2,
    x0: u32,
    x1: u32,
    y1: u32,
    cx: u32,
    cy: u32,
}

impl Iterator for Neighbourhood {
    type Item = NeighbourPixel;

    fn next(&mut self) -> Option<NeighbourPixel> {
        if self.cx >= self.x1 {
            self.cx = self.x0;
            self.cy += 1;
        }
        if self.cy >= self.y1 || self.x0 >= self.x1 {
            return None;
        }
        let (px, py) = (self.cx, self.cy);
        self.cx += 1;
        // Shaded sample of (px, py) minus target subsample of (x, y).
        let d = Vec2::new(px as f32 - self.x as f32, py as f32 - self.y as f32) - self.offset;
        Some(NeighbourPixel {
            x: px,
            y: py,
            distance2: d.length_squared(),
        })
    }
}
