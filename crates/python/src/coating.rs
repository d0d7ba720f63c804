//! Coatings for Python: `gonio.coating.Coating`, a formulation (a TOML description as
//! `docs/coatings.md` gives it, read from a file or built from a dict), and what the `gonio
//! coating` commands compute from it: its summary (`info`), its spectral table (`compute`), its
//! multi-angle reading, a formulation study, and its picture on the curved panel. Each is one
//! call into `gonio-coating`, `gonio-instrument` or `gonio-render`, the calls the CLI makes, so
//! that Python gives the CLI's numbers.

use crate::error::{Result, invalid};
use crate::instruments::{ReadingColumns, reading_columns};
use crate::table::Table;
use gonio_brdf::table::Resolution;
use gonio_coating::cell::CellWalks;
use gonio_coating::description;
use gonio_coating::system::{self, default_bands};
use gonio_formulation::appearance::Output;
use gonio_formulation::coating_sensitivity::{Method, Plan, Settings, Varied};
use gonio_formulation::sensitivity;
use gonio_instrument::coating_readings::{ReadingsRequest, readings};
use gonio_instrument::coating_study::{self, Constituent};
use gonio_instrument::coating_study_output;
use gonio_instrument::coating_summary::summarise;
use gonio_instrument::multiangle::Standard;
use gonio_io::Cancel;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A coating's formulation, read over the default bands (400–700 nm in 10 nm steps).
#[pyclass(name = "Coating", module = "gonio._gonio", frozen)]
pub struct Coating {
    pub coating: system::Coating,
    /// Where it came from: the file, or "dict".
    #[pyo3(get)]
    pub source: String,
    /// The TOML text it was read from (a match writes the fitted values into it).
    #[pyo3(get)]
    pub toml: String,
}

/// Read the coating description `path` (TOML), or parse `text` (TOML, or JSON of the same
/// structure when `json` is true; relative file names in it start in `base_dir`).
#[pyfunction]
#[pyo3(signature = (path, text, json, base_dir))]
pub fn read_coating(
    path: Option<PathBuf>,
    text: Option<String>,
    json: bool,
    base_dir: PathBuf,
) -> Result<Coating> {
    let wavelengths = default_bands();
    match (path, text) {
        (Some(path), None) => Ok(Coating {
            coating: description::read(&path, &wavelengths)?,
            source: path.display().to_string(),
            toml: std::fs::read_to_string(&path)
                .map_err(|e| invalid(format!("{}: {e}", path.display())))?,
        }),
        (None, Some(text)) => {
            let toml = if json {
                let value: serde_json::Value =
                    serde_json::from_str(&text).map_err(|e| invalid(format!("coating: {e}")))?;
                toml::to_string(&value).map_err(|e| {
                    invalid(format!(
                        "coating: {e} (give a dict of tables as docs/coatings.md describes, \
                         without None values)"
                    ))
                })?
            } else {
                text
            };
            Ok(Coating {
                coating: description::parse_in(&toml, &base_dir, &wavelengths)?,
                source: "dict".into(),
                toml,
            })
        }
        _ => Err(invalid("give a coating file or a description")),
    }
}

#[pymethods]
impl Coating {
    /// The summary `gonio coating info --json` prints, as JSON text: coat index, base
    /// reflectance, the coat's mirror reflectance at 20/60/85°, the directional-hemispherical
    /// reflectance at 0/45/75° (550 nm), the E2194 colour and the flop index; `samples` walks
    /// per geometry (a rough top or flakes).
    #[pyo3(signature = (samples))]
    fn info_json(&self, py: Python<'_>, samples: usize) -> Result<String> {
        let coating = self.coating.clone();
        let summary = py.detach(move || summarise(&coating, &default_bands(), samples))?;
        Ok(summary.to_json().to_string())
    }

    /// Every reading the lab shows (`coating_readings::readings`), as JSON text
    /// (`Readings::to_json`): `standard` ("e2194" or "e2539"), the in-plane BRDF's
    /// `incidence_deg`, and the walks, `None` for the lab's defaults.
    #[pyo3(signature = (standard, incidence_deg, walks, brdf_walks, gloss_walks, albedo_samples, seed))]
    #[allow(clippy::too_many_arguments)]
    fn readings_json(
        &self,
        py: Python<'_>,
        standard: &str,
        incidence_deg: f64,
        walks: Option<usize>,
        brdf_walks: Option<usize>,
        gloss_walks: Option<usize>,
        albedo_samples: Option<usize>,
        seed: u64,
    ) -> Result<String> {
        let d = ReadingsRequest::default();
        let request = ReadingsRequest {
            standard: Standard::parse(standard)?,
            incidence_deg,
            walks: walks.unwrap_or(d.walks),
            brdf_walks: brdf_walks.unwrap_or(d.brdf_walks),
            gloss_walks: gloss_walks.unwrap_or(d.gloss_walks),
            albedo_samples: albedo_samples.unwrap_or(d.albedo_samples),
            seed,
            ..d
        };
        let coating = self.coating.clone();
        let r = py.detach(move || readings(&coating, &request, &Cancel::default()))?;
        Ok(r.to_json().to_string())
    }

