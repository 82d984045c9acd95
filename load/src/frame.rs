//! Frames written to files: PNG (8-bit sRGB) and EXR (linear f32).

use std::path::{Path, PathBuf};

use subcone_scene::{Frame, RenderError};

/// Writing a [`Frame`] to a file, for the contract crate's `Frame`, which
/// knows no image format.
pub trait SaveFrame {
    /// Write the frame to `path`: `.png` (8-bit sRGB) or `.exr` (linear f32).
    ///
    /// The file is written to a temporary file beside it and renamed into place,
    /// so a failure never leaves a half-written output. Errors name the path and
    /// the cause (e.g. a directory that does not exist).
    fn save(&self, path: &Path) -> Result<(), RenderError>;
}

impl SaveFrame for Frame {
    fn save(&self, path: &Path) -> Result<(), RenderError> {
        let err = |reason: String| RenderError::Output {
            path: path.to_path_buf(),
            reason,
        };
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        let format = match ext.as_str() {
            "png" => image::ImageFormat::Png,
            "exr" => image::ImageFormat::OpenExr,
            _ => return Err(err("unknown image format (expected .png or .exr)".into())),
        };
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !dir.is_dir() {
            return Err(err(format!("directory {} does not exist", dir.display())));
        }
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("frame");
        let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
        let written = match format {
            image::ImageFormat::Png => {
                let img = image::RgbImage::from_raw(self.width, self.height, self.to_srgb8())
                    .ok_or_else(|| err("frame size does not match its pixels".into()))?;
                img.save_with_format(&tmp, format)
            }
            _ => {
                let data: Vec<f32> = self.color.iter().flat_map(|c| [c.x, c.y, c.z]).collect();
                let img = image::Rgb32FImage::from_raw(self.width, self.height, data)
                    .ok_or_else(|| err("frame size does not match its pixels".into()))?;
                image::DynamicImage::ImageRgb32F(img).save_with_format(&tmp, format)
            }
        };
        if let Err(e) = written {
            let _ = std::fs::remove_file(&tmp);
            return Err(err(e.to_string()));
        }
        std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            err(e.to_string())
        })
    }
}
