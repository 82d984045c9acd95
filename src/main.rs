//! The `subcone` command line: `subcone render`.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use subcone::cli;

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
    /// Render one scene with one method.
    Render {
        /// A built-in scene name, or a path to an .obj, .gltf or .glb file.
        #[arg(long, default_value = "cornell")]
        scene: String,
        /// noaa, ssaaN (N = 4, 9, 16, 64, 256), sraa, sraa-rt, ctss, ctss-r, ssaaN+ctss.
        #[arg(long, default_value = "sraa-rt")]
        method: String,
        /// cpu.
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
        /// List the passes run, their times, the rays cast and the buffers allocated.
        #[arg(long)]
        verbose: bool,
    },
}

fn run() -> Result<()> {
    match Cli::parse().command {
        Command::Render {
            scene,
            method,
            backend,
            size,
            output,
            reflection_depth,
            verbose,
        } => {
            let (width, height) = cli::parse_size(&size)?;
            let method = method.parse().with_context(|| "--method")?;
            if backend != "cpu" {
                bail!("unknown backend {backend:?}: expected cpu");
            }
            let report = cli::render(&scene, method, width, height, reflection_depth, &output)?;
            println!("{}", report.summary());
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
