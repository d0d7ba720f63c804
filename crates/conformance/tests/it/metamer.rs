//! The metameric pair against colour-science.

use crate::common::python;
use gonio_color::Illuminant;
use gonio_conformance::metamer::{pair, pair_delta_e, wavelengths_nm, xyz};
use gonio_conformance::suite::SPECTRAL_INTEGRATION_DE;

/// The spectra are reflectances, equal in XYZ under D65 (to rounding) and apart under A.
#[test]
fn the_pair_is_metameric() {
    let p = pair().unwrap();
    assert!(p.first.iter().chain(&p.second).all(|&r| (0.0..=1.0).contains(&r)));
    let (a, b) = (
        xyz(&p.first, Illuminant::D65).unwrap(),
        xyz(&p.second, Illuminant::D65).unwrap(),
    );
    for (u, v) in a.to_array().into_iter().zip(b.to_array()) {
        assert!((u - v).abs() < 1e-12, "{a:?} {b:?}");
    }
    let de_a = pair_delta_e(&p, Illuminant::A).unwrap();
    assert!(pair_delta_e(&p, Illuminant::D65).unwrap() < 1e-9);
    assert!(de_a > 2.0, "ΔE00 under A {de_a}");
}

/// colour-science (0.4) computes the same ΔE00 under D65 and A from the same spectra, with
/// ASTM E308 (its `sd_to_XYZ` default for 10 nm data), within 0.02; integrating the spectra
/// interpolated linearly to 1 nm instead (what a renderer that interpolates between bands
/// does) moves each patch's colour by less than the suite's allowance.
#[test]
fn colour_science_agrees() {
    let p = pair().unwrap();
    let list = |v: &[f64]| format!("{v:?}");
    let code = format!(
        r#"
import colour, json, numpy as np
wl = {wl}
cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
out = {{}}
for name in ["D65", "A"]:
    ill = colour.SDS_ILLUMINANTS[name]
    def lab(values, fine):
        sd = colour.SpectralDistribution(dict(zip(wl, values)))
        white = colour.SpectralDistribution(dict(zip(wl, [1.0] * len(wl))))
        if fine:
            shape = colour.SpectralShape(400, 700, 1)
            sd = sd.copy().interpolate(shape, interpolator=colour.LinearInterpolator)
            white = white.copy().interpolate(shape, interpolator=colour.LinearInterpolator)
            kw = dict(method="Integration")
        else:
            kw = dict(method="ASTM E308")
        x = colour.sd_to_XYZ(sd, cmfs, ill, **kw)
        w = colour.sd_to_XYZ(white, cmfs, ill, **kw)
        return colour.XYZ_to_Lab(x / w[1], colour.XYZ_to_xy(w))
    a, b = lab({first}, False), lab({second}, False)
    fa, fb = lab({first}, True), lab({second}, True)
    out[name] = dict(pair=float(colour.delta_E(a, b, method="CIE 2000")),
                     fine_first=float(colour.delta_E(a, fa, method="CIE 2000")),
                     fine_second=float(colour.delta_E(b, fb, method="CIE 2000")))
print(json.dumps(out))
"#,
        wl = list(&wavelengths_nm()),
        first = list(&p.first),
        second = list(&p.second)
    );
    let Some(out) = python("colour", &code) else {
        return;
    };
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    println!("colour-science: {v}");
    for (name, ill) in [("D65", Illuminant::D65), ("A", Illuminant::A)] {
        let ours = pair_delta_e(&p, ill).unwrap();
        let theirs = v[name]["pair"].as_f64().unwrap();
        assert!((ours - theirs).abs() < 0.02, "{name}: {ours} against {theirs}");
        for k in ["fine_first", "fine_second"] {
            let d = v[name][k].as_f64().unwrap();
            assert!(d < SPECTRAL_INTEGRATION_DE, "{name} {k}: {d}");
        }
    }
}
