// Hybrid SRAA's pass 1 (§3.1): the four geometric subsamples rasterised, one
// layer of an Rgba32Float array per subsample: shading normal (facing the
// eye) in .xyz and view depth in .w (-1 where nothing was drawn). Follows
// subcone_kernels::wgsl::PARAMS and sraa::WGSL (for subcone_subpixel_offset).
//
// The projection is Camera::ray inverted: a point at view-space (x, y, z)
// (right, up, forward) lies on the ray through image point p with
// 2·p.x/W − 1 = x / (z·tan(fov/2)·aspect) and 1 − 2·p.y/H = y / (z·tan(fov/2)).
// Subsample k is put at the pixel centre by shifting the image by
// −SUBPIXEL_OFFSETS[k] in clip space, so the fragment at pixel (i, j) shows
// image point (i + 0.5, j + 0.5) + offset: the ray-traced subsample's point.
// Depth is reversed (near / z, compare greater) for precision.
//
// `+mat` (the material gate, sraa::material_gated_weight) draws with
// `fs_albedo` instead of `fs_main`: a second colour attachment, one more
// Rgba32Float array, receives the diffuse albedo at the same point (albedo.wgsl
// at the interpolated world position and uv): the G-buffer's albedo channel,
// the same draw and the same rasterised fragments. Follows albedo.wgsl.


// Bindings (raster.rs): frame (FrameUniform, frame.wgsl), tris, attrs, materials, texels.

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) @interpolate(flat) face: vec3<f32>,
    @location(3) uv: vec2<f32>,
    @location(4) @interpolate(flat) material: u32,
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) k: u32) -> VsOut {
    let tri = vi / 3u;
    let corner = vi % 3u;
    let v0 = tris[3u * tri].xyz;
    let v1 = tris[3u * tri + 1u].xyz;
    let v2 = tris[3u * tri + 2u].xyz;
    let p = tris[3u * tri + corner].xyz;
    let rel = p - frame.cam_pos;
    let z = dot(rel, frame.forward);
    let x = dot(rel, frame.right);
    let y = dot(rel, frame.up);
    // Camera::jitter moves every subsample with the image.
    let o = subcone_subpixel_offset(k) + frame.jitter;
    var out: VsOut;
    out.clip = vec4<f32>(
        x / (frame.half * frame.aspect) - (2.0 * o.x / frame.width_f) * z,
        y / frame.half + (2.0 * o.y / frame.height_f) * z,
        frame.near,
        z,
    );
    out.world = p;
    out.normal = attrs[4u * tri + corner].xyz;
    out.face = cross(v1 - v0, v2 - v0);
    // bvh.rs attrs: n0.xyz uv0.x | n1.xyz uv0.y | n2.xyz uv1.x | uv1.y uv2.x uv2.y 0.
    let a = attrs[4u * tri + 3u];
    switch corner {
        case 0u: { out.uv = vec2<f32>(attrs[4u * tri].w, attrs[4u * tri + 1u].w); }
        case 1u: { out.uv = vec2<f32>(attrs[4u * tri + 2u].w, a.x); }
        default: { out.uv = vec2<f32>(a.y, a.z); }
    }
    out.material = bitcast<u32>(tris[3u * tri].w);
    return out;
}

fn raster_normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let l2 = dot(v, v);
    if l2 > 0.0 && subcone_is_finite(l2) {
        let n = v * (1.0 / sqrt(l2));
        if subcone_sraa_is_finite3(n) {
            return n;
        }
    }
    return vec3<f32>(0.0);
}

// Tracer::intersect's normals and Camera::view_depth at the interpolated
// (perspective-correct, i.e. barycentric) surface point.
fn raster_geometry(in: VsOut) -> vec4<f32> {
    let d = in.world - frame.cam_pos;
    var ng = raster_normalize_or_zero(in.face);
    if dot(ng, d) > 0.0 {
        ng = -ng;
    }
    var n = raster_normalize_or_zero(in.normal);
    if all(n == vec3<f32>(0.0)) {
        n = ng;
    } else if dot(n, d) > 0.0 {
        n = -n;
    }
    return vec4<f32>(n, dot(d, frame.forward));
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return raster_geometry(in);
}

struct GeometryAlbedo {
    @location(0) geometry: vec4<f32>,
    @location(1) albedo: vec4<f32>,
}

// fs_main plus Tracer::primary_albedo at the fragment (`+mat`).
@fragment
fn fs_albedo(in: VsOut) -> GeometryAlbedo {
    var out: GeometryAlbedo;
    out.geometry = raster_geometry(in);
    out.albedo = vec4<f32>(albedo_at(materials[in.material], in.world, in.uv), 0.0);
    return out;
}
