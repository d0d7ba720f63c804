//! Turning a height map about its centre: exact quarter turns (no interpolation), and the pair
//! of an original and a turned map over the same area that the isotropy check compares.

use super::{crop, rotate};
use crate::error::{Result, SurfaceError};
use crate::heightmap::HeightMap;
use ndarray::Array2;

/// The map turned by `turns` quarter turns counter-clockwise (from +x toward +y) about its
/// centre, exactly: the point at `(x, y)` of the result is the point at `(y, -x)` of `map`
/// (about the centre), as [`rotate`] by 90° would give, but without interpolation; the grid and
/// spacings are swapped for odd turns.
pub fn quarter_turns(map: &HeightMap, turns: i64) -> Result<HeightMap> {
    let mut out = map.clone();
    for _ in 0..turns.rem_euclid(4) {
        let h = out.heights();
        let ny = h.nrows();
        let turned = Array2::from_shape_fn((h.ncols(), ny), |(iy, ix)| h[[ny - 1 - ix, iy]]);
        let meta = out.meta.clone();
        out = HeightMap::with_invalid(turned, out.dy(), out.dx())?;
        out.meta = meta;
    }
    Ok(out)
}

/// The number of quarter turns `angle_deg` is, when it is a whole number of them.
fn as_quarter_turns(angle_deg: f64) -> Option<i64> {
    let q = angle_deg / 90.0;
    ((q - q.round()).abs() < 1e-9).then(|| q.round() as i64)
}

