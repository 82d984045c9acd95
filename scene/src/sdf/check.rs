//! The parameter checks every node and shape constructor makes, each an
//! [`SdfError`] that names the node and the parameter.

use glam::Vec3;

use super::SdfError;

/// How far from 1 the length of a rotation quaternion or a plane normal may be
/// for it to be taken as unit and kept as given (a few f32 ulps): normalising
/// again would move its last bits.
pub const UNIT_TOLERANCE: f64 = 4.0 * f32::EPSILON as f64;

/// `Ok` when `finite` (the caller's test of a scalar, vector or quaternion
/// parameter), else the error that `param` of `node` is not finite.
pub(super) fn all_finite(
    node: &'static str,
    param: &'static str,
    finite: bool,
) -> Result<(), SdfError> {
    if finite {
        Ok(())
    } else {
        Err(SdfError::NonFinite { node, param })
    }
}

/// `v` when it is finite.
pub(super) fn finite(node: &'static str, param: &'static str, v: f32) -> Result<f32, SdfError> {
    all_finite(node, param, v.is_finite())?;
    Ok(v)
}

/// `v` when it is finite and above zero.
pub(super) fn positive(node: &'static str, param: &'static str, v: f32) -> Result<f32, SdfError> {
    finite(node, param, v)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(SdfError::NonPositive {
            node,
            param,
            value: v,
        })
    }
}

/// `v` when it is finite and not negative.
pub(super) fn nonneg(node: &'static str, param: &'static str, v: f32) -> Result<f32, SdfError> {
    finite(node, param, v)?;
    if v >= 0.0 {
        Ok(v)
    } else {
        Err(SdfError::Negative {
            node,
            param,
            value: v,
        })
    }
}

/// [`nonneg`] for each component of `v`, in the order x, y, z.
pub(super) fn nonneg3(node: &'static str, param: &'static str, v: Vec3) -> Result<(), SdfError> {
    for c in v.to_array() {
        nonneg(node, param, c)?;
    }
    Ok(())
}

/// `Ok` when `v` does not exceed `limit`, which the message calls `what`.
pub(super) fn at_most(
    node: &'static str,
    param: &'static str,
    v: f32,
    limit: f32,
    what: &'static str,
) -> Result<(), SdfError> {
    if v > limit {
        Err(SdfError::Invalid {
            node,
            reason: format!("{param} {v} exceeds {what} {limit}"),
        })
    } else {
        Ok(())
    }
}
