//! Chromatic adaptation (Bradford): the published D50 → D65 matrix, white to white and back.

use gonio_color::adaptation::*;
use gonio_color::xyz::Xyz;

/// B. Lindbloom, "Chromatic Adaptation" (brucelindbloom.com), Bradford matrix D50 → D65 for
/// the whites D50 = (0.96422, 1, 0.82521) and D65 = (0.95047, 1, 1.08883); the same numbers
/// come out of colour-science 0.4.7 `matrix_chromatic_adaptation_VonKries(..., "Bradford")`.
#[test]
fn matches_the_published_d50_to_d65_matrix() {
    let d50 = Xyz::new(0.96422, 1.0, 0.82521);
    let d65 = Xyz::new(0.95047, 1.0, 1.08883);
    let published = [
        [0.955_576_6, -0.023_039_3, 0.063_163_6],
        [-0.028_289_5, 1.009_941_6, 0.021_007_7],
        [0.012_298_2, -0.020_483_0, 1.329_909_8],
    ];
    let m = bradford_matrix(d50, d65);
    for r in 0..3 {
        for c in 0..3 {
            assert!(
                (m[r][c] - published[r][c]).abs() < 1e-7,
                "{r} {c}: {}",
                m[r][c]
            );
        }
    }
}

#[test]
fn maps_white_to_white_and_inverts() {
    let a = Xyz::new(109.85, 100.0, 35.585);
    let d65 = Xyz::new(95.047, 100.0, 108.883);
    let w = adapt(a, a, d65);
    for (x, y) in w.to_array().iter().zip(d65.to_array()) {
        assert!((x - y).abs() < 1e-10);
    }
    let colour = Xyz::new(20.0, 15.0, 8.0);
    let back = adapt(adapt(colour, a, d65), d65, a);
    for (x, y) in back.to_array().iter().zip(colour.to_array()) {
        assert!((x - y).abs() < 1e-12);
    }
}
