//! Every function `subcone-capi` exports, called as a C host could call it:
//! arbitrary scalars (NaN, ±∞, huge, subnormal, negative, zero), raw
//! integers for the codes and flags (out of range included), null pointers,
//! and buffers allocated at exactly the length passed with them, which may
//! disagree with the sizes (too short, too long, zero, `width·height`
//! overflowing). A length is never larger than its allocation (that would
//! break the C contract, not the library); AddressSanitizer sees any access
//! past it.
//!
//! Each call must return a documented status: `Ok` exactly when every input
//! is valid, otherwise one of the errors its defects allow (never `Panic`,
//! which means bad input reached a panic), and the out-pointers untouched
//! unless `Ok`; `subcone_last_error_message` must then be empty after `Ok`
//! and otherwise one line of UTF-8 naming the function. A
//! `SubconeSraaFrame` carries any `size` now and then, or is only that
//! `u32` (a smaller struct of another header): a wrong size must give
//! `StructSize`, read nothing past the `size`, and be named in the message.
//! `capi/tests/fuzz_target.rs` fails when an exported function is not
//! called here.
#![no_main]

use std::ffi::c_void;

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use subcone_capi::*;

/// Largest buffer allocated, in elements; longer lengths are passed with a
/// null pointer (which every function must refuse before reading).
const MAX_ALLOC: usize = 1024;
/// Distance evaluations a trace may make before the field answers NaN,
/// which ends it (`stop` 6): the step budget is the caller's and may be
/// `u32::MAX`.
const FIELD_BUDGET: u32 = 4096;

/// An f32 drawn from the values that break arithmetic as often as from raw
/// bit patterns.
#[derive(Clone, Copy)]
struct F(f32);

impl std::fmt::Debug for F {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "{:?}", self.0)
    }
}

const SPECIAL: [f32; 20] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    2.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MAX,
    f32::MIN,
    f32::MIN_POSITIVE,
    1e-45,
    f32::EPSILON,
    1e-20,
    1e20,
    1e30,
    -1e30,
    3.0,
    0.01,
];

impl<'a> Arbitrary<'a> for F {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(F(if u.ratio(1u8, 2u8)? {
            *u.choose(&SPECIAL)?
        } else {
            f32::from_bits(u.arbitrary()?)
        }))
    }
}

/// A size field: mostly small, sometimes any `u32`.
#[derive(Clone, Copy, Debug)]
struct Size(u32);

impl<'a> Arbitrary<'a> for Size {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(Size(match u.int_in_range(0u8..=7)? {
            0 => u.arbitrary()?,
            1 => *u.choose(&[u32::MAX, 1 << 16, 1 << 31, 17, 32, 33])?,
            _ => u.int_in_range(0..=6)?,
        }))
    }
}

/// `true` for one input in eight: pointers a call needs are null that
/// often, so most calls get past the null checks to the work behind them.
#[derive(Clone, Copy, Debug)]
struct Rarely(bool);

impl<'a> Arbitrary<'a> for Rarely {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(Rarely(u.ratio(1u8, 8u8)?))
    }
}

fn v3(a: [F; 3]) -> SubconeVec3 {
    SubconeVec3 {
        x: a[0].0,
        y: a[1].0,
        z: a[2].0,
    }
}

fn finite3(v: SubconeVec3) -> bool {
    v.x.is_finite() && v.y.is_finite() && v.z.is_finite()
}

#[derive(Arbitrary, Clone, Copy, Debug)]
struct Geometry {
    normal: [F; 3],
    depth: F,
}

impl From<Geometry> for SubconeGeometry {
    fn from(g: Geometry) -> Self {
        SubconeGeometry {
            normal: v3(g.normal),
            depth: g.depth.0,
        }
    }
}

/// SRAA parameters: a preset or any fields ([`AnySraaParams`]).
#[derive(Arbitrary, Clone, Copy, Debug)]
enum SraaParams {
    Paper,
    Tuned,
    Raw(AnySraaParams),
}

/// SRAA parameters with any fields: floats as [`F`] draws them, codes and
/// padding as raw integers.
#[derive(Clone, Copy, Debug)]
struct AnySraaParams(SubconeSraaParams);

impl<'a> Arbitrary<'a> for AnySraaParams {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(Self(SubconeSraaParams {
            sigma_z: u.arbitrary::<F>()?.0,
            sigma_n: u.arbitrary::<F>()?.0,
            scale: u.arbitrary::<F>()?.0,
            packed: u.arbitrary()?,
            sigma_s: u.arbitrary::<F>()?.0,
            shading: u.arbitrary()?,
            pad: u.arbitrary()?,
        }))
    }
}

impl SraaParams {
    fn get(self) -> SubconeSraaParams {
        let mut p = SubconeSraaParams::default();
        match self {
            SraaParams::Paper => assert_eq!(
                unsafe { subcone_sraa_params_paper(&mut p) },
                SubconeStatus::Ok
            ),
            SraaParams::Tuned => assert_eq!(
                unsafe { subcone_sraa_params_default(&mut p) },
                SubconeStatus::Ok
            ),
            SraaParams::Raw(AnySraaParams(raw)) => p = raw,
        }
        p
    }
}

/// What the C ABI refuses in SRAA parameters: a non-finite σ or scale.
/// (Unknown codes in `packed` and `shading` read as the kernels' defaults.)
fn sraa_params_valid(p: &SubconeSraaParams) -> bool {
    [p.sigma_z, p.sigma_n, p.scale, p.sigma_s]
        .iter()
        .all(|v| v.is_finite())
}

#[derive(Arbitrary, Clone, Copy, Debug)]
enum CtssParams {
    Default {
        tan_theta: F,
        flags: u32,
        visibility_k: u32,
        max_steps: u32,
        max_samples: u32,
    },
    Raw(AnyCtssParams),
}

/// CTSS parameters with any fields: floats as [`F`] draws them, budgets,
/// codes and padding as raw integers.
#[derive(Clone, Copy, Debug)]
struct AnyCtssParams(SubconeCtssParams);

impl<'a> Arbitrary<'a> for AnyCtssParams {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(Self(SubconeCtssParams {
            tan_theta: u.arbitrary::<F>()?.0,
            alpha: u.arbitrary::<F>()?.0,
            eps: u.arbitrary::<F>()?.0,
            t_min: u.arbitrary::<F>()?.0,
            t_max: u.arbitrary::<F>()?.0,
            min_sample_weight: u.arbitrary::<F>()?.0,
            max_steps: u.arbitrary()?,
            max_samples: u.arbitrary()?,
            visibility_k: u.arbitrary()?,
            flags: u.arbitrary()?,
            pad: u.arbitrary()?,
        }))
    }
}

