//! The piecewise-bilinear 2D distribution with parameter interpolation that Mitsuba 3
//! (`Marginal2D<Float, Dim, Continuous = true>` in `include/mitsuba/core/distr_2d.h`) and pbrt-v4
//! (`PiecewiseLinear2D`) build from the fields of a measured-BRDF tensor file. It must match
//! theirs exactly for our writer to place values where those renderers will look them up. The
//! table sampler (`table::sampler`) draws its correction on the square of visible normals from
//! one too, with theta_o (and phi_o) as the parameters; its lookups run per sample, so they
//! allocate nothing (at most three parameters).
//!
//! Data of `n_x × n_y` nodes on the unit square (node i at `i/(n-1)`), one such slice per
//! combination of parameter values; between parameter values everything (data and CDFs) is
//! interpolated linearly. As a warp, each slice is normalised to unit integral over the
//! square: the conditional CDF of each row integrates the linear interpolant along x, the
//! marginal CDF integrates the row totals along y (trapezoids), and `sample` inverts both in
//! closed form (a quadratic per patch); `invert` is its exact inverse. Not a warp, `eval` is the
//! plain bilinear interpolant.

/// A 2D distribution (or plain interpolant) with `D` parameters.
#[derive(Debug, Clone)]
pub struct Marginal2D {
    nx: usize,
    ny: usize,
    params: Vec<Vec<f64>>,
    strides: Vec<usize>,
    data: Vec<f64>,
    marginal_cdf: Vec<f64>,
    conditional_cdf: Vec<f64>,
    warp: bool,
}

/// The slices that a parameter point interpolates between: `(slice, weight)` of each corner
/// of its cell in the parameter grid with a nonzero weight, in corner order (bit k of the
/// corner's number set for the upper node of parameter k), found once per point so that every
/// lookup at the point is a short weighted sum.
/// Held in place, without allocation: a lookup runs per sample in the renderer.
struct Weights {
    corners: [(usize, f64); MAX_CORNERS],
    len: usize,
}

/// At most three parameters (Mitsuba's tensors have two angles and a wavelength): eight corners.
const MAX_PARAMS: usize = 3;
const MAX_CORNERS: usize = 1 << MAX_PARAMS;

impl Weights {
    /// The corners with a nonzero weight.
    fn corners(&self) -> &[(usize, f64)] {
        &self.corners[..self.len]
    }

    /// The same weights `by` slices further on.
    fn shifted(&self, by: usize) -> Weights {
        let mut out = Weights { ..*self };
        out.corners[..self.len]
            .iter_mut()
            .for_each(|(s, _)| *s += by);
        out
    }
}

/// Largest index i in [0, n - 2] with `pred(i)`, by bisection (Mitsuba's `find_interval`).
fn find_interval(n: usize, pred: impl Fn(usize) -> bool) -> usize {
    let (mut first, mut size) = (1usize, n.saturating_sub(2));
    while size > 0 {
        let half = size / 2;
        let middle = first + half;
        if pred(middle) {
            first = middle + 1;
            size -= half + 1;
        } else {
            size = half;
        }
    }
    first.saturating_sub(1).min(n.saturating_sub(2))
}

impl Marginal2D {
    /// Build from `data` (`[p0][p1]...[y][x]`, x fastest) of `nx × ny` nodes per slice, the
    /// parameter values of each parameter dimension, and whether it is a warp (normalised, with
    /// CDFs) or a plain interpolant.
    pub fn new(
        data: &[f32],
        nx: usize,
        ny: usize,
        params: Vec<Vec<f64>>,
        warp: bool,
    ) -> Result<Self, String> {
        if nx < 2 || ny < 2 {
            return Err(format!("a {nx} × {ny} grid is too small (at least 2 × 2)"));
        }
        if params.len() > MAX_PARAMS {
            return Err(format!(
                "{} parameters (at most {MAX_PARAMS})",
                params.len()
            ));
        }
        let mut strides = vec![0; params.len()];
        let mut slices = 1usize;
        for k in (0..params.len()).rev() {
            if params[k].is_empty() {
                return Err("a parameter has no values".into());
            }
            strides[k] = if params[k].len() > 1 { slices } else { 0 };
            slices *= params[k].len();
        }
        let n = nx * ny;
        if data.len() != slices * n {
            return Err(format!(
                "{} values for {slices} slices of {nx} × {ny}",
                data.len()
            ));
        }
        let mut out = Marginal2D {
            nx,
            ny,
            params,
            strides,
            data: data.iter().map(|&v| f64::from(v)).collect(),
            marginal_cdf: Vec::new(),
            conditional_cdf: Vec::new(),
            warp,
        };
        if warp {
            out.marginal_cdf = vec![0.0; slices * ny];
            out.conditional_cdf = vec![0.0; slices * n];
            for s in 0..slices {
                let d = &mut out.data[s * n..(s + 1) * n];
                let cond = &mut out.conditional_cdf[s * n..(s + 1) * n];
                for y in 0..ny {
                    let mut sum = 0.0;
                    for x in 0..nx - 1 {
                        sum += 0.5 * (d[y * nx + x] + d[y * nx + x + 1]);
                        cond[y * nx + x + 1] = sum;
                    }
                }
                let marg = &mut out.marginal_cdf[s * ny..(s + 1) * ny];
                let mut sum = 0.0;
                for y in 0..ny - 1 {
                    sum += 0.5 * (cond[(y + 1) * nx - 1] + cond[(y + 2) * nx - 1]);
                    marg[y + 1] = sum;
                }
                if !(sum > 0.0 && sum.is_finite()) {
                    return Err(format!("slice {s} has no positive finite integral"));
                }
                let norm = 1.0 / sum;
                cond.iter_mut().for_each(|v| *v *= norm);
                marg.iter_mut().for_each(|v| *v *= norm);
                d.iter_mut().for_each(|v| *v *= norm);
            }
        }
        Ok(out)
    }

