//! Kubelka-Munk two-constant theory of a pigmented layer: diffuse light in two opposite fluxes,
//! absorbed at rate K and scattered back at rate S per unit thickness. The reflectance of a
//! layer of finite thickness over a substrate, its transmittance, the reflectance of an opaque
//! layer, pigment mixtures, and the Saunderson correction between the layer's internal
//! reflectance and what an instrument reads through the layer's surface.
//!
//! Formulas (P. Kubelka, "New contributions to the optics of intensely light-scattering
//! materials, Part I", JOSA 38, 448 (1948), eqs. 6 and 12; Judd & Wyszecki, *Color in Business,
//! Science and Industry*, 3rd ed., ch. 3): with `a = 1 + K/S`, `b = √(a² − 1)`, a layer of
//! thickness X over a substrate of reflectance Rg reflects
//! `R = (1 − Rg (a − b coth bSX)) / (a − Rg + b coth bSX)`, transmits
//! `T = b / (a sinh bSX + b cosh bSX)`, and an opaque layer reflects `R∞ = a − b`.
//! Units: K and S in 1/µm, X in µm (only the products KX and SX matter).
//!
//! The interface with the medium above is not in these formulas: they give the reflectance
//! inside the layer's surface. A colour-matching program applies the Saunderson correction
//! ([`saunderson`]) to compare them with a measurement through an air–binder surface. gonio's
//! layered coating will count the interface once, in the stack's transport, and use the
//! internal reflectance directly.

use crate::error::{CoatingError, Result};

/// Absorption and scattering coefficients of a pigmented layer, 1/µm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients {
    /// Absorption K, 1/µm.
    pub k: f64,
    /// Scattering S, 1/µm.
    pub s: f64,
}

impl Coefficients {
    /// Coefficients that describe a medium: finite and non-negative.
    pub fn new(k: f64, s: f64) -> Result<Self> {
        if !(k.is_finite() && s.is_finite() && k >= 0.0 && s >= 0.0) {
            return Err(CoatingError::Invalid(format!(
                "Kubelka-Munk coefficients K = {k}, S = {s} (1/µm): both must be finite and \
                 non-negative"
            )));
        }
        Ok(Self { k, s })
    }

    /// The coefficients of a mixture: each pigment's coefficients per unit concentration
    /// weighted by its concentration, summed (Duncan's linear mixing; a binder is one more
    /// constituent, usually with K and S near 0).
    pub fn mixture(constituents: &[(f64, Coefficients)]) -> Result<Self> {
        let (mut k, mut s) = (0.0, 0.0);
        for &(c, co) in constituents {
            if !(c.is_finite() && c >= 0.0) {
                return Err(CoatingError::Invalid(format!(
                    "concentration {c}: must be finite and non-negative"
                )));
            }
            k += c * co.k;
            s += c * co.s;
        }
        Self::new(k, s)
    }

    /// Reflectance of an opaque layer, `R∞ = a − b = 1 + K/S − √((K/S)² + 2 K/S)`; 1 for a
    /// non-absorbing layer, 0 for one that only absorbs.
    pub fn r_infinity(&self) -> f64 {
        if self.s == 0.0 {
            return if self.k == 0.0 { 1.0 } else { 0.0 };
        }
        let q = self.k / self.s;
        // a − b written as 1/(a + b), which keeps its digits when K/S is large.
        1.0 / (1.0 + q + (q * q + 2.0 * q).sqrt())
    }

    /// Reflectance of a layer `thickness_um` thick over a substrate of reflectance `rg`.
    pub fn reflectance(&self, thickness_um: f64, rg: f64) -> f64 {
        let (k, s, x) = (self.k, self.s, thickness_um);
        if x == 0.0 {
            return rg;
        }
        if s == 0.0 {
            // Absorption only: the light crosses the layer twice.
            return rg * (-2.0 * k * x).exp();
        }
        let a = 1.0 + k / s;
        let b = (a * a - 1.0).sqrt();
        let bc = b_coth(b, s * x);
        (1.0 - rg * (a - bc)) / (a - rg + bc)
    }

