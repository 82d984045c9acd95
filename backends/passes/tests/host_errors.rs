//! The passes stay inside the host's error handling: they install no
//! callback (the host's uncaptured-error handler is still the one called
//! after they ran, and `subcone_wgpu::GpuContext::from_device` does not take
//! it over either), and inputs that do not fit are typed errors before
//! anything reaches the device.

mod common;

#[allow(dead_code)]
#[path = "../examples/host_sraa.rs"]
mod host_sraa;

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use subcone_kernels::sraa::SraaParams;
use subcone_passes::{
    FxaaInput, FxaaPass, FxaaPassDesc, PassError, SraaInputs, SraaPass, SraaPassDesc,
    SubsampleGeometry,
};

use host_sraa::host::{self, texture};

/// A host's device (or `None`: skip the test `what`) with the host's own
/// uncaptured-error handler installed: it counts the errors it sees.
fn device_counting_errors(what: &str) -> Option<(wgpu::Device, wgpu::Queue, Arc<AtomicUsize>)> {
    let (device, queue) = common::device_or_skip(what, host_sraa::open_device)?;
    let seen = Arc::new(AtomicUsize::new(0));
    let counter = seen.clone();
    device.on_uncaptured_error(Arc::new(move |_e: wgpu::Error| {
        counter.fetch_add(1, Ordering::SeqCst);
    }));
    Some((device, queue, seen))
}

/// Wait for the device (the host's poll), panicking on a timeout.
fn wait(device: &wgpu::Device) {
    host::wait(device).expect("poll");
}

#[test]
fn the_hosts_uncaptured_error_handler_stays_the_hosts() {
    let Some((device, queue, seen)) = device_counting_errors("host errors") else {
        return;
    };
    // subcone's own context on the host's device: no callback installed.
    let ctx = Arc::new(subcone_wgpu::GpuContext::from_device(
        device.clone(),
        queue.clone(),
    ));
    assert!(ctx.check_lost().is_ok());
    // The backend on the host's device: this host asked for wgpu's default
    // limits, too few for the backend's triangle passes (more than 8 storage
    // buffers per stage). The render fails as a value, caught by the
    // backend's own error scopes; the host's handler sees nothing.
    use subcone_scene::Backend;
    let scene = subcone_scene::builtin::builtin("cornell").expect("scene");
    let method = "sraa".parse().expect("method");
    let settings = subcone_scene::RenderSettings::new(16, 12);
    let refused = subcone_wgpu::WgpuBackend::with_context(ctx.clone()).render(
        &scene,
        &scene.camera,
        &method,
        &settings,
    );
    match refused {
        Err(e) => assert!(e.to_string().contains("limit"), "{e}"),
        Ok(_) => {
            // An adapter whose defaults suffice: nothing to refuse.
        }
    }
    assert_eq!(
        seen.load(Ordering::SeqCst),
        0,
        "the backend's error reached the host's handler"
    );
    // A host device with the adapter's limits (as `GpuContext::new` asks)
    // renders the frame the backend's own device renders.
    let (big, big_queue) = host::open_device_with_adapter_limits().expect("device");
    let hosted = subcone_wgpu::WgpuBackend::with_context(Arc::new(
        subcone_wgpu::GpuContext::from_device(big, big_queue),
    ))
    .render(&scene, &scene.camera, &method, &settings)
    .expect("render on the host's device");
    let own = subcone_wgpu::WgpuBackend::new()
        .expect("the backend's own device")
        .render(&scene, &scene.camera, &method, &settings)
        .expect("render on the backend's device");
    assert_eq!(hosted.color, own.color);
    // The passes run (SRAA through the host example, FXAA on its output).
    let image = host_sraa::render(&device, &queue, SraaParams::PAPER, 16, 8).expect("host render");
    assert_eq!(image.len(), 16 * 8);
    let fxaa = FxaaPass::new(
        &device,
        &FxaaPassDesc::default().with_input(FxaaInput::ToneMapped),
    )
    .expect("fxaa");
    let read = wgpu::TextureUsages::TEXTURE_BINDING;
    let src = texture(
        &device,
        "src",
        (16, 8, 1),
        1,
        wgpu::TextureFormat::Rgba16Float,
        read,
    );
    let dst = texture(
        &device,
        "dst",
        (16, 8, 1),
        1,
        wgpu::TextureFormat::Rgba16Float,
        wgpu::TextureUsages::STORAGE_BINDING,
    );
    let (src, dst) = (
        src.create_view(&Default::default()),
        dst.create_view(&Default::default()),
    );
    let mut enc = device.create_command_encoder(&Default::default());
    fxaa.encode(&device, &queue, &mut enc, &src, &dst, None)
        .expect("fxaa encode");
    queue.submit([enc.finish()]);
    wait(&device);
    assert_eq!(seen.load(Ordering::SeqCst), 0, "the passes raised an error");
    // A mistake of the host's own, outside any error scope: its handler
    // sees it, not subcone's.
    let _bad = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("invalid"),
        size: 16,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::MAP_WRITE,
        mapped_at_creation: false,
    });
    wait(&device);
    assert_eq!(
        seen.load(Ordering::SeqCst),
        1,
        "the host's handler did not see the host's error"
    );
    // And subcone's context recorded nothing of it: it is the host's.
    assert!(ctx.check_lost().is_ok());
}

