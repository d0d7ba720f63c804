//! BRDF tables for Python: `gonio.Table`, a tabulated BRDF (monochrome, RGB, XYZ or spectral)
//! opened from a `.gbrdf` file, imported from a measurement, tabulated from a model or computed
//! from a height map; evaluated at arrays of directions, its albedo, saved and exported to the
//! formats other renderers read.

use crate::error::{Result, invalid};
use crate::surface::Surface;
use glam::DVec3;
use gonio_brdf::formats::{astm, csv as brdf_csv, merl, mitsuba, pabopto, radiance_xml};
use gonio_brdf::models::ModelSpec;
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use gonio_brdf::{Brdf, Ior, gbrdf};
use gonio_io::Progress;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::table::{self, TableOptions, kirchhoff_table, ray_table};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;

/// A tabulated BRDF on gonio's half/difference-angle grid (`docs/brdf-tables.md`).
#[pyclass(name = "Table", module = "gonio._gonio", frozen)]
pub struct Table {
    pub table: Arc<BrdfTable>,
}

impl Table {
    pub(crate) fn new(table: BrdfTable) -> Table {
        Table {
            table: Arc::new(table),
        }
    }
}

/// A resolution from 3 (isotropic) or 4 (anisotropic) node counts.
fn resolution(nodes: &[usize]) -> Result<Resolution> {
    match *nodes {
        [th, td, pd] => Ok(Resolution::isotropic(th, td, pd)),
        [th, td, pd, ph] if ph > 1 => Ok(Resolution::anisotropic(th, td, pd, ph)),
        _ => Err(invalid(
            "resolution: give (theta_h, theta_d, phi_d) for an isotropic table or \
             (theta_h, theta_d, phi_d, phi_h) with phi_h > 1, e.g. (32, 90, 180)",
        )),
    }
}

/// Unit directions from an array whose last axis has 3 components.
fn directions(a: &PyReadonlyArrayDyn<'_, f64>, what: &str) -> Result<Vec<DVec3>> {
    let shape = a.shape();
    if shape.last() != Some(&3) {
        return Err(invalid(format!(
            "{what}: the last axis must hold x, y, z (shape (..., 3)), got shape {shape:?}"
        )));
    }
    let flat: Vec<f64> = a.as_array().iter().copied().collect();
    Ok(flat
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]).normalize_or_zero())
        .collect())
}

#[pymethods]
impl Table {
    /// Open a `.gbrdf` file (memory-mapped: a large table is read as it is used).
    #[staticmethod]
    fn open(py: Python<'_>, path: PathBuf) -> Result<Table> {
        Ok(Table::new(py.detach(|| gbrdf::open_mapped(&path))?))
    }

