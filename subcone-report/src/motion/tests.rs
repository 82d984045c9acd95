use super::*;
use glam::Vec3;

#[test]
fn the_path_starts_at_the_camera_and_moves_by_sub_pixel_steps() {
    let base = Camera::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::ZERO, Vec3::Y, 0.8).unwrap();
    let (w, h) = (320, 180);
    let path = camera_path(&base, 16, (w, h), 5.0).unwrap();
    assert_eq!(path.len(), 16);
    assert!((path[0].position - base.position).length() < 1e-6);
    assert!((path[0].forward - base.forward).length() < 1e-6);
    // The pan: the angle between consecutive view directions is
    // PAN_PIXELS pixels' worth of the vertical field of view.
    // (The sine, from the cross product: acos near 1 has no precision
    // left in f32.)
    let step = path[1].forward.cross(path[0].forward).length();
    let want = (PAN_PIXELS * 0.8 / h as f32).sin();
    assert!((step - want).abs() < 1e-3 * want, "{step} {want}");
    // The dolly: 2 · DOLLY_PIXELS / w of the subject distance per frame.
    let moved = (path[1].position - path[0].position).length();
    assert!((moved - 5.0 * 2.0 * DOLLY_PIXELS / w as f32).abs() < 1e-5);
    // A non-finite subject distance is an error, not a NaN camera.
    assert!(camera_path(&base, 4, (w, h), f32::NAN).is_err());
}

fn grey(w: u32, h: u32, v: impl Fn(u32, u32) -> u8) -> Rgb8 {
    let data = (0..w * h).flat_map(|i| [v(i % w, i / w); 3]).collect();
    Rgb8 {
        width: w,
        height: h,
        data,
    }
}

#[test]
fn following_the_reference_change_is_stable_and_flicker_is_not() {
    let (a, b) = (
        grey(4, 1, |x, _| x as u8 * 10),
        grey(4, 1, |x, _| x as u8 * 10 + 20),
    );
    // The method changes as the reference does: 0 everywhere.
    let same = instability((&a, &b), (&a, &b)).unwrap();
    assert!(same.iter().all(|v| v.abs() < 1e-6));
    // The method flickers where the reference stays still.
    let still = instability((&a, &b), (&a, &a)).unwrap();
    assert!(
        still.iter().all(|v| (v - 20.0 / 255.0).abs() < 1e-4),
        "{still:?}"
    );
    assert!(instability((&a, &b), (&a, &grey(2, 1, |_, _| 0))).is_err());
}

#[test]
fn the_worst_window_holds_the_largest_sum() {
    let mut map = vec![0.0f32; 40 * 30];
    map[25 * 40 + 33] = 1.0;
    let c = worst_window(&map, 40, 30, 8);
    assert!(
        c.x <= 33 && 33 < c.x + 8 && c.y <= 25 && 25 < c.y + 8,
        "{c:?}"
    );
    // A window larger than the image shrinks to it.
    assert_eq!(worst_window(&map, 40, 30, 100).side, 30);
}

#[test]
fn the_animation_is_an_animated_png_with_every_frame() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.png");
    let crop = MotionCrop {
        x: 1,
        y: 0,
        side: 2,
    };
    let frames: Vec<Rgb8> = (0..3u8)
        .map(|t| {
            strip(
                &[&grey(4, 2, move |x, _| x as u8 + t), &grey(4, 2, |_, _| 9)],
                &["noaa", "reference"],
                &format!("frame {} of 3", t + 1),
                crop,
            )
            .unwrap()
        })
        .collect();
    assert_eq!(frames[0].width, 2 * 2 * CROP_ZOOM + 2);
    assert_eq!(frames[0].height, 2 * CROP_ZOOM + 2 * LABEL_BAND);
    save_apng(&path, &frames).unwrap();
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
    let reader = dec.read_info().unwrap();
    let anim = reader.info().animation_control().unwrap();
    assert_eq!((anim.num_frames, anim.num_plays), (3, 0));
    assert!(save_apng(&path, &[]).is_err());
}

