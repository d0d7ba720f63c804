//! Synthesis of periodic Gaussian random surfaces from a power spectral density: a power law
//! `q^-n` between two wavelengths (a model of a clear coat's orange peel), or a measured radial
//! PSD read from a table.
//!
//! Method: the FFT filter of [`crate::synth`] (Garcia & Stoll 1984; Persson et al. 2005) with the
//! same white noise (one PCG-64 stream per row: the same seed gives the same map on any thread
//! count) and the same convention: the zero-frequency term is removed and the map stays periodic
//! (no plane is subtracted), and a requested rms height is Sq after least-squares levelling, as
//! [`crate::stats`] computes it, to rounding. A requested rms slope is the rms of the forward
//! differences along x, `(z[ix+1] − z[ix]) / dx` within each row, less the levelling plane's x
//! slope: the quantity [`crate::waviness`] band-passes, also exact to rounding.
//!
//! PSD convention (Jacobs, Junge & Pastewka, "Quantitative characterization of surface
//! topography using spectral analysis", Surf. Topogr.: Metrol. Prop. 5, 013001 (2017), §2–3;
//! the one [`crate::stats::radial_psd`] estimates). For an isotropic surface, with `q` the
//! wavenumber in rad/m (`q = 2π/λ`):
//!
//! - the areal PSD `C(q) = ∫ ACF(r) exp(−i q·r) d²r` (m⁴), so that
//!   `Sq² = (2π)⁻² ∫ C d²q = (1/2π) ∫₀^∞ q C(q) dq`;
//! - the profile (1-D) PSD of a line along x, `C¹ᴰ(qx) = (1/2π) ∫ C(√(qx² + qy²)) dqy` (m³),
//!   with `Sq² = (1/2π) ∫_{−∞}^{∞} C¹ᴰ(qx) dqx`;
//! - the rms profile slope along x, `s_x² = (1/2π) ∫ qx² C¹ᴰ(qx) dqx = (2π)⁻² ∫ qx² C d²q =
//!   (1/4π) ∫₀^∞ q³ C(q) dq`: half the mean square areal gradient `(1/2π) ∫ q³ C dq`;
//! - a band filter of amplitude transmission `T(λ)` applied to the profiles passes
//!   `s_band² = (1/2π) ∫ qx² T(2π/|qx|)² C¹ᴰ(qx) dqx`.
//!
//! For `C = C0 q^-n` between `q_L = 2π/λ_long` and `q_S = 2π/λ_short` (zero outside):
//! `Sq² = C0/(2π) ∫ q^(1−n) dq` and `s_x² = C0/(4π) ∫ q^(3−n) dq` over `[q_L, q_S]`; `n = 4` puts
//! equal mean square slope in every octave (a self-affine surface of Hurst exponent 1).
//!
//! Discretely, the periodic map of `nx × ny` points holds the modes `q = (2π kx/Lx, 2π ky/Ly)`;
//! each gets a complex Gaussian amplitude of variance `C(|q|) nx ny / (dx dy)` (white noise of unit
//! variance times `√(C/(dx dy))`), so that the expected periodogram `dx dy |Z(q)|² / (nx ny)` is
//! `C(|q|)`, and `Sq² = Σ C(|q|) Δqx Δqy / (2π)²` over the modes, the discrete form of the above.

use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use crate::ops;
use crate::synth::{check_grid, filtered_noise, levelled_rms, positive_rms, scaled};
use ndarray::{Array2, Zip};
use std::f64::consts::PI;
use std::path::Path;

/// A measured radially averaged (isotropic) PSD `C(q)`, tabulated at increasing wavenumbers.
#[derive(Debug, Clone, PartialEq)]
pub struct RadialPsd {
    /// Wavenumbers, rad/m, strictly increasing and positive.
    q: Vec<f64>,
    /// `C(q)`, m⁴, non-negative.
    psd: Vec<f64>,
}

/// A conversion of a table's abscissa to the wavenumber q, rad/m.
type ToWavenumber = fn(f64) -> f64;

/// The columns a PSD table may name: the abscissa's header and its conversion to q (rad/m).
const ABSCISSAE: [(&str, ToWavenumber); 2] = [
    ("wavelength_mm", |l| 2.0 * PI / (l * 1e-3)),
    ("frequency_per_mm", |f| 2.0 * PI * f * 1e3),
];

/// The header of the PSD column: the areal isotropic PSD in m⁴.
const PSD_COLUMN: &str = "psd_m4";

/// The format's name in errors.
const TABLE: &str = "PSD table";

