//! What a call did ([`SubconeStatus`]), why a call was refused
//! ([`Refusal`]), and the wrapper every fallible function's body runs in:
//! it keeps a panic from crossing the boundary and records the calling
//! thread's last error message.

use std::fmt::Display;
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::last_error;
// The function the documentation names.
#[cfg(doc)]
use crate::last_error::subcone_last_error_message;

/// What a call did. On any status but `Ok`, [`subcone_last_error_message`]
/// says what was wrong.
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
    /// A parameter struct's leading `size` field is not the `sizeof` of the
    /// struct this library was built with (a host compiled against another
    /// version of the header, or one that did not set it).
    StructSize = 5,
}

/// Why a call was refused: the status it returns and what was wrong (the
/// parameter, its value, what it must be), without the function's name,
/// which [`call`] puts in front.
#[derive(Debug)]
pub(crate) struct Refusal {
    pub(crate) status: SubconeStatus,
    pub(crate) message: String,
}

/// A value, or why the call is refused.
pub(crate) type Checked<T> = Result<T, Refusal>;

impl Refusal {
    /// `name` is a null pointer where one is required.
    pub(crate) fn null(name: &str) -> Self {
        Refusal {
            status: SubconeStatus::NullPointer,
            message: format!("{name} is NULL"),
        }
    }

    /// A parameter outside its domain.
    pub(crate) fn invalid(message: impl Display) -> Self {
        Refusal {
            status: SubconeStatus::InvalidArgument,
            message: message.to_string(),
        }
    }

    /// A zero size, or a length that does not match the sizes.
    pub(crate) fn size(message: impl Display) -> Self {
        Refusal {
            status: SubconeStatus::SizeMismatch,
            message: message.to_string(),
        }
    }

    /// The `size` field `name` of a `struct_name` is `got`, not `want`.
    pub(crate) fn struct_size(name: &str, struct_name: &str, got: u32, want: usize) -> Self {
        Refusal {
            status: SubconeStatus::StructSize,
            message: format!(
                "{name} is {got}, but sizeof({struct_name}) is {want} in this library: set it to \
                 sizeof({struct_name}) (a header of another version gives another size)"
            ),
        }
    }
}

/// Runs the body of the exported function `function` and returns `Ok` with
/// the calling thread's last error message cleared, or the refusal's status
/// with its message (`"function: message"`) recorded, or `Panic` with the
/// panic's message recorded when the body panicked. (Cleared at the end, so
/// that a call a callback made into the library while the body ran leaves
/// no message behind a success.)
pub(crate) fn call(function: &str, body: impl FnOnce() -> Checked<()>) -> SubconeStatus {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            last_error::clear();
            SubconeStatus::Ok
        }
        Ok(Err(refusal)) => {
            last_error::set(&format!("{function}: {}", refusal.message));
            refusal.status
        }
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .copied()
                .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
                .unwrap_or("(no message)");
            last_error::set(&format!(
                "{function}: an internal error was caught (a bug, please report it): {what}"
            ));
            SubconeStatus::Panic
        }
    }
}
