//! Helpers shared by the end-to-end tests: run the real `gonio` binary and check its status.
// Each test binary uses its own subset of these helpers.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

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

/// Run `gonio` with `args` in the working directory `dir` and assert that it succeeded.
pub fn ok_in(args: &[&str], dir: &std::path::Path) -> Output {
    let out = gonio_in(args, dir);
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

/// The output folder of one `gonio demo --quick` run, shared by every test in this binary that
/// reads it (the report's test and the curves' round trip): the demo is the suite's longest
/// command, and running it once saves its whole time. The folder lies under Cargo's temporary
/// directory for integration tests and is replaced at the first call of each test run.
pub fn quick_demo() -> &'static Path {
    static OUT: OnceLock<PathBuf> = OnceLock::new();
    OUT.get_or_init(|| {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("quick-demo");
        if out.exists() {
            std::fs::remove_dir_all(&out).expect("remove the previous run's demo output");
        }
        ok(&["demo", "--quick", "-o", out.to_str().expect("a UTF-8 path")]);
        out
    })
}