impl CtssParams {
    fn get(self) -> SubconeCtssParams {
        match self {
            CtssParams::Default {
                tan_theta,
                flags,
                visibility_k,
                max_steps,
                max_samples,
            } => {
                let mut p = SubconeCtssParams::default();
                let t = tan_theta.0.abs();
                let t = if t.is_finite() { t } else { 0.01 };
                assert_eq!(
                    unsafe { subcone_ctss_params_default(t, &mut p) },
                    SubconeStatus::Ok
                );
                // Flags, k and budgets sometimes as the defaults set them.
                if flags >> 31 != 0 {
                    p.flags = flags;
                    p.visibility_k = visibility_k;
                    p.max_steps = max_steps;
                    p.max_samples = max_samples;
                }
                p
            }
            CtssParams::Raw(AnyCtssParams(raw)) => raw,
        }
    }
}

/// The length passed with a buffer, relative to the one the sizes require
/// (that one half the time).
#[derive(Clone, Copy, Debug)]
enum Len {
    Needed,
    NeededMinus(u8),
    NeededPlus(u8),
    Zero,
    Small(u8),
    Huge(usize),
}

impl<'a> Arbitrary<'a> for Len {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(match u.int_in_range(0u8..=9)? {
            0 => Len::NeededMinus(u.arbitrary()?),
            1 => Len::NeededPlus(u.arbitrary()?),
            2 => Len::Zero,
            3 => Len::Small(u.arbitrary()?),
            4 => Len::Huge(u.arbitrary()?),
            _ => Len::Needed,
        })
    }
}

impl Len {
    fn get(self, needed: Option<usize>) -> usize {
        // An overflowing requirement: the caller can only pass something else.
        let n = needed.unwrap_or(usize::MAX);
        match self {
            Len::Needed => n,
            Len::NeededMinus(d) => n.saturating_sub(d as usize % 4 + 1),
            Len::NeededPlus(d) => n.saturating_add(d as usize % 4 + 1),
            Len::Zero => 0,
            Len::Small(s) => s as usize,
            Len::Huge(h) => h,
        }
    }
}

/// A buffer argument: its length, whether the pointer is null, and the
/// values it holds (repeated to fill the length).
#[derive(Arbitrary, Clone, Debug)]
struct Buf<T> {
    len: Len,
    null: Rarely,
    values: Vec<T>,
}

/// A buffer as passed: exactly `len` elements when the pointer is not null.
struct Passed<T> {
    data: Option<Vec<T>>,
    len: usize,
}

impl<T: Copy> Passed<T> {
    fn ptr(&self) -> *const T {
        match &self.data {
            // An empty Vec's pointer is dangling but non-null and aligned,
            // as a C caller's pointer to zero elements may be.
            Some(v) => v.as_ptr(),
            None => std::ptr::null(),
        }
    }

    fn is_null(&self) -> bool {
        self.data.is_none()
    }
}

impl<T> Buf<T> {
    fn pass<U: Copy + Default>(&self, needed: Option<usize>, f: impl Fn(&T) -> U) -> Passed<U> {
        let len = self.len.get(needed);
        if self.null.0 || len > MAX_ALLOC {
            return Passed { data: None, len };
        }
        let data = (0..len)
            .map(|i| {
                if self.values.is_empty() {
                    U::default()
                } else {
                    f(&self.values[i % self.values.len()])
                }
            })
            .collect();
        Passed {
            data: Some(data),
            len,
        }
    }
}

/// The `size` a host writes in a [`SubconeSraaFrame`].
#[derive(Clone, Copy, Debug)]
enum StructSize {
    /// `sizeof(SubconeSraaFrame)`.
    Right,
    /// Any value (the right one only by chance).
    Any(u32),
    /// Any value but the right one, in a struct that is only that `u32`
    /// (a host of an older, smaller header): the library must refuse it
    /// from the `size` alone, reading nothing past it.
    Short(u32),
}

impl<'a> Arbitrary<'a> for StructSize {
    fn arbitrary(u: &mut Unstructured<'a>) -> arbitrary::Result<Self> {
        Ok(match u.int_in_range(0u8..=15)? {
            0 => StructSize::Any(u.arbitrary()?),
            1 => StructSize::Any(
                size_of::<SubconeSraaFrame>() as u32 ^ (1 << u.int_in_range(0..=31)?),
            ),
            2 => StructSize::Short(u.arbitrary()?),
            _ => StructSize::Right,
        })
    }
}

#[derive(Arbitrary, Debug)]
struct Frame {
    /// Every buffer of the length the sizes require, none null: the resolve
    /// itself runs whenever the sizes and gates are valid.
    consistent: bool,
    size: StructSize,
    width: Size,
    height: Size,
    layers: Size,
    colors: Buf<[F; 3]>,
    /// `layers` gates when not null (the C contract gives it no length).
    layer_lights: Option<Vec<i8>>,
    shaded_geometry: Buf<Geometry>,
    shaded_shadow: Buf<u32>,
    subsample_geometry: Buf<Geometry>,
    subsample_shadow: Buf<u32>,
    out: Buf<u8>,
}

/// The field a trace marches through.
#[derive(Arbitrary, Clone, Debug)]
enum Shape {
    /// A sphere of radius `r` at the origin.
    Sphere { r: F },
    /// The plane `y = h`.
    Plane { h: F },
    /// Replayed samples, cycled.
    Replay(Vec<(F, F, u32)>),
}

#[derive(Arbitrary, Debug)]
struct Trace {
    params: Option<CtssParams>,
    origin: [F; 3],
    dir: [F; 3],
    up_hint: [F; 3],
    no_distance: Rarely,
    /// Null: differences of the distance; else replayed normals.
    normal: Option<Vec<[F; 3]>>,
    no_shade: Rarely,
    background: [F; 3],
    no_out: Rarely,
    shape: Shape,
    colors: Vec<[F; 3]>,
}

