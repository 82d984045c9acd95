//! The calling thread's last error message: set by every call that returns
//! an error status, cleared by every call that returns `Ok`, read with
//! [`subcone_last_error_message`].

use std::cell::RefCell;
use std::ffi::{c_char, CStr, CString};

// Documentation links.
#[cfg(doc)]
use crate::status::SubconeStatus;

thread_local! {
    /// The message of the last call on this thread that returned an error,
    /// none after a success.
    static LAST_ERROR: RefCell<Option<CString>> = const { RefCell::new(None) };
}

/// What [`subcone_last_error_message`] returns when there is no error.
const NO_ERROR: &CStr = c"";

/// Forgets this thread's message (a call succeeded). Cheap when there is
/// none.
pub(crate) fn clear() {
    // `try_with`: a call made while the thread's storage is being destroyed
    // keeps no message rather than panicking.
    let _ = LAST_ERROR.try_with(|m| {
        if let Ok(mut m) = m.try_borrow_mut() {
            if m.is_some() {
                *m = None;
            }
        }
    });
}

/// Records `message` as this thread's last error (a NUL in it, which no
/// message of this library has, becomes a space).
pub(crate) fn set(message: &str) {
    let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
    let _ = LAST_ERROR.try_with(|m| {
        if let Ok(mut m) = m.try_borrow_mut() {
            *m = Some(message);
        }
    });
}

/// The calling thread's last error message: what the last call on this
/// thread that returned a [`SubconeStatus`] found wrong, naming the
/// function, the parameter (`frame->colors_len`, say), its value and what
/// it must be, as one line of UTF-8 text. An empty string, never NULL, when
/// that call returned `SUBCONE_STATUS_OK` or no such call was made.
///
/// Every function that returns a `SubconeStatus` sets the message when it
/// fails and clears it when it succeeds, so read it right after the failing
/// call. The pointer is owned by the library and stays valid until the next
/// call into the library on the same thread (other than this function, and
/// `subcone_version`); copy the text to keep it longer. Each thread has its
/// own message.
///
/// ```c
/// SubconeStatus s = subcone_sraa_resolve(&params, &frame, out, out_len);
/// if (s != SUBCONE_STATUS_OK) {
///     fprintf(stderr, "SRAA resolve failed (%d): %s\n", (int)s, subcone_last_error_message());
/// }
/// ```
#[no_mangle]
pub extern "C" fn subcone_last_error_message() -> *const c_char {
    LAST_ERROR
        .try_with(|m| match m.try_borrow() {
            Ok(m) => m.as_deref().unwrap_or(NO_ERROR).as_ptr(),
            Err(_) => NO_ERROR.as_ptr(),
        })
        .unwrap_or(NO_ERROR.as_ptr())
}
