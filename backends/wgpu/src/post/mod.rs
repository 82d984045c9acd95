//! Post-processing passes over a finished frame that stays on the GPU.

pub(crate) mod fxaa;
pub(crate) mod taa;
