//! `gonio conformance`: its errors, and a run on gonio's renderer alone (the suite's checks are
//! gonio-conformance's tests).

use crate::common::gonio;

/// An unknown renderer and a bad sample count are errors (status 2) naming what is wrong.
#[test]
fn bad_arguments_are_named() {
    let out = gonio(&["conformance", "--renderers", "gonio,blender"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("unknown renderer `blender`"), "{err}");
    let out = gonio(&["conformance", "--spp", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--spp"));
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use crate::common::ok_in;

    /// gonio alone at 16 samples per pixel: every scene passes (status 0), the table names every
    /// scene, and the report, its pictures and the JSON are written.
    #[test]
    fn gonio_alone_passes_and_writes_the_report() {
        let dir = tempfile::tempdir().unwrap();
        let out = ok_in(
            &[
                "conformance",
                "--renderers",
                "gonio",
                "--spp",
                "16",
                "-o",
                "c",
            ],
            dir.path(),
        );
        let text = String::from_utf8_lossy(&out.stdout);
        for scene in ["white_furnace", "coat", "mirror", "metamer_a"] {
            assert!(text.contains(scene), "{text}");
        }
        assert!(!text.contains("FAIL"), "{text}");
        let c = dir.path().join("c");
        for f in [
            "report.html",
            "results.json",
            "coat_gonio.png",
            "coat_gonio_flip.png",
        ] {
            assert!(c.join(f).exists(), "{f}");
        }
    }
}
