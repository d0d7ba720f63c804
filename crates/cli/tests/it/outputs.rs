//! How `gonio` delivers its output. Files it writes (CSV, PNG, .gbrdf, .x3p) get the permissions
//! of an ordinary file, 0666 less the umask as `File::create` gives, not the 0600 of a private
//! temporary file, and no temporary file stays behind. When the reader of its stdout stops early
//! (`gonio ... --json | head`), it is ended by SIGPIPE like other Unix tools (status 141 in a
//! shell) with nothing on stderr, instead of panicking with "failed printing to stdout".
#![cfg(unix)]

use crate::common::ok;
use std::io::Read;
use std::os::unix::fs::PermissionsExt;
use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};

/// Analytic in-plane curves: fast, and about 260 kB of JSON with `--json`, more than a pipe
/// holds (64 KiB).
const CURVES: [&str; 10] = [
    "inplane",
    "--model",
    "geometric",
    "--sq-nm",
    "300",
    "--corr-um",
    "6",
    "--incidence-deg",
    "20,60",
    "--scatter-deg=-89:89:0.25",
];

#[test]
fn files_have_the_permissions_of_an_ordinary_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    std::fs::File::create(path("plain")).unwrap();
    let (csv, png) = (path("curves.csv"), path("curves.png"));
    ok(&[&CURVES[..], &["-o", &csv, "--plot", &png]].concat());
    ok(&[
        "brdf",
        "tabulate",
        "--model",
        r#"{"model":"lambert","albedo":0.5}"#,
        "--resolution",
        "4,4,8",
        "--mono",
        "-o",
        &path("lambert.gbrdf"),
    ]);
    ok(&[
        "surface",
        "gen",
        "--sq-nm",
        "100",
        "--corr-um",
        "5",
        "--size",
        "32",
        "--dx-um",
        "1",
        "-o",
        &path("map.x3p"),
    ]);
    let mut modes: Vec<(String, u32)> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let mode = e.metadata().unwrap().permissions().mode() & 0o7777;
            (e.file_name().to_string_lossy().into_owned(), mode)
        })
        .collect();
    modes.sort();
    let plain = modes.iter().find(|(n, _)| n == "plain").unwrap().1;
    let names = [
        "curves.csv",
        "curves.png",
        "lambert.gbrdf",
        "map.x3p",
        "plain",
    ];
    let expected: Vec<(String, u32)> = names.iter().map(|n| (n.to_string(), plain)).collect();
    assert_eq!(modes, expected);
}

#[test]
fn closed_stdout_ends_the_command_without_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("curves.csv");
    let mut child = Command::new(env!("CARGO_BIN_EXE_gonio"))
        .args(CURVES)
        .args(["--json", "-o"])
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
