//! Statistical validation of a BRDF's importance sampler, for any [`Brdf`] (analytic models and
//! tables alike): a chi-square goodness-of-fit test of the sampled directions against the pdf,
//! a check that every sample carries the value and pdf that `eval` and `pdf` give, and a check
//! that the Monte Carlo estimate `mean(f cos θi / pdf)` equals the albedo computed by
//! deterministic quadrature within its standard error.
//!
//! The chi-square test follows the one of Mitsuba (W. Jakob, `mitsuba/chi2.py`): bins in
//! (θ, φ), expected counts by integrating the pdf over each bin, bins of low expectation pooled
//! until the pool expects at least 5, and the p-value from the regularised incomplete gamma
//! function (Numerical Recipes, 3rd ed., §6.2).

use crate::bxdf::{Brdf, Rgb};
use glam::{DVec2, DVec3};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use std::f64::consts::{FRAC_PI_2, PI};

/// Settings of [`check_sampler`].
#[derive(Debug, Clone, PartialEq)]
pub struct SamplerCheck {
    /// Number of sampled directions.
    pub samples: usize,
    /// Bins in θ over [0, π/2] (equal widths in θ).
    pub theta_bins: usize,
    /// Bins in φ over [0, 2π).
    pub phi_bins: usize,
    /// Midpoint-rule points per bin and axis when integrating the pdf over a bin.
    pub quadrature: usize,
    /// Points in θ of the albedo quadrature (twice as many in φ).
    pub albedo_theta_points: usize,
    /// Relative error allowed to the albedo quadrature, on top of 4 standard errors of the
    /// Monte Carlo estimate.
    pub albedo_tolerance: f64,
    /// The test fails when the chi-square p-value falls below this.
    pub significance: f64,
    /// Seed of the random numbers fed to the sampler.
    pub seed: u64,
}

impl Default for SamplerCheck {
    fn default() -> Self {
        SamplerCheck {
            samples: 200_000,
            theta_bins: 40,
            phi_bins: 80,
            quadrature: 4,
            albedo_theta_points: 400,
            albedo_tolerance: 1e-3,
            significance: 1e-4,
            seed: 1,
        }
    }
}

/// The outcome of [`check_sampler`].
#[derive(Debug, Clone, PartialEq)]
pub struct SamplerReport {
    /// Pearson's chi-square statistic over the pooled bins.
    pub chi_square: f64,
    /// Degrees of freedom (pooled bins less one).
    pub dof: usize,
    /// Probability of a statistic at least this large if the sampler follows its pdf.
    pub p_value: f64,
    /// Monte Carlo estimate of the albedo `∫ f cos θi dωi`.
    pub albedo_mc: Rgb,
    /// Standard error of `albedo_mc`.
    pub albedo_std_error: Rgb,
    /// The albedo by deterministic quadrature.
    pub albedo_quadrature: Rgb,
    /// Every check that failed, in words; empty when the sampler passed.
    pub problems: Vec<String>,
}

impl SamplerReport {
    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.problems.is_empty()
    }
}

/// The direction at polar angle `theta` and azimuth `phi`.
fn direction(theta: f64, phi: f64) -> DVec3 {
    let (s, c) = theta.sin_cos();
    DVec3::new(s * phi.cos(), s * phi.sin(), c)
}

/// Albedo `∫ f(wo, wi) cos θi dωi` by the midpoint rule on `n × 2n` points in (θi, φi).
pub fn albedo(brdf: &dyn Brdf, wo: DVec3, n: usize) -> Rgb {
    let (dt, dp) = (FRAC_PI_2 / n as f64, PI / n as f64);
    let mut sum = Rgb::ZERO;
    for i in 0..n {
        let theta = (i as f64 + 0.5) * dt;
        let (s, c) = theta.sin_cos();
        for j in 0..2 * n {
            let wi = direction(theta, (j as f64 + 0.5) * dp);
            sum += brdf.eval(wo, wi) * (c * s);
        }
    }
    sum * (dt * dp)
}

/// Expected fraction of samples in each (θ, φ) bin: the pdf integrated over the bin.
fn bin_probabilities(brdf: &dyn Brdf, wo: DVec3, opts: &SamplerCheck) -> Vec<f64> {
    let (nt, np, q) = (opts.theta_bins, opts.phi_bins, opts.quadrature);
    let (dt, dp) = (FRAC_PI_2 / nt as f64, 2.0 * PI / np as f64);
    let (st, sp) = (dt / q as f64, dp / q as f64);
    let mut probs = Vec::with_capacity(nt * np);
    for i in 0..nt {
        for j in 0..np {
            let mut sum = 0.0;
            for a in 0..q {
                let theta = i as f64 * dt + (a as f64 + 0.5) * st;
                for b in 0..q {
                    let phi = j as f64 * dp + (b as f64 + 0.5) * sp;
                    sum += brdf.pdf(wo, direction(theta, phi)) * theta.sin();
                }
            }
            probs.push(sum * st * sp);
        }
    }
    probs
}

/// The bin of a direction above the surface.
fn bin_of(w: DVec3, opts: &SamplerCheck) -> usize {
    let theta = w.z.clamp(-1.0, 1.0).acos();
    let phi = w.y.atan2(w.x).rem_euclid(2.0 * PI);
    let i = ((theta / FRAC_PI_2 * opts.theta_bins as f64) as usize).min(opts.theta_bins - 1);
    let j = ((phi / (2.0 * PI) * opts.phi_bins as f64) as usize).min(opts.phi_bins - 1);
    i * opts.phi_bins + j
}

