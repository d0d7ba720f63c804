//! Facet normals at the interior points of a height map, the two ways the NIST ray method allows
//! (Germer & Marx, Appl. Opt. 43, 1266 (2004); `docs/ray-method.md`, "Method", and
//! `docs/surface.md`, "Facet normals"): from the least-squares plane through a point and its eight
//! neighbours, or from the derivatives of a bicubic spline through the data.
//!
//! Border points and points whose 3 × 3 neighbourhood holds an invalid point get a NaN normal:
//! facets touching invalid points are skipped by the methods that use them.
//!
//! Finite spacing biases both estimates. For `h = sin(k x)` the plane fit returns the slope
//! `k cos(kx) · sin(k dx)/(k dx)` (the plane's slope is `Σ i·z / (6 dx)` over the 3 × 3 block,
//! and `Σ_i i sin(k(x + i dx)) = 2 cos(kx) sin(k dx)`), and the not-a-knot spline, away from the
//! edges, `k cos(kx) · 3 sin(k dx) / (k dx (2 + cos(k dx)))`, an error of only `(k dx)⁴/180`.

use crate::heightmap::HeightMap;
use crate::spline::{slopes_along_columns, slopes_along_rows};
use glam::DVec3;
use ndarray::Array2;
use rayon::prelude::*;

/// How the slope at a grid point is estimated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NormalMethod {
    /// Least-squares plane through the point and its 8 neighbours.
    Plane,
    /// Derivatives at the grid point of the bicubic (not-a-knot) spline through the data.
    Spline,
}