    fn weights(&self, param: &[f64]) -> Weights {
        let mut offset = 0;
        let d = self.params.len();
        let mut w = [(1.0, 0.0); MAX_PARAMS];
        for (k, values) in self.params.iter().enumerate() {
            if values.len() == 1 {
                continue;
            }
            let i = find_interval(values.len(), |j| values[j] < param[k]);
            let (p0, p1) = (values[i], values[i + 1]);
            let t = ((param[k] - p0) / (p1 - p0)).clamp(0.0, 1.0);
            w[k] = (1.0 - t, t);
            offset += self.strides[k] * i;
        }
        let mut out = Weights {
            corners: [(0, 0.0); MAX_CORNERS],
            len: 0,
        };
        for corner in 0..1usize << d {
            let mut weight = 1.0;
            let mut slice = offset;
            for (k, &(lower, upper)) in w[..d].iter().enumerate() {
                if corner >> k & 1 == 1 {
                    weight *= upper;
                    slice += self.strides[k];
                } else {
                    weight *= lower;
                }
            }
            if weight != 0.0 {
                out.corners[out.len] = (slice, weight);
                out.len += 1;
            }
        }
        out
    }

    /// Parameter-interpolated element `i` of a slice of `size` elements of `array`.
    fn lookup(&self, array: &[f64], size: usize, i: usize, wt: &Weights) -> f64 {
        let mut total = 0.0;
        for &(slice, w) in wt.corners() {
            total += w * array[slice * size + i];
        }
        total
    }

    /// The values of parameter dimension `k`.
    pub fn param_values(&self, k: usize) -> &[f64] {
        &self.params[k]
    }

    fn patch_scale(&self) -> f64 {
        ((self.nx - 1) * (self.ny - 1)) as f64
    }

    /// The interpolant (a warp: the normalised density on the unit square) at `pos`.
    pub fn eval(&self, pos: [f64; 2], param: &[f64]) -> f64 {
        self.eval_weighted(pos, &self.weights(param))
    }

    /// [`Self::eval`] at `pos` for the leading parameters `head` (all but the last) at every
    /// node of the last parameter: `out[c]` is `eval(pos, [head.., nodes[c]])` to the bit (at a
    /// node the interpolation in the last parameter takes that node's slice with weight one),
    /// with the leading parameters' weights found once instead of once per node. A spectral
    /// table's wavelengths are such nodes.
    pub fn eval_at_last_nodes(&self, pos: [f64; 2], head: &[f64], out: &mut [f64]) {
        let last = self.params.len() - 1;
        let mut param = head.to_vec();
        param.push(self.params[last][0]);
        let wt = self.weights(&param);
        for (c, o) in out.iter_mut().enumerate().take(self.params[last].len()) {
            *o = self.eval_weighted(pos, &wt.shifted(self.strides[last] * c));
        }
    }

