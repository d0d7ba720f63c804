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

use super::lobe_model::LobeModel;
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

/// The samples sorted into a grid of cells over the first two coordinates `(u, t)`, and within
/// each cell by the third, `s cos p`, so that a query visits only the samples of the cells
/// within the kernel's reach, and of those only the ones within its reach in `s cos p`, instead
/// of all of them (the kernel is cut at 3.5 bandwidths: a sample farther than that in any
/// coordinate weighs 0). The third coordinate matters: its bandwidths are ten times narrower
/// than a cell, so most samples of the cells near a query lie outside the kernel in it, and
/// testing them was most of an import's time. The samples a query visits are taken in their own
/// order, as a scan of all of them would, so the sums, and so every fitted value, are the same
/// to the bit.
struct Cells {
    /// The grid's lower corner in `u` and `t`.
    origin: [f64; 2],
    /// Cells along `u` and `t`.
    count: [usize; 2],
    /// `samples[start[c]..start[c + 1]]`: the samples in cell `c` (`u` index slowest), in
    /// increasing `s cos p`.
    start: Vec<usize>,
    samples: Vec<usize>,
    /// `keys[i]`: the `s cos p` of `samples[i]`.
    keys: Vec<f64>,
}

impl Cells {
    /// The size of a cell in `u` and `t`: half the smallest reach of the cross-validated
    /// bandwidths (3.5 × 0.02 in `u`, 3.5 × 0.05 in `t`), so that a query with the narrowest
    /// kernel visits about three cells per coordinate.
    const SIZE: [f64; 2] = [0.035, 0.0875];

