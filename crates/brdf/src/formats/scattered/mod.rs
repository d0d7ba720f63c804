//! From scattered measurements to a full table: a smoothing interpolation fitted to the samples
//! and resampled on the table's grid (as NIST did with the painted-sample tables of Davidson),
//! on top of a physically based model of the same data ([`super::lobe_model`]) that the table
//! follows where the measurement says nothing.
//!
//! The smoothed quantity is the log-ratio of data to model, `ln((f + eps) / (model + eps))`
//! (`eps` 1% of the band's median keeps zeros finite), at four coordinates in which an
//! isotropic BRDF is smooth and which are regular at the specular direction:
//! `u = sqrt((δ + 2°)/180°) − sqrt(2°/180°)` with `δ` the angle between `wo` and the mirror
//! direction of `wi` (square-root steps away from the peak, linear within the round core
//! below), `t = θ_d / 90°`, and `(s cos p, s sin p)` with `s = t · max(0, δ − 2°)/180°` and
//! `p = φ_d` folded into [0, 180°] by mirror symmetry about the plane of incidence (which an
//! isotropic surface has). Rings about the specular direction are rings of constant `u`; within
//! [`ROUND_CORE`] of it the `φ_d` coordinates vanish, so the correction is round there, and at
//! the specular direction itself every `φ_d` (the same pair of directions turned about the
//! normal) is one point. Retro-reflection (`θ_d = 0`) is one point as well.
//! Reciprocity is not assumed: folding the Cornell paints by it as well
//! (`φ_d ~ φ_d + 180°`) tripled the held-out error, so those measurements are not reciprocal
//! within their scatter.
//!
//! `u` is a distance from the specular direction, but the specular direction is no edge of
//! the data: a line through it goes on beyond it, and a round peak has there the values it has
//! at the same distance on this side. The fit therefore also sees each sample's image through
//! the specular direction, at `−u` with its other coordinates. With samples on one side only,
//! a local plane has a slope in `u` at `u = 0`, and since `u` grows as `δ` from there, the peak
//! had a cone at the pole, pointing up or down (a Cayman pole lay 3% below its ring 0.011° from
//! it, at θ_d 29° and 610 nm); with the images the fit is an even function of `u`, smooth at
//! the pole.
//!
//! At any point the correction is the local linear regression (locally weighted least squares
//! of a plane, W. S. Cleveland, "Robust locally weighted regression and smoothing
//! scatterplots", JASA 74, 1979) of the log-ratios, with Gaussian weights of per-coordinate
//! bandwidths and a small ridge on the slopes. The plane's intercept is a weighted sum of the
//! samples' values whose weights sum to 1 (the equivalent kernel of local polynomial fitting:
//! J. Fan and I. Gijbels, "Local Polynomial Modelling and Its Applications", 1996); where some
//! are negative the plane extrapolates, which where samples are sparse can leave their values
//! far behind, and the intercept is kept between the kernel-weighted mean and the mean under
//! the plane's positive weights, both weighted means of the samples. Where the samples within
//! reach weigh little the kernel is widened (up to 8 times), so beyond the measured angles the
//! nearest data's ratio continues and the table has the model's shape; with no sample even
//! then, the table is the model. Every step is continuous in the point, and smooth where it
//! can be: the kernel falls to zero at its cut with a zero slope, the plane's intercept is
//! limited by a clamp between two continuous bounds, and the wider kernel is blended in as the
//! weight within reach falls. (Switches at thresholds — a kernel cut where it was 0.0022, the
//! mean taken at once where the intercept left the range of the samples weighing more than
//! 0.05, the wider kernel taken at once where no sample was left — put steps into the table:
//! issue #35's pit in the Cayman peak, whose pole at θ_d 69° read 20 1/sr and its ring 0.044°
//! from it 54 over most of φ_d, falling in steps to 33 and 20.) Every value is then softly capped
//! at the largest measured value near it (a `tanh` knee from 90% of it; samples near the edge
//! of "near" count in part), so that no cell holds a peak the nearby data do not show. Unless
//! given, the bandwidths are chosen by leave-one-out cross-validation of the channel mean from
//! a small grid. The fit residual at the measured points is reported, overall and per band.

