//! `subcone shaders`: every pass of `subcone-passes` as SPIR-V, HLSL, GLSL
//! and MSL, cross-compiled by naga from the one WGSL the wgpu pass runs,
//! each with a resource table an engine binds from.
//!
//! For every [`StandaloneShader`] (the catalog of
//! [`subcone_passes::standalone::catalog`], plus a host's own CTSS field
//! with `--ctss-field`) it writes, under `<out>/<pass>/`:
//!
//! | file | what |
//! |---|---|
//! | `<variant>.wgsl` | the source, bindings declared |
//! | `<variant>.spv` | SPIR-V 1.0, entry point as named in the table |
//! | `<variant>.hlsl` | HLSL, shader model 6.0 |
//! | `<variant>.comp` | GLSL 450 |
//! | `<variant>.es.comp` | GLSL ES 310, where naga can express the shader in it |
//! | `<variant>.metal` | MSL 2.1 |
//!
//! and `<out>/<pass>.json` and `<out>/<pass>.md`: per variant, the entry
//! point, the workgroup size and dispatch, each binding's set, binding,
//! kind, format and access with its register, binding or slot in each
//! language, and every struct the host fills or reads (uniforms, buffer
//! elements) with its members' offsets from naga's layouter: the layout
//! the shader reads. `<out>/README.md` lists them all.
//!
//! Every output is a pure function of the WGSL, so the committed
//! `shaders/` is checked by regenerating it (`--check`, and the test
//! `tests/shaders.rs`). Every text file's first line says so in the file's
//! own comment syntax ([`GENERATED`], written by [`mark_generated`]): `//`
//! in WGSL, HLSL and MSL, an HTML comment in Markdown; in GLSL the `//`
//! line is the second, after `#version`, which GLSL ES 3.x requires on the
//! first line (glslang rejects an ES shader with a comment before it). JSON has no comments (its `generator` field
//! names the generator, and the repository's `.gitattributes` marks the
//! directory generated) and SPIR-V is binary: both are written as they are.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use naga::back::{glsl, hlsl, msl, spv};
use naga::proc::{BoundsCheckPolicies, BoundsCheckPolicy};
use subcone_passes::bind::{BindingEntry, BindingKind};
use subcone_passes::standalone::StandaloneShader;

/// A shader that naga could not parse, validate or translate.
#[derive(Debug)]
pub struct ShaderError {
    /// `pass/variant`.
    pub shader: String,
    /// The stage and naga's message.
    pub message: String,
}

impl std::fmt::Display for ShaderError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.shader, self.message)
    }
}

impl std::error::Error for ShaderError {}

/// One file of the output: its path under the output directory and bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OutputFile {
    /// Relative path (`sraa/buffers.spv`).
    pub path: PathBuf,
    /// Contents.
    pub bytes: Vec<u8>,
}

/// Bounds checks of every translation: out-of-range indices and texel
/// loads read zero and writes are skipped, as wgpu's own translation does
/// by default, so no language's output reads memory the WGSL could not.
const POLICIES: BoundsCheckPolicies = BoundsCheckPolicies {
    index: BoundsCheckPolicy::ReadZeroSkipWrite,
    buffer: BoundsCheckPolicy::ReadZeroSkipWrite,
    image_load: BoundsCheckPolicy::ReadZeroSkipWrite,
    binding_array: BoundsCheckPolicy::Unchecked,
};

/// GLSL ES 3.10 cannot query a texture's levels or samples, so naga cannot
/// bounds-check a texel load's level or sample index there: its texel
/// loads are unchecked. Every pass clamps its texel coordinates to the
/// size in its uniform and loads level 0 and samples `0..4`, so a host that
/// binds textures of that size and of the table's sample count stays in
/// bounds (the table says so on each ES file).
const POLICIES_ES: BoundsCheckPolicies = BoundsCheckPolicies {
    image_load: BoundsCheckPolicy::Unchecked,
    ..POLICIES
};

/// What the table says of a GLSL ES file.
const ES_NOTE: &str = "texel loads are not bounds-checked (ES 3.10 cannot query levels or \
     samples): bind textures of the uniform's size and the table's sample count";

/// The GLSL versions written: desktop 450 always, ES 310 where naga can.
const GLSL_CORE: u16 = 450;
const GLSL_ES: u16 = 310;
/// The MSL version written.
const MSL_VERSION: (u8, u8) = (2, 1);

