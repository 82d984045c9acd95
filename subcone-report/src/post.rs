//! Post-process steps: antialiasing the report judges as data, NoAA's frame
//! followed by an image filter.
//!
//! A post-process row is NoAA plus one step: the step gets the NoAA frame a
//! backend rendered (as displayed, and with its AOVs), returns an image of
//! the same size, and is judged by the same edge-class rules as every method
//! ([`POST_PROCESS_CLAIMS`](subcone_scene::registry::POST_PROCESS_CLAIMS):
//! a filter over the finished image can act on any luminance edge). Its time
//! is NoAA's plus the step's.
//!
//! Two kinds ship: SMAA 1x on the GPU ([`SmaaPost`](crate::smaa::SmaaPost),
//! the `smaa` row) and any outside program ([`CommandPost`], `report
//! --post-process NAME=COMMAND`). FXAA is not one: it is a backend technique,
//! timed inside the frame. A library caller can implement [`PostProcess`]
//! for its own filter.
//!
//! # The command contract
//!
//! For each scene, backend and size, the report writes the NoAA frame and
//! its AOVs to a fresh temporary directory, runs the command once as a
//! warm-up and then once per timed run, and reads the output back after
//! each run. The files, each named by a placeholder (substituted inside any
//! word of COMMAND) and by an environment variable:
//!
//! | placeholder | variable | file |
//! |---|---|---|
//! | `{color}` | `SUBCONE_POST_COLOR` | the frame as displayed: 8-bit sRGB PNG |
//! | `{linear}` | `SUBCONE_POST_LINEAR` | linear RGB radiance, PFM (3 channels) |
//! | `{depth}` | `SUBCONE_POST_DEPTH` | view depth, PFM (1 channel, +∞ on misses) |
//! | `{normal}` | `SUBCONE_POST_NORMAL` | world-space shading normal, PFM (3 channels, 0 on misses) |
//! | `{albedo}` | `SUBCONE_POST_ALBEDO` | diffuse albedo, linear, PFM (3 channels, 0 on misses) |
//! | `{output}` | `SUBCONE_POST_OUTPUT` | where the command writes its result: an 8-bit RGB or RGBA PNG of the same size, sRGB-encoded like `{color}` |
//! | `{width}`, `{height}` | `SUBCONE_POST_WIDTH`, `SUBCONE_POST_HEIGHT` | the frame size (no file) |
//! | `{scene}` | `SUBCONE_POST_SCENE` | the scene's name (no file) |
//!
//! PFM is the portable float map (`PF`/`Pf`, little-endian, rows from the
//! bottom up, as the format defines), the format Intel Open Image Denoise's
//! example tool reads. COMMAND is split into words like a POSIX shell would
//! (quotes, backslashes) but run without one, so a placeholder's path needs
//! no quoting; for pipes, run `sh -c '…'` and read the variables.
//!
//! The time of a run is the command's wall time, from spawning the process
//! to its exit: it includes the process start and the command's own reading
//! and writing of files, not the report's. A missing program, a non-zero
//! exit (with the last lines of its standard error), a missing output, an
//! output that is not an 8-bit RGB(A) PNG or not of the frame's size, and a
//! run longer than the timeout ([`DEFAULT_TIMEOUT`] unless `--post-timeout`
//! says otherwise; the process is killed) are errors naming the step; the
//! report adds the scene and backend, and with `--keep-going` lists them
//! under *Failures*.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use glam::Vec3;
use subcone_scene::{Frame, PassTiming};

use subcone_metrics::Rgb8;

/// What a post-process step gets: NoAA's frame on one scene and backend.
#[derive(Clone, Copy, Debug)]
pub struct PostInput<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// The frame as displayed ([`Rgb8::from_frame`] of `frame`).
    pub image: &'a Rgb8,
    /// The frame, with its AOVs when it was rendered with them.
    pub frame: &'a Frame,
}

