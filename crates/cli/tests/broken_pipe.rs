//! `gonio` ends quietly when the reader of its stdout stops early (`gonio ... --json | head`):
//! it is ended by SIGPIPE like other Unix tools (status 141 in a shell), with nothing on stderr,
//! instead of panicking with "failed printing to stdout".
#![cfg(unix)]

use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};

#[test]
fn closed_stdout_ends_the_command_without_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("curves.csv");
    // About 260 kB of JSON: more than a pipe holds (64 KiB), so gonio is still writing when the
    // reader goes away.
    let mut child = Command::new(env!("CARGO_BIN_EXE_gonio"))
        .args([
            "inplane",
            "--model",
            "geometric",
            "--sq-nm",
            "300",
            "--corr-um",
            "6",
        ])
        .args([
            "--incidence-deg",
            "20,60",
            "--scatter-deg=-89:89:0.25",
            "--json",
            "-o",
        ])
        .arg(&csv)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run gonio");
    let mut stdout = child.stdout.take().unwrap();
    let mut head = [0u8; 10];
    stdout.read_exact(&mut head).unwrap();
    assert_eq!(head[0], b'{');
    drop(stdout);
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("panicked") && !stderr.contains("Broken pipe"),
        "stderr: {stderr}"
    );
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
}
