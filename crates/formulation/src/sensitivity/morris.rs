//! Morris's elementary effects (Morris, Technometrics 33, 161, 1991): a screening of which
//! inputs matter at a few evaluations per input, with the statistics of Campolongo, Cariboni &
//! Saltelli (Environ. Model. Softw. 22, 1509, 2007).
//!
//! Design (SALib 1.6.0's `sample.morris` with optimal_trajectories = None, no groups): each
//! input's unit range is a grid of p levels `0, 1/(p−1), …, 1` (p even) and the step is
//! `Δ = p / (2 (p − 1))`. A trajectory starts at a random grid point x* whose coordinates are
//! drawn from the lower half of the levels, `{0, …, (p/2 − 1)/(p − 1)}`, and a random direction
//! D_j = ±1 per input; its d + 1 points move the inputs one at a time, in a random order, each
//! by +Δ (D_j = +1, from x*_j) or −Δ (D_j = −1, from x*_j + Δ), so that every point stays on the
//! grid: the matrix B* = x* + (Δ/2) ((2 B P* − J) D* + J) of Morris's eq. (3), B the strictly
//! lower triangular matrix of ones, P* a random permutation, J ones. Trajectories follow each
//! other: r (d + 1) rows.
//!
//! Elementary effects, as SALib's `analyze.morris` (src/SALib/analyze/morris.py): between two
//! consecutive points of a trajectory exactly one input j changed, and
//! `EE_j = (y(up) − y(down)) / Δ`, with y(up) the output at the point where x_j is the larger.
//! Δ is the step in unit range, so EE is the output's change per whole range of the input: for
//! `y = c x_j` over `[lo, hi]`, `EE_j = c (hi − lo)`. Over the r trajectories: μ (mean), μ*
//! (mean of |EE|, Campolongo et al.: large for an input that matters even when its effects
//! change sign), σ (standard deviation with r − 1: nonlinearity or interactions), and μ*'s 95%
//! interval by bootstrap (r effects resampled with replacement, [`super::RESAMPLES`] times,
//! seeded; `± Z95 · s*` as in [`super::sobol`]).

use super::{Problem, RESAMPLES, Z95, check_finite, invalid, mean, resamples, sample_std};
use crate::error::Result;
use ndarray::Array2;
use rand::seq::SliceRandom;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// Grid levels unless told otherwise (SALib's default).
pub const LEVELS: usize = 4;

/// Morris's step in unit range for `levels` grid levels, `p / (2 (p − 1))`.
pub fn delta(levels: usize) -> f64 {
    levels as f64 / (2.0 * (levels as f64 - 1.0))
}

/// Refuse a number of levels that is odd or below 2 (the design needs `p` even so that every
/// step of Δ lands on the grid with equal probability from each level; SALib warns).
fn check_levels(levels: usize) -> Result<()> {
    if levels < 2 || !levels.is_multiple_of(2) {
        return Err(invalid(format!(
            "{levels} Morris levels: an even number, 2 or more (4 is usual)"
        )));
    }
    Ok(())
}

/// `trajectories` Morris trajectories on a grid of `levels` levels for `problem`, from a PCG-64
/// stream seeded by `seed`: `trajectories (d + 1)` rows of d columns, physical units.
pub fn sample(
    problem: &Problem,
    trajectories: usize,
    levels: usize,
    seed: u64,
) -> Result<Array2<f64>> {
    check_levels(levels)?;
    if trajectories < 2 {
        return Err(invalid(format!(
            "{trajectories} Morris trajectories: at least 2 (σ needs two effects per input)"
        )));
    }
    let d = problem.dimension();
    let step = delta(levels);
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut points = Array2::zeros((trajectories * (d + 1), d));
    for t in 0..trajectories {
        // The order in which the inputs move: input j moves at step order[j] + 1.
        let mut order: Vec<usize> = (0..d).collect();
        order.shuffle(&mut rng);
        for (j, input) in problem.inputs().iter().enumerate() {
            let up = rng.random_bool(0.5);
            let start = rng.random_range(0..levels / 2) as f64 / (levels - 1) as f64;
            for k in 0..=d {
                let moved = order[j] < k;
                let u = match (up, moved) {
                    (true, false) | (false, true) => start,
                    (true, true) | (false, false) => start + step,
                };
                points[[t * (d + 1) + k, j]] = input.scale(u);
            }
        }
    }
    Ok(points)
}