/// Where one binding lands in each language.
struct Slots {
    /// HLSL `register(<letter><n>, space<g>)`.
    hlsl: String,
    /// GLSL `layout(binding = n)`.
    glsl: u32,
    /// MSL `[[buffer(n)]]` for a buffer, `[[texture(n)]]` for a texture
    /// ([`msl_slot`]): each kind counts its own slots.
    msl: u8,
}

/// MSL's spelling of a binding's slot.
fn msl_slot(kind: &BindingKind, index: u8) -> String {
    let space = if is_buffer(kind) { "buffer" } else { "texture" };
    format!("{space}({index})")
}

/// HLSL's register class of a binding: constant buffers `b`, what the
/// shader only reads `t`, what it writes `u`.
fn hlsl_register(kind: &BindingKind) -> char {
    match kind {
        BindingKind::Uniform { .. } => 'b',
        BindingKind::Storage { read_only: true } | BindingKind::Texture { .. } => 't',
        BindingKind::Storage { read_only: false } | BindingKind::StorageTexture { .. } => 'u',
    }
}

fn is_buffer(kind: &BindingKind) -> bool {
    matches!(
        kind,
        BindingKind::Uniform { .. } | BindingKind::Storage { .. }
    )
}

/// The slots of every binding, and the MSL slot of the buffer of runtime
/// array sizes (naga's `_buffer_sizes`), after the last buffer.
fn slots(bindings: &[BindingEntry]) -> (Vec<Slots>, u8) {
    let (mut buffers, mut textures) = (0u8, 0u8);
    let glsl = glsl_bindings(bindings);
    let list = bindings
        .iter()
        .zip(glsl)
        .map(|(b, glsl)| {
            let counter = if is_buffer(&b.kind) {
                &mut buffers
            } else {
                &mut textures
            };
            let msl = *counter;
            *counter += 1;
            Slots {
                hlsl: format!(
                    "register({}{}, space{})",
                    hlsl_register(&b.kind),
                    b.binding,
                    b.group
                ),
                glsl,
                msl,
            }
        })
        .collect();
    (list, buffers)
}

/// Each binding's GLSL `layout(binding = n)`: GLSL has no sets, so a
/// pass's own bindings (group 0) keep their numbers and a host's (group 1,
/// a CTSS field's own resources) follow after the largest of them, in
/// order.
fn glsl_bindings(bindings: &[BindingEntry]) -> Vec<u32> {
    let mut next = bindings
        .iter()
        .filter(|b| b.group == 0)
        .map(|b| b.binding + 1)
        .max()
        .unwrap_or(0);
    bindings
        .iter()
        .map(|b| {
            if b.group == 0 {
                b.binding
            } else {
                next += 1;
                next - 1
            }
        })
        .collect()
}

/// `s` with the resources its module declares beyond `s.bindings` (a host
/// CTSS field's own `@group(1)` uniforms, storage buffers and textures)
/// appended, so that every language's output binds them and the tables
/// list them. A resource no table row can describe (a sampler, a binding
/// array, a storage texture of a format the tables do not name) is an
/// error naming it, rather than a shader that silently lacks its entry
/// point or binding.
fn with_module_bindings(
    s: &StandaloneShader,
    m: &naga::Module,
    layouter: &naga::proc::Layouter,
) -> Result<StandaloneShader, String> {
    let mut out = s.clone();
    for (_, var) in m.global_variables.iter() {
        let Some(rb) = var.binding else { continue };
        if out
            .bindings
            .iter()
            .any(|b| b.group == rb.group && b.binding == rb.binding)
        {
            continue;
        }
        let name = var.name.clone().unwrap_or_default();
        let refuse = |what: &str| {
            format!(
                "@group({}) @binding({}) `{name}` is {what}: the standalone shaders' tables                  and every language's bindings describe uniform and storage buffers and                  textures read with textureLoad, so this field's resource cannot be                  expressed (read a texture with textureLoad instead)",
                rb.group, rb.binding
            )
        };
        let kind = match (var.space, &m.types[var.ty].inner) {
            (naga::AddressSpace::Uniform, _) => BindingKind::Uniform {
                size: Some(u64::from(layouter[var.ty].size)),
            },
            (naga::AddressSpace::Storage { access }, _) => BindingKind::Storage {
                read_only: !access.contains(naga::StorageAccess::STORE),
            },
            (
                naga::AddressSpace::Handle,
                naga::TypeInner::Image {
                    dim: naga::ImageDimension::D2,
                    arrayed,
                    class,
                },
            ) => match class {
                naga::ImageClass::Sampled { kind, multi } => BindingKind::Texture {
                    sample: match kind {
                        naga::ScalarKind::Uint => "uint",
                        naga::ScalarKind::Sint => "sint",
                        _ => "float",
                    },
                    array: *arrayed,
                    multisampled: *multi,
                },
                naga::ImageClass::Depth { multi } => BindingKind::Texture {
                    sample: "depth",
                    array: *arrayed,
                    multisampled: *multi,
                },
                naga::ImageClass::Storage { format, .. } if !*arrayed => {
                    BindingKind::StorageTexture {
                        format: storage_format(*format)
                            .ok_or_else(|| refuse(&format!("a storage texture of {format:?}")))?,
                    }
                }
                _ => return Err(refuse("an arrayed storage texture")),
            },
            (naga::AddressSpace::Handle, naga::TypeInner::Sampler { .. }) => {
                return Err(refuse("a sampler"))
            }
            (naga::AddressSpace::Handle, naga::TypeInner::BindingArray { .. }) => {
                return Err(refuse("a binding array"))
            }
            _ => return Err(refuse("a resource of another kind")),
        };
        out.bindings.push(BindingEntry {
            group: rb.group,
            binding: rb.binding,
            name,
            wgsl_type: wgsl_type(m, var.ty),
            kind,
        });
    }
    out.bindings.sort_by_key(|b| (b.group, b.binding));
    Ok(out)
}

