//! A picture's manifest: the SHA-256 of its files against coreutils' `sha256sum`, and its
//! fields; a view's files and their manifest together.

use crate::oracle;
use gonio_color::Observer;
use gonio_render::picture::{
    DisplayPicture, DisplaySpace, MANIFEST_FORMAT, XyzPicture, sha256_file, write_manifest,
    write_view,
};
use std::process::Command;

/// `sha256sum`'s hash of `path` (coreutils, an implementation independent of the `sha2`
/// crate); `None` (after [`oracle::missing`]) where the program is missing.
fn sha256sum(path: &std::path::Path) -> Option<String> {
    let Ok(out) = Command::new("sha256sum").arg(path).output() else {
        oracle::missing("sha256sum (GNU coreutils) cannot be started");
        return None;
    };
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    Some(
        String::from_utf8(out.stdout)
            .unwrap()
            .split_whitespace()
            .next()?
            .to_string(),
    )
}

#[test]
fn manifest_hashes_match_sha256sum_and_record_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let scene = dir.path().join("booth.toml");
    std::fs::write(&scene, "[booth]\nilluminance_lux = 2000\n").unwrap();
    let empty = dir.path().join("empty.txt");
    std::fs::write(&empty, "").unwrap();
    // Larger than the hashing buffer (64 KiB), not a multiple of it.
    let big = out_dir.join("view.exr");
    std::fs::write(
        &big,
        (0..200_003u32)
            .map(|i| (i * 7 % 251) as u8)
            .collect::<Vec<_>>(),
    )
    .unwrap();
    let settings = serde_json::json!({ "spp": 64, "view": "45", "observer": "CIE 1931 2°" });
    let manifest_path = out_dir.join("manifest.json");
    let m = write_manifest(&manifest_path, &[&scene, &empty], 7, &settings, &[&big]).unwrap();
    let read: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&manifest_path).unwrap()).unwrap();
    assert_eq!(read, m);
    assert_eq!(m["format"], MANIFEST_FORMAT);
    assert_eq!(m["gonio_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(m["seed"], 7);
    assert_eq!(m["settings"], settings);
    assert_eq!(m["outputs"][0]["path"], "view.exr");
    assert_eq!(m["outputs"][0]["bytes"], 200_003);
    assert_eq!(m["inputs"][0]["path"], scene.to_string_lossy().as_ref());
    // The empty file's hash is FIPS 180-4's for the empty message.
    assert_eq!(
        m["inputs"][1]["sha256"],
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
    );
    for (entry, path) in [
        (&m["inputs"][0], &scene),
        (&m["inputs"][1], &empty),
        (&m["outputs"][0], &big),
    ] {
        assert_eq!(entry["sha256"], sha256_file(path).unwrap().0);
        match sha256sum(path) {
            Some(h) => assert_eq!(entry["sha256"], h.as_str(), "{}", path.display()),
            None => eprintln!("only the empty file's known hash is checked"),
        }
    }
}

#[test]
fn a_missing_input_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no-such-scene.toml");
    let err = write_manifest(
        &dir.path().join("manifest.json"),
        &[&missing],
        1,
        &serde_json::Value::Null,
        &[],
    )
    .unwrap_err();
    assert!(err.to_string().contains("no-such-scene.toml"), "{err}");
    assert!(!dir.path().join("manifest.json").exists());
}

/// A view's five files, named after it, with the fractions its renderings report, and the
/// manifest naming them relative to its folder.
#[test]
fn a_view_writes_its_files_and_its_manifest_lists_them() {
    let dir = tempfile::tempdir().unwrap();
    let white = [95.047f64, 100.0, 108.883];
    // A grey, a highlight above the white, and a saturated green outside sRGB.
    let xyz = [
        [19.0f32, 20.0, 21.8],
        [190.0, 200.0, 217.8],
        [17.0, 50.0, 9.0],
    ];
    let picture = XyzPicture::new(3, 1, &xyz, Observer::Cie1931TwoDegree).unwrap();
    let files = write_view(dir.path(), "45deg", &picture, white).unwrap();
    let names: Vec<String> = files
        .paths()
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "45deg.exr",
            "45deg-srgb.png",
            "45deg-srgb-mask.png",
            "45deg-p3.png",
            "45deg-p3-mask.png"
        ]
    );
    for d in &files.displays {
        let shown = DisplayPicture::new(&picture, white, d.space).unwrap();
        assert_eq!(
            (d.out_of_gamut_fraction, d.over_range_fraction),
            (shown.out_of_gamut_fraction(), shown.over_range_fraction())
        );
        assert!(!std::fs::read(&d.png).unwrap().is_empty());
    }
    assert_eq!(files.displays[0].space, DisplaySpace::Srgb);
    assert_eq!(files.displays[0].out_of_gamut_fraction, 1.0 / 3.0);
    assert_eq!(files.displays[0].over_range_fraction, 1.0 / 3.0);
    let m = write_manifest(
        &dir.path().join("manifest.json"),
        &[],
        3,
        &serde_json::json!({}),
        &files.paths(),
    )
    .unwrap();
    for (entry, name) in m["outputs"].as_array().unwrap().iter().zip(&names) {
        assert_eq!(entry["path"], name.as_str());
    }
}