/// Each wrong input is its typed error, and nothing reaches the device (the
/// host's handler sees no error).
#[test]
fn inputs_that_do_not_fit_are_typed_errors() {
    let Some((device, queue, seen)) = device_counting_errors("pass input checks") else {
        return;
    };
    use wgpu::TextureFormat::{Depth32Float, R32Float, Rgba16Float, Rgba8UnormSrgb};
    let read = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT;
    let store = wgpu::TextureUsages::STORAGE_BINDING;
    let size = (8, 4, 1);
    let depth = texture(&device, "depth", size, 4, Depth32Float, read);
    let normal = texture(&device, "normal", size, 4, Rgba16Float, read);
    let normal1 = texture(&device, "normal1", size, 1, Rgba16Float, read);
    let small = texture(&device, "small", (4, 4, 1), 4, Rgba16Float, read);
    let color = texture(&device, "color", size, 1, Rgba16Float, read);
    let linear = texture(&device, "linear", size, 4, R32Float, read);
    let output = texture(&device, "output", size, 1, Rgba16Float, store);
    let [depth, normal, normal1, small, color, linear, output] =
        [&depth, &normal, &normal1, &small, &color, &linear, &output]
            .map(|t| t.create_view(&Default::default()));
    let sraa = SraaPass::new(&device, &SraaPassDesc::msaa()).expect("pass");
    let separate = |depth, normal| SubsampleGeometry::Separate { depth, normal };
    let good = SraaInputs {
        geometry: separate(&depth, &normal),
        projection: glam::Mat4::IDENTITY.to_cols_array_2d(),
        centre: None,
        color: &color,
        shadows: None,
        albedo: None,
        secondary: None,
        output: &output,
    };
    let mut enc = device.create_command_encoder(&Default::default());
    assert_eq!(sraa.encode(&device, &queue, &mut enc, &good, None), Ok(()));
    type Case<'a> = (SraaInputs<'a>, fn(&PassError) -> bool);
    let cases: Vec<Case<'_>> = vec![
        (
            SraaInputs {
                geometry: separate(&depth, &normal1),
                ..good
            },
            |e| {
                matches!(
                    e,
                    PassError::SampleCount {
                        expected: 4,
                        found: 1,
                        ..
                    }
                )
            },
        ),
        (
            SraaInputs {
                geometry: separate(&depth, &small),
                ..good
            },
            |e| matches!(e, PassError::Size { .. }),
        ),
        (
            SraaInputs {
                geometry: separate(&linear, &normal),
                ..good
            },
            |e| matches!(e, PassError::Format { .. }),
        ),
        (
            // Packed geometry to a pass built for depth + normals.
            SraaInputs {
                geometry: SubsampleGeometry::Packed(&normal),
                ..good
            },
            |e| matches!(e, PassError::Config(_)),
        ),
        (
            SraaInputs {
                output: &color,
                ..good
            },
            |e| matches!(e, PassError::Usage { .. }),
        ),
    ];
    for (i, (inputs, expected)) in cases.iter().enumerate() {
        match sraa.encode(&device, &queue, &mut enc, inputs, None) {
            Err(e) if expected(&e) => {}
            other => panic!("case {i}: {other:?}"),
        }
    }
    // The tuned preset shades the centre: its geometry is required.
    let tuned = SraaPass::new(
        &device,
        &SraaPassDesc::msaa().with_params(SraaParams::TUNED),
    )
    .expect("tuned pass");
    assert!(matches!(
        tuned.encode(&device, &queue, &mut enc, &good, None),
        Err(PassError::Missing(_))
    ));
    // Secondary shading needs the secondary hits.
    let mirrors =
        SraaPass::new(&device, &SraaPassDesc::msaa().with_secondary(true)).expect("secondary pass");
    // (with the colour's two groups of layers, as it needs).
    let color2 = texture(&device, "color2", (size.0, size.1, 2), 1, Rgba16Float, read)
        .create_view(&Default::default());
    assert!(matches!(
        mirrors.encode(&device, &queue, &mut enc, &good, None),
        Err(PassError::Layers {
            expected: 2,
            found: 1,
            ..
        })
    ));
    assert!(matches!(
        mirrors.encode(
            &device,
            &queue,
            &mut enc,
            &SraaInputs {
                color: &color2,
                ..good
            },
            None,
        ),
        Err(PassError::Missing(_))
    ));
    // Configurations out of range.
    for desc in [
        SraaPassDesc::msaa().with_lights(9),
        SraaPassDesc::msaa().with_output_format(Rgba8UnormSrgb),
    ] {
        assert!(SraaPass::new(&device, &desc).is_err(), "{desc:?}");
    }
    // Timestamps on a device opened without TIMESTAMP_QUERY are refused
    // before anything is recorded.
    if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("timestamps"),
            ty: wgpu::QueryType::Occlusion,
            count: 2,
        });
        let writes = wgpu::ComputePassTimestampWrites {
            query_set: &set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        };
        assert!(matches!(
            sraa.encode(&device, &queue, &mut enc, &good, Some(writes)),
            Err(PassError::Config(_))
        ));
    }
    drop(enc);
    wait(&device);
    assert_eq!(
        seen.load(Ordering::SeqCst),
        0,
        "a refused input reached the device"
    );
}
