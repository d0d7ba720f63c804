//! Height maps for Python: `gonio.Surface` (heights in metres, NaN where not measured; spacings
//! in metres), read from any instrument file gonio reads, made from a numpy array, or
//! synthesised; its ISO 25178 statistics, levelling, crop and rotation.

use crate::error::{Result, invalid};
use gonio_surface::synth::{Acf, GaussianSurface};
use gonio_surface::{ChannelSelector, HeightMap, io, ops, stats};
use numpy::{PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::Arc;

/// A measured or synthetic height map: heights in metres on a regular grid of spacings `dx`
/// (along x, the columns) and `dy` (along y, the rows), NaN where the instrument measured
/// nothing. Immutable: `level`, `crop` and `rotate` return new surfaces.
#[pyclass(name = "Surface", module = "gonio._gonio", frozen)]
pub struct Surface {
    pub map: Arc<HeightMap>,
}

impl Surface {
    pub fn new(map: HeightMap) -> Surface {
        Surface { map: Arc::new(map) }
    }
}

#[pymethods]
impl Surface {
    /// A surface from a 2-D array of heights in metres (rows along y), NaN where not measured,
    /// and the spacings `dx`, `dy` in metres (`dy` defaults to `dx`). The heights are copied.
    #[staticmethod]
    #[pyo3(signature = (heights, dx, dy=None))]
    fn from_array(heights: PyReadonlyArray2<'_, f64>, dx: f64, dy: Option<f64>) -> Result<Surface> {
        let map = HeightMap::with_invalid(heights.as_array().to_owned(), dx, dy.unwrap_or(dx))?;
        Ok(Surface::new(map))
    }

    /// The heights in metres, shape (ny, nx), NaN where not measured. A read-only view of the
    /// surface's own array when every point was measured, else a copy with the NaNs.
    #[getter]
    fn heights<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let py = slf.py();
        let map = &slf.get().map;
        match map.mask() {
            None => {
                // SAFETY: the array lives in the frozen Surface, which the view keeps alive
                // (its base object) and which never changes or moves its heights.
                let view =
                    unsafe { PyArray2::borrow_from_array(map.heights(), slf.clone().into_any()) };
                view.call_method1("setflags", ((), false))?;
                Ok(view)
            }
            Some(mask) => {
                let mut h = map.heights().clone();
                h.zip_mut_with(mask, |v, &ok| {
                    if !ok {
                        *v = f64::NAN;
                    }
                });
                Ok(PyArray2::from_owned_array(py, h))
            }
        }
    }

    /// Spacing along x (between columns), m.
    #[getter]
    fn dx(&self) -> f64 {
        self.map.dx()
    }

    /// Spacing along y (between rows), m.
    #[getter]
    fn dy(&self) -> f64 {
        self.map.dy()
    }

    /// The grid's shape (ny, nx), as numpy gives it.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (self.map.ny(), self.map.nx())
    }

    /// What the file says about the map: format, instrument, date, source, channels (the
    /// channel read is `channel`), other key/value pairs and the reader's warnings.
    #[getter]
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let meta = &self.map.meta;
        let d = PyDict::new(py);
        d.set_item("format", &meta.format)?;
        d.set_item("instrument", &meta.instrument)?;
        d.set_item("date", &meta.date)?;
        d.set_item(
            "source",
            meta.source.as_ref().map(|p| p.display().to_string()),
        )?;
        let channels = meta
            .channels
            .iter()
            .map(|c| {
                let ch = PyDict::new(py);
                ch.set_item("index", c.index)?;
                ch.set_item("name", &c.name)?;
                ch.set_item("unit", &c.unit)?;
                ch.set_item("is_height", c.is_height)?;
                ch.set_item("problem", &c.problem)?;
                Ok(ch)
            })
            .collect::<PyResult<Vec<_>>>()?;
        d.set_item("channels", channels)?;
        d.set_item("channel", meta.channel)?;
        let extra = PyDict::new(py);
        for (k, v) in &meta.extra {
            extra.set_item(k, v)?;
        }
        d.set_item("extra", extra)?;
        d.set_item("warnings", meta.warnings().collect::<Vec<_>>())?;
        Ok(d)
    }

    /// ISO 25178-2 parameters after least-squares levelling, with the keys of
    /// `gonio surface info --json`: lengths in metres (`sq_m`, `sa_m`, `sal_m`), `ssk`, `sku`,
    /// `sdq` (rms gradient), `str` (texture aspect ratio; `str_upper_bound` when only a bound),
    /// `sal_m` and `str` None where the autocorrelation does not decay within half the map.
    fn statistics<'py>(&self, py: Python<'py>) -> Result<Bound<'py, PyDict>> {
        let map = self.map.clone();
        let st = py.detach(move || stats::statistics(&map))?;
        let d = PyDict::new(py);
        d.set_item("nx", self.map.nx())?;
        d.set_item("ny", self.map.ny())?;
        d.set_item("dx_m", self.map.dx())?;
        d.set_item("dy_m", self.map.dy())?;
        d.set_item("valid_fraction", self.map.valid_fraction())?;
        d.set_item("sq_m", st.sq)?;
        d.set_item("sa_m", st.sa)?;
        d.set_item("ssk", st.ssk)?;
        d.set_item("sku", st.sku)?;
        d.set_item("sdq", st.sdq)?;
        d.set_item("sal_m", st.sal)?;
        d.set_item("str", st.str)?;
        d.set_item("str_upper_bound", st.str_is_upper_bound)?;
        Ok(d)
    }

    /// The map less its least-squares plane.
    fn level(&self) -> Result<Surface> {
        Ok(Surface::new(ops::level(&self.map)?))
    }

    /// The part of `nx` × `ny` points whose first point is column `x0`, row `y0`.
    fn crop(&self, x0: usize, y0: usize, nx: usize, ny: usize) -> Result<Surface> {
        Ok(Surface::new(ops::crop(&self.map, x0, y0, nx, ny)?))
    }

    /// The map turned by `deg` degrees counter-clockwise (from +x toward +y) about its centre on
    /// the same grid: bicubic-spline heights; points whose source lies outside the map become
    /// NaN (not measured).
    fn rotate(&self, deg: f64) -> Result<Surface> {
        Ok(Surface::new(ops::rotate(&self.map, deg.to_radians())?))
    }

    /// A surface from a SurfaceTopography topography (heights and sizes converted to metres from
    /// the topography's unit; masked points become NaN).
    #[staticmethod]
    fn from_topography<'py>(topography: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let py = topography.py();
        py.import("gonio._topography")?
            .call_method1("from_topography", (topography,))
    }

    /// The surface as a SurfaceTopography `Topography` in metres (NaN points masked); needs
    /// SurfaceTopography installed.
    fn to_topography<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        slf.py()
            .import("gonio._topography")?
            .call_method1("to_topography", (slf,))
    }

    fn __repr__(&self) -> String {
        format!(
            "Surface({} × {} points, dx = {} µm, dy = {} µm{})",
            self.map.nx(),
            self.map.ny(),
            micrometres(self.map.dx()),
            micrometres(self.map.dy()),
            self.map
                .meta
                .source
                .as_ref()
                .map(|p| format!(", from {}", p.display()))
                .unwrap_or_default()
        )
    }
}

