//! Many random objects at a bounded cost per evaluation: a grid of cells, each
//! holding at most one hashed variation of a template, evaluated one cell at a
//! time (the authors' `GRID_TRACE` idea).

use glam::{Quat, Vec3};
use subcone_kernels::math::Euclidean;

use super::SdfNode;
use crate::sdf::bounds::{round_cell, Aabb};
use crate::sdf::check::{all_finite, nonneg, positive};
use crate::sdf::SdfError;

/// The most cells a scatter may have (the per-cell table is 48 bytes a cell).
pub const MAX_SCATTER_CELLS: u64 = 1 << 18;

const EMPTY: u32 = u32::MAX;

/// Layout and randomness of [`SdfNode::scatter`].
///
/// Cell `i` (in `lo..=hi`) is the box of size `cell` centred at
/// `origin + i · cell`. With probability `fill` it holds one template, chosen
/// uniformly, scaled so that its bounding sphere has radius
/// `u · R` with `u` uniform in `[min_size, max_size]` and
/// `R = min(cell)/2 − margin`, rotated uniformly at random (if `rotate`) and
/// offset at random within what keeps it `margin` away from the cell walls (if
/// `jitter`). Everything is a hash of `seed` and the cell index, so the layout
/// does not depend on evaluation order.
///
/// Evaluation visits the cell of `p` (clamped to the grid) only and returns
/// `min(d_object, w + margin)`, `w` the distance from `p` to the walls of its
/// cell that have neighbours: every other object is at least that far, so the
/// result never overestimates (a bound) and is exact wherever the own object is
/// nearer than `w + margin`. A larger margin gives longer steps through empty
/// cells.
#[derive(Clone, Debug, PartialEq)]
pub struct ScatterConfig {
    /// Centre of cell `(0, 0, 0)`.
    pub origin: Vec3,
    /// Cell size per axis.
    pub cell: Vec3,
    /// First cell index (inclusive).
    pub lo: [i32; 3],
    /// Last cell index (inclusive).
    pub hi: [i32; 3],
    /// Random seed.
    pub seed: u64,
    /// Probability that a cell is occupied, in `[0, 1]`.
    pub fill: f32,
    /// Gap kept between an object and its cell's walls, `≥ 0`.
    pub margin: f32,
    /// Smallest object size as a fraction of the largest that fits, in `(0, 1]`.
    pub min_size: f32,
    /// Largest object size as a fraction of the largest that fits, in
    /// `[min_size, 1]`.
    pub max_size: f32,
    /// Rotate objects at random.
    pub rotate: bool,
    /// Offset objects at random within their cell.
    pub jitter: bool,
    /// Materials to pick from at random per object; empty keeps the templates'
    /// own materials.
    pub palette: Vec<u32>,
}

impl ScatterConfig {
    /// Cells of size `cell` over `lo..=hi` centred on the origin: every cell
    /// filled, margin 5 % of the smallest cell side, sizes 0.5–1, rotation and
    /// jitter on, templates' own materials.
    pub fn new(cell: Vec3, lo: [i32; 3], hi: [i32; 3], seed: u64) -> Self {
        ScatterConfig {
            origin: Vec3::ZERO,
            cell,
            lo,
            hi,
            seed,
            fill: 1.0,
            margin: 0.05 * cell.min_element(),
            min_size: 0.5,
            max_size: 1.0,
            rotate: true,
            jitter: true,
            palette: Vec::new(),
        }
    }
}

/// One cell's object of a [`Scatter`]: its template, placement and material.
#[derive(Clone, Copy, Debug)]
pub struct Instance {
    /// Index into the scatter's templates, or `u32::MAX` for an empty cell.
    pub template: u32,
    /// Palette material, or `u32::MAX` for the template's own.
    pub material: u32,
    /// World to instance rotation.
    pub inv_rotation: Quat,
    /// The instance's centre, from the cell's centre.
    pub offset: Vec3,
    /// Uniform scale of the template.
    pub scale: f32,
    /// `1 / scale`.
    pub inv_scale: f32,
    /// Bounding-sphere radius around `offset`.
    pub radius: f32,
}

