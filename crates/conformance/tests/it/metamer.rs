//! The metameric pair against colour-science.

use crate::common::python;
use gonio_color::Illuminant;
use gonio_conformance::compare::delta_e;
use gonio_conformance::metamer::{lab, pair, pair_delta_e, wavelengths_nm, xyz};
use gonio_conformance::suite::SPECTRAL_INTEGRATION_DE;

/// The spectra are reflectances, equal in XYZ under D65 (to rounding) and apart under A.
#[test]
fn the_pair_is_metameric() {
    let p = pair().unwrap();
    assert!(
        p.first
            .iter()
            .chain(&p.second)
            .all(|&r| (0.0..=1.0).contains(&r))
    );
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

/// colour-science (0.4) computes the same colours from the same spectra: integrated at 1 nm
/// with the spectra interpolated linearly between their bands (gonio_color's rule, and what a
/// renderer that interpolates between bands integrates), each patch's CIELAB within 0.02 ΔE00
/// of ours and the pair's ΔE00 within 0.02 under D65 and A. With ASTM E308's 10 nm weights
/// (colour-science's default for 10 nm data, another integration rule) each patch moves by
/// less than the suite's allowance for the integration rule (`SPECTRAL_INTEGRATION_DE`).
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
    out[name] = dict(pair=float(colour.delta_E(fa, fb, method="CIE 2000")),
                     first=[float(x) for x in fa], second=[float(x) for x in fb],
                     astm_first=float(colour.delta_E(a, fa, method="CIE 2000")),
                     astm_second=float(colour.delta_E(b, fb, method="CIE 2000")))
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
        assert!(
            (ours - theirs).abs() < 0.02,
            "{name}: {ours} against {theirs}"
        );
        for (k, spectrum) in [("first", &p.first), ("second", &p.second)] {
            let l = lab(spectrum, ill).unwrap();
            let c: Vec<f64> = v[name][k]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let d = delta_e([l.l, l.a, l.b], [c[0], c[1], c[2]]);
            assert!(d < 0.02, "{name} {k}: ΔE00 {d} from colour-science");
            let astm = v[name][format!("astm_{k}")].as_f64().unwrap();
            assert!(
                astm < SPECTRAL_INTEGRATION_DE,
                "{name} {k}: ASTM E308 {astm}"
            );
        }
    }
}
