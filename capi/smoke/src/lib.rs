//! Test-only: the C smoke test (`c/smoke.c`) and the README's C example
//! (`c/readme_example.c`), compiled against `include/subcone.h` and linked to
//! `subcone-capi`. The tests in `tests/` drive them; see there.

use std::os::raw::{c_char, c_int};

// Keep the C ABI's symbols in every binary that links this crate.
pub use subcone_capi;
use subcone_capi::{SubconeCtssResult, SubconeVec3};

/// What `subcone_smoke_run` computed through the C ABI, for the Rust side to
/// compare with the kernels. Mirrors `SmokeOutputs` in `c/smoke.c`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct SmokeOutputs {
    /// `subcone_version()`.
    pub version: u32,
    /// eq. 1.
    pub bilateral: f32,
    /// eq. 2, shadow states equal.
    pub shadow_same: f32,
    /// eq. 2, shadow states differ.
    pub shadow_differ: f32,
    /// eq. 1 with the spatial term, d² = 0.5.
    pub reconstruction: f32,
    /// albedo difference.
    pub albedo: f32,
    /// resolve of four colours.
    pub resolved: SubconeVec3,
    /// eq. 3.
    pub tan_theta: f32,
    /// eq. 4.
    pub radius: f32,
    /// eq. 5.
    pub occlusion: f32,
    /// advance.
    pub advanced: f32,
    /// eq. 9–10.
    pub entry: f32,
    /// §3.6.
    pub hard_hit: f32,
    /// projected normal.
    pub projected: [f32; 2],
    /// eq. 7–8.
    pub mask: u32,
    /// eq. 6 weight.
    pub sample_weight: f32,
    /// a 3×2 SRAA frame resolved.
    pub sraa: [SubconeVec3; 6],
    /// a CTSS trace of a sphere, pixel-edge ray.
    pub ctss: SubconeCtssResult,
}

/// What `subcone_smoke_vectors` checked. Mirrors `VectorTally` in
/// `c/vectors.c`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct VectorTally {
    /// Vector files read.
    pub files: u32,
    /// Cases read.
    pub cases: u32,
    /// Cases whose parameters the C ABI refuses (and did, with the error).
    pub refused: u32,
    /// Cases whose outputs matched the file's bit for bit (NaN as NaN).
    pub exact: u32,
    /// Cases that failed.
    pub failures: u32,
}

extern "C" {
    /// Reads the golden vectors in `dir` (`subcone vectors --out DIR`) for the
    /// kernels the C ABI exports and checks each case within its file's
    /// tolerance; returns the number of failures, described in `log`.
    pub fn subcone_smoke_vectors(
        dir: *const c_char,
        tally: *mut VectorTally,
        log: *mut c_char,
        log_len: usize,
    ) -> c_int;
    /// Calls every exported function with fixed inputs into `out`; also calls
    /// each with bad input (null pointers, NaN parameters, zero sizes,
    /// mismatched lengths) and returns how many of those did not give the
    /// documented error code (0 when all did). Writes what failed into `log`.
    pub fn subcone_smoke_run(out: *mut SmokeOutputs, log: *mut c_char, log_len: usize) -> c_int;
    /// The README's C example: returns 0 when it ran as the README says.
    pub fn subcone_readme_example() -> c_int;
}