/// A validated scatter with its per-cell table: the operand of
/// [`Op::Scatter`](super::Op::Scatter), built by
/// [`SdfNode::scatter`](super::SdfNode::scatter) from a [`ScatterConfig`].
#[derive(Clone, Debug)]
pub struct Scatter {
    /// The grid's origin (a cell's centre at index 0).
    pub origin: Vec3,
    /// The cell size per axis.
    pub cell: Vec3,
    /// `1 / cell`.
    pub inv_cell: Vec3,
    /// Lowest cell index per axis.
    pub lo: Vec3,
    /// Highest cell index per axis.
    pub hi: Vec3,
    /// Cells per axis.
    pub dims: [usize; 3],
    /// The margin added to the distance to a cell's walls.
    pub margin: f32,
    /// The shapes instanced.
    pub templates: Vec<SdfNode>,
    /// The materials drawn per instance (empty: the templates' own).
    pub palette: Vec<u32>,
    /// One entry per cell, x fastest.
    pub instances: Vec<Instance>,
    objects: u64,
    /// The material where no instance decides.
    pub default_material: u32,
    bounds: Aabb,
    /// What it was built from (the palette as given; see [`Scatter::config`]).
    config: ScatterConfig,
}

fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A tiny splitmix64 stream.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        mix(self.0)
    }

    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn cell_rng(seed: u64, i: [i32; 3]) -> Rng {
    let h = mix(i[2] as u32 as u64 ^ 0x51_7cc1_b727_220a);
    let h = mix(i[1] as u32 as u64 ^ h.rotate_left(21));
    let h = mix(i[0] as u32 as u64 ^ h.rotate_left(21));
    Rng(mix(seed ^ h))
}

/// Uniform random rotation (Shoemake).
fn random_rotation(rng: &mut Rng) -> Quat {
    let (u1, u2, u3) = (rng.unit(), rng.unit(), rng.unit());
    let tau = std::f32::consts::TAU;
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    Quat::from_xyzw(
        a * (tau * u2).sin(),
        a * (tau * u2).cos(),
        b * (tau * u3).sin(),
        b * (tau * u3).cos(),
    )
    .normalize()
}

fn invalid(reason: String) -> SdfError {
    SdfError::Invalid { node: NAME, reason }
}

/// The name errors give.
const NAME: &str = "scatter";

/// What a cell without an object holds.
const VACANT: Instance = Instance {
    template: EMPTY,
    material: EMPTY,
    inv_rotation: Quat::IDENTITY,
    offset: Vec3::ZERO,
    scale: 1.0,
    inv_scale: 1.0,
    radius: 0.0,
};

impl ScatterConfig {
    /// The number of cells along each axis, once the origin, the cell size and
    /// the cell range are checked.
    fn checked_dims(&self) -> Result<[u64; 3], SdfError> {
        all_finite(NAME, "origin", self.origin.is_finite())?;
        for v in self.cell.to_array() {
            positive(NAME, "cell size", v)?;
        }
        if (0..3).any(|k| self.lo[k] > self.hi[k]) {
            return Err(invalid(format!(
                "empty cell range {:?}..={:?}",
                self.lo, self.hi
            )));
        }
        let dims64: [u64; 3] =
            std::array::from_fn(|k| (self.hi[k] as i64 - self.lo[k] as i64 + 1) as u64);
        let cells = dims64.iter().try_fold(1u64, |acc, &n| acc.checked_mul(n));
        match cells {
            Some(n) if n <= MAX_SCATTER_CELLS => Ok(dims64),
            _ => Err(invalid(format!(
                "{:?}..={:?} is more than {MAX_SCATTER_CELLS} cells",
                self.lo, self.hi
            ))),
        }
    }

