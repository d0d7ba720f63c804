//! `gonio brdf compute` end to end: a ray table of a small synthetic map, its provenance in
//! the .gbrdf header and its albedo near Fresnel; bad flags exit with status 2 and no file.

use crate::common::gonio_in as gonio;

#[test]
fn compute_writes_a_table_with_provenance() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let make_map = [
        "surface",
        "gen",
        "--sq-nm",
        "100",
        "--corr-um",
        "6",
        "--size",
        "128",
        "--dx-um",
        "0.5",
        "-o",
        "s.x3p",
    ];
    assert!(gonio(&make_map, d).status.success());
    let out = gonio(
        &[
            "brdf",
            "compute",
            "s.x3p",
            "--resolution",
            "16,18,36",
            "--index",
            "1.5",
            "--json",
            "-o",
            "t.gbrdf",
        ],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // A gently sloped surface (rms slope 0.033) reflects about what a flat one does at 30°
    // (the physics is tested in gonio-scatter; this coarse table is good to a few percent).
    let albedo = v["albedo"][1]["albedo"][0].as_f64().unwrap();
    let fresnel = v["albedo"][1]["fresnel_reflectance"].as_f64().unwrap();
    assert!((albedo / fresnel - 1.0).abs() < 0.05, "{v}");

    let out = gonio(&["brdf", "info", "t.gbrdf", "--json"], d);
    assert!(out.status.success());
    let info: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let p = &info["provenance"];
    assert_eq!(p["method"], "ray");
    assert_eq!(p["source"], "s.x3p");
    assert_eq!(p["refractive_index"][0], 1.5);
    assert_eq!(p["incidences"]["polar"], 9);
    assert!(p["date"].as_str().unwrap().starts_with("20"));
}

#[test]
fn bad_flags_exit_with_status_2_and_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let make_map = [
        "surface",
        "gen",
        "--sq-nm",
        "100",
        "--corr-um",
        "6",
        "--size",
        "32",
        "--dx-um",
        "0.5",
        "-o",
        "s.x3p",
    ];
    assert!(gonio(&make_map, d).status.success());
    for args in [
        &[
            "brdf",
            "compute",
            "s.x3p",
            "--resolution",
            "16,18",
            "-o",
            "t.gbrdf",
        ][..],
        &[
            "brdf",
            "compute",
            "s.x3p",
            "--resolution",
            "16,18,35",
            "-o",
            "t.gbrdf",
        ],
        &[
            "brdf",
            "compute",
            "s.x3p",
            "--wavelength-nm",
            "500,600",
            "-o",
            "t.gbrdf",
        ],
        &["brdf", "compute", "missing.x3p", "-o", "t.gbrdf"],
    ] {
        let out = gonio(args, d);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
        assert!(!d.join("t.gbrdf").exists());
    }
}
