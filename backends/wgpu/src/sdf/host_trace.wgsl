// CtssPass's host trace (subcone_passes::CtssTrace::Host), for what the
// kernels' subcone_ctss_trace does not do: sphere tracing (NoAA, SSAA:
// noaa_sample, SdfView::noaa) and semi-transparent scenes (CTSS §5.3:
// ctss_translucent_sample and noaa_translucent_sample, translucent.wgsl).
// sdf/mod.rs (`HostTrace`) defines host_sample as one of them. The pass's
// cross-section axes are not needed: the translucent cone computes the same
// ones itself.
fn subcone_trace(params: subcone_CtssParams, origin: vec3<f32>, dir: vec3<f32>, right: vec3<f32>, up: vec3<f32>, background: vec3<f32>) -> subcone_CtssTraceResult {
    var steps = 0u;
    var samples = 0u;
    var shadow = 0u;
    let c = host_sample(origin, dir, background, &steps, &samples, &shadow);
    shadow_rays_traced += shadow;
    return subcone_CtssTraceResult(c, samples, steps, 0u, 0u);
}
