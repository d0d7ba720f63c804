//! The virtual instruments for Python: in-plane curves by several methods at once (the columns of
//! `gonio inplane`'s CSV, computed by the same library call), the gloss and appearance meters,
//! and the multi-angle spectrophotometer.

use crate::error::{Result, invalid};
use crate::surface::Surface;
use crate::table::Table;
use gonio_brdf::Ior;
use gonio_color::{Illuminant, Observer};
use gonio_instrument::inplane::{self, InplaneRequest, Method};
use gonio_instrument::meter::{self, MapMethod};
use gonio_instrument::multiangle::{self, Geometry, GeometryReading, MultiangleReading, Settings};
use gonio_io::Progress;
use gonio_scatter::analytic::AnalyticModel;
use gonio_scatter::ray::RayOptions;
use gonio_surface::normals::NormalMethod;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The in-plane curves as columns (those of `gonio inplane`'s CSV: method, wavelength_nm,
/// incidence_deg, scatter_deg, brdf_per_sr, reflectance, rel_uncertainty; NaN where the CSV
/// leaves a cell empty) and the warnings. `methods` names map methods ("ray", "kirchhoff") and
/// analytic models of a Gaussian surface ("beckmann", "geometric", "microfacet", "smooth").
#[pyfunction]
#[pyo3(signature = (surface, methods, incidence_deg, scatter_deg, aperture_deg, index, index_imag, wavelength_nm, sq_nm, corr_um, shadowing, second_bounce, normals, azimuths, spot_um, spots))]
#[allow(clippy::too_many_arguments)]
pub fn inplane_columns<'py>(
    py: Python<'py>,
    surface: Option<&Surface>,
    methods: Vec<String>,
    incidence_deg: Vec<f64>,
    scatter_deg: Vec<f64>,
    aperture_deg: f64,
    index: f64,
    index_imag: Option<f64>,
    wavelength_nm: Vec<f64>,
    sq_nm: Option<f64>,
    corr_um: Option<f64>,
    shadowing: bool,
    second_bounce: bool,
    normals: &str,
    azimuths: usize,
    spot_um: Option<f64>,
    spots: usize,
) -> Result<(Bound<'py, PyDict>, Vec<String>)> {
    let (mut map_methods, mut models) = (Vec::new(), Vec::new());
    for m in &methods {
        match m.as_str() {
            "ray" => map_methods.push(Method::Ray),
            "kirchhoff" => map_methods.push(Method::Kirchhoff),
            "beckmann" => models.push(AnalyticModel::Beckmann),
            "geometric" => models.push(AnalyticModel::Geometric),
            "microfacet" => models.push(AnalyticModel::Microfacet),
            "smooth" => models.push(AnalyticModel::Smooth),
            other => {
                return Err(invalid(format!(
                    "method `{other}`: use \"ray\" or \"kirchhoff\" (on a surface) or a model: \
                     \"beckmann\", \"geometric\", \"microfacet\", \"smooth\""
                )));
            }
        }
    }
    if surface.is_none() && !map_methods.is_empty() {
        return Err(invalid(format!(
            "method `{}` needs a surface",
            map_methods[0].name()
        )));
    }
    let request = InplaneRequest {
        methods: map_methods,
        incidence_deg,
        scatter_deg,
        aperture_deg,
        ior: match index_imag {
            Some(k) if k > 0.0 => Ior::Conductor(num_complex::Complex64::new(index, k)),
            _ => Ior::Dielectric(index),
        },
        wavelength_nm,
        ray: RayOptions {
            normals: match normals {
                "plane" => NormalMethod::Plane,
                "spline" => NormalMethod::Spline,
                other => {
                    return Err(invalid(format!(
                        "normals `{other}`: use \"plane\" or \"spline\""
                    )));
                }
            },
            shadowing,
            second_bounce,
            azimuths,
            ..RayOptions::default()
        },
        spot_um,
        spots,
        models,
        sq_nm,
        corr_um,
    };
    let map = surface.map(|s| s.map.clone());
    let result = py.detach(|| inplane::compute(map.as_deref(), &request, &Progress::silent()))?;
    let rows: usize = result.curves.iter().map(|c| c.points.len()).sum();
    let mut method = Vec::with_capacity(rows);
    let (mut wl, mut ti, mut ts) = (vec![], vec![], vec![]);
    let (mut f, mut rho, mut unc) = (vec![], vec![], vec![]);
    for c in &result.curves {
        for p in &c.points {
            method.push(c.method.clone());
            wl.push(c.wavelength_nm.unwrap_or(f64::NAN));
            ti.push(c.incidence_deg);
            ts.push(p.scatter_deg);
            f.push(p.brdf_per_sr);
            rho.push(p.reflectance);
            unc.push(p.rel_uncertainty.unwrap_or(f64::NAN));
        }
    }
    let d = PyDict::new(py);
    d.set_item("method", method)?;
    for (name, v) in [
        ("wavelength_nm", wl),
        ("incidence_deg", ti),
        ("scatter_deg", ts),
        ("brdf_per_sr", f),
        ("reflectance", rho),
        ("rel_uncertainty", unc),
    ] {
        d.set_item(name, PyArray1::from_vec(py, v))?;
    }
    Ok((d, result.warnings))
}

