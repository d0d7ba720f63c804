//! Running a Python snippet for the tests that compare with a Python package.

use std::process::Command;

/// Run `code` with `python3` (or `$GONIO_PYTHON`), its stdout; `None` (with a note) when
/// `module` is missing and oracles are not required (`GONIO_REQUIRE_ORACLES=1`).
pub fn python(module: &str, code: &str) -> Option<String> {
    let python = std::env::var("GONIO_PYTHON").unwrap_or_else(|_| "python3".into());
    let required = gonio_conformance::oracles_required();
    let probe = Command::new(&python)
        .args(["-c", &format!("import {module}")])
        .output();
    match probe {
        Ok(o) if o.status.success() => {}
        _ => {
            assert!(!required, "GONIO_REQUIRE_ORACLES=1 but {module} is missing");
            eprintln!("skipping: the Python module {module} is not installed");
            return None;
        }
    }
    let out = Command::new(&python).args(["-c", code]).output().unwrap();
    assert!(
        out.status.success(),
        "python failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(String::from_utf8(out.stdout).unwrap())
}