/// One call of each exported function.
#[derive(Arbitrary, Debug)]
enum Call {
    Version,
    SraaPassUniform {
        params: Option<SraaParams>,
        width: Size,
        height: Size,
        projection: Option<[F; 16]>,
        depth_miss: F,
        exposure: F,
        out: bool,
    },
    CtssPassUniform {
        eye: [F; 3],
        forward: [F; 3],
        up_hint: [F; 3],
        fov_y: F,
        width: Size,
        height: Size,
        background: [F; 3],
        out: bool,
    },
    FxaaParamsQuality {
        out: bool,
    },
    FxaaPassFrame {
        width: Size,
        height: Size,
        out: bool,
    },
    TaaParams {
        width: Size,
        height: Size,
        history_frames: u32,
        exposure: F,
        out: bool,
    },
    TaaJitter {
        frame: u32,
        phases: Size,
        x: bool,
        y: bool,
    },
    PinholeRay {
        /// A uniform from `subcone_ctss_pass_uniform`'s arguments, then
        /// any field overwritten: (`tan_half_fov`, jitter, projection code).
        uniform: Option<([F; 3], [F; 3], F, [F; 2], u32)>,
        x: F,
        y: F,
        out: bool,
    },
    SraaParamsDefault {
        out: bool,
    },
    SraaParamsPaper {
        out: bool,
    },
    CtssParamsDefault {
        tan_theta: F,
        out: bool,
    },
    BilateralWeight {
        params: Option<SraaParams>,
        gi: Option<Geometry>,
        gj: Option<Geometry>,
        out: bool,
    },
    ShadowGatedWeight {
        params: Option<SraaParams>,
        gi: Option<Geometry>,
        gj: Option<Geometry>,
        si: u32,
        sj: u32,
        out: bool,
    },
    ReconstructionWeight {
        params: Option<SraaParams>,
        gi: Option<Geometry>,
        gj: Option<Geometry>,
        distance2: F,
        out: bool,
    },
    AlbedoDifference {
        a: [F; 3],
        b: [F; 3],
        out: bool,
    },
    ResolvePixel {
        subsamples: Option<[[F; 3]; 4]>,
        out: bool,
    },
    ConeTanTheta {
        fov_y: F,
        height: Size,
        coverage: F,
        footprint: u32,
        out: bool,
    },
    ConeRadius {
        t: F,
        tan_theta: F,
        out: bool,
    },
    ConeOcclusion {
        d: F,
        rc: F,
        out: bool,
    },
    Advance {
        t: F,
        d: F,
        alpha: F,
        rc: F,
        out: bool,
    },
    BacktraceConeEntry {
        t_i: F,
        tan_theta: F,
        out: bool,
    },
    BacktraceHardHit {
        t_prev: F,
        d_prev: F,
        t_i: F,
        out: bool,
    },
    ProjectNormal {
        normal: [F; 3],
        right: [F; 3],
        up: [F; 3],
        out: bool,
    },
    VisibilityMask {
        occlusion: F,
        nx: F,
        ny: F,
        placement: u32,
        out: bool,
    },
    SampleWeight {
        visible: u32,
        weighting: u32,
        min_weight: F,
        out: bool,
    },
    SraaResolve {
        params: Option<SraaParams>,
        frame: Option<Frame>,
    },
    CtssTrace(Trace),
    FxaaImage(FxaaImage),
    TaaResolve(TaaResolve),
}

/// A `subcone_fxaa_image` call.
#[derive(Arbitrary, Debug)]
struct FxaaImage {
    /// `(subpix, edge_threshold, edge_threshold_min)`, or a null pointer.
    params: Option<[F; 3]>,
    width: Size,
    height: Size,
    /// Every buffer of the length the size requires, none null.
    consistent: bool,
    src: Buf<F>,
    dst: Buf<u8>,
}

/// A `subcone_taa_resolve` call.
#[derive(Arbitrary, Debug)]
struct TaaResolve {
    /// `(exposure, min_current_weight, clip_gamma)`, `history_frames`,
    /// width, height and `tone_mapped`, or a null pointer.
    params: Option<([F; 3], u32, Size, Size, u32)>,
    /// Every buffer of the length the size requires, none null.
    consistent: bool,
    current: Buf<F>,
    velocity: Buf<F>,
    history: Buf<F>,
    out: Buf<u8>,
}

/// What a call's inputs allow it to return: `Ok` only when nothing is wrong,
/// otherwise an error of one of the kinds present.
#[derive(Default)]
struct Defects {
    null: bool,
    invalid: bool,
    size: bool,
    /// A parameter struct's `size` field is not its `sizeof`.
    struct_size: bool,
}

impl Defects {
    /// `s`, the status of the call of `what` just made, is one the defects
    /// allow, and the thread's last error message says so: empty after
    /// `Ok`, else one line naming `what`.
    fn check(&self, s: SubconeStatus, what: &str) {
        let message = last_error_message();
        assert_ne!(
            s,
            SubconeStatus::Panic,
            "{what}: a panic was caught: {message}"
        );
        let allowed = match s {
            SubconeStatus::Ok => !(self.null || self.invalid || self.size || self.struct_size),
            SubconeStatus::NullPointer => self.null,
            SubconeStatus::InvalidArgument => self.invalid,
            SubconeStatus::SizeMismatch => self.size,
            SubconeStatus::StructSize => self.struct_size,
            SubconeStatus::Panic => false,
        };
        assert!(
            allowed,
            "{what}: returned {s:?} ({message}) for null {}, invalid {}, size {}, struct size {}",
            self.null, self.invalid, self.size, self.struct_size
        );
        if s == SubconeStatus::Ok {
            assert_eq!(message, "", "{what}: a message after Ok");
        } else {
            assert!(
                message.starts_with(&format!("{what}: ")) && message.len() > what.len() + 2,
                "{what}: returned {s:?} with the message {message:?}"
            );
            assert!(!message.contains('\n'), "{what}: {message:?}");
        }
    }
}

/// The calling thread's last error message: never null, NUL-terminated
/// UTF-8.
fn last_error_message() -> String {
    let p = subcone_last_error_message();
    assert!(!p.is_null(), "subcone_last_error_message returned NULL");
    // SAFETY: a NUL-terminated string the library owns until its next call
    // on this thread.
    let m = unsafe { std::ffi::CStr::from_ptr(p) };
    m.to_str()
        .unwrap_or_else(|e| panic!("the last error message is not UTF-8: {e}: {m:?}"))
        .to_string()
}

/// An out-pointer: null, or a value pre-set to a sentinel that must survive
/// every error.
struct Out<T> {
    value: Option<Box<T>>,
    sentinel: T,
}

impl<T: Copy + std::fmt::Debug> Out<T> {
    fn new(present: bool, sentinel: T) -> Self {
        Self {
            value: present.then(|| Box::new(sentinel)),
            sentinel,
        }
    }

    fn ptr(&mut self) -> *mut T {
        match &mut self.value {
            Some(b) => &mut **b,
            None => std::ptr::null_mut(),
        }
    }

    fn is_null(&self) -> bool {
        self.value.is_none()
    }

    /// The written value on `Ok`; on an error, checks nothing was written
    /// (compared as bytes: NaN sentinels compare unequal).
    fn after(&self, s: SubconeStatus, what: &str) -> Option<T> {
        let v = **self.value.as_ref()?;
        if s == SubconeStatus::Ok {
            return Some(v);
        }
        assert!(
            bytes(&v) == bytes(&self.sentinel),
            "{what}: wrote {v:?} and returned {s:?}"
        );
        None
    }
}

fn bytes<T>(v: &T) -> &[u8] {
    // SAFETY: reads the value's own bytes; only used on padding-free
    // `repr(C)` types of f32 and u32 fields.
    unsafe { std::slice::from_raw_parts((v as *const T).cast::<u8>(), size_of::<T>()) }
}

const SENTINEL_F32: f32 = -12345.678;
const SENTINEL_V3: SubconeVec3 = SubconeVec3 {
    x: SENTINEL_F32,
    y: SENTINEL_F32,
    z: SENTINEL_F32,
};

fn opt_ptr<T>(v: &Option<T>) -> *const T {
    v.as_ref().map_or(std::ptr::null(), |v| v as *const T)
}

