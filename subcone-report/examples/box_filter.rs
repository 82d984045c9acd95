//! A 3×3 box filter as an outside post-process for `subcone report`.
//!
//! ```text
//! cargo build --release -p subcone-report --example box_filter
//! cargo run --release -- report --quick \
//!     --post-process 'box=target/release/examples/box_filter {color} {output}'
//! ```
//!
//! It reads the NoAA frame (an 8-bit sRGB PNG), replaces every pixel by the
//! mean of its 3×3 neighbourhood (clamped at the borders, on the encoded
//! values, rounded to nearest) and writes the result as a PNG of the same
//! size. It is the smallest filter that blurs every edge: the report judges
//! it by the same rules as FXAA and SMAA, so it should beat NoAA on some
//! edges and lose on flat texture. Errors go to standard error with exit
//! code 1, which the report shows under *Failures* with `--keep-going`.

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, output] = args.as_slice() else {
        eprintln!("usage: box_filter INPUT.png OUTPUT.png");
        return ExitCode::FAILURE;
    };
    match run(input, output) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("box_filter: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(input: &str, output: &str) -> Result<(), String> {
    let img = image::open(input)
        .map_err(|e| format!("cannot read {input}: {e}"))?
        .to_rgb8();
    box3(&img)
        .save(output)
        .map_err(|e| format!("cannot write {output}: {e}"))
}

/// The 3×3 mean of every pixel, the border clamped.
fn box3(img: &image::RgbImage) -> image::RgbImage {
    let (w, h) = img.dimensions();
    image::RgbImage::from_fn(w, h, |x, y| {
        let mut sum = [0u32; 3];
        for dy in -1i64..=1 {
            for dx in -1i64..=1 {
                let sx = (x as i64 + dx).clamp(0, w as i64 - 1) as u32;
                let sy = (y as i64 + dy).clamp(0, h as i64 - 1) as u32;
                let p = img.get_pixel(sx, sy).0;
                for c in 0..3 {
                    sum[c] += p[c] as u32;
                }
            }
        }
        image::Rgb(sum.map(|s| ((s + 4) / 9) as u8))
    })
}
