//! Levelling, crops, rotation and resampling of height maps: a plane is removed exactly, rotations
//! of planes and quarter turns are exact, resampling keeps the extent and smooth shapes.

use gonio_surface::heightmap::HeightMap;
use gonio_surface::ops::*;
use ndarray::Array2;

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
    let req = gonio_surface::synth::GaussianSurface::square(1e-7, 4e-6, 128, 0.5e-6, 9);
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
