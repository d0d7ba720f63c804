//! `gonio brdf` end to end: tabulate a model, summarise, export to every format, import back,
//! fit, and a missing file exits with status 2.

use crate::common::{gonio_in as gonio, ok_in};

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// `brdf plot --measured` draws a measurement beside the table imported from it, and refuses,
    /// with exit status 2 and the reason, a measurement whose channels are not the table's.
    #[test]
    fn plot_beside_the_measurement() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        let astm = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../brdf/tests/data/krylon_blue.astm");
        let astm = astm.to_str().unwrap();
        // A coarse table (the default 90,90,48 takes six times as long): the plot and the
        // channel check do not depend on resolving the specular peak.
        let coarse = ["--resolution", "30,30,16"];
        ok_in(
            &[&["brdf", "import", astm, "-o", "blue.gbrdf"][..], &coarse].concat(),
            d,
        );
        ok_in(
            &[
                "brdf",
                "plot",
                "blue.gbrdf",
                "-o",
                "blue.png",
                "--measured",
                astm,
            ],
            d,
        );
        assert!(std::fs::metadata(d.join("blue.png")).unwrap().len() > 10_000);
        ok_in(
            &[
                "brdf",
                "import",
                astm,
                "-o",
                "rgb.gbrdf",
                "--colour",
                "srgb",
                coarse[0],
                coarse[1],
            ],
            d,
        );
        let out = gonio(
            &[
                "brdf",
                "plot",
                "rgb.gbrdf",
                "-o",
                "rgb.png",
                "--measured",
                astm,
            ],
            d,
        );
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("31 channels") && err.contains("--colour"),
            "{err}"
        );
        assert!(!d.join("rgb.png").exists());
    }

    #[test]
    fn tabulate_info_export_import_fit() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        let model = r#"{"model":"ward","specular":0.05,"alpha":0.1,"diffuse":0.4}"#;
        let out = gonio(
            &[
                "brdf",
                "tabulate",
                "--model",
                model,
                "--resolution",
                "45,32,32",
                "-o",
                "w.gbrdf",
            ],
            d,
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );

        let out = gonio(&["brdf", "info", "w.gbrdf", "--json"], d);
        assert!(out.status.success());
        let info: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        // Lambert 0.4 plus a Ward lobe of rho_s 0.05: albedo at normal incidence about 0.45.
        let a0 = info["albedo"][0]["albedo"][0].as_f64().unwrap();
        assert!((a0 - 0.45).abs() < 0.01, "{a0}");
        assert!(info["reciprocity_error"].as_f64().unwrap() < 1e-6);

        for (format, output) in [
            ("merl", "w.binary"),
            ("mitsuba", "w.bsdf"),
            ("csv", "w.csv"),
            ("pabopto", "pab"),
            ("radiance-xml", "w.xml"),
        ] {
            let out = gonio(
                &[
                    "brdf",
                    "export",
                    "w.gbrdf",
                    "--format",
                    format,
                    "-o",
                    output,
                    "--step-deg",
                    "15",
                ],
                d,
            );
            assert!(
                out.status.success(),
                "{format}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            assert!(d.join(output).exists());
        }
        let out = gonio(&["brdf", "import", "w.binary", "-o", "back.gbrdf"], d);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );

        let out = gonio(
            &[
                "brdf",
                "fit",
                "w.gbrdf",
                "--model",
                "ward",
                "--diffuse",
                "--json",
            ],
            d,
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let fit: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let alpha = fit["parameters"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == "alpha")
            .unwrap()["value"]
            .as_f64()
            .unwrap();
        assert!((alpha - 0.1).abs() < 0.005, "{alpha}");

        let out = gonio(&["brdf", "plot", "w.gbrdf", "-o", "w.png"], d);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );

        let out = gonio(&["brdf", "info", "missing.gbrdf"], d);
        assert_eq!(out.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&out.stderr).contains("missing.gbrdf"));
    }
}

/// `brdf export --format radiance-xml` writes Radiance's XML BSDF: a TensorTree3 for a
/// monochrome isotropic table, a TensorTree4 with CIE u′ v′ for a colour one, of the order
/// `--tree-order` asks; an order the rank cannot take exits with status 2 and says why.
#[test]
fn export_radiance_xml() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let model = r#"{"model":"ward","specular":0.05,"alpha":0.1,"diffuse":0.4}"#;
    let small = ["--resolution", "16,16,16"];
    ok_in(
        &[
            &[
                "brdf", "tabulate", "--model", model, "--mono", "-o", "m.gbrdf",
            ][..],
            &small,
        ]
        .concat(),
        d,
    );
    ok_in(
        &[
            &["brdf", "tabulate", "--model", model, "-o", "c.gbrdf"][..],
            &small,
        ]
        .concat(),
        d,
    );
    let export = |table: &str, order: &str| {
        gonio(
            &[
                "brdf",
                "export",
                table,
                "--format",
                "radiance-xml",
                "-o",
                "t.xml",
                "--tree-order",
                order,
            ],
            d,
        )
    };
    let out = export("m.gbrdf", "4");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("TensorTree3 of order 4"));
    let xml = std::fs::read_to_string(d.join("t.xml")).unwrap();
    assert!(xml.contains("<IncidentDataStructure>TensorTree3</IncidentDataStructure>"));
    assert!(!xml.contains("CIE-u"));
    let out = export("c.gbrdf", "3");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let xml = std::fs::read_to_string(d.join("t.xml")).unwrap();
    assert!(xml.contains("TensorTree4") && xml.contains(">CIE-v</Wavelength>"));
    let out = export("c.gbrdf", "7");
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("order 7") && err.contains("TensorTree4"),
        "{err}"
    );
}
