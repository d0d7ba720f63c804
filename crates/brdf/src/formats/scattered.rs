//! From scattered measurements to a full table: a smoothing interpolation fitted to the samples
//! and resampled on the table's grid (as NIST did with the painted-sample tables of Davidson).
//!
//! Each sample `(wi, wo, f)` is placed at three coordinates in which an isotropic BRDF is smooth:
//! `u = sqrt(theta_h / 90°)` (the table's own spacing, which spreads the specular peak), and
//! `(t cos p, t sin p)` with `t = theta_d / 90°` and `p = phi_d` folded into [0, 180°] by mirror
//! symmetry about the plane of incidence (`phi_d ~ 360° - phi_d`), which an isotropic surface
//! has. The polar form keeps `theta_d = 0`, where phi_d is undefined, a single point.
//! Reciprocity is not assumed: folding the Cornell paints by it as well
//! (`phi_d ~ phi_d + 180°`) tripled the held-out error, so those measurements are not
//! reciprocal within their scatter.
//! At any point the value is the local linear regression (locally weighted least squares of a
//! plane, W. S. Cleveland, "Robust locally weighted regression and smoothing scatterplots",
//! JASA 74, 1979) of `ln(f + eps)` on the samples, with Gaussian weights of per-coordinate
//! bandwidths and a small ridge on the slopes, clamped to the range of the samples that weigh
//! in (so that a plane never extrapolates into a spike where samples are sparse). `eps` (1% of
//! the channel's median) keeps zeros finite. Unless given, the bandwidths are chosen by
//! leave-one-out cross-validation of the channel mean from a small grid. The fit residual at
//! the measured points is reported.

use crate::error::{BrdfError, Result};
use crate::table::{BrdfTable, Channels, HalfDiff, Provenance, Resolution, TableBuilder};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

/// One measured geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Direction toward the light (unit, local frame).
    pub wi: DVec3,
    /// Direction toward the detector.
    pub wo: DVec3,
    /// f in 1/sr per channel.
    pub values: Vec<f64>,
}

/// Relative residuals of the fit at the measured points.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FitResidual {
    /// Median over samples and channels of `|fit - f| / f`, for values above a floor.
    pub median_relative: f64,
    /// Root mean square of the same relative residuals.
    pub rms_relative: f64,
    /// Number of (sample, channel) values counted.
    pub count: usize,
}

/// Values below this (1/sr, 0.3% of a white Lambertian's 1/π) are left out of residuals: the
/// Cornell files print 6 decimals and their smallest values scatter by tens of per cent.
pub const NOISE_FLOOR_PER_SR: f64 = 1e-3;

/// Bandwidths of the kernel in the (u, t cos p, t sin p) coordinates.
pub type Bandwidths = [f64; 3];

/// A smoothing interpolant of scattered samples.
pub struct ScatteredFit {
    points: Vec<[f64; 3]>,
    /// `logs[i * nc + c]`: ln(f + eps_c) of sample i, channel c.
    logs: Vec<f64>,
    eps: Vec<f64>,
    nc: usize,
    bw: Bandwidths,
    log_range: (f64, f64),
}

/// The (u, t cos p, t sin p) coordinates of a pair of directions.
pub fn coordinates(wi: DVec3, wo: DVec3) -> Option<[f64; 3]> {
    let a = HalfDiff::from_dirs(wi, wo)?;
    Some(coordinates_of(&a))
}

fn coordinates_of(a: &HalfDiff) -> [f64; 3] {
    let mut p = a.phi_d.rem_euclid(2.0 * PI);
    if p > PI {
        p = 2.0 * PI - p;
    }
    let t = a.theta_d / FRAC_PI_2;
    [
        (a.theta_h.max(0.0) / FRAC_PI_2).sqrt(),
        t * p.cos(),
        t * p.sin(),
    ]
}

/// Gaussian kernel weight, cut at 3.5 bandwidths.
#[inline]
fn kernel(x: &[f64; 3], y: &[f64; 3], bw: &Bandwidths) -> f64 {
    let mut q = 0.0;
    for k in 0..3 {
        let d = (x[k] - y[k]) / bw[k];
        q += d * d;
    }
    if q > 12.25 { 0.0 } else { (-0.5 * q).exp() }
}