    /// Diffuse transmittance of a layer `thickness_um` thick (into a non-reflecting medium).
    pub fn transmittance(&self, thickness_um: f64) -> f64 {
        let (k, s, x) = (self.k, self.s, thickness_um);
        if s == 0.0 {
            return (-k * x).exp();
        }
        let a = 1.0 + k / s;
        let b = (a * a - 1.0).sqrt();
        let y = b * s * x;
        if y == 0.0 {
            // No absorption: T = 1 / (1 + SX).
            return 1.0 / (1.0 + s * x);
        }
        b / (a * y.sinh() + b * y.cosh())
    }
}

/// `b coth(b y)`, continued to `1/y` at b = 0 (a non-absorbing layer) by its series
/// `1/y + b² y/3 − b⁴ y³/45 + …`, used where `b y < 1e-4` (the next term is below 1e-17 of the
/// first there). `y` is positive.
fn b_coth(b: f64, y: f64) -> f64 {
    let by = b * y;
    if by < 1e-4 {
        1.0 / y + b * by / 3.0
    } else {
        b / by.tanh()
    }
}

/// The Saunderson correction (J. L. Saunderson, JOSA 32, 727 (1942)): the reflectance an
/// instrument reads through the layer's surface, `k1 + (1 − k1)(1 − k2) R / (1 − k2 R)`, from the
/// internal reflectance `r` (Kubelka-Munk's), the surface's external reflectance `k1` for the
/// instrument's illumination (specular included: about 0.04 for n = 1.5 at normal incidence) and
/// its internal reflectance `k2` for diffuse light from inside (about 0.6 for n = 1.5, total
/// internal reflection included).
pub fn saunderson(r: f64, k1: f64, k2: f64) -> f64 {
    k1 + (1.0 - k1) * (1.0 - k2) * r / (1.0 - k2 * r)
}

