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

    #[test]
    fn crop_takes_the_block_and_checks_bounds() {
        let map = tilted(17, 9, 1e-6, 3e-6, true);
        let c = crop(&map, 2, 3, 5, 4).unwrap();
        assert_eq!((c.nx(), c.ny(), c.dx(), c.dy()), (5, 4, 1e-6, 3e-6));
        for iy in 0..4 {
            for ix in 0..5 {
                assert_eq!(c.get(ix, iy), map.get(ix + 2, iy + 3));
            }
        }
        assert!(crop(&map, 13, 0, 5, 4).is_err());
        assert!(crop(&map, 0, 0, 0, 4).is_err());
        assert!(crop(&map, usize::MAX, 0, 2, 2).is_err());
    }

    /// A plane rotated by θ is the plane with its gradient rotated by θ (the spline reproduces
    /// planes exactly); corners whose source falls outside the map become invalid; 90° on a
    /// square grid maps grid points onto grid points.
    #[test]
    fn rotation_of_planes_and_quarter_turns() {
        let (a, b) = (2e-3, -5e-4);
        let n = 21;
        let map = HeightMap::new(
            Array2::from_shape_fn((n, n), |(iy, ix)| {
                a * ix as f64 * 1e-6 + b * iy as f64 * 1e-6
            }),
            1e-6,
            1e-6,
        )
        .unwrap();
        let theta: f64 = 0.3;
        let rot = rotate(&map, theta).unwrap();
        let p = fit_plane(&rot).unwrap();
        let (s, c) = theta.sin_cos();
        assert!((p.slope_x - (c * a - s * b)).abs() < 1e-12, "{p:?}");
        assert!((p.slope_y - (s * a + c * b)).abs() < 1e-12, "{p:?}");
        assert!(!rot.is_valid(0, 0) && !rot.is_valid(n - 1, n - 1) && rot.is_valid(10, 10));
        let ident = rotate(&map, 2.0 * std::f64::consts::PI).unwrap();
        for (u, v) in ident.heights().iter().zip(map.heights()) {
            assert!((u - v).abs() < 1e-15);
        }
        let quarter = rotate(&map, std::f64::consts::FRAC_PI_2).unwrap();
        for iy in 0..n {
            for ix in 0..n {
                // Content at (x, y) came from (y, -x) about the centre.
                let src = map.get(iy, n - 1 - ix).unwrap();
                assert!((quarter.get(ix, iy).unwrap() - src).abs() < 1e-15);
            }
        }
    }

    /// Resampling a bicubic polynomial is exact; the extent is kept.
    #[test]
    fn resampling_keeps_extent_and_smooth_shapes() {
        let f = |x: f64, y: f64| (x * x * x - 3.0 * x) * (1.0 + y - y * y);
        let map = HeightMap::new(
            Array2::from_shape_fn((11, 16), |(iy, ix)| f(ix as f64 * 0.2, iy as f64 * 0.3)),
            0.2,
            0.3,
        )
        .unwrap();
        let fine = resample(&map, 0.1, 0.1).unwrap();
        assert_eq!((fine.nx(), fine.ny()), (31, 31));
        for ((iy, ix), z) in fine.heights().indexed_iter() {
            assert!(
                (z - f(ix as f64 * 0.1, iy as f64 * 0.1)).abs() < 1e-12,
                "({ix}, {iy})"
            );
        }
        let coarse = resample(&map, 0.7, 0.45).unwrap();
        assert_eq!((coarse.nx(), coarse.ny()), (5, 7));
        assert!(resample(&map, 0.0, 1.0).is_err());
        assert!(resample(&map, 1e-30, 1e-30).is_err());
    }

    /// Rotating a smooth random surface (8 points per correlation length) by 30° and back
    /// returns it, within the bicubic interpolation error, inside the inscribed disc. A Gaussian
    /// spectrum exp(-q²T²/4) has little power beyond q = 3/T, where k dx = 3/8 and de Boor's
    /// bound on cubic-spline interpolation, (5/384)(k dx)⁴ of the amplitude, is 2.6e-4 per pass:
    /// two passes stay well under 1% of Sq.
    #[test]
    fn rotation_there_and_back_recovers_the_surface() {
        let req = crate::synth::GaussianSurface::square(1e-7, 4e-6, 128, 0.5e-6, 9);
        let map = req.generate().unwrap();
        let angle = 30f64.to_radians();
        let back = rotate(&rotate(&map, angle).unwrap(), -angle).unwrap();
        let c = 63.5;
        let mut worst = 0.0f64;
        for ((iy, ix), z) in map.heights().indexed_iter() {
            if (ix as f64 - c).hypot(iy as f64 - c) < 60.0 {
                let b = back.heights()[[iy, ix]];
                assert!(!b.is_nan(), "({ix}, {iy}) became invalid");
                worst = worst.max((b - z).abs());
            }
        }
        assert!(worst < 0.01 * req.sq, "worst difference {worst}");
    }
}
