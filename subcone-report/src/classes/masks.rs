//! The classification: each pixel's classes from its sub-samples' AOVs.

use anyhow::{bail, Result};
use glam::Vec3;
use subcone_scene::Frame;

use super::{
    flip_near_edge_radius, Class, CREASE_COS, SILHOUETTE_DEPTH, SSIM_NEAR_EDGE_RADIUS,
    TEXTURE_ALBEDO,
};

/// One mask per class over a `width × height` image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ClassMasks {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The masks, indexed by [`Class::index`], row-major.
    pub masks: [Vec<bool>; 6],
    /// The near-edge band under FLIP, row-major: pixels in none of the
    /// classes within [`flip_near_edge_radius`] of a classed pixel (and so
    /// not flat). `masks[Class::Flat]` is FLIP's flat: the
    /// rest.
    pub near_edge: Vec<bool>,
    /// The near-edge band under SSIM (its window's reach), row-major.
    pub ssim_near_edge: Vec<bool>,
    /// Flat under SSIM: in no class and not in SSIM's near-edge band.
    pub ssim_flat: Vec<bool>,
}

impl ClassMasks {
    /// The mask of `class`.
    pub fn mask(&self, class: Class) -> &[bool] {
        &self.masks[class.index()]
    }

    /// Pixels in `class`.
    pub fn count(&self, class: Class) -> u64 {
        self.mask(class).iter().filter(|&&m| m).count() as u64
    }

    /// The pixels in no class, near-edge band included: flat for a
    /// per-pixel measure, which carries no error onto a neighbour (the
    /// motion section's instability).
    pub fn unclassed(&self) -> Vec<bool> {
        self.mask(Class::Flat)
            .iter()
            .zip(&self.near_edge)
            .map(|(&f, &n)| f || n)
            .collect()
    }

    /// These masks with FLIP's near-edge band (and flat) `radius` pixels
    /// wide instead of its filters' reach: to judge flat as a target was
    /// stated before the band followed the metric (2 px).
    pub fn with_flip_band(&self, radius: u32) -> ClassMasks {
        let mut out = self.clone();
        let classed: Vec<bool> = self
            .mask(Class::Flat)
            .iter()
            .zip(&self.near_edge)
            .map(|(&f, &n)| !f && !n)
            .collect();
        let (near, flat) = self.band(&classed, radius);
        out.masks[Class::Flat.index()] = flat;
        out.near_edge = near;
        out
    }

    /// Split the pixels in no class into each metric's near-edge band
    /// (within [`flip_near_edge_radius`] or [`SSIM_NEAR_EDGE_RADIUS`] of a
    /// classed pixel, Chebyshev) and flat (the rest): sets the bands and
    /// the two flat masks.
    fn split_near_edge(&mut self) {
        let classed: Vec<bool> = self.masks[Class::Flat.index()].iter().map(|f| !f).collect();
        let (flip_near, flip_flat) = self.band(&classed, flip_near_edge_radius());
        let (ssim_near, ssim_flat) = self.band(&classed, SSIM_NEAR_EDGE_RADIUS);
        self.masks[Class::Flat.index()] = flip_flat;
        self.near_edge = flip_near;
        self.ssim_near_edge = ssim_near;
        self.ssim_flat = ssim_flat;
    }

    /// The near-edge band of radius `r` around the `classed` pixels and
    /// the flat pixels outside it (both empty for an empty image).
    fn band(&self, classed: &[bool], r: u32) -> (Vec<bool>, Vec<bool>) {
        let (w, h) = (self.width as usize, self.height as usize);
        let r = r as usize;
        if w == 0 || h == 0 {
            return (Vec::new(), Vec::new());
        }
        // Separable dilation by a (2r+1)² square: rows, then columns.
        let mut rows = vec![false; w * h];
        for y in 0..h {
            for x in 0..w {
                let (a, b) = (x.saturating_sub(r), (x + r).min(w - 1));
                rows[y * w + x] = classed[y * w + a..=y * w + b].iter().any(|&c| c);
            }
        }
        let mut near = vec![false; w * h];
        for y in 0..h {
            let (a, b) = (y.saturating_sub(r), (y + r).min(h - 1));
            for x in 0..w {
                near[y * w + x] = !classed[y * w + x] && (a..=b).any(|yy| rows[yy * w + x]);
            }
        }
        let flat = classed.iter().zip(&near).map(|(&c, &n)| !c && !n).collect();
        (near, flat)
    }

    /// One byte per pixel, row-major, bit `i` set when the pixel is in
    /// class `i` ([`Class::index`]): every class of a pixel in one lookup,
    /// as the interactive page reads them.
    pub fn bits(&self) -> Vec<u8> {
        let mut out = vec![0u8; (self.width * self.height) as usize];
        for (i, mask) in self.masks.iter().enumerate() {
            for (b, &m) in out.iter_mut().zip(mask) {
                *b |= u8::from(m) << i;
            }
        }
        out
    }
}

/// The AOVs a classification needs, checked against the frame size.
struct Aovs<'a> {
    w: usize,
    h: usize,
    depth: &'a [f32],
    normal: &'a [Vec3],
    albedo: &'a [Vec3],
    visibility: &'a [u32],
    mirror: &'a [f32],
}

