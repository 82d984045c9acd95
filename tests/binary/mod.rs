//! Running the `subcone` binary from the end-to-end tests.

use std::process::Command;

/// Runs `subcone args…`: whether it succeeded, and its stdout then its
/// stderr. A panic is never an answer, whatever the arguments: it fails the
/// test here.
pub fn subcone(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_subcone"))
        .args(args)
        .output()
        .expect("run subcone");
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(!text.contains("panicked"), "subcone panicked: {text}");
    (out.status.success(), text)
}
