// SraaPass (sraa.rs): SRAA's antialiasing pass (Chiu et al., §3, the
// paper's pass 2) over the host's textures. The loop is the wgpu backend's
// resolve (backends/wgpu/src/triangles/sraa.wgsl) and the kernels' Resolver:
// for each of the four geometric subsamples, sraa::reconstruct_layers over
// the neighbourhood's shaded samples (eq. 1, eq. 2 per light, the material
// gate; the kernels' loop subcone_kernels::sraa::RECONSTRUCT_WGSL, shared
// with the backend), then sraa::resolve_pixel. All the mathematics is the
// kernels' (subcone_kernels::sraa::WGSL and RECONSTRUCT_WGSL); this file
// only reads the host's textures.
//
// Follows subcone_kernels::wgsl::PARAMS, subcone_kernels::sraa::WGSL and the
// header sraa.rs generates, and comes before
// subcone_kernels::sraa::RECONSTRUCT_WGSL (the loop, whose hooks this file
// defines): the constants LIGHTS, MATERIAL, HARDWARE_DEPTH,
// UNSIGNED_NORMALS, SHADED_GIVEN (the shaded sample's geometry is an input
// of its own), DECODED (geometry is stored as the kernels' subcone_Geometry,
// taken as it is), SECONDARY, TONE_MAPPED_RESOLVE (sraa::ResolveSpace),
// the bindings, the loaders
// sraa_load_sub (normal and depth), sraa_load_sub_shadow and
// sraa_load_sub_albedo (subsample k of pixel p),
// sraa_load_sec_shaded / sraa_load_sec_sub (secondary normal and path
// length), sraa_load_sec_shaded_shadow / sraa_load_sec_sub_shadow,
// sraa_load_shaded (the shaded sample's own normal and depth),
// sraa_load_color (layer l), sraa_load_shaded_shadow and
// sraa_load_shaded_albedo (the shaded sample), and sraa_store (the output).

// sraa.rs `SraaFrame` (80 bytes).
struct SraaFrame {
    sraa: subcone_SraaParams,
    // The host projection's entries that map view-space z to clip z and w
    // (column-major m[2][2], m[3][2], m[2][3], m[3][3]): clip.z = x·z + y,
    // clip.w = z·z + w. Read only with HARDWARE_DEPTH.
    projection: vec4<f32>,
    width: u32,
    height: u32,
    // The hardware depth of a sample nothing covered (the clear value).
    depth_miss: f32,
    albedo_tolerance: f32,
    // The top-left pixel of the rect resolved (SraaPass::encode_rect; 0 for
    // the whole texture and for buffers): width and height are the rect's,
    // the reconstruction runs in the rect's own coordinates (so its
    // neighbourhood is clipped to the rect) and every texel is read and
    // written at origin + those coordinates (sraa_texel).
    origin_x: u32,
    origin_y: u32,
    // The tone-mapped resolve's exposure (TONE_MAPPED_RESOLVE).
    exposure: f32,
    _pad: u32,
}

// The texel of the rect's pixel (x, y).
fn sraa_texel(x: u32, y: u32) -> vec2<i32> {
    return vec2<i32>(i32(x + frame.origin_x), i32(y + frame.origin_y));
}

// View depth from the host's depth sample: a linear view depth (> 0 and
// finite, anything else a miss), or a hardware depth d inverted through the
// projection, z = |(m32 − d·m33) / (d·m23 − m22)| (forward or reversed Z,
// finite or infinite far plane); +inf (a miss) for the clear value.
fn sraa_decode_depth(d: f32) -> f32 {
    var z = d;
    if HARDWARE_DEPTH {
        if d == frame.depth_miss {
            return subcone_inf();
        }
        let m = frame.projection;
        z = abs((m.y - d * m.w) / (d * m.z - m.x));
    }
    if subcone_is_finite(z) && z > 0.0 {
        return z;
    }
    return subcone_inf();
}

// A unit normal from the host's encoding (xyz signed, or xyz·0.5 + 0.5 with
// UNSIGNED_NORMALS); zero when the vector is zero or not finite.
fn sraa_decode_normal(v: vec3<f32>) -> vec3<f32> {
    var n = v;
    if UNSIGNED_NORMALS {
        n = v * 2.0 - vec3<f32>(1.0);
    }
    let l2 = dot(n, n);
    if l2 > 0.0 && subcone_is_finite(l2) {
        return n * (1.0 / sqrt(l2));
    }
    return vec3<f32>(0.0);
}

// The geometry of a sample from its stored normal (.xyz) and depth (.w):
// decoded, or as stored (DECODED: already the kernels' convention).
fn sraa_geometry(v: vec4<f32>) -> subcone_Geometry {
    if DECODED {
        return subcone_Geometry(v.xyz, v.w);
    }
    let z = sraa_decode_depth(v.w);
    if z == subcone_inf() {
        return subcone_Geometry(vec3<f32>(0.0), z);
    }
    return subcone_Geometry(sraa_decode_normal(v.xyz), z);
}

