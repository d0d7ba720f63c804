//! `gonio pigments` end to end: the list, one pigment as text and JSON (its colours are the
//! library's, through gonio's colorimetry), the PNGs it writes (the swatches are filled with the
//! colours it prints), and an unknown name (exit 2, the closest name and the library).

use crate::common::{gonio, ok};
use gonio_coating::pigment_library::{self as library, find};
use gonio_color::{Colorimetry, Illuminant, Observer};

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_slice(&ok(args).stdout).unwrap()
}

#[test]
fn the_list_names_all_nineteen_pigments() {
    let text = String::from_utf8(ok(&["pigments"]).stdout).unwrap();
    for p in library::pigments() {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("{} ", p.name)))
            .unwrap_or_else(|| panic!("{} missing:\n{text}", p.name));
        assert!(
            line.contains(&p.colour_index) && line.contains('#'),
            "{line}"
        );
    }
    let v = json(&["pigments", "--json"]);
    let list = v["pigments"].as_array().unwrap();
    assert_eq!(list.len(), 19);
    assert_eq!(v["library"]["scale_per_um"], library::SCALE_PER_UM);
    assert_eq!(v["library"]["observer_deg"], 10);
    let black = list.iter().find(|p| p["name"] == "bone_black").unwrap();
    assert_eq!(black["colour_index"], "PBk9");
    // The shared README's check value of bone black's masstone (inside, D65, 10°): 23.0, 0.0,
    // −1.9 (within 0.1: rounding and the 1 nm interpolation, see the coating tests).
    let lab = &black["masstone"]["inside"]["cielab"];
    for (key, want) in [("l_star", 23.0), ("a_star", 0.0), ("b_star", -1.9)] {
        assert!((lab[key].as_f64().unwrap() - want).abs() < 0.1, "{lab}");
    }
}

/// One pigment: its JSON carries the library's relative K and S, and masstone and tint colours
/// equal to gonio's colorimetry of the library's R∞ (to the JSON's round trip) under the chosen
/// illuminant and observer; the swatches PNG is filled with the printed sRGB, and the K/S plot
/// is written.
#[test]
fn one_pigment_as_json_with_its_pictures() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let v = json(&[
        "pigments",
        "pyrrole_red",
        "-o",
        out,
        "--json",
        "--illuminant",
        "A",
        "--observer",
        "2",
    ]);
    let p = find("pyrrole_red").unwrap();
    assert_eq!(v["colour_index"], "PR254");
    let k: Vec<f64> = serde_json::from_value(v["k_relative"].clone()).unwrap();
    assert_eq!(k, p.k.values());
    assert_eq!(v["tint"]["parts_white_per_part"], 10.0);
    let check = |seen: &serde_json::Value, r: &gonio_color::Spectrum| {
        let c = Colorimetry::of_reflectance(r, Illuminant::A, Observer::Cie1931TwoDegree);
        let lab = &seen["cielab"];
        for (key, want) in [
            ("l_star", c.lab.l),
            ("a_star", c.lab.a),
            ("b_star", c.lab.b),
        ] {
            assert!((lab[key].as_f64().unwrap() - want).abs() < 1e-12, "{lab}");
        }
        assert_eq!(seen["srgb_hex"], c.srgb.to_hex());
        c.srgb.to_u8()
    };
    let mass = p.masstone().unwrap();
    let tint = p.tint().unwrap();
    let mass_seen = check(
        &v["masstone"]["through_surface"],
        &library::as_measured(&mass),
    );
    check(&v["masstone"]["inside"], &mass);
    let tint_seen = check(
        &v["tint"]["colour"]["through_surface"],
        &library::as_measured(&tint),
    );
    check(&v["tint"]["colour"]["inside"], &tint);
    let swatches = image::open(dir.path().join("pyrrole_red_swatches.png"))
        .unwrap()
        .to_rgb8();
    // The middle of the top-left swatch (masstone through the surface) and of the top-right
    // (tint through the surface): see the layout in src/pigments.rs.
    assert_eq!(swatches.get_pixel(280, 180).0, mass_seen);
    assert_eq!(swatches.get_pixel(520, 180).0, tint_seen);
    let plot = image::open(dir.path().join("pyrrole_red_ks.png")).unwrap();
    assert_eq!((plot.width(), plot.height()), (900, 560));
    assert_eq!(v["files"].as_array().unwrap().len(), 2);
}

#[test]
fn one_pigment_as_text() {
    let text = String::from_utf8(ok(&["pigments", "titanium_white"]).stdout).unwrap();
    assert!(text.starts_with("titanium_white (PW6)"), "{text}");
    for row in [
        "masstone, through the surface",
        "masstone, inside (R∞)",
        "tint 1:10 with titanium_white, through surface",
    ] {
        assert!(text.contains(row), "{row}: {text}");
    }
}

/// An unknown name exits 2 with the closest name and the library; -o without a name is refused.
#[test]
fn an_unknown_pigment_exits_2_with_a_suggestion() {
    let out = gonio(&["pigments", "quinacridone"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("did you mean 'quinacridone_"), "{err}");
    assert!(
        err.contains("titanium_white") && err.contains("bone_black"),
        "{err}"
    );
    let out = gonio(&["pigments", "-o", "somewhere"]);
    assert_eq!(out.status.code(), Some(2));
}
