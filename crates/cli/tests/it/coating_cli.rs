//! `gonio coating info | compute` on the example coatings: the directional-hemispherical
//! reflectance `info` prints equals the closed form for a smooth lossless coat over a diffuse
//! base, computed here from the base reflectance it prints; the table `compute` writes reads,
//! through `gonio multiangle`, the colour `info` prints; a bad description exits with status 2,
//! naming the file and the field.

use crate::common::{gonio_in as gonio, ok_in};
use gonio_brdf::fresnel::dielectric as fresnel;
use std::path::PathBuf;

fn example(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/coatings")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn info_and_compute_agree_with_the_closed_form_and_each_other() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let toml = example("red_solid.toml");
    let out = ok_in(&["coating", "info", &toml, "--json"], d);
    let info: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let n = info["coat_index"]["550"].as_f64().unwrap();
    let rho = info["base_reflectance"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["nm"] == 550.0)
        .unwrap()["reflectance"]
        .as_f64()
        .unwrap();
    // F̄: the internal hemispherical Fresnel average, midpoint rule in θ.
    let steps = 100_000;
    let h = 0.5 * std::f64::consts::PI / steps as f64;
    let f_bar: f64 = (0..steps)
        .map(|k| {
            let t = (k as f64 + 0.5) * h;
            fresnel(t.cos(), 1.0 / n) * 2.0 * t.cos() * t.sin() * h
        })
        .sum();
    for row in info["albedo"].as_array().unwrap() {
        let c = row["theta_i_deg"].as_f64().unwrap().to_radians().cos();
        let f = fresnel(c, n);
        let want = f + (1.0 - f) * rho * (1.0 - f_bar) / (1.0 - rho * f_bar);
        let got = row["albedo"].as_f64().unwrap();
        assert!((got - want).abs() < 1e-6, "{row}: {got} vs {want}");
    }

    ok_in(
        &[
            "coating",
            "compute",
            &toml,
            "-o",
            "red.gbrdf",
            "--resolution",
            "45,45,24",
        ],
        d,
    );
    let out = ok_in(&["multiangle", "red.gbrdf", "--json"], d);
    let table: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for (t, i) in table["geometries"]
        .as_array()
        .unwrap()
        .iter()
        .zip(info["multiangle"].as_array().unwrap())
    {
        assert_eq!(t["name"], i["name"]);
        // The table interpolates a BRDF that depends on θi and θo only: a few hundredths of a
        // CIELAB unit at 45 × 45 × 24.
        for k in ["L", "a", "b"] {
            let (x, y) = (t[k].as_f64().unwrap(), i[k].as_f64().unwrap());
            assert!((x - y).abs() < 0.1, "{}: {k} {x} vs {y}", t["name"]);
        }
    }
    // --colour reduces the spectral table as `brdf import` does, saying so in its provenance.
    ok_in(
        &[
            "coating",
            "compute",
            &toml,
            "-o",
            "red_xyz.gbrdf",
            "--resolution",
            "20,20,8",
            "--colour",
            "xyz",
            "--observer",
            "10",
        ],
        d,
    );
    let out = gonio(&["brdf", "info", "red_xyz.gbrdf", "--json"], d);
    let xyz: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(xyz["channels"]["kind"], "xyz");
    assert_eq!(xyz["provenance"]["colour"]["observer_deg"], 10);
    ok_in(&["coating", "info", &example("red_pigmented.toml")], d);
}

#[test]
fn bad_descriptions_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    std::fs::write(
        d.join("bad.toml"),
        "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 1.3\n",
    )
    .unwrap();
    let out = gonio(&["coating", "compute", "bad.toml", "-o", "t.gbrdf"], d);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml") && err.contains("base reflectance"),
        "{err}"
    );
    assert!(!d.join("t.gbrdf").exists());
    let out = gonio(&["coating", "info", "missing.toml"], d);
    assert_eq!(out.status.code(), Some(2));
}

