// The frame's constants of SRAA-RT on SDF scenes (sdf/sraa.rs
// `SdfSraaFrame`): trace.wgsl's SdfFrame, member for member, then the
// method's SRAA parameters. The program binds `frame` as this struct, so
// trace.wgsl's functions read the members they know and the SRAA hooks read
// `frame.sraa`. Both structs are checked against their Rust twins by
// layout_tests.rs, so the shared members cannot drift.
struct SdfSraaFrame {
    position: vec3<f32>,
    width: u32,
    forward: vec3<f32>,
    height: u32,
    right: vec3<f32>,
    half: f32,
    up: vec3<f32>,
    max_distance: f32,
    background: vec3<f32>,
    max_steps: u32,
    ambient: vec3<f32>,
    side: u32,
    cone: u32,
    ao_rays: u32,
    ao_radius: f32,
    _pad: u32,
    sraa: subcone_SraaParams,
}
