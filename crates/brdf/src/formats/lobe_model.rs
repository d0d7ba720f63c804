//! The physically based base under an imported measurement: a Lambertian body plus one or two
//! microfacet lobes, fitted to the measured samples per band. Where the measurement says
//! nothing (beyond its angles, between its sparse geometries near the specular direction) the
//! imported table follows this model; where it says something, a smooth correction of the
//! model reproduces the data ([`super::scattered`]).
//!
//! Per band `c`, `f_c(wi, wo) = ρ_c/π + Σ_k s_ck g_k(wi, wo)` with round lobes about the
//! mirror direction, `g_k = D(θ*; α_k)`: the GGX (Trowbridge-Reitz) distribution of normals
//! ([`crate::microfacet`]) at `θ* = δ/2`, half the angle `δ` between `wo` and the mirror
//! direction of `wi` (the tilt of the facet or flake that reflects `wi` into `wo` about an
//! axis in the plane of incidence; in that plane `θ* = θ_h`). Lobes round about the mirror
//! direction are how measured paints are commonly modelled (E. Lafortune et al., "Non-linear
//! approximation of reflectance functions", SIGGRAPH 1997, fitted the Cornell measurements
//! with cosine lobes about it), and how an instrument with a circular aperture sees a peak
//! narrower than its aperture. The Cook-Torrance factors `G F / (4 cos θ_i cos θ_o)` are left
//! out: the measured paints do not rise toward grazing as they predict (Cayman, band mean, one
//! lobe: median |ln(model/f)| 0.36 without them, 0.80 with them). Every term is reciprocal
//! (`δ` is the same with `wi` and `wo` exchanged, the mirror being its own inverse) and the
//! table built on the model is too where no data correct it. With `∫ D(θ*) cos θ_o dω_o ≤ 4`
//! (`dω_o = 4 cos(δ/2) dω_{θ*}` about the mirror direction) a lobe weight `s ≤ 1/4` cannot
//! create energy.
//!
//! The roughnesses `α_k` are chosen from a logarithmic grid by the weighted least-squares error
//! of the channel mean; with them fixed, each band's non-negative coefficients solve a linear
//! least-squares problem with weights `1/(f + m)²` (`m` the band's median value: relative
//! error for the bright values, absolute for those far below the median, so that the faint
//! readings near the noise floor do not steer the fit), so the fit is a few hundred small
//! solves and deterministic.

use super::scattered::{Sample, mirror_angle, solve};
use crate::microfacet::Microfacet;
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// The roughness grid the lobes are chosen from: 16 values from 0.02 to 0.8, evenly spaced in
/// `ln α` (a factor 1.28 between neighbours). The narrowest lobe has a half width at half
/// maximum of `0.64 α` = 0.7° in `θ*` (1.5° from the mirror direction): measured files sample
/// the specular direction 0.2-1° apart at best (the Cornell paints have one geometry per
/// incidence within 2° of it), so a narrower lobe would be shaped by a single sample and
/// would put a peak between samples that none of them shows (with the grid from 0.005 the
/// Cayman table held 25 1/sr 0.2° from the specular direction at 60°, where the measurement
/// 0.66° from it reads 8.1).
fn alpha_grid() -> Vec<f64> {
    let (lo, hi, n) = (0.02f64, 0.8f64, 16);
    (0..n)
        .map(|k| (lo.ln() + (hi / lo).ln() * k as f64 / (n - 1) as f64).exp())
        .collect()
}

/// One round lobe: its GGX roughness and its weight (1/sr per unit `D`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Lobe {
    /// GGX roughness `α`.
    pub alpha: f64,
    /// Weight `s` of `D(θ*; α)`.
    pub weight: f64,
}

/// The model of one band: a Lambertian body and one or two lobes.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BandModel {
    /// Albedo of the Lambertian body.
    pub rho: f64,
    /// The lobes, narrowest first.
    pub lobes: Vec<Lobe>,
}

/// A fitted Lambert + round-lobe model, one per band.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LobeModel {
    /// One model per band (channel).
    pub bands: Vec<BandModel>,
}

