//! Quarter turns and turned pairs of height maps: four quarter turns are the identity, a quarter
//! turn agrees with a rotation by 90°, a turned pair crops to the inscribed square.

use gonio_surface::heightmap::HeightMap;
use gonio_surface::ops::turns::*;
use gonio_surface::ops::{crop, rotate};
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
