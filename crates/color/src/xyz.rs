//! Tristimulus values and the colour spaces derived from them without a display: CIE XYZ,
//! chromaticity (xyY) and CIELAB.
//!
//! Scale: XYZ on the 0–100 scale, Y = 100 for the perfect reflecting diffuser under the chosen
//! illuminant (CIE 15:2004, section 7.1).

/// CIE XYZ tristimulus values (0–100 scale).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Xyz {
    /// X.
    pub x: f64,
    /// Y (luminance factor × 100 for a reflector).
    pub y: f64,
    /// Z.
    pub z: f64,
}

/// Chromaticity coordinates x, y and the luminance Y.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct XyY {
    /// x = X / (X + Y + Z).
    pub x: f64,
    /// y = Y / (X + Y + Z).
    pub y: f64,
    /// Y, unchanged from XYZ.
    pub big_y: f64,
}

/// CIE 1976 L*a*b* (CIELAB) coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lab {
    /// Lightness L* (0–100).
    pub l: f64,
    /// Red–green opponent coordinate a*.
    pub a: f64,
    /// Yellow–blue opponent coordinate b*.
    pub b: f64,
}

impl Xyz {
    /// XYZ from its three components.
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }

    /// As an array [X, Y, Z].
    pub fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }

    /// From an array [X, Y, Z].
    pub fn from_array([x, y, z]: [f64; 3]) -> Self {
        Self { x, y, z }
    }

    /// Chromaticity and luminance (CIE 15:2004, eq. 7.3); `None` for black (X + Y + Z = 0), whose
    /// chromaticity is undefined.
    pub fn to_xyy(self) -> Option<XyY> {
        let sum = self.x + self.y + self.z;
        (sum != 0.0).then(|| XyY {
            x: self.x / sum,
            y: self.y / sum,
            big_y: self.y,
        })
    }

    /// CIELAB relative to the reference white `white` (the XYZ of the perfect reflecting diffuser
    /// under the same illuminant and observer). CIE 15:2004, section 8.2.1, eqs. 8.3–8.5, with
    /// the exact constants (6/29)³ and (29/6)²/3 of the linear segment.
    pub fn to_lab(self, white: Xyz) -> Lab {
        let fx = lab_f(self.x / white.x);
        let fy = lab_f(self.y / white.y);
        let fz = lab_f(self.z / white.z);
        Lab {
            l: 116.0 * fy - 16.0,
            a: 500.0 * (fx - fy),
            b: 200.0 * (fy - fz),
        }
    }
}

impl XyY {
    /// Back to XYZ; a chromaticity with y = 0 has no finite XYZ unless Y = 0, so it gives black.
    pub fn to_xyz(self) -> Xyz {
        if self.y == 0.0 {
            return Xyz::default();
        }
        let scale = self.big_y / self.y;
        Xyz {
            x: self.x * scale,
            y: self.big_y,
            z: (1.0 - self.x - self.y) * scale,
        }
    }
}

impl Lab {
    /// Back to XYZ for the reference white `white`: the inverse of [`Xyz::to_lab`] (CIE 15:2004,
    /// section 8.2.1, note 3).
    pub fn to_xyz(self, white: Xyz) -> Xyz {
        let fy = (self.l + 16.0) / 116.0;
        let fx = fy + self.a / 500.0;
        let fz = fy - self.b / 200.0;
        Xyz {
            x: white.x * lab_f_inverse(fx),
            y: white.y * lab_f_inverse(fy),
            z: white.z * lab_f_inverse(fz),
        }
    }

    /// Chroma C*ab = √(a*² + b*²).
    pub fn chroma(self) -> f64 {
        self.a.hypot(self.b)
    }

    /// Hue angle h_ab in degrees, [0, 360).
    pub fn hue_deg(self) -> f64 {
        self.b.atan2(self.a).to_degrees().rem_euclid(360.0)
    }
}

/// δ = 6/29: the CIELAB function is cubic above δ³ and linear below.
const LAB_DELTA: f64 = 6.0 / 29.0;

