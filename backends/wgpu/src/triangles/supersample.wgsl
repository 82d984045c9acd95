// NoAA and SSAA: subcone-cpu render.rs `supersample`, one invocation per pixel.
// Follows trace.wgsl and the generated frame bindings (`color`, `sample_row`).

// render.rs `supersample`: a regular n×n grid of rays through the pixel
// (n = 1 for NoAA), Whitted radiance, box filter. One dispatch per row `sy`
// of the grid (`sample_row[0]`), accumulating into `color` in the CPU's order
// (rows, then columns); the last row divides by n². Splitting bounds the loop
// iterations of one invocation: llvmpipe (lavapipe) stops any loop of a shader
// invocation after 65 535 iterations in total, which 256 samples of BVH
// traversal exceed.
@compute @workgroup_size(8, 8)
fn supersample_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let j = id.y * frame.width + id.x;
    var c = counts_zero();
    let n = max(frame.ssaa_side, 1u);
    if frame.ssaa_diagonal != 0u {
        // ssaa2: the grid's diagonal, samples (k, k), in one dispatch.
        var diag = vec3<f32>(0.0);
        for (var k = 0u; k < n; k++) {
            let off = vec2<f32>((f32(k) + 0.5) / f32(n), (f32(k) + 0.5) / f32(n));
            let p = vec2<f32>(f32(id.x), f32(id.y)) + off;
            let d = camera_ray(p);
            c.primary += 1u;
            diag = diag + radiance(frame.cam_pos, d, 0u, &c);
        }
        color[j] = vec4<f32>(diag / f32(n), 0.0);
        counts_flush(c);
        return;
    }
    let sy = sample_row[0];
    var sum = vec3<f32>(0.0);
    if sy > 0u {
        sum = color[j].xyz;
    }
    for (var sx = 0u; sx < n; sx++) {
        let off = vec2<f32>((f32(sx) + 0.5) / f32(n), (f32(sy) + 0.5) / f32(n));
        let p = vec2<f32>(f32(id.x), f32(id.y)) + off;
        let d = camera_ray(p);
        c.primary += 1u;
        sum = sum + radiance(frame.cam_pos, d, 0u, &c);
    }
    if sy + 1u >= n {
        color[j] = vec4<f32>(sum / f32(n * n), 0.0);
    } else {
        color[j] = vec4<f32>(sum, 0.0);
    }
    counts_flush(c);
}
