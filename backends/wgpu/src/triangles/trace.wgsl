// BVH traversal and Whitted shading: the GPU twin of subcone-cpu's bvh.rs and
// shade.rs. Concatenated after subcone_kernels::wgsl::PARAMS, sraa::WGSL,
// frame.wgsl and albedo.wgsl; the entry points (supersample.wgsl, subpixel.wgsl) follow.

struct BvhNode {
    min: vec3<f32>,
    count: u32,
    max: vec3<f32>,
    index: u32,
}

struct LightGpu {
    v: vec3<f32>,
    kind: u32,
    value: vec3<f32>,
    _pad: u32,
}

// Group 0 (triangles/mod.rs scene_bindings): frame, nodes, tris, attrs,
// materials, texels, lights and the ray counters.

// STACK_SIZE and MAX_LIGHTS are the host's constants, declared by the
// source triangles/mod.rs `limits_wgsl` puts before this file.
// Mirror bounces a shader follows at most (reflection_depth is clamped to it).
const MAX_BOUNCES: u32 = 64u;
const FRAC_1_PI: f32 = 0.31830987;

// Per-invocation ray counts (shade::Counts), added to `counters` once.
struct Counts {
    primary: u32,
    geometry: u32,
    shadow: u32,
    secondary: u32,
    shaded: u32,
    ao: u32,
}

fn counts_zero() -> Counts {
    return Counts(0u, 0u, 0u, 0u, 0u, 0u);
}

fn counter_add(k: u32, v: u32) {
    if v == 0u {
        return;
    }
    let old = atomicAdd(&counters[2u * k], v);
    if old > 0xffffffffu - v {
        atomicAdd(&counters[2u * k + 1u], 1u);
    }
}

// A traversal's loop ended without finishing: its iteration bound, or a
// driver's loop limiter (llvmpipe stops all loops of an invocation after
// 65 535 iterations in total). The frame is then refused, not returned wrong.
fn traversal_cut() {
    atomicAdd(&counters[10], 1u);
}

fn counts_flush(c: Counts) {
    counter_add(0u, c.primary);
    counter_add(1u, c.geometry);
    counter_add(2u, c.shadow);
    counter_add(3u, c.secondary);
    counter_add(4u, c.shaded);
    // [10] and [11] are the traversal flags; the AO rays follow them.
    counter_add(6u, c.ao);
}

// Camera::ray: the unit direction through image point p (pixels, y down).
fn camera_ray(p_in: vec2<f32>) -> vec3<f32> {
    let p = p_in + frame.jitter;
    let u = (2.0 * p.x / frame.width_f - 1.0) * frame.half * frame.aspect;
    let v = (1.0 - 2.0 * p.y / frame.height_f) * frame.half;
    return normalize(frame.forward + u * frame.right + v * frame.up);
}

// Camera::view_depth.
fn view_depth(p: vec3<f32>) -> f32 {
    return dot(p - frame.cam_pos, frame.forward);
}

// obvhs' Triangle::intersect (Möller–Trumbore as obvhs writes it): t in
// [tmin, tmax] or +inf.
fn intersect_triangle(o: vec3<f32>, d: vec3<f32>, i: u32, tmin: f32, tmax: f32) -> f32 {
    let v0 = tris[3u * i].xyz;
    let v1 = tris[3u * i + 1u].xyz;
    let v2 = tris[3u * i + 2u].xyz;
    let e1 = v0 - v1;
    let e2 = v2 - v0;
    let n = cross(e1, e2);
    let c = v0 - o;
    let r = cross(d, c);
    let inv_det = 1.0 / dot(n, d);
    let u = dot(r, e2) * inv_det;
    let v = dot(r, e1) * inv_det;
    let w = 1.0 - u - v;
    let hit = bitcast<u32>(u) | bitcast<u32>(v) | bitcast<u32>(w);
    if inv_det != 0.0 && (hit & 0x80000000u) == 0u && subcone_is_finite(inv_det) {
        let t = dot(n, c) * inv_det;
        if t >= tmin && t <= tmax {
            return t;
        }
    }
    return subcone_inf();
}

