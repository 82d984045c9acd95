//! The caller's pointers and values, checked: reads and writes through
//! pointers that may be null, slices of a pointer and a length, finite
//! parameters.

use crate::status::SubconeStatus;

/// `*p` when `p` is not null.
///
/// # Safety
/// `p` is null or points to a valid `T`.
pub(crate) unsafe fn read<T: Copy>(p: *const T) -> Result<T, SubconeStatus> {
    // SAFETY: the caller's contract; null was checked.
    unsafe { p.as_ref() }
        .copied()
        .ok_or(SubconeStatus::NullPointer)
}

/// Write `v` through `p` when `p` is not null.
///
/// # Safety
/// `p` is null or points to writable memory for a `T`.
pub(crate) unsafe fn write<T>(p: *mut T, v: T) -> SubconeStatus {
    // SAFETY: the caller's contract; null was checked.
    match unsafe { p.as_mut() } {
        Some(out) => {
            *out = v;
            SubconeStatus::Ok
        }
        None => SubconeStatus::NullPointer,
    }
}

/// Whether `len` elements at `p` can be a slice: `Ok` for `len == 0`, an
/// error for a null `p` with `len > 0` or a length that overflows the
/// address space.
fn extent<T>(p: *const T, len: usize) -> Result<(), SubconeStatus> {
    if len == 0 {
        return Ok(());
    }
    if p.is_null() {
        return Err(SubconeStatus::NullPointer);
    }
    if len
        .checked_mul(size_of::<T>())
        .is_none_or(|b| b > isize::MAX as usize)
    {
        return Err(SubconeStatus::SizeMismatch);
    }
    Ok(())
}

/// `len` elements at `p`: empty for `len == 0`, else checked by [`extent`].
///
/// # Safety
/// `p` is null or points to `len` valid, initialised `T`.
pub(crate) unsafe fn slice<'a, T>(p: *const T, len: usize) -> Result<&'a [T], SubconeStatus> {
    extent(p, len)?;
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
pub(crate) unsafe fn slice_mut<'a, T>(p: *mut T, len: usize) -> Result<&'a mut [T], SubconeStatus> {
    extent(p.cast_const(), len)?;
    if len == 0 {
        return Ok(&mut []);
    }
    // SAFETY: as `slice`.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, len) })
}

pub(crate) fn finite(values: &[f32]) -> Result<(), SubconeStatus> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SubconeStatus::InvalidArgument)
    }
}
