//! WGSL code generation: an [`SdfNode`] tree as WGSL functions that evaluate
//! the same field as [`SdfNode::eval`] and [`SdfNode::eval_split`], operation
//! for operation (same formulas, same order of the f32 operations where it
//! changes the rounding, same skipping rules for unions and bounded groups).
//!
//! The generated source defines
//!
//! ```text
//! fn scene_sdf(p: vec3<f32>) -> vec2<f32>        // (distance, material) = SdfNode::eval
//! fn scene_sdf_split(p: vec3<f32>) -> vec3<f32>  // (safe step, surface, material) = SdfNode::eval_split
//! ```
//!
//! with the material index as an `f32` (exact: indices are far below 2²⁴).
//! It uses `subcone_inf` and `subcone_is_finite` of
//! `subcone_kernels::wgsl::PARAMS`: include that first, as every shader does.
//! Constants become literals. Scatter grids keep their per-cell instance table
//! in [`WgslField::data`]; when it is not empty the caller binds it as
//! `var<storage, read> sdf_data: array<vec4<f32>>` (WGSL has no includes, so
//! the binding is the caller's: it knows its group and slot).
//!
//! Differences from the CPU are those of the GPU's arithmetic: `sqrt`,
//! `sin` and fused multiply-adds may differ in the last bits, and NaN inputs
//! (which the CPU maps to cell 0 in repetition) give unspecified cells.
//!
//! ```
//! use subcone_scene::builtin::sdf_builtin;
//! use subcone_sdf::wgsl::WgslField;
//!
//! let scene = sdf_builtin("primitives").unwrap().unwrap();
//! let field = WgslField::compile(&scene.root);
//! assert!(field.source.contains("fn scene_sdf("));
//! assert!(field.data.is_empty());
//! ```

use std::fmt::Write;

use glam::{Quat, Vec3, Vec4};

// The short names the generator's format strings use.
use self::{f32_literal as f, vec3_literal as v3};

use subcone_scene::sdf::{Op, Repeat, Scatter, SdfNode, Shape, Transform};

/// A field compiled to WGSL.
#[derive(Clone, Debug, PartialEq)]
pub struct WgslField {
    /// WGSL source: helper functions, one function per node, `scene_sdf` and
    /// `scene_sdf_split`. Self-contained apart from `sdf_data` (see
    /// [`WgslField::data`]).
    pub source: String,
    /// Scatter instance tables, three `vec4<f32>` per cell, to be bound as
    /// `sdf_data`; empty when the tree has no scatter grid (then `sdf_data`
    /// is not referenced).
    pub data: Vec<[f32; 4]>,
}

