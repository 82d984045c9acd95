//! SRAA's antialiasing pass over a whole frame in CPU buffers.

use glam::Vec3;
use subcone_kernels::sraa::{
    Geometry, Resolver, ShadedFrame, ShadedGroup, Subsamples, ALBEDO_TOLERANCE, MAX_LAYERS,
};

use crate::checks::{read_sized, slice, slice_mut};
use crate::geometry::{SubconeGeometry, SubconeVec3};
use crate::params::{sraa_params, SubconeSraaParams};
use crate::status::{call, Checked, Refusal, SubconeStatus};

/// A frame's worth of SRAA input for [`subcone_sraa_resolve`], in
/// caller-owned CPU buffers (row-major, `width × height` pixels). Set
/// `size` to `sizeof(SubconeSraaFrame)`:
///
/// ```c
/// SubconeSraaFrame frame;
/// memset(&frame, 0, sizeof frame);
/// frame.size = sizeof frame;
/// frame.width = width;
/// /* ... */
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct SubconeSraaFrame {
    /// `sizeof(SubconeSraaFrame)`, which the library checks against its own
    /// (`SUBCONE_STATUS_STRUCT_SIZE` when they differ): a host built with a
    /// header of another version is refused rather than misread.
    pub size: u32,
    /// Image width in pixels (> 0).
    pub width: u32,
    /// Image height in pixels (> 0).
    pub height: u32,
    /// Shaded layers per pixel, 1..=16 (`layer_lights` gives each its gate).
    pub layers: u32,
    /// `width·height·layers` linear RGB colours: every pixel's shaded sample,
    /// one colour per layer (e.g. layer 0 ambient and indirect, layer `1 + l`
    /// light `l`'s direct light).
    pub colors: *const SubconeVec3,
    /// Length of `colors`.
    pub colors_len: usize,
    /// `layers` entries: the light whose shadow gates each layer (eq. 2), or
    /// −1 for an ungated layer (eq. 1). Null: every layer ungated.
    pub layer_lights: *const i8,
    /// `width·height` geometries of the shaded samples.
    pub shaded_geometry: *const SubconeGeometry,
    /// Length of `shaded_geometry`.
    pub shaded_geometry_len: usize,
    /// `width·height` shadow bit sets of the shaded samples (bit `l`: in light
    /// `l`'s shadow), or null for none.
    pub shaded_shadow: *const u32,
    /// Length of `shaded_shadow` (0 when null).
    pub shaded_shadow_len: usize,
    /// `4·width·height` geometries of the four subsamples of every pixel, at
    /// `SUBPIXEL_OFFSETS` (the 4× MSAA pattern: (−⅛,−⅜), (⅜,−⅛), (−⅜,⅛),
    /// (⅛,⅜)), pixel by pixel.
    pub subsample_geometry: *const SubconeGeometry,
    /// Length of `subsample_geometry`.
    pub subsample_geometry_len: usize,
    /// `4·width·height` shadow bit sets of the subsamples, or null for none.
    pub subsample_shadow: *const u32,
    /// Length of `subsample_shadow` (0 when null).
    pub subsample_shadow_len: usize,
}

/// An empty frame whose `size` is set: every pointer null, every size and
/// length 0.
impl Default for SubconeSraaFrame {
    fn default() -> Self {
        SubconeSraaFrame {
            size: size_of::<SubconeSraaFrame>() as u32,
            width: 0,
            height: 0,
            layers: 0,
            colors: std::ptr::null(),
            colors_len: 0,
            layer_lights: std::ptr::null(),
            shaded_geometry: std::ptr::null(),
            shaded_geometry_len: 0,
            shaded_shadow: std::ptr::null(),
            shaded_shadow_len: 0,
            subsample_geometry: std::ptr::null(),
            subsample_geometry_len: 0,
            subsample_shadow: std::ptr::null(),
            subsample_shadow_len: 0,
        }
    }
}

/// SRAA's antialiasing pass (§3, pass 2) over a whole frame: every layer of
/// every subsample reconstructed from the 3×3 neighbourhood's shaded samples
/// (eq. 1, gated by eq. 2 per light), then the box resolve, written to `out`
/// (`width·height` colours). The same loop, to the bit, as the CPU backend's
/// (the kernels' `sraa::Resolver`). Primary hits only: reconstruct the
/// reflections on their own geometry with a second call and add.
///
/// Errors: null pointers where data is required, a `frame->size` that is
/// not `sizeof(SubconeSraaFrame)` (`SUBCONE_STATUS_STRUCT_SIZE`), a zero
/// size or more than 16 layers, lengths that do not match the sizes, a gate
/// naming a light above 31, non-finite parameters.
///
/// # Safety
/// Every pointer is null or points to as many valid values as its length says.
#[no_mangle]
pub unsafe extern "C" fn subcone_sraa_resolve(
    params: *const SubconeSraaParams,
    frame: *const SubconeSraaFrame,
    out: *mut SubconeVec3,
    out_len: usize,
) -> SubconeStatus {
    // SAFETY: forwarded contract.
    call("subcone_sraa_resolve", || unsafe {
        sraa_resolve(params, frame, out, out_len)
    })
}

/// `len`, the length of `name`, must be `want` (`what` says what that is);
/// `None`: the requirement overflows `size_t`.
fn exact(name: &str, len: usize, want: Option<usize>, what: &str) -> Checked<()> {
    match want {
        Some(want) if len == want => Ok(()),
        Some(want) => Err(Refusal::size(format!(
            "{name} is {len}; it must be {what} = {want}"
        ))),
        None => Err(Refusal::size(format!(
            "{what} overflows size_t, so no {name} ({len}) can match it"
        ))),
    }
}