/// WGSL's name of a storage texel format the tables can name.
fn storage_format(f: naga::StorageFormat) -> Option<&'static str> {
    use naga::StorageFormat as F;
    Some(match f {
        F::Rgba8Unorm => "rgba8unorm",
        F::Rgba16Float => "rgba16float",
        F::Rgba32Float => "rgba32float",
        F::R32Float => "r32float",
        F::R32Uint => "r32uint",
        F::R32Sint => "r32sint",
        F::Rg32Float => "rg32float",
        _ => return None,
    })
}

/// A binding's WGSL type as the tables print it: a buffer's type, or a
/// texture's (`texture_2d<f32>`).
fn wgsl_type(m: &naga::Module, ty: naga::Handle<naga::Type>) -> String {
    match &m.types[ty].inner {
        naga::TypeInner::Image {
            arrayed,
            class: naga::ImageClass::Sampled { kind, multi },
            ..
        } => {
            let scalar = match kind {
                naga::ScalarKind::Uint => "u32",
                naga::ScalarKind::Sint => "i32",
                _ => "f32",
            };
            let shape = match (multi, arrayed) {
                (true, _) => "texture_multisampled_2d",
                (false, true) => "texture_2d_array",
                (false, false) => "texture_2d",
            };
            format!("{shape}<{scalar}>")
        }
        naga::TypeInner::Image {
            class: naga::ImageClass::Depth { .. },
            ..
        } => "texture_depth_2d".into(),
        naga::TypeInner::Image {
            class: naga::ImageClass::Storage { format, .. },
            ..
        } => format!(
            "texture_storage_2d<{}, write>",
            storage_format(*format).unwrap_or("?")
        ),
        _ => type_name(m, ty),
    }
}

fn resource_binding(b: &BindingEntry) -> naga::ResourceBinding {
    naga::ResourceBinding {
        group: b.group,
        binding: b.binding,
    }
}

/// Parse and validate `wgsl`.
fn module(wgsl: &str) -> Result<(naga::Module, naga::valid::ModuleInfo), String> {
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| e.emit_to_string(wgsl))?;
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::empty(),
    )
    .validate(&module)
    .map_err(|e| e.emit_to_string(wgsl))?;
    Ok((module, info))
}

fn spirv(
    m: &naga::Module,
    info: &naga::valid::ModuleInfo,
    s: &StandaloneShader,
) -> Result<Vec<u8>, String> {
    let options = spv::Options {
        lang_version: (1, 0),
        flags: spv::WriterFlags::empty(),
        bounds_check_policies: POLICIES,
        ..Default::default()
    };
    let pipeline = spv::PipelineOptions {
        shader_stage: naga::ShaderStage::Compute,
        entry_point: s.entry_point.to_owned(),
    };
    let words = spv::write_vec(m, info, &options, Some(&pipeline)).map_err(|e| e.to_string())?;
    Ok(words.iter().flat_map(|w| w.to_le_bytes()).collect())
}