// Geometric subsample k of pixel p (at SUBPIXEL_OFFSETS[k]).
fn sraa_sub_geo(p: vec2<i32>, k: u32) -> subcone_Geometry {
    return sraa_geometry(sraa_load_sub(p, k));
}

// The geometry of pixel p's shaded sample: its own (SHADED_GIVEN: the
// pixel centre's when the preset shades there, or a host's shaded geometry),
// else subsample SHADED_SUBSAMPLE.
fn sraa_shaded_geo(p: vec2<i32>) -> subcone_Geometry {
    if SHADED_GIVEN {
        return sraa_geometry(sraa_load_shaded(p));
    }
    return sraa_sub_geo(p, subcone_SHADED_SUBSAMPLE);
}

// A secondary hit's geometry from (normal, path length): a NaN depth (no
// mirror here, excluded by every weight) for a negative or NaN length, a
// miss for 0 or +inf, else a hit; as stored with DECODED.
fn sraa_secondary_geometry(v: vec4<f32>) -> subcone_Geometry {
    if DECODED {
        return subcone_Geometry(v.xyz, v.w);
    }
    if subcone_is_nan(v.w) || v.w < 0.0 {
        return subcone_Geometry(vec3<f32>(0.0), bitcast<f32>(0x7fc00000u));
    }
    if v.w == 0.0 || v.w == subcone_inf() {
        return subcone_Geometry(vec3<f32>(0.0), subcone_inf());
    }
    return subcone_Geometry(sraa_decode_normal(v.xyz), v.w);
}

// The hooks of the reconstruction loop (subcone_kernels::sraa::RECONSTRUCT_WGSL).
const SRAA_GATES: u32 = 1u + LIGHTS;
const SRAA_MATERIAL: bool = MATERIAL;

fn sraa_params() -> subcone_SraaParams {
    return frame.sraa;
}

fn sraa_size() -> vec2<u32> {
    return vec2<u32>(frame.width, frame.height);
}

fn sraa_albedo_tolerance() -> f32 {
    return frame.albedo_tolerance;
}

fn sraa_shaded_geometry(x: u32, y: u32, secondary: bool) -> subcone_Geometry {
    let p = sraa_texel(x, y);
    if secondary {
        return sraa_secondary_geometry(sraa_load_sec_shaded(p));
    }
    return sraa_shaded_geo(p);
}

fn sraa_shaded_shadow(x: u32, y: u32, secondary: bool) -> u32 {
    let p = sraa_texel(x, y);
    if secondary {
        return sraa_load_sec_shaded_shadow(p);
    }
    return sraa_load_shaded_shadow(p);
}

fn sraa_shaded_albedo(x: u32, y: u32) -> vec3<f32> {
    return sraa_load_shaded_albedo(sraa_texel(x, y));
}

fn sraa_shaded_value(x: u32, y: u32, layer: u32) -> vec3<f32> {
    return sraa_load_color(sraa_texel(x, y), layer);
}

// Subsample k of pixel (x, y), reconstructed: its primary layers, plus its
// secondary layers where it sees a mirror (§3.3).
fn sraa_reconstruct_subsample(x: u32, y: u32, k: u32) -> vec3<f32> {
    let p = sraa_texel(x, y);
    var c = subcone_sraa_reconstruct_run(sraa_sub_geo(p, k), sraa_load_sub_shadow(p, k), sraa_load_sub_albedo(p, k), false, 0u, x, y, k);
    if SECONDARY {
        let tgt2 = sraa_secondary_geometry(sraa_load_sec_sub(p, k));
        if !subcone_is_nan(tgt2.depth) {
            c = c + subcone_sraa_reconstruct_run(tgt2, sraa_load_sec_sub_shadow(p, k), vec3<f32>(0.0), true, SRAA_GATES, x, y, k);
        }
    }
    return c;
}

@compute @workgroup_size(8, 8)
fn sraa_resolve_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let s0 = sraa_reconstruct_subsample(id.x, id.y, 0u);
    let s1 = sraa_reconstruct_subsample(id.x, id.y, 1u);
    let s2 = sraa_reconstruct_subsample(id.x, id.y, 2u);
    let s3 = sraa_reconstruct_subsample(id.x, id.y, 3u);
    // sraa::ResolveSpace: the box (sraa::resolve_pixel) or Karis' weights
    // (sraa::resolve_pixel_tone_mapped).
    var c: vec3<f32>;
    if TONE_MAPPED_RESOLVE {
        c = subcone_resolve_pixel_tone_mapped(s0, s1, s2, s3, frame.exposure);
    } else {
        c = subcone_resolve_pixel(s0, s1, s2, s3);
    }
    sraa_store(sraa_texel(id.x, id.y), vec4<f32>(c, 1.0));
}
