//! The illuminated spot as a grid of facets: the bicubic spline through the height map sampled at
//! the centres of cells `r` times finer than the map, each cell carrying its centred height, the
//! spline's slopes there and the Schwartz window weight. Built once per refinement and reused for
//! every direction (the set-up half of the Kirchhoff engine).

use super::Spot;
use gonio_fft::Fft;
use gonio_surface::spline::BicubicSpline;
use num_complex::Complex64;
use rayon::prelude::*;
use std::sync::Arc;

/// The Schwartz test function `b(t) = exp(-1/(1 - t²))` for |t| < 1, else 0 (the window of
/// `docs/kirchhoff.md`, "Window"): smooth to every order at the edge of the spot, so the spot's
/// diffraction pattern decays faster than any power and does not ring.
pub(crate) fn schwartz(t: f64) -> f64 {
    if t.abs() < 1.0 {
        (-1.0 / (1.0 - t * t)).exp()
    } else {
        0.0
    }
}

/// The facets of one refinement, row-major `(ny, nx)`, coordinates relative to the spot centre.
pub(crate) struct FacetGrid {
    pub nx: usize,
    pub ny: usize,
    /// Cell size along x and y, metres.
    pub ax: f64,
    pub ay: f64,
    /// Centre of cell (0, 0) relative to the spot centre, metres.
    pub x0: f64,
    pub y0: f64,
    /// Mean height of the cell minus the window-weighted mean height of the spot, metres.
    pub h: Vec<f64>,
    /// Slopes ∂h/∂x, ∂h/∂y of the spline at the cell centre.
    pub hx: Vec<f64>,
    pub hy: Vec<f64>,
    /// Window weight; 0 outside the spot and on cells touching non-measured points.
    pub w: Vec<f64>,
    /// `Σ w² · ax · ay`, the discrete `∫∫ W² dx dy` of the normalisation.
    pub w2_area: f64,
    /// Cells inside the spot left out because they touch non-measured points.
    pub invalid_cells: usize,
    /// Inverse (e^{+i…}) FFTs along a row and along a column.
    pub row_fft: Arc<dyn Fft<f64>>,
    pub col_fft: Arc<dyn Fft<f64>>,
}

impl FacetGrid {
    /// Cells of `dx/r × dy/r` covering the spot's bounding square.
    pub fn build(spline: &BicubicSpline, spot: &Spot, r: usize) -> Self {
        let ax = spline.dx() / r as f64;
        let ay = spline.dy() / r as f64;
        let nx = cells_across(spot.diameter, ax);
        let ny = cells_across(spot.diameter, ay);
        let x0 = -0.5 * (nx - 1) as f64 * ax;
        let y0 = -0.5 * (ny - 1) as f64 * ay;
        let radius = 0.5 * spot.diameter;
        let cells: Vec<[f64; 4]> = (0..nx * ny)
            .into_par_iter()
            .map(|i| {
                let (x, y) = (x0 + (i % nx) as f64 * ax, y0 + (i / nx) as f64 * ay);
                let w = schwartz((x * x + y * y).sqrt() / radius);
                if w == 0.0 {
                    return [0.0; 4];
                }
                let (h, g) = spline.eval_with_gradient(spot.center.0 + x, spot.center.1 + y);
                if h.is_nan() || g.is_nan() {
                    [f64::NAN, 0.0, 0.0, 0.0]
                } else {
                    [h, g.x, g.y, w]
                }
            })
            .collect();
        let invalid_cells = cells.iter().filter(|c| c[0].is_nan()).count();
        let (sum_w, sum_wh) = cells
            .iter()
            .filter(|c| c[3] > 0.0)
            .fold((0.0, 0.0), |(s, sh), c| (s + c[3], sh + c[3] * c[0]));
        let mean = if sum_w > 0.0 { sum_wh / sum_w } else { 0.0 };
        // Mean height over the cell of the quadratic surface: the centre height plus
        // (h_xx ax² + h_yy ay²)/24, the curvatures from the neighbours' slopes. This removes the
        // first-order phase error of the tangent plane on the cells near stationary phase,
        // which carry the scattered field.
        let slope = |i: usize, j: usize, axis: usize| cells[j * nx + i][axis];
        let h = (0..nx * ny)
            .into_par_iter()
            .map(|idx| {
                let c = cells[idx];
                if c[3] <= 0.0 {
                    return 0.0;
                }
                let (i, j) = (idx % nx, idx / nx);
                let mut quad = 0.0;
                if i > 0 && i + 1 < nx {
                    quad += (slope(i + 1, j, 1) - slope(i - 1, j, 1)) * ax / 48.0;
                }
                if j > 0 && j + 1 < ny {
                    quad += (slope(i, j + 1, 2) - slope(i, j - 1, 2)) * ay / 48.0;
                }
                c[0] - mean + if quad.is_finite() { quad } else { 0.0 }
            })
            .collect();
        let w2_area = cells.iter().map(|c| c[3] * c[3]).sum::<f64>() * ax * ay;
        FacetGrid {
            nx,
            ny,
            ax,
            ay,
            x0,
            y0,
            h,
            hx: cells.iter().map(|c| c[1]).collect(),
            hy: cells.iter().map(|c| c[2]).collect(),
            w: cells.iter().map(|c| c[3]).collect(),
            w2_area,
            invalid_cells,
            row_fft: gonio_fft::plan_inverse(nx),
            col_fft: gonio_fft::plan_inverse(ny),
        }
    }

