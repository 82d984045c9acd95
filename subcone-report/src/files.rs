//! Image files of the report: PNGs written atomically.

use std::path::Path;

use anyhow::{anyhow, Result};
use image::ImageEncoder;
use subcone_metrics::Rgb8;

use crate::reference::write_atomic;

/// Save an 8-bit RGB image as PNG (atomically), creating its directory.
pub fn save_png(path: &Path, img: &Rgb8) -> Result<()> {
    if img.data.len() != img.pixels() * 3 {
        return Err(anyhow!(
            "image for {} does not match its size",
            path.display()
        ));
    }
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| anyhow!("cannot create {}: {e}", d.display()))?;
    }
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(
            &img.data,
            img.width,
            img.height,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| anyhow!("cannot encode {}: {e}", path.display()))?;
    write_atomic(path, &bytes)
}

/// A mask as a black-and-white image.
pub fn mask_image(width: u32, height: u32, mask: &[bool]) -> Rgb8 {
    Rgb8 {
        width,
        height,
        data: mask
            .iter()
            .flat_map(|&m| if m { [255u8; 3] } else { [0u8; 3] })
            .collect(),
    }
}
