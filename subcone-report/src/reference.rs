//! Reference images (SSAA256 by default), cached on disk.
//!
//! A reference is keyed by a SHA-256 of: the scene (its name, or for a file its
//! canonical path, modification time and length), the image size, the reference
//! method, the reflection depth, the backend that rendered it, and the code
//! version (`CARGO_PKG_VERSION` plus the git HEAD of the source tree when `git`
//! can tell it at run time, else `"unknown"`), and for a camera other than the
//! scene's (the error's sub-pixel camera offsets) that camera. It is
//! re-rendered only when one of those changes (or with
//! `--refresh-references`).
//!
//! The file is raw little-endian `f32` linear RGB after a small header
//! (`SUBCONE-REF1`, width, height as `u32`), written to a temporary file and
//! renamed into place; a file that does not parse is re-rendered, not trusted.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use std::time::UNIX_EPOCH;

use anyhow::{anyhow, bail, Context, Result};
use glam::Vec3;
use sha2::{Digest, Sha256};
use subcone_scene::Frame;

const MAGIC: &[u8; 12] = b"SUBCONE-REF1";

/// The code version that reference keys include: the package version and the
/// git HEAD (`"unknown"` without git or outside a repository).
pub fn code_version() -> String {
    static VERSION: OnceLock<String> = OnceLock::new();
    VERSION
        .get_or_init(|| format!("{}+{}", env!("CARGO_PKG_VERSION"), git_head()))
        .clone()
}

/// The git HEAD of the source tree this binary was built from, abbreviated, or
/// `"unknown"`.
pub fn git_head() -> String {
    let out = Command::new("git")
        .args(["-C", env!("CARGO_MANIFEST_DIR"), "rev-parse", "HEAD"])
        .output();
    match out {
        Ok(o) if o.status.success() => {
            let s = String::from_utf8_lossy(&o.stdout).trim().to_string();
            if s.len() >= 12 && s.bytes().all(|b| b.is_ascii_hexdigit()) {
                s[..12].to_string()
            } else {
                "unknown".into()
            }
        }
        _ => "unknown".into(),
    }
}

/// What identifies a scene argument on disk: the name for a built-in scene, or
/// the canonical path, modification time and length of a file.
pub fn scene_identity(arg: &str) -> String {
    let p = Path::new(arg);
    match fs::metadata(p) {
        Ok(m) if m.is_file() => {
            let path = fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
            let mtime = m
                .modified()
                .ok()
                .and_then(|t| t.duration_since(UNIX_EPOCH).ok())
                .map(|d| d.as_nanos())
                .unwrap_or(0);
            format!("file:{}:{}:{}", path.display(), mtime, m.len())
        }
        _ => format!("name:{arg}"),
    }
}

/// The inputs of a reference image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReferenceKey {
    /// [`scene_identity`] of the scene argument.
    pub scene: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Reference method, e.g. `ssaa256`.
    pub method: String,
    /// Mirror bounces.
    pub reflection_depth: u32,
    /// Ambient-occlusion rays per shaded point (0: off).
    pub ao_rays: u32,
    /// Backend that renders references.
    pub backend: String,
    /// [`code_version`].
    pub version: String,
    /// The camera, when it is not the scene's: a description of the
    /// offset camera (its position, view and up vectors and field of view).
    /// `None` keeps the key of the scene's own camera unchanged.
    pub camera: Option<String>,
}

impl ReferenceKey {
    /// The text hashed into the key (also written beside the cache file).
    pub fn describe(&self) -> String {
        let mut s = format!(
            "scene={}\nsize={}x{}\nmethod={}\nreflection_depth={}\nao_rays={}\nbackend={}\nversion={}\n",
            self.scene,
            self.width,
            self.height,
            self.method,
            self.reflection_depth,
            self.ao_rays,
            self.backend,
            self.version
        );
        if let Some(c) = &self.camera {
            s.push_str(&format!("camera={c}\n"));
        }
        s
    }

    /// Hex SHA-256 of [`ReferenceKey::describe`].
    pub fn hash(&self) -> String {
        let d = Sha256::digest(self.describe().as_bytes());
        d.iter().map(|b| format!("{b:02x}")).collect()
    }

    /// The cache file in `dir`.
    pub fn path(&self, dir: &Path) -> PathBuf {
        dir.join(format!("ref-{}.f32", &self.hash()[..32]))
    }
}

