//! Bicubic spline interpolation of a height map: the tensor product of not-a-knot cubic splines
//! along x and along y, evaluated anywhere between the grid points with its gradient.
//!
//! Construction (de Boor, *A Practical Guide to Splines*, 1978, ch. IV and XVII): the 1D cubic
//! spline through each row gives ∂h/∂x at the grid points, the spline through each column gives
//! ∂h/∂y, and the spline along x through the ∂h/∂y values gives ∂²h/∂x∂y. On each cell the
//! surface is the bicubic Hermite patch fixed by these 16 values at its four corners, which is
//! exactly the tensor-product spline: C² everywhere and equal to the data at the grid points.
//!
//! Boundary conditions: not-a-knot at both ends of every row and column (the first two and the
//! last two intervals share one cubic), so cubic polynomials are reproduced exactly up to the
//! edges and the error is O(h⁴) everywhere. Runs of 3 or 2 points get the parabola or the line
//! through them.
//!
//! Invalid (NaN) points split rows and columns into runs of valid points, each with its own
//! spline; a cell with an invalid corner evaluates to NaN. Points outside the grid evaluate to NaN
//! (no extrapolation), except within 1e-9 of a spacing of the edge.

use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use glam::DVec2;
use gonio_fft::fft2;
use ndarray::{Array2, ArrayView2};
use rayon::prelude::*;

/// How far outside the grid, in spacings, a position may lie and still count as on the edge.
const EDGE_TOLERANCE: f64 = 1e-9;

/// A bicubic spline through a height map, built once and evaluated many times.
///
/// Coordinates are metres from grid point `(0, 0)`: point `(ix, iy)` lies at `(ix·dx, iy·dy)`,
/// as in [`HeightMap`]. The spline covers `[0, (nx-1)·dx] × [0, (ny-1)·dy]`.
#[derive(Debug, Clone)]
pub struct BicubicSpline {
    /// `[h, ∂h/∂x, ∂h/∂y, ∂²h/∂x∂y]` at every grid point, row-major `(ny, nx)`.
    nodes: Vec<[f64; 4]>,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
}

impl BicubicSpline {
    /// The spline through `heights` (shape `(ny, nx)`, NaN at invalid points) on spacings `dx`,
    /// `dy` metres. Fails on a bad spacing, an infinite height or fewer than 2 × 2 points.
    pub fn new(heights: ArrayView2<f64>, dx: f64, dy: f64) -> Result<Self> {
        let (ny, nx) = heights.dim();
        if !(dx.is_finite() && dx > 0.0 && dy.is_finite() && dy > 0.0) {
            return Err(SurfaceError::Invalid(format!(
                "spline spacing {dx} × {dy} m must be positive and finite"
            )));
        }
        if nx < 2 || ny < 2 {
            return Err(SurfaceError::Invalid(format!(
                "a bicubic spline needs at least 2 × 2 points, got {nx} × {ny}"
            )));
        }
        if heights.iter().any(|h| h.is_infinite()) {
            return Err(SurfaceError::Invalid(
                "infinite height in spline data".into(),
            ));
        }
        let z = heights.as_standard_layout().into_owned();
        let zx = slopes_along_rows(z.view(), dx);
        let zy = slopes_along_columns(z.view(), dy);
        let zxy = slopes_along_columns(zx.view(), dy);
        let mut nodes = vec![[0.0; 4]; nx * ny];
        let (zs, zxs, zys, zxys) = (flat(&z), flat(&zx), flat(&zy), flat(&zxy));
        nodes.par_iter_mut().enumerate().for_each(|(k, n)| {
            *n = [zs[k], zxs[k], zys[k], zxys[k]];
        });
        Ok(BicubicSpline {
            nodes,
            nx,
            ny,
            dx,
            dy,
        })
    }

    /// The spline through a height map's heights.
    pub fn from_map(map: &HeightMap) -> Result<Self> {
        Self::new(map.heights().view(), map.dx(), map.dy())
    }

    /// Points along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Points along y.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Spacing along x, metres.
    pub fn dx(&self) -> f64 {
        self.dx
    }

    /// Spacing along y, metres.
    pub fn dy(&self) -> f64 {
        self.dy
    }

