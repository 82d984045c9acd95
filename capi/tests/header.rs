//! `include/subcone.h` is what cbindgen generates from `src/` today:
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

/// The text of every file of `src/` (`lib.rs` and its modules).
fn sources(crate_dir: &Path) -> String {
    let mut files: Vec<_> = std::fs::read_dir(crate_dir.join("src"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every public `#[repr(C)]` struct of `src/` is in the header: a C
/// host cannot fill a struct it cannot name (cbindgen writes only what an
/// exported function reaches, unless `cbindgen.toml` includes it).
#[test]
fn every_public_struct_is_in_the_header() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let src = sources(crate_dir);
    let header = std::fs::read_to_string(crate_dir.join("include/subcone.h")).unwrap();
    let structs: Vec<&str> = src
        .lines()
        .filter_map(|l| l.trim().strip_prefix("pub struct "))
        .filter_map(|rest| rest.split([' ', '{', '<', '(']).next())
        .collect();
    assert!(structs.len() > 10, "found only {structs:?}");
    for name in structs {
        assert!(
            header.contains(&format!("typedef struct {name} {{")),
            "{name} is not in capi/include/subcone.h: add it to `include` in cbindgen.toml"
        );
    }
}