/// `coating match` on the solid red (Kubelka-Munk red and white under a smooth coat, computed
/// exactly): the target is the red at concentration 0.3 read by `gonio multiangle --spectra`
/// (reflectance factors per E2194 geometry, the CSV layout targets take); from the example's 1.0
/// the match finds 0.3 to 1e-3 (a noiseless target: only the optimiser's tolerance remains),
/// ΔE00 falls from above 2 to under 0.05 at every geometry, and the fitted TOML keeps the
/// example's comments and reads back (`coating info`) to the target's colour; `--objective
/// spectral` finds the same 0.3 to 1e-3 with rms ΔR from above 0.01 to under 1e-3, and the JSON
/// names the objective. Bad inputs exit
/// with status 2 naming what is wrong: an unknown constituent, reversed bounds, a target without
/// the standard's geometries, a missing target, a spectral match of a CIELAB target or with gloss
/// readings, an unknown objective.
#[test]
fn match_recovers_a_concentration_and_writes_the_formulation() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let red = example("red_pigmented.toml");
    let text = std::fs::read_to_string(&red).unwrap();
    std::fs::write(
        d.join("variant.toml"),
        text.replace("concentration = 1.0", "concentration = 0.3"),
    )
    .unwrap();
    ok_in(
        &["multiangle", "variant.toml", "--spectra", "target.csv"],
        d,
    );
    let args = |vary: &str, target: &str, extra: &[&str]| -> Vec<String> {
        let mut a: Vec<String> = [
            "coating",
            "match",
            &red,
            "--target",
            target,
            "--vary",
            vary,
            "-o",
            "fitted.toml",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        a.extend(extra.iter().map(|s| s.to_string()));
        a
    };
    let run = |a: &[String]| {
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        gonio(&a, d)
    };
    let out = run(&args("concentration:red=0.1:2", "target.csv", &["--json"]));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let c = &json["constituents"][0];
    assert!((c["fitted"].as_f64().unwrap() - 0.3).abs() < 1e-3, "{c}");
    assert_eq!(c["start"], 1.0);
    for g in json["geometries"].as_array().unwrap() {
        assert!(g["de00_start"].as_f64().unwrap() > 2.0, "{g}");
        assert!(g["de00_fitted"].as_f64().unwrap() < 0.05, "{g}");
    }
    // The default objective, auto: spectral, the target giving reflectance factors.
    assert_eq!(json["objective"], "spectral");
    let out = run(&args(
        "concentration:red=0.1:2",
        "target.csv",
        &["--json", "--objective", "spectral"],
    ));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let spectral: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(spectral["objective"], "spectral");
    let c = &spectral["constituents"][0];
    assert!((c["fitted"].as_f64().unwrap() - 0.3).abs() < 1e-3, "{c}");
    assert!(spectral["rms_reflectance_start"].as_f64().unwrap() > 0.01);
    assert!(spectral["rms_reflectance_fitted"].as_f64().unwrap() < 1e-3);
    assert!(spectral["mean_de00_fitted"].as_f64().unwrap() < 0.05);
    let fitted = std::fs::read_to_string(d.join("fitted.toml")).unwrap();
    assert!(fitted.contains("# A pigmented red basecoat"), "{fitted}");
    let colour = |file: &str| {
        let out = ok_in(&["coating", "info", file, "--json"], d);
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["multiangle"].clone()
    };
    let (a, b) = (colour("fitted.toml"), colour("variant.toml"));
    for (x, y) in a.as_array().unwrap().iter().zip(b.as_array().unwrap()) {
        for k in ["L", "a", "b"] {
            let (x, y) = (x[k].as_f64().unwrap(), y[k].as_f64().unwrap());
            assert!((x - y).abs() < 0.05, "{k}: {x} against {y}");
        }
    }
    std::fs::write(
        d.join("two.csv"),
        "geometry,L,a,b\n45as15,40,50,30\n45as45,30,40,20\n",
    )
    .unwrap();
    std::fs::write(
        d.join("lab.csv"),
        "geometry,L,a,b\n45as15,40,50,30\n45as25,40,50,30\n45as45,30,40,20\n\
         45as75,30,40,20\n45as110,30,40,20\n",
    )
    .unwrap();
    // --geometry matches the target's own geometries, where the standard's are refused.
    let out = run(&args(
        "concentration:red=0.1:2",
        "two.csv",
        &["--geometry", "45as15,45as45", "--starts", "1", "--json"],
    ));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let names: Vec<&str> = v["geometries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["45as15", "45as45"]);
    for (a, says) in [
        (args("gloss=0:1", "target.csv", &[]), "vary one of"),
        (
            args(
                "concentration:red=0.1:2",
                "lab.csv",
                &["--objective", "spectral"],
            ),
            "gives CIELAB only",
        ),
        (
            args(
                "concentration:red=0.1:2",
                "target.csv",
                &["--objective", "rms"],
            ),
            "de00 (mean CIEDE2000) or spectral",
        ),
        (
            args(
                "concentration:red=0.1:2",
                "target.csv",
                &["--objective", "spectral", "--target-gloss", "60=90"],
            ),
            "gloss readings with the de00 objective",
        ),
        (
            args("concentration:red=2:0.1", "target.csv", &[]),
            "below the upper",
        ),
        (
            args("concentration:red=0.1:2", "two.csv", &[]),
            "no geometry 45as25",
        ),
        (
            args("concentration:red=0.1:2", "missing.csv", &[]),
            "missing.csv",
        ),
        (
            args(
                "concentration:red=0.1:2",
                "target.csv",
                &["--standard", "e2539"],
            ),
            "no geometry 45as-15",
        ),
        (
            args(
                "concentration:red=0.1:2",
                "two.csv",
                &["--geometry", "45as15,45as45,15as15"],
            ),
            "no geometry 15as15",
        ),
        (
            args(
                "concentration:red=0.1:2",
                "two.csv",
                &["--geometry", "45as15,45as500"],
            ),
            "45as500",
        ),
    ] {
        let out = run(&a);
        assert_eq!(out.status.code(), Some(2), "{a:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{a:?}: {err}");
    }
}

/// `--select`: a green made of two library pigments in a white basecoat (its reflectance
/// factors written by `gonio multiangle --spectra`) is matched from the white alone, selecting
/// up to 2 of 4 candidates: the 4 + 6 combinations screened and listed, 2 finalists with ΔE00
/// per geometry, the true pigments chosen, and the fitted TOML (the pigments as library
/// entries) reading as the green within 0.05 in L*, a*, b* (the fit of the target without
/// noise: exact but for the search's tolerance). Bad selections exit 2 naming what is wrong.
#[test]
fn match_selects_library_pigments() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let white = "# white\n[coat]\nindex = 1.5\nthickness_um = 40\n\n[base]\nkind = \"kubelka-munk\"\nthickness_um = 30\nsubstrate = 0.6\n\n[[base.pigment]]\nlibrary = \"titanium_white\"\nconcentration = 1.0\n";
    std::fs::write(d.join("white.toml"), white).unwrap();
    std::fs::write(
        d.join("green.toml"),
        format!(
            "{white}\n[[base.pigment]]\nlibrary = \"phthalo_blue_green_shade\"\nconcentration = 0.04\n\n[[base.pigment]]\nlibrary = \"hansa_yellow_opaque\"\nconcentration = 0.15\n"
        ),
    )
    .unwrap();
    ok_in(&["multiangle", "green.toml", "--spectra", "green.csv"], d);
    let select = |extra: &[&str]| {
        let mut a = vec![
            "coating",
            "match",
            "white.toml",
            "--target",
            "green.csv",
            "-o",
            "fitted.toml",
        ];
        a.extend(extra);
        gonio(&a, d)
    };
    let out = select(&[
        "--select",
        "2",
        "--from",
        "pyrrole_red,hansa_yellow_opaque,phthalo_blue_green_shade,bone_black",
        "--finalists",
        "2",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let sel = &json["selection"];
    assert_eq!(sel["combinations"], 10);
    assert_eq!(sel["tried"].as_array().unwrap().len(), 10);
    let finalists = sel["finalists"].as_array().unwrap();
    assert_eq!(finalists.len(), 2);
    for f in finalists {
        assert_eq!(f["de00"].as_array().unwrap().len(), 5, "{f}");
    }
    let mut chosen: Vec<&str> = sel["pigments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_str().unwrap())
        .collect();
    chosen.sort();
    assert_eq!(chosen, ["hansa_yellow_opaque", "phthalo_blue_green_shade"]);
    assert_eq!(json["objective"], "spectral");
    assert!(json["mean_de00_fitted"].as_f64().unwrap() < 0.05, "{json}");
    let fitted = std::fs::read_to_string(d.join("fitted.toml")).unwrap();
    assert!(
        fitted.contains("library = \"hansa_yellow_opaque\""),
        "{fitted}"
    );
    assert!(fitted.starts_with("# white"), "{fitted}");
    let colour = |file: &str| {
        let out = ok_in(&["coating", "info", file, "--json"], d);
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["multiangle"].clone()
    };
    let (a, b) = (colour("fitted.toml"), colour("green.toml"));
    for (x, y) in a.as_array().unwrap().iter().zip(b.as_array().unwrap()) {
        for k in ["L", "a", "b"] {
            let (x, y) = (x[k].as_f64().unwrap(), y[k].as_f64().unwrap());
            assert!((x - y).abs() < 0.05, "{k}: {x} against {y}");
        }
    }
    // The text report names the screen, the finalists and the choice.
    let out = select(&["--select", "1", "--from", "pyrrole_red,bone_black"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("2 combinations of up to 1 of 2 pigments screened")
            && text.contains("finalists")
            && text.contains("chosen:"),
        "{text}"
    );
    std::fs::write(
        d.join("diffuse.toml"),
        "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.5\n",
    )
    .unwrap();
    for (a, says) in [
        (vec!["--select", "0"], "select at least 1 pigment"),
        (
            vec!["--select", "2", "--from", "pyrrole_red,phthalo_blu"],
            "'phthalo_blu' is not a pigment of gonio's library",
        ),
        (
            vec!["--select", "2", "--finalists", "0"],
            "at least 1 finalist",
        ),
        (vec!["--from", "pyrrole_red"], "--select"),
    ] {
        let out = select(&a);
        assert_eq!(out.status.code(), Some(2), "{a:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{a:?}: {err}");
    }
    let out = gonio(
        &[
            "coating",
            "match",
            "diffuse.toml",
            "--target",
            "green.csv",
            "--select",
            "2",
            "-o",
            "f.toml",
        ],
        d,
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("diffuse.toml") && err.contains("kind = \"kubelka-munk\""),
        "{err}"
    );
}

mod slow {
    use super::*;

    /// A layered system through the commands: `gonio multiangle` on the silver metallic's TOML
    /// (its BRDF evaluated by random walks at the geometries) agrees with `gonio coating info`'s
    /// colour (the same estimator, fewer walks: within 1 L* unit at 4096 walks, where the walks'
    /// spread is about 0.3), shows the lightness flop of a metallic (L* falls from 45as15 to
    /// 45as110; flop index above 5), and the table `compute` writes reads as the same coating near
    /// the specular direction within its noise and interpolation (a small 30 × 30 × 16 table, 16
    /// walks per cell: within 5 L* units at 45as15 and 45as25).
    #[test]
    fn layered_coating_through_the_commands() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        let toml = example("silver_metallic.toml");
        let json = |args: &[&str]| -> serde_json::Value {
            let out = ok_in(args, d);
            serde_json::from_slice(&out.stdout).unwrap()
        };
        let direct = json(&["multiangle", &toml, "--json"]);
        let info = json(&["coating", "info", &toml, "--json", "--samples", "4096"]);
        let l = |v: &serde_json::Value, key: &str, i: usize| v[key][i]["L"].as_f64().unwrap();
        for i in 0..5 {
            let (a, b) = (l(&direct, "geometries", i), l(&info, "multiangle", i));
            assert!((a - b).abs() < 1.0, "geometry {i}: {a} vs {b}");
        }
        assert!(l(&direct, "geometries", 0) > l(&direct, "geometries", 4) + 50.0);
        assert!(direct["flop_index"].as_f64().unwrap() > 5.0);
        // A rough top's reflection is in the BRDF: no mirror reflectance.
        assert_eq!(info["specular"][0]["reflectance"].as_f64().unwrap(), 0.0);

        let table = d.join("silver.gbrdf");
        let out = ok_in(
            &[
                "coating",
                "compute",
                &toml,
                "-o",
                table.to_str().unwrap(),
                "--resolution",
                "30,30,16",
                "--samples",
                "16",
            ],
            d,
        );
        assert!(String::from_utf8_lossy(&out.stderr).contains("16 random walks per cell"));
        let from_table = json(&["multiangle", table.to_str().unwrap(), "--json"]);
        for i in 0..2 {
            let (a, b) = (l(&from_table, "geometries", i), l(&direct, "geometries", i));
            assert!((a - b).abs() < 5.0, "geometry {i}: table {a} vs direct {b}");
        }
    }
}

/// `coating sensitivity` on the red under a rough coat, varying the top's roughness and the
/// coat's thickness (the coat is clear, so its thickness changes nothing the instruments read):
/// the JSON gives each output's indices per input, thickness's μ* is exactly 0 (the same
/// readings, common random numbers), roughness's is not; the folder holds the CSV, the summary
/// and a bar chart per output; a bad bound exits with status 2 saying how to write it.
#[test]
fn sensitivity_finds_what_matters_and_writes_its_files() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let toml = example("red_rough.toml");
    let args = [
        "coating",
        "sensitivity",
        &toml,
        "--vary",
        "roughness=0.05:0.2,thickness",
        "--bounds",
        "thickness=20:60",
        "--outputs",
        "gu60,L@45as15",
        "--method",
        "morris",
        "--samples",
        "3",
        "--walks",
        "16",
        "-o",
        "out",
        "--json",
    ];
    let out = ok_in(&args, d);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["readings"], 9);
    assert_eq!(json["inputs"][1]["lo"], 20.0);
    for o in json["outputs"].as_array().unwrap() {
        let mu_star = &o["indices"]["mu_star"];
        assert_eq!(mu_star["thickness"], 0.0, "{o}");
        assert!(mu_star["roughness"].as_f64().unwrap() > 0.1, "{o}");
    }
    assert!(
        json["summary"]
            .as_str()
            .unwrap()
            .contains("driven by roughness")
    );
    for f in [
        "sensitivity.csv",
        "summary.txt",
        "sensitivity-gu60.png",
        "sensitivity-L_45as15.png",
    ] {
        assert!(d.join("out").join(f).is_file(), "{f}");
    }
    let csv = std::fs::read_to_string(d.join("out/sensitivity.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 2, "{csv}");
    let bad = gonio(
        &["coating", "sensitivity", &toml, "--vary", "roughness=0.05"],
        d,
    );
    assert_eq!(bad.status.code(), Some(2));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("NAME=LO:HI"), "{err}");
}
