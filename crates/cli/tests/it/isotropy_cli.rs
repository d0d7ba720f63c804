//! End-to-end tests of `gonio isotropy`: a synthesised map through the real binary, the JSON, the
//! CSV and the plots, and errors that exit with status 2 without writing output.

use crate::common::{gonio, ok};
use std::path::Path;

fn gen_map(dir: &Path) -> String {
    let path = dir.join("gauss.x3p").to_str().unwrap().to_string();
    ok(&[
        "surface",
        "gen",
        "--sq-nm",
        "300",
        "--corr-um",
        "3",
        "--size",
        "128",
        "--dx-um",
        "0.5",
        "--seed",
        "3",
        "-o",
        &path,
    ]);
    path
}

#[test]
fn quarter_and_eighth_turns_json_csv_and_plots() {
    let dir = tempfile::tempdir().unwrap();
    let map = gen_map(dir.path());
    let csv = dir.path().join("iso.csv");
    let png = dir.path().join("iso.png");
    let out = ok(&[
        "isotropy",
        &map,
        "--angle-deg",
        "90,45",
        "--json",
        "--csv",
        csv.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["method"], "ray");
    assert!(v["wavelength_nm"].is_null());
    let checks = v["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 2);
    let quarter = &checks[0];
    assert_eq!(quarter["angle_deg"], 90.0);
    assert_eq!(quarter["exact"], true);
    assert_eq!(quarter["rotated"]["nx"], 128);
    let slope = |o: &str, k: &str| quarter[o][k].as_f64().unwrap();
    assert!((slope("rotated", "rms_slope_x") - slope("original", "rms_slope_y")).abs() < 1e-12);
    let comparisons = quarter["comparisons"].as_array().unwrap();
    assert_eq!(comparisons.len(), 4);
    for c in comparisons {
        assert!(c["rms_log10"].as_f64().unwrap().is_finite());
        assert!(c["peak_a"]["position_deg"].is_number() && c["peak_b"]["reflectance"].is_number());
    }
    // 45°: both maps cropped to the square inside the turned one (127/√2 = 89.8 points, less one
    // of margin, made even like 128).
    assert_eq!(checks[1]["exact"], false);
    assert_eq!(checks[1]["rotated"]["nx"], 88);
    assert_eq!(checks[1]["original"]["ny"], 88);

    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "rotation_deg,orientation,method,wavelength_nm,incidence_deg,scatter_deg,brdf_per_sr,\
         reflectance,rel_uncertainty"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2 * 2 * 4 * 151);
    assert!(rows.iter().all(|r| r.len() == 9));
    assert!(
        rows.iter()
            .any(|r| r[0] == "45" && r[1] == "rotated" && r[2] == "ray")
    );
    for angle in ["90", "45"] {
        let plot = dir.path().join(format!("iso_rot{angle}.png"));
        let img = image::open(&plot).unwrap();
        assert!(img.width() > 500, "{}", plot.display());
    }

    let text_out = ok(&["isotropy", &map, "--incidence-deg", "20"]);
    let text_out = String::from_utf8(text_out.stdout).unwrap();
    assert!(text_out.contains("turned by 90°") && text_out.contains("left: original"));
}

#[test]
fn kirchhoff_method_reports_its_wavelength() {
    let dir = tempfile::tempdir().unwrap();
    let map = gen_map(dir.path());
    let out = ok(&[
        "isotropy",
        &map,
        "--method",
        "kirchhoff",
        "--wavelength-nm",
        "600",
        "--incidence-deg",
        "20",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["method"], "kirchhoff");
    assert_eq!(v["wavelength_nm"], 600.0);
    let c = &v["checks"][0]["comparisons"][0];
    assert_eq!(c["wavelength_nm"], 600.0);
    assert!(c["rms_log10"].as_f64().unwrap().is_finite());
}

#[test]
fn bad_input_exits_2_without_output() {
    let dir = tempfile::tempdir().unwrap();
    let map = gen_map(dir.path());
    let csv = dir.path().join("never.csv");
    let missing = dir.path().join("missing.x3p");
    for (args, expect) in [
        (vec![missing.to_str().unwrap()], "missing.x3p"),
        (vec![&map, "--incidence-deg", "95"], "--incidence-deg 95"),
        (vec![&map, "--angle-deg", "nan"], "--angle-deg"),
        (vec![&map, "--wavelength-nm", "0"], "--wavelength-nm"),
    ] {
        let out = gonio(
            &[
                &["isotropy"][..],
                &args,
                &["--csv", csv.to_str().unwrap()][..],
            ]
            .concat(),
        );
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(expect), "{args:?}: {err}");
        assert!(!csv.exists());
    }
}