/// An image filter the report runs on NoAA's frame and judges like a method.
pub trait PostProcess: Send + Sync {
    /// The row's name: file-safe, and not a method name.
    fn name(&self) -> &str;
    /// What ran and where, for the row's `post_process` column and the line
    /// under the scene's table; it ends by saying what its time covers.
    fn describe(&self) -> String;
    /// Whether it reads the AOVs (depth, normal, albedo): the report then
    /// hands it frames rendered with them.
    fn needs_aovs(&self) -> bool {
        false
    }
    /// The filtered image, of the input's size, and the time the step took
    /// with how it was measured (a pass named `post-process`).
    fn apply(&self, input: &PostInput<'_>) -> Result<(Rgb8, PassTiming)>;
}

/// The name of a post-process step's pass in its [`PassTiming`].
pub const POST_PASS: &str = "post-process";

/// How long one run of a command may take before it is killed, unless
/// `--post-timeout` says otherwise.
pub const DEFAULT_TIMEOUT: Duration = Duration::from_secs(60);

/// The placeholders of COMMAND, in the order of the table in the module doc.
pub const PLACEHOLDERS: [&str; 9] = [
    "color", "linear", "depth", "normal", "albedo", "output", "width", "height", "scene",
];

/// An outside program as a post-process step (`--post-process NAME=COMMAND`).
#[derive(Clone, Debug, PartialEq)]
pub struct CommandPost {
    name: String,
    command: String,
    words: Vec<String>,
    timeout: Duration,
}

impl CommandPost {
    /// Parse `NAME=COMMAND`. Fails on a missing `=`, a name that is empty,
    /// not file-safe (ASCII letters, digits, `-`, `_`, `+`, `.`), or a
    /// method name or `smaa`, on a command with no word or unbalanced
    /// quotes, and on an unknown placeholder. The program itself is looked
    /// for when it runs.
    pub fn parse(spec: &str, timeout: Duration) -> Result<CommandPost> {
        let (name, command) = spec.split_once('=').ok_or_else(|| {
            anyhow!("--post-process {spec:?}: expected NAME=COMMAND, e.g. box='box_filter {{color}} {{output}}'")
        })?;
        let name = name.trim();
        let command = command.trim();
        let safe = |c: char| c.is_ascii_alphanumeric() || "-_+.".contains(c);
        if name.is_empty() || !name.chars().all(safe) || name.starts_with('.') {
            bail!(
                "--post-process {spec:?}: the name {name:?} must be non-empty ASCII letters, \
                 digits, '-', '_', '+' or '.' (it names the row and its image files)"
            );
        }
        if name == crate::SMAA || name.parse::<subcone_scene::Method>().is_ok() {
            bail!("--post-process {spec:?}: {name:?} is already a method's name; choose another");
        }
        let words = shlex::split(command)
            .ok_or_else(|| anyhow!("--post-process {name}: unbalanced quotes in {command:?}"))?;
        if words.is_empty() {
            bail!("--post-process {name}: the command is empty");
        }
        for w in &words {
            check_placeholders(w).with_context(|| format!("--post-process {name}"))?;
        }
        if timeout.is_zero() {
            bail!("--post-process {name}: the timeout must be positive");
        }
        Ok(CommandPost {
            name: name.to_string(),
            command: command.to_string(),
            words,
            timeout,
        })
    }

    /// The command as given.
    pub fn command(&self) -> &str {
        &self.command
    }

    /// How long one run may take.
    pub fn timeout(&self) -> Duration {
        self.timeout
    }

    fn uses(&self, placeholder: &str) -> bool {
        let p = format!("{{{placeholder}}}");
        self.words.iter().any(|w| w.contains(&p))
    }