    /// The BRDF f(wi, wo) in 1/sr for arrays of unit directions in the surface frame (+z the
    /// normal; `wi` toward the light, `wo` toward the viewer), shape (..., 3), broadcast
    /// against each other. Returns shape (..., 3), linear sRGB (a spectral table through its
    /// band weights under D65), or with `channels=True` shape (..., C): the table's own
    /// channels (C bands of a spectral table). Zero below the horizon.
    #[pyo3(signature = (wi, wo, channels=false))]
    fn eval<'py>(
        &self,
        py: Python<'py>,
        wi: PyReadonlyArrayDyn<'py, f64>,
        wo: PyReadonlyArrayDyn<'py, f64>,
        channels: bool,
    ) -> Result<Bound<'py, PyArrayDyn<f64>>> {
        let np = py.import("numpy")?;
        let (wi_b, wo_b) = {
            let b = np.call_method1("broadcast_arrays", (wi.as_any(), wo.as_any()))?;
            let wi_b: PyReadonlyArrayDyn<'py, f64> = b.get_item(0)?.extract()?;
            let wo_b: PyReadonlyArrayDyn<'py, f64> = b.get_item(1)?.extract()?;
            (wi_b, wo_b)
        };
        let shape = wi_b.shape().to_vec();
        let wis = directions(&wi_b, "wi")?;
        let wos = directions(&wo_b, "wo")?;
        let table = self.table.clone();
        let nc = if channels { table.channel_count() } else { 3 };
        let values = py.detach(move || {
            use rayon::prelude::*;
            let mut out = vec![0.0; wis.len() * nc];
            out.par_chunks_mut(nc)
                .zip(wis.par_iter().zip(&wos))
                .for_each(|(o, (&wi, &wo))| {
                    if channels {
                        table.eval_channels(wo, wi, o);
                    } else {
                        o.copy_from_slice(&table.eval(wo, wi).to_array());
                    }
                });
            out
        });
        let mut out_shape = shape;
        *out_shape.last_mut().expect("checked to end in 3") = nc;
        Ok(PyArray1::from_vec(py, values).reshape(out_shape)?)
    }

    /// Directional-hemispherical reflectance (albedo) per channel for light from polar angle
    /// `theta_i_deg` (degrees) and azimuth `phi_i_deg`.
    #[pyo3(signature = (theta_i_deg, phi_i_deg=0.0))]
    fn albedo<'py>(
        &self,
        py: Python<'py>,
        theta_i_deg: f64,
        phi_i_deg: f64,
    ) -> Result<Bound<'py, PyArray1<f64>>> {
        if !(0.0..90.0).contains(&theta_i_deg) {
            return Err(invalid(format!(
                "theta_i_deg {theta_i_deg}: must be in [0, 90) degrees"
            )));
        }
        let table = self.table.clone();
        let a = py.detach(move || table.albedo(theta_i_deg.to_radians(), phi_i_deg.to_radians()));
        Ok(PyArray1::from_vec(py, a))
    }

    /// What the channels hold: "mono", "rgb", "xyz" or "spectral (N wavelengths, A-B nm)".
    #[getter]
    fn channels(&self) -> String {
        self.table.channels().describe()
    }

    /// Band centres in nm of a spectral table, else None.
    #[getter]
    fn wavelengths_nm(&self) -> Option<Vec<f64>> {
        match self.table.channels() {
            gonio_brdf::table::Channels::Spectral { wavelengths_nm } => {
                Some(wavelengths_nm.clone())
            }
            _ => None,
        }
    }

    /// The node counts (theta_h, theta_d, phi_d) or (theta_h, theta_d, phi_d, phi_h).
    #[getter]
    fn resolution(&self) -> Vec<usize> {
        let r = self.table.resolution();
        if r.is_isotropic() {
            vec![r.theta_h, r.theta_d, r.phi_d]
        } else {
            vec![r.theta_h, r.theta_d, r.phi_d, r.phi_h]
        }
    }

    /// Write the table as a `.gbrdf` file (atomically: no half-written file on failure).
    fn save(&self, py: Python<'_>, path: PathBuf) -> Result<()> {
        let table = self.table.clone();
        Ok(py.detach(move || gbrdf::write(&table, &path))?)
    }

    /// Export for another renderer or reader: `format` "mitsuba" (Mitsuba 3 / pbrt-v4 tensor
    /// `.bsdf`), "merl" (`.binary`), "csv" (in-plane samples every `step_deg`), "radiance-xml"
    /// (Radiance's XML BSDF, a tensor tree of the default order, for its BSDF material),
    /// "pabopto" (Radiance's `pabopto2bsdf` input: a directory of files, one per incidence).
    #[pyo3(signature = (format, path, step_deg=1.0))]
    fn export(&self, py: Python<'_>, format: &str, path: PathBuf, step_deg: f64) -> Result<()> {
        let table = self.table.clone();
        match format {
            "mitsuba" => py.detach(move || mitsuba::write(&table, &path, Default::default()))?,
            "merl" => {
                py.detach(move || merl::write(&table, &path))?;
            }
            "csv" => py.detach(move || brdf_csv::write(&table, &path, step_deg))?,
            "radiance-xml" => {
                let name = gonio_brdf::formats::radiance_name(&path).to_string();
                py.detach(move || radiance_xml::write(&table, &path, &name, None))?;
            }
            "pabopto" => {
                let name = gonio_brdf::formats::radiance_name(&path).to_string();
                py.detach(move || {
                    pabopto::write(&table, &path, &name, &pabopto::DEFAULT_THETA_I_DEG)
                })?;
            }
            other => {
                return Err(invalid(format!(
                    "export format `{other}`: use \"mitsuba\", \"merl\", \"csv\", \"radiance-xml\" \
                     or \"pabopto\""
                )));
            }
        }
        Ok(())
    }

    fn __repr__(&self) -> String {
        format!(
            "Table({}, {})",
            self.table.resolution().describe(),
            self.table.channels().describe()
        )
    }
}