/// The Morris statistics of one output, one value per input in the problem's order, in the
/// output's units per whole range of the input.
#[derive(Clone, Debug, PartialEq)]
pub struct MorrisEffects {
    /// Mean elementary effect μ.
    pub mu: Vec<f64>,
    /// Mean absolute elementary effect μ*.
    pub mu_star: Vec<f64>,
    /// Standard deviation of the elementary effects σ (r − 1 in the denominator).
    pub sigma: Vec<f64>,
    /// Half-width of μ*'s 95% bootstrap interval.
    pub mu_star_conf: Vec<f64>,
}

/// The elementary effects of each column of `outputs` at `points` (a design of [`sample`] with
/// `levels` levels, rows in its order), μ*'s intervals from [`RESAMPLES`] resamples drawn from
/// `seed`. Points that are not trajectories (consecutive points differing in other than one
/// input, an input not moving once per trajectory) are refused.
pub fn analyze(
    problem: &Problem,
    points: &Array2<f64>,
    outputs: &Array2<f64>,
    levels: usize,
    seed: u64,
) -> Result<Vec<MorrisEffects>> {
    check_levels(levels)?;
    problem.check_points(points)?;
    let d = problem.dimension();
    let rows = points.nrows();
    if rows != outputs.nrows() {
        return Err(invalid(format!(
            "{rows} points but {} rows of outputs",
            outputs.nrows()
        )));
    }
    if rows == 0 || !rows.is_multiple_of(d + 1) || rows / (d + 1) < 2 {
        return Err(invalid(format!(
            "{rows} points: a Morris design of {d} inputs has r (d + 1) = r × {} rows, r ≥ 2",
            d + 1
        )));
    }
    check_finite(outputs)?;
    let r = rows / (d + 1);
    // For each trajectory and input: the rows (up, down) between which the input moved.
    let mut moves = vec![vec![(0, 0); d]; r];
    for (t, row) in moves.iter_mut().enumerate() {
        let mut seen = vec![false; d];
        for k in 0..d {
            let (p, q) = (t * (d + 1) + k, t * (d + 1) + k + 1);
            let changed: Vec<usize> = (0..d)
                .filter(|&j| points[[q, j]] != points[[p, j]])
                .collect();
            let &[j] = changed.as_slice() else {
                return Err(invalid(format!(
                    "rows {} and {}: {} inputs change between them, one expected (not a Morris \
                     trajectory)",
                    p + 1,
                    q + 1,
                    changed.len()
                )));
            };
            if seen[j] {
                return Err(invalid(format!(
                    "trajectory {}: input '{}' moves twice (not a Morris trajectory)",
                    t + 1,
                    problem.inputs()[j].name
                )));
            }
            seen[j] = true;
            row[j] = if points[[q, j]] > points[[p, j]] {
                (q, p)
            } else {
                (p, q)
            };
        }
    }
    let step = delta(levels);
    let draws = resamples(r, RESAMPLES, seed);
    Ok(outputs
        .columns()
        .into_iter()
        .map(|y| {
            let mut effects = MorrisEffects {
                mu: vec![0.0; d],
                mu_star: vec![0.0; d],
                sigma: vec![0.0; d],
                mu_star_conf: vec![0.0; d],
            };
            for j in 0..d {
                let ee: Vec<f64> = moves
                    .iter()
                    .map(|m| (y[m[j].0] - y[m[j].1]) / step)
                    .collect();
                effects.mu[j] = mean(ee.iter().copied());
                effects.mu_star[j] = mean(ee.iter().map(|e| e.abs()));
                effects.sigma[j] = sample_std(&ee);
                let resampled: Vec<f64> = draws
                    .iter()
                    .map(|rows| mean(rows.iter().map(|&k| ee[k].abs())))
                    .collect();
                effects.mu_star_conf[j] = Z95 * sample_std(&resampled);
            }
            effects
        })
        .collect())
}
