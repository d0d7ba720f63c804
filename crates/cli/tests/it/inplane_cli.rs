//! End-to-end tests of `gonio inplane`: a synthesised height map through the real binary, the
//! CSV columns, the JSON, the plot, and errors that exit with status 2 without writing output.

use crate::common::{gonio, ok};
use std::path::Path;

fn gen_map(dir: &Path) -> String {
    let path = dir.join("gauss.x3p").to_str().unwrap().to_string();
    let args = [
        "surface",
        "gen",
        "--sq-nm",
        "300",
        "--corr-um",
        "6",
        "--size",
        "256",
    ];
    ok(&[&args[..], &["--dx-um", "0.5", "--seed", "4", "-o", &path]].concat());
    path
}

#[test]
fn ray_curves_csv_json_and_plot() {
    let dir = tempfile::tempdir().unwrap();
    let map = gen_map(dir.path());
    let csv = dir.path().join("out.csv");
    let png = dir.path().join("out.png");
    let out = ok(&[
        "inplane",
        &map,
        "--method",
        "ray",
        "--incidence-deg",
        "20,60",
        "--scatter-deg=-75:75:1",
        "--aperture-deg",
        "1.4",
        "--index",
        "1.55",
        "--wavelength-nm",
        "550",
        "-o",
        csv.to_str().unwrap(),
        "--plot",
        png.to_str().unwrap(),
        "--json",
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert!(
        header
            .starts_with("method,wavelength_nm,incidence_deg,scatter_deg,brdf_per_sr,reflectance")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2 * 151);
    // The brightest detector of each curve lies near the specular angle +ti (slopes ~0.1 rad).
    for ti in ["20", "60"] {
        let best = rows
            .iter()
            .filter(|r| r[0] == "ray" && r[1] == "550" && r[2] == ti)
            .max_by(|a, b| {
                a[5].parse::<f64>()
                    .unwrap()
                    .total_cmp(&b[5].parse::<f64>().unwrap())
            })
            .unwrap();
        let peak: f64 = best[3].parse().unwrap();
        assert!(
            (peak - ti.parse::<f64>().unwrap()).abs() <= 6.0,
            "{ti}: peak at {peak}"
        );
    }
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["curves"].as_array().unwrap().len(), 2);
    assert_eq!(json["curves"][1]["incidence_deg"], 60.0);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
}

#[test]
fn bad_input_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let map = gen_map(dir.path());
    let csv = dir.path().join("x.csv");
    let csv = csv.to_str().unwrap();
    for args in [
        vec!["inplane", &map, "--incidence-deg", "95", "-o", csv],
        vec![
            "inplane",
            &map,
            "--incidence-deg",
            "20",
            "--scatter-deg=5:1:1",
            "-o",
            csv,
        ],
        vec![
            "inplane",
            &map,
            "--incidence-deg",
            "20",
            "--aperture-deg",
            "0",
            "-o",
            csv,
        ],
        vec!["inplane", "--incidence-deg", "20", "-o", csv],
        vec!["inplane", "missing.x3p", "--incidence-deg", "20", "-o", csv],
        vec![
            "inplane",
            &map,
            "--incidence-deg",
            "20",
            "--no-shadowing",
            "--second-bounce",
            "-o",
            csv,
        ],
    ] {
        let out = gonio(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
    }
    assert!(!Path::new(csv).exists());
}

/// `--json` alone prints the curves at the STARR incidences (20/45/60/70°) on standard output and
/// writes no file; with neither `-o` nor `--json` the CSV goes to standard output.
#[test]
fn default_geometry_and_json_without_output() {
    let dir = tempfile::tempdir().unwrap();
    let map = gen_map(dir.path());
    let before = std::fs::read_dir(dir.path()).unwrap().count();
    let out = ok(&["inplane", &map, "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let incidences: Vec<f64> = json["curves"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["incidence_deg"].as_f64().unwrap())
        .collect();
    assert_eq!(incidences, [20.0, 45.0, 60.0, 70.0]);
    assert!(json["output"].is_null());
    assert!(json["warnings"].as_array().unwrap().is_empty());
    let out = ok(&["inplane", &map, "--incidence-deg", "30"]);
    let csv = String::from_utf8(out.stdout).unwrap();
    assert!(csv.starts_with("method,wavelength_nm,incidence_deg,scatter_deg"));
    assert_eq!(csv.lines().count(), 1 + 151);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), before);
}

/// The ray method on a map far smoother than the wavelength (Sq 5 nm: Rayleigh roughness
/// g = (4π · 5 nm · cos 20° / 550 nm)² = 0.01 at 20°) warns on stderr and in the JSON.
#[test]
fn ray_method_on_a_smooth_map_warns() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("smooth.x3p");
    let path = path.to_str().unwrap();
    ok(&[
        "surface",
        "gen",
        "--sq-nm",
        "5",
        "--corr-um",
        "6",
        "--size",
        "64",
        "--dx-um",
        "0.5",
        "--seed",
        "1",
        "-o",
        path,
    ]);
    let out = ok(&["inplane", path, "--incidence-deg", "20", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let warnings = json["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].as_str().unwrap().contains("coherently"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("warning: the map is smooth"), "{stderr}");
}