    /// Row `m` of the grid.
    pub fn row(&self, m: usize) -> super::kernel::RowCells<'_> {
        let range = m * self.nx..(m + 1) * self.nx;
        super::kernel::RowCells {
            h: &self.h[range.clone()],
            hx: &self.hx[range.clone()],
            hy: &self.hy[range.clone()],
            w: &self.w[range],
        }
    }

    /// The direct sum `Σ_j A_j exp(i (v·x_j + vz h_j))` at wave vector `v`, the facet integrals'
    /// sinc factors taken at `v_sinc` (equal to `v` for the exact facet integral).
    pub fn field(&self, v: [f64; 3], v_sinc: [f64; 3]) -> Complex64 {
        (0..self.ny)
            .into_par_iter()
            .map_init(
                || vec![Complex64::default(); self.nx],
                |row, m| {
                    let params = self.row_params(v, v_sinc, m);
                    super::kernel::fill_row(&self.row(m), &params, row);
                    row.iter().sum::<Complex64>()
                },
            )
            .collect::<Vec<_>>()
            .into_iter()
            .sum()
    }

    /// The kernel constants of row `m` for phase wave vector `v` and sinc wave vector `v_sinc`.
    pub fn row_params(&self, v: [f64; 3], v_sinc: [f64; 3], m: usize) -> super::kernel::RowParams {
        let y = self.y0 + m as f64 * self.ay;
        super::kernel::RowParams {
            vz: v[2],
            phase0: v[0] * self.x0 + v[1] * y,
            dphase: v[0] * self.ax,
            sx0: 0.5 * v_sinc[0] * self.ax,
            sx1: 0.5 * v_sinc[2] * self.ax,
            sy0: 0.5 * v_sinc[1] * self.ay,
            sy1: 0.5 * v_sinc[2] * self.ay,
            area: self.ax * self.ay,
        }
    }
}

/// Number of cells of size `a` spanning `diameter`, rounded up to the next product of 2, 3 and 5
/// so that the FFTs along rows and columns are fast (a prime factor like 31 in 1023 makes them
/// several times slower); the extra cells lie outside the spot, with zero weight.
pub(crate) fn cells_across(diameter: f64, a: f64) -> usize {
    let mut n = ((diameter / a - 1e-9).ceil() as usize).max(1);
    loop {
        let mut m = n;
        for p in [2, 3, 5] {
            while m.is_multiple_of(p) {
                m /= p;
            }
        }
        if m == 1 {
            return n;
        }
        n += 1;
    }
}

/// 99.9th percentiles over the spot of the curvature measure
/// `C = |Δxx h| + 2|Δxy h| + |Δyy h|` (second differences of the grid, metres) and of the slope
/// `|∇h|` (central differences). The largest departure of the surface from its tangent plane over
/// a cell of the map is about `C/8`, and over a cell `r` times smaller `C/(8 r²)`. Percentiles
/// rather than maxima keep a few spikes of a measured map from refining everything.
pub(crate) fn spot_percentiles(
    heights: &ndarray::Array2<f64>,
    dx: f64,
    dy: f64,
    spot: &Spot,
) -> (f64, f64) {
    let (ny, nx) = heights.dim();
    let radius2 = (0.5 * spot.diameter).powi(2);
    let (mut curvature, mut slope): (Vec<f64>, Vec<f64>) = (1..ny.saturating_sub(1))
        .into_par_iter()
        .flat_map_iter(|iy| {
            (1..nx - 1).filter_map(move |ix| {
                let (x, y) = (
                    ix as f64 * dx - spot.center.0,
                    iy as f64 * dy - spot.center.1,
                );
                if x * x + y * y >= radius2 {
                    return None;
                }
                let z = |i: usize, j: usize| heights[[j, i]];
                let dxx = z(ix + 1, iy) - 2.0 * z(ix, iy) + z(ix - 1, iy);
                let dyy = z(ix, iy + 1) - 2.0 * z(ix, iy) + z(ix, iy - 1);
                let dxy = 0.25
                    * (z(ix + 1, iy + 1) - z(ix + 1, iy - 1) - z(ix - 1, iy + 1)
                        + z(ix - 1, iy - 1));
                let c = dxx.abs() + 2.0 * dxy.abs() + dyy.abs();
                let sx = (z(ix + 1, iy) - z(ix - 1, iy)) / (2.0 * dx);
                let sy = (z(ix, iy + 1) - z(ix, iy - 1)) / (2.0 * dy);
                let s = (sx * sx + sy * sy).sqrt();
                (c.is_finite() && s.is_finite()).then_some((c, s))
            })
        })
        .unzip();
    (percentile(&mut curvature), percentile(&mut slope))
}

/// The 99.9th percentile of `values` (0 when empty).
fn percentile(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let k = ((values.len() - 1) as f64 * 0.999).round() as usize;
    *values.select_nth_unstable_by(k, f64::total_cmp).1
}
