//! Helpers shared by the end-to-end tests: run the real `gonio` binary and check its status.
// Each test binary uses its own subset of these helpers.
#![allow(dead_code)]

use std::process::{Command, Output};

/// Run `gonio` with `args`.
pub fn gonio(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gonio"))
        .args(args)
        .output()
        .expect("run gonio")
}

/// Run `gonio` with `args` and assert that it succeeded.
pub fn ok(args: &[&str]) -> Output {
    let out = gonio(args);
    assert!(
        out.status.success(),
        "gonio {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Run `gonio` with `args` in the working directory `dir`.
pub fn gonio_in(args: &[&str], dir: &std::path::Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gonio"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run gonio")
}