/// The shape of one lobe at a pair of directions (1/sr per unit weight).
fn lobe(alpha: f64, wi: DVec3, wo: DVec3) -> f64 {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return 0.0;
    }
    let half = 0.5 * mirror_angle(wi, wo);
    Microfacet::ggx(alpha).d(DVec3::new(half.sin(), 0.0, half.cos()))
}

/// Most unknowns of a model: the body and two lobes.
const MAX_TERMS: usize = 3;

/// Non-negative least squares of `Σ_j w_j (b_j · x - y_j)²` for at most [`MAX_TERMS`] unknowns,
/// by the active-set method of Lawson & Hanson ("Solving least squares problems", 1974, ch. 23)
/// in its simplest form: solve on the free set, fix the most negative unknown at 0, repeat.
fn nnls(rows: &[(Vec<f64>, f64, f64)], n: usize) -> Vec<f64> {
    debug_assert!(n <= MAX_TERMS);
    let mut free = [false; MAX_TERMS];
    free[..n].fill(true);
    loop {
        // Normal equations on the free unknowns; a fixed or unused unknown gets the row
        // `x_k = 0`.
        let mut a = [[0.0f64; MAX_TERMS]; MAX_TERMS];
        let mut r = [0.0f64; MAX_TERMS];
        for (b, y, w) in rows {
            for p in (0..n).filter(|&p| free[p]) {
                r[p] += w * b[p] * y;
                for q in (0..n).filter(|&q| free[q]) {
                    a[p][q] += w * b[p] * b[q];
                }
            }
        }
        for k in (0..MAX_TERMS).filter(|&k| !free[k]) {
            a[k][k] = 1.0;
        }
        match solve(a, &mut r, 1) {
            Some(()) => {
                let worst = (0..n)
                    .filter(|&k| free[k] && r[k] < 0.0)
                    .min_by(|&p, &q| r[p].total_cmp(&r[q]));
                match worst {
                    Some(k) => free[k] = false,
                    None => return r[..n].to_vec(),
                }
            }
            // A singular system: the last free lobe duplicates another; drop it.
            None => match (0..n).rev().find(|&k| free[k]) {
                Some(k) => free[k] = false,
                None => return vec![0.0; n],
            },
        }
    }
}

/// Least-squares rows of one band: the basis `[1/π, D(θ*; α_1), ...]` at each sample, the value
/// to fit and its weight.
struct Rows<'a> {
    /// `D(θ*; α)` at every sample, per grid roughness: `shapes[k][j]` (computed once, shared
    /// by every band).
    shapes: &'a [Vec<f64>],
    /// Weight `1/(f + m)²` of each sample (`m` the band's median value: relative error for
    /// the bright values, absolute for those far below the median, so that readings near the
    /// noise floor do not steer the fit).
    weights: Vec<f64>,
    /// The value to fit at each sample.
    values: Vec<f64>,
}

