//! `subcone-kernels`: the equations of two antialiasing papers as pure, `no_std`,
//! allocation-free `f32` functions.
//!
//! - **SRAA for ray tracing** (Chiu, Chen, Chang, Lee): [`sraa`]: the rotated-grid
//!   subpixel layout, bilateral weights (eq. 1), shadow-gated weights (eq. 2),
//!   reconstruction and the pixel resolve.
//! - **Cone-traced supersampling** (Chubarau, Zhao, Rao, Kry, Nowrouzezahrai):
//!   [`cone`] (eq. 3–5, 9–10), [`mask`] (eq. 7–8, §3.5), [`aggregate`] (eq. 6),
//!   and [`ctss`], the hit-group logic of Algorithm 1 as a stepper any SDF and any
//!   shading can drive; [`transparency`], the `K` masks of §5.3 for
//!   semi-transparent surfaces.
//! - [`fxaa`]: FXAA 3.11 (Lottes), the post-process baseline the papers'
//!   methods are compared with.
//! - [`taa`]: temporal antialiasing (Karis 2014, Salvi 2016's variance
//!   clipping), the temporal baseline engines ship, and what the papers'
//!   methods run under as `+taa`.
//! - [`ao`]: the fixed, stratified, cosine-weighted ambient-occlusion
//!   directions in the tangent frame of a normal (the report's shading-cost
//!   axis; not from either paper).
//! - [`camera`]: the pinhole camera GPU shaders trace through, one uniform
//!   and one ray rule.
//! - [`uniforms`]: the uniforms of the GPU passes (SRAA, CTSS) and the
//!   one way to fill them, shared by `subcone-passes` and the C ABI.
//! - [`passes`]: which passes a technique needs on a scene, so nothing a scene does
//!   not need is computed or allocated.
//!
//! Every function states its paper section and equation, its input domain, and
//! what it returns outside that domain. The policy for non-finite input, crate-wide:
//! **no panic, no endless loop, and no NaN out of a weight, a reconstruction or an
//! aggregation.** NaN geometry excludes a sample (weight 0), NaN distances end a
//! trace, the cone occlusion saturates to `[−1, 2]`, and every trace ends within
//! its step budget.
//!
//! ```
//! use glam::Vec3;
//! use subcone_kernels::sraa::{bilateral_weight, shadow_gated_weight, Geometry, SraaParams};
//!
//! let p = SraaParams::PAPER;
//! let floor = Geometry::new(Vec3::Y, 10.0);
//! let wall = Geometry::new(Vec3::Z, 14.0); // 40 % deeper, perpendicular
//! assert_eq!(bilateral_weight(&p, &floor, &floor), 1.0);
//! assert!(bilateral_weight(&p, &floor, &wall) < 0.01);
//! // Eq. 2: a neighbour across a shadow edge never contributes.
//! assert_eq!(shadow_gated_weight(&p, &floor, &floor, true, false), 0.0);
//! ```
#![no_std]
#![deny(missing_docs)]
#![forbid(unsafe_code)]
// `!(x > 0.0)` is how these kernels say "not positive, or NaN"; the lint's
// rewrite would hide exactly the NaN case the domain docs are about.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

// With `std`, `math::sqrt` is `f32::sqrt` (VEX-encodable), not libm's asm.
#[cfg(feature = "std")]
extern crate std;

pub mod aggregate;
pub mod ao;
pub mod camera;
pub mod cone;
pub mod ctss;
pub mod fxaa;
pub mod mask;
pub mod math;
pub mod passes;
pub mod sraa;
mod sum;
pub mod taa;
pub mod transparency;
pub mod uniforms;
pub mod wgsl;

pub use glam;
