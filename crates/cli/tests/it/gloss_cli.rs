//! End-to-end tests of `gonio gloss`: the readings as JSON (gloss, the haze of ASTM E430 A/B and
//! D4039, DOI), the validity warnings, and the refusal of an index that is not positive.

use crate::common::{gonio, ok};

fn gen_map(dir: &std::path::Path, sq_nm: &str) -> String {
    let path = dir.join(format!("sq{sq_nm}.x3p"));
    let path = path.to_str().unwrap().to_string();
    ok(&[
        "surface",
        "gen",
        "--sq-nm",
        sq_nm,
        "--corr-um",
        "6",
        "--size",
        "64",
        "--dx-um",
        "0.5",
        "--seed",
        "2",
        "-o",
        &path,
    ]);
    path
}

/// An index that is not positive exits with status 2 and says why, without output;
/// one below 1 is read with a warning.
#[test]
fn index_not_positive_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let map = gen_map(dir.path(), "300");
    for index in ["--index=-1", "--index=0", "--index=nan"] {
        let out = gonio(&["gloss", &map, index]);
        assert_eq!(out.status.code(), Some(2), "{index}");
        assert!(out.stdout.is_empty(), "{index}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("refractive index"), "{index}: {stderr}");
    }
    let out = ok(&["gloss", &map, "--index=0.8", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let warnings = json["warnings"].as_array().unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().unwrap().contains("below 1")),
        "{warnings:?}"
    );
}

/// The JSON carries every reading and the warnings. A Sq 5 nm map is smooth at every meter
/// geometry (g ≤ 0.01), so the ray method warns that it is smooth; a Sq 800 nm map (g = 2.5
/// even at 85°) is not, but on so small a map its DOI rests on a handful of rays, and the
/// warning about the DOI's uncertainty says so (and the uncertainty is in the JSON). The D4039
/// index is 60° minus 20° gloss by definition; the log haze follows its formula.
#[test]
fn json_readings_and_warnings() {
    let dir = tempfile::tempdir().unwrap();
    for (sq, smooth) in [("5", true), ("800", false)] {
        let map = gen_map(dir.path(), sq);
        let out = ok(&["gloss", &map, "--json"]);
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let get = |k: &str| json[k].as_f64().unwrap_or_else(|| panic!("{k} missing"));
        for key in [
            "gu20",
            "gu60",
            "gu85",
            "haze",
            "haze_wide",
            "haze_20",
            "doi",
            "doi_uncertainty",
        ] {
            assert!(get(key).is_finite(), "{key}");
        }
        assert!((get("haze_d4039") - (get("gu60") - get("gu20"))).abs() < 1e-9);
        let log = 1285.097 * (get("haze_20") / 20.0 + 1.0).log10();
        assert!(
            (get("haze_20_log") - log).abs() < 1e-3 * (1.0 + log),
            "log haze"
        );
        let warnings = json["warnings"].as_array().unwrap();
        let says = |what: &str| warnings.iter().any(|w| w.as_str().unwrap().contains(what));
        assert_eq!(says("the map is smooth"), smooth, "Sq {sq}: {warnings:?}");
        assert_eq!(
            says("is uncertain by"),
            get("doi_uncertainty") > 5.0,
            "Sq {sq}: {warnings:?}"
        );
        assert!(smooth || says("is uncertain by"), "Sq {sq}: {warnings:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            stderr.contains("warning: the map is smooth"),
            smooth,
            "Sq {sq}: {stderr}"
        );
    }
}
