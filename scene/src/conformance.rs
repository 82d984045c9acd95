//! The one reading of `SUBCONE_REQUIRE_GPU`, and how a test that lacks a GPU
//! (or a browser) skips: one line each, counted by `.ci/run`. The checks of
//! the [`Backend`](crate::backend::Backend) contract themselves
//! (`plan_scenes`, `plan_matches_render`) are the `subcone-conformance`
//! crate's; this policy stays here because the wgpu backend's own code reads
//! it (`subcone_wgpu::gpu_required`, its `test-util` helpers), and a backend's
//! normal dependencies never include the conformance crate, which builds the
//! CPU backend.

/// Whether a GPU is required: `SUBCONE_REQUIRE_GPU` set to anything but `0`
/// or empty, as CI sets it. GPU tests then fail instead of skipping when no
/// adapter exists: a GPU test must never pass by skipping where a GPU is
/// expected. The one reading of the variable, for every crate's tests.
pub fn gpu_required() -> bool {
    std::env::var("SUBCONE_REQUIRE_GPU").is_ok_and(|v| !v.is_empty() && v != "0")
}

/// What a GPU test opened (`opened`), or `None` when it could not be opened
/// and no GPU is required ([`gpu_required`]): the test then skips, printing
/// one line, `skipped: <test>: no GPU adapter (<what>: <why>)`
/// ([`print_skipped`]), so machines without a GPU still run the rest and a
/// reader can count what checked nothing. Panics, naming `what` and the
/// error, when a GPU is required.
///
/// ```
/// use subcone_scene::conformance::or_skip;
///
/// let opened: Result<u32, &str> = Err("no adapter");
/// if !subcone_scene::conformance::gpu_required() {
///     assert_eq!(or_skip("an example", opened), None);
/// }
/// assert_eq!(or_skip("an example", Ok::<_, &str>(7)), Some(7));
/// ```
pub fn or_skip<T, E: std::fmt::Display>(what: &str, opened: Result<T, E>) -> Option<T> {
    match opened {
        Ok(t) => Some(t),
        Err(e) if !gpu_required() => {
            print_skipped(SKIP_NO_GPU, &format!("{what}: {e}"));
            None
        }
        Err(e) => panic!("{what}: no GPU adapter, and SUBCONE_REQUIRE_GPU is set: {e}"),
    }
}

/// The reason a test skips without a GPU adapter, as [`print_skipped`]
/// prints it (and as `.ci/run` counts it).
pub const SKIP_NO_GPU: &str = "no GPU adapter";

/// The reason a test skips without a browser, as [`print_skipped`] prints it.
pub const SKIP_NO_BROWSER: &str = "no browser";

/// Print the one line of a test that skips for want of a resource:
/// `skipped: <test>: <reason> (<detail>)`, where `<test>` is the running
/// test's name (libtest names each test's thread after it; `detail` alone
/// outside a test).
///
/// The line goes straight to the process's standard error, past the test
/// harness's capture, so that `cargo test` shows it even for a test that
/// passes: "470 passed" must not hide the tests that checked nothing.
/// `.ci/run` counts these lines after the README's test command.
pub fn print_skipped(reason: &str, detail: &str) {
    use std::io::Write;
    let thread = std::thread::current();
    let test = match thread.name() {
        Some(name) if name != "main" => name,
        _ => "(outside a test)",
    };
    let line = format!("skipped: {test}: {reason} ({detail})\n");
    // One write of the whole line, so that lines of parallel tests do not
    // interleave; nothing to do if standard error is gone.
    let _ = std::io::stderr().lock().write_all(line.as_bytes());
}
