//! Tabulated BRDFs over the whole hemisphere of incidence and reflection: the currency between
//! the scattering engines, the instruments, the fitter, the renderer and the exchange formats.
//!
//! A table stores `f(wi, wo)` in 1/sr at the nodes of a grid over the Rusinkiewicz half/difference
//! angles (see [`coords`]): isotropic tables over (theta_h, theta_d, phi_d), anisotropic ones add
//! phi_h. theta_h is spaced as the square of the node index, as in the MERL tables, so that a
//! table of 90 theta_h nodes has nodes 0.011°, 0.044°, 0.1°, 0.18°, 0.28° ... from the specular
//! direction: a specular lobe 0.5° wide (0.25° in theta_h) spans several nodes, while the broad
//! part of the hemisphere gets the coarse spacing it needs. A grid over (theta_i, theta_o, phi)
//! would need about 0.1° steps everywhere, i.e. ~10⁴ times more nodes, for the same lobe.
//!
//! Values are evaluated by multilinear interpolation between the 8 (16 when anisotropic)
//! surrounding nodes. Nodes where `wi` or `wo` lies below the horizon hold NaN ("no data") and
//! are left out of the interpolation, whose weights are renormalised over the nodes with data.
//!
//! Channels are one value (monochrome), three (linear RGB) or a list of wavelengths (spectral).

mod analysis;
mod builder;
pub mod colour;
pub mod coords;
mod fit_samples;
mod sampler;
mod spectral;
mod vndf_warp;

pub use analysis::AlbedoCurve;
pub use builder::{Cell, TableBuilder};
pub use coords::{HalfDiff, Resolution};
pub use sampler::{SampledTable, SamplerOptions, TableSampler};
pub use spectral::band_value;

use crate::bxdf::{Brdf, BrdfSample, Rgb};
use crate::error::{BrdfError, Result};
use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf};
use glam::{DVec2, DVec3};
use std::collections::BTreeMap;

/// What the channels of a table hold.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Channels {
    /// One value per node.
    Mono,
    /// Linear RGB (sRGB primaries).
    Rgb,
    /// CIE XYZ divided by 100 (a BRDF in 1/sr per component: Y is the luminance-weighted BRDF),
    /// e.g. a spectral table reduced under an illuminant by [`colour::reduce`].
    Xyz,
    /// One value per wavelength, in nanometres, strictly increasing.
    Spectral { wavelengths_nm: Vec<f64> },
}

impl Channels {
    /// Number of values per node.
    pub fn count(&self) -> usize {
        match self {
            Channels::Mono => 1,
            Channels::Rgb | Channels::Xyz => 3,
            Channels::Spectral { wavelengths_nm } => wavelengths_nm.len(),
        }
    }

    /// Column names with units, for CSV and plots: `f_per_sr`, `r_per_sr`, ..., `f_550nm_per_sr`.
    pub fn column_names(&self) -> Vec<String> {
        match self {
            Channels::Mono => vec!["f_per_sr".into()],
            Channels::Rgb => vec!["r_per_sr".into(), "g_per_sr".into(), "b_per_sr".into()],
            Channels::Xyz => vec!["x_per_sr".into(), "y_per_sr".into(), "z_per_sr".into()],
            Channels::Spectral { wavelengths_nm } => wavelengths_nm
                .iter()
                .map(|w| format!("f_{w}nm_per_sr"))
                .collect(),
        }
    }

    /// Check that a spectral list is non-empty, finite, positive and increasing.
    pub fn validate(&self) -> std::result::Result<(), String> {
        if let Channels::Spectral { wavelengths_nm } = self {
            if wavelengths_nm.is_empty() {
                return Err("a spectral table needs at least one wavelength".into());
            }
            if wavelengths_nm.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
                return Err("wavelengths must be finite and positive (nm)".into());
            }
            if wavelengths_nm.windows(2).any(|p| p[1] <= p[0]) {
                return Err("wavelengths must be strictly increasing".into());
            }
        }
        Ok(())
    }

    /// `mono`, `rgb` or `spectral (N wavelengths, A-B nm)`.
    pub fn describe(&self) -> String {
        match self {
            Channels::Mono => "mono".into(),
            Channels::Rgb => "rgb".into(),
            Channels::Xyz => "xyz".into(),
            Channels::Spectral { wavelengths_nm: w } => {
                format!(
                    "spectral ({} wavelengths, {}-{} nm)",
                    w.len(),
                    w[0],
                    w[w.len() - 1]
                )
            }
        }
    }
}

/// Where a table came from. Every field is optional; unknown keys read from a file are kept in
/// `extra`.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Provenance {
    /// The source: a height-map file, a measurement file or an analytic model's description.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
    /// How the values were obtained: `ray`, `kirchhoff`, `model`, `import:astm`, ...
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub method: Option<String>,
    /// Refractive index of the material, `[n, kappa]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refractive_index: Option<[f64; 2]>,
    /// UTC date of creation, ISO 8601 (`YYYY-MM-DD`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub date: Option<String>,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Any other key/value pair (fit residuals of an import, engine settings, ...).
    #[serde(default, flatten)]
    pub extra: BTreeMap<String, serde_json::Value>,
}

