//! What a call did ([`SubconeStatus`]), and the guard that keeps a panic
//! from crossing the boundary.

use std::panic::{catch_unwind, AssertUnwindSafe};

/// What a call did.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SubconeStatus {
    /// Success: the out-pointers were written.
    Ok = 0,
    /// A required pointer was null.
    NullPointer = 1,
    /// A parameter was not finite or out of its range (named in the function's
    /// documentation).
    InvalidArgument = 2,
    /// A size was zero, or a buffer's length does not match the sizes given.
    SizeMismatch = 3,
    /// An internal error was caught before it crossed the boundary (a bug:
    /// please report it).
    Panic = 4,
}

pub(crate) fn guard(f: impl FnOnce() -> SubconeStatus) -> SubconeStatus {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or(SubconeStatus::Panic)
}

pub(crate) fn status(r: Result<SubconeStatus, SubconeStatus>) -> SubconeStatus {
    r.unwrap_or_else(|e| e)
}