    fn new(points: &[[f64; DIM]]) -> Cells {
        let origin = [0, 1].map(|k| points.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
        let count = [0, 1].map(|k| {
            let hi = points.iter().map(|p| p[k]).fold(origin[k], f64::max);
            ((hi - origin[k]) / Self::SIZE[k]).floor() as usize + 1
        });
        let mut cells = Cells {
            origin,
            count,
            start: Vec::new(),
            samples: Vec::new(),
            keys: Vec::new(),
        };
        let cell_of: Vec<usize> = points
            .iter()
            .map(|p| cells.index(0, p[0]) * count[1] + cells.index(1, p[1]))
            .collect();
        cells.start = vec![0; count[0] * count[1] + 1];
        for &c in &cell_of {
            cells.start[c + 1] += 1;
        }
        for c in 1..cells.start.len() {
            cells.start[c] += cells.start[c - 1];
        }
        let mut next = cells.start.clone();
        cells.samples = vec![0; points.len()];
        for (j, &c) in cell_of.iter().enumerate() {
            cells.samples[next[c]] = j;
            next[c] += 1;
        }
        for c in 0..count[0] * count[1] {
            cells.samples[cells.start[c]..cells.start[c + 1]]
                .sort_by(|&i, &j| points[i][2].total_cmp(&points[j][2]));
        }
        cells.keys = cells.samples.iter().map(|&j| points[j][2]).collect();
        cells
    }

    /// The cell index along coordinate `k` of the value `v`, clamped to the grid.
    fn index(&self, k: usize, v: f64) -> usize {
        (((v - self.origin[k]) / Self::SIZE[k]).floor().max(0.0) as usize).min(self.count[k] - 1)
    }

    /// The runs of `samples` (ranges of indices into it) that hold every sample which may lie
    /// within the kernel of bandwidths `bw` about `x`: one run per cell within reach in `u` and
    /// `t`, cut to the samples within reach in `s cos p`.
    fn runs(&self, x: &[f64; DIM], bw: &Bandwidths) -> impl Iterator<Item = (usize, usize)> {
        // 3.5 bandwidths, widened by a part in a million against rounding at the boundary.
        let reach = [0, 1, 2].map(|k| 3.5 * bw[k] * (1.0 + 1e-6));
        let [u0, u1] = [x[0] - reach[0], x[0] + reach[0]].map(|v| self.index(0, v));
        let [t0, t1] = [x[1] - reach[1], x[1] + reach[1]].map(|v| self.index(1, v));
        let (lo, hi) = (x[2] - reach[2], x[2] + reach[2]);
        (u0..=u1)
            .flat_map(move |iu| (iu * self.count[1] + t0)..=(iu * self.count[1] + t1))
            .map(move |c| {
                let (a, b) = (self.start[c], self.start[c + 1]);
                let keys = &self.keys[a..b];
                (
                    a + keys.partition_point(|&k| k < lo),
                    a + keys.partition_point(|&k| k <= hi),
                )
            })
    }

    /// Calls `visit` with every sample that may lie within the kernel of bandwidths `bw` about
    /// `x`, in increasing order (a superset of those with nonzero weight).
    fn near(&self, x: &[f64; DIM], bw: &Bandwidths, mut visit: impl FnMut(usize)) {
        let n = self.samples.len();
        let mut marked = vec![0u64; n.div_ceil(64)];
        for (first, last) in self.runs(x, bw) {
            for &j in &self.samples[first..last] {
                marked[j / 64] |= 1 << (j % 64);
            }
        }
        for (w, mut bits) in marked.into_iter().enumerate() {
            while bits != 0 {
                visit(w * 64 + bits.trailing_zeros() as usize);
                bits &= bits - 1;
            }
        }
    }

    /// Calls `visit` with the samples that may lie within the kernel of bandwidths `bw` about
    /// `x`, in no particular order, until it returns true.
    fn any_near(&self, x: &[f64; DIM], bw: &Bandwidths, mut visit: impl FnMut(usize) -> bool) {
        for (first, last) in self.runs(x, bw) {
            for &j in &self.samples[first..last] {
                if visit(j) {
                    return;
                }
            }
        }
    }
}

/// The `(u, t, s cos p, s sin p)` coordinates of a pair of directions (module docs).
pub fn coordinates(wi: DVec3, wo: DVec3) -> Option<[f64; DIM]> {
    let a = HalfDiff::from_dirs(wi, wo)?;
    Some(coordinates_of(&a, mirror_angle(wi, wo)))
}

/// The angle between `wo` and the mirror direction of `wi` (radians; the same with `wi` and
/// `wo` exchanged, the mirror being an isometry and its own inverse).
pub fn mirror_angle(wi: DVec3, wo: DVec3) -> f64 {
    let wr = DVec3::new(-wi.x, -wi.y, wi.z);
    wo.cross(wr).length().atan2(wo.dot(wr))
}

fn coordinates_of(a: &HalfDiff, delta: f64) -> [f64; DIM] {
    let mut p = a.phi_d.rem_euclid(2.0 * PI);
    if p > PI {
        p = 2.0 * PI - p;
    }
    let t = a.theta_d / FRAC_PI_2;
    let d = delta.max(0.0);
    let u = ((d + ROUND_CORE) / PI).sqrt() - (ROUND_CORE / PI).sqrt();
    let s = ((d - ROUND_CORE) / PI).max(0.0) * t;
    [u, t, s * p.cos(), s * p.sin()]
}

/// Angle from the mirror direction (radians) below which the fit cannot depend on `phi_d`: the
/// core of the specular peak is round. 2°: the Cornell paint files have one geometry per
/// incidence within 2° of the specular direction (in the plane of incidence, on one side of
/// the peak), so nothing in them tells the azimuths about it apart; and a peak narrower than
/// the instrument's circular aperture is measured as the aperture's round image.
pub const ROUND_CORE: f64 = 2.0 * PI / 180.0;

/// The squared kernel distance `Σ ((x_k - y_k) / h_k)²` between two points.
#[inline]
fn distance2(x: &[f64; DIM], y: &[f64; DIM], bw: &Bandwidths) -> f64 {
    let mut q = 0.0;
    for k in 0..DIM {
        let d = (x[k] - y[k]) / bw[k.min(2)];
        q += d * d;
    }
    q
}

/// The kernel's cut-off: 3.5 bandwidths, squared.
const CUT2: f64 = 12.25;

/// Gaussian kernel weight cut at 3.5 bandwidths, less its tangent at the cut:
/// `exp(-q/2) - E (1 + (CUT2 - q)/2)` with `E = exp(-CUT2/2)` and `q` the squared distance in
/// bandwidths. It falls to 0 at the cut with a zero slope, so a sample's weight, and the fit,
/// change smoothly as a sample leaves the kernel's reach (cut where it was 0.0022, a sample
/// entering the reach with high leverage moved the Cayman peak by a factor 1.6 at once; cut
/// where it was 0 with a slope, the peak had a kink wherever a sample crossed the cut). The
/// Gaussian is convex in `q`, so it lies above its tangent: the weight is positive inside.
#[inline]
fn kernel(x: &[f64; DIM], y: &[f64; DIM], bw: &Bandwidths) -> f64 {
    let q = distance2(x, y, bw);
    if q >= CUT2 {
        0.0
    } else {
        (-0.5 * q).exp() - KERNEL_AT_CUT * (1.0 + 0.5 * (CUT2 - q))
    }
}

/// The Gaussian at the cut, `exp(-CUT2 / 2)`.
const KERNEL_AT_CUT: f64 = 0.002187491118182885;

/// The weight of the samples within the kernel's reach from which it is not widened (one sample
/// 2.45 bandwidths away).
const WELL_WEIGHTED: f64 = 0.05;

/// The point of `y`'s image through the specular direction (module docs): `u` negated.
fn through_pole(y: [f64; DIM]) -> [f64; DIM] {
    [-y[0], y[1], y[2], y[3]]
}

/// Whether `y` is within the kernel's reach of `x` (its weight is nonzero).
#[inline]
fn within(x: &[f64; DIM], y: &[f64; DIM], bw: &Bandwidths) -> bool {
    distance2(x, y, bw) <= CUT2
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

/// `v` limited to `cap` with a smooth knee: unchanged up to 90% of the cap, then rising as
/// `tanh` toward the cap (slope 1 at the knee), so a capped peak keeps a rounded top instead of
/// a flat box and never exceeds the data's bound.
fn soft_cap(v: f64, cap: f64) -> f64 {
    const KNEE: f64 = SOFT_CAP_KNEE;
    if cap <= 0.0 {
        return 0.0;
    }
    let x = v / cap;
    if x <= KNEE {
        v
    } else {
        cap * (KNEE + (1.0 - KNEE) * ((x - KNEE) / (1.0 - KNEE)).tanh())
    }
}

/// How far a sample at the squared distance `q` (in the doubled bandwidths) counts in the cap
/// of [`ScatteredFit::nearby_maximum`]: 1 within 2.5 bandwidths, 0 from the kernel's cut at
/// 3.5, between them the smoothstep `3s² − 2s³` of `s = 3.5 − sqrt(q)`, continuous with its
/// slope at both ends.
fn cap_presence(q: f64) -> f64 {
    let s = (CUT2.sqrt() - q.sqrt()).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// The fraction of the cap up to which [`soft_cap`] leaves a value unchanged.
const SOFT_CAP_KNEE: f64 = 0.9;

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

/// Solve the symmetric N×N system `a x = rhs` for `m` right-hand sides stored row-wise in `rhs`
/// (`rhs[r * m + k]`), in place, by Gaussian elimination with partial pivoting.
pub(super) fn solve<const N: usize>(mut a: [[f64; N]; N], rhs: &mut [f64], m: usize) -> Option<()> {
    for col in 0..N {
        let piv = (col..N).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-12 {
            return None;
        }
        if piv != col {
            a.swap(piv, col);
            for k in 0..m {
                rhs.swap(piv * m + k, col * m + k);
            }
        }
        for r in col + 1..N {
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
    for col in (0..N).rev() {
        for k in 0..m {
            let mut v = rhs[col * m + k];
            for c in col + 1..N {
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
        let samples = smooth_samples();
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

    /// At the specular direction every phi_d is the same pair of directions turned about the
    /// normal: the coordinates must be one point. A mirror image about the plane of incidence
    /// has the coordinates of the original.
    #[test]
    fn coordinates_are_regular_at_the_specular_direction() {
        let at = |phi_d: f64| {
            coordinates_of(
                &HalfDiff {
                    theta_h: 0.0,
                    phi_h: 0.3,
                    theta_d: 0.6,
                    phi_d,
                },
                0.0,
            )
        };
        let x0 = at(0.0);
        for k in 1..24 {
            assert_eq!(at(k as f64 * PI / 12.0), x0);
        }
        // Through directions, δ from atan2 of the cross and dot products carries a round-off
        // of a few 1e-16 rad; u is linear near 0 (slope 1 / (2 sqrt(π · 2°)) = 1.5 per rad),
        // so below 1e-14; the phi_d coordinates are exactly 0 in the round core; t (theta_d
        // from the rotations, through acos) is off by up to sqrt(2 · 1.1e-16) / 90° = 1e-8.
        for k in 0..24 {
            let (wi, wo) = HalfDiff {
                theta_h: 0.0,
                phi_h: 0.3,
                theta_d: 0.6,
                phi_d: k as f64 * PI / 12.0,
            }
            .to_dirs();
            let x = coordinates(wi, wo).unwrap();
            assert!(x[0] < 1e-14 && (x[1] - x0[1]).abs() < 1e-8, "{x:?}");
            assert!(x[2] == 0.0 && x[3] == 0.0, "{x:?}");
        }
        let mirror = |w: DVec3| DVec3::new(w.x, -w.y, w.z);
        let (wi, wo) = (dir(0.5, 0.2), dir(0.7, 2.9));
        let (a, b) = (
            coordinates(wi, wo).unwrap(),
            coordinates(mirror(wi), mirror(wo)).unwrap(),
        );
        for (a, b) in a.iter().zip(&b) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }

    /// The cells find every sample the kernel weighs, in increasing order (and in any order,
    /// without repeats, for the cap's scan), for narrow and wide kernels and for queries inside, at the edge of and beyond the samples (a scan of all
    /// samples is the reference).
    #[test]
    fn cells_find_every_weighted_sample_in_order() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let mut next = || rng.random::<f64>();
        let points: Vec<[f64; DIM]> = (0..3000)
            .map(|_| [next(), next(), 0.1 * next() - 0.05, 0.1 * next()])
            .collect();
        let cells = Cells::new(&points);
        for bw in [[0.02, 0.05, 0.002], [0.08, 0.2, 0.02], [0.64, 1.6, 0.16]] {
            for _ in 0..200 {
                let x = [
                    1.4 * next() - 0.2,
                    1.4 * next() - 0.2,
                    0.14 * next() - 0.07,
                    0.12 * next() - 0.01,
                ];
                let scan: Vec<usize> = (0..points.len())
                    .filter(|&j| kernel(&x, &points[j], &bw) > 0.0)
                    .collect();
                let mut found = Vec::new();
                cells.near(&x, &bw, |j| {
                    if kernel(&x, &points[j], &bw) > 0.0 {
                        found.push(j);
                    }
                });
                assert_eq!(found, scan, "x {x:?}, bandwidths {bw:?}");
                let mut any = Vec::new();
                cells.any_near(&x, &bw, |j| {
                    if within(&x, &points[j], &bw) {
                        any.push(j);
                    }
                    false
                });
                any.sort();
                assert_eq!(any, scan, "x {x:?}, bandwidths {bw:?}");
            }
        }
    }

    /// Samples of a smooth isotropic BRDF with a peak about the mirror direction, at
    /// incidences 10-70° and outgoing directions every 9° and 15°.
    fn smooth_samples() -> Vec<Sample> {
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
        samples
    }

    /// The kernel falls to 0 at its cut, and so does its slope; the cap's presence goes from 1
    /// to 0 between 2.5 and 3.5 bandwidths, with zero slopes at both ends: a sample entering or
    /// leaving their reach changes the fit continuously (issue #35).
    #[test]
    fn kernel_and_cap_presence_fade_smoothly() {
        let bw = [1.0; 3];
        let at = |d: f64| kernel(&[0.0; DIM], &[d, 0.0, 0.0, 0.0], &bw);
        let cut = CUT2.sqrt();
        // Near the cut the weight is E (q_c - q)² / 8 to leading order, q_c - q ≈ 2 r ε.
        for eps in [1e-3, 1e-4] {
            let w = at(cut - eps);
            let leading = KERNEL_AT_CUT * (2.0 * cut * eps).powi(2) / 8.0;
            assert!((w / leading - 1.0).abs() < 0.01, "{w} against {leading}");
        }
        assert_eq!(at(cut), 0.0);
        assert!(at(0.0) > 0.98 && at(cut - 0.5) > 0.0);
        let r = |d: f64| cap_presence(d * d);
        assert_eq!((r(2.0), r(2.5), r(3.5), r(4.0)), (1.0, 1.0, 0.0, 0.0));
        let h = 1e-6;
        for d in [2.5, 3.5] {
            assert!(
                ((r(d + h) - r(d - h)) / (2.0 * h)).abs() < 1e-5,
                "slope at {d}"
            );
        }
        assert!((r(3.0) - 0.5).abs() < 1e-12);
    }

    /// The fit is an even function of `u` about the specular direction (each sample's image
    /// through it weighs in), so the peak's top is smooth: along the plane of incidence its
    /// change from the pole grows as δ², four times over from δ to 2δ, where a cone (a plane
    /// sloping in `u` at `u = 0`, the samples on one side only) grows twice. The ratio must lie
    /// between 3 and 5, nearer a smooth top's 4 than a cone's 2 or a δ⁴ top's 16 (without the
    /// images: 1.87 at 20°; with them 4.41, 4.01, 4.00 at 20°, 40°, 62°).
    #[test]
    fn peak_top_is_smooth_at_the_specular_direction() {
        let fit = ScatteredFit::new(&smooth_samples(), None).unwrap();
        for ti in [20.0f64, 40.0, 62.0] {
            let mut corr = [[0.0]; 2];
            let x = coordinates(dir(ti.to_radians(), 0.0), dir(ti.to_radians() + 0.01, PI));
            let x = x.unwrap();
            fit.correction(&x, &mut corr[0]);
            fit.correction(&through_pole(x), &mut corr[1]);
            assert!((corr[0][0] - corr[1][0]).abs() < 1e-12, "{ti}°: {corr:?}");
            let along = |delta: f64| {
                let (wi, wo) = (
                    dir((ti - delta / 2.0).to_radians(), 0.0),
                    dir((ti + delta / 2.0).to_radians(), PI),
                );
                let mut out = [0.0];
                fit.predict(wi, wo, &mut out);
                out[0]
            };
            let (f0, f1, f2) = (along(0.0), along(0.05), along(0.1));
            let ratio = (f2 - f0) / (f1 - f0);
            assert!(
                (3.0..5.0).contains(&ratio),
                "{ti}°: {f0} {f1} {f2}, ratio {ratio}"
            );
        }
    }

    #[test]
    fn solve_solves() {
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
        solve(a, &mut rhs, 1).unwrap();
        for k in 0..4 {
            assert!((rhs[k] - x[k]).abs() < 1e-12);
        }
    }
}