fn hlsl_source(
    m: &naga::Module,
    info: &naga::valid::ModuleInfo,
    s: &StandaloneShader,
) -> Result<String, String> {
    let options = hlsl::Options {
        shader_model: hlsl::ShaderModel::V6_0,
        // Register = binding, space = group (the table's `hlsl` column).
        fake_missing_bindings: true,
        ..Default::default()
    };
    let pipeline = hlsl::PipelineOptions {
        entry_point: Some((naga::ShaderStage::Compute, s.entry_point.to_owned())),
    };
    let mut out = String::new();
    hlsl::Writer::new(&mut out, &options, &pipeline)
        .write(m, info, None)
        .map_err(|e| e.to_string())?;
    Ok(out)
}

fn glsl_source(
    m: &naga::Module,
    info: &naga::valid::ModuleInfo,
    s: &StandaloneShader,
    version: glsl::Version,
    policies: BoundsCheckPolicies,
) -> Result<String, String> {
    let binding_map = s
        .bindings
        .iter()
        .zip(glsl_bindings(&s.bindings))
        .map(|(b, glsl)| (resource_binding(b), glsl as u8))
        .collect();
    let options = glsl::Options {
        version,
        writer_flags: glsl::WriterFlags::empty(),
        binding_map,
        zero_initialize_workgroup_memory: true,
    };
    let pipeline = glsl::PipelineOptions {
        shader_stage: naga::ShaderStage::Compute,
        entry_point: s.entry_point.to_owned(),
        multiview: None,
    };
    let mut out = String::new();
    glsl::Writer::new(&mut out, m, info, &options, &pipeline, policies)
        .and_then(|mut w| w.write().map(|_| ()))
        .map_err(|e| e.to_string())?;
    Ok(out)
}

fn msl_source(
    m: &naga::Module,
    info: &naga::valid::ModuleInfo,
    s: &StandaloneShader,
    slots: &[Slots],
    sizes_slot: u8,
) -> Result<String, String> {
    let resources = s
        .bindings
        .iter()
        .zip(slots)
        .map(|(b, slot)| {
            let target = if is_buffer(&b.kind) {
                msl::BindTarget {
                    buffer: Some(slot.msl),
                    mutable: matches!(b.kind, BindingKind::Storage { read_only: false }),
                    ..Default::default()
                }
            } else {
                msl::BindTarget {
                    texture: Some(slot.msl),
                    mutable: matches!(b.kind, BindingKind::StorageTexture { .. }),
                    ..Default::default()
                }
            };
            (resource_binding(b), target)
        })
        .collect();
    let mut per_entry_point_map = BTreeMap::new();
    per_entry_point_map.insert(
        s.entry_point.to_owned(),
        msl::EntryPointResources {
            resources,
            sizes_buffer: Some(sizes_slot),
            ..Default::default()
        },
    );
    let options = msl::Options {
        lang_version: MSL_VERSION,
        per_entry_point_map,
        fake_missing_bindings: false,
        bounds_check_policies: POLICIES,
        ..Default::default()
    };
    let pipeline = msl::PipelineOptions {
        entry_point: Some((naga::ShaderStage::Compute, s.entry_point.to_owned())),
        ..Default::default()
    };
    msl::write_string(m, info, &options, &pipeline)
        .map(|(source, _)| source)
        .map_err(|e| e.to_string())
}

/// A struct's members, flattened (`sraa.sigma_z`), with offsets from
/// naga's layouter.
fn struct_members(
    m: &naga::Module,
    layouter: &naga::proc::Layouter,
    ty: naga::Handle<naga::Type>,
    prefix: &str,
    base: u32,
    out: &mut Vec<serde_json::Value>,
) {
    match &m.types[ty].inner {
        naga::TypeInner::Struct { members, .. } => {
            for member in members {
                let name = format!("{prefix}{}", member.name.as_deref().unwrap_or("?"));
                if let naga::TypeInner::Struct { .. } = m.types[member.ty].inner {
                    let nested = format!("{name}.");
                    struct_members(m, layouter, member.ty, &nested, base + member.offset, out);
                } else {
                    out.push(serde_json::json!({
                        "name": name,
                        "offset": base + member.offset,
                        "size": layouter[member.ty].size,
                        "type": type_name(m, member.ty),
                    }));
                }
            }
        }
        _ => out.push(serde_json::json!({
            // A buffer of scalars or vectors: its element, unnamed.
            "name": match prefix.trim_end_matches('.') {
                "" => "(element)",
                name => name,
            },
            "offset": base,
            "size": layouter[ty].size,
            "type": type_name(m, ty),
        })),
    }
}

