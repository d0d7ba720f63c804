//! End-to-end tests of `gonio surface ...`: synthesise, inspect, edit and plot height maps
//! through the real binary.

use crate::common::{gonio, ok};
use gonio_surface::waviness::{Direction, Quantity};
use std::path::Path;

fn info_json(file: &Path) -> serde_json::Value {
    let out = ok(&["surface", "info", file.to_str().unwrap(), "--json"]);
    serde_json::from_slice(&out.stdout).expect("info --json prints one JSON object")
}

fn gen_map(dir: &Path, name: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    ok(&[
        "surface",
        "gen",
        "--sq-nm",
        "150",
        "--corr-um",
        "3",
        "--size",
        "256",
        "--dx-um",
        "0.375",
        "--seed",
        "5",
        "-o",
        path.to_str().unwrap(),
    ]);
    path
}

/// gen → info --json: Sq is the request (0.1%), Sdq is near 2 Sq/T (5%: 8 points per T, whose
/// finite-difference bias is 0.4%, plus one realisation's spread), and every documented key is
/// there.
#[test]
fn generated_surface_reports_the_requested_statistics() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["x3p", "gsf"] {
        let path = gen_map(dir.path(), &format!("g.{ext}"));
        let j = info_json(&path);
        for key in [
            "nx",
            "ny",
            "dx_m",
            "dy_m",
            "valid_fraction",
            "sq_m",
            "sa_m",
            "ssk",
            "sku",
            "sdq",
            "sal_m",
            "str",
        ] {
            assert!(j.get(key).is_some(), "{ext}: key {key} missing in {j}");
        }
        assert_eq!((j["nx"].as_u64(), j["ny"].as_u64()), (Some(256), Some(256)));
        let dx = j["dx_m"].as_f64().unwrap();
        assert!((dx / 0.375e-6 - 1.0).abs() < 1e-6, "{ext}: dx {dx}");
        let sq = j["sq_m"].as_f64().unwrap();
        // X3P and GSF store float heights; GSF's float32 rounds at 1e-7 relative.
        assert!((sq / 150e-9 - 1.0).abs() < 1e-3, "{ext}: Sq {sq}");
        let sdq = j["sdq"].as_f64().unwrap();
        assert!(
            (sdq / (2.0 * 150e-9 / 3e-6) - 1.0).abs() < 0.05,
            "{ext}: Sdq {sdq}"
        );
        assert_eq!(j["valid_fraction"].as_f64(), Some(1.0));
        // An isotropic random surface decays in every direction: Str is a value, not a bound.
        assert_eq!(j["str_upper_bound"].as_bool(), Some(false), "{ext}: {j}");
    }
}