impl RadialPsd {
    /// A table of `(q, C(q))` pairs (rad/m, m⁴), in any order; at least two points, each
    /// finite, `q > 0`, `C ≥ 0`, no wavenumber twice.
    pub fn new(mut points: Vec<(f64, f64)>) -> Result<RadialPsd> {
        if points.len() < 2 {
            return Err(SurfaceError::Request(format!(
                "a PSD table needs at least two points, it has {}",
                points.len()
            )));
        }
        for &(q, c) in &points {
            if !(q.is_finite() && q > 0.0 && c.is_finite() && c >= 0.0) {
                return Err(SurfaceError::Request(format!(
                    "PSD point q = {q} rad/m, C = {c} m⁴: need a positive, finite wavenumber and \
                     a finite PSD >= 0"
                )));
            }
        }
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let Some(w) = points.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(SurfaceError::Request(format!(
                "the PSD table gives the wavenumber {} rad/m twice",
                w[0].0
            )));
        }
        let (q, psd) = points.into_iter().unzip();
        Ok(RadialPsd { q, psd })
    }

    /// Parse a PSD table (the format of [`RadialPsd::read`]); `path` names the source in errors.
    pub fn parse(text: &str, path: &Path) -> Result<RadialPsd> {
        let err = |line: usize, what: String| {
            SurfaceError::format(path, TABLE, format!("line {line}: {what}"))
        };
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let split = |l: &str| -> Vec<String> {
            l.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
                .filter(|s| !s.is_empty())
                .map(str::to_owned)
                .collect()
        };
        let (hl, header) = lines
            .next()
            .ok_or_else(|| err(1, "no header line and no data".into()))?;
        let header = split(header);
        let to_q = match header.as_slice() {
            [x, c] if c == PSD_COLUMN => ABSCISSAE
                .iter()
                .find(|(h, _)| h == x)
                .map(|(_, f)| *f)
                .ok_or_else(|| {
                    err(
                        hl,
                        format!(
                            "the first column is '{x}': name it wavelength_mm or frequency_per_mm"
                        ),
                    )
                })?,
            _ => {
                return Err(err(
                    hl,
                    format!(
                        "the header is '{}': expected two columns, wavelength_mm or \
                         frequency_per_mm, then {PSD_COLUMN}",
                        header.join(",")
                    ),
                ));
            }
        };
        let mut points = Vec::new();
        for (i, l) in lines {
            let cols = split(l);
            let nums: Vec<f64> = cols.iter().filter_map(|c| c.parse().ok()).collect();
            if cols.len() != 2 || nums.len() != 2 {
                return Err(err(i, format!("'{l}' is not two numbers")));
            }
            if !(nums[0].is_finite() && nums[0] > 0.0) {
                return Err(err(i, format!("the abscissa {} must be positive", nums[0])));
            }
            points.push((to_q(nums[0]), nums[1]));
        }
        RadialPsd::new(points).map_err(|e| SurfaceError::format(path, TABLE, e.to_string()))
    }

    /// Read a PSD table from a text file: `#` comments and blank lines are skipped; the first
    /// line is a header of two columns, `wavelength_mm` (λ in mm) or `frequency_per_mm` (1/λ in
    /// cycles per mm), then `psd_m4` (the areal isotropic PSD `C(q)` in m⁴, the module's
    /// convention); each further line two numbers separated by a comma, semicolon or spaces.
    pub fn read(path: &Path) -> Result<RadialPsd> {
        let text = std::fs::read_to_string(path).map_err(|e| SurfaceError::io(path, e))?;
        RadialPsd::parse(&text, path)
    }

    /// `C(q)` (m⁴): interpolated linearly in log q and log C between the tabulated points
    /// (linearly in C where a neighbour is zero), zero outside the table.
    pub fn at(&self, q: f64) -> f64 {
        let (first, last) = (self.q[0], self.q[self.q.len() - 1]);
        if !(q >= first && q <= last) {
            return 0.0;
        }
        let i = self
            .q
            .partition_point(|&v| v <= q)
            .clamp(1, self.q.len() - 1);
        let (q0, q1, c0, c1) = (self.q[i - 1], self.q[i], self.psd[i - 1], self.psd[i]);
        if c0 > 0.0 && c1 > 0.0 {
            let t = (q / q0).ln() / (q1 / q0).ln();
            (c0.ln() + t * (c1 / c0).ln()).exp()
        } else {
            c0 + (q - q0) / (q1 - q0) * (c1 - c0)
        }
    }

    /// The tabulated range of wavelengths, m: (shortest, longest).
    pub fn wavelengths(&self) -> (f64, f64) {
        (2.0 * PI / self.q[self.q.len() - 1], 2.0 * PI / self.q[0])
    }
}

