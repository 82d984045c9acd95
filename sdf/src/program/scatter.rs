//! The lane-wise union culling and scatter evaluation the interpreter's
//! steps call.

use super::*;

/// A union's bound culling of one child against the accumulator `acc`, in
/// the `active` lanes: the lanes that must evaluate the child. A split union takes the skipped child's sphere distance
/// into its safe step, as the tree does.
#[inline(always)]
pub(super) fn cull(sphere: &Vec4, p: &V3, acc: &mut Value, active: W8, split: bool) -> W8 {
    let c = V3::splat(sphere.truncate());
    let d2 = {
        let e = p.sub(c);
        e.dot(e)
    };
    let reach = acc.surf + sphere.w;
    // `&`, not `&&`: lane-wise masks without branches.
    let skipped = active.and(W8::from_fn(|k| {
        (reach.0[k] >= 0.0) & (d2.0[k] >= reach.0[k] * reach.0[k])
    }));
    if split && skipped.any() {
        let bound = d2.sqrt() - sphere.w;
        acc.safe = skipped.select(acc.safe.min(bound), acc.safe);
    }
    active.and_not(skipped)
}

/// `Scatter::split` (or its `eval` bound) lane-wise: each lane's cell and
/// instance, then each distinct template among the lanes that reach their
/// object, run once over those lanes.
#[inline(always)]
pub(super) fn scatter_lanes(
    sc: &Scatter,
    templates: &[SdfProgram<'_>],
    p: V3,
    active: LaneMask,
    nested: &mut Option<Box<Scratch>>,
    split: bool,
) -> Value {
    let (q, guard, idx) = scatter_cell(sc, p);
    // Gather each lane's instance: a lane with none (inactive, outside the
    // table, or an unknown template) reads `NONE`, whose zeros are what the
    // lanes without an instance carry. Each field is built lane by lane in
    // registers, not stored per lane and reloaded as a vector (which stalls
    // store forwarding). The gather stays in this function: moved to a
    // helper, even inlined, it changed the code of the interpreter loop
    // this function is inlined into, and every SDF scene measured slower.
    let lookup = |k: usize| match sc.instances.get(idx[k] as usize) {
        Some(i) if (i.template as usize) < sc.templates.len() => i,
        _ => &NONE,
    };
    // Neighbouring rays are mostly in one cell: when every active lane is,
    // its instance is read once and broadcast (the same values in every
    // lane, so the same bits as the lane-by-lane gather).
    let lead = (active.trailing_zeros() as usize).min(LANES - 1);
    let shared = (0..LANES).all(|k| active & (1 << k) == 0 || idx[k] == idx[lead]);
    let one = shared.then(|| lookup(lead));
    let act = W8::of_bits(active);
    let inst: [&Instance; LANES] = each_lane!(|k| {
        if active & (1 << k) == 0 {
            &NONE
        } else if let Some(i) = one {
            i
        } else {
            lookup(k)
        }
    });
    let field = |f: fn(&Instance) -> f32| match one {
        Some(i) => act.select(F8::splat(f(i)), F8::splat(f(&NONE))),
        None => F8(each_lane!(|k| f(inst[k]))),
    };
    let off = [
        field(|i| i.offset.x),
        field(|i| i.offset.y),
        field(|i| i.offset.z),
    ];
    let rot = [
        field(|i| i.inv_rotation.x),
        field(|i| i.inv_rotation.y),
        field(|i| i.inv_rotation.z),
        field(|i| i.inv_rotation.w),
    ];
    let (radius, scale, inv_scale) = (
        field(|i| i.radius),
        field(|i| i.scale),
        field(|i| i.inv_scale),
    );
    let template: [u32; LANES] = each_lane!(|k| inst[k].template);
    let inst_mat: [u32; LANES] = each_lane!(|k| inst[k].material);
    let own: [u32; LANES] = each_lane!(|k| {
        if inst_mat[k] != EMPTY {
            inst_mat[k]
        } else {
            sc.default_material
        }
    });
    let local = q.sub(V3::new(off[0], off[1], off[2]));
    let sphere = local.length() - radius;
    let has = W8::from_fn(|k| template[k] != EMPTY);
    // No instance: `(guard, ∞, default)`; far from the object: its sphere.
    let mut out = Value {
        safe: guard,
        surf: F8::select(has, sphere, F8::splat(f32::INFINITY)),
        mat: own,
    };
    let reach = active & has.and_not(sphere.ge(guard)).bits();
    if reach != 0 {
        let tp = local.rotate_lanes(rot).scale(inv_scale);
        let scratch = nested.get_or_insert_with(|| templates_scratch(templates));
        let mut left = reach;
        while left != 0 {
            let first = left.trailing_zeros() as usize;
            let t = template[first];
            let mut lanes = 0u8;
            for (k, tk) in template.iter().enumerate() {
                if left & (1 << k) != 0 && *tk == t {
                    lanes |= 1 << k;
                }
            }
            left &= !lanes;
            let Some(prog) = templates.get(t as usize) else {
                continue;
            };
            let v = prog.run::<true>(tp, lanes, scratch);
            let d = v.surf * scale;
            let m = W8::from_fn(|k| inst_mat[k] == EMPTY).select_u(v.mat, inst_mat);
            let sel = W8::of_bits(lanes);
            out.safe = F8::select(sel, guard.min(d), out.safe);
            out.surf = F8::select(sel, d, out.surf);
            out.mat = sel.select_u(m, out.mat);
        }
    }
    if !split {
        // `eval`: the bound alone.
        out.surf = out.safe;
    }
    out
}

/// Each lane's cell of the scatter's grid: the point `p` relative to the
/// cell's centre, the guard (how far the point may move without leaving the
/// cell, through the walls it shares with other cells, plus the margin), and
/// the cell's index in the instance table.
#[inline(always)]
fn scatter_cell(sc: &Scatter, p: V3) -> (V3, F8, [i32; LANES]) {
    let rel = p.sub(V3::splat(sc.origin));
    let f = rel.mul(V3::splat(sc.inv_cell));
    let f = V3::new(round_cell(f.x), round_cell(f.y), round_cell(f.z));
    // glam's `clamp`: `max(lo).min(hi)` by comparisons.
    let lo = V3::splat(sc.lo);
    let hi = V3::splat(sc.hi);
    let f = {
        let m = f.gmax(lo);
        V3::new(m.x.gmin(hi.x), m.y.gmin(hi.y), m.z.gmin(hi.z))
    };
    let q = rel.sub(f.mul(V3::splat(sc.cell)));
    let mut wall = F8::splat(f32::INFINITY);
    let (fa, qa) = ([f.x, f.y, f.z], [q.x, q.y, q.z]);
    for k in 0..3 {
        let below = fa[k].lt(F8::splat(sc.hi[k]));
        wall = F8::select(below, wall.min(0.5 * sc.cell[k] - qa[k]), wall);
        let above = fa[k].gt(F8::splat(sc.lo[k]));
        wall = F8::select(above, wall.min(0.5 * sc.cell[k] + qa[k]), wall);
    }
    let guard = wall + sc.margin;
    let i = f.sub(lo);

    // The cell's index: `i` is clamped to the grid (NaN to its first cell),
    // so every term is an integer below 2¹⁸ and exact in `f32`.
    let idx: [i32; LANES] = {
        let f = i.x + sc.dims[0] as f32 * (i.y + sc.dims[1] as f32 * i.z);
        each_lane!(|k| f.0[k] as i32)
    };
    (q, guard, idx)
}

/// A template or material index that names none.
const EMPTY: u32 = u32::MAX;

/// The instance a lane without one reads: its zeros are what such lanes
/// carry.
const NONE: Instance = Instance {
    template: EMPTY,
    material: EMPTY,
    inv_rotation: Quat::from_xyzw(0.0, 0.0, 0.0, 0.0),
    offset: Vec3::ZERO,
    scale: 0.0,
    inv_scale: 0.0,
    radius: 0.0,
};

/// The scratch the templates of a scatter run in, deep enough for the
/// deepest of them.
#[inline(always)]
fn templates_scratch(templates: &[SdfProgram<'_>]) -> Box<Scratch> {
    let d = templates
        .iter()
        .map(|t| t.depth)
        .fold([0; 4], |a, b| core::array::from_fn(|k| a[k].max(b[k])));
    Box::new(Scratch::with_depth(d))
}