impl Provenance {
    /// A provenance with source and method and today's UTC date.
    pub fn new(source: impl Into<String>, method: impl Into<String>) -> Provenance {
        Provenance {
            source: Some(source.into()),
            method: Some(method.into()),
            date: Some(today_utc()),
            ..Provenance::default()
        }
    }
}

/// Today's UTC date as `YYYY-MM-DD`.
pub fn today_utc() -> String {
    jiff::Timestamp::now().strftime("%Y-%m-%d").to_string()
}

/// The f32 values of a table: owned, or borrowed from a memory-mapped `.gbrdf` file.
pub(crate) enum Storage {
    Owned(Vec<f32>),
    Mapped {
        map: memmap2::Mmap,
        offset: usize,
        len: usize,
    },
}

impl Storage {
    fn values(&self) -> &[f32] {
        match self {
            Storage::Owned(v) => v,
            Storage::Mapped { map, offset, len } => {
                bytemuck::cast_slice(&map[*offset..*offset + *len * 4])
            }
        }
    }
}

/// A tabulated BRDF. See the module documentation for the grid.
pub struct BrdfTable {
    res: Resolution,
    channels: Channels,
    provenance: Provenance,
    data: Storage,
    /// Per channel, its contribution to linear RGB in [`Brdf::eval`].
    rgb_weights: Vec<[f64; 3]>,
}

impl std::fmt::Debug for BrdfTable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BrdfTable")
            .field("resolution", &self.res)
            .field("channels", &self.channels)
            .field("provenance", &self.provenance)
            .finish_non_exhaustive()
    }
}

impl Clone for BrdfTable {
    fn clone(&self) -> Self {
        BrdfTable {
            res: self.res,
            channels: self.channels.clone(),
            provenance: self.provenance.clone(),
            data: Storage::Owned(self.values().to_vec()),
            rgb_weights: self.rgb_weights.clone(),
        }
    }
}

/// Directions closer to the horizon than this cosine are treated as below it when cells are
/// filled (the values of analytic models diverge or vanish there).
pub(crate) const MIN_COS: f64 = 1e-3;

impl BrdfTable {
    /// A table from its values, laid out cell by cell (see [`Resolution::cell_index`]) with the
    /// channels of a cell adjacent. NaN marks a cell without data.
    pub fn from_values(
        res: Resolution,
        channels: Channels,
        provenance: Provenance,
        values: Vec<f32>,
    ) -> Result<BrdfTable> {
        BrdfTable::from_storage(res, channels, provenance, Storage::Owned(values))
    }

    pub(crate) fn from_storage(
        res: Resolution,
        channels: Channels,
        provenance: Provenance,
        data: Storage,
    ) -> Result<BrdfTable> {
        res.validate().map_err(BrdfError::Invalid)?;
        channels.validate().map_err(BrdfError::Invalid)?;
        let want = res.cell_count() * channels.count();
        let got = data.values().len();
        if got != want {
            return Err(BrdfError::Invalid(format!(
                "a {} table with {} channels needs {want} values, got {got}",
                res.describe(),
                channels.count()
            )));
        }
        let rgb_weights = rgb_weights(&channels)?;
        Ok(BrdfTable {
            res,
            channels,
            provenance,
            data,
            rgb_weights,
        })
    }

    /// The grid.
    pub fn resolution(&self) -> Resolution {
        self.res
    }

    /// What the channels hold.
    pub fn channels(&self) -> &Channels {
        &self.channels
    }

    /// Number of values per cell.
    pub fn channel_count(&self) -> usize {
        self.channels.count()
    }

    /// Where the table came from.
    pub fn provenance(&self) -> &Provenance {
        &self.provenance
    }

    /// Replace the provenance.
    pub fn set_provenance(&mut self, provenance: Provenance) {
        self.provenance = provenance;
    }

    /// All values, cell by cell, channels adjacent (NaN: no data).
    pub fn values(&self) -> &[f32] {
        self.data.values()
    }

    /// Whether the values are read from a memory-mapped file rather than held in memory.
    pub fn is_mapped(&self) -> bool {
        matches!(self.data, Storage::Mapped { .. })
    }

    /// Mutable values (a mapped table is copied into memory first).
    pub(crate) fn values_mut(&mut self) -> &mut [f32] {
        if let Storage::Mapped { .. } = self.data {
            self.data = Storage::Owned(self.data.values().to_vec());
        }
        match &mut self.data {
            Storage::Owned(v) => v,
            Storage::Mapped { .. } => unreachable!("converted to owned above"),
        }
    }

    /// The values of one cell (all channels).
    pub fn cell_values(&self, cell: usize) -> &[f32] {
        let c = self.channel_count();
        &self.values()[cell * c..(cell + 1) * c]
    }