impl<'a> Aovs<'a> {
    fn of(f: &'a Frame) -> Result<Self> {
        let (w, h) = (f.width as usize, f.height as usize);
        let (Some(depth), Some(normal), Some(albedo), Some(visibility), Some(mirror)) = (
            f.depth.as_deref(),
            f.normal.as_deref(),
            f.albedo.as_deref(),
            f.light_visibility.as_deref(),
            f.mirror.as_deref(),
        ) else {
            bail!(
                "the sub-sample frame lacks an AOV: classes need depth, normal, albedo, \
                 light visibility and mirror (render with aovs = true on the cpu backend)"
            );
        };
        let n = w * h;
        if [
            depth.len(),
            normal.len(),
            albedo.len(),
            visibility.len(),
            mirror.len(),
        ]
        .iter()
        .any(|&l| l != n)
        {
            bail!("the sub-sample AOVs do not match the frame size {w}x{h}");
        }
        Ok(Aovs {
            w,
            h,
            depth,
            normal,
            albedo,
            visibility,
            mirror,
        })
    }

    fn hit(&self, i: usize) -> bool {
        self.depth[i].is_finite()
    }

    /// Whether sub-samples `a` and `b` (4-neighbours) see different
    /// surfaces ([`metrics::depth_discontinuity`](crate::metrics::depth_discontinuity)
    /// at [`SILHOUETTE_DEPTH`]); `oa` and `ob` are their neighbours on the
    /// same line, away from each other.
    fn silhouette(&self, a: usize, b: usize, oa: Option<usize>, ob: Option<usize>) -> bool {
        crate::metrics::depth_discontinuity(self.depth, a, b, oa, ob, SILHOUETTE_DEPTH)
    }

    /// Whether the normals of `a` and `b` (both surface points) fold.
    fn crease(&self, a: usize, b: usize) -> bool {
        let (na, nb) = (self.normal[a], self.normal[b]);
        na.is_finite()
            && nb.is_finite()
            && na.length_squared() > 0.25
            && nb.length_squared() > 0.25
            && na.normalize().dot(nb.normalize()) < CREASE_COS
    }
}

/// Classify every pixel of a `sub.width / side × sub.height / side` image
/// from `sub`, a frame rendered at `side`× that size on each side with the
/// AOVs [`Frame::albedo`], [`Frame::light_visibility`], [`Frame::mirror`],
/// depth and normal (the CPU backend records them all).
///
/// Errors when an AOV is missing, the sizes disagree or `side` is 0; never
/// panics on NaN or infinite AOV values (a NaN depth is a miss, a NaN normal
/// never creases, NaN albedo never differs).
pub fn classify(sub: &Frame, side: u32) -> Result<ClassMasks> {
    if side == 0 || sub.width % side != 0 || sub.height % side != 0 {
        bail!(
            "a {}x{} sub-sample frame does not divide into {side}x{side} sub-samples per pixel",
            sub.width,
            sub.height
        );
    }
    let a = Aovs::of(sub)?;
    let s = side as usize;
    let (w, h) = (a.w / s, a.h / s);
    let mut masks: [Vec<bool>; 6] = std::array::from_fn(|_| vec![false; w * h]);
    for py in 0..h {
        for px in 0..w {
            let mut silhouette = false;
            let mut crease = false;
            let (mut vis_or, mut vis_and) = (0u32, u32::MAX);
            let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
            let mut mirror = false;
            let mut surfaces = 0;
            for j in 0..s {
                for i in 0..s {
                    let (x, y) = (px * s + i, py * s + j);
                    let k = y * a.w + x;
                    // Pairs inside the pixel: with the right and lower neighbour.
                    if i + 1 < s {
                        let oa = (x > 0).then(|| k - 1);
                        let ob = (x + 2 < a.w).then(|| k + 2);
                        let sil = a.silhouette(k, k + 1, oa, ob);
                        silhouette |= sil;
                        crease |= !sil && a.hit(k) && a.hit(k + 1) && a.crease(k, k + 1);
                    }
                    if j + 1 < s {
                        let oa = (y > 0).then(|| k - a.w);
                        let ob = (y + 2 < a.h).then(|| k + 2 * a.w);
                        let sil = a.silhouette(k, k + a.w, oa, ob);
                        silhouette |= sil;
                        crease |= !sil && a.hit(k) && a.hit(k + a.w) && a.crease(k, k + a.w);
                    }
                    mirror |= a.mirror[k] > 0.0;
                    if a.hit(k) {
                        surfaces += 1;
                        vis_or |= a.visibility[k];
                        vis_and &= a.visibility[k];
                        let c = a.albedo[k].max(Vec3::ZERO);
                        let e = Vec3::new(c.x.sqrt(), c.y.sqrt(), c.z.sqrt());
                        if e.is_finite() {
                            lo = lo.min(e);
                            hi = hi.max(e);
                        }
                    }
                }
            }
            let smooth = !silhouette && !crease;
            let shadow = smooth && surfaces > 1 && vis_or != vis_and;
            let texture = smooth && lo.x.is_finite() && (hi - lo).max_element() > TEXTURE_ALBEDO;
            let p = py * w + px;
            masks[Class::Silhouette.index()][p] = silhouette;
            masks[Class::Crease.index()][p] = crease;
            masks[Class::Shadow.index()][p] = shadow;
            masks[Class::Texture.index()][p] = texture;
            masks[Class::Reflection.index()][p] = mirror;
            masks[Class::Flat.index()][p] = !(silhouette || crease || shadow || texture || mirror);
        }
    }
    let mut out = ClassMasks {
        width: w as u32,
        height: h as u32,
        masks,
        near_edge: Vec::new(),
        ssim_near_edge: Vec::new(),
        ssim_flat: Vec::new(),
    };
    out.split_near_edge();
    Ok(out)
}