/// Unit normals `(-∂h/∂x, -∂h/∂y, 1)/|…|` at every point, shape `(ny, nx)`; NaN vectors on the
/// border and wherever the 3 × 3 neighbourhood holds an invalid point.
pub fn facet_normals(map: &HeightMap, method: NormalMethod) -> Array2<DVec3> {
    let (ny, nx) = (map.ny(), map.nx());
    let (dx, dy) = (map.dx(), map.dy());
    let mut out = Array2::from_elem((ny, nx), DVec3::NAN);
    if nx < 3 || ny < 3 {
        return out;
    }
    let h = map.heights().as_standard_layout();
    let z = h.as_slice().expect("standard layout is contiguous");
    let spline = (method == NormalMethod::Spline).then(|| {
        (
            slopes_along_rows(h.view(), dx),
            slopes_along_columns(h.view(), dy),
        )
    });
    let out_rows = out.as_slice_mut().expect("built in standard layout");
    out_rows
        .par_chunks_mut(nx)
        .enumerate()
        .skip(1)
        .take(ny - 2)
        .for_each(|(iy, row)| {
            let (a, b, c) = (
                &z[(iy - 1) * nx..iy * nx],
                &z[iy * nx..(iy + 1) * nx],
                &z[(iy + 1) * nx..(iy + 2) * nx],
            );
            for ix in 1..nx - 1 {
                let (below, mid, above) = (
                    a[ix - 1] + a[ix] + a[ix + 1],
                    b[ix - 1] + b[ix] + b[ix + 1],
                    c[ix - 1] + c[ix] + c[ix + 1],
                );
                // Heights are finite where valid, so the block sum is NaN exactly when the 3 × 3
                // block holds an invalid point.
                if (below + mid + above).is_nan() {
                    continue;
                }
                let (gx, gy) = match &spline {
                    Some((sx, sy)) => (sx[[iy, ix]], sy[[iy, ix]]),
                    // Least squares on the symmetric 3 × 3 stencil: the offsets i, j ∈ {-1, 0, 1}
                    // are orthogonal, so slope_x = Σ i·z / (dx Σ i²) = Σ i·z / (6 dx), likewise y.
                    None => (
                        ((a[ix + 1] - a[ix - 1])
                            + (b[ix + 1] - b[ix - 1])
                            + (c[ix + 1] - c[ix - 1]))
                            / (6.0 * dx),
                        (above - below) / (6.0 * dy),
                    ),
                };
                row[ix] = DVec3::new(-gx, -gy, 1.0).normalize();
            }
        });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map_of(nx: usize, ny: usize, dx: f64, dy: f64, f: impl Fn(f64, f64) -> f64) -> HeightMap {
        let h = Array2::from_shape_fn((ny, nx), |(iy, ix)| f(ix as f64 * dx, iy as f64 * dy));
        HeightMap::with_invalid(h, dx, dy).unwrap()
    }

    #[test]
    fn tilted_plane_is_exact() {
        let (a, b) = (0.3, -0.7);
        let map = map_of(12, 9, 1e-6, 2.5e-6, |x, y| 1e-4 + a * x + b * y);
        let expect = DVec3::new(-a, -b, 1.0).normalize();
        for method in [NormalMethod::Plane, NormalMethod::Spline] {
            let n = facet_normals(&map, method);
            for ((iy, ix), v) in n.indexed_iter() {
                let border = ix == 0 || iy == 0 || ix == 11 || iy == 8;
                if border {
                    assert!(v.is_nan(), "{method:?} border ({ix}, {iy})");
                } else {
                    assert!(
                        (*v - expect).length() < 1e-12,
                        "{method:?} ({ix}, {iy}): {v}"
                    );
                }
            }
        }
    }

    /// h = A sin(kx x) sin(ky y) on a grid with dx ≠ dy. The plane fit's slopes follow from the
    /// stencil sums (module docs): along x the factor sin(kx dx)/(kx dx) from the x offsets and
    /// (1 + 2 cos(ky dy))/3 from averaging the three rows, and symmetrically along y. The spline's
    /// slopes along a grid line carry 3 sin(k d)/(k d (2 + cos(k d))) (module docs), and the
    /// spline is exact across lines because it interpolates. Both are checked to rounding, and
    /// both against the true normals within the error these factors predict.
    #[test]
    fn sinusoid_normals_match_the_predicted_discretisation_error() {
        let (dx, dy) = (0.5e-6, 0.8e-6);
        let (nx, ny) = (96, 64);
        let (kx, ky) = (
            2.0 * std::f64::consts::PI / (16.0 * dx),
            2.0 * std::f64::consts::PI / (8.0 * dy),
        );
        let amp = 0.2e-6;
        let map = map_of(nx, ny, dx, dy, |x, y| amp * (kx * x).sin() * (ky * y).sin());
        let true_slope = |x: f64, y: f64| {
            (
                amp * kx * (kx * x).cos() * (ky * y).sin(),
                amp * ky * (kx * x).sin() * (ky * y).cos(),
            )
        };
        let sinc = |u: f64| u.sin() / u;
        let plane = (
            sinc(kx * dx) * (1.0 + 2.0 * (ky * dy).cos()) / 3.0,
            sinc(ky * dy) * (1.0 + 2.0 * (kx * dx).cos()) / 3.0,
        );
        let spline_factor = |u: f64| 3.0 * u.sin() / (u * (2.0 + u.cos()));
        let spline = (spline_factor(kx * dx), spline_factor(ky * dy));
        for (method, (fx, fy), margin) in [
            (NormalMethod::Plane, plane, 1),
            (NormalMethod::Spline, spline, 20),
        ] {
            let n = facet_normals(&map, method);
            let (mut worst_pred, mut worst_true, mut bound) = (0.0f64, 0.0f64, 0.0f64);
            for iy in margin..ny - margin {
                for ix in margin..nx - margin {
                    let (x, y) = (ix as f64 * dx, iy as f64 * dy);
                    let (gx, gy) = true_slope(x, y);
                    let predicted = DVec3::new(-gx * fx, -gy * fy, 1.0).normalize();
                    let truth = DVec3::new(-gx, -gy, 1.0).normalize();
                    worst_pred = worst_pred.max((n[[iy, ix]] - predicted).length());
                    worst_true = worst_true.max((n[[iy, ix]] - truth).length());
                    bound = bound.max((predicted - truth).length());
                }
            }
            assert!(
                worst_pred < 1e-9,
                "{method:?}: {worst_pred} from the predicted normals"
            );
            assert!(
                worst_true <= bound * 1.0001 + 1e-12,
                "{method:?}: {worst_true} > {bound}"
            );
        }
        // The spline's error is far below the plane fit's at 8 to 16 points per period.
        assert!(spline.0 - 1.0 > -1e-3 && plane.0 - 1.0 < -0.02);
    }

    #[test]
    fn facets_touching_invalid_points_are_skipped() {
        let mut map = map_of(10, 10, 1.0, 1.0, |x, y| 0.1 * x + 0.2 * y);
        let mut h = map.heights().clone();
        h[[5, 5]] = f64::NAN;
        map = map.with_heights(h).unwrap();
        for method in [NormalMethod::Plane, NormalMethod::Spline] {
            let n = facet_normals(&map, method);
            for iy in 1..9usize {
                for ix in 1..9usize {
                    let near = ix.abs_diff(5) <= 1 && iy.abs_diff(5) <= 1;
                    assert_eq!(n[[iy, ix]].is_nan(), near, "{method:?} ({ix}, {iy})");
                }
            }
        }
    }
}