/// WGSL's spelling of a member's type (scalars, vectors, matrices, fixed
/// arrays of them).
fn type_name(m: &naga::Module, ty: naga::Handle<naga::Type>) -> String {
    let scalar = |s: naga::Scalar| match (s.kind, s.width) {
        (naga::ScalarKind::Float, 4) => "f32",
        (naga::ScalarKind::Uint, 4) => "u32",
        (naga::ScalarKind::Sint, 4) => "i32",
        (naga::ScalarKind::Bool, _) => "bool",
        _ => "?",
    };
    match &m.types[ty].inner {
        naga::TypeInner::Scalar(s) => scalar(*s).to_owned(),
        naga::TypeInner::Vector { size, scalar: s } => {
            format!("vec{}<{}>", *size as u8, scalar(*s))
        }
        naga::TypeInner::Matrix {
            columns,
            rows,
            scalar: s,
        } => format!("mat{}x{}<{}>", *columns as u8, *rows as u8, scalar(*s)),
        naga::TypeInner::Array { base, size, .. } => match size {
            naga::ArraySize::Constant(n) => format!("array<{}, {n}>", type_name(m, *base)),
            _ => format!("array<{}>", type_name(m, *base)),
        },
        naga::TypeInner::Struct { .. } => m.types[ty].name.clone().unwrap_or_default(),
        _ => "?".to_owned(),
    }
}

/// The host-visible layout of the binding named `name`: a uniform's struct,
/// or a storage buffer's element (its stride and, for a struct, members).
fn binding_layout(
    m: &naga::Module,
    layouter: &naga::proc::Layouter,
    name: &str,
) -> Option<serde_json::Value> {
    let (_, var) = m
        .global_variables
        .iter()
        .find(|(_, v)| v.name.as_deref() == Some(name))?;
    let (ty, stride) = match &m.types[var.ty].inner {
        naga::TypeInner::Array { base, stride, .. } => (*base, Some(*stride)),
        naga::TypeInner::Struct { .. } => (var.ty, None),
        _ => return None,
    };
    let mut members = Vec::new();
    struct_members(m, layouter, ty, "", 0, &mut members);
    Some(serde_json::json!({
        "type": type_name(m, ty),
        "size": layouter[ty].size,
        "array_stride": stride,
        "members": members,
    }))
}

fn kind_fields(kind: &BindingKind) -> (&'static str, String, &'static str) {
    match kind {
        BindingKind::Uniform { .. } => ("uniform buffer", String::new(), "read"),
        BindingKind::Storage { read_only } => (
            "storage buffer",
            String::new(),
            if *read_only { "read" } else { "read_write" },
        ),
        BindingKind::Texture {
            sample,
            array,
            multisampled,
        } => {
            let shape = match (array, multisampled) {
                (_, true) => "2d multisampled",
                (true, false) => "2d array",
                (false, false) => "2d",
            };
            ("sampled texture", format!("{sample}, {shape}"), "read")
        }
        BindingKind::StorageTexture { format } => {
            ("storage texture", format!("{format}, 2d"), "write")
        }
    }
}

