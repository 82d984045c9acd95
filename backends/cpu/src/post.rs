//! Post-processing of a finished frame: FXAA 3.11 (`subcone_kernels::fxaa`),
//! the post-process baseline.

use std::time::Instant;

use glam::Vec4;
use rayon::prelude::*;
use subcone_kernels::fxaa::{edge_clamped, fxaa_decode, fxaa_encode, fxaa_pixel, FxaaParams};
use subcone_scene::{Frame, PassTiming};

/// Run FXAA over `frame.color` in place, as an engine runs it on the image it
/// displays: each pixel is clamped and sRGB-encoded with its luma
/// ([`fxaa_encode`]), filtered ([`fxaa_pixel`]) and decoded back to linear
/// RGB, so the frame's 8-bit sRGB view is FXAA's output. Colours above 1 are
/// clamped, as the display clamps them; NaN reads as 0.
///
/// Timed as the pass `"post-process"`; its encoded input buffer is recorded
/// as `"post-process input"`.
pub fn fxaa(frame: &mut Frame, params: &FxaaParams) {
    let (w, h) = (frame.width as usize, frame.height as usize);
    if w == 0 || h == 0 {
        return;
    }
    let start = Instant::now();
    let encoded: Vec<Vec4> = frame.color.par_iter().map(|&c| fxaa_encode(c)).collect();
    let fetch = edge_clamped(&encoded, frame.width, frame.height);
    frame
        .color
        .par_chunks_mut(w)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, out) in row.iter_mut().enumerate() {
                *out = fxaa_decode(fxaa_pixel(&fetch, x as i32, y as i32, params));
            }
        });
    frame
        .stats
        .timings
        .push(PassTiming::cpu("post-process", start.elapsed()));
    frame.stats.buffers.push((
        "post-process input",
        std::mem::size_of_val(encoded.as_slice()),
    ));
}
