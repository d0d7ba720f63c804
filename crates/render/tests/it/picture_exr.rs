//! The booth's absolute XYZ pictures as OpenEXR: values and header read back by the `exr`
//! crate and by OpenEXR's own library (PyPI `OpenEXR`, the Academy Software Foundation's
//! bindings), an independent reader.

use crate::oracle;
use exr::prelude::*;
use gonio_color::Observer;
use gonio_render::picture::{UNITS_ATTRIBUTE, XyzPicture, write_xyz_exr};

/// A 7 × 5 picture whose values span what a booth picture holds: black, a dark grey of
/// 1e-3 cd/m², a few hundred cd/m² and a specular highlight of 2e5 cd/m², every pixel distinct.
fn values() -> Vec<[f32; 3]> {
    (0..35)
        .map(|i| {
            let t = i as f32;
            match i {
                0 => [0.0; 3],
                1 => [0.95e-3, 1e-3, 1.09e-3],
                2 => [1.9e5, 2e5, 2.2e5],
                _ => [3.1 * t, 2.9 * t + 0.5, 1.7 * t * t],
            }
        })
        .collect()
}

#[test]
fn exr_holds_absolute_xyz_and_its_header_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("view.exr");
    let xyz = values();
    let picture = XyzPicture::new(7, 5, &xyz, Observer::Cie1964TenDegree).unwrap();
    write_xyz_exr(&path, &picture).unwrap();

    let image = read_all_flat_layers_from_file(&path).unwrap();
    let chroma = image.attributes.chromaticities.unwrap();
    assert_eq!(
        (chroma.red, chroma.green, chroma.blue, chroma.white),
        (
            Vec2(1.0, 0.0),
            Vec2(0.0, 1.0),
            Vec2(0.0, 0.0),
            Vec2(1.0 / 3.0, 1.0 / 3.0)
        )
    );
    let layer = &image.layer_data[0];
    assert_eq!(layer.size, Vec2(7, 5));
    assert_eq!(layer.attributes.white_luminance, Some(1.0));
    let Some(AttributeValue::Text(units)) =
        layer.attributes.other.get(&Text::from(UNITS_ATTRIBUTE))
    else {
        panic!("no {UNITS_ATTRIBUTE} attribute")
    };
    let units = units.to_string();
    assert!(
        units.contains("cd/m^2") && units.contains("CIE 1964 10 degree"),
        "{units}"
    );
    let names: Vec<String> = layer
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    assert_eq!(names, ["X", "Y", "Z"]);
    for (k, channel) in layer.channel_data.list.iter().enumerate() {
        let FlatSamples::F32(samples) = &channel.sample_data else {
            panic!("channel {k} is not f32")
        };
        let expected: Vec<f32> = xyz.iter().map(|p| p[k]).collect();
        assert_eq!(
            samples, &expected,
            "channel {k} changed on its way through the file"
        );
    }
}

#[test]
fn bad_pictures_are_refused_with_the_reason() {
    let xyz = values();
    let err = XyzPicture::new(6, 5, &xyz, Observer::Cie1931TwoDegree).unwrap_err();
    assert!(err.to_string().contains("needs 30 values, not 35"), "{err}");
    let err = XyzPicture::new(0, 5, &xyz, Observer::Cie1931TwoDegree).unwrap_err();
    assert!(err.to_string().contains("empty"), "{err}");
    let mut bad = xyz.clone();
    bad[9][1] = f32::NAN;
    let err = XyzPicture::new(7, 5, &bad, Observer::Cie1931TwoDegree).unwrap_err();
    assert!(err.to_string().contains("pixel (2, 1)"), "{err}");
}

/// OpenEXR's own reader (the C++ library through its Python bindings) finds the same values,
/// channels and header: the file is standard OpenEXR, not only what the `exr` crate reads.
#[test]
fn openexr_reads_the_same_values_and_header() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("view.exr");
    let xyz = values();
    let picture = XyzPicture::new(7, 5, &xyz, Observer::Cie1931TwoDegree).unwrap();
    write_xyz_exr(&path, &picture).unwrap();
    let script = r#"
import json, sys, OpenEXR
path = json.load(sys.stdin)["path"]
with OpenEXR.File(path) as f:
    h = f.header()
    ch = f.channels()
    print(json.dumps({
        "chromaticities": [float(v) for v in h["chromaticities"]],
        "whiteLuminance": float(h["whiteLuminance"]),
        "units": h["gonioUnits"],
        "channels": sorted(ch),
        "types": [str(ch[c].pixels.dtype) for c in "XYZ"],
        "shape": list(ch["Y"].pixels.shape),
        "bits": [[int(v) for v in ch[c].pixels.ravel().view("uint32")] for c in "XYZ"],
    }))
"#;
    let Some(out) = oracle::run::<serde_json::Value>(
        script,
        "OpenEXR",
        "OpenEXR",
        &serde_json::json!({ "path": path }),
    ) else {
        return;
    };
    let third = f64::from(1.0f32 / 3.0);
    assert_eq!(
        out["chromaticities"],
        serde_json::json!([1.0, 0.0, 0.0, 1.0, 0.0, 0.0, third, third])
    );
    assert_eq!(out["whiteLuminance"], 1.0);
    assert!(out["units"].as_str().unwrap().contains("CIE 1931 2 degree"));
    assert_eq!(out["channels"], serde_json::json!(["X", "Y", "Z"]));
    assert_eq!(
        out["types"],
        serde_json::json!(["float32", "float32", "float32"])
    );
    assert_eq!(out["shape"], serde_json::json!([5, 7]));
    // Compared bit for bit (the f32 values' bit patterns, which JSON carries exactly).
    for k in 0..3 {
        let expected: Vec<u32> = xyz.iter().map(|p| p[k].to_bits()).collect();
        let got: Vec<u32> = serde_json::from_value(out["bits"][k].clone()).unwrap();
        assert_eq!(got, expected, "channel {k}");
    }
}