/// Everything written for one shader: its files and its table row.
fn translate(s: &StandaloneShader) -> Result<(Vec<OutputFile>, serde_json::Value), ShaderError> {
    let id = format!("{}/{}", s.pass, s.variant);
    let fail = |stage: &str, message: String| ShaderError {
        shader: id.clone(),
        message: format!("{stage}: {message}"),
    };
    let (m, info) = module(&s.wgsl).map_err(|e| fail("WGSL", e))?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(m.to_ctx())
        .map_err(|e| fail("layout", e.to_string()))?;
    let extended = with_module_bindings(s, &m, &layouter).map_err(|e| fail("bindings", e))?;
    let s = &extended;
    let glsl_module = match &s.glsl_wgsl {
        Some(wgsl) => Some(module(wgsl).map_err(|e| fail("WGSL for GLSL", e))?),
        None => None,
    };
    let (gm, ginfo) = glsl_module.as_ref().map_or((&m, &info), |(m, i)| (m, i));
    let (slots, sizes_slot) = slots(&s.bindings);
    let base = PathBuf::from(s.pass);
    let file = |ext: &str, bytes: Vec<u8>| OutputFile {
        path: base.join(format!("{}.{ext}", s.variant)),
        bytes,
    };
    let mut files = vec![
        file("wgsl", s.wgsl.clone().into_bytes()),
        file("spv", spirv(&m, &info, s).map_err(|e| fail("SPIR-V", e))?),
        file(
            "hlsl",
            hlsl_source(&m, &info, s)
                .map_err(|e| fail("HLSL", e))?
                .into_bytes(),
        ),
        file(
            "comp",
            glsl_source(gm, ginfo, s, glsl::Version::Desktop(GLSL_CORE), POLICIES)
                .map_err(|e| fail("GLSL 450", e))?
                .into_bytes(),
        ),
        file(
            "metal",
            msl_source(&m, &info, s, &slots, sizes_slot)
                .map_err(|e| fail("MSL", e))?
                .into_bytes(),
        ),
    ];
    // GLSL ES 3.10 lacks some of what desktop GLSL has (multisampled
    // arrays, some storage formats): written where naga can, the reason
    // recorded where it cannot.
    let es = match glsl_source(gm, ginfo, s, glsl::Version::new_gles(GLSL_ES), POLICIES_ES) {
        Ok(src) => {
            files.push(file("es.comp", src.into_bytes()));
            let samples_textures = s
                .bindings
                .iter()
                .any(|b| matches!(b.kind, BindingKind::Texture { .. }));
            serde_json::json!({
                "file": format!("{}.es.comp", s.variant),
                "note": if samples_textures { ES_NOTE } else { "" },
            })
        }
        Err(e) => serde_json::json!({ "file": null, "not_expressible": e }),
    };
    let bindings = binding_rows(s, &slots, &m, &layouter);
    let msl_sizes = msl_buffer_sizes(&m);
    let row = serde_json::json!({
        "variant": s.variant,
        "summary": s.summary,
        "entry_point": s.entry_point,
        "workgroup_size": s.workgroup_size,
        "dispatch": s.dispatch,
        "files": {
            "wgsl": format!("{}.wgsl", s.variant),
            "spirv": format!("{}.spv", s.variant),
            "hlsl": format!("{}.hlsl", s.variant),
            "glsl": format!("{}.comp", s.variant),
            "glsl_es": es,
            "msl": format!("{}.metal", s.variant),
        },
        "bindings": bindings,
        "msl_buffer_sizes": if !msl_sizes.is_empty() {
            serde_json::json!({
                "slot": format!("buffer({sizes_slot})"),
                "what": "struct _mslBufferSizes: one uint per storage buffer, its size in bytes, \
                         in this order",
                "members": msl_sizes,
            })
        } else {
            serde_json::Value::Null
        },
    });
    Ok((files, row))
}

/// The table rows of `s`'s bindings, with their `slots` in each language
/// and the layouts of their types in module `m`.
fn binding_rows(
    s: &StandaloneShader,
    slots: &[Slots],
    m: &naga::Module,
    layouter: &naga::proc::Layouter,
) -> Vec<serde_json::Value> {
    s.bindings
        .iter()
        .zip(slots)
        .map(|(b, slot)| {
            let (kind, format, access) = kind_fields(&b.kind);
            let glsl_float_depth = s.glsl_wgsl.is_some()
                && matches!(b.kind, BindingKind::Texture { sample: "depth", .. });
            serde_json::json!({
                "set": b.group,
                "binding": b.binding,
                "name": b.name,
                "kind": kind,
                "format": format,
                "access": access,
                "wgsl_type": b.wgsl_type,
                "hlsl": slot.hlsl,
                "glsl_binding": slot.glsl,
                "glsl_note": if glsl_float_depth {
                    "a float sampler: bind the depth image, depth in .r (GLSL has no texel fetch of depth)"
                } else {
                    ""
                },
                "msl": msl_slot(&b.kind, slot.msl),
                "layout": binding_layout(m, layouter, &b.name),
            })
        })
        .collect()
}

/// The members of naga's `_mslBufferSizes` for module `m`: one `uint
/// size<N>` per global holding a runtime-sized array, in the module's order
/// of globals (not binding order), N the global's index: each buffer's size
/// in bytes.
fn msl_buffer_sizes(m: &naga::Module) -> Vec<serde_json::Value> {
    m.global_variables
        .iter()
        .filter(|(_, v)| m.types[v.ty].inner.is_dynamically_sized(&m.types))
        .map(|(h, v)| {
            serde_json::json!({
                "member": format!("size{}", h.index()),
                "binding": v.name.clone().unwrap_or_default(),
            })
        })
        .collect()
}