/// The original map and the map turned by `angle_deg`, over the same area: for a quarter turn
/// the whole map and its exact turn; otherwise both cropped to the largest centred square that
/// lies inside the turned map. Returns `(original, turned, exact)`.
pub fn turned_pair(map: &HeightMap, angle_deg: f64) -> Result<(HeightMap, HeightMap, bool)> {
    if !angle_deg.is_finite() {
        return Err(SurfaceError::Invalid(format!(
            "rotation angle {angle_deg}° is not finite"
        )));
    }
    if let Some(turns) = as_quarter_turns(angle_deg) {
        return Ok((map.clone(), quarter_turns(map, turns)?, true));
    }
    // A centred square of half-side h turned by theta stays inside the half-extents (a, b) when
    // h (|cos| + |sin|) <= min(a, b); one point of margin keeps its corners off the edge.
    let theta = angle_deg.to_radians();
    let a = 0.5 * (map.nx() - 1) as f64 * map.dx();
    let b = 0.5 * (map.ny() - 1) as f64 * map.dy();
    let half = a.min(b) / (theta.cos().abs() + theta.sin().abs());
    // Points along an axis of `n` with spacing `d`: the same parity as `n`, so the crop is
    // centred exactly, and within 2·half less one point of margin.
    let side = |n: usize, d: f64| -> usize {
        let fit = ((2.0 * half / d).floor() as usize).saturating_sub(1);
        let mut m = fit.min(n);
        if (n - m) % 2 == 1 {
            m = m.saturating_sub(1);
        }
        m
    };
    let (cx, cy) = (side(map.nx(), map.dx()), side(map.ny(), map.dy()));
    if cx < 8 || cy < 8 {
        return Err(SurfaceError::Invalid(format!(
            "the {} × {} map leaves only {cx} × {cy} points inside its turn by {angle_deg}°; \
             use a larger map",
            map.nx(),
            map.ny()
        )));
    }
    let (x0, y0) = ((map.nx() - cx) / 2, (map.ny() - cy) / 2);
    let turned = rotate(map, theta)?;
    Ok((
        crop(map, x0, y0, cx, cy)?,
        crop(&turned, x0, y0, cx, cy)?,
        false,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array2;

    /// A non-square map with unequal spacings and a non-measured point.
    fn odd_map() -> HeightMap {
        let h = Array2::from_shape_fn((5, 7), |(iy, ix)| {
            if (ix, iy) == (1, 3) {
                f64::NAN
            } else {
                1e-7 * (ix as f64 * 1.3 + (iy * iy) as f64 * 0.7).sin()
            }
        });
        HeightMap::with_invalid(h, 1e-6, 2e-6).unwrap()
    }

    /// Four quarter turns give the map back bit for bit; one turn swaps the grid and spacings and
    /// moves the non-measured point where the rotation takes it.
    #[test]
    fn four_quarter_turns_are_the_identity() {
        let map = odd_map();
        let one = quarter_turns(&map, 1).unwrap();
        assert_eq!((one.nx(), one.ny(), one.dx(), one.dy()), (5, 7, 2e-6, 1e-6));
        // Content at (x, y) came from (y, -x) about the centre: point (ix, iy) from (iy, 4 - ix).
        assert!(!one.is_valid(4 - 3, 1));
        assert_eq!(one.valid_count(), map.valid_count());
        let back = quarter_turns(
            &quarter_turns(&quarter_turns(&one, 1).unwrap(), 1).unwrap(),
            1,
        );
        let back = back.unwrap();
        assert_eq!(
            (back.nx(), back.ny(), back.dx(), back.dy()),
            (7, 5, 1e-6, 2e-6)
        );
        for (a, b) in back.heights().iter().zip(map.heights()) {
            assert!(a.to_bits() == b.to_bits(), "{a} != {b}");
        }
        let minus = quarter_turns(&map, -1).unwrap();
        let three = quarter_turns(&map, 3).unwrap();
        assert_eq!(minus.heights().shape(), three.heights().shape());
        assert!(
            minus
                .heights()
                .iter()
                .zip(three.heights())
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
    }

    /// The exact quarter turn is the interpolating rotation by 90° on a square grid.
    #[test]
    fn quarter_turn_agrees_with_rotate() {
        let n = 9;
        let h = Array2::from_shape_fn((n, n), |(iy, ix)| 1e-7 * ((ix * 3 + iy * 7) % 5) as f64);
        let map = HeightMap::new(h, 1e-6, 1e-6).unwrap();
        let exact = quarter_turns(&map, 1).unwrap();
        let spline = rotate(&map, std::f64::consts::FRAC_PI_2).unwrap();
        for (a, b) in exact.heights().iter().zip(spline.heights()) {
            assert!((a - b).abs() < 1e-15, "{a} vs {b}");
        }
    }

    /// A turn by 45° crops both maps to the largest centred square inside the turned map: for a
    /// 101 × 101 map, half-side 50/√2 = 35.4 points, so 70 points less one of margin, made odd to
    /// stay centred: 69. Every point of the crop is measured; 90° is exact and uncropped.
    #[test]
    fn turned_pair_crops_to_the_inscribed_square() {
        let n = 101;
        let h = Array2::from_shape_fn((n, n), |(iy, ix)| {
            1e-8 * (ix as f64 * 0.3).sin() * iy as f64
        });
        let map = HeightMap::new(h, 1e-6, 1e-6).unwrap();
        let (orig, turned, exact) = turned_pair(&map, 45.0).unwrap();
        assert!(!exact);
        assert_eq!(
            (orig.nx(), orig.ny(), turned.nx(), turned.ny()),
            (69, 69, 69, 69)
        );
        assert_eq!(turned.valid_count(), 69 * 69);
        assert_eq!(orig.get(0, 0), map.get(16, 16));
        let (orig, turned, exact) = turned_pair(&map, -270.0).unwrap();
        assert!(exact && orig.nx() == n && turned.nx() == n);
        // A wide map: the square is set by its short side, and centred on both axes.
        let wide = crop(&map, 0, 20, 101, 40).unwrap();
        let (o, t, _) = turned_pair(&wide, 30.0).unwrap();
        assert_eq!((o.nx(), o.ny()), (27, 26));
        assert_eq!(t.valid_count(), 27 * 26);
        assert!(turned_pair(&map, f64::NAN).is_err());
        let tiny = crop(&map, 0, 0, 9, 9).unwrap();
        assert!(
            turned_pair(&tiny, 45.0)
                .unwrap_err()
                .to_string()
                .contains("larger map")
        );
    }
}