/// Relative difference, safe at zero.
fn rel_diff(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

/// Sample `brdf` from `wo` with the settings `opts` and run every check (see the module
/// documentation). A failed `sample` (`None`) counts in its own bin, whose expected share is
/// one less the integral of the pdf over the hemisphere.
pub fn check_sampler(brdf: &dyn Brdf, wo: DVec3, opts: &SamplerCheck) -> SamplerReport {
    let mut problems = Vec::new();
    let mut rng = Pcg64::seed_from_u64(opts.seed);
    let cells = opts.theta_bins * opts.phi_bins;
    let mut observed = vec![0.0; cells + 1];
    let (mut sum, mut sum2) = (Rgb::ZERO, Rgb::ZERO);
    let mut mismatches = 0usize;
    for _ in 0..opts.samples {
        let u = DVec2::new(rng.random::<f64>(), rng.random::<f64>());
        let Some(s) = brdf.sample(wo, u) else {
            observed[cells] += 1.0;
            continue;
        };
        let (f, pdf) = (brdf.eval(wo, s.wi), brdf.pdf(wo, s.wi));
        let bad = (s.wi.length() - 1.0).abs() > 1e-9
            || s.wi.z <= 0.0
            || !(s.pdf > 0.0 && s.pdf.is_finite())
            || rel_diff(s.pdf, pdf) > 1e-6
            || (0..3).any(|c| rel_diff(s.f[c], f[c]) > 1e-6);
        if bad {
            if mismatches < 5 {
                problems.push(format!(
                    "sample wi = {} has f = {}, pdf = {}, but eval gives {f} and pdf gives {pdf}",
                    s.wi, s.f, s.pdf
                ));
            }
            mismatches += 1;
            continue;
        }
        observed[bin_of(s.wi, opts)] += 1.0;
        let weight = s.f * (s.wi.z / s.pdf);
        sum += weight;
        sum2 += weight * weight;
    }
    if mismatches > 5 {
        problems.push(format!(
            "{mismatches} samples in all disagree with eval/pdf"
        ));
    }

    let n = opts.samples as f64;
    let mut expected: Vec<f64> = bin_probabilities(brdf, wo, opts)
        .into_iter()
        .map(|p| p * n)
        .collect();
    let total: f64 = expected.iter().sum();
    expected.push((n - total).max(0.0));
    let (chi_square, dof) = pooled_chi_square(&observed, &expected);
    let p_value = chi_square_p_value(chi_square, dof);
    if p_value < opts.significance {
        problems.push(format!(
            "chi-square {chi_square:.1} with {dof} degrees of freedom: p = {p_value:.3e} < {}",
            opts.significance
        ));
    }

    let albedo_mc = sum / n;
    let variance = (sum2 / n - albedo_mc * albedo_mc).max(Rgb::ZERO) * (n / (n - 1.0));
    let albedo_std_error = (variance / n).powf(0.5);
    let albedo_quadrature = albedo(brdf, wo, opts.albedo_theta_points);
    for c in 0..3 {
        let allowed = 4.0 * albedo_std_error[c] + opts.albedo_tolerance * albedo_quadrature[c];
        if (albedo_mc[c] - albedo_quadrature[c]).abs() > allowed {
            problems.push(format!(
                "channel {c}: Monte Carlo albedo {:.6} ± {:.6} but quadrature gives {:.6}",
                albedo_mc[c], albedo_std_error[c], albedo_quadrature[c]
            ));
        }
    }
    SamplerReport {
        chi_square,
        dof,
        p_value,
        albedo_mc,
        albedo_std_error,
        albedo_quadrature,
        problems,
    }
}

/// Pearson's statistic over cells whose expected counts are pooled, smallest first, until
/// each pooled cell expects at least 5; returns the statistic and the degrees of freedom.
pub fn pooled_chi_square(observed: &[f64], expected: &[f64]) -> (f64, usize) {
    let mut order: Vec<usize> = (0..expected.len()).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let (mut chi2, mut cells) = (0.0, 0usize);
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    for k in order {
        let (o, e) = (observed[k], expected[k]);
        if e < 5.0 || pool_e > 0.0 && pool_e < 5.0 {
            pool_o += o;
            pool_e += e;
            if pool_e >= 5.0 {
                chi2 += (pool_o - pool_e).powi(2) / pool_e;
                cells += 1;
                (pool_o, pool_e) = (0.0, 0.0);
            }
        } else {
            chi2 += (o - e).powi(2) / e;
            cells += 1;
        }
    }
    if pool_e > 0.0 {
        chi2 += (pool_o - pool_e).powi(2) / pool_e;
        cells += 1;
    } else if pool_o > 0.0 {
        // Samples where the pdf integrates to nothing: no sampler that matches its pdf does it.
        return (f64::INFINITY, cells.max(1));
    }
    (chi2, cells.saturating_sub(1).max(1))
}

/// Probability that a chi-square variable with `dof` degrees of freedom exceeds `statistic`:
/// `Q(dof/2, statistic/2)`.
pub fn chi_square_p_value(statistic: f64, dof: usize) -> f64 {
    if statistic.is_infinite() {
        return 0.0;
    }
    gamma_q(0.5 * dof as f64, 0.5 * statistic)
}

/// The regularised upper incomplete gamma function `Q(a, x) = Γ(a, x)/Γ(a)` for `a > 0`,
/// `x ≥ 0`: its series for `x < a + 1`, else Lentz's continued fraction (Numerical Recipes,
/// 3rd ed., §6.2.1 and §6.2.2), both to relative precision 1e-15.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let log_prefactor = -x + a * x.ln() - libm::lgamma(a);
    if x < a + 1.0 {
        let (mut term, mut sum, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..100_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        1.0 - sum * log_prefactor.exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..100_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        log_prefactor.exp() * h
    }
}