    /// The largest bounding-sphere radius an object may have (`R`), once the
    /// fill, the margin and the sizes are checked.
    fn checked_r_max(&self) -> Result<f32, SdfError> {
        if !(self.fill.is_finite() && (0.0..=1.0).contains(&self.fill)) {
            return Err(invalid(format!("fill {} is not in [0, 1]", self.fill)));
        }
        nonneg(NAME, "margin", self.margin)?;
        let r_max = 0.5 * self.cell.min_element() - self.margin;
        if r_max <= 0.0 {
            return Err(invalid(format!(
                "margin {} leaves no room in cells of {}",
                self.margin, self.cell
            )));
        }
        if !(self.min_size > 0.0 && self.min_size <= self.max_size && self.max_size <= 1.0) {
            return Err(invalid(format!(
                "sizes {}..{} are not within (0, 1]",
                self.min_size, self.max_size
            )));
        }
        Ok(r_max)
    }

    /// Cell `i`'s object, drawn from the cell's own random stream (see the
    /// type's docs); `None` when the cell is empty. Every draw is made whether
    /// the cell is occupied or not.
    fn place(&self, i: [i32; 3], radii: &[f32], r_max: f32) -> Option<Instance> {
        let mut rng = cell_rng(self.seed, i);
        let occupied = rng.unit() < self.fill;
        let template = rng.below(radii.len());
        let u = self.min_size + (self.max_size - self.min_size) * rng.unit();
        let radius = u * r_max;
        let scale = radius / radii[template];
        let rotation = if self.rotate {
            random_rotation(&mut rng)
        } else {
            Quat::IDENTITY
        };
        let mut offset = Vec3::ZERO;
        if self.jitter {
            for k in 0..3 {
                let slack = (0.5 * self.cell[k] - self.margin - radius).max(0.0);
                offset[k] = (2.0 * rng.unit() - 1.0) * slack;
            }
        }
        let material = if self.palette.is_empty() {
            EMPTY
        } else {
            self.palette[rng.below(self.palette.len())]
        };
        (occupied && scale.is_finite() && scale > 0.0).then(|| Instance {
            template: template as u32,
            material,
            inv_rotation: rotation.conjugate(),
            offset,
            scale,
            inv_scale: 1.0 / scale,
            radius,
        })
    }
}

/// Each template's bounding-sphere radius about its origin, which must be
/// finite and non-zero for a template to be scaled to a cell.
fn template_radii(templates: &[SdfNode]) -> Result<Vec<f32>, SdfError> {
    let mut radii = Vec::with_capacity(templates.len());
    for t in templates {
        let r = t.bounds().radius_about_origin();
        if !(r.is_finite() && r > 0.0) {
            return Err(invalid(format!(
                "a template has no finite, non-zero extent about the origin (radius {r})"
            )));
        }
        radii.push(r);
    }
    Ok(radii)
}

/// The per-cell table, `x` fastest, and the number of objects it places.
fn fill_cells(
    c: &ScatterConfig,
    templates: &[SdfNode],
    radii: &[f32],
    r_max: f32,
    dims: [usize; 3],
) -> (Vec<Instance>, u64) {
    let mut instances = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
    let mut objects: u64 = 0;
    for z in c.lo[2]..=c.hi[2] {
        for y in c.lo[1]..=c.hi[1] {
            for x in c.lo[0]..=c.hi[0] {
                match c.place([x, y, z], radii, r_max) {
                    Some(instance) => {
                        let template = &templates[instance.template as usize];
                        objects =
                            objects.saturating_add(template.object_count().unwrap_or(u64::MAX));
                        instances.push(instance);
                    }
                    None => instances.push(VACANT),
                }
            }
        }
    }
    (instances, objects)
}

