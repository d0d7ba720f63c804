//! `gonio color xyz` end to end: a ColorChecker patch written as a spectrum CSV, its JSON and text
//! output, and the errors for bad files and flags.

use crate::common::gonio;
use std::path::{Path, PathBuf};

/// Patch 1 ("dark skin") of N. Ohta's ColorChecker table as a `wavelength_nm,value` CSV.
fn dark_skin_csv(dir: &Path) -> PathBuf {
    let table = include_str!("../../../color/data/MacbethColorChecker.dat");
    let mut csv = String::from("wavelength_nm,reflectance\n");
    for line in table.lines().filter(|l| !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split(',').collect();
        csv.push_str(&format!("{},{}\n", fields[0], fields[1]));
    }
    let path = dir.join("dark_skin.csv");
    std::fs::write(&path, csv).unwrap();
    path
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// The JSON carries the XYZ that colour-science computes for this patch (reference in
/// crates/color/tests/it/colorchecker.rs: 10.972394, 9.704581, 6.057211 under D65, 2°) and the
/// published CIELAB check value 37.30, 13.69, 15.57 (within 0.02, see that test).
#[test]
fn json_output_for_a_colorchecker_patch() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dark_skin_csv(dir.path());
    let out = gonio(&[
        "color",
        "xyz",
        "--spectrum",
        csv.to_str().unwrap(),
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["illuminant"], "D65");
    assert_eq!(v["observer_deg"], 2);
    let xyz = [&v["xyz"]["x"], &v["xyz"]["y"], &v["xyz"]["z"]].map(|x| x.as_f64().unwrap());
    for (got, want) in xyz.iter().zip([10.972394, 9.704581, 6.057211]) {
        assert!((got - want).abs() < 1e-5, "{xyz:?}");
    }
    let lab = &v["cielab"];
    for (key, want) in [("l_star", 37.30), ("a_star", 13.69), ("b_star", 15.57)] {
        assert!((lab[key].as_f64().unwrap() - want).abs() < 0.02, "{lab}");
    }
    assert_eq!(v["srgb_in_gamut"], true);
    let hex = v["srgb_hex"].as_str().unwrap();
    assert!(hex.starts_with('#') && hex.len() == 7);
}

/// Under A with the 10° observer the perfect white is still white on the display (Bradford
/// adaptation), and the text output names every quantity.
#[test]
fn text_output_and_illuminant_a() {
    let dir = tempfile::tempdir().unwrap();
    let white = write(
        dir.path(),
        "white.csv",
        "wavelength_nm,value\n380,1\n780,1\n",
    );
    let out = gonio(&[
        "color",
        "xyz",
        "--spectrum",
        &white,
        "--illuminant",
        "A",
        "--observer",
        "10",
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["srgb_hex"], "#ffffff");
    for c in ["r", "g", "b"] {
        assert!((v["linear_srgb"][c].as_f64().unwrap() - 1.0).abs() < 1e-9);
    }
    assert!((v["cielab"]["l_star"].as_f64().unwrap() - 100.0).abs() < 1e-9);

    let out = gonio(&["color", "xyz", "--spectrum", &white]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for label in [
        "XYZ",
        "xyY",
        "CIELAB",
        "linear sRGB",
        "sRGB",
        "#ffffff",
        "D65",
    ] {
        assert!(text.contains(label), "{label} missing from:\n{text}");
    }
}

/// Bad input exits with status 2 and a message naming the file, the line and the fix.
#[test]
fn errors_name_the_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let bad_value = write(
        dir.path(),
        "bad.csv",
        "wavelength_nm,value\n400,0.1\n410,abc\n",
    );
    let bad_header = write(
        dir.path(),
        "um.csv",
        "wavelength_um,value\n0.4,0.1\n0.5,0.2\n",
    );
    let unsorted = write(
        dir.path(),
        "unsorted.csv",
        "wavelength_nm,value\n500,0.1\n400,0.2\n",
    );
    let missing = dir.path().join("missing.csv").display().to_string();
    let cases = [
        (
            bad_value.as_str(),
            "bad.csv, line 3: column 2: `abc` is not a number",
        ),
        (
            bad_header.as_str(),
            "um.csv, line 1: expected the header `wavelength_nm,value`",
        ),
        (unsorted.as_str(), "unsorted.csv, line 3: wavelength 400 nm"),
        (missing.as_str(), "missing.csv: cannot read the file"),
    ];
    for (file, message) in cases {
        let out = gonio(&["color", "xyz", "--spectrum", file]);
        assert_eq!(out.status.code(), Some(2));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(message), "{stderr}");
        assert!(out.stdout.is_empty());
    }
    let good = dark_skin_csv(dir.path());
    for (flag, value, message) in [
        ("--illuminant", "F2", "use D65 or A"),
        ("--observer", "5", "use 2 (CIE 1931) or 10 (CIE 1964)"),
    ] {
        let out = gonio(&[
            "color",
            "xyz",
            "--spectrum",
            good.to_str().unwrap(),
            flag,
            value,
        ]);
        assert_eq!(out.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&out.stderr).contains(message));
    }
}
