//! A case's input words, built up and read back, and its output words.

use glam::{Vec2, Vec3};
use subcone_kernels::sraa::{Geometry, SraaParams};

/// Input words, built up.
#[derive(Default)]
pub(super) struct W(pub(super) Vec<u32>);

impl W {
    pub(super) fn f(mut self, x: f32) -> Self {
        self.0.push(x.to_bits());
        self
    }
    pub(super) fn u(mut self, x: u32) -> Self {
        self.0.push(x);
        self
    }
    pub(super) fn v(mut self, v: &[f32]) -> Self {
        self.0.extend(v.iter().map(|x| x.to_bits()));
        self
    }
    pub(super) fn params(self, p: &SraaParams) -> Self {
        self.f(p.sigma_z)
            .f(p.sigma_n)
            .f(p.scale)
            .u(p.packed)
            .f(p.sigma_s)
            .u(p.shading)
    }
    pub(super) fn geometry(self, g: &Geometry) -> Self {
        self.v(&g.normal.to_array()).f(g.depth)
    }
}

/// Input words, read back in order.
pub(super) struct R<'a>(pub(super) &'a [u32]);

impl R<'_> {
    pub(super) fn u(&mut self) -> u32 {
        let (x, rest) = self.0.split_first().expect("input word");
        self.0 = rest;
        *x
    }
    pub(super) fn f(&mut self) -> f32 {
        f32::from_bits(self.u())
    }
    pub(super) fn b(&mut self) -> bool {
        self.u() != 0
    }
    pub(super) fn v2(&mut self) -> Vec2 {
        Vec2::new(self.f(), self.f())
    }
    pub(super) fn v3(&mut self) -> Vec3 {
        Vec3::new(self.f(), self.f(), self.f())
    }
    pub(super) fn params(&mut self) -> SraaParams {
        SraaParams {
            sigma_z: self.f(),
            sigma_n: self.f(),
            scale: self.f(),
            packed: self.u(),
            sigma_s: self.f(),
            shading: self.u(),
            _pad: [0; 2],
        }
    }
    pub(super) fn geometry(&mut self) -> Geometry {
        Geometry::new(self.v3(), self.f())
    }
}

pub(super) fn out(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}