/// A weight function's call: `(params, gi, gj)` as pointers, then the call.
fn weight(
    what: &str,
    params: Option<SraaParams>,
    gi: Option<Geometry>,
    gj: Option<Geometry>,
    out: bool,
    call: impl FnOnce(
        *const SubconeSraaParams,
        *const SubconeGeometry,
        *const SubconeGeometry,
        *mut f32,
    ) -> SubconeStatus,
) {
    let p = params.map(SraaParams::get);
    let (gi, gj) = (gi.map(SubconeGeometry::from), gj.map(SubconeGeometry::from));
    let mut o = Out::new(out, SENTINEL_F32);
    let s = call(opt_ptr(&p), opt_ptr(&gi), opt_ptr(&gj), o.ptr());
    Defects {
        null: p.is_none() || gi.is_none() || gj.is_none() || o.is_null(),
        invalid: p.as_ref().is_some_and(|p| !sraa_params_valid(p)),
        size: false,
        struct_size: false,
    }
    .check(s, what);
    if let Some(w) = o.after(s, what) {
        assert!((0.0..=1.0).contains(&w), "{what}: weight {w}");
    }
}

/// A call with only an out-pointer to fail on: every input is in its domain.
fn plain<T: Copy + std::fmt::Debug>(
    what: &str,
    out: bool,
    sentinel: T,
    call: impl FnOnce(*mut T) -> SubconeStatus,
) -> Option<T> {
    scalar(what, out, false, sentinel, call)
}

/// A call with an out-pointer and scalar arguments, `invalid` when one of
/// them is outside its domain: its status, and the value written.
fn scalar<T: Copy + std::fmt::Debug>(
    what: &str,
    out: bool,
    invalid: bool,
    sentinel: T,
    call: impl FnOnce(*mut T) -> SubconeStatus,
) -> Option<T> {
    let mut o = Out::new(out, sentinel);
    let s = call(o.ptr());
    Defects {
        null: o.is_null(),
        invalid,
        size: false,
        struct_size: false,
    }
    .check(s, what);
    o.after(s, what)
}

/// A preset's constructor of SRAA parameters: refuses only a null
/// out-pointer, and the preset is valid.
fn sraa_preset(
    what: &str,
    out: bool,
    preset: impl FnOnce(*mut SubconeSraaParams) -> SubconeStatus,
) {
    if let Some(p) = plain(what, out, SubconeSraaParams::default(), preset) {
        assert!(sraa_params_valid(&p), "{what}: {p:?}");
    }
}

fn sraa_resolve(params: Option<SraaParams>, frame: Option<Frame>) {
    let what = "subcone_sraa_resolve";
    let p = params.map(SraaParams::get);
    let Some(fr) = frame else {
        let mut o = [SENTINEL_V3];
        let s = unsafe { subcone_sraa_resolve(opt_ptr(&p), std::ptr::null(), o.as_mut_ptr(), 1) };
        Defects {
            null: true,
            invalid: p.as_ref().is_some_and(|p| !sraa_params_valid(p)),
            size: false,
            struct_size: false,
        }
        .check(s, what);
        assert_eq!(bytes(&o[0]), bytes(&SENTINEL_V3), "{what}: wrote on {s:?}");
        return;
    };
    let mut fr = fr;
    if fr.consistent {
        make_consistent(
            &mut [
                &mut fr.colors.len,
                &mut fr.shaded_geometry.len,
                &mut fr.shaded_shadow.len,
                &mut fr.subsample_geometry.len,
                &mut fr.subsample_shadow.len,
                &mut fr.out.len,
            ],
            &mut [
                &mut fr.colors.null,
                &mut fr.shaded_geometry.null,
                &mut fr.shaded_shadow.null,
                &mut fr.subsample_geometry.null,
                &mut fr.subsample_shadow.null,
                &mut fr.out.null,
            ],
        );
    }
    let (w, h, layers) = (
        fr.width.0 as usize,
        fr.height.0 as usize,
        fr.layers.0 as usize,
    );
    let n = w.checked_mul(h);
    let colors = fr
        .colors
        .pass(n.and_then(|n| n.checked_mul(layers)), |c| v3(*c));
    let geometry = fr.shaded_geometry.pass(n, |g| SubconeGeometry::from(*g));
    let shadow = fr.shaded_shadow.pass(n, |s| *s);
    let sub_needed = n.and_then(|n| n.checked_mul(4));
    let sub_geometry = fr
        .subsample_geometry
        .pass(sub_needed, |g| SubconeGeometry::from(*g));
    let sub_shadow = fr.subsample_shadow.pass(sub_needed, |s| *s);
    // `layers` gates, as the C contract requires of a non-null pointer;
    // null when that many cannot be allocated.
    let lights: Option<Vec<i8>> = fr.layer_lights.as_ref().and_then(|l| {
        (layers <= MAX_ALLOC).then(|| {
            (0..layers)
                .map(|i| if l.is_empty() { -1 } else { l[i % l.len()] })
                .collect()
        })
    });
    let out_len = fr.out.len.get(n);
    let mut out: Option<Vec<SubconeVec3>> =
        (!fr.out.null.0 && out_len <= MAX_ALLOC).then(|| vec![SENTINEL_V3; out_len]);
    let frame = SubconeSraaFrame {
        size: match fr.size {
            StructSize::Right => size_of::<SubconeSraaFrame>() as u32,
            StructSize::Any(s) => s,
            StructSize::Short(_) => 0,
        },
        width: fr.width.0,
        height: fr.height.0,
        layers: fr.layers.0,
        colors: colors.ptr(),
        colors_len: colors.len,
        layer_lights: lights.as_ref().map_or(std::ptr::null(), |l| l.as_ptr()),
        shaded_geometry: geometry.ptr(),
        shaded_geometry_len: geometry.len,
        shaded_shadow: shadow.ptr(),
        shaded_shadow_len: shadow.len,
        subsample_geometry: sub_geometry.ptr(),
        subsample_geometry_len: sub_geometry.len,
        subsample_shadow: sub_shadow.ptr(),
        subsample_shadow_len: sub_shadow.len,
    };
    let out_ptr = out
        .as_mut()
        .map_or(std::ptr::null_mut(), |o| o.as_mut_ptr());
    // A short struct: only its `u32` size, never the right one.
    let short = match fr.size {
        StructSize::Short(s) if s as usize == size_of::<SubconeSraaFrame>() => Some(Box::new(0u32)),
        StructSize::Short(s) => Some(Box::new(s)),
        _ => None,
    };
    let frame_ptr = short
        .as_deref()
        .map_or(&frame as *const SubconeSraaFrame, |s| {
            (s as *const u32).cast::<SubconeSraaFrame>()
        });
    let struct_size = short.is_some() || frame.size as usize != size_of::<SubconeSraaFrame>();
    let s = unsafe { subcone_sraa_resolve(opt_ptr(&p), frame_ptr, out_ptr, out_len) };
    let params_ok = p.as_ref().is_some_and(sraa_params_valid);
    if struct_size && params_ok {
        // The size is checked right after the parameters, before any field
        // it would misread.
        assert_eq!(
            s,
            SubconeStatus::StructSize,
            "{what}: {}",
            last_error_message()
        );
        assert!(
            last_error_message().contains("SubconeSraaFrame"),
            "{what}: {}",
            last_error_message()
        );
    }

    // The documented refusals.
    let size_ok = w > 0 && h > 0 && (1..=16).contains(&layers);
    let exact = |len: usize, want: Option<usize>| want == Some(len);
    let optional = |len: usize, want: Option<usize>| len == 0 || want == Some(len);
    let lengths_ok = exact(colors.len, n.and_then(|n| n.checked_mul(layers)))
        && exact(geometry.len, n)
        && exact(sub_geometry.len, sub_needed)
        && exact(out_len, n)
        && optional(shadow.len, n)
        && optional(sub_shadow.len, sub_needed);
    let null = p.is_none()
        || out.is_none()
        || null_with_data(&colors)
        || null_with_data(&geometry)
        || null_with_data(&shadow)
        || null_with_data(&sub_geometry)
        || null_with_data(&sub_shadow);
    let gates_ok = lights.as_ref().is_none_or(|l| l.iter().all(|&g| g < 32));
    let invalid = p.as_ref().is_some_and(|p| !sraa_params_valid(p)) || !gates_ok;
    Defects {
        null,
        invalid,
        size: !(size_ok && lengths_ok),
        struct_size,
    }
    .check(s, what);
    if let Some(out) = &out {
        for c in out {
            if s == SubconeStatus::Ok {
                assert!(finite3(*c), "{what}: colour {c:?}");
            } else {
                assert_eq!(bytes(c), bytes(&SENTINEL_V3), "{what}: wrote on {s:?}");
            }
        }
    }
}

