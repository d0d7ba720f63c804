//! Colorimetry for Python: a reflectance spectrum's CIE XYZ, chromaticity, CIELAB and sRGB under
//! a CIE illuminant and observer, with the keys of `gonio color xyz --json`.

use crate::error::{Result, invalid};
use gonio_color::{Colorimetry, Illuminant, Lab, Observer, Spectrum};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The colour of the reflectance (or transmittance) spectrum `values` (0–1) at `wavelengths_nm`
/// (increasing) under `illuminant` ("D65" or "A") for the CIE `observer` (2 or 10 degrees):
/// XYZ on the scale Y = 100 for the perfect diffuser, xy, CIELAB, linear and encoded sRGB.
#[pyfunction]
#[pyo3(signature = (wavelengths_nm, values, illuminant="D65", observer=2))]
pub fn xyz<'py>(
    py: Python<'py>,
    wavelengths_nm: Vec<f64>,
    values: Vec<f64>,
    illuminant: &str,
    observer: u32,
) -> Result<Bound<'py, PyDict>> {
    let (ill, obs) = conditions(illuminant, observer)?;
    let spectrum = Spectrum::new(wavelengths_nm, values)?;
    report(py, Colorimetry::of_reflectance(&spectrum, ill, obs))
}

/// The colour of CIELAB `lab` (L*, a*, b*) relative to the perfect diffuser under `illuminant`
/// for `observer`, with [`xyz`]'s keys: for swatches of a multi-angle reading or a target.
#[pyfunction]
#[pyo3(signature = (lab, illuminant="D65", observer=10))]
pub fn from_lab<'py>(
    py: Python<'py>,
    lab: [f64; 3],
    illuminant: &str,
    observer: u32,
) -> Result<Bound<'py, PyDict>> {
    let (ill, obs) = conditions(illuminant, observer)?;
    let lab = Lab {
        l: lab[0],
        a: lab[1],
        b: lab[2],
    };
    let xyz = lab.to_xyz(gonio_color::white(ill, obs));
    report(py, Colorimetry::of_xyz(xyz, ill, obs))
}

/// The illuminant and observer named `illuminant` and `observer`.
fn conditions(illuminant: &str, observer: u32) -> Result<(Illuminant, Observer)> {
    let ill = Illuminant::from_name(illuminant)
        .ok_or_else(|| invalid(format!("illuminant `{illuminant}`: use \"D65\" or \"A\"")))?;
    let obs = Observer::from_field_deg(observer).ok_or_else(|| {
        invalid(format!(
            "observer {observer}: use 2 (CIE 1931) or 10 (CIE 1964)"
        ))
    })?;
    Ok((ill, obs))
}

/// The keys of `gonio color xyz --json`.
fn report(py: Python<'_>, c: Colorimetry) -> Result<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("illuminant", c.illuminant.name())?;
    d.set_item("observer_deg", c.observer.field_deg())?;
    d.set_item("xyz", [c.xyz.x, c.xyz.y, c.xyz.z])?;
    d.set_item("chromaticity", c.xyy.map(|v| [v.x, v.y]))?;
    d.set_item("white_xyz", [c.white.x, c.white.y, c.white.z])?;
    d.set_item("cielab", [c.lab.l, c.lab.a, c.lab.b])?;
    d.set_item("chroma_ab", c.lab.chroma())?;
    d.set_item("hue_ab_deg", c.lab.hue_deg())?;
    d.set_item(
        "linear_srgb",
        [c.linear_srgb.r, c.linear_srgb.g, c.linear_srgb.b],
    )?;
    d.set_item("srgb_in_gamut", c.linear_srgb.in_gamut())?;
    d.set_item("srgb", [c.srgb.r, c.srgb.g, c.srgb.b])?;
    d.set_item("srgb_hex", c.srgb.to_hex())?;
    Ok(d)
}
