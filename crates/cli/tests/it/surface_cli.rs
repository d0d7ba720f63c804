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
    let lib = gonio_surface::waviness::waviness(&map, Direction::X, Quantity::Slope).unwrap();
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

/// `surface gen` with no spectrum flags makes the default orange peel (q^-4, 0.3-10 mm, rms
/// slope along x 1 mrad): the map read back is the library's for the same request (X3P keeps
/// doubles), and `waviness` reads its slope bands and, with `--quantity curvature`, curvature
/// bands in 1/m. A band's curvature over its slope is its waves' 2π/λ, so it lies between
/// 2π/λc and 2π/λs of the band, with a factor 2 of room either way for the Gaussian bands'
/// tails (they pass 0.03 of a wave at λs/2 or 2 λc).
#[test]
fn gen_makes_an_orange_peel_that_waviness_reads() {
    use gonio_surface::synth_psd::{PsdSurface, Spectrum, Target};
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("peel.x3p");
    let p = path.to_str().unwrap();
    let out = ok(&[
        "surface", "gen", "--size", "1024", "--dx-um", "20", "--seed", "2", "-o", p,
    ]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("q^-4 between 0.3 and 10 mm")
            && said.contains("rms slope along x 1.0000 mrad"),
        "{said}"
    );
    let map = gonio_surface::io::read(&path).unwrap();
    let want = PsdSurface {
        spectrum: Spectrum::PowerLaw {
            exponent: 4.0,
            long: 10e-3,
            short: 0.3e-3,
        },
        target: Target::SlopeX(1e-3),
        nx: 1024,
        ny: 1024,
        dx: 20e-6,
        dy: 20e-6,
        seed: 2,
    }
    .generate()
    .unwrap();
    let peak = want.heights().iter().fold(0.0f64, |m, z| m.max(z.abs()));
    assert!(
        map.heights()
            .iter()
            .zip(want.heights())
            .all(|(a, b)| (a - b).abs() <= 1e-12 * peak)
    );
    let bands = |quantity: &str| -> Vec<serde_json::Value> {
        let out = ok(&["surface", "waviness", p, "--quantity", quantity, "--json"]);
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["quantity"].as_str(), Some(quantity));
        v["bands"].as_array().unwrap().clone()
    };
    let (slope, curvature) = (bands("slope"), bands("curvature"));
    for (s, c) in slope.iter().zip(&curvature).take(3) {
        let name = s["name"].as_str().unwrap();
        let sr = s["rms_slope_rad"].as_f64().unwrap();
        let cr = c["rms_curvature_per_m"].as_f64().unwrap();
        assert!(sr > 0.0 && sr < 1e-3, "{name}: {sr}");
        assert!(
            c["value"].is_null() && s["value"].as_f64().is_some(),
            "{name}"
        );
        let (short, long) = (
            s["short_m"].as_f64().unwrap(),
            s["long_m"].as_f64().unwrap(),
        );
        let k = cr / sr;
        assert!(
            k > 2.0 * std::f64::consts::PI / long / 2.0
                && k < 2.0 * std::f64::consts::PI / short * 2.0,
            "{name}: curvature / slope {k} 1/m"
        );
    }
    let text = ok(&["surface", "waviness", p, "--quantity", "curvature"]);
    let text = String::from_utf8(text.stdout).unwrap();
    assert!(
        text.contains("1/m") && !text.contains("gonio's own scale"),
        "{text}"
    );
}

/// A measured PSD table: read from the file and scaled to the requested slope; a table that
/// cannot be read, a missing one, and impossible or contradictory requests exit 2 with a
/// message that says why, and write nothing; `--help` names the units and the defaults.
#[test]
fn gen_from_a_psd_table_and_its_errors() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("psd.csv");
    std::fs::write(
        &table,
        "# measured\nwavelength_mm,psd_m4\n8,1e-17\n2,4e-19\n0.5,1.6e-21\n",
    )
    .unwrap();
    let out_path = dir.path().join("t.gsf");
    let o = out_path.to_str().unwrap();
    let t = table.to_str().unwrap();
    let out = ok(&[
        "surface",
        "gen",
        "--size",
        "512",
        "--dx-um",
        "20",
        "--psd",
        t,
        "--slope-mrad",
        "0.5",
        "-o",
        o,
    ]);
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("rms slope along x 0.5000 mrad"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bad = dir.path().join("bad.csv");
    std::fs::write(&bad, "wavelength_mm,psd_m4\n8,1e-17\n2,oops\n").unwrap();
    let b = bad.to_str().unwrap();
    let missing = dir.path().join("missing.csv");
    let m = missing.to_str().unwrap();
    let never = dir.path().join("never.x3p");
    let n = never.to_str().unwrap();
    let base = ["surface", "gen", "--size", "256", "--dx-um", "20", "-o", n];
    for (extra, says) in [
        (
            vec!["--long-mm", "8"],
            "exceeds the map's shorter side, 5.12 mm",
        ),
        (
            vec!["--long-mm", "5", "--short-mm", "0.03"],
            "under two spacings",
        ),
        (
            vec!["--long-mm", "5", "--short-mm", "6"],
            "below the long one",
        ),
        (vec!["--psd", b], "line 3"),
        (vec!["--psd", m], "missing.csv"),
        (vec!["--psd", t, "--long-mm", "3"], "cannot be used with"),
        (
            vec!["--corr-um", "3", "--slope-mrad", "1"],
            "cannot be used with",
        ),
        (vec!["--acf", "exponential"], "--corr-um"),
    ] {
        let args: Vec<&str> = base.iter().copied().chain(extra.iter().copied()).collect();
        let out = gonio(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(says), "{extra:?}: {err}");
        assert!(!never.exists(), "{extra:?} wrote a file");
    }
    let help = ok(&["surface", "gen", "--help"]);
    let help = String::from_utf8(help.stdout).unwrap();
    for needle in [
        "[default: 4]",
        "[default: 10]",
        "[default: 0.3]",
        "in mrad",
        "psd_m4",
        "micrometres",
        "1 mrad",
    ] {
        assert!(help.contains(needle), "--help lacks {needle:?}");
    }
}