mod cells;
mod coords;
mod linear;
#[cfg(test)]
mod tests;
mod weights;

use super::lobe_model::LobeModel;
use crate::error::{BrdfError, Result};
use crate::table::{BrdfTable, Channels, Provenance, Resolution, TableBuilder};
use cells::Cells;
use coords::coordinates_of;
pub use coords::{ROUND_CORE, coordinates, mirror_angle};
use glam::DVec3;
pub(super) use linear::solve;
use rayon::prelude::*;
use std::path::Path;
use weights::{
    SOFT_CAP_KNEE, WELL_WEIGHTED, cap_presence, distance2, kernel, soft_cap, through_pole, within,
};

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

/// Bandwidths of the kernel: in `u`, in `t`, and in each of `(s cos p, s sin p)`.
pub type Bandwidths = [f64; 3];

/// Number of regression coordinates.
const DIM: usize = 4;

/// A smoothing interpolant of scattered samples.
pub struct ScatteredFit {
    points: Vec<[f64; DIM]>,
    /// `logs[i * nc + c]`: the log-ratio `ln((f + eps_c) / (model + eps_c))` of sample i,
    /// channel c.
    logs: Vec<f64>,
    /// `values[i * nc + c]`: the measured f of sample i, channel c (negative readings as 0).
    values: Vec<f64>,
    /// Per channel, the largest measured value in the file.
    largest: Vec<f64>,
    eps: Vec<f64>,
    nc: usize,
    bw: Bandwidths,
    model: LobeModel,
    cells: Cells,
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
        let kept: Vec<Sample> = kept.into_iter().cloned().collect();
        let model = LobeModel::fit(&kept);
        let mut values = Vec::with_capacity(kept.len() * nc);
        let mut logs = Vec::with_capacity(kept.len() * nc);
        // The channel mean's log-ratio, on which the bandwidths are cross-validated.
        let mut z_mean = Vec::with_capacity(kept.len());
        let eps_mean = eps.iter().sum::<f64>() / nc as f64;
        let mut m = vec![0.0; nc];
        for s in &kept {
            model.eval(s.wi, s.wo, &mut m);
            for ((v, mc), e) in s.values.iter().zip(&m).zip(&eps) {
                values.push(v.max(0.0));
                logs.push(((v.max(0.0) + e) / (mc + e)).ln());
            }
            let mean = |v: &[f64]| v.iter().map(|v| v.max(0.0)).sum::<f64>() / nc as f64;
            z_mean.push(((mean(&s.values) + eps_mean) / (mean(&m) + eps_mean)).ln());
        }
        let largest = (0..nc)
            .map(|c| {
                values
                    .iter()
                    .skip(c)
                    .step_by(nc)
                    .fold(0.0f64, |m, v| m.max(*v))
            })
            .collect();
        let mut fit = ScatteredFit {
            cells: Cells::new(&points),
            points,
            logs,
            values,
            largest,
            eps,
            nc,
            bw: [0.1; 3],
            model,
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

    /// Leave-one-out choice of bandwidths on `z`, the log-ratio of the channel mean to the
    /// model's.
    fn cross_validated_bandwidths(&self, z: &[f64]) -> Bandwidths {
        let mut best = ([0.1; 3], f64::INFINITY);
        for hu in [0.02, 0.03, 0.05, 0.08] {
            for ht in [0.05, 0.08, 0.13, 0.2] {
                for hp in [0.002, 0.005, 0.01, 0.02] {
                    let bw = [hu, ht, hp];
                    // Errors computed in parallel, summed serially in sample order: the same
                    // choice for any thread count (a parallel sum's order depends on it).
                    let errors: Vec<f64> = (0..self.points.len())
                        .into_par_iter()
                        .map(|i| {
                            let mut out = [0.0];
                            let near = self.local_linear(
                                &self.points[i],
                                &bw,
                                Some(i),
                                |j| &z[j..j + 1],
                                &mut out,
                            );
                            // With no sample near, the prediction is the model (ratio 0).
                            if near.is_none() {
                                out[0] = 0.0;
                            }
                            (out[0] - z[i]).abs()
                        })
                        .collect();
                    let err: f64 = errors.iter().sum();
                    if err < best.1 {
                        best = (bw, err);
                    }
                }
            }
        }
        best.0
    }

    /// Local linear regression at `x` of the per-sample vectors `z(j)`, the samples' images
    /// through the specular direction included (module docs), leaving out sample `skip` and
    /// its image: the weight sum of the samples that count, `None` when none is near. Where the
    /// plane extrapolates, its intercept is kept between the kernel-weighted mean and the mean
    /// under the plane's positive weights (module docs): both lie within the samples' values,
    /// so the result does, and where no weight is negative the intercept is that second mean
    /// itself and is left as it is.
    ///
    /// The fitted value is the plane's intercept `b0 = e0ᵀ A⁻¹ Σ_j w_j d_j z_j`, with `A` the
    /// normal matrix `Σ_j w_j d_j d_jᵀ` (plus the ridge) and `d_j = (1, (y_j - x)/h)`. `A` is
    /// the same for every channel, so `b0 = Σ_j w_j (g·d_j) z_j` with `g = A⁻¹ e0` (`A` is
    /// symmetric): one weight per sample, found once, instead of five right-hand sides per
    /// channel carried through the elimination. The intercept is the same up to rounding.
    fn local_linear<'a>(
        &self,
        x: &[f64; DIM],
        bw: &Bandwidths,
        skip: Option<usize>,
        z: impl Fn(usize) -> &'a [f64],
        out: &mut [f64],
    ) -> Option<f64> {
        // Normal equations of z ≈ b0 + b·(y - x)/bw, accumulated as a 5×5 matrix, and the
        // samples (and images) that count with their weights and offsets.
        let mut a = [[0.0f64; DIM + 1]; DIM + 1];
        let mut wsum = 0.0;
        let mut weighed: Vec<(usize, f64, [f64; DIM + 1])> = Vec::with_capacity(64);
        let mut add = |j: usize, y: [f64; DIM]| {
            let w = kernel(x, &y, bw);
            if Some(j) == skip || w == 0.0 {
                return;
            }
            wsum += w;
            let d = [
                1.0,
                (y[0] - x[0]) / bw[0],
                (y[1] - x[1]) / bw[1],
                (y[2] - x[2]) / bw[2],
                (y[3] - x[3]) / bw[2],
            ];
            for (row, dr) in a.iter_mut().zip(d) {
                for (x, dc) in row.iter_mut().zip(d) {
                    *x += w * dr * dc;
                }
            }
            weighed.push((j, w, d));
        };
        self.cells.near(x, bw, |j| add(j, self.points[j]));
        // The images lie at u <= 0: within reach only of points less than the reach from it.
        let images = x[0] < 3.5 * bw[0];
        if images {
            let image = through_pole(*x);
            self.cells
                .near(&image, bw, |j| add(j, through_pole(self.points[j])));
        }
        if wsum < 1e-6 {
            return None;
        }
        // Ridge on the slopes: a plane only where the samples support one.
        for (r, row) in a.iter_mut().enumerate().skip(1) {
            row[r] += 0.05 * wsum;
        }
        let mut g = [1.0, 0.0, 0.0, 0.0, 0.0];
        // Samples on a line or a point: no plane, the local constant.
        let plane = solve(a, &mut g, 1).is_some();
        // The local constant (kernel-weighted mean), the intercept, and the mean under the
        // plane's positive weights.
        let m = out.len();
        let mut mean = vec![0.0f64; m];
        let mut positive = vec![0.0f64; m];
        let mut positive_sum = 0.0;
        out.fill(0.0);
        for &(j, w, d) in &weighed {
            let zj = z(j);
            for (s, zk) in mean.iter_mut().zip(zj) {
                *s += w * zk;
            }
            if plane {
                let l = w * g.iter().zip(d).map(|(g, d)| g * d).sum::<f64>();
                for (o, zk) in out.iter_mut().zip(zj) {
                    *o += l * zk;
                }
                if l > 0.0 {
                    positive_sum += l;
                    for (p, zk) in positive.iter_mut().zip(zj) {
                        *p += l * zk;
                    }
                }
            }
        }
        for ((o, mean), positive) in out.iter_mut().zip(&mean).zip(&positive) {
            let mean = mean / wsum;
            *o = if plane {
                // The plane's weights sum to 1 (the ridge spares the intercept), so the
                // positive ones to at least 1.
                let positive = positive / positive_sum;
                o.clamp(mean.min(positive), mean.max(positive))
            } else {
                mean
            };
        }
        Some(wsum)
    }

