//! The scene's materials and lights as WGSL: `material_albedo`,
//! `material_emission`, `material_opacity`, `MATERIAL_COUNT` and
//! `shade_lights`, with the same formulas as `Material::albedo_at`,
//! `Material::opacity` and `Light::incident` and the light loop of
//! `SdfView::shade` (subcone-cpu).

use std::fmt::Write;

use glam::{Vec2, Vec3};
use subcone_scene::{Albedo, Light, Material, RenderError};

use crate::context::err;

use subcone_sdf::wgsl::{f32_literal as f, vec3_literal as v3};

/// Materials and lights as WGSL. Errors on no materials.
pub(crate) fn shading_wgsl(
    materials: &[Material],
    lights: &[Light],
    shadows: bool,
) -> Result<String, RenderError> {
    if materials.is_empty() {
        return Err(err("the scene has no materials"));
    }
    let mut s = String::new();
    push_material_albedo(&mut s, materials);
    push_material_emission(&mut s, materials);
    push_material_opacity(&mut s, materials);
    push_shade_lights(&mut s, &light_rows(lights), shadows);
    Ok(s)
}

/// `MATERIAL_COUNT`, `material_cell` and `material_albedo`: a switch over
/// the materials' [`albedo_body`]s.
fn push_material_albedo(s: &mut String, materials: &[Material]) {
    let _ = write!(
        s,
        concat!(
            "const MATERIAL_COUNT: u32 = {}u;\n\n",
            "// Material::albedo_at's cell: (floor(x / size), floor(z / size)).\n",
            "fn material_cell(p: vec3<f32>, size: f32) -> vec2<i32> {{\n",
            "    return vec2<i32>(i32(floor(p.x / size)), i32(floor(p.z / size)));\n",
            "}}\n\n",
            "// Material::albedo_at (SDF scenes have no texture coordinates: uv = 0).\n",
            "fn material_albedo(m: u32, p: vec3<f32>) -> vec3<f32> {{\n",
            "    switch m {{\n",
        ),
        materials.len()
    );
    for (i, m) in materials.iter().enumerate() {
        let body = albedo_body(&m.albedo);
        let _ = writeln!(s, "        case {i}u: {{\n            {body}\n        }}");
    }
    s.push_str("        default: { return vec3<f32>(0.5); }\n    }\n}\n\n");
}

/// The WGSL statements of `Material::albedo_at` for one albedo at point `p`.
fn albedo_body(albedo: &Albedo) -> String {
    match albedo {
        Albedo::Solid(c) => format!("return {};", v3(*c)),
        Albedo::Checker { a, b, size } => {
            let size = if *size > 0.0 && size.is_finite() {
                *size
            } else {
                1.0
            };
            format!(
                "let c = material_cell(p, {}); if ((c.x + c.y) & 1) == 0 {{ return {}; }} return {};",
                f(size),
                v3(*a),
                v3(*b)
            )
        }
        Albedo::Patches { palette, size } => {
            if palette.is_empty() {
                "return vec3<f32>(0.5);".to_string()
            } else {
                let size = if *size > 0.0 && size.is_finite() {
                    *size
                } else {
                    1.0
                };
                let mut b = format!(
                    concat!(
                        "let c = bitcast<vec2<u32>>(material_cell(p, {}));\n",
                        "            var h = (c.x * 0x9E3779B1u) ^ (c.y * 0x85EBCA77u);\n",
                        "            h = (h ^ (h >> 15u)) * 0x2C1B3C6Du;\n",
                        "            switch (h >> 7u) % {}u {{\n",
                    ),
                    f(size),
                    palette.len()
                );
                for (j, c) in palette.iter().enumerate() {
                    let _ = writeln!(b, "                case {j}u: {{ return {}; }}", v3(*c));
                }
                b.push_str("                default: { return vec3<f32>(0.5); }\n            }");
                b
            }
        }
        // Without texture coordinates every point samples uv = (0, 0).
        Albedo::Texture(t) => format!("return {};", v3(t.sample(Vec2::ZERO))),
    }
}

/// `material_emission`: a switch over the materials' emission.
fn push_material_emission(s: &mut String, materials: &[Material]) {
    s.push_str("fn material_emission(m: u32) -> vec3<f32> {\n    switch m {\n");
    for (i, m) in materials.iter().enumerate() {
        let _ = writeln!(s, "        case {i}u: {{ return {}; }}", v3(m.emission));
    }
    s.push_str("        default: { return vec3<f32>(0.0); }\n    }\n}\n\n");
}

/// `material_opacity`: Material::opacity (NaN is 1); ids past the list read
/// the last material, as SdfView::material_opacity does. The
/// semi-transparent path (translucent.wgsl, CTSS §5.3) is its only caller.
fn push_material_opacity(s: &mut String, materials: &[Material]) {
    s.push_str(concat!(
        "// SdfView::material_opacity: the object's opacity along a ray.\n",
        "fn material_opacity(m: u32) -> f32 {\n",
        "    switch m {\n",
    ));
    for (i, m) in materials.iter().enumerate().take(materials.len() - 1) {
        let _ = writeln!(s, "        case {i}u: {{ return {}; }}", f(m.opacity()));
    }
    let last = materials.last().map_or(1.0, Material::opacity);
    let _ = writeln!(
        s,
        "        default: {{ return {}; }}\n    }}\n}}\n",
        f(last)
    );
}

