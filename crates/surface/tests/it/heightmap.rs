//! Height maps: NaN marks a point not measured, bad spacings and values are refused, a profile
//! is a map of one marked row.

use gonio_surface::heightmap::*;
use ndarray::{Array2, array};

#[test]
fn nan_marks_invalid_points() {
    let map = HeightMap::with_invalid(array![[0.0, f64::NAN], [1.0, 2.0]], 1e-6, 2e-6).unwrap();
    assert_eq!((map.nx(), map.ny()), (2, 2));
    assert!(!map.is_valid(1, 0));
    assert!(map.is_valid(0, 1));
    assert_eq!(map.get(0, 1), Some(1.0));
    assert_eq!(map.valid_count(), 3);
    assert!((map.valid_fraction() - 0.75).abs() < 1e-15);
}

#[test]
fn rejects_bad_spacing_and_values() {
    let h = array![[0.0, 1.0]];
    assert!(HeightMap::new(h.clone(), 0.0, 1.0).is_err());
    assert!(HeightMap::new(h.clone(), 1.0, -1.0).is_err());
    assert!(HeightMap::new(h.clone(), f64::NAN, 1.0).is_err());
    assert!(HeightMap::new(array![[0.0, f64::NAN]], 1.0, 1.0).is_err());
    assert!(HeightMap::with_invalid(array![[0.0, f64::INFINITY]], 1.0, 1.0).is_err());
    assert!(HeightMap::new(Array2::zeros((0, 3)), 1.0, 1.0).is_err());
    assert!(HeightMap::new(h, 1.0, 1.0).unwrap().mask().is_none());
}

#[test]
fn profiles_are_one_marked_row() {
    let p = HeightMap::profile(vec![0.0, 1e-9, f64::NAN], 1e-6).unwrap();
    assert!(p.is_profile());
    assert_eq!((p.nx(), p.ny(), p.dy()), (3, 1, 1e-6));
    assert!(
        p.with_heights(array![[1.0, 2.0, 3.0]])
            .unwrap()
            .is_profile()
    );
    let areal = HeightMap::new(array![[0.0], [1.0]], 1.0, 1.0).unwrap();
    assert!(!areal.is_profile());
    assert!(areal.into_profile().is_err());
    assert!(HeightMap::profile(vec![], 1e-6).is_err());
}
