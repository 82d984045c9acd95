//! The one skeleton every pass is built on: a pass states what differs
//! (its names, what it is built for, its checks, bindings and WGSL), and
//! [`pipeline`] and [`standalone`] do the rest, the same way for all.
//!
//! A new pass implements [`PassShader`] for its type:
//!
//! - [`PassShader::NAMES`]: its name in `shaders/`, the label of its wgpu
//!   objects, its compute entry point;
//! - [`PassShader::Key`]: what it is built for, its `…PassDesc` (with
//!   whatever else its `new` takes, such as CTSS's host WGSL);
//! - [`PassShader::check`]: the key's refusals, before anything is built;
//! - [`PassShader::group`]: its bindings (`@group(0)`) for the key;
//! - [`PassShader::wgsl`]: its WGSL for the key, which the skeleton puts
//!   between the kernels' prelude (`subcone_kernels::wgsl::PARAMS`) and the
//!   group's declarations;
//! - where they differ from the defaults, [`PassShader::host_layout`],
//!   [`PassShader::summary`] and [`PassShader::glsl_variant`].
//!
//! Then its `new` is [`pipeline`] (and the pass's own fields), and its
//! function in [`crate::standalone`] is [`standalone`]: the wgpu pass and
//! the standalone shader come from the same group and the same source.

use std::fmt::Debug;

use crate::bind::{
    BindGroupLayout, Device, Group, PassPipeline, TextureFormat, TextureSampleType,
    TextureViewDimension, WORKGROUP,
};
use crate::standalone::{StandaloneShader, DISPATCH};
use crate::PassError;

/// A pass's names: in `shaders/`, on its wgpu objects, of its entry point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PassNames {
    /// The pass, as [`StandaloneShader::pass`] names it: `"sraa"`…
    pub(crate) pass: &'static str,
    /// The label of every wgpu object the pass makes.
    pub(crate) label: &'static str,
    /// The compute entry point.
    pub(crate) entry_point: &'static str,
}

impl PassNames {
    /// `pass`, labelled `label`, entered at `entry_point`.
    pub(crate) const fn new(
        pass: &'static str,
        label: &'static str,
        entry_point: &'static str,
    ) -> Self {
        PassNames {
            pass,
            label,
            entry_point,
        }
    }
}

/// What one pass states: its names, the key it is built for and how the
/// key becomes its checks, bindings and WGSL.
///
/// Crate-internal: it is how this crate builds its passes, not a way for
/// a host to add one (its functions return the crate-private
/// `PassPipeline` side of the binding layer). A host reaches each pass
/// through its `new` and its `standalone` function, whose signatures do
/// not name it, so the skeleton can change without a breaking release.
pub(crate) trait PassShader {
    /// Its name, label and entry point.
    const NAMES: PassNames;
    /// What the pass is built for: its desc, and what else its `new`
    /// takes.
    type Key<'a>: Debug;

    /// Refuse a key the pass cannot be built for, before anything is
    /// built.
    fn check(key: &Self::Key<'_>) -> Result<(), PassError>;

    /// The bindings (`@group(0)`), in binding order.
    fn group(key: &Self::Key<'_>) -> Result<Group, PassError>;

    /// The shader for the key, but for the kernels' prelude before it and
    /// the group's declarations after it ([`shader`] adds both).
    fn wgsl(key: &Self::Key<'_>) -> String;

    /// The layout of the host's own bind group (`@group(1)`), if the key
    /// has one: none by default.
    fn host_layout<'a>(_key: &Self::Key<'a>) -> Option<&'a BindGroupLayout> {
        None
    }

    /// The configuration in a sentence ([`StandaloneShader::summary`]): the
    /// key's `Debug` by default.
    fn summary(key: &Self::Key<'_>) -> String {
        format!("{key:?}")
    }

    /// The group and WGSL ([`Self::group`], [`Self::wgsl`]) the GLSL is
    /// translated from, where they differ from the pass's, given its
    /// `group` ([`StandaloneShader::glsl_wgsl`]): none by default.
    fn glsl_variant(
        _key: &Self::Key<'_>,
        _group: &Group,
    ) -> Result<Option<(Group, String)>, PassError> {
        Ok(None)
    }
}

/// `g` (a filter's uniforms) with the filter's `inputs`, one-sample 2D
/// float textures read texel by texel, and its `output`, a storage
/// texture of `format`: the rest of FXAA's and TAA's groups.
pub(crate) fn filter_textures(
    mut g: Group,
    inputs: &[&'static str],
    output: &'static str,
    format: TextureFormat,
) -> Result<Group, PassError> {
    for &name in inputs {
        g.texture(
            name,
            TextureSampleType::Float { filterable: false },
            TextureViewDimension::D2,
            false,
        );
    }
    g.storage_texture(output, format)?;
    Ok(g)
}

/// The whole shader: the kernels' prelude, a pass's `wgsl`, the
/// declarations of its `group`.
fn assemble(wgsl: &str, group: &Group) -> String {
    [subcone_kernels::wgsl::PARAMS, wgsl, &group.declarations()].concat()
}

/// `P`'s group and whole shader for `key`, checked first.
pub(crate) fn shader<P: PassShader>(key: &P::Key<'_>) -> Result<(Group, String), PassError> {
    P::check(key)?;
    let group = P::group(key)?;
    let source = assemble(&P::wgsl(key), &group);
    Ok((group, source))
}

/// `P`'s pipeline for `key` on the host's device (what each pass's `new`
/// compiles).
pub(crate) fn pipeline<P: PassShader>(
    device: &Device,
    key: &P::Key<'_>,
) -> Result<PassPipeline, PassError> {
    let (group, source) = shader::<P>(key)?;
    PassPipeline::new(
        device,
        P::NAMES.label,
        group,
        source,
        P::host_layout(key),
        P::NAMES.entry_point,
    )
}

/// `P` for `key` as a standalone shader: the source [`pipeline`] compiles,
/// with its bindings, as the `"custom"` variant.
pub(crate) fn standalone<P: PassShader>(key: &P::Key<'_>) -> Result<StandaloneShader, PassError> {
    let (group, wgsl) = shader::<P>(key)?;
    let glsl = P::glsl_variant(key, &group)?;
    Ok(StandaloneShader {
        pass: P::NAMES.pass,
        variant: "custom".to_owned(),
        summary: P::summary(key),
        wgsl,
        glsl_wgsl: glsl.map(|(group, wgsl)| assemble(&wgsl, &group)),
        entry_point: P::NAMES.entry_point,
        workgroup_size: [WORKGROUP, WORKGROUP, 1],
        bindings: group.entries(),
        dispatch: DISPATCH,
    })
}