/// The spectrum of a [`PsdSurface`].
#[derive(Debug, Clone, PartialEq)]
pub enum Spectrum {
    /// `C(q) ∝ q^-exponent` for wavelengths between `short` and `long` (m), zero outside. It has
    /// no magnitude of its own: the surface's [`Target`] sets it.
    PowerLaw {
        exponent: f64,
        long: f64,
        short: f64,
    },
    /// A measured radial PSD.
    Radial(RadialPsd),
}

impl Spectrum {
    /// `C(q)` at wavenumber `q` (rad/m): m⁴ for a table, relative (`(q λ_long / 2π)^-n`) for a
    /// power law.
    pub fn psd(&self, q: f64) -> f64 {
        match self {
            Spectrum::PowerLaw {
                exponent,
                long,
                short,
            } => {
                let (q_long, q_short) = (2.0 * PI / long, 2.0 * PI / short);
                // A mode exactly at a cutoff is inside: 1e-9 absorbs the rounding of 2π/L.
                if q >= q_long * (1.0 - 1e-9) && q <= q_short * (1.0 + 1e-9) {
                    (q / q_long).powf(-exponent)
                } else {
                    0.0
                }
            }
            Spectrum::Radial(table) => table.at(q),
        }
    }
}

/// What sets the heights' magnitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// Sq after levelling, m.
    Sq(f64),
    /// rms slope along x after levelling (forward differences), rad.
    SlopeX(f64),
    /// The PSD's own magnitude (a measured table only): the heights are the filtered noise as
    /// it comes, so Sq and the slope are those of the PSD within one realisation's spread.
    AsGiven,
}

/// Request for a periodic Gaussian random surface with a given PSD (SI units: metres).
#[derive(Debug, Clone, PartialEq)]
pub struct PsdSurface {
    pub spectrum: Spectrum,
    pub target: Target,
    /// Points along x and y.
    pub nx: usize,
    pub ny: usize,
    /// Spacings along x and y, m.
    pub dx: f64,
    pub dy: f64,
    /// Seed of the random numbers (the same noise as [`crate::synth::GaussianSurface`]'s).
    pub seed: u64,
}

impl PsdSurface {
    /// Synthesise the surface. Fails, saying why, for a spacing or target that is not positive
    /// and finite, a power law whose long wavelength exceeds the map's shorter side or whose
    /// short wavelength is under two spacings (or not below the long one), a power law without a
    /// target, and a spectrum with no power at any of the map's modes.
    pub fn generate(&self) -> Result<HeightMap> {
        self.check()?;
        let amplitude = self.filter();
        if !amplitude.iter().any(|&a| a > 0.0) {
            return Err(SurfaceError::Request(format!(
                "the PSD has no power at the wavelengths a {} × {} mm map at {} mm spacing holds \
                 ({} to {} mm)",
                mm(self.nx as f64 * self.dx),
                mm(self.ny as f64 * self.dy),
                mm(self.dx.max(self.dy)),
                mm(2.0 * self.dx.max(self.dy)),
                mm((self.nx as f64 * self.dx).max(self.ny as f64 * self.dy))
            )));
        }
        let raw = filtered_noise(&amplitude, self.nx, self.ny, self.dx, self.dy, self.seed)?;
        let scale = match self.target {
            Target::Sq(sq) => sq / levelled_rms(&raw)?,
            Target::SlopeX(s) => s / positive_rms(mean_square_slope_x(&raw)?, &raw)?,
            Target::AsGiven => 1.0,
        };
        let mut map = scaled(raw, scale)?;
        let mut extra = match &self.spectrum {
            Spectrum::PowerLaw {
                exponent,
                long,
                short,
            } => vec![
                ("psd".into(), format!("q^-{exponent}")),
                ("long_wavelength_m".into(), format!("{long:e}")),
                ("short_wavelength_m".into(), format!("{short:e}")),
            ],
            Spectrum::Radial(t) => {
                let (s, l) = t.wavelengths();
                vec![
                    ("psd".into(), "table".into()),
                    ("table_wavelengths_m".into(), format!("{s:e} to {l:e}")),
                ]
            }
        };
        match self.target {
            Target::Sq(sq) => extra.push(("sq_m".into(), format!("{sq:e}"))),
            Target::SlopeX(s) => extra.push(("rms_slope_x_rad".into(), format!("{s:e}"))),
            Target::AsGiven => {}
        }
        extra.push(("seed".into(), self.seed.to_string()));
        map.meta.extra = extra;
        Ok(map)
    }