/// convert, level, crop and rotate each write a readable map with the expected grid.
#[test]
fn editing_commands_write_new_files() {
    let dir = tempfile::tempdir().unwrap();
    let src = gen_map(dir.path(), "src.x3p");
    let s = src.to_str().unwrap();
    let p = |n: &str| dir.path().join(n).to_str().unwrap().to_string();

    ok(&["surface", "convert", s, &p("c.gsf")]);
    let converted = info_json(Path::new(&p("c.gsf")));
    assert_eq!(converted["nx"].as_u64(), Some(256));

    ok(&["surface", "level", s, "-o", &p("l.x3p")]);
    let levelled = info_json(Path::new(&p("l.x3p")));
    let original = info_json(&src);
    let rel = levelled["sq_m"].as_f64().unwrap() / original["sq_m"].as_f64().unwrap() - 1.0;
    assert!(
        rel.abs() < 1e-9,
        "levelling a levelled Sq changes nothing: {rel}"
    );

    ok(&[
        "surface",
        "crop",
        s,
        "--x-px",
        "10",
        "--width-px",
        "100",
        "--height-px",
        "50",
        "-o",
        &p("k.x3p"),
    ]);
    let cropped = info_json(Path::new(&p("k.x3p")));
    assert_eq!(
        (cropped["nx"].as_u64(), cropped["ny"].as_u64()),
        (Some(100), Some(50))
    );
    // 30 µm at 0.375 µm is 80 points.
    ok(&[
        "surface",
        "crop",
        s,
        "--width-um",
        "30",
        "--height-um",
        "30",
        "-o",
        &p("u.gsf"),
    ]);
    assert_eq!(info_json(Path::new(&p("u.gsf")))["nx"].as_u64(), Some(80));

    ok(&[
        "surface",
        "rotate",
        s,
        "--angle-deg",
        "-30",
        "-o",
        &p("r.x3p"),
    ]);
    let rotated = info_json(Path::new(&p("r.x3p")));
    let valid = rotated["valid_fraction"].as_f64().unwrap();
    // A square turned by 30° keeps its inscribed disc and loses most of its corners:
    // between π/4 (the disc) and 1.
    assert!(
        valid > std::f64::consts::FRAC_PI_4 && valid < 0.95,
        "{valid}"
    );

    let out = gonio(&["surface", "crop", s, "--x-px", "300", "-o", &p("bad.x3p")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!Path::new(&p("bad.x3p")).exists(), "no output on failure");
}

#[test]
fn plot_writes_a_png() {
    let dir = tempfile::tempdir().unwrap();
    let src = gen_map(dir.path(), "p.gsf");
    let png = dir.path().join("p.png");
    ok(&[
        "surface",
        "plot",
        src.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert!(
        bytes.len() > 10_000,
        "a false-colour image is not tiny: {} bytes",
        bytes.len()
    );
}

/// A corrupt file exits with status 2 and a message that names it; so does a missing one.
#[test]
fn corrupt_input_exits_2_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let src = gen_map(dir.path(), "t.gsf");
    let bytes = std::fs::read(&src).unwrap();
    let bad = dir.path().join("truncated.gsf");
    std::fs::write(&bad, &bytes[..bytes.len() / 2]).unwrap();
    for path in [bad, dir.path().join("missing.x3p")] {
        let out = gonio(&["surface", "info", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{}", path.display());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(path.file_name().unwrap().to_str().unwrap()),
            "{err}"
        );
    }
    let out = gonio(&[
        "surface",
        "gen",
        "--sq-nm",
        "-1",
        "--corr-um",
        "3",
        "--size",
        "64",
        "--dx-um",
        "0.5",
        "-o",
        "x.x3p",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

/// `surface waviness`: the FRT profilometer's 12 mm map gives its short bands in mrad (JSON equal
/// to the library's) and says the long ones are too long for it; a line profile is read too; a
/// missing file exits 2 naming it.
#[test]
fn waviness_reads_the_bands_a_file_resolves() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../surface/tests/data");
    let frt = data.join("frt-1.frt");
    let out = ok(&["surface", "waviness", frt.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let bands = v["bands"].as_array().unwrap();
    let names: Vec<&str> = bands.iter().map(|b| b["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["Wa", "Wb", "Wc", "Wd", "We", "SW", "LW"]);
    let map = gonio_surface::io::read(&frt).unwrap();
    let lib =
        gonio_surface::waviness::waviness(&map, Direction::X, Quantity::Slope).unwrap();
    for (b, r) in bands.iter().zip(&lib) {
        match (b["rms_slope_rad"].as_f64(), r.rms) {
            // JSON's shortest decimal form reads back within an ulp or two.
            (Some(j), Some(l)) => {
                assert!((j - l).abs() <= 1e-15 * l, "{}: {j} vs {l}", r.band.name)
            }
            (j, l) => assert_eq!(j, l, "{}", r.band.name),
        }
    }
    assert!(
        bands[3]["unresolved"]
            .as_str()
            .unwrap()
            .contains("too short")
    );
    let text = ok(&["surface", "waviness", frt.to_str().unwrap()]);
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(
        text.contains("Wa") && text.contains("mrad") && text.contains("gonio's own scale"),
        "{text}"
    );
    let profile = data.join("opdx-3.opdx");
    let out = gonio(&["surface", "waviness", profile.to_str().unwrap(), "--json"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = gonio(&["surface", "waviness", "missing.sdf"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("missing.sdf"));
}