    fn eval_weighted(&self, pos: [f64; 2], wt: &Weights) -> f64 {
        let n = self.nx * self.ny;
        let x = pos[0].clamp(0.0, 1.0) * (self.nx - 1) as f64;
        let y = pos[1].clamp(0.0, 1.0) * (self.ny - 1) as f64;
        let (ix, iy) = ((x as usize).min(self.nx - 2), (y as usize).min(self.ny - 2));
        let (tx, ty) = (x - ix as f64, y - iy as f64);
        let at =
            |dx: usize, dy: usize| self.lookup(&self.data, n, (iy + dy) * self.nx + ix + dx, wt);
        let v = (1.0 - ty) * ((1.0 - tx) * at(0, 0) + tx * at(1, 0))
            + ty * ((1.0 - tx) * at(0, 1) + tx * at(1, 1));
        if self.warp { v * self.patch_scale() } else { v }
    }

    /// Warp two uniform numbers to a point of the square distributed as the density; returns the
    /// point and the density there.
    pub fn sample(&self, u: [f64; 2], param: &[f64]) -> ([f64; 2], f64) {
        let wt = self.weights(param);
        let (nx, ny, n) = (self.nx, self.ny, self.nx * self.ny);
        let eps = f64::from(f32::EPSILON) * 0.5;
        let (mut ux, mut uy) = (u[0].clamp(eps, 1.0 - eps), u[1].clamp(eps, 1.0 - eps));
        let marg = |i: usize| self.lookup(&self.marginal_cdf, ny, i, &wt);
        let row = find_interval(ny, |i| marg(i) < uy);
        uy -= marg(row);
        let cond = |i: usize| self.lookup(&self.conditional_cdf, n, i, &wt);
        let (r0, r1) = (cond(row * nx + nx - 1), cond((row + 1) * nx + nx - 1));
        let y = if (r0 - r1).abs() < 1e-4 * (r0 + r1) {
            2.0 * uy / (r0 + r1)
        } else {
            (r0 - (r0 * r0 - 2.0 * uy * (r0 - r1)).max(0.0).sqrt()) / (r0 - r1)
        };
        ux *= (1.0 - y) * r0 + y * r1;
        let cond_at = |i: usize| (1.0 - y) * cond(row * nx + i) + y * cond((row + 1) * nx + i);
        let col = find_interval(nx, |i| cond_at(i) < ux);
        ux -= cond_at(col);
        let data = |i: usize| self.lookup(&self.data, n, i, &wt);
        let base = row * nx + col;
        let c0 = (1.0 - y) * data(base) + y * data(base + nx);
        let c1 = (1.0 - y) * data(base + 1) + y * data(base + nx + 1);
        let x = if (c0 - c1).abs() < 1e-4 * (c0 + c1) {
            if c0 + c1 != 0.0 {
                2.0 * ux / (c0 + c1)
            } else {
                ux
            }
        } else {
            (c0 - (c0 * c0 - 2.0 * ux * (c0 - c1)).max(0.0).sqrt()) / (c0 - c1)
        };
        let pos = [
            (col as f64 + x) / (nx - 1) as f64,
            (row as f64 + y) / (ny - 1) as f64,
        ];
        (pos, ((1.0 - x) * c0 + x * c1) * self.patch_scale())
    }

    /// The inverse of [`Marginal2D::sample`]: the uniform numbers that map to `pos`, and the
    /// density at `pos`.
    pub fn invert(&self, pos: [f64; 2], param: &[f64]) -> ([f64; 2], f64) {
        let wt = self.weights(param);
        let (nx, ny, n) = (self.nx, self.ny, self.nx * self.ny);
        let sx = pos[0].clamp(0.0, 1.0) * (nx - 1) as f64;
        let sy = pos[1].clamp(0.0, 1.0) * (ny - 1) as f64;
        let (ix, iy) = ((sx as usize).min(nx - 2), (sy as usize).min(ny - 2));
        let (x, y) = (sx - ix as f64, sy - iy as f64);
        let base = iy * nx + ix;
        let data = |i: usize| self.lookup(&self.data, n, i, &wt);
        let cond = |i: usize| self.lookup(&self.conditional_cdf, n, i, &wt);
        let c0 = (1.0 - y) * data(base) + y * data(base + nx);
        let c1 = (1.0 - y) * data(base + 1) + y * data(base + nx + 1);
        let pdf = (1.0 - x) * c0 + x * c1;
        let mut ux = x * (c0 + 0.5 * x * (c1 - c0));
        ux += (1.0 - y) * cond(base) + y * cond(base + nx);
        let (r0, r1) = (cond(iy * nx + nx - 1), cond((iy + 1) * nx + nx - 1));
        ux /= (1.0 - y) * r0 + y * r1;
        let uy = y * (r0 + 0.5 * y * (r1 - r0)) + self.lookup(&self.marginal_cdf, ny, iy, &wt);
        ([ux, uy], pdf * self.patch_scale())
    }
}