/// The caller's side of a trace: the field, normals and colours it answers
/// with, and what the trace asked.
struct Host {
    shape: Shape,
    normals: Vec<[F; 3]>,
    colors: Vec<[F; 3]>,
    evaluations: u32,
    normal_calls: usize,
    shaded: usize,
    /// The first direction `shade` was given that is not of unit length.
    bad_dir: Option<SubconeVec3>,
}

extern "C" fn host_distance(user: *mut c_void, p: SubconeVec3) -> SubconeFieldSample {
    // SAFETY: `user` is the `Host` of `ctss_trace`, alive for the call.
    let host = unsafe { &mut *user.cast::<Host>() };
    host.evaluations += 1;
    if host.evaluations > FIELD_BUDGET {
        return SubconeFieldSample {
            distance: f32::NAN,
            step: f32::NAN,
            object: u32::MAX,
        };
    }
    let (d, step, object) = match &host.shape {
        Shape::Sphere { r } => {
            let d = (p.x * p.x + p.y * p.y + p.z * p.z).sqrt() - r.0;
            (d, d, 0)
        }
        Shape::Plane { h } => (p.y - h.0, p.y - h.0, 1),
        Shape::Replay(samples) if !samples.is_empty() => {
            let (d, s, o) = samples[host.evaluations as usize % samples.len()];
            (d.0, s.0, o)
        }
        Shape::Replay(_) => (f32::INFINITY, f32::INFINITY, u32::MAX),
    };
    SubconeFieldSample {
        distance: d,
        step,
        object,
    }
}

extern "C" fn host_normal(user: *mut c_void, _p: SubconeVec3, _h: f32) -> SubconeVec3 {
    // SAFETY: as `host_distance`.
    let host = unsafe { &mut *user.cast::<Host>() };
    host.normal_calls += 1;
    match host.normals.len() {
        0 => SubconeVec3 {
            x: 0.0,
            y: 1.0,
            z: 0.0,
        },
        n => v3(host.normals[host.normal_calls % n]),
    }
}

extern "C" fn host_shade(
    user: *mut c_void,
    _p: SubconeVec3,
    _n: SubconeVec3,
    dir: SubconeVec3,
) -> SubconeVec3 {
    // SAFETY: as `host_distance`.
    let host = unsafe { &mut *user.cast::<Host>() };
    host.shaded += 1;
    let length = ((dir.x as f64).powi(2) + (dir.y as f64).powi(2) + (dir.z as f64).powi(2)).sqrt();
    if host.bad_dir.is_none() && ((length - 1.0).abs() >= 1e-5 || length.is_nan()) {
        host.bad_dir = Some(dir);
    }
    match host.colors.len() {
        0 => SubconeVec3 {
            x: 0.5,
            y: 0.5,
            z: 0.5,
        },
        n => v3(host.colors[host.shaded % n]),
    }
}

fn ctss_trace(t: Trace) {
    let what = "subcone_ctss_trace";
    let p = t.params.map(CtssParams::get);
    let mut host = Host {
        shape: t.shape,
        normals: t.normal.clone().unwrap_or_default(),
        colors: t.colors,
        evaluations: 0,
        normal_calls: 0,
        shaded: 0,
        bad_dir: None,
    };
    let (origin, dir, up_hint) = (v3(t.origin), v3(t.dir), v3(t.up_hint));
    let mut o = Out::new(
        !t.no_out.0,
        SubconeCtssResult {
            color: SENTINEL_V3,
            samples: 0xdead,
            steps: 0xbeef,
            coverage: 0xfeed,
            stop: 0xface,
        },
    );
    let s = unsafe {
        subcone_ctss_trace(
            opt_ptr(&p),
            origin,
            dir,
            up_hint,
            (!t.no_distance.0).then_some(host_distance as _),
            t.normal.is_some().then_some(host_normal as _),
            (!t.no_shade.0).then_some(host_shade as _),
            (&mut host as *mut Host).cast::<c_void>(),
            v3(t.background),
            o.ptr(),
        )
    };
    let invalid = p.as_ref().is_some_and(|p| {
        ![
            p.tan_theta,
            p.alpha,
            p.eps,
            p.t_min,
            p.t_max,
            p.min_sample_weight,
        ]
        .iter()
        .all(|v| v.is_finite())
            || p.tan_theta < 0.0
            || !(1..=32).contains(&p.visibility_k)
    }) || !(finite3(origin) && finite3(dir) && finite3(up_hint))
        || [dir.x, dir.y, dir.z].iter().all(|&c| c == 0.0);
    Defects {
        null: p.is_none() || t.no_distance.0 || t.no_shade.0 || o.is_null(),
        invalid,
        size: false,
        struct_size: false,
    }
    .check(s, what);
    if s != SubconeStatus::Ok {
        assert!(
            host.evaluations == 0 && host.shaded == 0 && host.normal_calls == 0,
            "{what}: called back and returned {s:?}"
        );
    }
    if let Some(r) = o.after(s, what) {
        assert!(r.stop <= 6, "{what}: stop {}", r.stop);
        assert!(
            host.bad_dir.is_none(),
            "{what}: shaded along {:?} for dir {dir:?}",
            host.bad_dir
        );
    }
}

