//! The caller's pointers and values, checked: reads and writes through
//! pointers that may be null, parameter structs with a leading `size`,
//! slices of a pointer and a length, finite parameters. Each refusal names
//! the parameter (`name`) as the header does.

use glam::Vec3;

use crate::status::{Checked, Refusal};

/// `*p` when `p` is not null.
///
/// # Safety
/// `p` is null or points to a valid `T`.
pub(crate) unsafe fn read<T: Copy>(p: *const T, name: &str) -> Checked<T> {
    // SAFETY: the caller's contract; null was checked.
    unsafe { p.as_ref() }
        .copied()
        .ok_or_else(|| Refusal::null(name))
}

/// `*p` when `p` is not null and the struct's leading `u32` (its `size`
/// field, `{name}->size`) is `size_of::<T>()`: the leading field is read
/// first, so a smaller struct of another version is refused without being
/// read past its end.
///
/// # Safety
/// `p` is null or points to a `u32` that, when it is `size_of::<T>()`,
/// begins a valid `T`.
pub(crate) unsafe fn read_sized<T: Copy>(p: *const T, name: &str, struct_name: &str) -> Checked<T> {
    if p.is_null() {
        return Err(Refusal::null(name));
    }
    // SAFETY: non-null, and a `T` of any version begins with its `u32` size
    // (the caller's contract).
    let size = unsafe { p.cast::<u32>().read() };
    if size as usize != size_of::<T>() {
        return Err(Refusal::struct_size(
            &format!("{name}->size"),
            struct_name,
            size,
            size_of::<T>(),
        ));
    }
    // SAFETY: the size says it is a `T` of this version.
    unsafe { read(p, name) }
}

/// Write `v` through `p` when `p` is not null.
///
/// # Safety
/// `p` is null or points to writable memory for a `T`.
pub(crate) unsafe fn write<T>(p: *mut T, v: T, name: &str) -> Checked<()> {
    // SAFETY: the caller's contract; null was checked.
    match unsafe { p.as_mut() } {
        Some(out) => {
            *out = v;
            Ok(())
        }
        None => Err(Refusal::null(name)),
    }
}

/// Whether `len` elements at `p` can be a slice: `Ok` for `len == 0`, an
/// error for a null `p` with `len > 0` or a length that overflows the
/// address space.
fn extent<T>(p: *const T, len: usize, name: &str) -> Checked<()> {
    if len == 0 {
        return Ok(());
    }
    if p.is_null() {
        return Err(Refusal::null(&format!("{name} (of length {len})")));
    }
    if len
        .checked_mul(size_of::<T>())
        .is_none_or(|b| b > isize::MAX as usize)
    {
        return Err(Refusal::size(format!(
            "{name} has a length of {len} elements of {} bytes, more than the address space holds",
            size_of::<T>()
        )));
    }
    Ok(())
}

/// `len` elements at `p`: empty for `len == 0`, else checked by [`extent`].
///
/// # Safety
/// `p` is null or points to `len` valid, initialised `T`.
pub(crate) unsafe fn slice<'a, T>(p: *const T, len: usize, name: &str) -> Checked<&'a [T]> {
    extent(p, len, name)?;
    if len == 0 {
        return Ok(&[]);
    }
    // SAFETY: non-null, a length that fits (checked), the caller's contract
    // on validity.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// `len` writable elements at `p`, checked as [`slice`] checks.
///
/// # Safety
/// `p` is null or points to `len` writable `T`, not otherwise borrowed.
pub(crate) unsafe fn slice_mut<'a, T>(p: *mut T, len: usize, name: &str) -> Checked<&'a mut [T]> {
    extent(p.cast_const(), len, name)?;
    if len == 0 {
        return Ok(&mut []);
    }
    // SAFETY: as `slice`.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, len) })
}

/// Every `(name, value)` finite; the first that is not is named.
pub(crate) fn finite(values: &[(&str, f32)]) -> Checked<()> {
    match values.iter().find(|(_, v)| !v.is_finite()) {
        None => Ok(()),
        Some((name, v)) => Err(Refusal::invalid(format!(
            "{name} is {v}; it must be finite"
        ))),
    }
}

/// Every element of the array `name` finite; the first that is not is
/// named with its index.
pub(crate) fn finite_array(name: &str, values: &[f32]) -> Checked<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(Refusal::invalid(format!(
            "{name}[{i}] is {}; it must be finite",
            values[i]
        ))),
    }
}

/// The vector `name` finite in every component.
pub(crate) fn finite_vec(name: &str, v: Vec3) -> Checked<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(Refusal::invalid(format!(
            "{name} is ({}, {}, {}); it must be finite",
            v.x, v.y, v.z
        )))
    }
}
