//! `CtssPass` for compositing: coverage alpha over a transparent background
//! (`CtssBackground`), view depth (`CtssDepth`), cameras from the host's
//! matrices (`CtssProjection`) and a sub-rectangle of the output
//! (`CtssRect`), on the host's device.

mod common;

#[path = "../examples/host/mod.rs"]
mod host;

use glam::{Mat4, Vec2, Vec3};
use subcone_kernels::aggregate::Weighting;
use subcone_kernels::ctss::CtssParams;
use subcone_passes::{
    CtssBackground, CtssBuffers, CtssCamera, CtssDepth, CtssFrame, CtssOutput, CtssPass,
    CtssPassDesc, CtssProjection, CtssRect, CtssView, PassError,
};

const W: u32 = 24;
const H: u32 = 18;
const FOV_Y: f32 = 0.9;

/// A unit sphere 4 ahead, shaded by its normal's height.
const SPHERE: &str = "
fn subcone_field(p: vec3<f32>) -> vec3<f32> {
    let d = length(p - vec3<f32>(0.0, 0.0, 4.0)) - 1.0;
    return vec3<f32>(d, d, 0.0);
}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.5 + 0.5 * n.y, 0.25, 1.0);
}
";

/// A cone about as wide as a pixel, so that edge pixels are partly covered.
fn params(tan_theta: f32) -> CtssParams {
    CtssParams::new(tan_theta)
        .with_range(0.0, 50.0)
        .with_max_steps(256)
}

fn pinhole() -> CtssCamera {
    CtssCamera::new(Vec3::ZERO, Vec3::Z, Vec3::Y, FOV_Y)
}

/// The pinhole's view: from the origin towards +z, y up, right-handed (the
/// view looks down its −z; right is +z × +y = −x, as the pinhole's).
fn view() -> Mat4 {
    let (f, u) = (Vec3::Z, Vec3::Y);
    let s = f.cross(u);
    Mat4::from_rows(
        s.extend(0.0),
        u.extend(0.0),
        (-f).extend(0.0),
        glam::Vec4::W,
    )
}

/// A symmetric perspective projection (wgpu's depth range, right-handed).
fn perspective(fov_y: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let t = near * (0.5 * fov_y).tan();
    frustum(-t * aspect, t * aspect, -t, t, near, far)
}

/// An orthographic projection of `[l, r] × [b, t]`, view depths `near` to
/// `far` (wgpu's depth range, right-handed).
fn orthographic(l: f32, r: f32, b: f32, t: f32, near: f32, far: f32) -> Mat4 {
    Mat4::from_rows(
        [2.0 / (r - l), 0.0, 0.0, -(r + l) / (r - l)].into(),
        [0.0, 2.0 / (t - b), 0.0, -(t + b) / (t - b)].into(),
        [0.0, 0.0, -1.0 / (far - near), -near / (far - near)].into(),
        [0.0, 0.0, 0.0, 1.0].into(),
    )
}

/// A perspective frustum with wgpu's depth range: x in `[l, r]`, y in
/// `[b, t]` on the near plane `n`, far plane `f`.
fn frustum(l: f32, r: f32, b: f32, t: f32, n: f32, f: f32) -> Mat4 {
    Mat4::from_cols(
        [2.0 * n / (r - l), 0.0, 0.0, 0.0].into(),
        [0.0, 2.0 * n / (t - b), 0.0, 0.0].into(),
        [(r + l) / (r - l), (t + b) / (t - b), f / (n - f), -1.0].into(),
        [0.0, 0.0, n * f / (n - f), 0.0].into(),
    )
}

fn storage(device: &wgpu::Device, bytes: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("ctss composite test"),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn read<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    enc: &mut Option<wgpu::CommandEncoder>,
    buffer: &wgpu::Buffer,
) -> Vec<T> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("ctss composite read-back"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut e = enc
        .take()
        .unwrap_or_else(|| device.create_command_encoder(&Default::default()));
    e.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    queue.submit([e.finish()]);
    bytemuck::cast_slice(&host::read_buffer(device, &staging).expect("read-back")).to_vec()
}

/// A traced image: colours and view depths, row-major.
struct Image {
    size: (u32, u32),
    colour: Vec<[f32; 4]>,
    depth: Vec<f32>,
}

impl Image {
    fn at(&self, x: u32, y: u32) -> ([f32; 4], f32) {
        let i = (y * self.size.0 + x) as usize;
        (self.colour[i], self.depth[i])
    }
}

/// The colour of every pixel not written: the buffers start as it.
const UNWRITTEN: f32 = -7.0;

