//! A rendered frame: linear RGB plus optional AOVs and the statistics of the
//! passes that made it. Writing it to a file is `subcone-load`'s
//! (`subcone_load::save_frame`).

use std::time::Duration;

use glam::Vec3;
use subcone_kernels::passes::Passes;

/// Where the time of a pass comes from. A figure is only comparable with
/// figures of the same source: GPU timestamps measure the GPU's work alone,
/// a wall clock also counts submission, driver and waiting.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TimingSource {
    /// The CPU backend: the wall clock around the pass, on this CPU.
    Cpu,
    /// GPU timestamp queries written before and after the pass, converted
    /// with the queue's timestamp period.
    GpuTimestamps,
    /// A GPU pass timed by the CPU's wall clock from submission to
    /// completion, because its timestamps are not used; `why` says why
    /// (e.g. a software adapter, whose timestamps are not trusted).
    GpuWallClock {
        /// Why the GPU's timestamps were not used.
        why: &'static str,
    },
}

impl TimingSource {
    /// A short tag for tables and CSV: `cpu`, `gpu-timestamps` or
    /// `gpu-wall-clock`.
    pub fn tag(&self) -> &'static str {
        match self {
            TimingSource::Cpu => "cpu",
            TimingSource::GpuTimestamps => "gpu-timestamps",
            TimingSource::GpuWallClock { .. } => "gpu-wall-clock",
        }
    }
}

impl std::fmt::Display for TimingSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TimingSource::Cpu => f.write_str("CPU wall clock"),
            TimingSource::GpuTimestamps => f.write_str("GPU timestamps"),
            TimingSource::GpuWallClock { why } => {
                write!(f, "wall clock from submission to completion ({why})")
            }
        }
    }
}

/// The time of one pass and where it comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// Pass name, e.g. `"geometry"` (SRAA-RT's pass 1) or `"antialiasing"` (pass 2).
    pub name: &'static str,
    /// The pass's time.
    pub time: Duration,
    /// How `time` was measured.
    pub source: TimingSource,
}

impl PassTiming {
    /// A pass of the CPU backend, timed by the wall clock.
    pub fn cpu(name: &'static str, time: Duration) -> Self {
        PassTiming {
            name,
            time,
            source: TimingSource::Cpu,
        }
    }
}

/// Rays cast, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Primary rays that are shaded.
    pub primary: u64,
    /// Geometry-only rays (SRAA subsamples, primary and secondary).
    pub geometry: u64,
    /// Shadow rays.
    pub shadow: u64,
    /// Reflection rays that are shaded.
    pub secondary: u64,
    /// Ambient-occlusion rays (any-hit, `RenderSettings::ao_rays` per
    /// shaded primary hit).
    pub ao: u64,
}

impl RayCounts {
    /// All rays.
    pub fn total(&self) -> u64 {
        self.primary + self.geometry + self.shadow + self.secondary + self.ao
    }
}

/// What it took to render a frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameStats {
    /// The passes run (from `subcone_kernels::passes::required_passes`).
    pub passes: Passes,
    /// Time per pass, in the order run, each with its source.
    pub timings: Vec<PassTiming>,
    /// Bytes of each buffer allocated for the frame, by name.
    pub buffers: Vec<(&'static str, usize)>,
    /// Rays cast.
    pub rays: RayCounts,
    /// Shaded samples (shading evaluations at primary hits or CTSS groups).
    pub shaded_samples: u64,
    /// SDF evaluations of primary tracing (sphere or cone tracing), for SDF scenes.
    pub sdf_evaluations: u64,
    /// Pixels that took more than one shaded sample (the CTSS paper's Fig. 9).
    pub multi_sample_pixels: u64,
    /// Primary samples (pixel centres, supersamples, SRAA's shaded samples
    /// and subsamples) whose visible triangle the rasteriser found
    /// (`-hybrid` methods); a sample where the tracer's test on that
    /// triangle missed is traced as well, and counted in [`Self::rays`].
    pub raster_samples: u64,
}

impl FrameStats {
    /// Total bytes of frame buffers.
    pub fn buffer_bytes(&self) -> usize {
        self.buffers.iter().map(|b| b.1).sum()
    }

    /// Total time of all passes.
    pub fn total_time(&self) -> Duration {
        self.timings.iter().map(|t| t.time).sum()
    }

    /// The distinct sources of the pass times, in the order first seen (a
    /// frame whose passes mix sources says so).
    pub fn timing_sources(&self) -> Vec<TimingSource> {
        let mut out: Vec<TimingSource> = Vec::new();
        for t in &self.timings {
            if !out.contains(&t.source) {
                out.push(t.source);
            }
        }
        out
    }
}

/// A rendered image, linear RGB, row-major from the top-left pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB per pixel.
    pub color: Vec<Vec3>,
    /// View depth per pixel (∞ for misses), when the backend records it.
    pub depth: Option<Vec<f32>>,
    /// Shading normal per pixel, when the backend records it.
    pub normal: Option<Vec<Vec3>>,
    /// Shaded samples per pixel, when the backend records it.
    pub samples_per_pixel: Option<Vec<f32>>,
    /// Diffuse albedo at the surface through the pixel centre (the texture
    /// or pattern at the hit; black for a miss), when the backend records it.
    pub albedo: Option<Vec<Vec3>>,
    /// Per-light visibility at the surface through the pixel centre, when
    /// the backend records it: bit `l` set when nothing blocks the segment to
    /// light `l`. A light the surface faces away from counts as visible: the
    /// cosine falls smoothly to 0 there, which is shading, not a shadow edge.
    /// 0 for a miss.
    pub light_visibility: Option<Vec<u32>>,
    /// Mirror reflectance of the material through the pixel centre (0 for a
    /// miss or a surface that is no mirror), when the backend records it.
    pub mirror: Option<Vec<f32>>,
    /// Statistics.
    pub stats: FrameStats,
}

/// Linear to sRGB transfer, for one channel in `[0, 1]`.
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

impl Frame {
    /// A black frame.
    pub fn new(width: u32, height: u32) -> Self {
        Frame {
            width,
            height,
            color: vec![Vec3::ZERO; (width as usize) * (height as usize)],
            depth: None,
            normal: None,
            samples_per_pixel: None,
            albedo: None,
            light_visibility: None,
            mirror: None,
            stats: FrameStats::default(),
        }
    }

    /// Colour of pixel `(x, y)`.
    pub fn pixel(&self, x: u32, y: u32) -> Vec3 {
        self.color[(y * self.width + x) as usize]
    }

    /// The colours' bits, channel by channel, pixel by pixel: what two
    /// frames must share to be the same image bit for bit.
    pub fn color_bits(&self) -> Vec<u32> {
        self.color
            .iter()
            .flat_map(|c| c.to_array())
            .map(f32::to_bits)
            .collect()
    }

    /// The image a user would look at: clamped to `[0, 1]`, sRGB-encoded, 8-bit RGB.
    pub fn to_srgb8(&self) -> Vec<u8> {
        let q = |c: f32| (linear_to_srgb(c) * 255.0 + 0.5) as u8;
        self.color
            .iter()
            .flat_map(|c| [q(c.x), q(c.y), q(c.z)])
            .collect()
    }
}
