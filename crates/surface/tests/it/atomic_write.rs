//! `io::write_atomic`: outputs get ordinary permissions, replaced files keep theirs, and a write
//! that fails leaves the old file whole and no temporary file behind.
#![cfg(unix)]

use gonio_surface::io::write_atomic;
use std::io::Write;
use std::os::unix::fs::PermissionsExt;
use std::path::Path;

fn mode(path: &Path) -> u32 {
    std::fs::metadata(path).unwrap().permissions().mode() & 0o7777
}

fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn new_file_gets_the_permissions_of_an_ordinary_file() {
    let dir = tempfile::tempdir().unwrap();
    let plain = dir.path().join("plain.txt");
    std::fs::File::create(&plain).unwrap();
    let out = dir.path().join("out.gsf");
    write_atomic(&out, |w| w.write_all(b"data")).unwrap();
    assert_eq!(std::fs::read(&out).unwrap(), b"data");
    // 0666 less the umask, like `File::create`; temporary-file crates would leave 0600.
    assert_eq!(mode(&out), mode(&plain));
    assert_eq!(names(dir.path()), ["out.gsf", "plain.txt"]);
}

#[test]
fn replaced_file_keeps_its_permissions() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.x3p");
    std::fs::write(&out, b"old").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o640)).unwrap();
    write_atomic(&out, |w| w.write_all(b"new")).unwrap();
    assert_eq!(std::fs::read(&out).unwrap(), b"new");
    assert_eq!(mode(&out), 0o640);
}

#[test]
fn failed_write_leaves_the_old_file_and_no_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.x3p");
    std::fs::write(&out, b"old content").unwrap();
    let err = write_atomic(&out, |w| {
        w.write_all(&[7u8; 100_000])?;
        Err(std::io::Error::other("disk full"))
    })
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("out.x3p") && err.contains("disk full"),
        "{err}"
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"old content");
    assert_eq!(names(dir.path()), ["out.x3p"]);
}

#[test]
fn failed_rename_leaves_the_target_untouched() {
    let dir = tempfile::tempdir().unwrap();
    // A non-empty directory cannot be replaced by a file: the rename fails after the write.
    // (atomic-write-file 0.3.1 then leaves its temporary `.taken.XXXXXX` behind, so only the
    // target is checked here.)
    let out = dir.path().join("taken");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("inside"), b"x").unwrap();
    let err = write_atomic(&out, |w| w.write_all(b"data")).unwrap_err();
    assert!(err.to_string().contains("taken"), "{err}");
    assert_eq!(names(&out), ["inside"]);
    assert_eq!(std::fs::read(out.join("inside")).unwrap(), b"x");
}