    /// The smoothed f (1/sr) per channel at a pair of directions; zero below the horizon and far
    /// from every sample.
    pub fn predict(&self, wi: DVec3, wo: DVec3, out: &mut [f64]) {
        out.fill(0.0);
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return;
        }
        if let Some(x) = coordinates(wi, wo) {
            self.predict_at(&x, wi, wo, out);
        }
    }

    /// The fitted f at the coordinates `x` of the pair `(wi, wo)`: the model times the
    /// smoothed correction, softly capped at the largest measured value near the pair.
    fn predict_at(&self, x: &[f64; DIM], wi: DVec3, wo: DVec3, out: &mut [f64]) {
        let nc = self.nc;
        let mut model = vec![0.0; nc];
        self.model.eval(wi, wo, &mut model);
        self.correction(x, out);
        for ((o, m), e) in out.iter_mut().zip(&model).zip(&self.eps) {
            *o = ((m + e) * o.exp() - e).max(0.0);
        }
        let cap = self.nearby_maximum(x, out);
        for (o, c) in out.iter_mut().zip(cap) {
            *o = soft_cap(*o, c);
        }
    }

    /// The smoothed log-ratio of data to model at `x` for prediction. Where the samples within
    /// the kernel's reach weigh less than [`WELL_WEIGHTED`] together, the correction of a kernel
    /// twice as wide is blended in, in proportion as they weigh less (up to 8 times wider):
    /// beyond the measured angles the correction of the nearest data continues as a constant
    /// ratio, i.e. the table follows the model's shape scaled to the edge of the measurement;
    /// with no sample even then, the table is the model.
    fn correction(&self, x: &[f64; DIM], out: &mut [f64]) {
        self.widened_correction(x, self.bw, 3, out);
    }

    /// [`ScatteredFit::correction`] with the bandwidths `bw`, which may still be doubled
    /// `doublings` times.
    fn widened_correction(&self, x: &[f64; DIM], bw: Bandwidths, doublings: u32, out: &mut [f64]) {
        let nc = self.nc;
        let logs = |j: usize| &self.logs[j * nc..(j + 1) * nc];
        let wsum = self.local_linear(x, &bw, None, logs, out);
        // The share of this kernel's correction: 0 where the weight within reach is at the
        // threshold of `local_linear` (1e-6), so that the blend is continuous there too.
        let share = wsum.map_or(0.0, |w| ((w - 1e-6) / (WELL_WEIGHTED - 1e-6)).min(1.0));
        if share >= 1.0 {
            return;
        }
        let mut wider = vec![0.0; nc];
        if doublings > 0 {
            self.widened_correction(x, bw.map(|b| 2.0 * b), doublings - 1, &mut wider);
        }
        for (o, w) in out.iter_mut().zip(wider) {
            *o = if share > 0.0 {
                share * *o + (1.0 - share) * w
            } else {
                w
            };
        }
    }

    /// Per channel, the largest measured value among the samples within twice the kernel's
    /// reach of `x` (the file's largest where none is): the data's own bound on the peak there,
    /// as far as [`soft_cap`] of the uncapped values `v` needs it. A sample counts in full
    /// within 2.5 of the doubled bandwidths and fades out over the last one (its presence `r`
    /// falls smoothly from 1 to 0, [`cap_presence`]; its image through the specular direction
    /// counts as well): the bound is `max(max_j r_j v_j, L (1 - max_j r_j))` with `L` the
    /// file's largest, so that it changes continuously as samples enter and leave the reach
    /// (counted in full up to the edge, a sample entering it raised the bound at once: Garnet
    /// red's specular cells at θ_d ≤ 1° and θ_h ≤ 0.044° were 17% below their neighbours). The
    /// scan stops once every channel's running `max_j r_j v_j`, `m`, leaves its value unchanged
    /// (`v` is 0, or `m > 0` and `v / m` at most the knee): `m` only grows and the bound is at
    /// least `m`, and a larger bound leaves such a value unchanged too (rounded division is
    /// monotonic in the divisor), so the capped values are those of the full scan, to the bit.
    /// Most of the table is well below the data near it, and the scan ends at the first few
    /// samples instead of visiting the hundreds within reach.
    fn nearby_maximum(&self, x: &[f64; DIM], v: &[f64]) -> Vec<f64> {
        let nc = self.nc;
        let wide = self.bw.map(|b| 2.0 * b);
        let mut top = vec![0.0f64; nc];
        let settled = |top: &[f64]| {
            v.iter()
                .zip(top)
                .all(|(&v, &m)| v == 0.0 || (m > 0.0 && v / m <= SOFT_CAP_KNEE))
        };
        let mut presence = 0.0f64;
        self.cells.any_near(x, &wide, |j| {
            if !within(x, &self.points[j], &wide) {
                return false;
            }
            // The sample and its image through the specular direction (module docs): either
            // counts, together as independent chances, so that the presence is even in u. The
            // original is never farther from x than the image (u >= 0 for both), so the scan
            // of the originals within reach finds every image within reach.
            let y = self.points[j];
            let (a, b) = (
                cap_presence(distance2(x, &y, &wide)),
                cap_presence(distance2(x, &through_pole(y), &wide)),
            );
            let r = a + b - a * b;
            presence = presence.max(r);
            for (m, &s) in top.iter_mut().zip(&self.values[j * nc..(j + 1) * nc]) {
                *m = m.max(r * s);
            }
            settled(&top)
        });
        top.iter()
            .zip(&self.largest)
            .map(|(&m, &l)| m.max(l * (1.0 - presence)))
            .collect()
    }

    /// Relative residuals of the fit at the samples it was fitted to (each predicted with all
    /// samples, itself included), over values of at least [`NOISE_FLOOR_PER_SR`].
    pub fn residual(&self, samples: &[Sample]) -> FitResidual {
        residual_of(samples, NOISE_FLOOR_PER_SR, |s, out| {
            self.predict(s.wi, s.wo, out)
        })
    }

    /// Per channel, the median relative residual at the samples (values of at least
    /// [`NOISE_FLOOR_PER_SR`]; NaN for a channel with none).
    pub fn residual_per_band(&self, samples: &[Sample]) -> Vec<f64> {
        let predictions: Vec<Vec<f64>> = samples
            .par_iter()
            .map(|s| {
                let mut out = vec![0.0; self.nc];
                self.predict(s.wi, s.wo, &mut out);
                out
            })
            .collect();
        (0..self.nc)
            .map(|c| {
                let mut rel: Vec<f64> = samples
                    .iter()
                    .zip(&predictions)
                    .filter(|(s, _)| s.values[c] >= NOISE_FLOOR_PER_SR)
                    .map(|(s, p)| ((p[c] - s.values[c]) / s.values[c]).abs())
                    .collect();
                rel.sort_by(f64::total_cmp);
                rel.get(rel.len() / 2).copied().unwrap_or(f64::NAN)
            })
            .collect()
    }

    /// The physically based model under the correction.
    pub fn model(&self) -> &LobeModel {
        &self.model
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
        b.fill(|cell, out| {
            let x = coordinates_of(&cell.angles, mirror_angle(cell.wi, cell.wo));
            self.predict_at(&x, cell.wi, cell.wo, out)
        });
        b.build()
    }
}

/// Import measured samples read from `path`: smooth them with a [`ScatteredFit`] and resample it
/// on an isotropic table. The table's `provenance` gains the fit's residual at the measured
/// points (`fit_median_relative_residual`, `fit_rms_relative_residual`), its bandwidths
/// (`fit_bandwidths_u_t_ut`) and the sample count (`samples`); the residual is also returned.
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
    let model = fit.model();
    let extra: [(&str, serde_json::Value); 6] = [
        (
            "fit_median_relative_residual",
            residual.median_relative.into(),
        ),
        ("fit_rms_relative_residual", residual.rms_relative.into()),
        (
            "fit_median_relative_residual_per_band",
            fit.residual_per_band(samples).into(),
        ),
        ("fit_bandwidths_u_t_p", fit.bandwidths().to_vec().into()),
        (
            "model_per_band",
            serde_json::to_value(&model.bands).unwrap_or_default(),
        ),
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
