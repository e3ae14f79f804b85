//! Helpers shared by the command-line tests: running the `mdr-dem` binary this test suite was
//! built with, and reading its output.

#![allow(dead_code)]

use std::process::{Command, Output};

/// Runs `mdr-dem` with `args` and waits for it.
pub fn mdr_dem(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_mdr-dem"))
        .args(args)
        .output()
        .expect("run mdr-dem")
}

/// The standard output of a run that succeeded (the test fails with its standard error
/// otherwise).
pub fn stdout(output: &Output) -> String {
    assert!(
        output.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout.clone()).unwrap()
}

/// A fresh temporary directory, removed when dropped.
pub fn scratch(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("mdr-dem-cli-{name}-"))
        .tempdir()
        .unwrap()
}
