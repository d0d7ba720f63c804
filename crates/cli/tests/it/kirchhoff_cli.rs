//! End-to-end tests of `gonio inplane --method kirchhoff` and `--model ...` through the real
//! binary: the CSV they write, the agreement of the two on a smooth surface, and the errors.

use crate::common::{gonio, ok};

/// Rows `(method, wavelength_nm, incidence_deg, scatter_deg, reflectance)` of a CSV.
fn rows(path: &std::path::Path) -> Vec<(String, String, f64, f64, f64)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert!(
        lines
            .next()
            .unwrap()
            .starts_with("method,wavelength_nm,incidence_deg,scatter_deg,brdf_per_sr,reflectance")
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (
                f[0].to_string(),
                f[1].to_string(),
                f[2].parse().unwrap(),
                f[3].parse().unwrap(),
                f[5].parse().unwrap(),
            )
        })
        .collect()
}

/// A smooth surface (Sq = 3 nm): Kirchhoff and the Beckmann model written side by side, labelled
/// with the wavelengths as given; the specular detectors of both read R e^(-g) within 2%.
#[test]
fn kirchhoff_and_model_in_one_file() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("smooth.x3p");
    let m = map.to_str().unwrap();
    ok(&[
        "surface",
        "gen",
        "--sq-nm",
        "3",
        "--corr-um",
        "5",
        "--size",
        "129",
        "--dx-um",
        "1",
        "--seed",
        "4",
        "-o",
        m,
    ]);
    let csv = dir.path().join("out.csv");
    ok(&[
        "inplane",
        m,
        "--method",
        "kirchhoff",
        "--model",
        "beckmann",
        "--sq-nm",
        "3",
        "--corr-um",
        "5",
        "--wavelength-nm",
        "500,600",
        "--incidence-deg",
        "20,60",
        "--scatter-deg=-10:70:10",
        "-o",
        csv.to_str().unwrap(),
    ]);
    let rows = rows(&csv);
    assert_eq!(rows.len(), 2 * 2 * 2 * 9);
    for method in ["kirchhoff", "beckmann"] {
        for w in ["500", "600"] {
            for ti in [20.0, 60.0] {
                let spec: Vec<_> = rows
                    .iter()
                    .filter(|r| r.0 == method && r.1 == w && r.2 == ti && r.3 == ti)
                    .collect();
                assert_eq!(spec.len(), 1, "{method} {w} {ti}");
            }
        }
    }
    for w in ["500", "600"] {
        for ti in [20.0, 60.0] {
            let read = |method: &str| {
                rows.iter()
                    .find(|r| r.0 == method && r.1 == w && r.2 == ti && r.3 == ti)
                    .unwrap()
                    .4
            };
            let (k, b) = (read("kirchhoff"), read("beckmann"));
            assert!((k / b - 1.0).abs() < 0.02, "{w} nm {ti}°: {k} vs {b}");
        }
    }
}

#[test]
fn models_without_surface_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("m.csv");
    let c = csv.to_str().unwrap();
    ok(&[
        "inplane",
        "--model",
        "beckmann,microfacet,smooth",
        "--sq-nm",
        "50",
        "--corr-um",
        "3",
        "--wavelength-nm",
        "550",
        "--incidence-deg",
        "45",
        "--scatter-deg=0:60:20",
        "-o",
        c,
    ]);
    let rows = rows(&csv);
    assert_eq!(rows.len(), 3 * 4);
    assert!(rows.iter().any(|r| r.0 == "microfacet" && r.1.is_empty()));
    assert!(rows.iter().all(|r| r.0 == "microfacet" || r.1 == "550"));
    for bad in [
        vec![
            "inplane",
            "--model",
            "beckmann",
            "--sq-nm",
            "5",
            "--corr-um",
            "1",
            "--incidence-deg",
            "20",
            "-o",
            c,
        ],
        vec![
            "inplane",
            "--model",
            "beckmann",
            "--wavelength-nm",
            "550",
            "--incidence-deg",
            "20",
            "-o",
            c,
        ],
        vec![
            "inplane",
            "missing.x3p",
            "--method",
            "kirchhoff",
            "--incidence-deg",
            "20",
            "-o",
            c,
        ],
    ] {
        let out = gonio(&bad);
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
        assert!(!String::from_utf8_lossy(&out.stderr).is_empty());
    }
}
