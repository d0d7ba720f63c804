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
