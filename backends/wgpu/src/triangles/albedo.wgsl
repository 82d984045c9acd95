// Material albedo lookup (subcone_scene::material::Material::albedo_at), shared
// by the ray-tracing shaders (trace.wgsl) and the raster G-buffer
// (raster.wgsl). The including shader declares
// `materials: array<MaterialGpu>` and `texels: array<vec4<f32>>`.

// bvh.rs GpuMaterial.
struct MaterialGpu {
    a: vec3<f32>,
    kind: u32,
    b: vec3<f32>,
    size: f32,
    emission: vec3<f32>,
    mirror: f32,
    extra: vec4<u32>,
}

// material::cell: floor(p.x / s), floor(p.z / s).
fn cell(p: vec3<f32>, size: f32) -> vec2<i32> {
    var s = 1.0;
    if size > 0.0 && subcone_is_finite(size) {
        s = size;
    }
    return vec2<i32>(i32(floor(p.x / s)), i32(floor(p.z / s)));
}

// f32::rem_euclid(x, 1.0).
fn rem_euclid1(x: f32) -> f32 {
    let r = x - trunc(x);
    if r < 0.0 {
        return r + 1.0;
    }
    return r;
}

// Material::albedo_at.
fn albedo_at(m: MaterialGpu, p: vec3<f32>, uv: vec2<f32>) -> vec3<f32> {
    switch m.kind {
        case 1u: {
            let c = cell(p, m.size);
            if ((c.x + c.y) & 1) == 0 {
                return m.a;
            }
            return m.b;
        }
        case 2u: {
            let len = m.extra.y;
            if len == 0u {
                return vec3<f32>(0.5);
            }
            let c = cell(p, m.size);
            var h = (bitcast<u32>(c.x) * 0x9E3779B1u) ^ (bitcast<u32>(c.y) * 0x85EBCA77u);
            h = (h ^ (h >> 15u)) * 0x2C1B3C6Du;
            return texels[m.extra.x + (h >> 7u) % len].xyz;
        }
        case 3u: {
            // Texture::sample: nearest, wrapping.
            let w = m.extra.y;
            let hgt = m.extra.z;
            if m.extra.w == 0u || w == 0u || hgt == 0u || !(subcone_is_finite(uv.x) && subcone_is_finite(uv.y)) {
                return vec3<f32>(0.5);
            }
            let x = u32(rem_euclid1(uv.x) * f32(w)) % w;
            let y = u32(rem_euclid1(1.0 - uv.y) * f32(hgt)) % hgt;
            return texels[m.extra.x + min(y * w + x, m.extra.w - 1u)].xyz;
        }
        default: {
            return m.a;
        }
    }
}