    /// Run the command once on files already written to `files`.
    fn run(&self, files: &InputFiles) -> Result<(Rgb8, Duration)> {
        let _ = std::fs::remove_file(&files.output);
        let words: Vec<String> = self.words.iter().map(|w| files.substitute(w)).collect();
        let stdout = std::fs::File::create(files.dir.join("stdout.txt"))?;
        let stderr_path = files.dir.join("stderr.txt");
        let stderr = std::fs::File::create(&stderr_path)?;
        let start = Instant::now();
        let mut child = Command::new(&words[0])
            .args(&words[1..])
            .envs(files.variables())
            .stdin(Stdio::null())
            .stdout(stdout)
            .stderr(stderr)
            .spawn()
            .map_err(|e| anyhow!("cannot run {:?}: {e}", words[0]))?;
        let status = loop {
            if let Some(status) = child.try_wait()? {
                break status;
            }
            if start.elapsed() > self.timeout {
                let _ = child.kill();
                let _ = child.wait();
                bail!(
                    "{:?} ran past the timeout of {} s and was killed (--post-timeout sets it)",
                    self.command,
                    self.timeout.as_secs_f64()
                );
            }
            std::thread::sleep(poll_interval(start.elapsed()));
        };
        let wall = start.elapsed();
        if !status.success() {
            let tail = tail_of(&stderr_path, 10);
            bail!(
                "{:?} failed ({status}){}",
                self.command,
                if tail.is_empty() {
                    String::new()
                } else {
                    format!("; its standard error ends with:\n{tail}")
                }
            );
        }
        let out = read_output(&files.output, files.width, files.height)
            .with_context(|| format!("{:?} exited 0, but its output", self.command))?;
        Ok((out, wall))
    }
}

impl PostProcess for CommandPost {
    fn name(&self) -> &str {
        &self.name
    }

    fn describe(&self) -> String {
        format!(
            "the command `{}`; its time is NoAA's plus the command's wall time (process start \
             to exit)",
            self.command
        )
    }

    fn needs_aovs(&self) -> bool {
        // Through the variables, a command can read any file.
        true
    }