/// Trace `size` into buffers (initially [`UNWRITTEN`]) with depth.
#[allow(clippy::too_many_arguments)]
fn trace(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    background: CtssBackground,
    side: u32,
    camera: CtssView,
    params: CtssParams,
    size: (u32, u32),
    rect: Option<CtssRect>,
) -> Result<Image, PassError> {
    let desc = CtssPassDesc::default()
        .with_output(CtssOutput::Buffers { counts: false })
        .with_background(background)
        .with_depth(CtssDepth::View)
        .with_samples_per_side(side);
    let pass = CtssPass::new(device, SPHERE, &desc)?;
    let n = u64::from(size.0 * size.1);
    let (output, depth) = (storage(device, n * 16), storage(device, n * 4));
    queue.write_buffer(
        &output,
        0,
        bytemuck::cast_slice(&vec![UNWRITTEN; 4 * n as usize]),
    );
    queue.write_buffer(
        &depth,
        0,
        bytemuck::cast_slice(&vec![UNWRITTEN; n as usize]),
    );
    let mut enc = device.create_command_encoder(&Default::default());
    pass.encode_buffers(
        device,
        queue,
        &mut enc,
        &CtssBuffers {
            camera,
            params,
            background: Vec3::new(0.2, 0.4, 0.6),
            host_group: None,
            size,
            rect,
            output: &output,
            counts: None,
            depth: Some(&depth),
        },
        None,
    )?;
    let mut enc = Some(enc);
    let colour = read(device, queue, &mut enc, &output);
    let depth = read(device, queue, &mut enc, &depth);
    Ok(Image {
        size,
        colour,
        depth,
    })
}

/// Largest and mean absolute difference of the colours (RGB and alpha) of
/// `a`'s pixels and `b`'s `origin + (x, y)`.
fn colour_difference(a: &Image, b: &Image, origin: (u32, u32)) -> (f32, f32) {
    let (mut max, mut sum, mut n) = (0.0f32, 0.0f32, 0);
    for y in 0..a.size.1 {
        for x in 0..a.size.0 {
            let (ca, _) = a.at(x, y);
            let (cb, _) = b.at(origin.0 + x, origin.1 + y);
            for k in 0..4 {
                let d = (ca[k] - cb[k]).abs();
                max = max.max(d);
                sum += d;
                n += 1;
            }
        }
    }
    (max, sum / n as f32)
}

/// With a transparent background the pass writes premultiplied colour and
/// the coverage of the masks as alpha: `over` the opaque pass's background
/// it gives the opaque pass's image (up to rounding), for one cone and for
/// 2 × 2 cones a pixel; the sphere's edge pixels are partly covered, the
/// corners not at all, the centre wholly.
#[test]
fn transparent_over_the_background_is_the_opaque_image() {
    let Some((device, queue)) = common::device_or_skip("ctss composite", host::open_device) else {
        return;
    };
    let background = [0.2, 0.4, 0.6];
    for side in [1, 2] {
        let run = |b| {
            trace(
                &device,
                &queue,
                b,
                side,
                pinhole().into(),
                params(0.04),
                (W, H),
                None,
            )
            .expect("trace")
        };
        let (opaque, clear) = (
            run(CtssBackground::Opaque),
            run(CtssBackground::Transparent),
        );
        let mut fractional = 0;
        for (o, c) in opaque.colour.iter().zip(&clear.colour) {
            let a = c[3];
            assert!((0.0..=1.0).contains(&a), "alpha {a}");
            assert_eq!(o[3], 1.0);
            for k in 0..3 {
                let over = c[k] + (1.0 - a) * background[k];
                assert!(
                    (over - o[k]).abs() < 1e-5,
                    "side {side}: {c:?} over ≠ {o:?}"
                );
            }
            if a > 0.0 && a < 1.0 {
                fractional += 1;
            }
        }
        assert!(
            fractional >= 8,
            "side {side}: {fractional} edge pixels partly covered"
        );
        assert_eq!(clear.at(0, 0).0, [0.0; 4], "a corner: nothing covers it");
        assert_eq!(clear.at(W / 2, H / 2).0[3], 1.0, "the centre is covered");
    }
}