// Slab test: entry distance of the ray into the node's box within [tmin, tmax],
// or +inf when it misses.
fn intersect_box(o: vec3<f32>, inv_d: vec3<f32>, n: u32, tmin: f32, tmax: f32) -> f32 {
    let t1 = (nodes[n].min - o) * inv_d;
    let t2 = (nodes[n].max - o) * inv_d;
    let lo = min(t1, t2);
    let hi = max(t1, t2);
    let t0 = max(max(lo.x, lo.y), max(lo.z, tmin));
    let t3 = min(min(hi.x, hi.y), min(hi.z, tmax));
    if t0 <= t3 {
        return t0;
    }
    return subcone_inf();
}

struct Hit {
    t: f32,
    // Triangle in BVH order; 0xffffffff for a miss.
    tri: u32,
}

// SceneBvh::closest: the closest hit along o + t·d, t in [tmin, ∞).
fn closest(o: vec3<f32>, d: vec3<f32>, tmin: f32) -> Hit {
    var best = Hit(subcone_inf(), 0xffffffffu);
    let inv_d = 1.0 / d;
    var stack: array<u32, STACK_SIZE>;
    var sp = 0u;
    var node = 0u;
    var done = false;
    if intersect_box(o, inv_d, 0u, tmin, best.t) == subcone_inf() {
        return best;
    }
    // Each node is visited at most once per ray: node_count bounds the loop.
    for (var it = 0u; it <= frame.node_count; it++) {
        let nd = nodes[node];
        if nd.count > 0u {
            for (var k = 0u; k < min(nd.count, 255u); k++) {
                let t = intersect_triangle(o, d, nd.index + k, tmin, best.t);
                if t < best.t {
                    best = Hit(t, nd.index + k);
                }
            }
        } else {
            let a = nd.index;
            let b = nd.index + 1u;
            let ta = intersect_box(o, inv_d, a, tmin, best.t);
            let tb = intersect_box(o, inv_d, b, tmin, best.t);
            let hit_a = ta != subcone_inf();
            let hit_b = tb != subcone_inf();
            if hit_a && hit_b {
                let near = select(b, a, ta <= tb);
                let far = select(a, b, ta <= tb);
                if sp < STACK_SIZE {
                    stack[sp] = far;
                    sp++;
                }
                node = near;
                continue;
            } else if hit_a {
                node = a;
                continue;
            } else if hit_b {
                node = b;
                continue;
            }
        }
        // Pop the next node whose box is still in reach.
        var found = false;
        loop {
            if sp == 0u {
                break;
            }
            sp--;
            let cand = stack[sp];
            if intersect_box(o, inv_d, cand, tmin, best.t) != subcone_inf() {
                node = cand;
                found = true;
                break;
            }
        }
        if !found {
            done = true;
            break;
        }
    }
    if !done {
        traversal_cut();
    }
    return best;
}

// SceneBvh::occluded: whether a triangle that casts shadows (emitters do not)
// blocks o + t·d for t in [tmin, tmax].
fn occluded(o: vec3<f32>, d: vec3<f32>, tmin: f32, tmax: f32) -> bool {
    let inv_d = 1.0 / d;
    var stack: array<u32, STACK_SIZE>;
    var sp = 0u;
    var node = 0u;
    var done = false;
    if intersect_box(o, inv_d, 0u, tmin, tmax) == subcone_inf() {
        return false;
    }
    for (var it = 0u; it <= frame.node_count; it++) {
        let nd = nodes[node];
        if nd.count > 0u {
            for (var k = 0u; k < min(nd.count, 255u); k++) {
                let i = nd.index + k;
                if bitcast<u32>(tris[3u * i + 1u].w) != 0u {
                    if intersect_triangle(o, d, i, tmin, tmax) != subcone_inf() {
                        return true;
                    }
                }
            }
        } else {
            let a = nd.index;
            let b = nd.index + 1u;
            let hit_a = intersect_box(o, inv_d, a, tmin, tmax) != subcone_inf();
            let hit_b = intersect_box(o, inv_d, b, tmin, tmax) != subcone_inf();
            if hit_a && hit_b {
                if sp < STACK_SIZE {
                    stack[sp] = b;
                    sp++;
                }
                node = a;
                continue;
            } else if hit_a {
                node = a;
                continue;
            } else if hit_b {
                node = b;
                continue;
            }
        }
        if sp == 0u {
            done = true;
            break;
        }
        sp--;
        node = stack[sp];
    }
    if !done {
        traversal_cut();
    }
    return false;
}

// shade::Surface.
struct Surface {
    p: vec3<f32>,
    t: f32,
    n: vec3<f32>,
    material: u32,
    ng: vec3<f32>,
    hit: bool,
    uv: vec2<f32>,
}

fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let l2 = dot(v, v);
    if l2 > 0.0 && subcone_is_finite(l2) {
        let r = 1.0 / sqrt(l2);
        let n = v * r;
        if subcone_sraa_is_finite3(n) {
            return n;
        }
    }
    return vec3<f32>(0.0);
}

// Tracer::intersect: the closest surface along a ray, with interpolated
// shading normal and uv (barycentrics from areas), both normals facing the ray.
fn intersect(o: vec3<f32>, d: vec3<f32>, tmin: f32) -> Surface {
    var s: Surface;
    let h = closest(o, d, tmin);
    s.hit = h.tri != 0xffffffffu;
    if !s.hit {
        return s;
    }
    let i = h.tri;
    let v0 = tris[3u * i].xyz;
    let v1 = tris[3u * i + 1u].xyz;
    let v2 = tris[3u * i + 2u].xyz;
    let p = o + h.t * d;
    let e1 = v1 - v0;
    let e2 = v2 - v0;
    var ng = cross(e1, e2);
    let area2 = max(dot(ng, ng), 1.17549435e-38);
    let b1 = dot(cross(p - v0, e2), ng) / area2;
    let b2 = dot(cross(e1, p - v0), ng) / area2;
    let b0 = 1.0 - b1 - b2;
    let a0 = attrs[4u * i];
    let a1 = attrs[4u * i + 1u];
    let a2 = attrs[4u * i + 2u];
    let a3 = attrs[4u * i + 3u];
    ng = normalize_or_zero(ng);
    if dot(ng, d) > 0.0 {
        ng = -ng;
    }
    var n = normalize_or_zero(b0 * a0.xyz + b1 * a1.xyz + b2 * a2.xyz);
    if all(n == vec3<f32>(0.0)) {
        n = ng;
    } else if dot(n, d) > 0.0 {
        n = -n;
    }
    let uv0 = vec2<f32>(a0.w, a1.w);
    let uv1 = vec2<f32>(a2.w, a3.x);
    let uv2 = vec2<f32>(a3.y, a3.z);
    s.p = p;
    s.t = h.t;
    s.n = n;
    s.ng = ng;
    s.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
    s.material = bitcast<u32>(tris[3u * i].w);
    return s;
}

// Tracer::primary_geometry.
fn primary_geometry(s: Surface) -> subcone_Geometry {
    if !s.hit {
        return subcone_Geometry(vec3<f32>(0.0), subcone_inf());
    }
    return subcone_Geometry(s.n, view_depth(s.p));
}

// Tracer::primary_albedo: the diffuse albedo at a primary hit (texture or
// pattern lookup), black for a miss; the material gate's input.
fn primary_albedo(s: Surface) -> vec3<f32> {
    if !s.hit {
        return vec3<f32>(0.0);
    }
    return albedo_at(materials[s.material], s.p, s.uv);
}

// light::Incident; `ok` false where Light::incident returns None.
struct Incident {
    direction: vec3<f32>,
    distance: f32,
    irradiance: vec3<f32>,
    ok: bool,
}

// Light::incident.
fn incident(l: LightGpu, p: vec3<f32>) -> Incident {
    var r: Incident;
    r.ok = false;
    if l.kind == 0u {
        let to = l.v - p;
        let d2 = dot(to, to);
        if !(subcone_is_finite(d2) && d2 > 0.0) {
            return r;
        }
        let d = sqrt(d2);
        r.direction = to / d;
        r.distance = d;
        r.irradiance = l.value / d2;
        r.ok = true;
    } else if l.kind == 1u {
        r.direction = l.v;
        r.distance = subcone_inf();
        r.irradiance = l.value;
        r.ok = true;
    }
    return r;
}

// shade::Tracer::shadow_states_masked: bit l set = in light l's shadow,
// casting a shadow ray only for the lights in `cast_mask`; the others keep the free answers
// (no incident light: lit; facing away: shadowed) and otherwise take their bit
// from `inherited`.
fn shadow_states_masked(s: Surface, cast_mask: u32, inherited: u32, c: ptr<function, Counts>) -> u32 {
    var bits = 0u;
    let origin = s.p + s.ng * frame.eps;
    for (var l = 0u; l < min(frame.lights, MAX_LIGHTS); l++) {
        let inc = incident(lights[l], s.p);
        if !inc.ok {
            continue;
        }
        if dot(inc.direction, s.ng) <= 0.0 {
            bits |= 1u << l;
            continue;
        }
        if (cast_mask & (1u << l)) == 0u {
            bits |= inherited & (1u << l);
            continue;
        }
        (*c).shadow += 1u;
        if occluded(origin, inc.direction, 0.0, inc.distance - frame.eps) {
            bits |= 1u << l;
        }
    }
    return bits;
}