    fn check(&self) -> Result<()> {
        for (name, v) in [("dx", self.dx), ("dy", self.dy)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(SurfaceError::Request(format!(
                    "{name} = {v} m must be a positive, finite length"
                )));
            }
        }
        check_grid(self.nx, self.ny)?;
        match self.target {
            Target::Sq(v) | Target::SlopeX(v) if !(v.is_finite() && v > 0.0) => {
                return Err(SurfaceError::Request(format!(
                    "the requested rms height or slope {v} must be positive and finite"
                )));
            }
            _ => {}
        }
        if let Spectrum::PowerLaw {
            exponent,
            long,
            short,
        } = self.spectrum
        {
            if self.target == Target::AsGiven {
                return Err(SurfaceError::Request(
                    "a power-law PSD has no magnitude of its own: request an rms height or an rms \
                     slope"
                        .into(),
                ));
            }
            if !exponent.is_finite() {
                return Err(SurfaceError::Request(format!(
                    "the PSD exponent {exponent} must be finite"
                )));
            }
            if !(short.is_finite() && long.is_finite() && short > 0.0 && short < long) {
                return Err(SurfaceError::Request(format!(
                    "the wavelengths {} mm (short) and {} mm (long) must be positive with the \
                     short one below the long one",
                    mm(short),
                    mm(long)
                )));
            }
            let side = (self.nx as f64 * self.dx).min(self.ny as f64 * self.dy);
            if long > side * (1.0 + 1e-9) {
                return Err(SurfaceError::Request(format!(
                    "the long wavelength {} mm exceeds the map's shorter side, {} mm: a periodic \
                     map holds no longer wave",
                    mm(long),
                    mm(side)
                )));
            }
            let spacing = self.dx.max(self.dy);
            if short < 2.0 * spacing * (1.0 - 1e-9) {
                return Err(SurfaceError::Request(format!(
                    "the short wavelength {} mm is under two spacings ({} mm): the grid cannot \
                     hold it",
                    mm(short),
                    mm(2.0 * spacing)
                )));
            }
        }
        Ok(())
    }

    /// `√(C(|q|)/(dx dy))` on the half spectrum `[kx, ky]` (module docs).
    fn filter(&self) -> Array2<f64> {
        let (nx, ny) = (self.nx, self.ny);
        let (dqx, dqy) = (
            2.0 * PI / (nx as f64 * self.dx),
            2.0 * PI / (ny as f64 * self.dy),
        );
        let area = self.dx * self.dy;
        let mut a = Array2::zeros((nx / 2 + 1, ny));
        Zip::indexed(&mut a).par_for_each(|(kx, ky), v| {
            let fy = if ky <= ny / 2 {
                ky as f64
            } else {
                ky as f64 - ny as f64
            };
            let q = (kx as f64 * dqx).hypot(fy * dqy);
            *v = (self.spectrum.psd(q) / area).sqrt();
        });
        a
    }
}

/// Length in mm for messages, to four significant digits.
fn mm(m: f64) -> String {
    let v = m * 1e3;
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let scale = 10f64.powi(3 - v.abs().log10().floor() as i32);
    format!("{}", (v * scale).round() / scale)
}

/// The mean square forward-difference slope along x of `map` less the levelling plane's x slope,
/// over the pairs of neighbouring valid points within each row.
fn mean_square_slope_x(map: &HeightMap) -> Result<f64> {
    let tilt = ops::fit_plane(map)?.slope_x;
    let dx = map.dx();
    let (sum, n) = ops::per_row(map.heights(), |_, row| {
        row.iter()
            .zip(row.iter().skip(1))
            .map(|(z0, z1)| (z1 - z0) / dx - tilt)
            .filter(|s| !s.is_nan())
            .fold((0.0, 0usize), |(s, n), v| (s + v * v, n + 1))
    })
    .into_iter()
    .fold((0.0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    if n == 0 {
        return Err(SurfaceError::Invalid(
            "no two neighbouring valid points along x for a slope".into(),
        ));
    }
    Ok(sum / n as f64)
}

/// The rms slope along x of `map` after levelling: forward differences within each row between
/// neighbouring valid points, less the least-squares plane's x slope (the slope a
/// [`Target::SlopeX`] sets).
pub fn rms_slope_x(map: &HeightMap) -> Result<f64> {
    Ok(mean_square_slope_x(map)?.sqrt())
}
