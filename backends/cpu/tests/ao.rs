//! Ambient occlusion (`RenderSettings::ao_rays`) on the CPU backend: off
//! changes nothing, the unoccluded fraction is in [0, 1] and never rises
//! when occluders are added, the rays are counted, on triangle and SDF
//! scenes.
use glam::{Vec2, Vec3};
use subcone_cpu::shade::{Counts, Surface, Tracer};
use subcone_cpu::CpuBackend;
use subcone_scene::{
    builtin::builtin, Backend, Camera, Frame, Material, Method, RenderSettings, Scene, TriangleMesh,
};

fn render(scene: &Scene, method: &str, w: u32, h: u32, ao: u32) -> Frame {
    let m: Method = method.parse().unwrap();
    let mut s = RenderSettings::new(w, h);
    s.ao_rays = ao;
    CpuBackend::new()
        .render(scene, &scene.camera, &m, &s)
        .unwrap_or_else(|e| panic!("{method} --ao {ao}: {e}"))
}

/// FNV-1a over the bits of every colour channel.
fn frame_hash(f: &Frame) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for c in &f.color {
        for v in [c.x, c.y, c.z] {
            for b in v.to_bits().to_le_bytes() {
                h ^= b as u64;
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}

/// With AO off (the default), cornell at 32×24 is bit for bit the image of
/// the code before ambient occlusion existed: the hashes below were taken
/// from commit ed65dae (the parent of the AO change). NoAA's and SSAA's were
/// re-taken when hit reconstruction switched to the intersector's
/// barycentrics, a change of the hit alone that left every AO line as it
/// was (FXAA's image at this size kept its bits). SRAA and SRAA-RT
/// reach the same `Tracer::parts` with `ao = 1` (and were compared bit for
/// bit with that commit when AO was added), but are not pinned here: their
/// reconstruction is tuned independently of the shading, and a pinned hash
/// would fail on every such change.
#[test]
fn ao_off_changes_no_bit() {
    let scene = builtin("cornell").unwrap();
    let mut changed = Vec::new();
    for (method, before) in [
        ("noaa", 0x6df0_df39_8385_bde6u64),
        ("ssaa4", 0x2550_23d9_98d2_c91c),
        ("fxaa", 0x31cc_b91e_b12c_dac2),
    ] {
        let f = render(&scene, method, 32, 24, 0);
        if frame_hash(&f) != before {
            changed.push(format!("{method}: {:#x}", frame_hash(&f)));
        }
        assert_eq!(f.stats.rays.ao, 0, "{method}: AO rays with AO off");
    }
    assert!(
        changed.is_empty(),
        "the AO-off images changed (new hashes: {}); if shading changed on purpose, update the hashes",
        changed.join(", ")
    );
}

/// AO only darkens: every channel of every pixel of an AO frame is at most
/// the AO-off frame's (the ambient term times a fraction in [0, 1], the
/// rest unchanged, every operation monotone under rounding), some pixels
/// strictly; and it casts at most N rays per shaded primary hit.
#[test]
fn ao_only_darkens_and_is_counted() {
    let scene = builtin("cornell").unwrap();
    for method in ["noaa", "ssaa4", "sraa-rt"] {
        let off = render(&scene, method, 32, 24, 0);
        let on = render(&scene, method, 32, 24, 4);
        for (a, b) in on.color.iter().zip(&off.color) {
            assert!(a.cmple(*b).all(), "{method}: AO brightened {b} to {a}");
        }
        assert!(
            on.color.iter().zip(&off.color).any(|(a, b)| a != b),
            "{method}: AO changed nothing"
        );
        let r = on.stats.rays;
        assert!(r.ao > 0 && r.ao <= 4 * r.primary, "{method}: {r:?}");
        assert_eq!(r.primary, off.stats.rays.primary);
        assert_eq!(r.total(), off.stats.rays.total() + r.ao, "{method}");
    }
}

/// A floor, and optionally walls around the origin, all flat.
fn room(walls: usize) -> Scene {
    let mut mesh = TriangleMesh::default();
    let f = 5.0;
    mesh.push_quad(
        [
            Vec3::new(-f, 0.0, -f),
            Vec3::new(-f, 0.0, f),
            Vec3::new(f, 0.0, f),
            Vec3::new(f, 0.0, -f),
        ],
        0,
    );
    // Walls through x = 0 (facing +x) and z = 0 (facing +z), and a low
    // ceiling over the corner: each adds occluders near the corner point.
    let quads = [
        [
            Vec3::new(0.0, 0.0, -f),
            Vec3::new(0.0, 2.0, -f),
            Vec3::new(0.0, 2.0, f),
            Vec3::new(0.0, 0.0, f),
        ],
        [
            Vec3::new(-f, 0.0, 0.0),
            Vec3::new(f, 0.0, 0.0),
            Vec3::new(f, 2.0, 0.0),
            Vec3::new(-f, 2.0, 0.0),
        ],
        [
            Vec3::new(0.0, 0.3, 0.0),
            Vec3::new(0.0, 0.3, 1.0),
            Vec3::new(1.0, 0.3, 1.0),
            Vec3::new(1.0, 0.3, 0.0),
        ],
    ];
    for q in quads.iter().take(walls) {
        mesh.push_quad(*q, 0);
    }
    let camera = Camera::look_at(Vec3::new(3.0, 3.0, 3.0), Vec3::ZERO, Vec3::Y, 0.8).unwrap();
    Scene::triangles(
        "room",
        mesh,
        vec![Material::diffuse("grey", Vec3::splat(0.5))],
        vec![],
        camera,
    )
    .unwrap()
}

/// The unoccluded fraction at `p` on the floor (normal +y), with `n` rays
/// of length 1.
fn ao_at(scene: &Scene, p: Vec3, n: u32) -> f32 {
    let backend = CpuBackend::new();
    let bvh = backend.bvh(scene).unwrap();
    let mesh = scene.mesh().unwrap();
    let mut t = Tracer::new(&bvh, scene, mesh, &scene.camera, 1);
    t.ao_rays = n;
    // The same radius in every scene (the default follows the bounds).
    t.ao_radius = 1.0;
    let s = Surface {
        p,
        n: Vec3::Y,
        ng: Vec3::Y,
        uv: Vec2::ZERO,
        material: 0,
        t: 1.0,
    };
    t.ambient_occlusion(&s, &mut Counts::default())
}

#[test]
fn ao_is_a_fraction_that_occluders_only_lower() {
    let corner = Vec3::new(0.1, 0.0, 0.1);
    let open = Vec3::new(3.0, 0.0, 3.0);
    for n in [1, 4, 16, 64] {
        let mut last = 1.0f32;
        for walls in 0..=3 {
            let scene = room(walls);
            let c = ao_at(&scene, corner, n);
            let o = ao_at(&scene, open, n);
            assert!((0.0..=1.0).contains(&c), "{n} rays, {walls} walls: {c}");
            // Far from every wall, nothing occludes within the radius.
            assert_eq!(o, 1.0, "{n} rays, {walls} walls: open floor {o}");
            assert!(c <= last, "{n} rays: {walls} walls raised AO {last} → {c}");
            last = c;
        }
        // Two walls and a ceiling over the corner hide most of the sky.
        if n >= 4 {
            assert!(last < 0.5, "{n} rays: corner AO {last}");
        }
        // Off: exactly 1, whatever the occluders.
        assert_eq!(ao_at(&room(3), corner, 0), 1.0);
    }
}

#[test]
fn ao_settings_are_checked() {
    let mut s = RenderSettings::new(8, 8);
    s.ao_rays = subcone_scene::backend::MAX_AO_RAYS;
    assert!(s.validate().is_ok());
    s.ao_rays += 1;
    let e = s.validate().unwrap_err().to_string();
    assert!(e.contains("at most 256"), "{e}");
}

/// Ambient occlusion on an SDF scene: every SDF method casts its rays (one
/// per direction per shaded sample at most), never brightens a pixel and
/// darkens the frame. (With AO off the scalar path multiplies the ambient
/// term by exactly 1 and the packets, which have no occlusion, must give its
/// frames bit for bit: `tests/packets.rs`.)
#[test]
fn ao_on_sdf_scenes_darkens() {
    let scene = builtin("primitives").unwrap();
    let radius = scene.sdf_geometry().unwrap().ao_radius();
    // The objects' box (about 9.5 × 1.7 × 6.9), not the infinite floor.
    assert!(radius > 0.5 && radius < 2.0, "AO radius {radius}");
    for method in ["noaa", "ssaa4", "sraa-rt", "ctss", "ctss-r"] {
        let plain = render(&scene, method, 32, 24, 0);
        assert_eq!(plain.stats.rays.ao, 0, "{method}: AO rays with AO off");
        let ao = render(&scene, method, 32, 24, 8);
        let rays = ao.stats.rays.ao;
        assert!(
            rays > 0 && rays <= 8 * ao.stats.shaded_samples,
            "{method}: {rays} AO rays for {} shaded samples",
            ao.stats.shaded_samples
        );
        let mut darker = 0;
        for (i, (a, p)) in ao.color.iter().zip(&plain.color).enumerate() {
            // SRAA-RT's reconstruction mixes neighbours by weights that do
            // not depend on the colour: darker layers give a darker pixel,
            // up to rounding.
            assert!(
                a.cmple(*p + Vec3::splat(1e-5)).all(),
                "{method}: pixel {i} brighter with AO: {a} > {p}"
            );
            darker += (a.element_sum() < p.element_sum()) as u32;
        }
        assert!(darker > 32 * 24 / 10, "{method}: {darker} pixels darker");
    }
}
