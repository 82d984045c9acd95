//! The motion section's animation: the window where NoAA is least
//! stable, each method's tile beside the reference's, as an animated PNG.

use super::*;

/// The `side × side` window (on a half-side grid) where `map`, summed, is
/// largest.
pub(super) fn worst_window(map: &[f32], w: u32, h: u32, side: u32) -> MotionCrop {
    let side = side.min(w).min(h).max(1);
    let stride = (side / 2).max(1);
    let mut best = (f64::NEG_INFINITY, MotionCrop { x: 0, y: 0, side });
    let mut y = 0;
    while y + side <= h {
        let mut x = 0;
        while x + side <= w {
            let s: f64 = (y..y + side)
                .flat_map(|yy| (x..x + side).map(move |xx| (yy * w + xx) as usize))
                .map(|i| f64::from(map[i]))
                .sum();
            if s > best.0 {
                best = (s, MotionCrop { x, y, side });
            }
            x += stride;
        }
        y += stride;
    }
    best.1
}

/// One animation frame: the crop of each image, zoomed, side by side with
/// a 2-pixel grey gap, under a band naming each tile (`names`, one per
/// image) and over a band with `caption` (the frame's number).
pub(super) fn strip(
    images: &[&Rgb8],
    names: &[&str],
    caption: &str,
    crop: MotionCrop,
) -> Result<Rgb8> {
    let tile = crop.side * CROP_ZOOM;
    let gap = 2;
    let n = images.len() as u32;
    let (w, h) = (
        n * tile + (n.saturating_sub(1)) * gap,
        tile + 2 * LABEL_BAND,
    );
    let mut data = vec![128u8; (w * h * 3) as usize];
    // The label bands are white, the tiles' gaps grey.
    let band = (w * LABEL_BAND * 3) as usize;
    data[..band].fill(255);
    let below = ((LABEL_BAND + tile) * w * 3) as usize;
    data[below..].fill(255);
    for (k, img) in images.iter().enumerate() {
        let x0 = k as u32 * (tile + gap);
        for y in 0..tile {
            for x in 0..tile {
                let (sx, sy) = (crop.x + x / CROP_ZOOM, crop.y + y / CROP_ZOOM);
                let s = ((sy * img.width + sx) * 3) as usize;
                let d = (((y + LABEL_BAND) * w + x0 + x) * 3) as usize;
                data[d..d + 3].copy_from_slice(&img.data[s..s + 3]);
            }
        }
    }
    crate::plot::register_fonts()?;
    {
        let pe = |e| anyhow!("motion labels: {e:?}");
        let root = BitMapBackend::with_buffer(&mut data, (w, h)).into_drawing_area();
        let size = (LABEL_BAND - 3) as i32;
        for (k, name) in names.iter().enumerate() {
            let font = (FAMILY, size).into_font().color(&BLACK);
            let x0 = (k as u32 * (tile + gap)) as i32 + 1;
            root.draw(&Text::new(name.to_string(), (x0, 1), font))
                .map_err(pe)?;
        }
        let font = (FAMILY, size).into_font().color(&BLACK);
        root.draw(&Text::new(
            caption.to_string(),
            (1, (LABEL_BAND + tile) as i32 + 1),
            font,
        ))
        .map_err(pe)?;
        root.present().map_err(pe)?;
    }
    Ok(Rgb8 {
        width: w,
        height: h,
        data,
    })
}

/// The order the animation plays `n` frames in: forward, then backward
/// without repeating either end (`0 1 2 3 2 1` for 4), so that each step of
/// the loop, the one back to the start included, is one camera step.
pub fn ping_pong(n: usize) -> Vec<usize> {
    (0..n).chain((1..n.saturating_sub(1)).rev()).collect()
}

/// Write `frames` (all one size) as an animated PNG that loops forever.
pub fn save_apng(path: &Path, frames: &[Rgb8]) -> Result<()> {
    let first = frames
        .first()
        .ok_or_else(|| anyhow!("{}: no frame to animate", path.display()))?;
    let file =
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let pe = |e: png::EncodingError| anyhow!("cannot write {}: {e}", path.display());
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), first.width, first.height);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_animated(frames.len() as u32, 0).map_err(pe)?;
    enc.set_frame_delay(1, ANIMATION_FPS).map_err(pe)?;
    let mut writer = enc.write_header().map_err(pe)?;
    for f in frames {
        if (f.width, f.height) != (first.width, first.height) {
            return Err(anyhow!(
                "{}: animation frames differ in size",
                path.display()
            ));
        }
        writer.write_image_data(&f.data).map_err(pe)?;
    }
    writer.finish().map_err(pe)
}