impl ScatteredFit {
    /// Fit the samples (all with the same number of channels, at least 20 samples).
    pub fn new(samples: &[Sample], bandwidths: Option<Bandwidths>) -> Result<ScatteredFit> {
        let nc = samples.first().map_or(0, |s| s.values.len());
        if samples.len() < 20 || nc == 0 {
            return Err(BrdfError::Invalid(format!(
                "{} samples of {nc} channels: a smoothing fit needs at least 20 samples",
                samples.len()
            )));
        }
        let mut points = Vec::with_capacity(samples.len());
        let mut kept = Vec::with_capacity(samples.len());
        for s in samples {
            if s.values.len() != nc {
                return Err(BrdfError::Invalid(
                    "samples have different channel counts".into(),
                ));
            }
            if s.wi.z <= 0.0 || s.wo.z <= 0.0 || s.values.iter().any(|v| !v.is_finite()) {
                continue;
            }
            if let Some(x) = coordinates(s.wi, s.wo) {
                points.push(x);
                kept.push(s);
            }
        }
        let eps: Vec<f64> = (0..nc)
            .map(|c| {
                let mut v: Vec<f64> = kept.iter().map(|s| s.values[c].max(0.0)).collect();
                v.sort_by(f64::total_cmp);
                (0.01 * v[v.len() / 2]).max(1e-9)
            })
            .collect();
        let logs: Vec<f64> = kept
            .iter()
            .flat_map(|s| {
                s.values
                    .iter()
                    .zip(&eps)
                    .map(|(v, e)| (v.max(0.0) + e).ln())
            })
            .collect();
        let lo = logs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = logs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        // The channel mean, on which the bandwidths are cross-validated.
        let means: Vec<f64> = kept
            .iter()
            .map(|s| s.values.iter().map(|v| v.max(0.0)).sum::<f64>() / nc as f64)
            .collect();
        let mut sorted = means.clone();
        sorted.sort_by(f64::total_cmp);
        let eps_mean = (0.01 * sorted[sorted.len() / 2]).max(1e-9);
        let z_mean: Vec<f64> = means.iter().map(|m| (m + eps_mean).ln()).collect();
        let mut fit = ScatteredFit {
            points,
            logs,
            eps,
            nc,
            bw: [0.1; 3],
            log_range: (lo, hi),
        };
        fit.bw = match bandwidths {
            Some(b) => b,
            None => fit.cross_validated_bandwidths(&z_mean),
        };
        Ok(fit)
    }

    /// The bandwidths in use.
    pub fn bandwidths(&self) -> Bandwidths {
        self.bw
    }

    /// Number of channels.
    pub fn channel_count(&self) -> usize {
        self.nc
    }

    /// Leave-one-out choice of bandwidths on `z` = ln(mean f + eps), the channel mean.
    fn cross_validated_bandwidths(&self, z: &[f64]) -> Bandwidths {
        let mut best = ([0.1; 3], f64::INFINITY);
        for hu in [0.03, 0.05, 0.08, 0.12] {
            for ht in [0.05, 0.08, 0.13] {
                for hp in [0.05, 0.1, 0.2] {
                    let bw = [hu, ht, hp];
                    let err: f64 = (0..self.points.len())
                        .into_par_iter()
                        .map(|i| {
                            let mut out = [0.0];
                            let ok = self.local_linear(
                                &self.points[i],
                                &bw,
                                Some(i),
                                |j| &z[j..j + 1],
                                &mut out,
                            );
                            if ok {
                                (out[0] - z[i]).abs()
                            } else {
                                z[i].abs()
                            }
                        })
                        .sum();
                    if err < best.1 {
                        best = (bw, err);
                    }
                }
            }
        }
        best.0
    }

