//! Synthesis of periodic Gaussian random surfaces by spectral filtering, and the roughness series
//! of the NIST epoxy samples.
//!
//! Method (the standard FFT filter, e.g. Garcia & Stoll, Phys. Rev. Lett. 52, 1798 (1984);
//! Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)): white Gaussian noise on the grid is
//! transformed, multiplied by the square root of the power spectral density, and transformed back.
//! The PSD is the discrete Fourier transform of the requested autocorrelation sampled on the
//! periodic grid (distances taken to the nearest periodic image), so the expected autocorrelation
//! of the result is exactly that periodic ACF at the grid points. The mean (zero-frequency term)
//! is removed, and the heights are scaled so that Sq after least-squares levelling, as
//! [`crate::stats`] computes it, equals the request to rounding. The map stays periodic: the
//! plane is not subtracted, so the raw rms may exceed `sq` by the tiny tilt of one realisation.

use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use crate::ops;
use gonio_fft::fft2;
use ndarray::{Array2, Zip};
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64;
use rayon::prelude::*;

/// Shape of the autocorrelation function `C(r)` of a random surface of rms height `sigma` and
/// correlation length `T`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Acf {
    /// `C(r) = sigma² exp(-r²/T²)`: rms slope (total) `2 sigma / T`, ISO Sal = `T √(ln 5)`.
    Gaussian,
    /// `C(r) = sigma² exp(-r/T)`: a fractal-like surface whose rms slope grows without bound as
    /// the spacing shrinks; ISO Sal = `T ln 5`.
    Exponential,
}

impl Acf {
    /// `C(r)/sigma²` at distance `r` for correlation length `t` (same units).
    pub fn normalised(self, r: f64, t: f64) -> f64 {
        match self {
            Acf::Gaussian => (-(r / t).powi(2)).exp(),
            Acf::Exponential => (-r / t).exp(),
        }
    }
}

/// Request for a periodic Gaussian random surface (SI units: metres).
#[derive(Debug, Clone, PartialEq)]
pub struct GaussianSurface {
    /// rms height Sq, metres.
    pub sq: f64,
    /// Correlation length T, metres.
    pub corr_length: f64,
    /// Shape of the autocorrelation.
    pub acf: Acf,
    /// Points along x.
    pub nx: usize,
    /// Points along y.
    pub ny: usize,
    /// Spacing along x, metres.
    pub dx: f64,
    /// Spacing along y, metres.
    pub dy: f64,
    /// Seed of the random numbers: the same request and seed give the same map on any machine
    /// and thread count.
    pub seed: u64,
}

impl GaussianSurface {
    /// The request for a surface with a Gaussian ACF on a square `n × n` grid of spacing `dx`
    /// (`sq`, `corr_length` and `dx` in metres).
    pub fn square(sq: f64, corr_length: f64, n: usize, dx: f64, seed: u64) -> GaussianSurface {
        GaussianSurface {
            sq,
            corr_length,
            acf: Acf::Gaussian,
            nx: n,
            ny: n,
            dx,
            dy: dx,
            seed,
        }
    }

    /// Synthesise the surface. Fails if a length is not positive and finite or the grid has
    /// fewer than 2 points along an axis.
    pub fn generate(&self) -> Result<HeightMap> {
        self.check()?;
        let raw = filtered_noise(
            &self.filter(),
            self.nx,
            self.ny,
            self.dx,
            self.dy,
            self.seed,
        )?;
        let rms = levelled_rms(&raw)?;
        let mut map = scaled(raw, self.sq / rms)?;
        map.meta.extra = vec![
            ("acf".into(), format!("{:?}", self.acf).to_lowercase()),
            ("sq_m".into(), format!("{:e}", self.sq)),
            ("corr_length_m".into(), format!("{:e}", self.corr_length)),
            ("seed".into(), self.seed.to_string()),
        ];
        Ok(map)
    }

    fn check(&self) -> Result<()> {
        for (name, v) in [
            ("sq", self.sq),
            ("corr_length", self.corr_length),
            ("dx", self.dx),
            ("dy", self.dy),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(SurfaceError::Invalid(format!(
                    "{name} = {v} m must be a positive, finite length"
                )));
            }
        }
        check_grid(self.nx, self.ny)
    }

    /// Square root of the PSD on the half spectrum: the DFT of the ACF sampled at the nearest
    /// periodic image of each grid offset. Tiny negative values (truncation of the ACF at the
    /// period) are clipped to zero.
    fn filter(&self) -> Array2<f64> {
        let (nx, ny) = (self.nx, self.ny);
        let wrap = |i: usize, n: usize| i.min(n - i) as f64;
        let mut acf = Array2::zeros((ny, nx));
        Zip::indexed(&mut acf).par_for_each(|(iy, ix), c| {
            let r = (wrap(ix, nx) * self.dx).hypot(wrap(iy, ny) * self.dy);
            *c = self.acf.normalised(r, self.corr_length);
        });
        fft2::forward(acf.view())
            .data
            .mapv(|s| s.re.max(0.0).sqrt())
    }
}

/// Check a grid of `nx × ny` points: at least 2 × 2, at most [`crate::heightmap::MAX_POINTS`].
pub(crate) fn check_grid(nx: usize, ny: usize) -> Result<()> {
    if nx < 2 || ny < 2 {
        return Err(SurfaceError::Invalid(format!(
            "grid {nx} × {ny} is too small: need at least 2 × 2 points"
        )));
    }
    if nx.saturating_mul(ny) > crate::heightmap::MAX_POINTS {
        return Err(SurfaceError::Invalid(format!(
            "grid {nx} × {ny} exceeds the limit of {} points",
            crate::heightmap::MAX_POINTS
        )));
    }
    Ok(())
}