/// The inverse of [`saunderson`]: the internal reflectance behind a measured reflectance `rm`.
pub fn inverse_saunderson(rm: f64, k1: f64, k2: f64) -> f64 {
    (rm - k1) / ((1.0 - k1) * (1.0 - k2) + k2 * (rm - k1))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kubelka's exponential form of the same solution (JOSA 38, 448, eq. 6 rearranged with
    /// R∞): `R = [(Rg − R∞)/R∞ − R∞ (Rg − 1/R∞) e^{SX(1/R∞ − R∞)}] /
    /// [(Rg − R∞) − (Rg − 1/R∞) e^{SX(1/R∞ − R∞)}]`, written here independently of the coth form.
    fn exponential_form(k: f64, s: f64, x: f64, rg: f64) -> f64 {
        let q = k / s;
        let r_inf = 1.0 + q - (q * q + 2.0 * q).sqrt();
        let e = (s * x * (1.0 / r_inf - r_inf)).exp();
        ((rg - r_inf) / r_inf - r_inf * (rg - 1.0 / r_inf) * e)
            / ((rg - r_inf) - (rg - 1.0 / r_inf) * e)
    }

    #[test]
    fn finite_layer_equals_kubelkas_exponential_form() {
        for (k, s) in [(0.01, 0.5), (0.2, 0.3), (1.0, 0.05), (0.05, 2.0)] {
            let c = Coefficients::new(k, s).unwrap();
            for x in [0.5, 5.0, 20.0] {
                for rg in [0.0, 0.3, 0.9] {
                    let got = c.reflectance(x, rg);
                    let want = exponential_form(k, s, x, rg);
                    assert!(
                        (got - want).abs() < 1e-9,
                        "K {k} S {s} X {x} Rg {rg}: {got} vs {want}"
                    );
                }
            }
        }
    }

    /// Thick layers reach R∞ = a − b whatever the substrate; no thickness shows the substrate.
    #[test]
    fn limits() {
        let c = Coefficients::new(0.2, 0.3).unwrap();
        let a: f64 = 1.0 + 0.2 / 0.3;
        let r_inf = a - (a * a - 1.0).sqrt();
        assert!((c.r_infinity() - r_inf).abs() < 1e-15);
        for rg in [0.0, 0.5, 1.0] {
            assert!((c.reflectance(500.0, rg) - r_inf).abs() < 1e-12);
            assert_eq!(c.reflectance(0.0, rg), rg);
        }
    }

    /// A non-absorbing layer over a black substrate: R = SX/(1 + SX) and T = 1/(1 + SX), which
    /// conserve energy, R + T = 1; over a white one it stays white. An absorbing layer loses
    /// light: R + T < 1. The series branch meets the coth branch continuously.
    #[test]
    fn non_absorbing_layer_conserves_energy() {
        let c = Coefficients::new(0.0, 0.4).unwrap();
        for x in [0.1, 1.0, 10.0] {
            let sx = 0.4 * x;
            let (r, t) = (c.reflectance(x, 0.0), c.transmittance(x));
            assert!((r - sx / (1.0 + sx)).abs() < 1e-15, "{r}");
            assert!((r + t - 1.0).abs() < 1e-15);
            assert!((c.reflectance(x, 1.0) - 1.0).abs() < 1e-15);
        }
        let absorbing = Coefficients::new(0.1, 0.4).unwrap();
        assert!(absorbing.reflectance(3.0, 0.0) + absorbing.transmittance(3.0) < 0.99);
        let tiny = Coefficients::new(1e-12, 0.4).unwrap();
        assert!((tiny.reflectance(2.0, 0.2) - c.reflectance(2.0, 0.2)).abs() < 1e-10);
    }

    /// The transmittance satisfies Kubelka's relation between R, T and R∞ for a layer over a
    /// black substrate (JOSA 38, eq. 12c): `T² = (R∞ − R)(1/R∞ − R)`.
    #[test]
    fn transmittance_obeys_kubelkas_relation() {
        for (k, s, x) in [(0.1, 0.4, 3.0), (0.02, 1.0, 0.7), (0.5, 0.5, 2.0)] {
            let c = Coefficients::new(k, s).unwrap();
            let (r, t, ri) = (c.reflectance(x, 0.0), c.transmittance(x), c.r_infinity());
            assert!(
                (t * t - (ri - r) * (1.0 / ri - r)).abs() < 1e-12,
                "{k} {s} {x}"
            );
        }
    }

    #[test]
    fn mixture_is_linear_and_bad_values_are_refused() {
        let white = Coefficients::new(0.001, 1.2).unwrap();
        let red = Coefficients::new(0.8, 0.1).unwrap();
        let m = Coefficients::mixture(&[(0.7, white), (0.3, red)]).unwrap();
        assert!((m.k - (0.7 * 0.001 + 0.3 * 0.8)).abs() < 1e-15);
        assert!((m.s - (0.7 * 1.2 + 0.3 * 0.1)).abs() < 1e-15);
        assert!(Coefficients::new(-1.0, 1.0).is_err());
        assert!(Coefficients::mixture(&[(f64::NAN, white)]).is_err());
    }

    #[test]
    fn saunderson_round_trip() {
        for r in [0.0, 0.2, 0.7, 1.0] {
            let rm = saunderson(r, 0.04, 0.6);
            assert!((inverse_saunderson(rm, 0.04, 0.6) - r).abs() < 1e-14);
        }
        // A black layer reads the surface's own reflection; a white one reads 1.
        assert_eq!(saunderson(0.0, 0.04, 0.6), 0.04);
        assert!((saunderson(1.0, 0.04, 0.6) - 1.0).abs() < 1e-15);
    }
}