    /// The coating's spectral table as `gonio coating compute` makes it: `resolution` (theta_h,
    /// cell's L* is less certain than `target_dl` (three times it where a direction is more than
    /// 70° from the normal; 0 or infinite: `samples` in every cell).
    /// cell's L* is less certain than `target_dl` (0 or infinite: `samples` in every cell).
    #[pyo3(signature = (resolution, bands, samples, target_dl))]
    fn compute(
        &self,
        py: Python<'_>,
        resolution: Vec<usize>,
        bands: Vec<f64>,
        samples: usize,
        target_dl: f64,
    ) -> Result<Table> {
        let [th, td, pd] = resolution[..] else {
            return Err(invalid(
                "resolution: give (theta_h, theta_d, phi_d), e.g. (90, 90, 48)",
            ));
        };
        let coating = self.coating.clone();
        let source = self.source.clone();
        let walks = CellWalks::adaptive(samples, target_dl);
        let table = py.detach(move || {
            let method = coating.method(walks);
            coating.table(
                Resolution::isotropic(th, td, pd),
                &bands,
                walks,
                coating.provenance(source, method),
            )
        })?;
        Ok(Table::new(table))
    }

    /// The multi-angle reading (D65/10°) at `standard`'s geometries, evaluated where the
    /// instrument looks (no table), `samples` walks per geometry: the columns, reflectance
    /// factors, wavelengths and flop index of `multiangle_columns`.
    #[pyo3(signature = (standard, samples))]
    fn multiangle_columns<'py>(
        &self,
        py: Python<'py>,
        standard: &str,
        samples: usize,
    ) -> Result<ReadingColumns<'py>> {
        let geometries = gonio_instrument::multiangle::standard(standard)?;
        let coating = self.coating.clone();
        let reading = py.detach(move || {
            let wl = default_bands();
            coating_study::multiangle_reading(&coating.evaluator(&wl)?, &wl, geometries, samples, 0)
        })?;
        reading_columns(py, &reading)
    }

    /// A formulation study as JSON text (`gonio coating study --json`): `vary` (roughness, tilt,
    /// coverage, tio2, thickness, base_thickness or concentration:NAME) at `values`, the
    /// multi-angle reading at `standard`'s geometries with `samples` walks each, the gloss meter with a sixty-fourth.
    #[pyo3(signature = (vary, values, standard, samples))]
    fn study_json(
        &self,
        py: Python<'_>,
        vary: &str,
        values: Vec<f64>,
        standard: &str,
        samples: usize,
    ) -> Result<String> {
        let constituent = Constituent::parse(vary)?;
        let geometries = gonio_instrument::multiangle::standard(standard)?;
        let coating = self.coating.clone();
        let rows = {
            let constituent = constituent.clone();
            let values = values.clone();
            py.detach(move || {
                coating_study::run(
                    &coating,
                    &constituent,
                    &values,
                    geometries,
                    &default_bands(),
                    samples,
                    (samples / 64).max(1),
                )
            })?
        };
        Ok(coating_study_output::json(&self.source, vary, &constituent.label(), &rows).to_string())
    }

    /// The coating on the curved panel in the dark studio, as `gonio coating study` draws it
    /// (its table computed for the picture, rendered spectrally): the (height, width, 3) uint8
    /// sRGB picture the PNG holds (the scene's exposure and filmic tone curve applied), the
    /// (height, width, 3) float32 linear sRGB radiance, and the render's seconds.
    #[pyo3(signature = ())]
    #[allow(clippy::type_complexity)]
    fn panel_picture<'py>(
        &self,
        py: Python<'py>,
    ) -> Result<(Bound<'py, PyArray3<u8>>, Bound<'py, PyArray3<f32>>, f64)> {
        let coating = self.coating.clone();
        let source = self.source.clone();
        let (image, display, stats) = py.detach(move || {
            let dir = tempfile::tempdir()
                .map_err(|e| invalid(format!("a temporary folder for the scene: {e}")))?;
            let panel = gonio_render::panel::table(&coating, &source, dir.path(), "panel")?;
            let scene = gonio_render::panel::scene(dir.path(), "panel", &[panel])?;
            Ok::<_, crate::error::Error>(gonio_render::panel::render_image(&scene)?)
        })?;
        let (h, w) = (image.height, image.width);
        let srgb = PyArray1::from_vec(py, image.to_srgb8(display)).reshape([h, w, 3])?;
        let flat: Vec<f32> = image.pixels.into_iter().flatten().collect();
        Ok((
            srgb,
            PyArray1::from_vec(py, flat).reshape([h, w, 3])?,
            stats.seconds,
        ))
    }
}