/// The gloss, haze and DOI readings of a surface (by "ray" or "kirchhoff" at `wavelength_nm`,
/// over a coating of refractive index `index`) or a table, as the JSON text of
/// `gonio gloss --json` (keys gu20, gu60, gu85, haze, haze_wide, haze_20, haze_20_log,
/// haze_d4039, doi, doi_uncertainty, warnings).
#[pyfunction]
#[pyo3(signature = (specimen, method, index, wavelength_nm))]
pub fn gloss_json(
    py: Python<'_>,
    specimen: &Bound<'_, PyAny>,
    method: &str,
    index: f64,
    wavelength_nm: f64,
) -> Result<String> {
    let reading = if let Ok(table) = specimen.cast::<Table>() {
        let table = table.get().table.clone();
        py.detach(move || meter::read_table(&table))?
    } else if let Ok(surface) = specimen.cast::<Surface>() {
        let map = surface.get().map.clone();
        let method = match method {
            "ray" => MapMethod::Ray,
            "kirchhoff" => MapMethod::Kirchhoff { wavelength_nm },
            other => {
                return Err(invalid(format!(
                    "method `{other}`: use \"ray\" or \"kirchhoff\""
                )));
            }
        };
        py.detach(move || meter::read_height_map(&map, method, index))?
    } else {
        return Err(invalid("gloss: give a Surface or a Table"));
    };
    let mut json =
        serde_json::to_value(reading.report).map_err(|e| invalid(format!("gloss report: {e}")))?;
    json["warnings"] = serde_json::json!(reading.warnings);
    Ok(json.to_string())
}

/// What a multi-angle spectrophotometer reads on a spectral table at `geometries` (names such as
/// "45as15"): columns geometry, illumination_deg, aspecular_deg, viewing_deg, L, a, b, C,
/// h_deg, X, Y, Z (one row per geometry), the reflectance factors as a 2D array (geometries ×
/// wavelengths), the wavelengths in nm, and Alman's flop index (None without 45as15, 45as45
/// and 45as110).
#[pyfunction]
#[pyo3(signature = (table, geometries, aperture_deg, illuminant, observer_deg))]
#[allow(clippy::type_complexity)]
pub fn multiangle_columns<'py>(
    py: Python<'py>,
    table: &Table,
    geometries: Vec<String>,
    aperture_deg: f64,
    illuminant: &str,
    observer_deg: u32,
) -> Result<ReadingColumns<'py>> {
    let geometries = geometries
        .iter()
        .map(|g| Geometry::parse(g))
        .collect::<gonio_instrument::Result<Vec<_>>>()?;
    let settings = Settings {
        illuminant: Illuminant::from_name(illuminant)
            .ok_or_else(|| invalid(format!("illuminant `{illuminant}`: use \"D65\" or \"A\"")))?,
        observer: Observer::from_field_deg(observer_deg)
            .ok_or_else(|| invalid(format!("observer {observer_deg}°: use 2 or 10")))?,
        aperture_deg,
    };
    let table = table.table.clone();
    let reading = py.detach(move || multiangle::read_table(&table, &geometries, &settings))?;
    reading_columns(py, &reading)
}

/// A multi-angle reading for Python: the columns, the reflectance factors (geometries ×
/// wavelengths), the wavelengths and the flop index.
pub type ReadingColumns<'py> = (
    Bound<'py, PyDict>,
    Bound<'py, numpy::PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Option<f64>,
);

/// A multi-angle reading as [`multiangle_columns`] returns it ([`ReadingColumns`]).
pub fn reading_columns<'py>(
    py: Python<'py>,
    reading: &MultiangleReading,
) -> Result<ReadingColumns<'py>> {
    let columns = PyDict::new(py);
    let g = &reading.geometries;
    let column = |f: &dyn Fn(&GeometryReading) -> f64| -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, g.iter().map(f).collect())
    };
    columns.set_item(
        "geometry",
        g.iter().map(|r| r.geometry.to_string()).collect::<Vec<_>>(),
    )?;
    columns.set_item("illumination_deg", column(&|r| r.geometry.illumination_deg))?;
    columns.set_item("aspecular_deg", column(&|r| r.geometry.aspecular_deg))?;
    columns.set_item("viewing_deg", column(&|r| r.geometry.viewing_deg()))?;
    columns.set_item("L", column(&|r| r.lab.l))?;
    columns.set_item("a", column(&|r| r.lab.a))?;
    columns.set_item("b", column(&|r| r.lab.b))?;
    columns.set_item("C", column(&|r| r.lab.chroma()))?;
    columns.set_item("h_deg", column(&|r| r.lab.hue_deg()))?;
    columns.set_item("X", column(&|r| r.xyz.x))?;
    columns.set_item("Y", column(&|r| r.xyz.y))?;
    columns.set_item("Z", column(&|r| r.xyz.z))?;
    let rows: Vec<Vec<f64>> = g.iter().map(|r| r.reflectance_factor.clone()).collect();
    let factors = numpy::PyArray2::from_vec2(py, &rows)
        .map_err(|e| invalid(format!("reflectance factors: {e}")))?;
    Ok((
        columns,
        factors,
        PyArray1::from_vec(py, reading.wavelengths_nm.clone()),
        reading.flop_index(),
    ))
}
