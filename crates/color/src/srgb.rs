//! sRGB (IEC 61966-2-1:1999): linear sRGB from XYZ and the encoded (gamma) values a display
//! takes. Linear and encoded values are on the [0, 1] scale; XYZ on the 0–100 scale.
//!
//! The XYZ → linear sRGB matrix is derived from the standard's primaries R (0.64, 0.33),
//! G (0.30, 0.60), B (0.15, 0.06) and white D65 (0.3127, 0.3290) by the normalised primary
//! matrix construction of SMPTE RP 177-1993, so that it and its inverse are exact inverses; the
//! standard prints both rounded to four decimals (checked in the tests).

use crate::mat3::{self, Mat3};
use crate::xyz::Xyz;
use std::sync::LazyLock;

/// Chromaticity (x, y) of the sRGB white, CIE D65 as IEC 61966-2-1 rounds it.
pub const SRGB_WHITE_XY: [f64; 2] = [0.3127, 0.3290];

/// Chromaticities (x, y) of the sRGB red, green and blue primaries (ITU-R BT.709).
pub const SRGB_PRIMARIES_XY: [[f64; 2]; 3] = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]];

/// Linear sRGB on the [0, 1] scale (1 = the display white). Values outside [0, 1] are colours
/// outside the sRGB gamut.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct LinearSrgb {
    /// Red.
    pub r: f64,
    /// Green.
    pub g: f64,
    /// Blue.
    pub b: f64,
}

/// Encoded (non-linear, "gamma") sRGB in [0, 1], as 8-bit files and displays use it.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Srgb {
    /// Red.
    pub r: f64,
    /// Green.
    pub g: f64,
    /// Blue.
    pub b: f64,
}

/// XYZ (Y = 1 for white) → linear sRGB, from the primaries and white (SMPTE RP 177, section 3.3):
/// the columns of P = [xᵢ/yᵢ, 1, zᵢ/yᵢ] are scaled by S = P⁻¹ W so that white maps to (1, 1, 1).
static XYZ_TO_LINEAR_SRGB: LazyLock<Mat3> = LazyLock::new(|| {
    let column = |[x, y]: [f64; 2]| [x / y, 1.0, (1.0 - x - y) / y];
    let cols = SRGB_PRIMARIES_XY.map(column);
    let p: Mat3 = std::array::from_fn(|r| std::array::from_fn(|c| cols[c][r]));
    let scale = mat3::mul_vec(&mat3::inverse(&p), column(SRGB_WHITE_XY));
    mat3::inverse(&mat3::mul(&p, &mat3::diag(scale)))
});

/// The matrix taking XYZ (Y = 1 for white, not 100) to linear sRGB.
pub fn xyz_to_linear_srgb_matrix() -> &'static Mat3 {
    &XYZ_TO_LINEAR_SRGB
}

/// The sRGB white as XYZ on the 0–100 scale: (95.046, 100, 108.906) from x, y = 0.3127, 0.3290.
pub fn srgb_white() -> Xyz {
    let [x, y] = SRGB_WHITE_XY;
    Xyz::new(100.0 * x / y, 100.0, 100.0 * (1.0 - x - y) / y)
}

impl LinearSrgb {
    /// Linear sRGB of XYZ (0–100 scale) already relative to the D65 white.
    pub fn from_xyz(xyz: Xyz) -> Self {
        let [r, g, b] = mat3::mul_vec(&XYZ_TO_LINEAR_SRGB, xyz.to_array().map(|v| v / 100.0));
        Self { r, g, b }
    }

    /// Back to XYZ (0–100 scale).
    pub fn to_xyz(self) -> Xyz {
        let m = mat3::inverse(&XYZ_TO_LINEAR_SRGB);
        Xyz::from_array(mat3::mul_vec(&m, [self.r, self.g, self.b]).map(|v| v * 100.0))
    }

    /// True when every component lies in [0, 1] (give or take 1e-9 of rounding): the colour is
    /// displayable in sRGB.
    pub fn in_gamut(self) -> bool {
        [self.r, self.g, self.b]
            .iter()
            .all(|v| (-1e-9..=1.0 + 1e-9).contains(v))
    }

    /// Encoded sRGB, each component clipped to [0, 1] first.
    pub fn encode(self) -> Srgb {
        Srgb {
            r: encode(self.r),
            g: encode(self.g),
            b: encode(self.b),
        }
    }
}

impl Srgb {
    /// Back to linear sRGB.
    pub fn decode(self) -> LinearSrgb {
        LinearSrgb {
            r: decode(self.r),
            g: decode(self.g),
            b: decode(self.b),
        }
    }