/// Helpers shared by every generated field: one WGSL function per
/// primitive of `shape.rs`, with the same names.
const PRELUDE: &str = r#"
// +inf and the finiteness test are `subcone_inf` and `subcone_is_finite` of
// `subcone_kernels::wgsl::PARAMS`, which every including shader puts first.
// glam's Quat * Vec3 (mul_vec3): v(w² − b·b) + b(2 v·b) + (b × v)(2w).
fn sdf_rotate(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let b = q.xyz;
    let b2 = dot(b, b);
    return v * (q.w * q.w - b2) + b * (dot(v, b) * 2.0) + cross(b, v) * (q.w * 2.0);
}
fn sdf_max3(v: vec3<f32>) -> f32 { return max(max(v.x, v.y), v.z); }
// lane.rs sd_box
fn sd_box(p: vec3<f32>, half: vec3<f32>) -> f32 {
    let q = abs(p) - half;
    return length(max(q, vec3<f32>(0.0))) + min(sdf_max3(q), 0.0);
}
fn sd_box_part(v: vec3<f32>) -> f32 { return length(max(v, vec3<f32>(0.0))) + min(sdf_max3(v), 0.0); }
// lane.rs sd_box_frame
fn sd_box_frame(p0: vec3<f32>, half: vec3<f32>, e: f32) -> f32 {
    let p = abs(p0) - half;
    let q = abs(p + vec3<f32>(e)) - vec3<f32>(e);
    return min(min(sd_box_part(vec3<f32>(p.x, q.y, q.z)), sd_box_part(vec3<f32>(q.x, p.y, q.z))),
               sd_box_part(vec3<f32>(q.x, q.y, p.z)));
}
// lane.rs sd_cylinder
fn sd_cylinder(p: vec3<f32>, radius: f32, half_height: f32) -> f32 {
    let d = abs(vec2<f32>(length(p.xz), p.y)) - vec2<f32>(radius, half_height);
    return min(max(d.x, d.y), 0.0) + length(max(d, vec2<f32>(0.0)));
}
// lane.rs sd_capped_cone
fn sd_capped_cone(p: vec3<f32>, h: f32, r1: f32, r2: f32) -> f32 {
    let q = vec2<f32>(length(p.xz), p.y);
    let k1 = vec2<f32>(r2, h);
    let k2 = vec2<f32>(r2 - r1, 2.0 * h);
    let ca = vec2<f32>(q.x - min(q.x, select(r2, r1, q.y < 0.0)), abs(q.y) - h);
    let k2k2 = dot(k2, k2);
    var s = 0.0;
    if k2k2 > 0.0 {
        s = clamp(dot(k1 - q, k2) / k2k2, 0.0, 1.0);
    }
    let cb = q - k1 + k2 * s;
    let side = k2.x * (q.y + h) - k2.y * (q.x - r1);
    let sgn = select(1.0, -1.0, side > 0.0 && ca.y < 0.0);
    return sgn * sqrt(min(dot(ca, ca), dot(cb, cb)));
}
// lane.rs sd_octahedron
fn sd_octahedron(p0: vec3<f32>, s: f32) -> f32 {
    let p = abs(p0);
    let m = p.x + p.y + p.z - s;
    var q: vec3<f32>;
    if 3.0 * p.x < m {
        q = p;
    } else if 3.0 * p.y < m {
        q = vec3<f32>(p.y, p.z, p.x);
    } else if 3.0 * p.z < m {
        q = vec3<f32>(p.z, p.x, p.y);
    } else {
        return m * 0.57735026;
    }
    let k = clamp(0.5 * (q.z - q.y + s), 0.0, s);
    return length(vec3<f32>(q.x, q.y - s + k, q.z - k));
}
// lane.rs sd_hex_prism
fn sd_hex_prism(p0: vec3<f32>, apothem: f32, half_height: f32) -> f32 {
    let k = vec3<f32>(-0.8660254, 0.5, 0.57735026);
    var p = abs(p0);
    let f = 2.0 * min(dot(k.xy, p.xy), 0.0);
    p.x -= f * k.x;
    p.y -= f * k.y;
    let edge = vec2<f32>(p.x - clamp(p.x, -k.z * apothem, k.z * apothem), p.y - apothem);
    let sgn = select(1.0, -1.0, p.y - apothem < 0.0);
    let d = vec2<f32>(length(edge) * sgn, p.z - half_height);
    return min(max(d.x, d.y), 0.0) + length(max(d, vec2<f32>(0.0)));
}
// lane.rs shape_distance, Shape::Ellipsoid
fn sd_ellipsoid(p: vec3<f32>, radii: vec3<f32>) -> f32 {
    let k0 = length(p / radii);
    let k1 = length(p / (radii * radii));
    if k1 == 0.0 {
        return -min(min(radii.x, radii.y), radii.z);
    } else if subcone_is_finite(k0) && subcone_is_finite(k1) {
        return k0 * ((k0 - 1.0) / k1);
    }
    return length(p) - sdf_max3(radii);
}
// bounds.rs Aabb::distance
fn sdf_aabb_distance(p: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> f32 {
    return length(max(max(lo - p, p - hi), vec3<f32>(0.0)));
}
"#;

/// An f32 as a WGSL expression that parses to the same bits (NaN as a
/// quiet NaN's bits, ±∞ through the prelude's `subcone_inf()`): how every
/// constant of a generated shader is written.
pub fn f32_literal(x: f32) -> String {
    if x.is_nan() {
        "bitcast<f32>(0x7fc00000u)".into()
    } else if x == f32::INFINITY {
        "subcone_inf()".into()
    } else if x == f32::NEG_INFINITY {
        "(-subcone_inf())".into()
    } else if x.is_sign_negative() {
        format!("(-{:?}f)", -x)
    } else {
        format!("{x:?}f")
    }
}

/// A `Vec3` as a WGSL `vec3<f32>` expression of [`f32_literal`]s.
pub fn vec3_literal(v: Vec3) -> String {
    format!("vec3<f32>({}, {}, {})", f(v.x), f(v.y), f(v.z))
}

fn quat(q: Quat) -> String {
    format!("vec4<f32>({}, {}, {}, {})", f(q.x), f(q.y), f(q.z), f(q.w))
}

fn mat(m: u32) -> String {
    // Material indices are small; as f32 they are exact.
    f(m as f32)
}

struct Gen {
    out: String,
    data: Vec<[f32; 4]>,
    next: usize,
}

/// The WGSL expression of `shape`'s distance at `p` (a `vec3<f32>` in
/// scope): an inline formula, or a call of one of the generated source's
/// `sd_*` functions (the WGSL form of
/// [`subcone_scene::sdf::lane::shape_distance`], the same operations).
pub fn shape_wgsl(shape: &Shape) -> String {
    match *shape {
        Shape::Sphere { radius } => format!("length(p) - {}", f(radius)),
        Shape::Box { half } => format!("sd_box(p, {})", v3(half)),
        Shape::RoundBox { half, radius } => format!(
            "sd_box(p, {}) - {}",
            v3(half - Vec3::splat(radius)),
            f(radius)
        ),
        Shape::BoxFrame { half, thickness } => {
            format!("sd_box_frame(p, {}, {})", v3(half), f(0.5 * thickness))
        }
        Shape::Torus { major, minor } => format!(
            "length(vec2<f32>(length(p.xz) - {}, p.y)) - {}",
            f(major),
            f(minor)
        ),
        Shape::Link {
            half_length,
            major,
            minor,
        } => format!(
            "length(vec2<f32>(length(vec2<f32>(p.x, max(abs(p.y) - {}, 0.0))) - {}, p.z)) - {}",
            f(half_length),
            f(major),
            f(minor)
        ),
        Shape::Capsule {
            half_height,
            radius,
        } => format!(
            "length(vec3<f32>(p.x, p.y - clamp(p.y, {}, {}), p.z)) - {}",
            f(-half_height),
            f(half_height),
            f(radius)
        ),
        Shape::Cylinder {
            radius,
            half_height,
        } => format!("sd_cylinder(p, {}, {})", f(radius), f(half_height)),
        Shape::RoundedCylinder {
            radius,
            half_height,
            rounding,
        } => format!(
            "sd_cylinder(p, {}, {}) - {}",
            f(radius - rounding),
            f(half_height - rounding),
            f(rounding)
        ),
        Shape::CappedCone {
            half_height,
            bottom,
            top,
        } => format!(
            "sd_capped_cone(p, {}, {}, {})",
            f(half_height),
            f(bottom),
            f(top)
        ),
        Shape::Octahedron { size } => format!("sd_octahedron(p, {})", f(size)),
        Shape::HexPrism {
            apothem,
            half_height,
        } => format!(
            "sd_hex_prism(vec3<f32>(p.x, p.z, p.y), {}, {})",
            f(apothem),
            f(half_height)
        ),
        Shape::Ellipsoid { radii } => format!("sd_ellipsoid(p, {})", v3(radii)),
        Shape::Plane { normal, offset } => format!("dot(p, {}) + {}", v3(normal), f(offset)),
    }
}

impl Gen {
    fn name(&mut self, kind: &str) -> String {
        self.next += 1;
        format!("sdf_{kind}{}", self.next)
    }

    /// `SdfNode::eval` of `n` as a function `(p) -> vec2<f32>`; returns its name.
    fn eval(&mut self, n: &SdfNode) -> String {
        let own = mat(n.default_material());
        let body = match n.op() {
            Op::Shape { shape, material } => {
                format!(
                    "    return vec2<f32>({}, {});\n",
                    shape_wgsl(shape),
                    mat(*material)
                )
            }
            Op::Transform(t) => {
                let child = self.eval(&t.child);
                let mut s = Self::transform_point(t);
                let _ = write!(
                    s,
                    "    let r = {child}(q);\n    return vec2<f32>(r.x * {}, r.y);\n",
                    f(t.scale)
                );
                s
            }
            Op::Union { children, spheres } => self.eval_union(children, spheres, &own),
            Op::Intersection(children) => self.eval_intersection(children, &own),
            Op::SmoothUnion { k, children } => self.eval_smooth_union(*k, children),
            Op::Subtract(ab) => {
                let a = self.eval(&ab.0);
                let b = self.eval(&ab.1);
                format!(
                    "    let a = {a}(p);\n    let b = {b}(p);\n    \
                     if a.x >= -b.x {{ return a; }}\n    return vec2<f32>(-b.x, b.y);\n"
                )
            }
            Op::Mirror { axes, child } => self.eval_mirror(axes, child),
            Op::Repeat(r) => {
                let c = self.eval(&r.child);
                let mut s = Self::repeat_cell(r);
                let _ = write!(
                    s,
                    "    let r = {c}(q);\n    let guard = wall + {};\n    \
                     return vec2<f32>(select(r.x, guard, guard < r.x), r.y);\n",
                    f(r.margin)
                );
                s
            }
            Op::Round { radius, child } => {
                let c = self.eval(child);
                format!(
                    "    let r = {c}(p);\n    return vec2<f32>(r.x - {}, r.y);\n",
                    f(*radius)
                )
            }
            Op::Onion { thickness, child } => {
                let c = self.eval(child);
                format!(
                    "    let r = {c}(p);\n    return vec2<f32>(abs(r.x) - {}, r.y);\n",
                    f(*thickness)
                )
            }
            Op::ScaleDistance { factor, child } => {
                let c = self.eval(child);
                format!(
                    "    let r = {c}(p);\n    return vec2<f32>(r.x * {}, r.y);\n",
                    f(*factor)
                )
            }
            Op::Displace {
                amplitude,
                frequency,
                child,
            } => {
                let c = self.eval(child);
                format!(
                    "    let r = {c}(p);\n    let s = p * {};\n    \
                     return vec2<f32>(r.x + {} * sin(s.x) * sin(s.y) * sin(s.z), r.y);\n",
                    f(*frequency),
                    f(*amplitude)
                )
            }
            Op::Bounded { pad, child } => {
                let c = self.eval(child);
                let b = child.bounds();
                format!(
                    "    let b = sdf_aabb_distance(p, {}, {});\n    \
                     if b > {} {{ return vec2<f32>(b, {own}); }}\n    return {c}(p);\n",
                    v3(b.min),
                    v3(b.max),
                    f(*pad)
                )
            }
            Op::Scatter(sc) => {
                let split = self.scatter(sc);
                format!("    let r = {split}(p);\n    return r.xz;\n")
            }
        };
        let name = self.name("eval");
        let _ = write!(
            self.out,
            "fn {name}(p: vec3<f32>) -> vec2<f32> {{\n{body}}}\n"
        );
        name
    }

    /// `Transform`'s point in the child's frame: declares `q`.
    fn transform_point(t: &Transform) -> String {
        let mut s = format!(
            "    var q = (p - {}) * {};\n",
            v3(t.translation),
            f(t.inv_scale)
        );
        if t.rotated {
            let _ = writeln!(s, "    q = sdf_rotate({}, q);", quat(t.inv_rotation));
        }
        s
    }

    /// A union's `eval` body: the nearest child.
    fn eval_union(&mut self, children: &[SdfNode], spheres: &[Vec4], own: &str) -> String {
        let names: Vec<String> = children.iter().map(|c| self.eval(c)).collect();
        let mut s = format!("    var best = vec2<f32>(subcone_inf(), {own});\n");
        for (name, sp) in names.iter().zip(spheres) {
            // A child whose bounding sphere is no nearer than the best so far is skipped.
            let _ = write!(
                s,
                "    {{\n        let reach = best.x + {};\n        let dp = p - {};\n        \
                 if !(reach >= 0.0 && dot(dp, dp) >= reach * reach) {{\n            \
                 let r = {name}(p);\n            if r.x < best.x {{ best = r; }}\n        }}\n    }}\n",
                f(sp.w),
                v3(sp.truncate())
            );
        }
        s.push_str("    return best;\n");
        s
    }

    /// An intersection's `eval` body: the farthest child.
    fn eval_intersection(&mut self, children: &[SdfNode], own: &str) -> String {
        let names: Vec<String> = children.iter().map(|c| self.eval(c)).collect();
        let mut s = format!("    var best = vec2<f32>(-subcone_inf(), {own});\n");
        for name in names {
            let _ = writeln!(
                s,
                "    {{ let r = {name}(p); if r.x > best.x {{ best = r; }} }}"
            );
        }
        s.push_str("    return best;\n");
        s
    }

    /// A smooth union's `eval` body: the children folded in order.
    fn eval_smooth_union(&mut self, k: f32, children: &[SdfNode]) -> String {
        let names: Vec<String> = children.iter().map(|c| self.eval(c)).collect();
        let mut s = format!("    var acc = {}(p);\n", names[0]);
        for name in &names[1..] {
            let _ = write!(
                s,
                "    {{\n        let r = {name}(p);\n        \
                 let h = max({k} - abs(acc.x - r.x), 0.0) / {k};\n        \
                 let m = select(acc.y, r.y, r.x < acc.x);\n        \
                 acc = vec2<f32>(min(acc.x, r.x) - 0.25 * {k} * h * h, m);\n    }}\n",
                k = f(k)
            );
        }
        s.push_str("    return acc;\n");
        s
    }

    /// A mirror's `eval` body: the child at `p` with the axes mirrored.
    fn eval_mirror(&mut self, axes: &[bool; 3], child: &SdfNode) -> String {
        let c = self.eval(child);
        let mut s = "    var q = p;\n".to_string();
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            if axes[k] {
                let _ = writeln!(s, "    q.{axis} = abs(q.{axis});");
            }
        }
        let _ = writeln!(s, "    return {c}(q);");
        s
    }

    /// `Repeat::cell`: declares `q` and `wall`.
    fn repeat_cell(r: &Repeat) -> String {
        let mut s = "    var q = p;\n    var wall = subcone_inf();\n".to_string();
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let c = r.period[k];
            if c > 0.0 {
                s.push_str(&Self::repeat_axis(axis, c, r.lo[k], r.hi[k], r.guard));
            }
        }
        s
    }

    /// One repeated axis of [`Gen::repeat_cell`], a block of its own: the
    /// cell index `i` (period `c`, limits `lo..=hi`), the point in the cell,
    /// and (`guard`) the walls that have a neighbouring cell.
    fn repeat_axis(axis: &str, c: f32, lo: f32, hi: f32, guard: bool) -> String {
        let (c, lo, hi) = (f(c), f(lo), f(hi));
        let walls = if guard {
            format!(
                "        if i < {hi} {{ wall = min(wall, 0.5 * {c} - q.{axis}); }}\n        \
                 if i > {lo} {{ wall = min(wall, 0.5 * {c} + q.{axis}); }}\n"
            )
        } else {
            String::new()
        };
        format!(
            "    {{\n        let i = min(max(floor(p.{axis} / {c} + 0.5), {lo}), {hi});\n        \
             q.{axis} = p.{axis} - {c} * i;\n{walls}    }}\n"
        )
    }

    /// `Scatter::eval_split` as a function `(p) -> vec3<f32>`; returns its name.
    fn scatter(&mut self, sc: &Scatter) -> String {
        let templates: Vec<String> = sc.templates.iter().map(|t| self.eval(t)).collect();
        let base = self.scatter_table(sc);
        let mut s = Self::scatter_cell(sc);
        s.push_str(&Self::scatter_instance(sc, base, templates.len()));
        s.push_str(&Self::scatter_dispatch(&templates));
        let name = self.name("scatter");
        let _ = write!(self.out, "fn {name}(p: vec3<f32>) -> vec3<f32> {{\n{s}}}\n");
        name
    }

    /// Appends the scatter's instance table to `sdf_data`, three `vec4`s a
    /// cell; returns where it starts.
    fn scatter_table(&mut self, sc: &Scatter) -> usize {
        let base = self.data.len();
        for i in &sc.instances {
            let q = i.inv_rotation;
            self.data.push([q.x, q.y, q.z, q.w]);
            self.data
                .push([i.offset.x, i.offset.y, i.offset.z, i.scale]);
            self.data.push([
                i.inv_scale,
                i.radius,
                f32::from_bits(i.template),
                f32::from_bits(i.material),
            ]);
        }
        base
    }

    /// The cell of `p`, clamped to the grid: declares `fi` (its index), `q`
    /// (the point in it) and `wall` (the distance to the walls that have a
    /// neighbouring cell).
    fn scatter_cell(sc: &Scatter) -> String {
        let (origin, cell, inv_cell, lo, hi) = (sc.origin, sc.cell, sc.inv_cell, sc.lo, sc.hi);
        let mut s = format!(
            "    let rel = p - {origin};\n    let fc = rel * {inv_cell};\n    \
             let fi = min(max(floor(fc + vec3<f32>(0.5)), {lo}), {hi});\n    \
             let q = rel - fi * {cell};\n    var wall = subcone_inf();\n",
            origin = v3(origin),
            inv_cell = v3(inv_cell),
            lo = v3(lo),
            hi = v3(hi),
            cell = v3(cell),
        );
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let _ = writeln!(
                s,
                "    if fi.{axis} < {hi} {{ wall = min(wall, 0.5 * {c} - q.{axis}); }}\n    \
                 if fi.{axis} > {lo} {{ wall = min(wall, 0.5 * {c} + q.{axis}); }}",
                c = f(cell[k]),
                lo = f(lo[k]),
                hi = f(hi[k])
            );
        }
        s
    }

    /// The cell's instance, read from the table at `base`: returns the bound
    /// where the cell is empty or `p` is outside the instance's sphere;
    /// otherwise declares `lp`, `p` in the instance's frame.
    fn scatter_instance(sc: &Scatter, base: usize, template_count: usize) -> String {
        let lo = sc.lo;
        let dims = sc.dims;
        let count = sc.instances.len();
        let default = mat(sc.default_material);
        format!(
            "    let guard = wall + {margin};\n    let ii = fi - {lo};\n    \
             let idx = u32(ii.x) + {d0}u * (u32(ii.y) + {d1}u * u32(ii.z));\n    \
             if idx >= {count}u {{ return vec3<f32>(guard, subcone_inf(), {default}); }}\n    \
             let ia = sdf_data[{base}u + 3u * idx];\n    \
             let ib = sdf_data[{base}u + 3u * idx + 1u];\n    \
             let ic = sdf_data[{base}u + 3u * idx + 2u];\n    \
             let tpl = bitcast<u32>(ic.z);\n    let material = bitcast<u32>(ic.w);\n    \
             if tpl >= {nt}u {{ return vec3<f32>(guard, subcone_inf(), {default}); }}\n    \
             let local = q - ib.xyz;\n    \
             let own = select(f32(material), {default}, material == 0xffffffffu);\n    \
             let sphere = length(local) - ic.y;\n    \
             if sphere >= guard {{ return vec3<f32>(guard, sphere, own); }}\n    \
             let lp = sdf_rotate(ia, local) * ic.x;\n",
            margin = f(sc.margin),
            lo = v3(lo),
            d0 = dims[0],
            d1 = dims[1],
            nt = template_count,
        )
    }

    /// The instance's template at `lp`, scaled back: the guard caps the safe
    /// step, and the instance's material, if any, is the object's.
    fn scatter_dispatch(templates: &[String]) -> String {
        let mut cases = String::new();
        for (i, t) in templates.iter().enumerate() {
            let _ = writeln!(cases, "        case {i}u: {{ r = {t}(lp); }}");
        }
        format!(
            "    var r = vec2<f32>(0.0);\n    switch tpl {{\n{cases}        default: {{}}\n    }}\n    \
             let d = r.x * ib.w;\n    \
             let m = select(f32(material), r.y, material == 0xffffffffu);\n    \
             return vec3<f32>(min(guard, d), d, m);\n"
        )
    }

    /// `SdfNode::eval_split` of `n` as a function `(p) -> vec3<f32>`.
    fn split(&mut self, n: &SdfNode) -> String {
        let own = mat(n.default_material());
        let body = match n.op() {
            Op::Shape { shape, material } => format!(
                "    let d = {};\n    return vec3<f32>(d, d, {});\n",
                shape_wgsl(shape),
                mat(*material)
            ),
            Op::Transform(t) => {
                let child = self.split(&t.child);
                let mut s = Self::transform_point(t);
                let _ = write!(
                    s,
                    "    let r = {child}(q);\n    return vec3<f32>(r.x * {sc}, r.y * {sc}, r.z);\n",
                    sc = f(t.scale)
                );
                s
            }
            Op::Union { children, spheres } => {
                let names: Vec<String> = children.iter().map(|c| self.split(c)).collect();
                let mut s = format!(
                    "    var safe = subcone_inf();\n    var surf = subcone_inf();\n    var mat = {own};\n"
                );
                for (name, sp) in names.iter().zip(spheres) {
                    let _ = write!(
                        s,
                        "    {{\n        let reach = surf + {w};\n        let dp = p - {c};\n        \
                         let d2 = dot(dp, dp);\n        \
                         if reach >= 0.0 && d2 >= reach * reach {{\n            \
                         safe = min(safe, sqrt(d2) - {w});\n        }} else {{\n            \
                         let r = {name}(p);\n            safe = min(safe, r.x);\n            \
                         if r.y < surf {{ surf = r.y; mat = r.z; }}\n        }}\n    }}\n",
                        w = f(sp.w),
                        c = v3(sp.truncate())
                    );
                }
                s.push_str("    return vec3<f32>(min(safe, surf), surf, mat);\n");
                s
            }
            Op::Repeat(r) if r.guard => {
                let c = self.split(&r.child);
                let mut s = Self::repeat_cell(r);
                let _ = write!(
                    s,
                    "    let r = {c}(q);\n    return vec3<f32>(min(r.x, wall + {}), r.y, r.z);\n",
                    f(r.margin)
                );
                s
            }
            Op::Scatter(sc) => {
                let name = self.scatter(sc);
                format!("    return {name}(p);\n")
            }
            Op::Bounded { pad, child } => {
                let c = self.split(child);
                let b = child.bounds();
                format!(
                    "    let b = sdf_aabb_distance(p, {}, {});\n    let r = {c}(p);\n    \
                     if b > {} {{ return vec3<f32>(min(max(r.x, b), r.y), r.y, r.z); }}\n    \
                     return r;\n",
                    v3(b.min),
                    v3(b.max),
                    f(*pad)
                )
            }
            _ => {
                let e = self.eval(n);
                format!("    let r = {e}(p);\n    return vec3<f32>(r.x, r.x, r.y);\n")
            }
        };
        let name = self.name("split");
        let _ = write!(
            self.out,
            "fn {name}(p: vec3<f32>) -> vec3<f32> {{\n{body}}}\n"
        );
        name
    }
}

impl WgslField {
    /// Compile the tree `root` to WGSL (see the [module docs](self)).
    pub fn compile(root: &SdfNode) -> WgslField {
        let mut g = Gen {
            out: String::from(PRELUDE),
            data: Vec::new(),
            next: 0,
        };
        let e = g.eval(root);
        let s = g.split(root);
        let _ = write!(
            g.out,
            "// SdfNode::eval\nfn scene_sdf(p: vec3<f32>) -> vec2<f32> {{ return {e}(p); }}\n\
             // SdfNode::eval_split\nfn scene_sdf_split(p: vec3<f32>) -> vec3<f32> {{ return {s}(p); }}\n"
        );
        WgslField {
            source: g.out,
            data: g.data,
        }
    }
}
