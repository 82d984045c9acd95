//! The library's version, as the header's `SUBCONE_VERSION_*` macros and
//! as a call.

/// Major version of this library (the crate's; see [`subcone_version`]).
pub const SUBCONE_VERSION_MAJOR: u32 = 0;
/// Minor version.
pub const SUBCONE_VERSION_MINOR: u32 = 2;
/// Patch version.
pub const SUBCONE_VERSION_PATCH: u32 = 0;

/// The library's version: `major << 16 | minor << 8 | patch`; compare it
/// with the header's `SUBCONE_VERSION_*` to catch a mismatched library.
#[no_mangle]
pub extern "C" fn subcone_version() -> u32 {
    SUBCONE_VERSION_MAJOR << 16 | SUBCONE_VERSION_MINOR << 8 | SUBCONE_VERSION_PATCH
}
