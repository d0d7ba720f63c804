//! Global sensitivity analysis of any model with a few bounded inputs and several outputs: which
//! inputs the outputs depend on, and how much. Generic (no physics): the model is a function of
//! a point in physical units returning its outputs.
//!
//! The workflow is SALib's (Herman & Usher, JOSS 2, 97, 2017; Iwanaga, Usher & Herman,
//! Socio-Environmental Systems Modelling 4, 18155, 2022): a method's sampler returns the points
//! (one row per evaluation, one column per input, in physical units), [`evaluate`] runs the model
//! at every point (rows × outputs), and the method's analysis turns the points and outputs into
//! indices, one set per output:
//!
//! - [`sobol`]: variance-based first-order and total indices (Saltelli's design, Saltelli 2010's
//!   and Jansen's estimators) with bootstrap confidence intervals;
//! - [`morris`]: elementary effects on a grid (Morris 1991; μ, μ* and σ per input, Campolongo
//!   et al. 2007), a screening at a few evaluations per input.
//!
//! The analyses are the formulas of SALib 1.6.0's `sobol.analyze` and `morris.analyze` and equal
//! them on the same points and outputs to about 1e-12 (an oracle test runs SALib).

pub mod morris;
pub mod sobol;

use crate::error::{FormulationError, Result};
use ndarray::Array2;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;

/// Φ⁻¹(0.975): the standard normal quantile of a two-sided 95% interval. The confidence
/// intervals are normal-approximation bootstrap intervals, `estimate ± Z95 · s*`, s* the standard
/// deviation (n − 1) of the estimate over the resamples (SALib's, with conf_level = 0.95).
pub const Z95: f64 = 1.959_963_984_540_054;

/// Resamples the bootstrap intervals draw unless told otherwise (SALib's default).
pub const RESAMPLES: usize = 100;

/// One input of a model: its name and its range `[lo, hi]` in physical units, over which it is
/// taken as uniformly distributed.
#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    pub name: String,
    pub lo: f64,
    pub hi: f64,
}

impl Input {
    /// The input `name` over `[lo, hi]`.
    pub fn new(name: impl Into<String>, lo: f64, hi: f64) -> Self {
        Input {
            name: name.into(),
            lo,
            hi,
        }
    }

    /// The physical value at the unit coordinate `u` ∈ [0, 1] (`u (hi − lo) + lo`, SALib's
    /// `scale_samples`).
    pub fn scale(&self, u: f64) -> f64 {
        u * (self.hi - self.lo) + self.lo
    }
}

/// The inputs of a sensitivity analysis, checked: at least one, each named once, bounds finite
/// with `lo < hi`.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    inputs: Vec<Input>,
}

impl Problem {
    /// Check and keep `inputs`.
    pub fn new(inputs: Vec<Input>) -> Result<Self> {
        if inputs.is_empty() {
            return Err(invalid("a sensitivity analysis needs at least one input"));
        }
        for (k, input) in inputs.iter().enumerate() {
            if input.name.trim().is_empty() {
                return Err(invalid(format!("input {}: the name is empty", k + 1)));
            }
            if inputs[..k].iter().any(|other| other.name == input.name) {
                return Err(invalid(format!("input '{}' is named twice", input.name)));
            }
            if !(input.lo.is_finite() && input.hi.is_finite() && input.lo < input.hi) {
                return Err(invalid(format!(
                    "input '{}': bounds [{}, {}] must be finite with the lower below the upper",
                    input.name, input.lo, input.hi
                )));
            }
        }
        Ok(Problem { inputs })
    }

    /// The inputs, in the order of the points' columns.
    pub fn inputs(&self) -> &[Input] {
        &self.inputs
    }

    /// The number of inputs, d.
    pub fn dimension(&self) -> usize {
        self.inputs.len()
    }

    /// Refuse `points` that do not have one column per input.
    fn check_points(&self, points: &Array2<f64>) -> Result<()> {
        if points.ncols() != self.dimension() {
            return Err(invalid(format!(
                "the points have {} columns for {} inputs",
                points.ncols(),
                self.dimension()
            )));
        }
        Ok(())
    }
}

/// Evaluate `model` at every row of `points` (one column per input, physical units), in
/// parallel, into a matrix of one row per point and `outputs` columns. Each point is evaluated
/// on its own and written to its own row, so the result does not depend on the number of
/// threads or on the order the points are run in (provided the model itself does not). A model
/// error, an output count other than `outputs` or a value that is not finite is an error naming
/// the point.
pub fn evaluate<F>(points: &Array2<f64>, outputs: usize, model: F) -> Result<Array2<f64>>
where
    F: Fn(&[f64]) -> Result<Vec<f64>> + Sync,
{
    let rows = (0..points.nrows())
        .into_par_iter()
        .map(|i| {
            let x = points.row(i).to_vec();
            let describe = || format!("point {} ({x:?})", i + 1);
            let y = model(&x).map_err(|e| invalid(format!("{}: {e}", describe())))?;
            if y.len() != outputs {
                return Err(invalid(format!(
                    "{}: the model returned {} outputs, {outputs} expected",
                    describe(),
                    y.len()
                )));
            }
            if let Some(k) = y.iter().position(|v| !v.is_finite()) {
                return Err(invalid(format!(
                    "{}: output {} is {}",
                    describe(),
                    k + 1,
                    y[k]
                )));
            }
            Ok(y)
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(
        Array2::from_shape_vec((points.nrows(), outputs), rows.concat())
            .expect("one row of `outputs` values per point"),
    )
}

/// Refuse outputs that are not all finite, naming the first such value.
fn check_finite(outputs: &Array2<f64>) -> Result<()> {
    if let Some(((row, column), v)) = outputs.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(invalid(format!(
            "output {} of row {} is {v}: the outputs must be finite",
            column + 1,
            row + 1
        )));
    }
    Ok(())
}

/// `count` bootstrap resamples of `n` rows (indices drawn uniformly with replacement), from a
/// PCG-64 stream seeded by `seed`: the same seed gives the same resamples.
fn resamples(n: usize, count: usize, seed: u64) -> Vec<Vec<usize>> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..count)
        .map(|_| (0..n).map(|_| rng.random_range(0..n)).collect())
        .collect()
}

/// The mean of `values`.
fn mean(values: impl ExactSizeIterator<Item = f64>) -> f64 {
    let n = values.len() as f64;
    values.sum::<f64>() / n
}

/// The standard deviation of `values` with `n − 1` in the denominator.
pub(crate) fn sample_std(values: &[f64]) -> f64 {
    let m = mean(values.iter().copied());
    let ss: f64 = values.iter().map(|v| (v - m) * (v - m)).sum();
    (ss / (values.len() as f64 - 1.0)).sqrt()
}

/// The error for an invalid input.
fn invalid(message: impl Into<String>) -> FormulationError {
    FormulationError::Invalid(message.into())
}
