//! Host WGSL that does not compile is a typed error of the pass's `new`
//! (`PassError::Shader`, carrying naga's message), caught in the pass's own
//! error scope: the host's uncaptured-error handler sees nothing, and the
//! host learns what is wrong with its field where it built the pass.

mod common;

#[path = "../examples/host/mod.rs"]
mod host;

use std::sync::{Arc, Mutex};

use subcone_passes::{standalone, CtssPass, CtssPassDesc, PassError};

/// A host field that compiles but for `body`, the field's last line.
fn host_wgsl(body: &str) -> String {
    format!(
        "fn subcone_field(p: vec3<f32>) -> vec3<f32> {{
    let d = length(p - vec3<f32>(0.0, 0.0, 5.0)) - 1.0;
    {body}
}}
fn subcone_shade(p: vec3<f32>, n: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {{
    return vec3<f32>(0.5) + 0.5 * n;
}}
"
    )
}

/// naga's own message for the whole shader the pass compiles from
/// `host` (its parser's, or else its validator's): what the typed error
/// must carry.
fn naga_message(host: &str) -> String {
    let shader = standalone::ctss(host, &CtssPassDesc::default()).expect("standalone source");
    let module = match naga::front::wgsl::parse_str(&shader.wgsl) {
        Err(e) => return e.message().to_owned(),
        Ok(module) => module,
    };
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    );
    match validator.validate(&module) {
        Err(e) => e.as_inner().to_string(),
        Ok(_) => panic!("naga accepted the broken host WGSL"),
    }
}

/// `CtssPass::new` on a host device whose uncaptured-error handler records
/// what it sees: the pass's result, and the errors the handler saw.
fn build(host: &str) -> Option<(Result<CtssPass, PassError>, Vec<String>)> {
    let (device, _queue) = common::device_or_skip("host WGSL errors", host::open_device)?;
    let seen = Arc::new(Mutex::new(Vec::new()));
    let record = seen.clone();
    device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
        record.lock().unwrap().push(e.to_string());
    }));
    let pass = CtssPass::new(&device, host, &CtssPassDesc::default());
    // Anything the device still had to report is reported by now.
    host::wait(&device).expect("poll");
    let seen = seen.lock().unwrap().clone();
    Some((pass, seen))
}

/// Build a pass from `host`, which naga refuses, and check the typed error.
fn refused_with_nagas_message(host: &str) {
    let expected = naga_message(host);
    let Some((pass, seen)) = build(host) else {
        return;
    };
    assert!(
        seen.is_empty(),
        "the host's uncaptured-error handler saw: {seen:?}"
    );
    match pass {
        Err(PassError::Shader { message }) => assert!(
            message.contains(&expected),
            "the error does not carry naga's message {expected:?}: {message}"
        ),
        Err(e) => panic!("another error: {e:?}"),
        Ok(_) => panic!("a pass was built from WGSL that does not compile"),
    }
}

#[test]
fn host_wgsl_with_a_syntax_error_is_a_typed_shader_error() {
    // A missing parenthesis.
    refused_with_nagas_message(&host_wgsl("return vec3<f32>(d, d, 0.0;"));
}

#[test]
fn host_wgsl_with_a_type_error_is_a_typed_shader_error() {
    // A scalar where the field returns a vector (naga's validator).
    refused_with_nagas_message(&host_wgsl("return d;"));
}

#[test]
fn host_wgsl_with_a_mistyped_declaration_is_a_typed_shader_error() {
    // A `u32` given to an `f32` (naga's parser).
    refused_with_nagas_message(&host_wgsl(
        "let s: f32 = 1u;\n    return vec3<f32>(d, s, 0.0);",
    ));
}

#[test]
fn host_wgsl_that_compiles_builds_a_pass_and_reports_nothing() {
    let Some((pass, seen)) = build(&host_wgsl("return vec3<f32>(d, d, 0.0);")) else {
        return;
    };
    assert!(pass.is_ok(), "{:?}", pass.err());
    assert!(seen.is_empty(), "the host's handler saw: {seen:?}");
}

/// The error's message names what went wrong and where: it says the shader
/// did not compile, and includes naga's message.
#[test]
fn the_shader_errors_message_says_what_failed() {
    let e = PassError::Shader {
        message: "expected `)`, found \";\"".into(),
    };
    let text = e.to_string();
    assert!(text.contains("compile"), "{text}");
    assert!(text.contains("expected `)`"), "{text}");
}