/// The Markdown table of one pass's variants.
fn markdown(pass: &str, rows: &[serde_json::Value]) -> String {
    let mut md = format!(
        "# `{pass}`: resource tables\n\nGenerated by `subcone shaders --out shaders`; do not edit. \
         Set = `@group`, binding = `@binding` (SPIR-V and Vulkan GLSL); HLSL registers; \
         GLSL `layout(binding = n)`; MSL argument slots. Offsets are bytes, from naga's layouter \
         (std140 for uniforms, std430 for storage buffers).\n"
    );
    for row in rows {
        let s = |k: &str| row[k].as_str().unwrap_or_default().to_owned();
        let _ = write!(
            md,
            "\n## `{pass}/{}`\n\n{}\n\n- entry point `{}`, workgroup size {}, dispatch {}\n",
            s("variant"),
            s("summary"),
            s("entry_point"),
            row["workgroup_size"],
            s("dispatch"),
        );
        let es = &row["files"]["glsl_es"];
        let _ = writeln!(
            md,
            "- files: `{0}.wgsl`, `{0}.spv`, `{0}.hlsl`, `{0}.comp` (GLSL 450), {1}`{0}.metal`\n",
            s("variant"),
            match es["file"].as_str() {
                Some(f) if es["note"].as_str().is_some_and(|n| !n.is_empty()) => format!(
                    "`{f}` (GLSL ES 310: {}), ",
                    es["note"].as_str().unwrap_or_default()
                ),
                Some(f) => format!("`{f}` (GLSL ES 310), "),
                None => format!(
                    "no GLSL ES 310 ({}), ",
                    es["not_expressible"].as_str().unwrap_or_default()
                ),
            }
        );
        md += "| set | binding | name | kind | format | access | HLSL | GLSL | MSL |\n";
        md += "|--:|--:|---|---|---|---|---|--:|---|\n";
        for b in row["bindings"].as_array().into_iter().flatten() {
            let f = |k: &str| match &b[k] {
                serde_json::Value::String(v) => v.clone(),
                v => v.to_string(),
            };
            let _ = writeln!(
                md,
                "| {} | {} | `{}` | {} | {} | {} | `{}` | {} | `{}` |",
                f("set"),
                f("binding"),
                f("name"),
                f("kind"),
                f("format"),
                f("access"),
                f("hlsl"),
                f("glsl_binding"),
                f("msl"),
            );
        }
        if let Some(sizes) = row["msl_buffer_sizes"].as_object() {
            let members: Vec<String> = sizes["members"]
                .as_array()
                .into_iter()
                .flatten()
                .map(|m| {
                    format!(
                        "`{}` = bytes of `{}`",
                        m["member"].as_str().unwrap_or_default(),
                        m["binding"].as_str().unwrap_or_default()
                    )
                })
                .collect();
            let _ = writeln!(
                md,
                "\nMSL also reads `{}`, `struct _mslBufferSizes {{ uint … }}`: {}.",
                sizes["slot"].as_str().unwrap_or_default(),
                members.join(", ")
            );
        }
        for b in row["bindings"].as_array().into_iter().flatten() {
            let Some(layout) = b["layout"].as_object() else {
                continue;
            };
            let _ = write!(
                md,
                "\n`{}`: `{}`, {} bytes",
                b["name"].as_str().unwrap_or_default(),
                layout["type"].as_str().unwrap_or_default(),
                layout["size"]
            );
            if let Some(stride) = layout["array_stride"].as_u64() {
                let _ = write!(md, ", an array of stride {stride}");
            }
            md += "\n\n| offset | size | member | type |\n|--:|--:|---|---|\n";
            for m in layout["members"].as_array().into_iter().flatten() {
                let _ = writeln!(
                    md,
                    "| {} | {} | `{}` | `{}` |",
                    m["offset"],
                    m["size"],
                    m["name"].as_str().unwrap_or_default(),
                    m["type"].as_str().unwrap_or_default()
                );
            }
        }
    }
    md
}