/// Import a measured BRDF: Cornell `.astm`, MERL `.binary` or a CSV of samples, by extension;
/// scattered measurements are fitted onto `resolution` (default: the import grid, 90 × 90 × 48).
#[pyfunction]
#[pyo3(signature = (path, resolution=None))]
pub fn import_table(
    py: Python<'_>,
    path: PathBuf,
    resolution: Option<Vec<usize>>,
) -> Result<Table> {
    let res = match resolution {
        Some(nodes) => self::resolution(&nodes)?,
        None => astm::default_resolution(),
    };
    let ext = gonio_io::extension(&path);
    let table = py.detach(|| match ext.as_str() {
        "astm" => astm::import(&path, res).map(|(t, _)| t),
        "csv" => brdf_csv::import(&path, res).map(|(t, _)| t),
        "binary" => merl::read(&path),
        _ => Err(gonio_brdf::BrdfError::Invalid(format!(
            "{}: cannot tell the format from the extension; use .astm, .binary (MERL) or .csv",
            path.display()
        ))),
    })?;
    Ok(Table::new(table))
}

/// Tabulate an analytic model given as a JSON text of `docs/brdf-models.md`
/// (`{"model": "ward", "specular": 0.05, "alpha": 0.1}`).
#[pyfunction]
#[pyo3(signature = (model_json, resolution, mono=false))]
pub fn tabulate(
    py: Python<'_>,
    model_json: &str,
    resolution: Vec<usize>,
    mono: bool,
) -> Result<Table> {
    let spec = ModelSpec::from_json(model_json)?;
    let model = spec.build()?;
    let res = self::resolution(&resolution)?;
    let provenance = Provenance::new(model_json.trim(), "model");
    let table = py.detach(|| BrdfTable::from_brdf(&model, res, mono, provenance))?;
    Ok(Table::new(table))
}

/// The table of a height map by the ray method or Kirchhoff, as `gonio brdf compute` makes it.
#[pyfunction]
#[pyo3(signature = (surface, method, index, index_imag, wavelength_nm, resolution, incidence_azimuths, shadowing, source))]
#[allow(clippy::too_many_arguments)]
pub fn compute_table(
    py: Python<'_>,
    surface: &Surface,
    method: &str,
    index: f64,
    index_imag: Option<f64>,
    wavelength_nm: Vec<f64>,
    resolution: Vec<usize>,
    incidence_azimuths: Option<usize>,
    shadowing: bool,
    source: String,
) -> Result<Table> {
    if !(index.is_finite() && index > 0.0) {
        return Err(invalid(format!(
            "index {index}: the refractive index must be positive"
        )));
    }
    let ior = match index_imag {
        Some(k) if k > 0.0 => Ior::Conductor(num_complex::Complex64::new(index, k)),
        _ => Ior::Dielectric(index),
    };
    let res = self::resolution(&resolution)?;
    let mut options = if res.is_isotropic() {
        TableOptions::for_resolution(res)
    } else {
        TableOptions {
            resolution: res,
            ..TableOptions::anisotropic()
        }
    };
    let map = surface.map.clone();
    let method = method.to_string();
    let table = py.detach(move || -> Result<BrdfTable> {
        if let Some(m) = incidence_azimuths {
            options.incidence_azimuths = m;
        } else if res.is_isotropic() {
            options.incidence_azimuths = table::isotropic_turns(table::texture_aspect_ratio(&map));
        }
        options.validate()?;
        let mut provenance = Provenance::new(source, &method);
        provenance.refractive_index = Some([index, index_imag.unwrap_or(0.0)]);
        let progress = Progress::silent();
        Ok(match method.as_str() {
            "ray" => {
                let engine = RayEngine::new(
                    &map,
                    RayOptions {
                        ior,
                        shadowing,
                        ..RayOptions::default()
                    },
                )?;
                ray_table(&engine, &options, provenance, &progress)?
            }
            "kirchhoff" => {
                let options_k = KirchhoffOptions {
                    shadowing,
                    ..KirchhoffOptions::new(ior)
                };
                let engine = Kirchhoff::new(&map, options_k)?;
                kirchhoff_table(&engine, &wavelength_nm, &options, provenance, &progress)?
            }
            other => {
                return Err(invalid(format!(
                    "method `{other}`: use \"ray\" or \"kirchhoff\""
                )));
            }
        })
    })?;
    Ok(Table::new(table))
}
