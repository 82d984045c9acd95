//! `include/subcone.h` is what cbindgen generates from `src/lib.rs` today:
//! regenerated in memory and compared; the test fails on any difference. To
//! update the checked-in header after changing the ABI, run
//! `SUBCONE_BLESS=1 cargo test -p subcone-capi --test header` (nothing else
//! writes into the source tree).

use std::path::Path;

#[test]
fn the_checked_in_header_is_current() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).unwrap();
    let bindings = cbindgen::Builder::new()
        .with_crate(crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let path = crate_dir.join("include/subcone.h");
    if std::env::var_os("SUBCONE_BLESS").is_some() {
        std::fs::write(&path, &generated).unwrap();
        return;
    }
    let checked_in = std::fs::read(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "capi/include/subcone.h is stale: regenerate it with \
         `SUBCONE_BLESS=1 cargo test -p subcone-capi --test header`"
    );
}

/// The header's version macros are the crate's version.
#[test]
fn the_version_constants_are_the_crate_version() {
    use subcone_capi::*;
    let v = |s: &str| s.parse::<u32>().unwrap();
    assert_eq!(SUBCONE_VERSION_MAJOR, v(env!("CARGO_PKG_VERSION_MAJOR")));
    assert_eq!(SUBCONE_VERSION_MINOR, v(env!("CARGO_PKG_VERSION_MINOR")));
    assert_eq!(SUBCONE_VERSION_PATCH, v(env!("CARGO_PKG_VERSION_PATCH")));
    assert_eq!(
        subcone_version(),
        SUBCONE_VERSION_MAJOR << 16 | SUBCONE_VERSION_MINOR << 8 | SUBCONE_VERSION_PATCH
    );
}