/// Read a cached reference; `Ok(None)` when it is absent, the wrong size or
/// does not parse (a stale or damaged file is re-rendered).
pub fn load(path: &Path, width: u32, height: u32) -> Result<Option<Frame>> {
    let bytes = match fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            return Err(anyhow!(
                "cannot read cached reference {}: {e}",
                path.display()
            ))
        }
    };
    Ok(decode(&bytes, width, height))
}

fn decode(bytes: &[u8], width: u32, height: u32) -> Option<Frame> {
    let n = width as usize * height as usize;
    let header = MAGIC.len() + 8;
    if bytes.len() != header + n * 12 || &bytes[..MAGIC.len()] != MAGIC {
        return None;
    }
    let u = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap_or([0; 4]));
    if u(MAGIC.len()) != width || u(MAGIC.len() + 4) != height {
        return None;
    }
    let f: Vec<f32> = bytes[header..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let mut frame = Frame::new(width, height);
    frame.color = f
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect();
    Some(frame)
}

/// Write a reference (atomically) with its key description beside it.
pub fn store(path: &Path, key: &ReferenceKey, frame: &Frame) -> Result<()> {
    let n = frame.width as usize * frame.height as usize;
    if frame.color.len() != n {
        bail!("reference frame does not match its size");
    }
    let dir = path
        .parent()
        .ok_or_else(|| anyhow!("cache path {} has no directory", path.display()))?;
    fs::create_dir_all(dir)
        .with_context(|| format!("cannot create cache directory {}", dir.display()))?;
    let mut bytes = Vec::with_capacity(MAGIC.len() + 8 + n * 12);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&frame.width.to_le_bytes());
    bytes.extend_from_slice(&frame.height.to_le_bytes());
    for c in &frame.color {
        for v in [c.x, c.y, c.z] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    write_atomic(path, &bytes)?;
    write_atomic(&path.with_extension("txt"), key.describe().as_bytes())
}

/// Write `bytes` to a temporary file beside `path` and rename it into place.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| anyhow!("{} is not a file path", path.display()))?;
    let tmp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let written = fs::File::create(&tmp).and_then(|mut f| {
        f.write_all(bytes)?;
        f.flush()
    });
    if let Err(e) = written {
        let _ = fs::remove_file(&tmp);
        bail!("cannot write {}: {e}", path.display());
    }
    fs::rename(&tmp, path).map_err(|e| {
        let _ = fs::remove_file(&tmp);
        anyhow!("cannot write {}: {e}", path.display())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key() -> ReferenceKey {
        ReferenceKey {
            scene: scene_identity("cornell"),
            width: 3,
            height: 2,
            method: "ssaa64".into(),
            reflection_depth: 1,
            ao_rays: 0,
            backend: "cpu".into(),
            version: "0.1.0+abc".into(),
            camera: None,
        }
    }

    #[test]
    fn key_changes_with_every_input() {
        let k = key();
        let mut others = vec![];
        for i in 0..9 {
            let mut o = k.clone();
            match i {
                0 => o.scene = "name:checker".into(),
                1 => o.width = 4,
                2 => o.height = 3,
                3 => o.method = "ssaa256".into(),
                4 => o.reflection_depth = 2,
                5 => o.ao_rays = 4,
                6 => o.camera = Some("offset 0.5,0.5".into()),
                7 => {
                    o.camera = Some("offset 0.25,0.75".into());
                    others.push(o.hash());
                    o.camera = Some("offset 0.75,0.25".into());
                }
                _ => o.version = "0.1.0+def".into(),
            }
            others.push(o.hash());
        }
        for h in &others {
            assert_ne!(h, &k.hash());
        }
        // Every offset camera has its own file.
        let mut sorted = others.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), others.len());
        // The scene's own camera keeps the key it had before cameras were
        // part of it.
        assert!(!k.describe().contains("camera="));
    }

    #[test]
    fn round_trip_and_damaged_files() {
        let dir = tempfile::tempdir().unwrap();
        let k = key();
        let path = k.path(dir.path());
        assert!(load(&path, 3, 2).unwrap().is_none());
        let mut f = Frame::new(3, 2);
        f.color[4] = Vec3::new(0.25, 2.0, -1.0);
        store(&path, &k, &f).unwrap();
        assert_eq!(load(&path, 3, 2).unwrap().unwrap().color, f.color);
        assert!(load(&path, 2, 3).unwrap().is_none());
        fs::write(&path, b"garbage").unwrap();
        assert!(load(&path, 3, 2).unwrap().is_none());
    }
}
