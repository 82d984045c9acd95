//! Compiles the C smoke test and the README's C snippet against the checked-in
//! header with the system C compiler (through the `cc` crate), into a static
//! library the tests link. Writes only into OUT_DIR.

fn main() {
    let include = std::path::Path::new("../include");
    println!("cargo:rerun-if-changed=../include/subcone.h");
    for f in ["c/smoke.c", "c/vectors.c", "c/readme_example.c"] {
        println!("cargo:rerun-if-changed={f}");
    }
    cc::Build::new()
        .files(["c/smoke.c", "c/vectors.c", "c/readme_example.c"])
        .include(include)
        .std("c99")
        .warnings(true)
        .extra_warnings(true)
        .warnings_into_errors(true)
        // Bit-for-bit comparisons with the Rust kernels: no fused multiply-adds.
        .flag_if_supported("-ffp-contract=off")
        .compile("subcone_smoke");
}
