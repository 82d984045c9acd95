//! The `subcone` command line: `subcone render` and `subcone report`.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use subcone::cli::{self, Aov, RenderOptions};
use subcone_scene::RenderSettings;

#[derive(Parser)]
#[command(
    name = "subcone",
    version,
    about = "Geometry-aware antialiasing for ray tracing and sphere tracing"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The main job: every method on every scene, image error against run time,
    /// as tables (report.md, results.csv, results.json), plots and images.
    Report(subcone_report::ReportArgs),
    /// Write a built-in SDF scene as an SDF scene file (`.sdf.ron`), which
    /// `--scene PATH` reads back as the same scene.
    Scene {
        /// The built-in SDF scene to write (the names: --help).
        #[arg(long, value_name = "NAME", long_help = scene_export_help())]
        export: String,
        /// The file to write (a name ending in .sdf.ron); standard output when
        /// omitted.
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
    },
    /// Write golden vectors for ports of the kernels: for every pure kernel,
    /// a few thousand input/output cases as JSON, one file per kernel (the
    /// format is documented in the `subcone::vectors` module).
    Vectors {
        /// The directory to write the files into (created if missing).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Write every GPU pass as SPIR-V, HLSL, GLSL and MSL with its resource
    /// table (the files of `shaders/`), cross-compiled from the passes' WGSL.
    Shaders {
        /// The directory to write into (created if missing).
        #[arg(long, value_name = "DIR", default_value = "shaders")]
        out: PathBuf,
        /// Compare with DIR instead of writing: exit with an error naming
        /// each stale, missing or extra file.
        #[arg(long)]
        check: bool,
        /// Also compile `CtssPass` over this WGSL field (it defines
        /// `subcone_field` and `subcone_shade`, as `CtssPass::new` takes),
        /// as the variants `ctss/host-buffers` and `ctss/host-texture`.
        #[arg(long, value_name = "FILE.wgsl")]
        ctss_field: Option<PathBuf>,
    },
    /// Render one scene with one method.
    Render {
        /// A built-in scene name, `sponza`/`sponza-mirror`, or a path to an .obj, .gltf, .glb or .sdf.ron (SDF scene) file (the names: --help).
        #[arg(long, default_value = "cornell", long_help = scene_help())]
        scene: String,
        /// The antialiasing method (the names: --help).
        #[arg(long, default_value = subcone_scene::registry::DEFAULT_METHOD, long_help = subcone_scene::registry::method_help())]
        method: String,
        /// cpu or wgpu.
        #[arg(long, default_value = "cpu")]
        backend: String,
        /// Image size, WxH.
        #[arg(long, default_value = "512x512")]
        size: String,
        /// Output image (.png, 8-bit sRGB; or .exr, linear).
        #[arg(short = 'o', long = "output", default_value = "out.png")]
        output: PathBuf,
        /// Mirror bounces.
        #[arg(long, default_value_t = 1)]
        reflection_depth: u32,
        /// CTSS cone coverage in pixels (§5.1); default: the method's (0.6 for
        /// the CTSS default, 1 for the -paper variants).
        #[arg(long)]
        cone_coverage: Option<f32>,
        /// CTSS visibility threshold k, 1..=32 (§5.1); default: 32.
        #[arg(long)]
        visibility_k: Option<u32>,
        /// Temporal methods (taa, +taa): frames of a still camera to
        /// accumulate; the last is written.
        #[arg(long, default_value_t = subcone_kernels::taa::PHASES_FINE)]
        frames: u32,
        /// SDF scenes: step budget per ray (default: the scene's).
        #[arg(long)]
        max_steps: Option<u32>,
        /// SDF scenes: maximum ray distance (default: the scene's).
        #[arg(long)]
        max_distance: Option<f32>,
        /// Ambient-occlusion rays per shaded point (triangle scenes; 0: off,
        /// at most 256): the ambient term times the unoccluded fraction.
        #[arg(long = "ao", value_name = "N", default_value_t = 0, value_parser = cli::parse_ao)]
        ao: u32,
        /// Also write an AOV image beside the output: samples, depth or normal.
        #[arg(long)]
        aov: Option<Aov>,
        /// Print per-frame statistics (SDF evaluations, samples, multi-sample pixels).
        #[arg(long)]
        stats: bool,
        /// List the passes run, their times, the rays cast and the buffers allocated
        /// (and, on the cpu backend, its instruction-set path).
        #[arg(long)]
        verbose: bool,
        /// The cpu backend's instruction-set path: baseline, avx2 or avx512
        /// (default: the widest the CPU supports; an unsupported one falls
        /// back to the widest supported below it). Every path renders the
        /// same image bit for bit.
        #[arg(long, value_parser = cli::parse_isa)]
        isa: Option<subcone_cpu::isa::Isa>,
    },
}