    /// Height at `(x, y)` metres; NaN outside the grid or in a cell touching an invalid point.
    pub fn eval(&self, x: f64, y: f64) -> f64 {
        self.patch(x, y).map_or(f64::NAN, |p| p.value())
    }

    /// Gradient `(∂h/∂x, ∂h/∂y)` at `(x, y)` metres; NaN where [`Self::eval`] is NaN.
    pub fn gradient(&self, x: f64, y: f64) -> DVec2 {
        self.patch(x, y).map_or(DVec2::NAN, |p| p.gradient())
    }

    /// Height and gradient together (cheaper than two calls).
    pub fn eval_with_gradient(&self, x: f64, y: f64) -> (f64, DVec2) {
        self.patch(x, y)
            .map_or((f64::NAN, DVec2::NAN), |p| (p.value(), p.gradient()))
    }

    /// The spline's gradient at grid point `(ix, iy)`: the derivatives of the row and column
    /// splines there. NaN at an invalid point or one whose run along x or y is a single point.
    pub fn node_gradient(&self, ix: usize, iy: usize) -> DVec2 {
        let n = self.nodes[iy * self.nx + ix];
        DVec2::new(n[1], n[2])
    }

    /// The cell containing `(x, y)` with the Hermite weights of the point inside it.
    fn patch(&self, x: f64, y: f64) -> Option<Patch<'_>> {
        // Positions within EDGE_TOLERANCE of a spacing outside the grid (rounding in a caller's
        // coordinate arithmetic) count as on its edge.
        let (umax, vmax) = ((self.nx - 1) as f64, (self.ny - 1) as f64);
        let inside = |w: f64, max: f64| w >= -EDGE_TOLERANCE && w <= max + EDGE_TOLERANCE;
        let (u, v) = (x / self.dx, y / self.dy);
        if !(inside(u, umax) && inside(v, vmax)) {
            return None;
        }
        let (u, v) = (u.clamp(0.0, umax), v.clamp(0.0, vmax));
        let ix = (u as usize).min(self.nx - 2);
        let iy = (v as usize).min(self.ny - 2);
        let i00 = iy * self.nx + ix;
        let i10 = i00 + self.nx;
        Some(Patch {
            corners: [
                &self.nodes[i00],
                &self.nodes[i00 + 1],
                &self.nodes[i10],
                &self.nodes[i10 + 1],
            ],
            wx: Hermite::new(u - ix as f64, self.dx),
            wy: Hermite::new(v - iy as f64, self.dy),
        })
    }
}

/// Cubic Hermite basis at `t ∈ [0, 1]` on an interval of length `h`: weights of the end values
/// (`a`), of the end slopes (`b`), and their derivatives with respect to the coordinate.
struct Hermite {
    a: [f64; 2],
    b: [f64; 2],
    da: [f64; 2],
    db: [f64; 2],
}

impl Hermite {
    fn new(t: f64, h: f64) -> Self {
        let (t2, t3) = (t * t, t * t * t);
        Hermite {
            a: [2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2],
            b: [(t3 - 2.0 * t2 + t) * h, (t3 - t2) * h],
            da: [(6.0 * t2 - 6.0 * t) / h, (-6.0 * t2 + 6.0 * t) / h],
            db: [3.0 * t2 - 4.0 * t + 1.0, 3.0 * t2 - 2.0 * t],
        }
    }
}

/// One bicubic Hermite cell: corners in the order (0,0), (1,0), (0,1), (1,1) as (x, y).
struct Patch<'a> {
    corners: [&'a [f64; 4]; 4],
    wx: Hermite,
    wy: Hermite,
}

impl Patch<'_> {
    /// Σ over corners of the tensor-product weights applied to `[h, hx, hy, hxy]`.
    fn combine(&self, ax: &[f64; 2], bx: &[f64; 2], ay: &[f64; 2], by: &[f64; 2]) -> f64 {
        let mut s = 0.0;
        for (k, c) in self.corners.iter().enumerate() {
            let (i, j) = (k & 1, k >> 1);
            s += ax[i] * ay[j] * c[0]
                + bx[i] * ay[j] * c[1]
                + ax[i] * by[j] * c[2]
                + bx[i] * by[j] * c[3];
        }
        s
    }

    fn value(&self) -> f64 {
        self.combine(&self.wx.a, &self.wx.b, &self.wy.a, &self.wy.b)
    }

    fn gradient(&self) -> DVec2 {
        DVec2::new(
            self.combine(&self.wx.da, &self.wx.db, &self.wy.a, &self.wy.b),
            self.combine(&self.wx.a, &self.wx.b, &self.wy.da, &self.wy.db),
        )
    }
}