#[test]
fn the_loop_steps_back_one_frame_at_a_time() {
    assert_eq!(ping_pong(4), vec![0, 1, 2, 3, 2, 1]);
    assert_eq!(ping_pong(2), vec![0, 1]);
    assert_eq!(ping_pong(1), vec![0]);
    assert!(ping_pong(0).is_empty());
    // Every step, the wrap from the last back to the first included,
    // moves by one frame.
    let order = ping_pong(16);
    for (i, &t) in order.iter().enumerate() {
        let next = order[(i + 1) % order.len()];
        assert_eq!(t.abs_diff(next), 1, "{order:?}");
    }
}

#[test]
fn every_frame_is_labelled() {
    let crop = MotionCrop {
        x: 0,
        y: 0,
        side: 4,
    };
    let img = grey(8, 8, |_, _| 60);
    let a = strip(&[&img, &img], &["noaa", "reference"], "frame 1 of 4", crop).unwrap();
    let b = strip(&[&img, &img], &["noaa", "reference"], "frame 2 of 4", crop).unwrap();
    let row = |f: &Rgb8, y: u32| {
        f.data[(y * f.width * 3) as usize..((y + 1) * f.width * 3) as usize].to_vec()
    };
    // Dark text in the top band over each tile, and in the bottom band.
    let tile = 4 * CROP_ZOOM;
    let dark_in = |f: &Rgb8, ys: std::ops::Range<u32>, xs: std::ops::Range<u32>| {
        ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
            .any(|(x, y)| f.data[((y * f.width + x) * 3) as usize] < 100)
    };
    assert!(dark_in(&a, 0..LABEL_BAND, 0..tile));
    assert!(dark_in(&a, 0..LABEL_BAND, tile + 2..2 * tile + 2));
    let bottom = LABEL_BAND + tile..a.height;
    assert!(dark_in(&a, bottom.clone(), 0..a.width));
    // The frames differ in their bottom band only (the number).
    assert!((0..LABEL_BAND + tile).all(|y| row(&a, y) == row(&b, y)));
    assert!(bottom.clone().any(|y| row(&a, y) != row(&b, y)));
}

/// The moving-object run on a small image: every row has one FLIP per
/// frame, the uncovered pixels are judged, TAA's error there stays
/// within 1.5× NoAA's (no smear), and the section states the
/// camera-only and the moving-object figures.
#[test]
fn the_moving_object_run_judges_the_uncovered_pixels() {
    let cpu = subcone_cpu::CpuBackend::new();
    let run = moving_object(&cpu, 5, (96, 64)).unwrap();
    assert_eq!(run.scene, "cornell-moving");
    assert_eq!(run.rows.len(), 3);
    assert!(run.rows.iter().all(|r| r.flip.len() == 5));
    assert_eq!(run.judged_frames, 2);
    assert!(run.uncovered_px > 0);
    let noaa = run.row("noaa").unwrap().uncovered.unwrap();
    for taa in ["taa", "taa, depth dilation"] {
        let u = run.row(taa).unwrap().uncovered.unwrap();
        assert!(
            u <= 1.5 * noaa,
            "{taa}: {u} on the uncovered pixels, noaa {noaa}"
        );
    }
    let camera_only = MotionRow {
        scene: "cornell".into(),
        method: TAA.to_string(),
        flip: vec![0.05, 0.03],
        ssim: vec![0.9, 0.9],
        frames_to_beat_noaa: Some(1),
        instability: Default::default(),
        ms_per_frame: 1.0,
    };
    let m = Motion {
        ran: true,
        frames: 5,
        size: (96, 64),
        rows: vec![camera_only],
        moving: Some(run.clone()),
        ..Default::default()
    };
    let md = section(&m);
    assert!(md.contains("### A moving object: cornell-moving"), "{md}");
    assert!(
        md.contains("Camera only, taa's mean FLIP: cornell 0.0400."),
        "{md}"
    );
    let taa = run.row("taa").unwrap();
    assert!(md.contains(&format!("taa {:.4}", taa.flip_mean())), "{md}");
    assert!(md.contains("frames later: taa"), "{md}");
    let json = json(&m);
    assert_eq!(json["moving_object"]["rows"].as_array().unwrap().len(), 3);
}

#[test]
fn the_subject_is_the_median_finite_depth() {
    let mut f = Frame::new(4, 1);
    f.depth = Some(vec![f32::INFINITY, 2.0, 8.0, 4.0]);
    assert_eq!(subject_distance(&f), 4.0);
    f.depth = Some(vec![f32::NAN; 4]);
    assert_eq!(subject_distance(&f), 1.0);
}
