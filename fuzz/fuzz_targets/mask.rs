//! Visibility masks (§3.4–3.5, eq. 7–8) and their correlation along a ray.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{unit, v2, v3};
use glam::{Vec2, Vec3};
use libfuzzer_sys::fuzz_target;
use subcone_kernels::mask::{
    cell_centre, half_plane, half_plane_mask, mask_weight, occlusion_to_distance, project_normal,
    visibility_mask, MaskPlacement, VisibilityAccumulator, FULL_MASK,
};

const PLACEMENTS: [MaskPlacement; 3] = [
    MaskPlacement::Derived,
    MaskPlacement::AuthorsCode,
    MaskPlacement::PaperEq8,
];

#[derive(Arbitrary, Debug)]
enum AccItem {
    Raw(u32),
    Mask {
        occlusion: f32,
        normal: [f32; 3],
        placement: u32,
    },
}

#[derive(Arbitrary, Debug)]
struct Input {
    occlusion: f32,
    /// A raw projected normal (any length, any value).
    projected: [f32; 2],
    /// A raw 3D normal, projected on the fixed frame right = X, up = Y.
    normal: [f32; 3],
    placement: u32,
    dir: [f32; 2],
    h: f32,
    bit: u32,
    acc: Vec<AccItem>,
}

/// Projected normals the input offers.
fn normals(x: &Input) -> [Vec2; 3] {
    [
        v2(x.projected),
        project_normal(v3(x.normal), Vec3::X, Vec3::Y),
        // The 3D normal's own (x, y), unnormalised: any length.
        Vec2::new(x.normal[0], x.normal[1]),
    ]
}

fuzz_target!(|x: Input| {
    // No panic anywhere, for anything.
    let _ = visibility_mask(x.occlusion, v2(x.projected), MaskPlacement::from_u32(x.placement));
    let _ = half_plane_mask(v2(x.dir), x.h);
    let _ = half_plane(x.occlusion, v2(x.projected), MaskPlacement::from_u32(x.placement));
    let c = cell_centre(x.bit);
    assert!(c.is_finite() && c.abs().max_element() < 1.0);
    if x.occlusion.is_nan() {
        for p in PLACEMENTS {
            assert!(visibility_mask(x.occlusion, v2(x.projected), p) == 0);
        }
    }

    // project_normal: finite, (0, 0) for an unusable normal, else the (x, y) of
    // the unit normal up to rounding (so |n_p| ≤ 1 up to rounding).
    let n3 = v3(x.normal);
    let np3 = project_normal(n3, Vec3::X, Vec3::Y);
    assert!(np3.is_finite(), "project_normal({n3:?}) = {np3:?}");
    match unit(n3) {
        None => assert!(np3 == Vec2::ZERO, "project_normal({n3:?}) = {np3:?}"),
        Some(u) => {
            // However long or short the normal: the kernel scales by its
            // largest component before normalising.
            let expect = Vec2::new(u.x, u.y);
            assert!(
                (np3 - expect).abs().max_element() <= 1e-6,
                "project_normal({n3:?}) = {np3:?}, expected {expect:?}"
            );
            assert!(
                np3.length() <= 1.0 + 1e-6,
                "project_normal({n3:?}) = {np3:?} longer than 1"
            );
        }
    }

    // Derived placement: empty at ω ≤ 0.0140 and full at ω > 0.9861, for every
    // projected normal of length ≤ 1 (or none).
    if x.occlusion.is_finite() {
        let w = x.occlusion;
        for np in normals(&x) {
            if !np.is_finite() || np.length() > 1.0 {
                continue;
            }
            let m = visibility_mask(w, np, MaskPlacement::Derived);
            if w <= 0.0140 {
                assert!(m == 0, "mask({w}, {np:?}) = {m:#010x}, expected empty");
            }
            if w > 0.9861 {
                assert!(m == FULL_MASK, "mask({w}, {np:?}) = {m:#010x}, expected full");
            }
        }
    }

    // Complement symmetry: (ω, n) and (1 − ω, −n) split the disk along the same
    // line, so they differ from complements only by ties at cell centres, at most
    // one cell per row (a whole row when the boundary is horizontal): 6 bits.
    // The pair is a complement only if f32 keeps it one: `1 − ω` rounds for
    // some ω < 0.5 (ω = 0.5 − 2⁻²⁵ gives exactly 0.5), and the derived
    // placement divides the resulting `d/R_c` mismatch by `|n_p|`, so a tiny
    // projected normal turns an ulp into the whole disk. So the pair is taken
    // from ω or, failing that, from ω' = 1 − ω (exact for ω' in [0.5, 1]), and
    // checked only when `d/R_c = 1 − 2ω` of its two halves is exactly mirrored.
    let exact_pair = |w: f32| occlusion_to_distance(1.0 - w) == -occlusion_to_distance(w);
    let w = if exact_pair(x.occlusion) {
        x.occlusion
    } else {
        1.0 - x.occlusion
    };
    if w.is_finite() && exact_pair(w) {
        for np in normals(&x) {
            if !np.is_finite() {
                continue;
            }
            // A fronto-parallel surface (no direction) at exactly d = 0 (ω = 0.5,
            // whose complement is itself) is a tie over the whole disk: both
            // masks are full by the documented rule. Excluded as a tie, not a bug.
            let fronto = half_plane(w, np, MaskPlacement::Derived).is_none();
            if fronto && w >= 0.5 && 1.0 - w >= 0.5 {
                continue;
            }
            for p in PLACEMENTS {
                let a = visibility_mask(w, np, p);
                let b = visibility_mask(1.0 - w, -np, p);
                let overlap = (a & b).count_ones();
                let missing = (!(a | b)).count_ones();
                assert!(
                    overlap <= 6 && missing <= 6,
                    "{p:?}: mask({w}, {np:?}) = {a:#034b} and mask({}, {:?}) = {b:#034b}: \
                     overlap {overlap}, missing {missing}",
                    1.0 - w,
                    -np
                );
            }
        }
    }

    // Correlation: disjoint visible masks, M only grows, weights sum to ≤ 1.
    let mut acc = VisibilityAccumulator::new();
    let mut seen = 0u32;
    let mut union = 0u32;
    let mut weight = 0.0f32;
    for item in x.acc.iter().take(64) {
        let m = match *item {
            AccItem::Raw(m) => m,
            AccItem::Mask {
                occlusion,
                normal,
                placement,
            } => visibility_mask(
                occlusion,
                project_normal(v3(normal), Vec3::X, Vec3::Y),
                MaskPlacement::from_u32(placement),
            ),
        };
        let before = acc.covered();
        let visible = acc.add(m);
        let after = acc.covered();
        assert!(visible & seen == 0, "visible {visible:#x} overlaps earlier {seen:#x}");
        assert!(visible & !m == 0, "visible {visible:#x} not within the mask {m:#x}");
        assert!(after & before == before, "M shrank: {before:#x} -> {after:#x}");
        seen |= visible;
        union |= m;
        weight += mask_weight(visible);
        assert!(weight <= 1.0, "visible weights sum to {weight}");
        assert!(after == union && after == seen);
        assert!(acc.covered_bits() == after.count_ones());
        let u = acc.uncovered_weight();
        assert!((0.0..=1.0).contains(&u) && (u + mask_weight(after) - 1.0).abs() < 1e-6);
    }
});