/// One row of the `LIGHTS` table per light that can light anything:
/// (position or unit direction, kind 0 = point / 1 = directional,
/// intensity or irradiance). Directions are normalised here as
/// Light::incident does (normalize_or_zero); zero ones never light
/// anything and get no row.
fn light_rows(lights: &[Light]) -> Vec<(Vec3, f32, Vec3)> {
    let mut rows = Vec::new();
    for l in lights {
        match *l {
            Light::Point {
                position,
                intensity,
            } => rows.push((position, 0.0, intensity)),
            Light::Directional {
                direction,
                irradiance,
            } => {
                let d = direction.normalize_or_zero();
                if d != Vec3::ZERO {
                    rows.push((d, 1.0, irradiance));
                }
            }
        }
    }
    rows
}

/// `shade_lights` (SdfView::shade's light loop over the `LIGHTS` table
/// `rows`, with hard shadows) and the table itself; without `shadows` or
/// lights, an empty loop and no table.
fn push_shade_lights(s: &mut String, rows: &[(Vec3, f32, Vec3)], shadows: bool) {
    s.push_str(concat!(
        "// SdfView::shade's light loop: Lambert, hard shadows by sphere tracing.\n",
        "fn shade_lights(p: vec3<f32>, n: vec3<f32>, albedo: vec3<f32>, c: ptr<function, vec3<f32>>, count: ptr<function, u32>) {\n",
    ));
    if shadows && !rows.is_empty() {
        let _ = writeln!(
            s,
            concat!(
                "    for (var i = 0u; i < {}u; i++) {{\n",
                "        let a = LIGHTS[2u * i];\n",
                "        let e = LIGHTS[2u * i + 1u].xyz;\n",
                "        var dir = a.xyz;\n",
                "        var dist = subcone_inf();\n",
                "        var irr = e;\n",
                "        if a.w == 0.0 {{\n",
                "            // Light::incident of a point light.\n",
                "            let to = a.xyz - p;\n",
                "            let d2 = dot(to, to);\n",
                "            if !(subcone_is_finite(d2) && d2 > 0.0) {{ continue; }}\n",
                "            dist = sqrt(d2);\n",
                "            dir = to / dist;\n",
                "            irr = e / d2;\n",
                "        }}\n",
                "        let cos = dot(dir, n);\n",
                "        if cos <= 0.0 || shadowed(p, n, dir, dist, count) {{ continue; }}\n",
                "        *c += albedo * 0.31830987f * cos * irr;\n",
                "    }}",
            ),
            rows.len()
        );
    } else {
        s.push_str("    // No lights: no shadow rays.\n");
    }
    s.push_str("}\n");
    if shadows && !rows.is_empty() {
        let _ = writeln!(
            s,
            "var<private> LIGHTS: array<vec4<f32>, {}> = array<vec4<f32>, {}>(",
            2 * rows.len(),
            2 * rows.len()
        );
        for (a, kind, e) in rows {
            let _ = writeln!(
                s,
                "    vec4<f32>({}, {}, {}, {}), vec4<f32>({}, {}, {}, 0.0),",
                f(a.x),
                f(a.y),
                f(a.z),
                f(*kind),
                f(e.x),
                f(e.y),
                f(e.z)
            );
        }
        s.push_str(");\n");
    }
}

/// `SdfIncident`, `SCENE_LIGHTS` and `light_incident(l, p)`: `Light::incident`
/// of the scene's light `l` (indexed as the scene lists them, up to the
/// kernels' `MAX_LIGHTS`, as SRAA-RT's shadow bits and light layers are),
/// `ok` false where it lights nothing (a point light at `p`, a zero
/// direction). Directions are made unit here as `Light::incident` makes them.
pub(crate) fn light_incident_wgsl(lights: &[Light]) -> String {
    use subcone_kernels::math::Euclidean;
    let lights = &lights[..lights.len().min(subcone_kernels::passes::MAX_LIGHTS)];
    let mut s = format!(
        concat!(
            "const SCENE_LIGHTS: u32 = {}u;\n\n",
            "struct SdfIncident {{\n",
            "    direction: vec3<f32>,\n",
            "    distance: f32,\n",
            "    irradiance: vec3<f32>,\n",
            "    ok: bool,\n",
            "}}\n\n",
            "// Light::incident of the scene's light l at p.\n",
            "fn light_incident(l: u32, p: vec3<f32>) -> SdfIncident {{\n",
            "    var r: SdfIncident;\n",
            "    r.ok = false;\n",
            "    switch l {{\n",
        ),
        lights.len()
    );
    for (i, l) in lights.iter().enumerate() {
        let body = match *l {
            Light::Point {
                position,
                intensity,
            } => format!(
                concat!(
                    "let to = {} - p;\n",
                    "            let d2 = dot(to, to);\n",
                    "            if subcone_is_finite(d2) && d2 > 0.0 {{\n",
                    "                r.ok = true;\n",
                    "                r.distance = sqrt(d2);\n",
                    "                r.direction = to / r.distance;\n",
                    "                r.irradiance = {} / d2;\n",
                    "            }}"
                ),
                v3(position),
                v3(intensity)
            ),
            Light::Directional {
                direction,
                irradiance,
            } => {
                let d = direction.unit_or_zero();
                if d == Vec3::ZERO {
                    "// A zero direction lights nothing.".to_string()
                } else {
                    format!(
                        "r.ok = true;\n            r.direction = {};\n            r.distance = subcone_inf();\n            r.irradiance = {};",
                        v3(d),
                        v3(irradiance)
                    )
                }
            }
        };
        let _ = writeln!(s, "        case {i}u: {{\n            {body}\n        }}");
    }
    s.push_str("        default: {}\n    }\n    return r;\n}\n");
    s
}