fn run() -> Result<()> {
    match Cli::parse().command {
        Command::Report(args) => {
            let summary = subcone_report::run(&args)?;
            println!(
                "report written to {} (interactive: {})",
                summary.report_md.display(),
                summary.report_html.display()
            );
            if !summary.failures.is_empty() {
                eprintln!(
                    "{} renders failed (--keep-going): listed under Failures in {}",
                    summary.failures.len(),
                    summary.report_md.display()
                );
            }
            Ok(())
        }
        Command::Scene { export, output } => {
            let text = cli::export_sdf_scene(&export)?;
            match output {
                Some(path) => {
                    std::fs::write(&path, text)
                        .with_context(|| format!("cannot write {}", path.display()))?;
                    println!("wrote {export} to {}", path.display());
                }
                None => print!("{text}"),
            }
            Ok(())
        }
        Command::Vectors { out } => {
            let written = subcone::vectors::write_all(&out)
                .with_context(|| format!("cannot write vectors to {}", out.display()))?;
            println!(
                "wrote {} kernel vector files to {}",
                written.len(),
                out.display()
            );
            Ok(())
        }
        Command::Shaders {
            out,
            check,
            ctss_field,
        } => shaders(&out, check, ctss_field.as_deref()),
        Command::Render {
            scene,
            method,
            backend,
            size,
            output,
            reflection_depth,
            cone_coverage,
            visibility_k,
            frames,
            max_steps,
            max_distance,
            ao,
            aov,
            stats,
            verbose,
            isa,
        } => {
            let (width, height) = cli::parse_size(&size)?;
            let mut method: subcone_scene::Method = method.parse().with_context(|| "--method")?;
            if let Some(c) = cone_coverage {
                method = method.with_cone_coverage(c).context("--cone-coverage")?;
            }
            if let Some(k) = visibility_k {
                method = method.with_visibility_k(k).context("--visibility-k")?;
            }
            let opts = RenderOptions {
                scene,
                method,
                backend,
                settings: RenderSettings {
                    reflection_depth,
                    max_steps,
                    max_distance,
                    ao_rays: ao,
                    ..RenderSettings::new(width, height)
                },
                aov,
                output,
                isa,
                frames,
            };
            let report = cli::render(&opts)?;
            println!("{}", report.summary());
            if stats {
                println!("{}", report.stats());
            }
            if verbose {
                println!("{}", report.details());
            }
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// `render --scene`'s long help: the built-in scenes from the registry.
fn scene_help() -> String {
    subcone_scene::builtin::scene_help(
        "The scene: a built-in scene, a data scene or a file.",
        false,
        "sponza, sponza-mirror: Sponza from the data directory ($SUBCONE_DATA_DIR), the second with a mirror floor.\n\
         Or a path to an .obj, .gltf, .glb or .sdf.ron (SDF scene) file.",
    )
}

/// `scene --export`'s long help: the built-in SDF scenes.
fn scene_export_help() -> String {
    subcone_scene::builtin::scene_help("The built-in SDF scene to write.", true, "")
}

/// `subcone shaders`.
fn shaders(out: &std::path::Path, check: bool, ctss_field: Option<&std::path::Path>) -> Result<()> {
    use subcone_passes::standalone;
    let mut list = standalone::catalog().context("the passes' catalog")?;
    if let Some(path) = ctss_field {
        let field = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read the CTSS field {}", path.display()))?;
        for (variant, desc) in [
            (
                "host-buffers",
                subcone_passes::CtssPassDesc::default()
                    .with_output(subcone_passes::CtssOutput::Buffers { counts: false }),
            ),
            ("host-texture", subcone_passes::CtssPassDesc::default()),
        ] {
            let mut s = standalone::ctss(&field, &desc)?;
            s.variant = variant.to_owned();
            s.summary = format!("CtssPass over {}", path.display());
            list.push(s);
        }
    }
    let files = subcone::shaders::generate(&list)?;
    if check {
        let stale = subcone::shaders::stale(out, &files);
        if !stale.is_empty() {
            anyhow::bail!(
                "{} is not what `subcone shaders` writes ({} problems; regenerate with \
                 `cargo run --release -- shaders --out {}`):\n  {}",
                out.display(),
                stale.len(),
                out.display(),
                stale.join("\n  ")
            );
        }
        println!("{}: {} files, all up to date", out.display(), files.len());
    } else {
        subcone::shaders::write(out, &files)
            .with_context(|| format!("cannot write shaders to {}", out.display()))?;
        println!("wrote {} files to {}", files.len(), out.display());
    }
    Ok(())
}