/// View depth is the nearest contributing group's distance along the
/// forward axis: the sphere's front (3 ahead) at the centre, the sphere's
/// depth `4 − √(1 − x²)` beside it (x the lateral offset of the hit), +∞
/// where nothing is hit, finite wherever alpha is not 0; and a perspective
/// `CtssProjection` of the same camera writes the same depths.
#[test]
fn view_depth_is_the_nearest_surface() {
    let Some((device, queue)) = common::device_or_skip("ctss composite", host::open_device) else {
        return;
    };
    let t = CtssBackground::Transparent;
    let img = trace(
        &device,
        &queue,
        t,
        1,
        pinhole().into(),
        params(0.04),
        (W, H),
        None,
    )
    .expect("trace");
    let (_, centre) = img.at(W / 2, H / 2);
    assert!((centre - 3.0).abs() < 0.02, "centre depth {centre}");
    for (c, d) in img.colour.iter().zip(&img.depth) {
        if c[3] == 0.0 {
            assert_eq!(*d, f32::INFINITY);
        } else {
            assert!(
                d.is_finite() && *d >= centre - 0.02 && *d < 4.0,
                "depth {d} at {c:?}"
            );
        }
    }
    // Three pixels right of the centre: the axis hits the sphere at lateral
    // offset x; its depth is that of the sphere there.
    let (cx, cy) = (W / 2 + 3, H / 2);
    let (o, dir) = pinhole().ray(Vec2::new(cx as f32 + 0.5, cy as f32 + 0.5), W, H);
    let oc = o - Vec3::new(0.0, 0.0, 4.0);
    let (bb, cc) = (oc.dot(dir), oc.length_squared() - 1.0);
    let hit = o + (-bb - (bb * bb - cc).sqrt()) * dir;
    let (_, d) = img.at(cx, cy);
    assert!(
        (d - hit.z).abs() < 0.03,
        "depth {d}, the sphere is at {}",
        hit.z
    );

    let aspect = W as f32 / H as f32;
    let projection = CtssProjection::new(view(), perspective(FOV_Y, aspect, 0.1, 100.0));
    let p = trace(
        &device,
        &queue,
        t,
        1,
        projection.into(),
        params(0.04),
        (W, H),
        None,
    )
    .expect("trace");
    for (a, b) in img.depth.iter().zip(&p.depth) {
        assert!(a == b || (a - b).abs() < 1e-3, "{a} ≠ {b}");
    }
}

/// A jittered projection matrix (the NDC offset a temporal method adds)
/// traces the image of the pinhole with the same jitter in pixels, up to
/// the rounding of two ways of making a ray.
#[test]
fn a_jittered_projection_is_the_jittered_pinhole() {
    let Some((device, queue)) = common::device_or_skip("ctss composite", host::open_device) else {
        return;
    };
    let jitter = Vec2::new(0.3, -0.2);
    let mut camera = pinhole();
    camera.jitter = jitter;
    let t = CtssBackground::Transparent;
    let a = trace(
        &device,
        &queue,
        t,
        1,
        camera.into(),
        params(0.04),
        (W, H),
        None,
    )
    .expect("pinhole");
    // Pixel p's ray goes through the unjittered NDC of p + jitter: the
    // projection moves the scene by minus that.
    let shift = Vec3::new(-2.0 * jitter.x / W as f32, 2.0 * jitter.y / H as f32, 0.0);
    let aspect = W as f32 / H as f32;
    let projection = Mat4::from_translation(shift) * perspective(FOV_Y, aspect, 0.1, 100.0);
    let b = trace(
        &device,
        &queue,
        t,
        1,
        CtssProjection::new(view(), projection).into(),
        params(0.04),
        (W, H),
        None,
    )
    .expect("projection");
    let (max, mean) = colour_difference(&a, &b, (0, 0));
    println!("jittered projection against pinhole: max {max:e}, mean {mean:e}");
    assert!(max < 1e-3 && mean < 1e-4, "max {max}, mean {mean}");
    // And the jitter did move the image.
    let unjittered = trace(
        &device,
        &queue,
        t,
        1,
        pinhole().into(),
        params(0.04),
        (W, H),
        None,
    )
    .expect("pinhole");
    let (moved, _) = colour_difference(&a, &unjittered, (0, 0));
    assert!(moved > 0.05, "the jitter moves edges by {moved}");
}