fn call(c: Call) {
    match c {
        Call::SraaPassUniform {
            params,
            width,
            height,
            projection,
            depth_miss,
            exposure,
            out,
        } => {
            let what = "subcone_sraa_pass_uniform";
            let p = params.map(SraaParams::get);
            let m = projection.map(|m| m.map(|f| f.0));
            let mut o = Out::new(
                out,
                SubconeSraaPassUniform {
                    width: 0xDEAD_BEEF,
                    ..Default::default()
                },
            );
            let mptr = m.as_ref().map_or(std::ptr::null(), |m| m.as_ptr());
            let s = unsafe {
                subcone_sraa_pass_uniform(
                    opt_ptr(&p),
                    width.0,
                    height.0,
                    mptr,
                    depth_miss.0,
                    exposure.0,
                    o.ptr(),
                )
            };
            Defects {
                null: p.is_none() || o.is_null(),
                invalid: p.as_ref().is_some_and(|p| !sraa_params_valid(p))
                    || !depth_miss.0.is_finite()
                    || !(exposure.0.is_finite() && exposure.0 >= 0.0)
                    || m.is_some_and(|m| !m.iter().all(|v| v.is_finite())),
                size: width.0 == 0 || height.0 == 0,
                struct_size: false,
            }
            .check(s, what);
            if let Some(u) = o.after(s, what) {
                assert_eq!((u.width, u.height), (width.0, height.0), "{what}");
            }
        }
        Call::CtssPassUniform {
            eye,
            forward,
            up_hint,
            fov_y,
            width,
            height,
            background,
            out,
        } => {
            let what = "subcone_ctss_pass_uniform";
            let mut o = Out::new(
                out,
                SubconeCtssPassUniform {
                    row_length: 0xDEAD_BEEF,
                    ..Default::default()
                },
            );
            let s = unsafe {
                subcone_ctss_pass_uniform(
                    v3(eye),
                    v3(forward),
                    v3(up_hint),
                    fov_y.0,
                    width.0,
                    height.0,
                    v3(background),
                    o.ptr(),
                )
            };
            let nonfinite = ![v3(eye), v3(forward), v3(up_hint), v3(background)]
                .into_iter()
                .all(finite3)
                || !(fov_y.0 > 0.0 && fov_y.0 < std::f32::consts::PI);
            // A zero forward, or one within LOOK_FRAME_MIN_SINE (1e-4) of
            // parallel to up_hint, has no frame: in f64, the two directions'
            // sine is below twice that (rounding decides near it), or a
            // length is 0.
            let degenerate = {
                let f = [forward[0].0, forward[1].0, forward[2].0].map(f64::from);
                let u = [up_hint[0].0, up_hint[1].0, up_hint[2].0].map(f64::from);
                let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                let c = [
                    f[1] * u[2] - f[2] * u[1],
                    f[2] * u[0] - f[0] * u[2],
                    f[0] * u[1] - f[1] * u[0],
                ];
                let (lf, lu) = (len(f), len(u));
                !(lf > 0.0 && lu > 0.0 && len(c) / (lf * lu) > 2e-4)
            };
            let defects = Defects {
                null: o.is_null(),
                invalid: nonfinite,
                size: width.0 == 0 || height.0 == 0,
                struct_size: false,
            };
            if s == SubconeStatus::InvalidArgument && !nonfinite {
                assert!(degenerate, "{what}: refused a camera with a frame");
            } else if !(degenerate && s == SubconeStatus::Ok) {
                defects.check(s, what);
            }
            if let Some(u) = o.after(s, what) {
                let unit =
                    |v: [f32; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - 1.0).abs() < 1e-3;
                assert!(
                    unit(u.camera.forward) && unit(u.camera.right) && unit(u.camera.up),
                    "{what}: {u:?}"
                );
            }
        }
        Call::FxaaParamsQuality { out } => {
            let p = plain(
                "subcone_fxaa_params_quality",
                out,
                SubconeFxaaParams::default(),
                |o| unsafe { subcone_fxaa_params_quality(o) },
            );
            if let Some(p) = p {
                assert!(p.subpix > 0.0 && p.edge_threshold > 0.0, "{p:?}");
            }
        }
        Call::FxaaPassFrame { width, height, out } => {
            let what = "subcone_fxaa_pass_frame";
            let mut o = Out::new(
                out,
                SubconeFxaaPassFrame {
                    width: 0xDEAD_BEEF,
                    ..Default::default()
                },
            );
            let s = unsafe { subcone_fxaa_pass_frame(width.0, height.0, o.ptr()) };
            Defects {
                null: o.is_null(),
                invalid: false,
                size: width.0 == 0 || height.0 == 0,
                struct_size: false,
            }
            .check(s, what);
            if let Some(f) = o.after(s, what) {
                assert_eq!((f.width, f.height), (width.0, height.0), "{what}");
            }
        }
        Call::TaaParams {
            width,
            height,
            history_frames,
            exposure,
            out,
        } => {
            let what = "subcone_taa_params";
            let mut o = Out::new(
                out,
                SubconeTaaParams {
                    width: 0xDEAD_BEEF,
                    ..Default::default()
                },
            );
            let s = unsafe {
                subcone_taa_params(width.0, height.0, history_frames, exposure.0, o.ptr())
            };
            Defects {
                null: o.is_null(),
                invalid: !(exposure.0.is_finite() && exposure.0 >= 0.0),
                size: width.0 == 0 || height.0 == 0,
                struct_size: false,
            }
            .check(s, what);
            if let Some(p) = o.after(s, what) {
                assert_eq!(p.history_frames, history_frames, "{what}");
                assert_eq!(p.tone_mapped, u32::from(exposure.0 > 0.0), "{what}");
            }
        }
        Call::TaaJitter {
            frame,
            phases,
            x,
            y,
        } => {
            let what = "subcone_taa_jitter";
            let mut ox = Out::new(x, SENTINEL_F32);
            let mut oy = Out::new(y, SENTINEL_F32);
            let s = unsafe { subcone_taa_jitter(frame, phases.0, ox.ptr(), oy.ptr()) };
            Defects {
                null: ox.is_null() || oy.is_null(),
                invalid: phases.0 == 0,
                size: false,
                struct_size: false,
            }
            .check(s, what);
            if let (Some(jx), Some(jy)) = (ox.after(s, what), oy.after(s, what)) {
                assert!(
                    (-0.5..0.5).contains(&jx) && (-0.5..0.5).contains(&jy),
                    "{what}: {jx} {jy}"
                );
            }
        }
        Call::PinholeRay { uniform, x, y, out } => {
            let what = "subcone_pinhole_ray";
            let u = uniform.map(|(eye, forward, tan, jitter, projection)| {
                let mut u = SubconeCtssPassUniform::default();
                let yaxis = SubconeVec3 {
                    x: 0.0,
                    y: 1.0,
                    z: 0.1,
                };
                unsafe {
                    subcone_ctss_pass_uniform(
                        v3(eye),
                        v3(forward),
                        yaxis,
                        0.8,
                        64,
                        48,
                        yaxis,
                        &mut u,
                    )
                };
                u.camera.tan_half_fov = tan.0;
                u.camera.jitter = jitter.map(|j| j.0);
                u.projection = projection % 4;
                u
            });
            let mut o = Out::new(out, SENTINEL_V3);
            let s = unsafe { subcone_pinhole_ray(opt_ptr(&u), x.0, y.0, o.ptr()) };
            let finite_u = |u: &SubconeCtssPassUniform| {
                [u.camera.forward, u.camera.right, u.camera.up]
                    .iter()
                    .flatten()
                    .chain(&u.camera.jitter)
                    .chain([&u.camera.tan_half_fov])
                    .all(|v| v.is_finite())
            };
            Defects {
                null: u.is_none() || o.is_null(),
                invalid: !(x.0.is_finite() && y.0.is_finite())
                    || u.as_ref()
                        .is_some_and(|u| u.projection != 0 || !finite_u(u)),
                size: false,
                struct_size: false,
            }
            .check(s, what);
            o.after(s, what);
        }
        Call::Version => {
            let v = subcone_version();
            assert_eq!(
                v,
                SUBCONE_VERSION_MAJOR << 16 | SUBCONE_VERSION_MINOR << 8 | SUBCONE_VERSION_PATCH
            );
        }
        Call::SraaParamsDefault { out } => {
            sraa_preset("subcone_sraa_params_default", out, |o| unsafe {
                subcone_sraa_params_default(o)
            })
        }
        Call::SraaParamsPaper { out } => {
            sraa_preset("subcone_sraa_params_paper", out, |o| unsafe {
                subcone_sraa_params_paper(o)
            })
        }
        Call::CtssParamsDefault { tan_theta, out } => {
            let what = "subcone_ctss_params_default";
            let invalid = !(tan_theta.0.is_finite() && tan_theta.0 >= 0.0);
            let p = scalar(
                what,
                out,
                invalid,
                SubconeCtssParams::default(),
                |o| unsafe { subcone_ctss_params_default(tan_theta.0, o) },
            );
            if let Some(p) = p {
                assert_eq!(p.tan_theta.to_bits(), tan_theta.0.to_bits(), "{what}");
            }
        }
        Call::BilateralWeight {
            params,
            gi,
            gj,
            out,
        } => weight(
            "subcone_bilateral_weight",
            params,
            gi,
            gj,
            out,
            |p, i, j, o| unsafe { subcone_bilateral_weight(p, i, j, o) },
        ),
        Call::ShadowGatedWeight {
            params,
            gi,
            gj,
            si,
            sj,
            out,
        } => weight(
            "subcone_shadow_gated_weight",
            params,
            gi,
            gj,
            out,
            |p, i, j, o| unsafe { subcone_shadow_gated_weight(p, i, j, si, sj, o) },
        ),
        Call::ReconstructionWeight {
            params,
            gi,
            gj,
            distance2,
            out,
        } => weight(
            "subcone_reconstruction_weight",
            params,
            gi,
            gj,
            out,
            |p, i, j, o| unsafe { subcone_reconstruction_weight(p, i, j, distance2.0, o) },
        ),
        Call::AlbedoDifference { a, b, out } => {
            let what = "subcone_albedo_difference";
            let d = plain(what, out, SENTINEL_F32, |o| unsafe {
                subcone_albedo_difference(v3(a), v3(b), o)
            });
            if let Some(d) = d {
                assert!(d >= 0.0, "{what}: {d}");
            }
        }
        Call::ResolvePixel { subsamples, out } => {
            let what = "subcone_resolve_pixel";
            // Exactly the four values the contract names, or null.
            let samples: Option<Vec<SubconeVec3>> =
                subsamples.map(|s| s.iter().map(|&c| v3(c)).collect());
            let ptr = samples.as_ref().map_or(std::ptr::null(), |s| s.as_ptr());
            let mut o = Out::new(out, SENTINEL_V3);
            let s = unsafe { subcone_resolve_pixel(ptr, o.ptr()) };
            Defects {
                null: samples.is_none() || o.is_null(),
                ..Defects::default()
            }
            .check(s, what);
            if let Some(c) = o.after(s, what) {
                assert!(finite3(c), "{what}: {c:?}");
            }
        }
        Call::ConeTanTheta {
            fov_y,
            height,
            coverage,
            footprint,
            out,
        } => {
            let what = "subcone_cone_tan_theta";
            let fov_ok = fov_y.0 > 0.0 && fov_y.0 < std::f32::consts::PI;
            let coverage_ok = coverage.0.is_finite() && coverage.0 > 0.0;
            let invalid = footprint > 2 || !fov_ok || height.0 == 0 || !coverage_ok;
            let t = scalar(what, out, invalid, SENTINEL_F32, |o| unsafe {
                subcone_cone_tan_theta(fov_y.0, height.0, coverage.0, footprint, o)
            });
            if let Some(t) = t {
                assert!(t >= 0.0 && !t.is_nan(), "{what}: {t}");
            }
        }
        Call::ConeRadius { t, tan_theta, out } => {
            plain("subcone_cone_radius", out, SENTINEL_F32, |o| unsafe {
                subcone_cone_radius(t.0, tan_theta.0, o)
            });
        }
        Call::ConeOcclusion { d, rc, out } => {
            let what = "subcone_cone_occlusion";
            let w = plain(what, out, SENTINEL_F32, |o| unsafe {
                subcone_cone_occlusion(d.0, rc.0, o)
            });
            if let Some(w) = w {
                assert!((-1.0..=2.0).contains(&w), "{what}: {w}");
            }
        }
        Call::Advance {
            t,
            d,
            alpha,
            rc,
            out,
        } => {
            plain("subcone_advance", out, SENTINEL_F32, |o| unsafe {
                subcone_advance(t.0, d.0, alpha.0, rc.0, o)
            });
        }
        Call::BacktraceConeEntry {
            t_i,
            tan_theta,
            out,
        } => {
            plain(
                "subcone_backtrace_cone_entry",
                out,
                SENTINEL_F32,
                |o| unsafe { subcone_backtrace_cone_entry(t_i.0, tan_theta.0, o) },
            );
        }
        Call::BacktraceHardHit {
            t_prev,
            d_prev,
            t_i,
            out,
        } => {
            plain(
                "subcone_backtrace_hard_hit",
                out,
                SENTINEL_F32,
                |o| unsafe { subcone_backtrace_hard_hit(t_prev.0, d_prev.0, t_i.0, o) },
            );
        }
        Call::ProjectNormal {
            normal,
            right,
            up,
            out,
        } => {
            // Exactly the two floats the contract names, or null.
            plain(
                "subcone_project_normal",
                out,
                [SENTINEL_F32; 2],
                |o| unsafe {
                    subcone_project_normal(v3(normal), v3(right), v3(up), o.cast::<f32>())
                },
            );
        }
        Call::VisibilityMask {
            occlusion,
            nx,
            ny,
            placement,
            out,
        } => {
            scalar(
                "subcone_visibility_mask",
                out,
                placement > 2,
                0xdead_beef_u32,
                |o| unsafe { subcone_visibility_mask(occlusion.0, nx.0, ny.0, placement, o) },
            );
        }
        Call::SampleWeight {
            visible,
            weighting,
            min_weight,
            out,
        } => {
            let what = "subcone_sample_weight";
            let invalid = weighting > 1 || !min_weight.0.is_finite();
            let w = scalar(what, out, invalid, SENTINEL_F32, |o| unsafe {
                subcone_sample_weight(visible, weighting, min_weight.0, o)
            });
            if let Some(w) = w {
                assert!((0.0..=1.0).contains(&w), "{what}: {w}");
            }
        }
        Call::SraaResolve { params, frame } => sraa_resolve(params, frame),
        Call::CtssTrace(t) => ctss_trace(t),
        Call::FxaaImage(c) => fxaa_image(c),
        Call::TaaResolve(c) => taa_resolve(c),
    }
}