    fn apply(&self, input: &PostInput<'_>) -> Result<(Rgb8, PassTiming)> {
        let files = InputFiles::write(self, input)?;
        let result = self.run(&files);
        let _ = std::fs::remove_dir_all(&files.dir);
        // An outside program: the wall clock from process start to exit.
        result.map(|(image, wall)| (image, PassTiming::cpu(POST_PASS, wall)))
    }
}

/// Poll often at first (a filter of a small image ends in milliseconds),
/// then less: the poll's latency is part of the measured wall time.
fn poll_interval(elapsed: Duration) -> Duration {
    if elapsed < Duration::from_millis(50) {
        Duration::from_micros(200)
    } else {
        Duration::from_millis(5)
    }
}

/// Fails on a `{name}` in `word` that is not one of [`PLACEHOLDERS`].
fn check_placeholders(word: &str) -> Result<()> {
    let mut rest = word;
    while let Some(open) = rest.find('{') {
        let after = &rest[open + 1..];
        let Some(close) = after.find('}') else { break };
        let name = &after[..close];
        if !name.is_empty()
            && name.chars().all(|c| c.is_ascii_lowercase() || c == '_')
            && !PLACEHOLDERS.contains(&name)
        {
            bail!(
                "unknown placeholder {{{name}}} (known: {})",
                PLACEHOLDERS
                    .iter()
                    .map(|p| format!("{{{p}}}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        rest = &after[close + 1..];
    }
    Ok(())
}

/// The last `n` lines of a text file (empty when unreadable).
fn tail_of(path: &Path, n: usize) -> String {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

/// The NoAA frame's files of one run, in their own temporary directory.
struct InputFiles {
    dir: PathBuf,
    output: PathBuf,
    /// (placeholder, value): paths of the files written, the size, the scene.
    values: Vec<(&'static str, String)>,
    width: u32,
    height: u32,
}

impl InputFiles {
    /// Write what `post` reads of `input` (every file when it reads the
    /// variables only) to a new temporary directory. An AOV the frame lacks
    /// is an error when a placeholder names it, and is left out otherwise.
    fn write(post: &CommandPost, input: &PostInput<'_>) -> Result<InputFiles> {
        let dir = tempfile::Builder::new()
            .prefix("subcone-post-")
            .tempdir()
            .context("cannot create a temporary directory for the post-process files")?
            .keep();
        let f = input.frame;
        let (w, h) = (f.width, f.height);
        let mut values: Vec<(&'static str, String)> = Vec::new();
        let mut file = |key: &'static str, name: &str| {
            let p = dir.join(name);
            values.push((key, p.display().to_string()));
            p
        };
        crate::files::save_png(&file("color", "color.png"), input.image)?;
        write_pfm3(&file("linear", "linear.pfm"), w, h, &f.color)?;
        let aov = |name: &str, present: bool| -> Result<bool> {
            if !present && post.uses(name) {
                bail!("the NoAA frame has no {name} AOV for {{{name}}} on this backend");
            }
            Ok(present)
        };
        if aov("depth", f.depth.is_some())? {
            write_pfm1(
                &file("depth", "depth.pfm"),
                w,
                h,
                f.depth.as_deref().unwrap_or(&[]),
            )?;
        }
        if aov("normal", f.normal.is_some())? {
            let n = f.normal.as_deref().unwrap_or(&[]);
            write_pfm3(&file("normal", "normal.pfm"), w, h, n)?;
        }
        if aov("albedo", f.albedo.is_some())? {
            let a = f.albedo.as_deref().unwrap_or(&[]);
            write_pfm3(&file("albedo", "albedo.pfm"), w, h, a)?;
        }
        let output = file("output", "output.png");
        values.push(("width", w.to_string()));
        values.push(("height", h.to_string()));
        values.push(("scene", input.scene.to_string()));
        Ok(InputFiles {
            dir,
            output,
            values,
            width: w,
            height: h,
        })
    }

    fn substitute(&self, word: &str) -> String {
        let mut out = word.to_string();
        for (k, v) in &self.values {
            out = out.replace(&format!("{{{k}}}"), v);
        }
        out
    }

    /// `SUBCONE_POST_<PLACEHOLDER>` for every value.
    fn variables(&self) -> Vec<(String, String)> {
        self.values
            .iter()
            .map(|(k, v)| {
                (
                    format!("SUBCONE_POST_{}", k.to_ascii_uppercase()),
                    v.clone(),
                )
            })
            .collect()
    }
}

/// A PFM of `channels` floats per pixel: header, then rows from the bottom
/// up, little-endian (the negative scale says so).
fn write_pfm(path: &Path, w: u32, h: u32, channels: usize, px: &[f32]) -> Result<()> {
    let n = w as usize * h as usize * channels;
    if px.len() != n {
        bail!(
            "{}: {} values for a {w}x{h} image of {channels} channels (expected {n})",
            path.display(),
            px.len()
        );
    }
    let mut bytes = Vec::with_capacity(n * 4 + 32);
    let mut header = String::new();
    let _ = write!(
        header,
        "{}\n{w} {h}\n-1.0\n",
        if channels == 3 { "PF" } else { "Pf" }
    );
    bytes.extend_from_slice(header.as_bytes());
    let row = w as usize * channels;
    for y in (0..h as usize).rev() {
        for v in &px[y * row..(y + 1) * row] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    std::fs::write(path, bytes).with_context(|| format!("cannot write {}", path.display()))
}

fn write_pfm1(path: &Path, w: u32, h: u32, px: &[f32]) -> Result<()> {
    write_pfm(path, w, h, 1, px)
}

fn write_pfm3(path: &Path, w: u32, h: u32, px: &[Vec3]) -> Result<()> {
    let flat: Vec<f32> = px.iter().flat_map(|v| v.to_array()).collect();
    write_pfm(path, w, h, 3, &flat)
}

/// Read a command's output: an 8-bit RGB or RGBA PNG of `w × h` (alpha
/// dropped).
fn read_output(path: &Path, w: u32, h: u32) -> Result<Rgb8> {
    if !path.exists() {
        bail!("{} was not written", path.display());
    }
    // By its signature, not its name: the output path always ends in .png.
    const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    if !bytes.starts_with(PNG_SIGNATURE) {
        let format = image::guess_format(&bytes)
            .map(|f| format!("{f:?}"))
            .unwrap_or_else(|_| "unknown format".into());
        bail!("{} is not a PNG ({format})", path.display());
    }
    let reader =
        image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png);
    let img = reader
        .decode()
        .with_context(|| format!("{} is not a valid PNG", path.display()))?;
    let data = match img {
        image::DynamicImage::ImageRgb8(i) => i,
        image::DynamicImage::ImageRgba8(i) => image::DynamicImage::ImageRgba8(i).to_rgb8(),
        other => bail!(
            "{} is a PNG of {:?}; expected 8-bit RGB or RGBA",
            path.display(),
            other.color()
        ),
    };
    if data.dimensions() != (w, h) {
        bail!(
            "{} is {}x{}; expected the frame's {w}x{h}",
            path.display(),
            data.width(),
            data.height()
        );
    }
    Ok(Rgb8 {
        width: w,
        height: h,
        data: data.into_raw(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Duration = DEFAULT_TIMEOUT;

    #[test]
    fn parses_a_name_and_a_command_with_quotes() {
        let p = CommandPost::parse("box = filter '{color}' \"a b\" {output}", T).unwrap();
        assert_eq!(p.name(), "box");
        assert_eq!(p.words, ["filter", "{color}", "a b", "{output}"]);
        assert!(p.uses("color") && p.uses("output") && !p.uses("depth"));
    }

    #[test]
    fn refuses_bad_specs_with_the_reason() {
        let err = |s: &str| format!("{:#}", CommandPost::parse(s, T).unwrap_err());
        assert!(err("box").contains("expected NAME=COMMAND"));
        assert!(err("=cmd").contains("must be non-empty"));
        assert!(err("a/b=cmd").contains("must be non-empty"));
        assert!(err("noaa=cmd").contains("already a method's name"));
        assert!(err("smaa=cmd").contains("already a method's name"));
        assert!(err("box=").contains("the command is empty"));
        assert!(err("box=f 'open").contains("unbalanced quotes"));
        let e = err("box=f {colour} {output}");
        assert!(e.contains("unknown placeholder {colour}"), "{e}");
        assert!(format!(
            "{:#}",
            CommandPost::parse("b=f", Duration::ZERO).unwrap_err()
        )
        .contains("timeout must be positive"));
    }

    #[test]
    fn a_pfm_is_written_bottom_row_first() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("d.pfm");
        write_pfm1(&p, 2, 2, &[1.0, 2.0, 3.0, f32::INFINITY]).unwrap();
        let b = std::fs::read(&p).unwrap();
        let head = b"Pf\n2 2\n-1.0\n";
        assert_eq!(&b[..head.len()], head);
        let vals: Vec<f32> = b[head.len()..]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(vals, [3.0, f32::INFINITY, 1.0, 2.0]);
        assert!(write_pfm1(&p, 3, 2, &[0.0; 4]).is_err());
    }

    #[test]
    fn the_output_must_be_an_8_bit_rgb_png_of_the_frame_size() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("o.png");
        assert!(format!("{:#}", read_output(&p, 2, 2).unwrap_err()).contains("was not written"));
        std::fs::write(&p, b"not an image").unwrap();
        assert!(format!("{:#}", read_output(&p, 2, 2).unwrap_err()).contains("not a PNG"));
        image::RgbaImage::from_pixel(2, 2, image::Rgba([1, 2, 3, 4]))
            .save(&p)
            .unwrap();
        assert_eq!(read_output(&p, 2, 2).unwrap().data, [1, 2, 3].repeat(4));
        let e = format!("{:#}", read_output(&p, 3, 2).unwrap_err());
        assert!(e.contains("is 2x2; expected the frame's 3x2"), "{e}");
        image::GrayImage::from_pixel(2, 2, image::Luma([9]))
            .save(&p)
            .unwrap();
        assert!(format!("{:#}", read_output(&p, 2, 2).unwrap_err()).contains("expected 8-bit RGB"));
    }
}