/// A length in µm to 6 decimals, as a person reads it (0.5, not 0.49999999999999994).
fn micrometres(metres: f64) -> f64 {
    (metres * 1e12).round() / 1e6
}

/// Read a height map from an instrument file (any format `gonio surface info` reads; the format
/// is detected from the content). `channel`: the name or 0-based index of the channel to read in
/// a multi-channel file (AFM), default the first height channel. A line profile is refused.
#[pyfunction]
#[pyo3(signature = (path, channel=None))]
pub fn read_surface(
    py: Python<'_>,
    path: PathBuf,
    channel: Option<Bound<'_, PyAny>>,
) -> Result<Surface> {
    let channel = match channel {
        None => None,
        Some(c) => Some(if let Ok(i) = c.extract::<usize>() {
            ChannelSelector::Index(i)
        } else if let Ok(name) = c.extract::<String>() {
            ChannelSelector::Name(name)
        } else {
            return Err(invalid(
                "channel: give a channel name (str) or a 0-based index (int)",
            ));
        }),
    };
    let options = io::ReadOptions { channel };
    let map = py.detach(|| io::read_with(&path, &options))?;
    if map.is_profile() {
        return Err(invalid(format!(
            "{}: the file holds a line profile ({} points), not an areal height map",
            path.display(),
            map.nx()
        )));
    }
    Ok(Surface::new(map))
}

/// A Gaussian random surface of rms height `sq` and correlation length `corr` (metres) on a
/// square grid of `size` × `size` points of spacing `dx` (metres); `acf` "gaussian"
/// (exp(−r²/T²)) or "exponential" (exp(−r/T)); the same `seed` gives the same surface.
#[pyfunction]
#[pyo3(signature = (sq, corr, size, dx, acf="gaussian", seed=1))]
pub fn synthesize(
    py: Python<'_>,
    sq: f64,
    corr: f64,
    size: usize,
    dx: f64,
    acf: &str,
    seed: u64,
) -> Result<Surface> {
    let acf = match acf {
        "gaussian" => Acf::Gaussian,
        "exponential" => Acf::Exponential,
        other => {
            return Err(invalid(format!(
                "acf `{other}`: use \"gaussian\" or \"exponential\""
            )));
        }
    };
    let request = GaussianSurface {
        acf,
        ..GaussianSurface::square(sq, corr, size, dx, seed)
    };
    Ok(Surface::new(py.detach(|| request.generate())?))
}
