//! In-plane curve files: errors name the line, round trip and layout.

use gonio_instrument::curves::*;
use gonio_scatter::{CurvePoint, InplaneCurve};

/// A bad value is reported on its own line of the file, comment lines counted.
#[test]
fn errors_name_the_line_in_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.csv");
    let text = "# measured 2026-12-01\n# STARR, 1.4 deg\nincidence_deg,scatter_deg,reflectance\n\
                20,-10,0.01\n20,x,0.02\n";
    std::fs::write(&path, text).unwrap();
    let e = read_csv(&path, None).unwrap_err().to_string();
    assert!(e.contains("line 5: scatter_deg 'x'"), "{e}");
}

#[test]
fn round_trip_and_simple_layout() {
    let dir = tempfile::tempdir().unwrap();
    let curve = InplaneCurve {
        method: "ray".into(),
        wavelength_nm: None,
        incidence_deg: 20.0,
        points: vec![
            CurvePoint {
                scatter_deg: -1.0,
                brdf_per_sr: 0.5,
                reflectance: 1e-3,
                rel_uncertainty: Some(0.1),
            },
            CurvePoint {
                scatter_deg: 20.0,
                brdf_per_sr: 20.0,
                reflectance: 0.04,
                rel_uncertainty: None,
            },
            CurvePoint {
                scatter_deg: 70.0,
                brdf_per_sr: 0.0,
                reflectance: 0.0,
                rel_uncertainty: Some(f64::INFINITY),
            },
        ],
    };
    let path = dir.path().join("c.csv");
    write_csv(&path, std::slice::from_ref(&curve)).unwrap();
    let back = read_csv(&path, None).unwrap();
    assert_eq!(back.len(), 1);
    assert_eq!(back[0].method, "ray");
    assert_eq!(back[0].points[1].reflectance, 0.04);
    assert_eq!(back[0].points[0].rel_uncertainty, Some(0.1));
    assert_eq!(back[0].points[2].rel_uncertainty, Some(f64::INFINITY));
    assert_eq!(back[0].points[2].reflectance, 0.0);

    let simple = dir.path().join("m.csv");
    std::fs::write(
        &simple,
        "incidence_deg,scatter_deg,reflectance\n45,40,0.01\n45,45,0.5\n60,60,0.6\n",
    )
    .unwrap();
    let m = read_csv(&simple, Some(1e-3)).unwrap();
    assert_eq!(m.len(), 2);
    assert_eq!(m[0].method, "measured");
    let expect = 0.5 / (1e-3 * 45f64.to_radians().cos());
    assert!((m[0].points[1].brdf_per_sr - expect).abs() < 1e-9);

    let bad = dir.path().join("b.csv");
    std::fs::write(&bad, "incidence_deg,scatter_deg,reflectance\n45,x,0.01\n").unwrap();
    let e = read_csv(&bad, None).unwrap_err().to_string();
    assert!(e.contains("b.csv") && e.contains("line 2"), "{e}");
    // Reflectance must be finite; only the uncertainty may be infinite, and never negative.
    for row in ["45,40,inf,", "45,40,0.01,-1"] {
        std::fs::write(
            &bad,
            format!("incidence_deg,scatter_deg,reflectance,rel_uncertainty\n{row}\n"),
        )
        .unwrap();
        assert!(read_csv(&bad, None).is_err(), "{row}");
    }
}