/// Independent standard normal numbers on an `nx × ny` grid; row `iy` comes from its own PCG
/// stream, so that rows can be drawn in parallel and the result does not depend on the thread
/// count.
fn white_noise(nx: usize, ny: usize, seed: u64) -> Array2<f64> {
    let mut noise = vec![0.0; nx * ny];
    noise.par_chunks_mut(nx).enumerate().for_each(|(iy, row)| {
        let mut rng = Pcg64::new(u128::from(seed) << 64 | 0x5851_f42d, iy as u128);
        row.iter_mut()
            .for_each(|v| *v = StandardNormal.sample(&mut rng));
    });
    Array2::from_shape_vec((ny, nx), noise).expect("shape matches the length")
}

/// White noise of `seed` filtered by `amplitude` (the square root of the PSD on the half
/// spectrum, shape `(nx/2 + 1, ny)` as [`fft2::forward`] lays it out), with the zero-frequency
/// term removed: a periodic map of mean zero, not yet scaled.
pub(crate) fn filtered_noise(
    amplitude: &Array2<f64>,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    seed: u64,
) -> Result<HeightMap> {
    let mut spectrum = fft2::forward(white_noise(nx, ny, seed).view());
    Zip::from(&mut spectrum.data)
        .and(amplitude)
        .par_for_each(|s, &a| *s *= a);
    spectrum.data[[0, 0]] = Default::default();
    HeightMap::new(fft2::inverse(spectrum), dx, dy)
}

/// The rms height of `raw` about its least-squares plane (Sq after levelling, as [`crate::stats`]
/// computes it); an error when it is zero (a grid too small to hold a random surface).
pub(crate) fn levelled_rms(raw: &HeightMap) -> Result<f64> {
    let plane = ops::fit_plane(raw)?;
    let (dx, dy) = (raw.dx(), raw.dy());
    let residual: f64 = ops::per_row(raw.heights(), |iy, row| {
        let y = iy as f64 * dy;
        row.iter()
            .enumerate()
            .map(|(ix, z)| (z - plane.height(ix as f64 * dx, y)).powi(2))
            .sum::<f64>()
    })
    .into_iter()
    .sum();
    positive_rms(residual / (raw.nx() * raw.ny()) as f64, raw)
}

/// `√mean_square`, or an error when it is zero.
pub(crate) fn positive_rms(mean_square: f64, raw: &HeightMap) -> Result<f64> {
    if mean_square > 0.0 {
        Ok(mean_square.sqrt())
    } else {
        Err(SurfaceError::Invalid(format!(
            "a {} × {} grid is too small to hold a random surface",
            raw.nx(),
            raw.ny()
        )))
    }
}

/// `raw` times `scale`, marked as gonio's synthetic map (the caller adds its parameters).
pub(crate) fn scaled(raw: HeightMap, scale: f64) -> Result<HeightMap> {
    let (dx, dy) = (raw.dx(), raw.dy());
    let mut heights = raw.into_heights();
    heights.par_mapv_inplace(|z| z * scale);
    let mut map = HeightMap::new(heights, dx, dy)?;
    map.meta.instrument = Some("gonio synthetic".into());
    Ok(map)
}

/// Sq of the NIST epoxy roughness series, metres: 3, 50, 150, 201, 400 and 805 nm.
///
/// The NIST study of clear epoxy samples of graded roughness spans Sq from 3 nm (nearly
/// smooth) to 805 nm and includes 3, 150, 201 and 805 nm; 50 and 400 nm fill the gaps on a roughly
/// logarithmic scale (the same list as the default of `gonio study`).
pub const EPOXY_SQ_M: [f64; 6] = [3e-9, 50e-9, 150e-9, 201e-9, 400e-9, 805e-9];

/// Default correlation length of the epoxy series: 6 µm (Gaussian ACF).
pub const EPOXY_CORR_LENGTH_M: f64 = 6e-6;
/// Default grid of the epoxy series: 1024 × 1024 points...
pub const EPOXY_N: usize = 1024;
/// ...at 0.5 µm spacing (a 512 µm square, about 85 correlation lengths across, and 12 points
/// per correlation length, so that the forward differences of [`crate::stats`] see 99.8% of the
/// true rms slope).
pub const EPOXY_SPACING_M: f64 = 0.5e-6;

/// The request for the epoxy sample of rms height `sq` metres with the default correlation
/// length, grid and a Gaussian ACF.
pub fn epoxy_surface(sq: f64, seed: u64) -> GaussianSurface {
    GaussianSurface::square(sq, EPOXY_CORR_LENGTH_M, EPOXY_N, EPOXY_SPACING_M, seed)
}

/// The whole epoxy series ([`EPOXY_SQ_M`]), synthesised with the same seed (so the samples
/// differ only in scale) and returned as `(sq, map)` pairs.
pub fn epoxy_series(seed: u64) -> Result<Vec<(f64, HeightMap)>> {
    EPOXY_SQ_M
        .iter()
        .map(|&sq| Ok((sq, epoxy_surface(sq, seed).generate()?)))
        .collect()
}