/// An off-axis frustum that is a tile of a larger symmetric one traces that
/// tile of the larger image.
#[test]
fn an_off_axis_frustum_is_a_tile_of_the_symmetric_one() {
    let Some((device, queue)) = common::device_or_skip("ctss composite", host::open_device) else {
        return;
    };
    let (near, far) = (0.1, 100.0);
    let top = near * (0.5 * FOV_Y).tan();
    let right = top * W as f32 / H as f32;
    let full = frustum(-right, right, -top, top, near, far);
    let t = CtssBackground::Transparent;
    let big = trace(
        &device,
        &queue,
        t,
        1,
        CtssProjection::new(view(), full).into(),
        params(0.04),
        (W, H),
        None,
    )
    .expect("symmetric");
    let (x0, y0, w, h) = (7u32, 4u32, 11u32, 9u32);
    let l = -right + 2.0 * right * x0 as f32 / W as f32;
    let r = -right + 2.0 * right * (x0 + w) as f32 / W as f32;
    let tt = top - 2.0 * top * y0 as f32 / H as f32;
    let b = top - 2.0 * top * (y0 + h) as f32 / H as f32;
    let tile = trace(
        &device,
        &queue,
        t,
        1,
        CtssProjection::new(view(), frustum(l, r, b, tt, near, far)).into(),
        params(0.04),
        (w, h),
        None,
    )
    .expect("off-axis");
    let (max, mean) = colour_difference(&tile, &big, (x0, y0));
    println!("off-axis tile against the symmetric image: max {max:e}, mean {mean:e}");
    assert!(max < 1e-3 && mean < 1e-4, "max {max}, mean {mean}");
    let covered = tile.colour.iter().filter(|c| c[3] > 0.0).count();
    let partial = tile
        .colour
        .iter()
        .filter(|c| c[3] > 0.0 && c[3] < 1.0)
        .count();
    assert!(covered > 0 && partial > 0, "the tile holds sphere and edge");
}

/// An orthographic camera 4 × 3 units wide at 32 × 24 pixels (8 pixels a
/// unit) sees the unit sphere as a disc of radius 8 pixels: one ray a
/// pixel covers the pixels whose centre lies in that disc (up to the
/// rounding of its rim), and the centre's view depth is the sphere's front
/// (within the trace's hit tolerance). A non-zero cone angle is
/// refused.
#[test]
fn an_orthographic_camera_sees_the_sphere_at_its_size() {
    let Some((device, queue)) = common::device_or_skip("ctss composite", host::open_device) else {
        return;
    };
    let (w, h) = (32, 24);
    let ortho = CtssProjection::new(view(), orthographic(-2.0, 2.0, -1.5, 1.5, 0.1, 100.0));
    let t = CtssBackground::Transparent;
    let img = trace(
        &device,
        &queue,
        t,
        1,
        ortho.into(),
        params(0.0),
        (w, h),
        None,
    )
    .expect("orthographic");
    let covered: f32 = img.colour.iter().map(|c| c[3]).sum();
    // The pixels whose centre is within 8 pixels of the image's centre.
    let inside = (0..w * h)
        .filter(|i| {
            let (x, y) = ((i % w) as f32 + 0.5, (i / w) as f32 + 0.5);
            (x - 16.0).hypot(y - 12.0) < 8.0
        })
        .count() as f32;
    let radius = (covered / std::f32::consts::PI).sqrt();
    println!("orthographic disc: {covered} pixels ({inside} centres in the predicted disc), radius {radius} (8 predicted)");
    assert!(
        (covered - inside).abs() <= 2.0,
        "{covered} pixels covered, {inside} predicted"
    );
    assert!(
        (radius - 8.0).abs() < 0.25,
        "radius {radius} pixels, 8 predicted"
    );
    let (_, d) = img.at(w / 2, h / 2);
    assert!((d - 3.0).abs() < 0.01, "centre depth {d}");
    // 4 × 4 rays a pixel antialias the edge, and the area stays.
    let ssaa = trace(
        &device,
        &queue,
        t,
        4,
        ortho.into(),
        params(0.0),
        (w, h),
        None,
    )
    .expect("orthographic 4x4");
    let covered4: f32 = ssaa.colour.iter().map(|c| c[3]).sum();
    assert!(ssaa.colour.iter().any(|c| c[3] > 0.0 && c[3] < 1.0));
    assert!((covered4 / std::f32::consts::PI).sqrt() - 8.0 < 0.25);
    match trace(
        &device,
        &queue,
        t,
        1,
        ortho.into(),
        params(0.01),
        (w, h),
        None,
    ) {
        Err(PassError::Config(m)) => assert!(m.contains("tan_theta"), "{m}"),
        other => panic!(
            "a cone angle with an orthographic camera: {:?}",
            other.err()
        ),
    }
}