    /// Local linear regression at `x` of the per-sample vectors `z(j)`, leaving out sample
    /// `skip`; false when no sample is near.
    fn local_linear<'a>(
        &self,
        x: &[f64; 3],
        bw: &Bandwidths,
        skip: Option<usize>,
        z: impl Fn(usize) -> &'a [f64],
        out: &mut [f64],
    ) -> bool {
        let m = out.len();
        // Normal equations of z ≈ b0 + b·(y - x)/bw, accumulated as a 4×4 matrix and 4×m right
        // sides.
        let mut a = [[0.0f64; 4]; 4];
        let mut rhs = vec![0.0f64; 4 * m];
        let mut wsum = 0.0;
        // Range of the values of the well-weighted samples: the plane may not extrapolate
        // beyond it.
        let mut lo = vec![f64::INFINITY; m];
        let mut hi = vec![f64::NEG_INFINITY; m];
        for (j, y) in self.points.iter().enumerate() {
            if Some(j) == skip {
                continue;
            }
            let w = kernel(x, y, bw);
            if w == 0.0 {
                continue;
            }
            wsum += w;
            let d = [
                1.0,
                (y[0] - x[0]) / bw[0],
                (y[1] - x[1]) / bw[1],
                (y[2] - x[2]) / bw[2],
            ];
            for (row, dr) in a.iter_mut().zip(d) {
                for (x, dc) in row.iter_mut().zip(d) {
                    *x += w * dr * dc;
                }
            }
            for (k, zk) in z(j).iter().enumerate() {
                for r in 0..4 {
                    rhs[r * m + k] += w * d[r] * zk;
                }
                if w > 0.05 {
                    lo[k] = lo[k].min(*zk);
                    hi[k] = hi[k].max(*zk);
                }
            }
        }
        if wsum < 1e-6 {
            return false;
        }
        // Ridge on the slopes: a plane only where the samples support one.
        for (r, row) in a.iter_mut().enumerate().skip(1) {
            row[r] += 0.05 * wsum;
        }
        match solve4(a, &mut rhs, m) {
            Some(()) => {
                for (k, o) in out.iter_mut().enumerate() {
                    *o = if lo[k] <= hi[k] {
                        rhs[k].clamp(lo[k], hi[k])
                    } else {
                        rhs[k]
                    };
                }
                true
            }
            None => false,
        }
    }

    /// The smoothed f (1/sr) per channel at a pair of directions; zero below the horizon and far
    /// from every sample.
    pub fn predict(&self, wi: DVec3, wo: DVec3, out: &mut [f64]) {
        out.fill(0.0);
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return;
        }
        if let Some(x) = coordinates(wi, wo) {
            self.predict_at(&x, out);
        }
    }

    fn predict_at(&self, x: &[f64; 3], out: &mut [f64]) {
        let nc = self.nc;
        // Widen the kernel where the samples are sparse (up to 8 times).
        let mut bw = self.bw;
        for _ in 0..4 {
            if self.local_linear(x, &bw, None, |j| &self.logs[j * nc..(j + 1) * nc], out) {
                let (lo, hi) = self.log_range;
                for (o, e) in out.iter_mut().zip(&self.eps) {
                    *o = (o.clamp(lo, hi).exp() - e).max(0.0);
                }
                return;
            }
            bw = bw.map(|b| 2.0 * b);
        }
        out.fill(0.0);
    }

    /// Relative residuals of the fit at the samples it was fitted to (each predicted with all
    /// samples, itself included), over values of at least [`NOISE_FLOOR_PER_SR`].
    pub fn residual(&self, samples: &[Sample]) -> FitResidual {
        residual_of(samples, NOISE_FLOOR_PER_SR, |s, out| {
            self.predict(s.wi, s.wo, out)
        })
    }

    /// Resample on a table grid (isotropic) with the given channels.
    pub fn to_table(
        &self,
        res: Resolution,
        channels: Channels,
        provenance: Provenance,
    ) -> Result<BrdfTable> {
        if channels.count() != self.nc {
            return Err(BrdfError::Invalid(format!(
                "{} channels requested for a fit of {}",
                channels.count(),
                self.nc
            )));
        }
        let mut b = TableBuilder::new(res, channels)?.with_provenance(provenance);
        b.fill(|cell, out| self.predict_at(&coordinates_of(&cell.angles), out));
        b.build()
    }
}

/// Import measured samples read from `path`: smooth them with a [`ScatteredFit`] and resample it
/// on an isotropic table. The table's `provenance` gains the fit's residual at the measured
/// points (`fit_median_relative_residual`, `fit_rms_relative_residual`), its bandwidths
/// (`fit_bandwidths_u_t_p`) and the sample count (`samples`); the residual is also returned.
pub fn import_samples(
    path: &Path,
    samples: &[Sample],
    channels: Channels,
    res: Resolution,
    mut provenance: Provenance,
) -> Result<(BrdfTable, FitResidual)> {
    let fit =
        ScatteredFit::new(samples, None).map_err(|e| BrdfError::format(path, e.to_string()))?;
    let residual = fit.residual(samples);
    let extra: [(&str, serde_json::Value); 4] = [
        (
            "fit_median_relative_residual",
            residual.median_relative.into(),
        ),
        ("fit_rms_relative_residual", residual.rms_relative.into()),
        ("fit_bandwidths_u_t_p", fit.bandwidths().to_vec().into()),
        ("samples", samples.len().into()),
    ];
    provenance
        .extra
        .extend(extra.map(|(key, value)| (key.to_string(), value)));
    Ok((fit.to_table(res, channels, provenance)?, residual))
}