impl<'a> Rows<'a> {
    fn new(shapes: &'a [Vec<f64>], values: Vec<f64>) -> Rows<'a> {
        let mut sorted = values.clone();
        sorted.sort_by(f64::total_cmp);
        let median = sorted
            .get(sorted.len() / 2)
            .copied()
            .unwrap_or(0.0)
            .max(0.0);
        let weights = values
            .iter()
            // A band of zeros weighs its rows equally.
            .map(|y| 1.0 / (y.max(0.0) + median).max(1e-150).powi(2))
            .collect();
        Rows {
            shapes,
            weights,
            values,
        }
    }

    /// Non-negative body and lobe weights for the grid roughnesses `lobes`, after subtracting
    /// `fixed` (a lobe already known) from the values; with the weighted squared error.
    fn solve(&self, lobes: &[usize], fixed: Option<(usize, f64)>) -> (Vec<f64>, f64) {
        let rows: Vec<(Vec<f64>, f64, f64)> = (0..self.values.len())
            .map(|j| {
                let mut b = vec![1.0 / PI];
                b.extend(lobes.iter().map(|&k| self.shapes[k][j]));
                let y = self.values[j] - fixed.map_or(0.0, |(k, s)| s * self.shapes[k][j]);
                (b, y, self.weights[j])
            })
            .collect();
        let x = nnls(&rows, lobes.len() + 1);
        let err = rows
            .iter()
            .map(|(b, y, w)| {
                let m: f64 = b.iter().zip(&x).map(|(b, x)| b * x).sum();
                w * (m - y).powi(2)
            })
            .sum();
        (x, err)
    }

    /// The best single lobe over the grid (smallest error; the first on ties).
    fn best_single(&self, grid: usize, fixed: Option<(usize, f64)>) -> (usize, Vec<f64>, f64) {
        let fits: Vec<(Vec<f64>, f64)> = (0..grid)
            .into_par_iter()
            .map(|k| self.solve(&[k], fixed))
            .collect();
        let (k, (x, err)) = fits
            .into_iter()
            .enumerate()
            .min_by(|a, b| a.1.1.total_cmp(&b.1.1))
            .expect("the grid is not empty");
        (k, x, err)
    }
}

impl LobeModel {
    /// Fit to samples (at least one channel; directions in the upper hemisphere).
    ///
    /// On the channel mean: the best single lobe, or the best pair of lobes at least two grid
    /// steps apart when that lowers the weighted error by more than 1% (a second lobe that
    /// changes nothing is not one). With two lobes the narrower one is the surface reflection
    /// of the clear binder, whose Fresnel reflectance is the same in every band (a
    /// dielectric's dispersion changes it by about 1% across the visible): its roughness and
    /// weight are the channel mean's in every band. Then per band the body and the other lobe
    /// (pigment, flakes: coloured, and of a width that may change with the band, as the
    /// colour of a metallic paint travels with angle) are fitted, the lobe's roughness chosen
    /// from the grid.
    pub fn fit(samples: &[Sample]) -> LobeModel {
        let above: Vec<&Sample> = samples
            .iter()
            .filter(|s| s.wi.z > 0.0 && s.wo.z > 0.0)
            .collect();
        let nc = above.first().map_or(0, |s| s.values.len());
        let grid = alpha_grid();
        let shapes: Vec<Vec<f64>> = grid
            .iter()
            .map(|&a| above.iter().map(|s| lobe(a, s.wi, s.wo)).collect())
            .collect();
        let mean = Rows::new(
            &shapes,
            above
                .iter()
                .map(|s| s.values.iter().sum::<f64>() / nc.max(1) as f64)
                .collect(),
        );
        let (_, _, single_err) = mean.best_single(grid.len(), None);
        let pairs: Vec<[usize; 2]> = (0..grid.len())
            .flat_map(|a| (a + 2..grid.len()).map(move |b| [a, b]))
            .collect();
        let pair_fits: Vec<(Vec<f64>, f64)> =
            pairs.par_iter().map(|p| mean.solve(p, None)).collect();
        let best_pair = pair_fits
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.1.total_cmp(&b.1.1));
        // (Errors below 1e-12, an rms relative error of 3e-8 over the samples, are round-off.)
        let grey = best_pair
            .filter(|(_, (_, err))| single_err - err > 0.01 * single_err.max(1e-12))
            .map(|(i, (x, _))| (pairs[i][0], x[1]));
        let bands = (0..nc)
            .map(|c| {
                let rows = Rows::new(&shapes, above.iter().map(|s| s.values[c]).collect());
                let (k, x, _) = rows.best_single(grid.len(), grey);
                let mut lobes: Vec<Lobe> = grey
                    .map(|(g, s)| Lobe {
                        alpha: grid[g],
                        weight: s,
                    })
                    .into_iter()
                    .collect();
                lobes.push(Lobe {
                    alpha: grid[k],
                    weight: x[1],
                });
                BandModel { rho: x[0], lobes }
            })
            .collect();
        LobeModel { bands }
    }

