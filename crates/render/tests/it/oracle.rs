//! Running a Python oracle: a script reads JSON on stdin and writes JSON on stdout. A missing
//! interpreter or package skips the test, saying why, unless `GONIO_REQUIRE_ORACLES=1` (set by
//! `.ci/run`) demands it, in which case the test fails.

use std::io::Write;
use std::process::{Command, Stdio};

/// The oracle is missing: fail when `GONIO_REQUIRE_ORACLES=1` demands it, else say why.
pub fn missing(why: &str) {
    assert!(
        std::env::var("GONIO_REQUIRE_ORACLES").as_deref() != Ok("1"),
        "GONIO_REQUIRE_ORACLES=1 but {why}"
    );
    eprintln!("skipping the oracle check: {why}");
}

/// Run `script` with `input` on stdin and parse its stdout; `None` (after [`missing`]) when
/// python3 or the `module` it imports (installed as the PyPI package `package`) is not there.
pub fn run<T: serde::de::DeserializeOwned>(
    script: &str,
    module: &str,
    package: &str,
    input: &serde_json::Value,
) -> Option<T> {
    let child = Command::new("python3")
        .args(["-c", script])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn();
    let Ok(mut child) = child else {
        missing("python3 cannot be started");
        return None;
    };
    child
        .stdin
        .take()
        .unwrap()
        .write_all(serde_json::to_string(input).unwrap().as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    if !out.status.success() {
        if stderr.contains(&format!("No module named '{module}'")) {
            missing(&format!(
                "the Python package {package} is not installed (pip install {package})"
            ));
            return None;
        }
        panic!("{package} failed: {stderr}");
    }
    Some(serde_json::from_slice(&out.stdout).unwrap())
}