/// Relative residuals of any prediction against samples, over the (sample, channel) values of
/// at least `floor_per_sr` (below it measurements are at their noise level).
pub fn residual_of(
    samples: &[Sample],
    floor_per_sr: f64,
    predict: impl Fn(&Sample, &mut [f64]) + Sync,
) -> FitResidual {
    let nc = samples.first().map_or(0, |s| s.values.len());
    let mut rel: Vec<f64> = samples
        .par_iter()
        .flat_map_iter(|s| {
            let mut out = vec![0.0; nc];
            predict(s, &mut out);
            (0..nc)
                .filter(|&c| s.values[c] >= floor_per_sr && s.values[c] > 0.0)
                .map(|c| ((out[c] - s.values[c]) / s.values[c]).abs())
                .collect::<Vec<_>>()
        })
        .collect();
    rel.sort_by(f64::total_cmp);
    let count = rel.len();
    FitResidual {
        median_relative: if count > 0 { rel[count / 2] } else { f64::NAN },
        rms_relative: (rel.iter().map(|r| r * r).sum::<f64>() / count.max(1) as f64).sqrt(),
        count,
    }
}

/// Solve the symmetric 4×4 system `a x = rhs` for `m` right-hand sides stored row-wise in `rhs`
/// (`rhs[r * m + k]`), in place, by Gaussian elimination with partial pivoting.
fn solve4(mut a: [[f64; 4]; 4], rhs: &mut [f64], m: usize) -> Option<()> {
    for col in 0..4 {
        let piv = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-12 {
            return None;
        }
        if piv != col {
            a.swap(piv, col);
            for k in 0..m {
                rhs.swap(piv * m + k, col * m + k);
            }
        }
        for r in col + 1..4 {
            let f = a[r][col] / a[col][col];
            if f == 0.0 {
                continue;
            }
            let pivot_row = a[col];
            for (x, p) in a[r][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            for k in 0..m {
                rhs[r * m + k] -= f * rhs[col * m + k];
            }
        }
    }
    for col in (0..4).rev() {
        for k in 0..m {
            let mut v = rhs[col * m + k];
            for c in col + 1..4 {
                v -= a[col][c] * rhs[c * m + k];
            }
            rhs[col * m + k] = v / a[col][col];
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::coords::dir;

    /// A smooth isotropic BRDF sampled at scattered geometries is recovered between them.
    #[test]
    fn recovers_a_smooth_brdf_between_samples() {
        let f = |wi: DVec3, wo: DVec3| {
            let h = (wi + wo).normalize();
            0.1 + 2.0 * (-(1.0 - h.z * h.z) / (h.z * h.z) / 0.09).exp()
        };
        let mut samples = vec![];
        for ti in [10.0f64, 25.0, 40.0, 55.0, 70.0] {
            for ts in (0..9).map(|k| 5.0 + 9.0 * k as f64) {
                for ps in (0..12).map(|k| 180.0 - 15.0 * k as f64) {
                    let wi = dir(ti.to_radians(), 0.0);
                    let wo = dir(ts.to_radians(), ps.to_radians());
                    samples.push(Sample {
                        wi,
                        wo,
                        values: vec![f(wi, wo)],
                    });
                }
            }
        }
        let held: Vec<Sample> = samples.iter().step_by(7).cloned().collect();
        let train: Vec<Sample> = samples
            .iter()
            .enumerate()
            .filter(|(i, _)| i % 7 != 0)
            .map(|(_, s)| s.clone())
            .collect();
        let fit = ScatteredFit::new(&train, None).unwrap();
        let r = residual_of(&held, 1e-3, |s, out| fit.predict(s.wi, s.wo, out));
        assert!(
            r.median_relative < 0.05,
            "{r:?} with bandwidths {:?}",
            fit.bandwidths()
        );
    }

    #[test]
    fn solve4_solves() {
        let a = [
            [4.0, 1.0, 0.0, 0.5],
            [1.0, 3.0, 0.2, 0.0],
            [0.0, 0.2, 2.0, 0.1],
            [0.5, 0.0, 0.1, 1.0],
        ];
        let x = [1.0, -2.0, 0.5, 3.0];
        let mut rhs: Vec<f64> = (0..4)
            .map(|r| (0..4).map(|c| a[r][c] * x[c]).sum())
            .collect();
        solve4(a, &mut rhs, 1).unwrap();
        for k in 0..4 {
            assert!((rhs[k] - x[k]).abs() < 1e-12);
        }
    }
}
