// Pass "geometry" of SRAA-RT, the entry point: `geometry_pixel`
// (subpixel.wgsl) for subsample `subsample[0]` of every pixel. Only the
// programs that trace subsamples include it (the hybrid path rasterises them
// and has no `subsample` binding).
@compute @workgroup_size(8, 8)
fn geometry_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    var c = counts_zero();
    geometry_pixel(id.x, id.y, id.y * frame.width + id.x, min(subsample[0], 3u), &c);
    counts_flush(c);
}
