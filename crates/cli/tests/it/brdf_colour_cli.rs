//! `gonio brdf import --colour`: the Cornell Cayman file (Cornell University Program of Computer
//! Graphics reflectance data) imported to an XYZ table under illuminant A and to a linear-sRGB
//! table; an unknown colour space or illuminant exits with status 2 and says what to use.

use crate::common::gonio_in as gonio;
use std::path::PathBuf;

fn cayman() -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../brdf/tests/data/cayman.astm");
    p.display().to_string()
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn spectral_import_reduces_to_colour() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        let src = cayman();
        for (space, kind) in [("xyz", "xyz"), ("srgb", "rgb")] {
            let out = gonio(
                &[
                    "brdf",
                    "import",
                    &src,
                    "--colour",
                    space,
                    "--illuminant",
                    "A",
                    "--observer",
                    "10",
                    "--resolution",
                    "16,16,16",
                    "-o",
                    "c.gbrdf",
                    "--json",
                ],
                d,
            );
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            assert_eq!(json["channels"]["kind"], kind, "{json}");
            let out = gonio(&["brdf", "info", "c.gbrdf", "--json"], d);
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(
                out.status.success() && text.contains("\"illuminant\": \"A\""),
                "{text}"
            );
        }
        for bad in [
            &["--colour", "lab"][..],
            &["--colour", "xyz", "--illuminant", "F2"],
        ] {
            let mut args = vec!["brdf", "import", &src, "-o", "x.gbrdf"];
            args.extend(bad);
            let out = gonio(&args, d);
            assert_eq!(out.status.code(), Some(2));
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(
                err.contains("xyz or srgb") || err.contains("D65 or A"),
                "{err}"
            );
            assert!(!d.join("x.gbrdf").exists());
        }
    }
}