/// A coating's sensitivity taken apart (`gonio_formulation::coating_sensitivity::Plan`), so
/// that Python can read the design's rows anywhere (on Dask workers) and analyse them here:
/// `design`, `read_points`, `noise`, `analyze`.
#[pyclass(name = "SensitivityPlan", module = "gonio._gonio", frozen)]
pub struct SensitivityPlan {
    plan: Plan,
    varied: Vec<Varied>,
}

/// The plan of `coating`'s sensitivity: `vary` (NAME=LO:HI,...), `outputs` (None: all at the
/// standard's geometries), `method` (sobol or morris) with `samples` base points or
/// trajectories (None: the defaults), the `standard`'s geometries, `walks` per geometry. Reads
/// the base formulation (about a second).
#[pyfunction]
#[pyo3(signature = (coating, vary, outputs, method, samples, standard, walks))]
#[allow(clippy::too_many_arguments)]
pub fn sensitivity_plan(
    py: Python<'_>,
    coating: &Coating,
    vary: &str,
    outputs: Option<String>,
    method: &str,
    samples: Option<usize>,
    standard: &str,
    walks: usize,
) -> Result<SensitivityPlan> {
    let varied = Varied::resolve_list(vary, None, &coating.coating, &default_bands())?;
    let geometries = gonio_instrument::multiangle::standard(standard)?;
    let outputs = match outputs {
        Some(list) => Output::parse_list(&list)?,
        None => Output::all(geometries),
    };
    let method = Method::parse(method, samples)?;
    let settings = Settings {
        geometries: geometries.to_vec(),
        walks,
        ..Settings::default()
    };
    let base = coating.coating.clone();
    let v = varied.clone();
    let plan = py.detach(move || Plan::new(&base, &v, &outputs, method, &settings))?;
    Ok(SensitivityPlan { plan, varied })
}

#[pymethods]
impl SensitivityPlan {
    /// The design: (readings, constituents) in physical units.
    fn design<'py>(&self, py: Python<'py>) -> Result<Bound<'py, PyArray2<f64>>> {
        Ok(self.plan.design()?.into_pyarray(py))
    }

    /// The outputs' names, in the order of the columns of `read_points`.
    fn output_names(&self) -> Vec<String> {
        self.plan.outputs().iter().map(Output::name).collect()
    }

    /// The outputs at each row of `points` (rows, constituents): (rows, outputs), read in
    /// parallel with the GIL released; a row's values do not depend on the other rows, their
    /// order or the machine.
    fn read_points<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'_, f64>,
    ) -> Result<Bound<'py, PyArray2<f64>>> {
        let points = points.as_array().to_owned();
        let plan = &self.plan;
        let values = py.detach(|| {
            sensitivity::evaluate(&points, plan.outputs().len(), |x| plan.read_point(x))
        })?;
        Ok(values.into_pyarray(py))
    }

    /// Each output's noise (one standard deviation over re-readings of the base formulation).
    fn noise(&self, py: Python<'_>) -> Result<Vec<f64>> {
        Ok(py.detach(|| self.plan.noise())?)
    }

    /// The indices of the design's readings `values` (rows of `design()` in order), as JSON
    /// text of `gonio coating sensitivity --json`'s structure (summary at `threshold`).
    fn analyze_json(
        &self,
        points: PyReadonlyArray2<'_, f64>,
        values: PyReadonlyArray2<'_, f64>,
        noise: Vec<f64>,
        threshold: f64,
    ) -> Result<String> {
        let s = self.plan.analyze(
            points.as_array().to_owned(),
            values.as_array().to_owned(),
            noise,
        )?;
        Ok(s.to_json(&self.varied, threshold).to_string())
    }
}
