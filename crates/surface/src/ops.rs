//! Operations on height maps that return a new map: least-squares plane levelling, cropping,
//! rotation about the centre and resampling to another spacing (both with bicubic-spline
//! interpolation), and exact quarter turns and turned pairs ([`turns`]).

pub mod turns;

pub use turns::{quarter_turns, turned_pair};

use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use crate::heightmap::MAX_POINTS;
use crate::spline::BicubicSpline;
use ndarray::{Array2, ArrayView1, Axis, s};
use rayon::prelude::*;

/// A plane `z = z0 + slope_x·x + slope_y·y`, with `x = ix·dx` and `y = iy·dy` in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Height at the origin (point `(0, 0)`), metres.
    pub z0: f64,
    /// dz/dx (dimensionless).
    pub slope_x: f64,
    /// dz/dy (dimensionless).
    pub slope_y: f64,
}

impl Plane {
    /// Height of the plane at `(x, y)` metres.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        self.z0 + self.slope_x * x + self.slope_y * y
    }
}

/// Sums over the valid points of one row (count, Σx, Σz, Σx², Σxz, Σy, Σy², Σxy, Σyz), for the
/// plane fit.
#[derive(Default, Clone, Copy)]
struct Moments {
    n: f64,
    sx: f64,
    sz: f64,
    sxx: f64,
    sxz: f64,
    sy: f64,
    syy: f64,
    sxy: f64,
    syz: f64,
}

impl Moments {
    fn add(self, o: Moments) -> Moments {
        Moments {
            n: self.n + o.n,
            sx: self.sx + o.sx,
            sz: self.sz + o.sz,
            sxx: self.sxx + o.sxx,
            sxz: self.sxz + o.sxz,
            sy: self.sy + o.sy,
            syy: self.syy + o.syy,
            sxy: self.sxy + o.sxy,
            syz: self.syz + o.syz,
        }
    }
}

/// Apply `f` to every row `(iy, row)` in parallel and return the results in row order, so that a
/// serial reduction of them does not depend on the thread count.
pub(crate) fn per_row<T: Send>(
    heights: &Array2<f64>,
    f: impl Fn(usize, ArrayView1<f64>) -> T + Sync,
) -> Vec<T> {
    heights
        .axis_iter(Axis(0))
        .into_par_iter()
        .enumerate()
        .map(|(iy, row)| f(iy, row))
        .collect()
}

/// The least-squares plane through the valid points of `map` (ordinary least squares in z).
///
/// Solved from the centred normal equations (two passes: means, then centred moments), so that a
/// large height offset does not cost precision. When the valid points are collinear the
/// minimum-norm slope is returned (a single row gives `slope_y = 0`).
pub fn fit_plane(map: &HeightMap) -> Result<Plane> {
    let (dx, dy) = (map.dx(), map.dy());
    let h = map.heights();
    let first = per_row(h, |iy, row| {
        let y = iy as f64 * dy;
        let mut m = Moments::default();
        for (ix, &z) in row.iter().enumerate() {
            if !z.is_nan() {
                m.n += 1.0;
                m.sx += ix as f64 * dx;
                m.sz += z;
            }
        }
        m.sy = m.n * y;
        m
    })
    .into_iter()
    .fold(Moments::default(), Moments::add);
    if first.n == 0.0 {
        return Err(SurfaceError::Invalid(
            "no valid points to fit a plane to".into(),
        ));
    }
    let (mx, my, mz) = (first.sx / first.n, first.sy / first.n, first.sz / first.n);
    let c = per_row(h, |iy, row| {
        let y = iy as f64 * dy - my;
        let mut m = Moments::default();
        for (ix, &z) in row.iter().enumerate() {
            if !z.is_nan() {
                let x = ix as f64 * dx - mx;
                let z = z - mz;
                m.n += 1.0;
                m.sxx += x * x;
                m.sxz += x * z;
                m.sx += x;
                m.sz += z;
            }
        }
        m.syy = m.n * y * y;
        m.sxy = y * m.sx;
        m.syz = y * m.sz;
        m
    })
    .into_iter()
    .fold(Moments::default(), Moments::add);
    let (slope_x, slope_y) = solve_sym2(c.sxx, c.sxy, c.syy, c.sxz, c.syz);
    Ok(Plane {
        z0: mz - slope_x * mx - slope_y * my,
        slope_x,
        slope_y,
    })
}

/// Minimum-norm solution of the symmetric positive semi-definite system
/// `[a b; b c] [u; v] = [r; s]`.
fn solve_sym2(a: f64, b: f64, c: f64, r: f64, s: f64) -> (f64, f64) {
    let det = a * c - b * b;
    if det > 1e-12 * a * c && det > 0.0 {
        return ((c * r - b * s) / det, (a * s - b * r) / det);
    }
    // Rank one (or zero): the matrix is λ v vᵀ with λ = a + c.
    let lambda = a + c;
    if lambda <= 0.0 {
        return (0.0, 0.0);
    }
    let (vx, vy) = if a >= c { (a, b) } else { (b, c) };
    let norm = vx.hypot(vy);
    let (vx, vy) = (vx / norm, vy / norm);
    let t = (vx * r + vy * s) / lambda;
    (t * vx, t * vy)
}

/// `map` with its least-squares plane subtracted; invalid points stay invalid.
pub fn level(map: &HeightMap) -> Result<HeightMap> {
    let plane = fit_plane(map)?;
    Ok(subtract_plane(map, &plane))
}