/// Every file `subcone shaders` writes for `shaders`, in a fixed order.
pub fn generate(shaders: &[StandaloneShader]) -> Result<Vec<OutputFile>, ShaderError> {
    let mut files = Vec::new();
    let mut passes: BTreeMap<&str, Vec<serde_json::Value>> = BTreeMap::new();
    for s in shaders {
        let (f, row) = translate(s)?;
        files.extend(f);
        passes.entry(s.pass).or_default().push(row);
    }
    let mut index = String::from(
        "# Shaders\n\nEvery pass of `subcone-passes` in SPIR-V, HLSL, GLSL and MSL, \
         cross-compiled by naga from the WGSL the wgpu pass runs. Generated by \
         `cargo run --release -- shaders --out shaders`; do not edit (CI regenerates them \
         and fails on a difference). Bind them from the resource tables.\n\n\
         | pass | variant | configuration | table |\n|---|---|---|---|\n",
    );
    for (pass, rows) in &passes {
        for row in rows {
            let _ = writeln!(
                index,
                "| {pass} | `{}` | {} | [{pass}.md]({pass}.md), [{pass}.json]({pass}.json) |",
                row["variant"].as_str().unwrap_or_default(),
                row["summary"].as_str().unwrap_or_default(),
            );
        }
        let mut json = serde_json::to_string_pretty(&serde_json::json!({
            "pass": pass,
            "generator": format!("subcone {} (naga {})", env!("CARGO_PKG_VERSION"), NAGA_VERSION),
            "variants": rows,
        }))
        .map_err(|e| ShaderError {
            shader: (*pass).to_owned(),
            message: e.to_string(),
        })?;
        json.push('\n');
        files.push(OutputFile {
            path: PathBuf::from(format!("{pass}.json")),
            bytes: json.into_bytes(),
        });
        files.push(OutputFile {
            path: PathBuf::from(format!("{pass}.md")),
            bytes: markdown(pass, rows).into_bytes(),
        });
    }
    files.push(OutputFile {
        path: PathBuf::from("README.md"),
        bytes: index.into_bytes(),
    });
    files.iter_mut().for_each(mark_generated);
    Ok(files)
}

/// The first line of every text file `subcone shaders` writes, inside the
/// file's comment syntax.
pub const GENERATED: &str = "Generated by `subcone shaders` from the passes' WGSL; do not edit.";

/// Put [`GENERATED`] first in `file`, as a comment of its language: `//`
/// for WGSL, HLSL and MSL, `<!-- -->` for Markdown. In GLSL (`.comp`,
/// `.es.comp`) the comment is the second line, after the `#version` line
/// naga writes first: GLSL ES 3.x wants `#version` before any comment.
/// JSON (which has no comments) and SPIR-V (binary) are left as they are;
/// so is a file whose extension this does not know.
pub fn mark_generated(file: &mut OutputFile) {
    let ext = file.path.extension().and_then(|e| e.to_str());
    let (line, at) = match ext {
        Some("wgsl" | "hlsl" | "metal") => (format!("// {GENERATED}\n"), 0),
        Some("comp") => {
            let after_version = match file.bytes.iter().position(|&b| b == b'\n') {
                Some(end) if file.bytes.starts_with(b"#version") => end + 1,
                _ => 0,
            };
            (format!("// {GENERATED}\n"), after_version)
        }
        Some("md") => (format!("<!-- {GENERATED} -->\n"), 0),
        _ => return,
    };
    file.bytes.splice(at..at, line.into_bytes());
}

/// The naga the translations come from (the major wgpu pairs with).
pub const NAGA_VERSION: &str = "30";

/// Write `files` under `out`.
pub fn write(out: &Path, files: &[OutputFile]) -> std::io::Result<()> {
    for f in files {
        let path = out.join(&f.path);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir)?;
        }
        std::fs::write(path, &f.bytes)?;
    }
    Ok(())
}

/// What differs between `files` and the directory `out`: files missing or
/// different, and files under `out` that `files` does not hold.
pub fn stale(out: &Path, files: &[OutputFile]) -> Vec<String> {
    let mut problems = Vec::new();
    for f in files {
        match std::fs::read(out.join(&f.path)) {
            Ok(bytes) if bytes == f.bytes => {}
            Ok(_) => problems.push(format!("{} differs", f.path.display())),
            Err(_) => problems.push(format!("{} is missing", f.path.display())),
        }
    }
    let expected: std::collections::BTreeSet<PathBuf> =
        files.iter().map(|f| f.path.clone()).collect();
    let mut stack = vec![out.to_path_buf()];
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if let Ok(rel) = p.strip_prefix(out) {
                if !expected.contains(rel) {
                    problems.push(format!("{} is not generated", rel.display()));
                }
            }
        }
    }
    problems.sort();
    problems
}