/// Make every buffer of `bufs` the length the sizes require, not null.
fn make_consistent(bufs: &mut [&mut Len], nulls: &mut [&mut Rarely]) {
    for len in bufs.iter_mut() {
        **len = Len::Needed;
    }
    for null in nulls.iter_mut() {
        null.0 = false;
    }
}

/// An output of `len` floats set to the sentinel, or null (when asked, or
/// when too long to allocate).
fn sentinel_out(buf: &Buf<u8>, needed: Option<usize>) -> (Option<Vec<f32>>, usize) {
    let len = buf.len.get(needed);
    let out = (!buf.null.0 && len <= MAX_ALLOC).then(|| vec![SENTINEL_F32; len]);
    (out, len)
}

/// `out` untouched unless `s` is `Ok`; when it is, every value passes `ok`.
fn check_out(
    out: &Option<Vec<f32>>,
    s: SubconeStatus,
    what: &str,
    ok: impl Fn(usize, f32) -> bool,
) {
    for (i, &v) in out.iter().flatten().enumerate() {
        if s == SubconeStatus::Ok {
            assert!(ok(i, v), "{what}: value {i} is {v}");
        } else {
            assert_eq!(
                v.to_bits(),
                SENTINEL_F32.to_bits(),
                "{what}: wrote on {s:?}"
            );
        }
    }
}

