//! Chromatic adaptation by the linearised Bradford transform: the XYZ a colour seen under one
//! white should have to look the same under another.
//!
//! Source: K. M. Lam, *Metamerism and colour constancy*, PhD thesis, University of Bradford
//! (1985); the linearised form (without the non-linear blue exponent) as specified in ICC.1:2010
//! (ICC profile format), Annex E.3, and in CIE 160:2004 section 2 (as the cone-response matrix
//! of CIECAT97s / CIECAM97s). A von Kries scaling in the Bradford "cone" space:
//! `M⁻¹ · diag(ρ_d / ρ_s) · M`.

use crate::mat3::{self, Mat3};
use crate::xyz::Xyz;

/// The Bradford cone-response matrix (Lam 1985; ICC.1:2010 eq. E.9).
pub const BRADFORD: Mat3 = [
    [0.8951, 0.2664, -0.1614],
    [-0.7502, 1.7135, 0.0367],
    [0.0389, -0.0685, 1.0296],
];

/// The matrix that adapts XYZ relative to `source_white` to XYZ relative to `target_white`
/// (both whites in the same units; the matrix maps one onto the other exactly).
pub fn bradford_matrix(source_white: Xyz, target_white: Xyz) -> Mat3 {
    let cone_s = mat3::mul_vec(&BRADFORD, source_white.to_array());
    let cone_t = mat3::mul_vec(&BRADFORD, target_white.to_array());
    let gain = std::array::from_fn(|i| cone_t[i] / cone_s[i]);
    mat3::mul(
        &mat3::inverse(&BRADFORD),
        &mat3::mul(&mat3::diag(gain), &BRADFORD),
    )
}

/// `xyz` seen under `source_white`, adapted to `target_white` (Bradford).
pub fn adapt(xyz: Xyz, source_white: Xyz, target_white: Xyz) -> Xyz {
    Xyz::from_array(mat3::mul_vec(
        &bradford_matrix(source_white, target_white),
        xyz.to_array(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