/// The slope of CIELAB lightness in the relative luminance, dL*/d(Y/Yn) at `t` = Y/Yn: from
/// L* = 116 f(t) − 16 (CIE 15:2004, section 8.2.1, eq. 8.3), (116/3) t^(−2/3) above t = (6/29)³
/// (L* 8) and 116/(3 δ²) = 903.3 below, where f is linear (the two meet there). A small error
/// dY in the luminance is an error of about this times dY/Yn in L*: what the walks of a coating's
/// table aim their noise at (`gonio_coating::cell`).
pub fn lightness_slope(t: f64) -> f64 {
    let knee = LAB_DELTA.powi(3);
    116.0 / 3.0 / t.max(knee).cbrt().powi(2)
}

fn lab_f(t: f64) -> f64 {
    if t > LAB_DELTA.powi(3) {
        t.cbrt()
    } else {
        t / (3.0 * LAB_DELTA * LAB_DELTA) + 4.0 / 29.0
    }
}

fn lab_f_inverse(f: f64) -> f64 {
    if f > LAB_DELTA {
        f.powi(3)
    } else {
        3.0 * LAB_DELTA * LAB_DELTA * (f - 4.0 / 29.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const D65_WHITE: Xyz = Xyz::new(95.047, 100.0, 108.883);

    #[test]
    fn white_is_l100_and_black_is_l0() {
        let lab = D65_WHITE.to_lab(D65_WHITE);
        assert!((lab.l - 100.0).abs() < 1e-12 && lab.a.abs() < 1e-12 && lab.b.abs() < 1e-12);
        let black = Xyz::default().to_lab(D65_WHITE);
        assert!(black.l.abs() < 1e-12);
        assert!(Xyz::default().to_xyy().is_none());
    }

    /// Y/Yn = 0.18 gives L* = 116 · 0.18^(1/3) − 16 = 49.4961 (middle grey), and the two branches
    /// of f meet at t = (6/29)³ where L* = 8.
    #[test]
    fn lightness_values() {
        let grey = Xyz::new(0.18 * D65_WHITE.x, 18.0, 0.18 * D65_WHITE.z).to_lab(D65_WHITE);
        assert!((grey.l - 49.496_1).abs() < 1e-4, "{}", grey.l);
        let knee = (6.0f64 / 29.0).powi(3);
        let below = lab_f(knee * (1.0 - 1e-12));
        let above = lab_f(knee * (1.0 + 1e-12));
        assert!((below - above).abs() < 1e-10);
        assert!((116.0 * lab_f(knee) - 16.0 - 8.0).abs() < 1e-10);
    }

    /// The slope against central differences of L* (step 1e-6 of t; the error of the
    /// difference is of order t² f'''/6 · 1e-12, far below the bound) on both branches and at the
    /// knee, where both sides give 903.3.
    #[test]
    fn lightness_slope_is_the_derivative() {
        let l = |t: f64| Xyz::new(0.0, 100.0 * t, 0.0).to_lab(D65_WHITE).l;
        for t in [1e-4f64, 3e-3, 0.0088, 0.0089, 0.05, 0.18, 0.5, 1.0, 2.5] {
            let h = 1e-6 * t.max(1e-3);
            let numeric = (l(t + h) - l(t - h)) / (2.0 * h);
            let slope = lightness_slope(t);
            assert!(
                (slope / numeric - 1.0).abs() < 1e-4,
                "t {t}: {slope} against {numeric}"
            );
        }
        let knee = LAB_DELTA.powi(3);
        assert!((lightness_slope(knee) - 116.0 * 841.0 / 108.0).abs() < 1e-9);
    }

    #[test]
    fn lab_and_xyy_round_trip() {
        for i in 0..=20 {
            for j in 0..=20 {
                for k in 0..=20 {
                    let xyz = Xyz::new(i as f64 * 5.0, j as f64 * 5.0 + 0.01, k as f64 * 5.5);
                    let lab_back = xyz.to_lab(D65_WHITE).to_xyz(D65_WHITE);
                    let xyy_back = xyz.to_xyy().unwrap().to_xyz();
                    for back in [lab_back, xyy_back] {
                        for (a, b) in back.to_array().iter().zip(xyz.to_array()) {
                            assert!((a - b).abs() < 1e-9, "{xyz:?} -> {back:?}");
                        }
                    }
                }
            }
        }
    }
}