impl Scatter {
    pub(crate) fn new(c: ScatterConfig, templates: Vec<SdfNode>) -> Result<Scatter, SdfError> {
        if templates.is_empty() {
            return Err(SdfError::Empty { node: NAME });
        }
        let dims64 = c.checked_dims()?;
        let r_max = c.checked_r_max()?;
        let radii = template_radii(&templates)?;

        let dims = dims64.map(|n| n as usize);
        let (instances, objects) = fill_cells(&c, &templates, &radii, r_max, dims);
        if objects == 0 {
            return Err(invalid(format!(
                "no cell is occupied (fill {}): the scatter would be empty",
                c.fill
            )));
        }
        let default_material = c
            .palette
            .first()
            .copied()
            .unwrap_or_else(|| templates[0].materials_used().first().copied().unwrap_or(0));
        let f = |v: [i32; 3]| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32);
        let (lo, hi) = (f(c.lo), f(c.hi));
        let half = 0.5 * c.cell - Vec3::splat(c.margin);
        let palette = c.palette.clone();
        let bounds = Aabb::new(c.origin + lo * c.cell - half, c.origin + hi * c.cell + half);
        Ok(Scatter {
            origin: c.origin,
            cell: c.cell,
            inv_cell: c.cell.recip(),
            lo,
            hi,
            dims,
            margin: c.margin,
            templates,
            palette,
            instances,
            objects,
            default_material,
            bounds,
            config: c,
        })
    }

    pub(crate) fn instances(&self) -> &[Instance] {
        &self.instances
    }

    pub(crate) fn margin(&self) -> f32 {
        self.margin
    }

    pub(crate) fn templates(&self) -> &[SdfNode] {
        &self.templates
    }

    pub(crate) fn palette(&self) -> &[u32] {
        &self.palette
    }

    pub(crate) fn object_count(&self) -> u64 {
        self.objects
    }

    pub(crate) fn default_material(&self) -> u32 {
        self.default_material
    }

    pub(crate) fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The configuration that builds this scatter again: the one it was built
    /// from, with the palette a change of material may have replaced
    /// (a one-colour palette draws the same instances: the palette is the
    /// last draw of a cell's random stream).
    pub fn config(&self) -> ScatterConfig {
        ScatterConfig {
            palette: self.palette.clone(),
            ..self.config.clone()
        }
    }

    pub(crate) fn set_material(&mut self, m: u32) {
        self.palette = vec![m];
        self.default_material = m;
        for i in &mut self.instances {
            if i.template != EMPTY {
                i.material = m;
            }
        }
    }

    #[inline]
    pub(crate) fn eval(&self, p: Vec3) -> (f32, u32) {
        self.eval_xyz(p.x, p.y, p.z)
    }

    /// `(guarded bound, own object's distance, material)`; see
    /// `SdfNode::eval_split`. An empty cell has no surface (`∞`); far from the
    /// object, its bounding sphere's distance stands in for the surface.
    pub(crate) fn split(&self, p: Vec3) -> (f32, f32, u32) {
        let rel = p - self.origin;
        let f = rel * self.inv_cell;
        let f =
            Vec3::new(round_cell(f.x), round_cell(f.y), round_cell(f.z)).clamp(self.lo, self.hi);
        let q = rel - f * self.cell;
        let mut wall = f32::INFINITY;
        for k in 0..3 {
            if f[k] < self.hi[k] {
                wall = wall.min(0.5 * self.cell[k] - q[k]);
            }
            if f[k] > self.lo[k] {
                wall = wall.min(0.5 * self.cell[k] + q[k]);
            }
        }
        let guard = wall + self.margin;
        let i = f - self.lo;
        let idx = i.x as usize + self.dims[0] * (i.y as usize + self.dims[1] * i.z as usize);
        let Some(inst) = self.instances.get(idx) else {
            return (guard, f32::INFINITY, self.default_material);
        };
        let Some(template) = self.templates.get(inst.template as usize) else {
            return (guard, f32::INFINITY, self.default_material);
        };
        let local = q - inst.offset;
        let own = if inst.material == EMPTY {
            self.default_material
        } else {
            inst.material
        };
        let sphere = local.norm() - inst.radius;
        if sphere >= guard {
            return (guard, sphere, own);
        }
        let (d, m) = template.eval(inst.inv_rotation * local * inst.inv_scale);
        let d = d * inst.scale;
        let m = if inst.material == EMPTY {
            m
        } else {
            inst.material
        };
        (guard.min(d), d, m)
    }

    #[inline(never)]
    fn eval_xyz(&self, x: f32, y: f32, z: f32) -> (f32, u32) {
        let (bound, _, m) = self.split(Vec3::new(x, y, z));
        (bound, m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The minimum over every occupied cell's object: the true field's bound.
    fn brute(s: &Scatter, p: Vec3) -> f32 {
        let mut best = f32::INFINITY;
        let mut idx = 0;
        for z in s.lo.z as i32..=s.hi.z as i32 {
            for y in s.lo.y as i32..=s.hi.y as i32 {
                for x in s.lo.x as i32..=s.hi.x as i32 {
                    let inst = &s.instances[idx];
                    idx += 1;
                    let Some(t) = s.templates.get(inst.template as usize) else {
                        continue;
                    };
                    let centre =
                        s.origin + Vec3::new(x as f32, y as f32, z as f32) * s.cell + inst.offset;
                    let local = inst.inv_rotation * (p - centre) * inst.inv_scale;
                    best = best.min(t.eval(local).0 * inst.scale);
                }
            }
        }
        best
    }

    #[test]
    fn scatter_never_overestimates_and_is_exact_near_objects() {
        let templates = vec![
            SdfNode::capped_cone(1.0, 0.9, 0.1)
                .unwrap()
                .translate(Vec3::new(0.0, 0.2, 0.0))
                .unwrap(),
            SdfNode::cuboid(Vec3::new(1.0, 0.3, 0.6)).unwrap(),
            SdfNode::torus(0.8, 0.2).unwrap(),
        ];
        let mut c = ScatterConfig::new(Vec3::new(1.5, 2.0, 1.0), [-3, 0, -2], [3, 1, 2], 42);
        c.fill = 0.6;
        c.margin = 0.08;
        c.min_size = 0.4;
        c.origin = Vec3::new(0.3, -0.2, 0.1);
        let s = Scatter::new(c.clone(), templates).unwrap();
        assert!(s.object_count() > 10 && s.object_count() < 70);
        let mut rng = Rng(7);
        let mut near = 0;
        for i in 0..60_000 {
            let r = if i % 3 == 0 { 9.0 } else { 5.0 };
            let p = Vec3::new(
                (2.0 * rng.unit() - 1.0) * r,
                (2.0 * rng.unit() - 1.0) * r,
                (2.0 * rng.unit() - 1.0) * r,
            );
            let truth = brute(&s, p);
            let (d, _) = s.eval(p);
            assert!(d <= truth + 1e-5, "{d} > {truth} at {p}");
            assert_eq!(d < 0.0, truth < 0.0, "{p}");
            if truth.abs() < c.margin {
                near += 1;
                assert!((d - truth).abs() < 1e-5, "near: {d} vs {truth} at {p}");
            }
        }
        assert!(near > 100, "{near}");
    }

    #[test]
    fn layout_depends_on_seed_only() {
        let t = || vec![SdfNode::sphere(1.0).unwrap()];
        let mut c = ScatterConfig::new(Vec3::ONE, [0, 0, 0], [5, 5, 5], 1);
        c.fill = 0.5;
        let a = Scatter::new(c.clone(), t()).unwrap();
        let b = Scatter::new(c.clone(), t()).unwrap();
        assert_eq!(a.object_count(), b.object_count());
        c.seed = 2;
        let d = Scatter::new(c, t()).unwrap();
        let p = Vec3::new(2.2, 3.1, 1.7);
        assert_eq!(a.eval(p), b.eval(p));
        assert_ne!(
            (0..6)
                .map(|i| a.eval(Vec3::splat(i as f32)).0)
                .collect::<Vec<_>>(),
            (0..6)
                .map(|i| d.eval(Vec3::splat(i as f32)).0)
                .collect::<Vec<_>>()
        );
    }
}