    /// The model's f (1/sr) per band at a pair of directions; zero below the horizon.
    pub fn eval(&self, wi: DVec3, wo: DVec3, out: &mut [f64]) {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            out.fill(0.0);
            return;
        }
        for (o, band) in out.iter_mut().zip(&self.bands) {
            *o = band.rho / PI
                + band
                    .lobes
                    .iter()
                    .map(|l| l.weight * lobe(l.alpha, wi, wo))
                    .sum::<f64>();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::coords::dir;

    fn samples_of(truth: &LobeModel) -> Vec<Sample> {
        let mut samples = vec![];
        for ti in [10.0f64, 30.0, 50.0, 70.0] {
            for k in 0..40 {
                let wi = dir(ti.to_radians(), 0.0);
                let wo = dir((2.0 * k as f64).to_radians(), PI * (k % 3) as f64 / 2.0);
                let mut v = vec![0.0; truth.bands.len()];
                truth.eval(wi, wo, &mut v);
                samples.push(Sample { wi, wo, values: v });
            }
        }
        samples
    }

    fn band(rho: f64, lobes: &[(f64, f64)]) -> BandModel {
        BandModel {
            rho,
            lobes: lobes
                .iter()
                .map(|&(alpha, weight)| Lobe { alpha, weight })
                .collect(),
        }
    }

    fn assert_recovered(fit: &LobeModel, truth: &LobeModel) {
        for (got, want) in fit.bands.iter().zip(&truth.bands) {
            let close = |g: f64, w: f64| (g - w).abs() <= 1e-9 * w.max(1.0);
            assert!(close(got.rho, want.rho), "{got:?} vs {want:?}");
            assert_eq!(got.lobes.len(), want.lobes.len(), "{got:?} vs {want:?}");
            for (g, w) in got.lobes.iter().zip(&want.lobes) {
                assert_eq!(g.alpha, w.alpha, "{got:?} vs {want:?}");
                assert!(close(g.weight, w.weight), "{got:?} vs {want:?}");
            }
        }
    }

    /// Samples of a known model with one lobe per band are fitted back exactly: with the
    /// roughness on the grid the problem is linear and noise-free, so the weights come back to
    /// round-off.
    #[test]
    fn recovers_a_lambert_plus_lobe_model() {
        let a = alpha_grid()[9];
        let truth = LobeModel {
            bands: vec![band(0.3, &[(a, 0.8)]), band(0.1, &[(a, 0.5)])],
        };
        assert_recovered(&LobeModel::fit(&samples_of(&truth)), &truth);
    }

    /// A grey narrow lobe over coloured bodies and broad lobes: the narrow lobe is found with
    /// its weight in every band, the rest per band.
    #[test]
    fn recovers_a_grey_surface_lobe_over_coloured_bands() {
        let (narrow, broad) = (alpha_grid()[2], alpha_grid()[11]);
        let truth = LobeModel {
            bands: vec![
                band(0.3, &[(narrow, 0.05), (broad, 0.4)]),
                band(0.1, &[(narrow, 0.05), (broad, 0.1)]),
            ],
        };
        assert_recovered(&LobeModel::fit(&samples_of(&truth)), &truth);
    }

    /// Every term is reciprocal.
    #[test]
    fn model_is_reciprocal() {
        let m = LobeModel {
            bands: vec![band(0.2, &[(0.05, 1.0), (0.3, 0.5)])],
        };
        let (wi, wo) = (dir(0.4, 0.1), dir(1.1, 2.9));
        let (mut a, mut b) = ([0.0], [0.0]);
        m.eval(wi, wo, &mut a);
        m.eval(wo, wi, &mut b);
        assert!((a[0] - b[0]).abs() < 1e-12 * a[0]);
    }

    /// `y = x - 0.5` on the basis `(x, 1)`: the unconstrained solution has a negative constant;
    /// the non-negative one drops it and fits `y ≈ b x` with `b = Σxy / Σx²`.
    #[test]
    fn nnls_drops_a_negative_coefficient() {
        let rows: Vec<(Vec<f64>, f64, f64)> = (1..10)
            .map(|k| {
                let x = k as f64;
                (vec![x, 1.0], x - 0.5, 1.0)
            })
            .collect();
        let sol = nnls(&rows, 2);
        let (sxy, sxx) = (1..10).fold((0.0, 0.0), |(a, b), k| {
            let x = k as f64;
            (a + x * (x - 0.5), b + x * x)
        });
        assert_eq!(sol[1], 0.0);
        assert!((sol[0] - sxy / sxx).abs() < 1e-12, "{sol:?}");
    }
}