/// Derivatives along each row (axis 1) of the splines through its runs of valid values.
pub(crate) fn slopes_along_rows(z: ArrayView2<f64>, h: f64) -> Array2<f64> {
    let (ny, nx) = z.dim();
    let z = z.as_standard_layout();
    let src = z.as_slice().expect("standard layout is contiguous");
    let mut out = vec![0.0; nx * ny];
    out.par_chunks_mut(nx)
        .zip(src.par_chunks(nx))
        .for_each(|(d, row)| slopes_along(row, h, d));
    Array2::from_shape_vec((ny, nx), out).expect("shape matches the length")
}

/// The elements of an array in standard layout.
fn flat(a: &Array2<f64>) -> &[f64] {
    a.as_slice().expect("built in standard layout")
}

/// Derivatives along each column (axis 0), in standard layout.
pub(crate) fn slopes_along_columns(z: ArrayView2<f64>, h: f64) -> Array2<f64> {
    fft2::transposed(slopes_along_rows(fft2::transposed(z).view(), h).view())
}

/// Derivatives at the points of `y` (spacing `h`) of the cubic splines through its maximal runs
/// of non-NaN values, written to `d` (NaN at NaN points and at runs of one point).
pub(crate) fn slopes_along(y: &[f64], h: f64, d: &mut [f64]) {
    let mut start = 0;
    while start < y.len() {
        if y[start].is_nan() {
            d[start] = f64::NAN;
            start += 1;
            continue;
        }
        let end = y[start..]
            .iter()
            .position(|v| v.is_nan())
            .map_or(y.len(), |p| start + p);
        run_slopes(&y[start..end], h, &mut d[start..end]);
        start = end;
    }
}

