//! `gonio brdf compute` end to end: a ray table of a small synthetic map, its provenance in
//! the .gbrdf header and its albedo near Fresnel; a Kirchhoff table of a rough map, the methods
//! it says it used where, and its estimate and progress lines when stderr is not a terminal;
//! bad flags exit with status 2 and no file.

use crate::common::gonio_in as gonio;
use std::process::Command;

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
        &[
            "brdf",
            "compute",
            "s.x3p",
            "--method",
            "kirchhoff",
            "--geometric-above-g",
            "0",
            "-o",
            "t.gbrdf",
        ],
    ] {
        let out = gonio(args, d);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
        assert!(!d.join("t.gbrdf").exists());
    }
}

/// A Kirchhoff table of a rough map (Sq 0.8 µm, T 6 µm: the 805 nm epoxy sample, cut down to
/// 64² points) says which method it used where: the stationary-phase limit where
/// `g = (2π σ (cos θi + cos θo)/λ)²` exceeds 25, the integral elsewhere, in its text report, its
/// JSON and the table's provenance. Its stderr, captured here and so not a terminal, carries the
/// estimated time and the progress lines: with `GONIO_PROGRESS_SECONDS=0` (a line at every
/// report, the estimate at the first) one line per hemisphere map, up to 100%; with the default
/// interval (10 s) this second-long run prints none of them.
#[test]
fn kirchhoff_compute_says_which_method_where_and_how_far_it_has_come() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let make_map = [
        "surface",
        "gen",
        "--sq-nm",
        "800",
        "--corr-um",
        "6",
        "--size",
        "64",
        "--dx-um",
        "0.5",
        "-o",
        "s.x3p",
    ];
    assert!(gonio(&make_map, d).status.success());
    let compute = |interval: Option<&str>, json: bool| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_gonio"));
        c.args([
            "brdf",
            "compute",
            "s.x3p",
            "--method",
            "kirchhoff",
            "--resolution",
            "8,8,16",
            "--incidences",
            "8",
            "-o",
            "t.gbrdf",
        ])
        .current_dir(d)
        .env_remove("GONIO_PROGRESS_SECONDS");
        if json {
            c.arg("--json");
        }
        if let Some(s) = interval {
            c.env("GONIO_PROGRESS_SECONDS", s);
        }
        let out = c.output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        (
            String::from_utf8(out.stdout).unwrap(),
            String::from_utf8(out.stderr).unwrap(),
        )
    };
    let (stdout, stderr) = compute(Some("0"), false);
    assert!(
        stdout.contains(
            "the stationary-phase (geometric) limit where g = (2π σ (cos θi + cos θo)/λ)² > 25"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("the full integral elsewhere (incidences from"),
        "{stdout}"
    );
    let lines: Vec<&str> = stderr.lines().collect();
    assert!(
        lines[0].starts_with("brdf compute (kirchhoff): estimated time about "),
        "{stderr}"
    );
    let progress: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| l.contains("% done, ") && l.contains(" elapsed, about "))
        .collect();
    assert_eq!(progress.len(), 8, "{stderr}");
    assert!(
        progress[7].starts_with("brdf compute (kirchhoff): 100% done, "),
        "{stderr}"
    );

    let (stdout, stderr) = compute(None, true);
    assert!(
        !stderr.contains("% done") && !stderr.contains("estimated"),
        "{stderr}"
    );
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let m = &v["kirchhoff_methods"][0];
    assert_eq!(m["wavelength_nm"], 550.0);
    assert_eq!(m["geometric_above_g"], 25.0);
    let share = m["geometric_share"].as_f64().unwrap();
    assert!(share > 0.5 && share < 1.0, "{m}");
    let out = gonio(&["brdf", "info", "t.gbrdf", "--json"], d);
    let info: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(info["provenance"]["kirchhoff_methods"][0], *m);
}