/// The pointer of an optional output.
fn out_ptr(out: &mut Option<Vec<f32>>) -> *mut f32 {
    out.as_mut()
        .map_or(std::ptr::null_mut(), |o| o.as_mut_ptr())
}

/// A null pointer passed with a positive length: a null-pointer defect (a
/// null pointer with length 0 is an empty buffer).
fn null_with_data<T: Copy>(b: &Passed<T>) -> bool {
    b.is_null() && b.len > 0
}

fn fxaa_image(mut c: FxaaImage) {
    let what = "subcone_fxaa_image";
    if c.consistent {
        make_consistent(
            &mut [&mut c.src.len, &mut c.dst.len],
            &mut [&mut c.src.null, &mut c.dst.null],
        );
    }
    let params = c.params.map(|[a, b, d]| SubconeFxaaParams {
        subpix: a.0,
        edge_threshold: b.0,
        edge_threshold_min: d.0,
        pad: 0.0,
    });
    let (w, h) = (c.width.0 as usize, c.height.0 as usize);
    let needed = w.checked_mul(h).and_then(|n| n.checked_mul(4));
    let src = c.src.pass(needed, |v| v.0);
    let (mut dst, dst_len) = sentinel_out(&c.dst, needed);
    let s = unsafe {
        subcone_fxaa_image(
            opt_ptr(&params),
            c.width.0,
            c.height.0,
            src.ptr(),
            src.len,
            out_ptr(&mut dst),
            dst_len,
        )
    };
    let lengths_ok = w > 0 && h > 0 && needed == Some(src.len) && needed == Some(dst_len);
    Defects {
        null: params.is_none() || dst.is_none() || null_with_data(&src),
        invalid: params.is_some_and(|p| {
            ![p.subpix, p.edge_threshold, p.edge_threshold_min]
                .iter()
                .all(|v| v.is_finite())
        }),
        size: !lengths_ok,
        struct_size: false,
    }
    .check(s, what);
    // Colour in [0, 1], alpha 1.
    check_out(&dst, s, what, |i, v| {
        if i % 4 == 3 {
            v == 1.0
        } else {
            (0.0..=1.0).contains(&v)
        }
    });
}

fn taa_resolve(mut c: TaaResolve) {
    let what = "subcone_taa_resolve";
    if c.consistent {
        make_consistent(
            &mut [
                &mut c.current.len,
                &mut c.velocity.len,
                &mut c.history.len,
                &mut c.out.len,
            ],
            &mut [
                &mut c.current.null,
                &mut c.velocity.null,
                &mut c.history.null,
                &mut c.out.null,
            ],
        );
    }
    let params = c.params.map(
        |([exposure, min_weight, gamma], history_frames, w, h, tone_mapped)| SubconeTaaParams {
            exposure: exposure.0,
            min_current_weight: min_weight.0,
            clip_gamma: gamma.0,
            history_frames,
            width: w.0,
            height: h.0,
            tone_mapped,
            depth_dilation: 0,
            motion_scale: [1.0, 1.0],
            pad: [0; 2],
        },
    );
    let (w, h) = params.map_or((0, 0), |p| (p.width as usize, p.height as usize));
    let n = w.checked_mul(h);
    let rgba = n.and_then(|n| n.checked_mul(4));
    let current = c.current.pass(rgba, |v| v.0);
    let velocity = c.velocity.pass(n.and_then(|n| n.checked_mul(2)), |v| v.0);
    let history = c.history.pass(rgba, |v| v.0);
    let (mut out, out_len) = sentinel_out(&c.out, rgba);
    let s = unsafe {
        subcone_taa_resolve(
            opt_ptr(&params),
            current.ptr(),
            current.len,
            velocity.ptr(),
            velocity.len,
            history.ptr(),
            history.len,
            out_ptr(&mut out),
            out_len,
        )
    };
    let reads_history = params.is_some_and(|p| p.history_frames != 0);
    let lengths_ok = w > 0
        && h > 0
        && rgba == Some(current.len)
        && n.and_then(|n| n.checked_mul(2)) == Some(velocity.len)
        && rgba == Some(out_len)
        && (history.len == 0 && !reads_history || rgba == Some(history.len));
    Defects {
        null: params.is_none()
            || out.is_none()
            || null_with_data(&current)
            || null_with_data(&velocity)
            || null_with_data(&history),
        invalid: params.is_some_and(|p| {
            ![p.exposure, p.min_current_weight, p.clip_gamma]
                .iter()
                .all(|v| v.is_finite())
        }),
        size: params.is_some() && !lengths_ok,
        struct_size: false,
    }
    .check(s, what);
    // Finite and non-negative colour, alpha 1.
    check_out(&out, s, what, |i, v| {
        if i % 4 == 3 {
            v == 1.0
        } else {
            v.is_finite() && v >= 0.0
        }
    });
}

fuzz_target!(|calls: Vec<Call>| {
    // A few calls per input, so one input can reach several functions.
    for c in calls.into_iter().take(8) {
        call(c);
    }
});