/// `len`, the length of the optional buffer `name`, must be 0 or `want`.
fn optional(name: &str, len: usize, want: usize, what: &str) -> Checked<()> {
    if len == 0 || len == want {
        Ok(())
    } else {
        Err(Refusal::size(format!(
            "{name} is {len}; it must be 0 (none) or {what} = {want}"
        )))
    }
}

/// The frame's sizes checked against each other and `out_len`: width and
/// height at least 1, layers in `1..=MAX_LAYERS`, every buffer length what
/// they make it. Returns the pixel count.
fn check_frame_sizes(f: &SubconeSraaFrame, out_len: usize) -> Checked<usize> {
    let (w, h, layers) = (f.width as usize, f.height as usize, f.layers as usize);
    if w == 0 || h == 0 {
        return Err(Refusal::size(format!(
            "frame->width × frame->height is {w} × {h}; both must be at least 1"
        )));
    }
    if layers == 0 || layers > MAX_LAYERS {
        return Err(Refusal::size(format!(
            "frame->layers is {layers}; it must be in 1..={MAX_LAYERS}"
        )));
    }
    let n = w.checked_mul(h).ok_or_else(|| {
        Refusal::size(format!(
            "frame->width × frame->height ({w} × {h}) overflows size_t"
        ))
    })?;
    exact(
        "frame->colors_len",
        f.colors_len,
        n.checked_mul(layers),
        "width·height·layers",
    )?;
    exact(
        "frame->shaded_geometry_len",
        f.shaded_geometry_len,
        Some(n),
        "width·height",
    )?;
    exact(
        "frame->subsample_geometry_len",
        f.subsample_geometry_len,
        n.checked_mul(4),
        "4·width·height",
    )?;
    exact("out_len", out_len, Some(n), "width·height")?;
    optional(
        "frame->shaded_shadow_len",
        f.shaded_shadow_len,
        n,
        "width·height",
    )?;
    optional(
        "frame->subsample_shadow_len",
        f.subsample_shadow_len,
        4 * n,
        "4·width·height",
    )?;
    Ok(n)
}

/// The layers' shadow gates from `frame->layer_lights` (negative: ungated;
/// a light below 32: gated by it; anything else refused).
fn layer_gates(gates: &[i8]) -> Checked<[Option<u8>; MAX_LAYERS]> {
    let mut layer_gates = [None; MAX_LAYERS];
    for (i, (g, &l)) in layer_gates.iter_mut().zip(gates).enumerate() {
        *g = match l {
            l if l < 0 => None,
            l if l < 32 => Some(l as u8),
            _ => {
                return Err(Refusal::invalid(format!(
                    "frame->layer_lights[{i}] is {l}; a gate must name a light below 32, or be \
                     negative for an ungated layer"
                )))
            }
        };
    }
    Ok(layer_gates)
}

/// # Safety
/// As [`subcone_sraa_resolve`].
unsafe fn sraa_resolve(
    params: *const SubconeSraaParams,
    frame: *const SubconeSraaFrame,
    out: *mut SubconeVec3,
    out_len: usize,
) -> Checked<()> {
    let p = sraa_params(params)?;
    // SAFETY: forwarded contract.
    let f = unsafe { read_sized(frame, "frame", "SubconeSraaFrame") }?;
    let (w, layers) = (f.width as usize, f.layers as usize);
    check_frame_sizes(&f, out_len)?;
    // SAFETY: lengths checked above against the sizes; pointers per contract.
    let (colors, geometry, shadow, sub_geometry, sub_shadow, gates) = unsafe {
        (
            slice(f.colors, f.colors_len, "frame->colors")?,
            slice(
                f.shaded_geometry,
                f.shaded_geometry_len,
                "frame->shaded_geometry",
            )?,
            slice(f.shaded_shadow, f.shaded_shadow_len, "frame->shaded_shadow")?,
            slice(
                f.subsample_geometry,
                f.subsample_geometry_len,
                "frame->subsample_geometry",
            )?,
            slice(
                f.subsample_shadow,
                f.subsample_shadow_len,
                "frame->subsample_shadow",
            )?,
            if f.layer_lights.is_null() {
                &[][..]
            } else {
                slice(f.layer_lights, layers, "frame->layer_lights")?
            },
        )
    };
    // SAFETY: `out` is null or holds `out_len` values (the caller's
    // contract), and `out_len` is `n` (checked above).
    let out = unsafe { slice_mut(out, out_len, "out") }?;
    let layer_gates = layer_gates(gates)?;
    // The kernels take glam types: the same layouts (checked above), copied
    // rather than reinterpreted.
    let colors: Vec<Vec3> = colors.iter().map(|&c| c.into()).collect();
    let geometry: Vec<Geometry> = geometry.iter().map(|&g| g.into()).collect();
    let resolver = Resolver::new(&p, &layer_gates[..layers], ALBEDO_TOLERANCE);
    let shaded = ShadedFrame {
        width: f.width,
        height: f.height,
        colors: &colors,
        layers,
        albedo: &[],
        primary: ShadedGroup {
            geometry: &geometry,
            shadow,
            first_layer: 0,
        },
        secondary: None,
    };
    for (j, o) in out.iter_mut().enumerate() {
        let g = &sub_geometry[4 * j..4 * j + 4];
        let subsamples = Subsamples {
            geometry: [g[0].into(), g[1].into(), g[2].into(), g[3].into()],
            shadow: match sub_shadow.get(4 * j..4 * j + 4) {
                Some(s) => [s[0], s[1], s[2], s[3]],
                None => [0; 4],
            },
            albedo: None,
        };
        let (x, y) = ((j % w) as u32, (j / w) as u32);
        *o = resolver.resolve(&shaded, x, y, &subsamples, None).into();
    }
    Ok(())
}