// Tracer::shadow_states: a shadow ray for every light that faces the surface.
fn shadow_states(s: Surface, c: ptr<function, Counts>) -> u32 {
    return shadow_states_masked(s, 0xffffffffu, 0u, c);
}

// shade::Parts.
struct Parts {
    base: vec3<f32>,
    mirror: f32,
    direct: array<vec3<f32>, 8>,
}

// Tracer::ambient_occlusion: the unoccluded fraction of frame.ao_rays fixed
// directions (subcone_ao_direction) around the shading normal, any-hit rays of
// length frame.ao_radius; a direction below the geometric surface is occluded
// without a ray. Exactly 1 when AO is off.
fn ambient_occlusion(s: Surface, c: ptr<function, Counts>) -> f32 {
    let n = frame.ao_rays;
    if n == 0u {
        return 1.0;
    }
    let origin = s.p + s.ng * frame.eps;
    var open = 0u;
    for (var i = 0u; i < n; i++) {
        let d = subcone_ao_direction(s.n, i, n);
        if dot(d, s.ng) <= 0.0 {
            continue;
        }
        (*c).ao += 1u;
        if !occluded(origin, d, 0.0, frame.ao_radius) {
            open += 1u;
        }
    }
    return subcone_ao_fraction(open, n);
}

// Tracer::parts: `ao` multiplies the ambient term (1 at mirror hits).
fn parts(s: Surface, shadowed: u32, ao: f32) -> Parts {
    let mat = materials[s.material];
    let albedo = albedo_at(mat, s.p, s.uv);
    var r: Parts;
    r.base = mat.emission + frame.ambient * ao * albedo;
    r.mirror = mat.mirror;
    for (var l = 0u; l < MAX_LIGHTS; l++) {
        r.direct[l] = vec3<f32>(0.0);
    }
    for (var l = 0u; l < min(frame.lights, MAX_LIGHTS); l++) {
        if (shadowed & (1u << l)) != 0u {
            continue;
        }
        let inc = incident(lights[l], s.p);
        if inc.ok {
            let cos = max(dot(inc.direction, s.n), 0.0);
            r.direct[l] = albedo * FRAC_1_PI * cos * inc.irradiance;
        }
    }
    return r;
}

// Parts::diffuse.
fn diffuse(p: Parts) -> vec3<f32> {
    var c = p.base;
    for (var l = 0u; l < min(frame.lights, MAX_LIGHTS); l++) {
        c = c + p.direct[l];
    }
    return c;
}

// Tracer::reflect.
fn reflect_dir(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return normalize(d - 2.0 * dot(d, n) * n);
}

// Tracer::radiance, iterated instead of recursed: (1 − m)·diffuse + m·(reflected),
// `depth` bounces already taken, at most MAX_BOUNCES followed; ambient
// occlusion at depth 0 only.
fn radiance(o0: vec3<f32>, d0: vec3<f32>, depth0: u32, c: ptr<function, Counts>) -> vec3<f32> {
    var o = o0;
    var d = d0;
    var depth = depth0;
    var acc = vec3<f32>(0.0);
    var thr = 1.0;
    let max_depth = min(frame.reflection_depth, depth0 + MAX_BOUNCES);
    for (var it = 0u; it <= MAX_BOUNCES; it++) {
        let s = intersect(o, d, 0.0);
        if !s.hit {
            acc = acc + thr * frame.background;
            break;
        }
        (*c).shaded += 1u;
        let sh = shadow_states(s, c);
        var ao = 1.0;
        if depth == 0u {
            ao = ambient_occlusion(s, c);
        }
        let pa = parts(s, sh, ao);
        let dif = diffuse(pa);
        if pa.mirror > 0.0 && depth < max_depth {
            (*c).secondary += 1u;
            acc = acc + thr * ((1.0 - pa.mirror) * dif);
            thr = thr * pa.mirror;
            o = s.p + s.ng * frame.eps;
            d = reflect_dir(d, s.n);
            depth++;
        } else {
            acc = acc + thr * dif;
            break;
        }
    }
    return acc;
}
