//! Sampling from tabulated weights: piecewise-constant densities on [0, 1) and [0, 1)², sampled
//! by inverting their cumulative distributions (pbrt-v4 §A.4.2 "Piecewise-constant 1D and 2D
//! distributions"). The renderer's environment light draws its pixels from a
//! [`PiecewiseConstant2D`]. (Inversion, not Walker's alias method: inversion is monotone, so it
//! keeps the stratification of low-discrepancy samples.)
//!
//! The Mitsuba tensor export and the table sampler (`table::sampler`) use the
//! piecewise-*bilinear* warp beside these ([`super::bilinear::Marginal2D`]): it must reproduce
//! Mitsuba's `Marginal2D` exactly, which interpolates its density between nodes rather than
//! holding it constant in cells, and as a warp it is continuous.

use glam::DVec2;

/// A piecewise-constant density on [0, 1) over `n` equal bins, in proportion to non-negative
/// weights, sampled by inverting its cumulative distribution.
#[derive(Debug, Clone)]
pub struct PiecewiseConstant1D {
    /// Cumulative sums normalised to end at 1; `cdf[0] = 0`, length `n + 1`.
    cdf: Vec<f64>,
    /// Sum of the weights.
    total: f64,
}

impl PiecewiseConstant1D {
    /// The density of `weights` (negative weights count as zero).
    pub fn new(weights: &[f64]) -> PiecewiseConstant1D {
        let mut cdf = Vec::with_capacity(weights.len() + 1);
        let mut acc = 0.0;
        cdf.push(0.0);
        for w in weights {
            acc += w.max(0.0);
            cdf.push(acc);
        }
        if acc > 0.0 {
            cdf.iter_mut().for_each(|c| *c /= acc);
        }
        PiecewiseConstant1D { cdf, total: acc }
    }

    /// Number of bins.
    pub fn len(&self) -> usize {
        self.cdf.len() - 1
    }

    /// Whether there are no bins.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Sum of the weights (zero: nothing can be sampled).
    pub fn total(&self) -> f64 {
        self.total
    }

    /// A bin and the continuous position in [0, 1) within the whole range from a uniform `u`.
    pub fn sample(&self, u: f64) -> (usize, f64) {
        let n = self.len();
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, n) - 1;
        let width = self.cdf[i + 1] - self.cdf[i];
        let frac = if width > 0.0 {
            ((u - self.cdf[i]) / width).clamp(0.0, 1.0 - 1e-12)
        } else {
            0.5
        };
        (i, (i as f64 + frac) / n as f64)
    }

    /// The density on [0, 1) in bin `i`.
    pub fn density(&self, i: usize) -> f64 {
        (self.cdf[i + 1] - self.cdf[i]) * self.len() as f64
    }
}

/// A piecewise-constant density on [0, 1)² over `width × height` equal cells: the marginal
/// density of the rows and, per row, the conditional density of its columns.
#[derive(Debug, Clone)]
pub struct PiecewiseConstant2D {
    rows: PiecewiseConstant1D,
    cols: Vec<PiecewiseConstant1D>,
}

impl PiecewiseConstant2D {
    /// The density of `weights`, row-major with `width` columns per row.
    pub fn new(weights: &[f64], width: usize) -> PiecewiseConstant2D {
        let cols: Vec<PiecewiseConstant1D> = weights
            .chunks(width.max(1))
            .map(PiecewiseConstant1D::new)
            .collect();
        let rows = PiecewiseConstant1D::new(&cols.iter().map(|c| c.total).collect::<Vec<_>>());
        PiecewiseConstant2D { rows, cols }
    }

    /// Sum of the weights (zero: nothing can be sampled).
    pub fn total(&self) -> f64 {
        self.rows.total
    }

    /// A cell (column, row) and the continuous position in [0, 1)² (x along the columns, y
    /// along the rows) from a uniform `u`: `u.x` picks the row, `u.y` the column in it.
    pub fn sample(&self, u: DVec2) -> ((usize, usize), DVec2) {
        let (j, y) = self.rows.sample(u.x);
        let (i, x) = self.cols[j].sample(u.y);
        ((i, j), DVec2::new(x, y))
    }

    /// The density on [0, 1)² in column `i` of row `j`.
    pub fn density(&self, i: usize, j: usize) -> f64 {
        self.rows.density(j) * self.cols[j].density(i)
    }
}