    /// Interpolated `f` in 1/sr for every channel at the pair (`wo` toward the viewer, `wi`
    /// toward the light), written into `out` (length [`BrdfTable::channel_count`]). Zero when
    /// either direction is at or below the horizon.
    pub fn eval_channels(&self, wo: DVec3, wi: DVec3, out: &mut [f64]) {
        out.fill(0.0);
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return;
        }
        if let Some(a) = HalfDiff::from_dirs_with(wi, wo, !self.res.is_isotropic()) {
            self.eval_angles(&a, out);
        }
    }

    /// Interpolated `f` at half/difference angles, written into `out`.
    pub fn eval_angles(&self, a: &HalfDiff, out: &mut [f64]) {
        let s = self.res.stencil(a);
        if self.res.is_isotropic() {
            self.interpolate(&self.res.corners_of::<8>(&s), out);
        } else {
            self.interpolate(&self.res.corners_of::<16>(&s), out);
        }
    }

    /// The weighted mean of the corners' values, over the corners with data.
    #[inline]
    fn interpolate(&self, corners: &[(usize, f64)], out: &mut [f64]) {
        let data = self.values();
        // The channel counts of mono and RGB tables as constants, so that the loops over the
        // channels unroll.
        match out.len() {
            1 => weighted_mean(data, 1, corners, out),
            3 => weighted_mean(data, 3, corners, out),
            nc => weighted_mean(data, nc, corners, out),
        }
    }

    /// The scalar that sampling and summaries use for a vector of channel values: the mean over
    /// the channels.
    pub fn scalar(values: &[f64]) -> f64 {
        values.iter().sum::<f64>() / values.len() as f64
    }

    /// Linear RGB of a vector of channel values.
    pub fn to_rgb(&self, values: &[f64]) -> Rgb {
        let mut rgb = Rgb::ZERO;
        for (w, v) in self.rgb_weights.iter().zip(values) {
            rgb += Rgb::from_array(*w) * *v;
        }
        rgb
    }
}

/// The mean of the values of the `corners` (cell index, weight) in `data` (`nc` channels per
/// cell), weighted and over the cells with data (not NaN), written into `out` (length `nc`);
/// zeros when no corner of nonzero weight has data.
#[inline(always)]
fn weighted_mean(data: &[f32], nc: usize, corners: &[(usize, f64)], out: &mut [f64]) {
    let out = &mut out[..nc];
    out.fill(0.0);
    let mut wsum = 0.0;
    for &(cell, w) in corners {
        if w == 0.0 {
            continue;
        }
        let values = &data[cell * nc..][..nc];
        if values[0].is_nan() {
            continue;
        }
        wsum += w;
        for (o, v) in out.iter_mut().zip(values) {
            *o += w * f64::from(*v);
        }
    }
    if wsum > 0.0 {
        out.iter_mut().for_each(|o| *o /= wsum);
    }
}

/// Per-channel weights turning channel values into linear RGB: identity for RGB, replication
/// for monochrome, and for spectra gonio-color's band weights (CIE 1931 2° observer under D65,
/// linear between bands, ASTM E308 construction), so that a flat spectrum of value v gives about
/// (v, v, v).
pub(crate) fn rgb_weights(channels: &Channels) -> Result<Vec<[f64; 3]>> {
    Ok(match channels {
        Channels::Mono => vec![[1.0; 3]],
        Channels::Rgb => vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        Channels::Xyz => colour::xyz_rgb_weights(),
        Channels::Spectral { wavelengths_nm } => {
            use gonio_color::{Illuminant, Observer, SpectralToXyz};
            SpectralToXyz::new(wavelengths_nm, Illuminant::D65, Observer::Cie1931TwoDegree)
                .map_err(|e| BrdfError::Invalid(format!("spectral table: {e}")))?
                .rgb_weights()
                .to_vec()
        }
    })
}

impl Brdf for BrdfTable {
    fn eval(&self, wo: DVec3, wi: DVec3) -> Rgb {
        let nc = self.channel_count();
        if nc <= 3 {
            // Mono and RGB: a buffer of their size (a render calls this twice per path).
            let mut buf = [0.0f64; 3];
            self.eval_channels(wo, wi, &mut buf[..nc]);
            if matches!(self.channels, Channels::Rgb) {
                Rgb::from_array(buf)
            } else {
                self.to_rgb(&buf[..nc])
            }
        } else if nc <= 64 {
            let mut buf = [0.0f64; 64];
            self.eval_channels(wo, wi, &mut buf[..nc]);
            self.to_rgb(&buf[..nc])
        } else {
            let mut v = vec![0.0; nc];
            self.eval_channels(wo, wi, &mut v);
            self.to_rgb(&v)
        }
    }

    /// Cosine-weighted sampling (for importance sampling of the table's lobes, wrap the table
    /// in a [`SampledTable`]).
    fn sample(&self, wo: DVec3, u: DVec2) -> Option<BrdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = cosine_hemisphere(u);
        let pdf = cosine_hemisphere_pdf(wi.z);
        if pdf <= 0.0 {
            return None;
        }
        Some(BrdfSample {
            wi,
            f: self.eval(wo, wi),
            pdf,
        })
    }

    fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        if wo.z <= 0.0 {
            0.0
        } else {
            cosine_hemisphere_pdf(wi.z)
        }
    }
}