    /// 8-bit code values (round to nearest).
    pub fn to_u8(self) -> [u8; 3] {
        [self.r, self.g, self.b].map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
    }

    /// `#rrggbb`.
    pub fn to_hex(self) -> String {
        let [r, g, b] = self.to_u8();
        format!("#{r:02x}{g:02x}{b:02x}")
    }
}

/// The sRGB transfer function (IEC 61966-2-1, eq. 5.2 inverted): linear → encoded, the input
/// clipped to [0, 1].
pub fn encode(linear: f64) -> f64 {
    let v = linear.clamp(0.0, 1.0);
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// Encoded → linear (IEC 61966-2-1, eq. 5.2), the input clipped to [0, 1].
pub fn decode(encoded: f64) -> f64 {
    let v = encoded.clamp(0.0, 1.0);
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// IEC 61966-2-1:1999, eqs. 5.1 and 5.3 (four-decimal matrices as printed in the standard).
    #[test]
    fn derived_matrices_match_the_printed_ones() {
        let printed = [
            [3.2406, -1.5372, -0.4986],
            [-0.9689, 1.8758, 0.0415],
            [0.0557, -0.2040, 1.0570],
        ];
        let printed_inverse = [
            [0.4124, 0.3576, 0.1805],
            [0.2126, 0.7152, 0.0722],
            [0.0193, 0.1192, 0.9505],
        ];
        let m = xyz_to_linear_srgb_matrix();
        let inv = mat3::inverse(m);
        // The RGB → XYZ matrix is printed rounded to four decimals: half a unit in the last place.
        // The printed XYZ → RGB matrix is the inverse of that rounded matrix, which moves its
        // entries by up to 4e-4 from the exact inverse.
        for r in 0..3 {
            for c in 0..3 {
                assert!(
                    (inv[r][c] - printed_inverse[r][c]).abs() <= 5e-5,
                    "{r} {c}: {}",
                    inv[r][c]
                );
                assert!(
                    (m[r][c] - printed[r][c]).abs() < 5e-4,
                    "{r} {c}: {}",
                    m[r][c]
                );
            }
        }
        let of_rounded = mat3::inverse(&printed_inverse);
        for r in 0..3 {
            for c in 0..3 {
                assert!((of_rounded[r][c] - printed[r][c]).abs() <= 5e-5);
            }
        }
    }

    #[test]
    fn white_maps_to_one() {
        let rgb = LinearSrgb::from_xyz(srgb_white());
        for v in [rgb.r, rgb.g, rgb.b] {
            assert!((v - 1.0).abs() < 1e-12);
        }
        assert_eq!(rgb.encode().to_hex(), "#ffffff");
    }

    /// The two branches of the transfer function meet (within the standard's rounding) at the
    /// break points, and 8-bit code values survive decode → encode.
    #[test]
    fn transfer_function_round_trips() {
        assert!((encode(0.003_130_8) - 0.040_45).abs() < 1e-6);
        assert!(
            (1.055 * 0.003_130_8f64.powf(1.0 / 2.4) - 0.055 - 12.92 * 0.003_130_8).abs() < 1e-6
        );
        for code in 0..=255u32 {
            let v = code as f64 / 255.0;
            assert!((encode(decode(v)) - v).abs() < 1e-12, "code {code}");
        }
        for k in 0..=1000 {
            let v = k as f64 / 1000.0;
            assert!((decode(encode(v)) - v).abs() < 1e-12);
        }
        // Middle grey: linear 0.18 encodes to 0.4614 (118 of 255).
        assert!((encode(0.18) - 0.461_356).abs() < 1e-6);
        assert_eq!(
            Srgb {
                r: encode(0.18),
                g: 0.0,
                b: 1.0
            }
            .to_u8(),
            [118, 0, 255]
        );
    }

    #[test]
    fn xyz_round_trips_through_linear_srgb() {
        for i in 0..=10 {
            for j in 0..=10 {
                for k in 0..=10 {
                    let rgb = LinearSrgb {
                        r: i as f64 / 10.0,
                        g: j as f64 / 10.0,
                        b: k as f64 / 10.0,
                    };
                    let back = LinearSrgb::from_xyz(rgb.to_xyz());
                    assert!(rgb.in_gamut());
                    let err =
                        (back.r - rgb.r).abs() + (back.g - rgb.g).abs() + (back.b - rgb.b).abs();
                    assert!(err < 1e-12);
                    let enc = rgb.encode().decode();
                    assert!(
                        (enc.r - rgb.r).abs() + (enc.g - rgb.g).abs() + (enc.b - rgb.b).abs()
                            < 1e-12
                    );
                }
            }
        }
    }
}
