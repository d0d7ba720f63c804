//! Variance-based sensitivity: Sobol's first-order and total indices (Sobol, Math. Comput.
//! Simul. 55, 271, 2001) of each output with respect to each input, the inputs independent and
//! uniform over their bounds.
//!
//! For an output Y = f(X₁ … X_d) of variance V, the first-order index of X_i is
//! `S_i = V[E(Y | X_i)] / V` (the share of the variance X_i explains alone) and the total index
//! `S_Ti = E[V(Y | X_~i)] / V` (the share left when every other input is known: X_i alone and
//! in all its interactions). An input with `S_Ti ≈ 0` can be fixed anywhere in its range.
//!
//! Design (Saltelli, Comput. Phys. Commun. 145, 280, 2002; SALib's `sample.sobol` with
//! calc_second_order = False): N points of a d × 2 dimensional Sobol sequence, Owen-scrambled
//! (Burley, JCGT 9(4), 2020, the `sobol_burley` crate), give two N × d matrices, A (the first d
//! coordinates) and B (the last d), and the d matrices `AB_i`, A with its column i taken from B.
//! The points are laid out as SALib lays them: for each base point n the rows A_n, AB_1,n …
//! AB_d,n, B_n, so N (d + 2) evaluations in all.
//!
//! Estimators (Saltelli, Annoni, Azzini, Campolongo, Ratto & Tarantola, Comput. Phys. Commun.
//! 181, 259, 2010, Table 2: (b) for the first order, (f) for the total, which is Jansen's, Comput.
//! Phys. Commun. 117, 35, 1999), as SALib 1.6.0's `analyze.sobol` computes them
//! (src/SALib/analyze/sobol.py, `first_order` and `total_order`): the outputs of each column are
//! first standardised over all N (d + 2) rows, `y ← (y − ȳ)/s` (s with n in the denominator),
//! then
//!
//! `S_i = (1/N) Σ_n f(B)_n (f(AB_i)_n − f(A)_n) / V`,
//! `S_Ti = (1/2N) Σ_n (f(A)_n − f(AB_i)_n)² / V`,
//!
//! V the variance (n in the denominator) of the 2N values of f(A) and f(B). An output that does
//! not vary over A and B (range below machine epsilon) gets indices 0, as SALib's.
//!
//! Confidence: the N rows are resampled with replacement ([`super::RESAMPLES`] times, seeded);
//! each interval is `± Z95 · s*`, s* the standard deviation of the estimate over the resamples
//! (the normal-approximation bootstrap interval SALib reports). It treats the rows as independent
//! draws, which over-states the error of a scrambled Sobol design (randomised quasi-Monte Carlo
//! converges faster than N^(−1/2) for smooth outputs): the intervals are conservative.

use super::{Problem, RESAMPLES, Z95, check_finite, invalid, mean, resamples, sample_std};
use crate::error::Result;
use ndarray::Array2;

/// The largest base sample (the Sobol sequence of `sobol_burley` has 2¹⁶ points).
pub const MAX_BASE: usize = 1 << 16;

/// The most inputs (the sequence has 256 dimensions, two per input).
pub const MAX_INPUTS: usize = 128;

/// Saltelli's design for `problem` from a base sample of `base` points (a power of two keeps the
/// Sobol sequence balanced) of the Owen-scrambled Sobol sequence seeded by `seed`: `base (d + 2)`
/// rows of d columns, physical units, laid out as the module says.
pub fn sample(problem: &Problem, base: usize, seed: u32) -> Result<Array2<f64>> {
    let d = problem.dimension();
    if d > MAX_INPUTS {
        return Err(invalid(format!(
            "a Sobol design of {d} inputs: at most {MAX_INPUTS}"
        )));
    }
    if !(2..=MAX_BASE).contains(&base) {
        return Err(invalid(format!(
            "a base sample of {base} points: between 2 and {MAX_BASE} (a power of two)"
        )));
    }
    let mut points = Array2::zeros((base * (d + 2), d));
    for n in 0..base {
        let u = |dim: usize| f64::from(sobol_burley::sample(n as u32, dim as u32, seed));
        let row0 = n * (d + 2);
        for (j, input) in problem.inputs().iter().enumerate() {
            let (a, b) = (input.scale(u(j)), input.scale(u(j + d)));
            points[[row0, j]] = a;
            for i in 0..d {
                points[[row0 + 1 + i, j]] = if i == j { b } else { a };
            }
            points[[row0 + d + 1, j]] = b;
        }
    }
    Ok(points)
}