/// A rectangle of the output holds the image the same camera traces at the
/// rectangle's size, bit for bit, colours and depths; pixels outside it are
/// not written.
#[test]
fn a_rectangle_holds_the_image_of_its_size() {
    let Some((device, queue)) = common::device_or_skip("ctss composite", host::open_device) else {
        return;
    };
    let rect = CtssRect {
        origin: [5, 3],
        size: [13, 11],
    };
    let t = CtssBackground::Transparent;
    for camera in [
        CtssView::from(pinhole()),
        CtssProjection::new(view(), perspective(FOV_Y, 13.0 / 11.0, 0.1, 100.0)).into(),
    ] {
        let big = trace(
            &device,
            &queue,
            t,
            2,
            camera,
            params(0.04),
            (W, H),
            Some(rect),
        )
        .expect("rect");
        let small =
            trace(&device, &queue, t, 2, camera, params(0.04), (13, 11), None).expect("small");
        for y in 0..H {
            for x in 0..W {
                let (c, d) = big.at(x, y);
                let inside = (5..18).contains(&x) && (3..14).contains(&y);
                if inside {
                    let (sc, sd) = small.at(x - 5, y - 3);
                    assert_eq!(c.map(f32::to_bits), sc.map(f32::to_bits), "({x}, {y})");
                    assert_eq!(d.to_bits(), sd.to_bits(), "({x}, {y})");
                } else {
                    assert_eq!((c, d), ([UNWRITTEN; 4], UNWRITTEN), "({x}, {y})");
                }
            }
        }
        assert!(small.colour.iter().any(|c| c[3] > 0.0 && c[3] < 1.0));
    }
    for bad in [
        CtssRect {
            origin: [20, 0],
            size: [5, 4],
        },
        CtssRect {
            origin: [0, 0],
            size: [0, 4],
        },
        CtssRect {
            origin: [u32::MAX, 0],
            size: [2, 4],
        },
    ] {
        match trace(
            &device,
            &queue,
            t,
            1,
            pinhole().into(),
            params(0.04),
            (W, H),
            Some(bad),
        ) {
            Err(PassError::Config(m)) => assert!(m.contains("CtssRect"), "{m}"),
            other => panic!("{bad:?}: {:?}", other.err()),
        }
    }
}

/// The texture forms: the depth texture is given exactly when the desc
/// asks for depth, `R32Float`, of the output's size; and a transparent
/// background refuses weights that do not sum to the coverage.
#[test]
fn texture_depth_and_weights_are_checked() {
    let Some((device, queue)) = common::device_or_skip("ctss composite", host::open_device) else {
        return;
    };
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC;
    let tex = |size: (u32, u32), format| {
        host::texture(&device, "ctss", (size.0, size.1, 1), 1, format, usage)
    };
    let colour = tex((W, H), wgpu::TextureFormat::Rgba32Float);
    let depth = tex((W, H), wgpu::TextureFormat::R32Float);
    let small_depth = tex((W - 1, H), wgpu::TextureFormat::R32Float);
    let wrong_depth = tex((W, H), wgpu::TextureFormat::Rgba32Float);
    let (cv, dv) = (
        colour.create_view(&Default::default()),
        depth.create_view(&Default::default()),
    );
    let (sv, wv) = (
        small_depth.create_view(&Default::default()),
        wrong_depth.create_view(&Default::default()),
    );
    let desc = CtssPassDesc::default()
        .with_output_format(wgpu::TextureFormat::Rgba32Float)
        .with_background(CtssBackground::Transparent)
        .with_depth(CtssDepth::View);
    let pass = CtssPass::new(&device, SPHERE, &desc).expect("pass");
    let plain = CtssPass::new(&device, SPHERE, &desc.with_depth(CtssDepth::None))
        .expect("pass without depth");
    let frame = |depth, params| CtssFrame {
        camera: pinhole().into(),
        params,
        background: Vec3::ZERO,
        host_group: None,
        output: &cv,
        depth,
        rect: None,
    };
    let mut enc = device.create_command_encoder(&Default::default());
    let p = params(0.04);
    let uniform = p.with_weighting(Weighting::Uniform);
    let floored = CtssParams {
        min_sample_weight: 0.01,
        ..p
    };
    for (pass, frame, what) in [
        (&pass, frame(None, p), "no depth texture"),
        (&plain, frame(Some(&dv), p), "an unread depth texture"),
        (
            &pass,
            frame(Some(&sv), p),
            "a depth texture of another size",
        ),
        (
            &pass,
            frame(Some(&wv), p),
            "a depth texture of another format",
        ),
        (&pass, frame(Some(&dv), uniform), "uniform weights"),
        (&pass, frame(Some(&dv), floored), "a minimum sample weight"),
    ] {
        let r = pass.encode(&device, &queue, &mut enc, &frame, None);
        assert!(r.is_err(), "{what}: accepted");
    }
    let r = pass.encode(&device, &queue, &mut enc, &frame(Some(&dv), p), None);
    assert!(r.is_ok(), "the frame that fits: {r:?}");
    let _ = enc.finish();
}