/// `map` with `plane` subtracted.
pub fn subtract_plane(map: &HeightMap, plane: &Plane) -> HeightMap {
    let (dx, dy) = (map.dx(), map.dy());
    let mut h = map.heights().clone();
    h.axis_iter_mut(Axis(0))
        .into_par_iter()
        .enumerate()
        .for_each(|(iy, mut row)| {
            let y = iy as f64 * dy;
            for (ix, z) in row.iter_mut().enumerate() {
                *z -= plane.height(ix as f64 * dx, y);
            }
        });
    map.with_heights(h)
        .expect("subtracting a finite plane keeps every height finite")
}

/// The block of `nx × ny` points starting at point `(ix0, iy0)`; spacing and metadata are kept.
pub fn crop(map: &HeightMap, ix0: usize, iy0: usize, nx: usize, ny: usize) -> Result<HeightMap> {
    let fits = |start: usize, len: usize, total: usize| {
        len > 0 && start.checked_add(len).is_some_and(|end| end <= total)
    };
    if !fits(ix0, nx, map.nx()) || !fits(iy0, ny, map.ny()) {
        return Err(SurfaceError::Invalid(format!(
            "crop of {nx} × {ny} points at ({ix0}, {iy0}) does not fit in the {} × {} map",
            map.nx(),
            map.ny()
        )));
    }
    let block = map
        .heights()
        .slice(s![iy0..iy0 + ny, ix0..ix0 + nx])
        .to_owned();
    let mut out = HeightMap::with_invalid(block, map.dx(), map.dy())?;
    out.meta = map.meta.clone();
    Ok(out)
}

/// The map rotated by `angle` radians counter-clockwise (from +x toward +y) about its centre, on
/// the same grid. Each output point takes the bicubic-spline height at the source position it
/// came from; points whose source lies outside the map, or in a cell touching an invalid point,
/// become invalid.
pub fn rotate(map: &HeightMap, angle: f64) -> Result<HeightMap> {
    if !angle.is_finite() {
        return Err(SurfaceError::Invalid(format!(
            "rotation angle {angle} is not finite"
        )));
    }
    let spline = BicubicSpline::from_map(map)?;
    let (cx, cy) = (
        (map.nx() - 1) as f64 * map.dx() / 2.0,
        (map.ny() - 1) as f64 * map.dy() / 2.0,
    );
    let (sin, cos) = angle.sin_cos();
    let (dx, dy) = (map.dx(), map.dy());
    let heights = sample(map.nx(), map.ny(), |ix, iy| {
        let (x, y) = (ix as f64 * dx - cx, iy as f64 * dy - cy);
        // Inverse rotation: where the content now at (x, y) was before.
        spline.eval(cx + cos * x + sin * y, cy - sin * x + cos * y)
    });
    let mut out = HeightMap::with_invalid(heights, dx, dy)?;
    out.meta = map.meta.clone();
    Ok(out)
}

/// The map resampled on spacings `dx`, `dy` metres over the same extent, starting at the same
/// first point: `floor((n-1)·d_old/d_new) + 1` points along each axis, heights from the bicubic
/// spline. This is point sampling: coarsening a map whose spectrum reaches beyond the new
/// Nyquist frequency aliases that roughness; smooth it first.
pub fn resample(map: &HeightMap, dx: f64, dy: f64) -> Result<HeightMap> {
    let spline = BicubicSpline::from_map(map)?;
    let count = |n: usize, old: f64, new: f64| -> Result<usize> {
        if !(new.is_finite() && new > 0.0) {
            return Err(SurfaceError::Invalid(format!(
                "resampling spacing {new} m must be positive and finite"
            )));
        }
        // The tolerance keeps the last point when the extent is a whole number of new steps.
        let steps = ((n - 1) as f64 * old / new * (1.0 + 1e-12)).floor();
        if steps + 1.0 > MAX_POINTS as f64 {
            return Err(SurfaceError::Invalid(format!(
                "resampling at {new} m gives more than {MAX_POINTS} points"
            )));
        }
        Ok(steps as usize + 1)
    };
    let nx = count(map.nx(), map.dx(), dx)?;
    let ny = count(map.ny(), map.dy(), dy)?;
    if nx.saturating_mul(ny) > MAX_POINTS {
        return Err(SurfaceError::Invalid(format!(
            "resampling gives {nx} × {ny} points, over the limit of {MAX_POINTS}"
        )));
    }
    let (w, h) = (
        (map.nx() - 1) as f64 * map.dx(),
        (map.ny() - 1) as f64 * map.dy(),
    );
    let heights = sample(nx, ny, |ix, iy| {
        spline.eval((ix as f64 * dx).min(w), (iy as f64 * dy).min(h))
    });
    let mut out = HeightMap::with_invalid(heights, dx, dy)?;
    out.meta = map.meta.clone();
    Ok(out)
}

/// An `(ny, nx)` grid of `f(ix, iy)`, filled row by row in parallel.
fn sample(nx: usize, ny: usize, f: impl Fn(usize, usize) -> f64 + Sync) -> Array2<f64> {
    let mut out = Array2::zeros((ny, nx));
    out.axis_iter_mut(Axis(0))
        .into_par_iter()
        .enumerate()
        .for_each(|(iy, mut row)| {
            for (ix, v) in row.iter_mut().enumerate() {
                *v = f(ix, iy);
            }
        });
    out
}