/// The indices of one output, one value per input in the problem's order.
#[derive(Clone, Debug, PartialEq)]
pub struct SobolIndices {
    /// First-order indices S_i.
    pub s1: Vec<f64>,
    /// Half-widths of their 95% bootstrap intervals.
    pub s1_conf: Vec<f64>,
    /// Total indices S_Ti.
    pub st: Vec<f64>,
    /// Half-widths of their 95% bootstrap intervals.
    pub st_conf: Vec<f64>,
    /// The output's variance over the whole design, in its own units squared (n in the
    /// denominator); 0 for an output that does not vary.
    pub variance: f64,
}

/// The Sobol indices of each column of `outputs` (rows: the evaluations of [`sample`]'s design,
/// in its order), with [`RESAMPLES`] bootstrap resamples drawn from `seed`.
pub fn analyze(problem: &Problem, outputs: &Array2<f64>, seed: u64) -> Result<Vec<SobolIndices>> {
    let d = problem.dimension();
    let rows = outputs.nrows();
    if rows == 0 || !rows.is_multiple_of(d + 2) {
        return Err(invalid(format!(
            "{rows} rows of outputs: a Sobol design of {d} inputs has a multiple of d + 2 = {} \
             rows (N base points × (d + 2))",
            d + 2
        )));
    }
    check_finite(outputs)?;
    let n = rows / (d + 2);
    if n < 2 {
        return Err(invalid("a Sobol design needs at least two base points"));
    }
    let draws = resamples(n, RESAMPLES, seed);
    Ok(outputs
        .columns()
        .into_iter()
        .map(|column| {
            let y: Vec<f64> = column.to_vec();
            let y_mean = mean(y.iter().copied());
            let variance = mean(y.iter().map(|v| (v - y_mean) * (v - y_mean)));
            let std = variance.sqrt();
            let y: Vec<f64> = y.iter().map(|v| (v - y_mean) / std).collect();
            let a: Vec<f64> = (0..n).map(|k| y[k * (d + 2)]).collect();
            let b: Vec<f64> = (0..n).map(|k| y[k * (d + 2) + d + 1]).collect();
            let mut indices = SobolIndices {
                s1: vec![0.0; d],
                s1_conf: vec![0.0; d],
                st: vec![0.0; d],
                st_conf: vec![0.0; d],
                variance,
            };
            if variance == 0.0 {
                return indices;
            }
            for i in 0..d {
                let ab: Vec<f64> = (0..n).map(|k| y[k * (d + 2) + 1 + i]).collect();
                let all: Vec<usize> = (0..n).collect();
                let (s1, st) = estimate(&a, &ab, &b, &all);
                let (s1s, sts): (Vec<f64>, Vec<f64>) =
                    draws.iter().map(|r| estimate(&a, &ab, &b, r)).unzip();
                indices.s1[i] = s1;
                indices.st[i] = st;
                indices.s1_conf[i] = Z95 * sample_std(&s1s);
                indices.st_conf[i] = Z95 * sample_std(&sts);
            }
            indices
        })
        .collect())
}

/// `(S_i, S_Ti)` from the rows `rows` of the standardised outputs at A, AB_i and B (Saltelli
/// 2010 (b) and Jansen), 0 when f(A) and f(B) do not vary over these rows.
fn estimate(a: &[f64], ab: &[f64], b: &[f64], rows: &[usize]) -> (f64, f64) {
    let pooled = || rows.iter().map(|&k| a[k]).chain(rows.iter().map(|&k| b[k]));
    let (lo, hi) = pooled().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if hi - lo <= f64::EPSILON {
        return (0.0, 0.0);
    }
    let m = pooled().sum::<f64>() / (2 * rows.len()) as f64;
    let var = pooled().map(|v| (v - m) * (v - m)).sum::<f64>() / (2 * rows.len()) as f64;
    if var <= f64::EPSILON {
        return (0.0, 0.0);
    }
    let first = mean(rows.iter().map(|&k| b[k] * (ab[k] - a[k])));
    let total = 0.5 * mean(rows.iter().map(|&k| (a[k] - ab[k]) * (a[k] - ab[k])));
    (first / var, total / var)
}
