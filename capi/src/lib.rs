//! A C ABI for subcone's kernels, for C and C++ engines: the SRAA weights
//! (SRAA for ray tracing, eq. 1 and 2) and per-pixel resolve, the CTSS cone
//! kernels (CTSS eq. 3–8) and one whole CTSS trace over a distance callback.
//! The header, `include/subcone.h`, is generated from this crate by cbindgen
//! and checked in (`tests/header.rs` keeps it current).
//!
//! # Contract
//!
//! - Every fallible function returns a [`SubconeStatus`] and writes its result
//!   through an out-pointer only on [`SubconeStatus::Ok`]. On any other
//!   status, [`subcone_last_error_message`] says what was wrong (the
//!   function, the parameter, its value and what it must be), until the
//!   next call into the library on the same thread.
//! - A parameter struct the library only reads on the host
//!   ([`SubconeSraaFrame`]) begins with a `size` field the host sets to
//!   `sizeof` the struct; any other value is refused with
//!   [`SubconeStatus::StructSize`]. The structs whose bytes the shaders
//!   read as they are (the parameters and pass uniforms) have the shaders'
//!   layouts and no such field.
//! - Null pointers, zero sizes, mismatched lengths and non-finite parameters
//!   (the fields of the parameter structs, camera and cone settings, a ray's
//!   origin and direction) are refused with an error code, never undefined
//!   behaviour. Per-sample data (depths, normals, colours, distances) may be
//!   anything: the kernels' documented domains say what they return outside
//!   them (see each function).
//! - Nothing panics across the boundary: every body runs under
//!   `catch_unwind`, and an unexpected panic becomes
//!   [`SubconeStatus::Panic`].
//! - Thread safety: every function is reentrant and thread-safe; there is no
//!   global state (the last error message is per thread).
//!   [`subcone_ctss_trace`] calls its callbacks synchronously on the calling
//!   thread; they must not unwind (a C callback cannot).
//!
//! ```
//! use subcone_capi::*;
//!
//! let mut params = SubconeSraaParams::default();
//! assert_eq!(unsafe { subcone_sraa_params_paper(&mut params) }, SubconeStatus::Ok);
//! let g = SubconeGeometry { normal: SubconeVec3 { x: 0.0, y: 0.0, z: 1.0 }, depth: 2.0 };
//! let mut w = 0.0;
//! assert_eq!(unsafe { subcone_bilateral_weight(&params, &g, &g, &mut w) }, SubconeStatus::Ok);
//! assert_eq!(w, 1.0);
//! // A null pointer is an error, not a crash, and the message names it.
//! let e = unsafe { subcone_bilateral_weight(&params, &g, std::ptr::null(), &mut w) };
//! assert_eq!(e, SubconeStatus::NullPointer);
//! let message = unsafe { std::ffi::CStr::from_ptr(subcone_last_error_message()) };
//! assert_eq!(message.to_str(), Ok("subcone_bilateral_weight: gj is NULL"));
//! ```
#![deny(unsafe_op_in_unsafe_fn)]
#![deny(missing_docs)]

// The modules, by concern, in the order of the header's declarations
// (cbindgen reads a crate's modules in the order they are declared here, and
// `include/subcone.h` must not change when code moves).

// `mirror_conversions!`: `From` both ways between a C struct and the
// kernels' struct it mirrors.
#[macro_use]
mod mirror;

// The version constants and `subcone_version`.
mod version;
pub use version::{
    subcone_version, SUBCONE_VERSION_MAJOR, SUBCONE_VERSION_MINOR, SUBCONE_VERSION_PATCH,
};

// The status codes, the refusals, and the wrapper that keeps a panic from
// crossing the boundary.
mod status;
pub use status::SubconeStatus;

// The calling thread's last error message and `subcone_last_error_message`.
mod last_error;
pub use last_error::subcone_last_error_message;

// Checked reads of the caller's pointers, slices and parameters.
mod checks;

// The plain vector and a sample's geometry.
mod geometry;
pub use geometry::{SubconeGeometry, SubconeVec3};

// The parameter structs of SRAA and CTSS and their defaults.
mod params;
pub use params::{
    subcone_ctss_params_default, subcone_sraa_params_default, subcone_sraa_params_paper,
    SubconeCtssParams, SubconeSraaParams,
};

// SRAA's per-sample weights (eq. 1 and 2) and box resolve.
mod sraa_weights;
pub use sraa_weights::{
    subcone_albedo_difference, subcone_bilateral_weight, subcone_reconstruction_weight,
    subcone_resolve_pixel, subcone_shadow_gated_weight,
};

// CTSS's cone kernels (eq. 3–10), visibility masks and sample weights.
mod ctss_cone;
pub use ctss_cone::{
    subcone_advance, subcone_backtrace_cone_entry, subcone_backtrace_hard_hit,
    subcone_cone_occlusion, subcone_cone_radius, subcone_cone_tan_theta, subcone_project_normal,
    subcone_sample_weight, subcone_visibility_mask,
};

// SRAA's antialiasing pass over a whole frame.
mod sraa_resolve;
pub use sraa_resolve::{subcone_sraa_resolve, SubconeSraaFrame};

// One whole CTSS trace through the caller's callbacks.
mod ctss_trace;
pub use ctss_trace::{
    subcone_ctss_trace, SubconeCtssResult, SubconeDistanceFn, SubconeFieldSample, SubconeNormalFn,
    SubconeShadeFn,
};

// The SRAA and CTSS passes' shader uniforms.
mod pass_uniforms;
pub use pass_uniforms::{
    subcone_ctss_pass_uniform, subcone_pinhole_ray, subcone_sraa_pass_uniform,
    SubconeCtssPassUniform, SubconePinholeCamera, SubconeSraaPassUniform,
};

// FXAA's and TAA's parameters and pass uniforms, and TAA's jitter.
mod post;
pub use post::{
    subcone_fxaa_params_quality, subcone_fxaa_pass_frame, subcone_taa_jitter, subcone_taa_params,
    SubconeFxaaParams, SubconeFxaaPassFrame, SubconeTaaParams, SubconeTaaPassOrigin,
};

// FXAA and the TAA resolve over whole images on the CPU.
mod images;
pub use images::{subcone_fxaa_image, subcone_taa_resolve};
