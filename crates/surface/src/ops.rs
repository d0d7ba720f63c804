//! Operations on height maps that return a new map: least-squares plane levelling, cropping,
//! rotation about the centre and resampling to another spacing (both with bicubic-spline
//! interpolation).

use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use ndarray::{Array2, ArrayView1, Axis};
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

#[cfg(test)]
mod tests {
    use super::*;

    fn tilted(nx: usize, ny: usize, dx: f64, dy: f64, hole: bool) -> HeightMap {
        let h = Array2::from_shape_fn((ny, nx), |(iy, ix)| {
            if hole && ix % 3 == 1 && iy % 2 == 0 {
                f64::NAN
            } else {
                1e-3 + 2e-3 * ix as f64 * dx - 5e-4 * iy as f64 * dy
            }
        });
        HeightMap::with_invalid(h, dx, dy).unwrap()
    }

    #[test]
    fn plane_is_recovered_exactly() {
        for hole in [false, true] {
            let map = tilted(17, 9, 1e-6, 3e-6, hole);
            let p = fit_plane(&map).unwrap();
            assert!((p.slope_x - 2e-3).abs() < 1e-12, "{p:?}");
            assert!((p.slope_y + 5e-4).abs() < 1e-12, "{p:?}");
            assert!((p.z0 - 1e-3).abs() < 1e-15, "{p:?}");
            let lev = level(&map).unwrap();
            assert!(
                lev.heights()
                    .iter()
                    .filter(|z| !z.is_nan())
                    .all(|z| z.abs() < 1e-15)
            );
            assert_eq!(lev.valid_count(), map.valid_count());
        }
    }

    #[test]
    fn single_row_and_empty_maps() {
        let map = tilted(10, 1, 1e-6, 1e-6, false);
        let p = fit_plane(&map).unwrap();
        assert!(
            (p.slope_x - 2e-3).abs() < 1e-12 && p.slope_y == 0.0,
            "{p:?}"
        );
        let empty = HeightMap::with_invalid(Array2::from_elem((3, 3), f64::NAN), 1.0, 1.0).unwrap();
        assert!(fit_plane(&empty).is_err());
    }
}
