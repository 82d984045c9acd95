// Closest-depth motion dilation (Karis 2014; FSR2's reconstruct & dilate):
// the WGSL mirror of subcone_kernels::taa::dilated_motion
// (kernels/src/taa.rs), same names with a subcone_ prefix, same statement
// order.
//
// Needs params.wgsl (subcone_TaaParams, subcone_is_finite, subcone_inf). The
// including shader defines the two fetches, the twins of dilated_motion's
// closures:
//     fn taa_motion(x: i32, y: i32) -> vec2<f32>   the host's motion vector
//     fn taa_depth(x: i32, y: i32) -> f32          the host's depth
// called only with coordinates inside the image.

// taa::nearness
fn subcone_taa_nearness(depth: f32, code: u32) -> f32 {
    if !subcone_is_finite(depth) {
        return -subcone_inf();
    } else if code == 2u {
        return depth;
    }
    return -depth;
}

// taa::dilated_motion
fn subcone_taa_dilated_motion(xy: vec2<i32>, params: subcone_TaaParams) -> vec2<f32> {
    let w = i32(max(params.width, 1u));
    let h = i32(max(params.height, 1u));
    let x = clamp(xy.x, 0, w - 1);
    let y = clamp(xy.y, 0, h - 1);
    let code = params.depth_dilation;
    if code != 1u && code != 2u {
        return taa_motion(x, y);
    }
    var best = vec2<i32>(x, y);
    var near = subcone_taa_nearness(taa_depth(x, y), code);
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            if dx == 0 && dy == 0 {
                continue;
            }
            let nx = clamp(x + dx, 0, w - 1);
            let ny = clamp(y + dy, 0, h - 1);
            let n = subcone_taa_nearness(taa_depth(nx, ny), code);
            if n > near {
                near = n;
                best = vec2<i32>(nx, ny);
            }
        }
    }
    return taa_motion(best.x, best.y);
}
