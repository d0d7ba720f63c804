//! What a new user meets in the first hour at the command line: negative numbers reach the range
//! checks, `surface convert` takes `-o`, a converted file keeps its source's metadata, errors
//! say their cause once, lengths print in a unit that suits them, and counts agree in number.

use crate::common::{gonio, ok};
use std::path::{Path, PathBuf};

/// The real X3P file of the surface crate's tests (MountainsMap export).
fn real_x3p() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../surface/tests/data/x3p-2.x3p")
}

fn info_json(file: &Path) -> serde_json::Value {
    let out = ok(&["surface", "info", file.to_str().unwrap(), "--json"]);
    serde_json::from_slice(&out.stdout).unwrap()
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A small synthetic map of rms height `sq_nm` at `path`.
fn gen_map(path: &Path, sq_nm: &str) {
    ok(&[
        "surface",
        "gen",
        "--sq-nm",
        sq_nm,
        "--corr-um",
        "20",
        "--size",
        "64",
        "--dx-um",
        "2",
        "-o",
        path.to_str().unwrap(),
    ]);
}

#[test]
fn a_negative_number_reaches_the_range_check() {
    let dir = tempfile::tempdir().unwrap();
    let out = gonio(&[
        "surface",
        "gen",
        "--sq-nm",
        "-5",
        "--corr-um",
        "3",
        "--size",
        "64",
        "--dx-um",
        "0.5",
        "-o",
        dir.path().join("x.x3p").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(!err.contains("unexpected argument"), "{err}");
    assert!(err.contains("--sq-nm"), "{err}");
}

#[test]
fn convert_takes_the_output_positionally_or_with_o() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("s.x3p");
    gen_map(&src, "100");
    let (a, b) = (dir.path().join("a.gsf"), dir.path().join("b.gsf"));
    let s = src.to_str().unwrap();
    ok(&["surface", "convert", s, a.to_str().unwrap()]);
    ok(&["surface", "convert", s, "-o", b.to_str().unwrap()]);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    let both = gonio(&["surface", "convert", s, "c.gsf", "-o", "d.gsf"]);
    assert_eq!(both.status.code(), Some(2), "{}", stderr(&both));
    let neither = gonio(&["surface", "convert", s]);
    assert_eq!(neither.status.code(), Some(2), "{}", stderr(&neither));
}

#[test]
fn convert_keeps_the_source_metadata_and_adds_its_step() {
    let dir = tempfile::tempdir().unwrap();
    let copy = dir.path().join("copy.x3p");
    let src = real_x3p();
    ok(&[
        "surface",
        "convert",
        src.to_str().unwrap(),
        "-o",
        copy.to_str().unwrap(),
    ]);
    let (before, after) = (info_json(&src), info_json(&copy));
    assert!(before["instrument"].is_string(), "{before}");
    assert_eq!(after["instrument"], before["instrument"]);
    assert_eq!(after["date"], before["date"]);
    let meta = |j: &serde_json::Value, key: &str| j["metadata"][key].as_str().map(String::from);
    for key in [
        "creator",
        "calibration date",
        "probing system",
        "instrument version",
    ] {
        assert_eq!(meta(&after, key), meta(&before, key), "{key}");
    }
    let comment = meta(&after, "comment").unwrap_or_default();
    assert!(
        comment.contains("written by gonio") && comment.contains("x3p-2.x3p"),
        "{comment}"
    );
    if let Some(original) = meta(&before, "comment") {
        assert!(comment.starts_with(&original), "{comment}");
    }
}

#[test]
fn an_error_says_its_cause_once() {
    let out = gonio(&["surface", "info", "/no/such/dir/missing.x3p"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("missing.x3p"), "{err}");
    assert_eq!(err.matches("(os error 2)").count(), 1, "{err}");
}

#[test]
fn info_prints_lengths_in_a_unit_that_suits_them_and_the_rms_as_read() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("rough.x3p");
    gen_map(&map, "20000");
    let out = ok(&["surface", "info", map.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    let line = |name: &str| {
        text.lines()
            .find(|l| l.trim_start().starts_with(name))
            .unwrap_or_else(|| panic!("no {name} line in\n{text}"))
            .to_string()
    };
    assert!(line("Sq ").contains("20.00 µm"), "{text}");
    assert!(line("rms ").contains("µm"), "{text}");
    assert!(line("grid").contains("spacing 2.000 µm"), "{text}");
    // Values are right-aligned in one column and the meanings start in the next, so that a
    // person can read them down.
    let columns: Vec<(usize, usize)> = [
        ("rms ", "rms height about"),
        ("Sq ", "rms height"),
        ("Sa ", "mean absolute height"),
        ("Ssk ", "skewness"),
        ("Sdq ", "rms gradient"),
        ("Sal ", "autocorrelation length"),
    ]
    .iter()
    .map(|(name, meaning)| {
        let l = line(name);
        let start = l[..l.find(meaning).unwrap()].chars().count();
        let value_end = l[..l.find(meaning).unwrap()].trim_end().chars().count();
        (value_end, start)
    })
    .collect();
    assert!(
        columns.iter().all(|c| *c == columns[0]),
        "{columns:?}\n{text}"
    );
    let json = info_json(&map);
    let (rms, sq) = (
        json["rms_unlevelled_m"].as_f64().unwrap(),
        json["sq_m"].as_f64().unwrap(),
    );
    assert!(rms >= sq * 0.999, "rms as read {rms} below Sq {sq}");
}

#[test]
fn one_curve_is_a_curve() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("m.x3p");
    gen_map(&map, "100");
    let out = ok(&[
        "inplane",
        map.to_str().unwrap(),
        "--incidence-deg",
        "20",
        "-o",
        dir.path().join("c.csv").to_str().unwrap(),
    ]);
    let err = stderr(&out);
    assert!(err.contains("wrote 1 curve to"), "{err}");
}

#[test]
fn brdf_info_says_what_reciprocity_means() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("w.gbrdf");
    ok(&[
        "brdf",
        "tabulate",
        "--model",
        r#"{"model":"ward","specular":0.05,"alpha":0.1,"diffuse":0.4}"#,
        "--resolution",
        "45,32,32",
        "-o",
        table.to_str().unwrap(),
    ]);
    let out = ok(&["brdf", "info", table.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("swapping light and viewer changes the BRDF by 0.0%")
            && text.contains("0 for a reciprocal (physical) BRDF"),
        "{text}"
    );
}