/// Node derivatives of the not-a-knot cubic spline through `y` (uniform spacing `h`, no NaN).
///
/// With second derivatives `M_i` and second differences `δ_i = (y_{i+1} - 2y_i + y_{i-1})/h²`,
/// C² continuity gives `M_{i-1} + 4M_i + M_{i+1} = 6δ_i`. Not-a-knot at `x_1` adds
/// `M_0 - 2M_1 + M_2 = 0`, which with the first equation gives `M_1 = δ_1` (likewise
/// `M_{n-2} = δ_{n-2}`); the rest is a (1, 4, 1) tridiagonal system solved by the Thomas
/// algorithm. The slopes are `y'_i = (y_{i+1} - y_i)/h - h(2M_i + M_{i+1})/6`.
fn run_slopes(y: &[f64], h: f64, d: &mut [f64]) {
    let n = y.len();
    match n {
        0 => {}
        1 => d[0] = f64::NAN,
        2 => d.fill((y[1] - y[0]) / h),
        3 => {
            d[0] = (-3.0 * y[0] + 4.0 * y[1] - y[2]) / (2.0 * h);
            d[1] = (y[2] - y[0]) / (2.0 * h);
            d[2] = (y[0] - 4.0 * y[1] + 3.0 * y[2]) / (2.0 * h);
        }
        _ => {
            let delta = |i: usize| (y[i + 1] - 2.0 * y[i] + y[i - 1]) / (h * h);
            let mut m = vec![0.0; n];
            m[1] = delta(1);
            m[n - 2] = delta(n - 2);
            // Unknowns m[2..n-2]: forward sweep storing modified diagonals in `c`.
            let interior = n.saturating_sub(4);
            if interior > 0 {
                let mut c = vec![0.0; interior];
                let mut r = vec![0.0; interior];
                for k in 0..interior {
                    let i = k + 2;
                    let mut rhs = 6.0 * delta(i);
                    if k == 0 {
                        rhs -= m[1];
                    }
                    if k == interior - 1 {
                        rhs -= m[n - 2];
                    }
                    let (cp, rp) = if k == 0 {
                        (0.0, 0.0)
                    } else {
                        (c[k - 1], r[k - 1])
                    };
                    let diag = 4.0 - cp;
                    c[k] = 1.0 / diag;
                    r[k] = (rhs - rp) / diag;
                }
                for k in (0..interior).rev() {
                    let next = if k + 1 < interior { m[k + 3] } else { 0.0 };
                    m[k + 2] = r[k] - c[k] * next;
                }
            }
            m[0] = 2.0 * m[1] - m[2];
            m[n - 1] = 2.0 * m[n - 2] - m[n - 3];
            for i in 0..n - 1 {
                d[i] = (y[i + 1] - y[i]) / h - h * (2.0 * m[i] + m[i + 1]) / 6.0;
            }
            d[n - 1] = (y[n - 1] - y[n - 2]) / h + h * (m[n - 2] + 2.0 * m[n - 1]) / 6.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bicubic polynomial is reproduced exactly by not-a-knot splines, edges included.
    #[test]
    fn reproduces_bicubic_polynomials() {
        let (dx, dy) = (0.5, 0.3);
        let p = |x: f64| 1.0 - 2.0 * x + 0.5 * x * x - 0.1 * x * x * x;
        let q = |y: f64| 0.3 + y - 0.7 * y * y + 0.2 * y * y * y;
        let dp = |x: f64| -2.0 + x - 0.3 * x * x;
        let dq = |y: f64| 1.0 - 1.4 * y + 0.6 * y * y;
        for (nx, ny) in [(9, 7), (4, 5), (5, 4), (12, 13)] {
            let z =
                Array2::from_shape_fn((ny, nx), |(iy, ix)| p(ix as f64 * dx) * q(iy as f64 * dy));
            let s = BicubicSpline::new(z.view(), dx, dy).unwrap();
            for k in 0..200 {
                let x = (k as f64 * 0.618_034).fract() * (nx - 1) as f64 * dx;
                let y = (k as f64 * 0.414_214).fract() * (ny - 1) as f64 * dy;
                let (v, g) = s.eval_with_gradient(x, y);
                assert!(
                    (v - p(x) * q(y)).abs() < 1e-12,
                    "{nx}×{ny} value at ({x}, {y})"
                );
                assert!(
                    (g.x - dp(x) * q(y)).abs() < 1e-11,
                    "{nx}×{ny} ∂x at ({x}, {y})"
                );
                assert!(
                    (g.y - p(x) * dq(y)).abs() < 1e-11,
                    "{nx}×{ny} ∂y at ({x}, {y})"
                );
            }
            let corner = ((nx - 1) as f64 * dx, (ny - 1) as f64 * dy);
            assert!((s.eval(corner.0, corner.1) - p(corner.0) * q(corner.1)).abs() < 1e-12);
            assert!(s.eval(-1e-9, 0.0).is_nan() && s.eval(0.0, corner.1 * 1.001).is_nan());
        }
    }

    /// Short runs get the line or the parabola through them.
    #[test]
    fn short_runs() {
        let mut d = [0.0; 3];
        slopes_along(&[1.0, 4.0, 9.0], 1.0, &mut d); // x² at x = 1, 2, 3
        assert_eq!(d, [2.0, 4.0, 6.0]);
        let mut d = [0.0; 5];
        slopes_along(&[1.0, 3.0, f64::NAN, 2.0, f64::NAN], 0.5, &mut d);
        assert_eq!(&d[..2], &[4.0, 4.0]);
        assert!(d[2].is_nan() && d[3].is_nan() && d[4].is_nan());
    }

    /// Invalid points make their cells NaN and leave cells away from them intact.
    #[test]
    fn invalid_points_only_spoil_their_cells() {
        let mut z = Array2::from_shape_fn((8, 8), |(iy, ix)| (ix + 2 * iy) as f64);
        z[[4, 4]] = f64::NAN;
        let s = BicubicSpline::new(z.view(), 1.0, 1.0).unwrap();
        assert!(s.eval(3.5, 3.5).is_nan() && s.eval(4.5, 4.5).is_nan());
        assert!((s.eval(1.5, 1.25) - 4.0).abs() < 1e-12);
        assert!((s.gradient(6.5, 1.5) - DVec2::new(1.0, 2.0)).length() < 1e-12);
        assert!(BicubicSpline::new(z.view(), 0.0, 1.0).is_err());
        assert!(BicubicSpline::new(Array2::zeros((1, 5)).view(), 1.0, 1.0).is_err());
    }
}
