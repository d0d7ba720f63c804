//! `gonio booth` end to end on a solid coating (`examples/coatings/red_solid.toml`) at a small
//! size: every file is written, the OpenEXR's mean luminance over the specimen is the summary's,
//! the manifest's hashes are the files', a seed gives the same pixels twice, and bad inputs exit
//! with status 2 and a message that names the file and the fix.

use crate::common::{gonio, ok};
use exr::prelude::*;
use serde_json::Value;
use sha2::{Digest, Sha256};
use std::path::Path;

const SOLID: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../examples/coatings/red_solid.toml"
);

/// Render the solid into `dir` at 40 × 28 pixels, 4 samples per pixel, and return the JSON
/// summary.
fn booth(dir: &Path, seed: &str) -> Value {
    let out = ok(&[
        "booth",
        SOLID,
        "-o",
        dir.to_str().unwrap(),
        "--size",
        "40x28",
        "--spp",
        "4",
        "--seed",
        seed,
        "--json",
    ]);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The Y channel of an XYZ OpenEXR.
fn exr_y(path: &Path) -> Vec<f32> {
    let image = read_all_flat_layers_from_file(path).unwrap();
    let layer = &image.layer_data[0];
    let channel = layer
        .channel_data
        .list
        .iter()
        .find(|c| c.name.to_string() == "Y")
        .expect("a Y channel");
    let FlatSamples::F32(y) = &channel.sample_data else {
        panic!("Y is not f32")
    };
    y.clone()
}

fn sha256(path: &Path) -> String {
    let bytes = std::fs::read(path).unwrap();
    Sha256::digest(&bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

#[test]
fn booth_writes_every_file_and_the_summary_reads_them() {
    let dir = tempfile::tempdir().unwrap();
    let summary = booth(dir.path(), "7");
    let views = summary["views"].as_array().unwrap();
    let names: Vec<&str> = views.iter().map(|v| v["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["near-specular", "45", "flank"]);
    for view in views {
        let name = view["name"].as_str().unwrap();
        for suffix in [
            ".exr",
            "-srgb.png",
            "-srgb-mask.png",
            "-p3.png",
            "-p3-mask.png",
            "-specimen.png",
        ] {
            let file = dir.path().join(format!("{name}{suffix}"));
            assert!(file.is_file(), "{} missing", file.display());
        }
        // The mean of the OpenEXR's Y over the specimen's mask is the summary's luminance.
        let y = exr_y(Path::new(view["exr"].as_str().unwrap()));
        let mask = image::open(view["specimen_mask"].as_str().unwrap())
            .unwrap()
            .to_luma8();
        assert_eq!(mask.len(), y.len());
        let inside: Vec<f64> = y
            .iter()
            .zip(mask.as_raw())
            .filter(|(_, m)| **m == 255)
            .map(|(v, _)| f64::from(*v))
            .collect();
        assert_eq!(
            inside.len() as u64,
            view["specimen_pixels"].as_u64().unwrap()
        );
        assert!(!inside.is_empty(), "{name}: the specimen covers no pixel");
        let mean = inside.iter().sum::<f64>() / inside.len() as f64;
        let reported = view["specimen_luminance_cd_m2"].as_f64().unwrap();
        // The same f32 values summed in f64 in the same order: equal to rounding of the sum.
        assert!(
            (mean - reported).abs() <= 1e-12 * reported.abs(),
            "{name}: EXR {mean} against the summary's {reported}"
        );
        assert!(mean > 0.0, "{name}: a black specimen");
        for d in view["displays"].as_array().unwrap() {
            for f in ["out_of_gamut_fraction", "over_range_fraction"] {
                let v = d[f].as_f64().unwrap();
                assert!((0.0..=1.0).contains(&v), "{name} {}: {f} {v}", d["display"]);
            }
        }
    }
    // The manifest: the input's and every output's SHA-256 are the files'.
    let manifest: Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("manifest.json")).unwrap()).unwrap();
    assert_eq!(manifest["seed"], 7);
    let inputs = manifest["inputs"].as_array().unwrap();
    assert_eq!(inputs.len(), 1);
    assert_eq!(inputs[0]["sha256"], sha256(Path::new(SOLID)));
    let outputs = manifest["outputs"].as_array().unwrap();
    assert_eq!(outputs.len(), 3 * 6);
    for o in outputs {
        let file = dir.path().join(o["path"].as_str().unwrap());
        assert_eq!(o["sha256"], sha256(&file), "{}", file.display());
    }
}

#[test]
fn same_seed_gives_the_same_pixels() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    booth(a.path(), "3");
    booth(b.path(), "3");
    for name in ["near-specular", "45", "flank"] {
        let file = format!("{name}.exr");
        let (ya, yb) = (exr_y(&a.path().join(&file)), exr_y(&b.path().join(&file)));
        let bits = |y: &[f32]| y.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&ya), bits(&yb), "{name}: the pixels differ");
    }
}

/// Run `gonio booth` on `args`, expect status 2 and return stderr.
fn fails(args: &[&str]) -> String {
    let out = gonio(args);
    assert_eq!(out.status.code(), Some(2), "gonio {args:?}");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn bad_inputs_exit_2_and_say_how_to_fix_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let missing = dir.path().join("missing.toml");
    let err = fails(&["booth", missing.to_str().unwrap(), "-o", out]);
    assert!(
        err.contains("missing.toml") && err.contains("No such file"),
        "{err}"
    );

    let neither = dir.path().join("neither.toml");
    std::fs::write(&neither, "[paint]\ncolour = \"red\"\n").unwrap();
    let err = fails(&["booth", neither.to_str().unwrap(), "-o", out]);
    assert!(
        err.contains("neither.toml")
            && err.contains("neither a booth spec nor a coating")
            && err.contains("`paint`"),
        "{err}"
    );

    let spec = dir.path().join("booth.toml");
    std::fs::write(&spec, "[light]\nilluminance_lux = 1000\n").unwrap();
    let err = fails(&["booth", spec.to_str().unwrap(), "-o", out]);
    assert!(
        err.contains("booth.toml") && err.contains("[specimen] material = "),
        "{err}"
    );

    let err = fails(&["booth", SOLID, "-o", out, "--size", "0x5"]);
    assert!(err.contains("0x5") && err.contains("1 to 32768"), "{err}");
    assert!(!Path::new(out).exists(), "a failed run wrote {out}");
}

/// A spec that names its material renders it: the material's path is relative to the spec.
#[test]
fn spec_names_its_material() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(SOLID, dir.path().join("red.toml")).unwrap();
    let spec = dir.path().join("booth.toml");
    std::fs::write(
        &spec,
        "[specimen]\nmaterial = \"red.toml\"\n[camera]\nviews = [\"45\"]\n[render]\nwidth = 16\nheight = 12\nspp = 2\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let stdout = ok(&[
        "booth",
        spec.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--json",
    ])
    .stdout;
    let summary: Value = serde_json::from_slice(&stdout).unwrap();
    assert_eq!(summary["views"].as_array().unwrap().len(), 1);
    let manifest: Value =
        serde_json::from_slice(&std::fs::read(out.join("manifest.json")).unwrap()).unwrap();
    let inputs: Vec<&str> = manifest["inputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["path"].as_str().unwrap())
        .collect();
    assert!(
        inputs[0].ends_with("booth.toml") && inputs[1].ends_with("red.toml"),
        "{inputs:?}"
    );
}
