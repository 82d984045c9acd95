//! The papers' published numbers that the report compares against, each
//! with the table or figure it comes from.

use subcone_scene::Method;

use crate::named::{CTSS, CTSS_R, SSAA4};

/// SRAA for ray tracing, Table 1: Sponza, (side, pass 1 ms, pass 2 ms, total ms).
pub const SRAA_TABLE1: [(u32, f64, f64, f64); 4] = [
    (256, 18.0, 5.0, 23.0),
    (512, 35.0, 14.0, 49.0),
    (768, 69.0, 28.0, 97.0),
    (1024, 116.0, 49.0, 165.0),
];
/// SRAA for ray tracing, Fig. 3: speed-up over 16× SSAA with the GPU hybrid.
pub const SRAA_SPEEDUP_OVER_SSAA16: f64 = 6.0;
/// CTSS Table 1: average frame-time ratio to NoAA, (paper's name, our method, ratio).
pub const CTSS_TABLE1: [(&str, Method, f64); 3] = [
    ("4x SS", SSAA4, 4.16),
    ("CTSS", CTSS, 1.30),
    ("CTSS-R", CTSS_R, 1.16),
];
