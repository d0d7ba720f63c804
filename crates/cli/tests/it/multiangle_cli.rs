//! `gonio multiangle`: the Cornell Cayman metallic (Cornell University Program of Computer
//! Graphics reflectance data) imported as a spectral table and read at the ASTM E2194 and E2539
//! geometries: text, JSON and the spectra CSV agree with each other; a table against itself
//! differs by nothing; an RGB table and an impossible geometry exit with status 2 and say why.

use crate::common::gonio_in as gonio;
use std::path::PathBuf;

#[test]
fn cayman_at_the_standard_geometries() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../brdf/tests/data/cayman.astm");
    let out = gonio(
        &[
            "brdf",
            "import",
            src.to_str().unwrap(),
            "--resolution",
            "32,32,32",
            "-o",
            "c.gbrdf",
        ],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    let out = gonio(&["multiangle", "c.gbrdf", "--json"], d);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let names: Vec<&str> = json["geometries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["45as15", "45as25", "45as45", "45as75", "45as110"]);
    assert_eq!(json["illuminant"], "D65");
    assert_eq!(json["observer_deg"], 10);
    let g = &json["geometries"][0];
    assert_eq!(g["viewing_deg"], -30.0);
    // The flop index is Alman's formula of the L* printed beside it.
    let l = |i: usize| json["geometries"][i]["L"].as_f64().unwrap();
    let fi = 2.69 * (l(0) - l(4)).powf(1.11) / l(2).powf(0.86);
    let got = json["flop_index"].as_f64().unwrap();
    assert!((got - fi).abs() < 1e-9 * fi, "{got} vs {fi}");
    // A metallic: far lighter near the specular direction.
    assert!(l(0) > 3.0 * l(4), "{json}");

    // E2539, a reference (itself), the spectra and the text table.
    let out = gonio(
        &[
            "multiangle",
            "c.gbrdf",
            "--standard",
            "e2539",
            "--reference",
            "c.gbrdf",
            "--spectra",
            "r.csv",
        ],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("45as-15") && text.contains("15as80"),
        "{text}"
    );
    assert!(
        text.contains("ΔE00") && text.contains("flop index"),
        "{text}"
    );
    let csv = std::fs::read_to_string(d.join("r.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 11, "{csv}");
    assert!(lines[0].starts_with("geometry,illumination_deg,aspecular_deg,R_400nm,"));
    assert_eq!(lines[0].split(',').count(), 3 + 31);
    assert!(lines[1].starts_with("45as-15,45,-15,"), "{}", lines[1]);
    let out = gonio(
        &["multiangle", "c.gbrdf", "--reference", "c.gbrdf", "--json"],
        d,
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for diff in json["differences"].as_array().unwrap() {
        assert_eq!(diff["dE00"], 0.0, "{diff}");
    }

    // Geometries of one's own; one below the surface is refused.
    let out = gonio(
        &["multiangle", "c.gbrdf", "--geometry", "45as15,60as-20"],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = gonio(&["multiangle", "c.gbrdf", "--geometry", "45as140"], d);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("45as140") && err.contains("below the surface"),
        "{err}"
    );
}

/// A table of RGB values has no spectrum to take a colour from: exit status 2, naming the file
/// and what to do.
#[test]
fn rgb_table_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let out = gonio(
        &[
            "brdf",
            "tabulate",
            "--model",
            r#"{"model":"lambert","albedo":0.5}"#,
            "--resolution",
            "8,8,8",
            "-o",
            "l.gbrdf",
        ],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = gonio(&["multiangle", "l.gbrdf"], d);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("l.gbrdf") && err.contains("needs a spectral table"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}
