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
    k1 + saunderson_specular_excluded(r, k1, k2)
}

/// Saunderson's correction as an instrument that excludes the specular reflection reads it
/// (45°/0° geometry, or a sphere with its specular port open): the surface's own reflection k1
/// is not collected, `(1 − k1)(1 − k2) R / (1 − k2 R)`, only the light that entered the layer
/// and came back out. The form the Unicolour library applies to the RIT artist-paint data
/// (`Pigment.CorrectR`, "assumes data measured in SPEX mode").
pub fn saunderson_specular_excluded(r: f64, k1: f64, k2: f64) -> f64 {
    (1.0 - k1) * (1.0 - k2) * r / (1.0 - k2 * r)
}

/// The inverse of [`saunderson`]: the internal reflectance behind a measured reflectance `rm`.
pub fn inverse_saunderson(rm: f64, k1: f64, k2: f64) -> f64 {
    (rm - k1) / ((1.0 - k1) * (1.0 - k2) + k2 * (rm - k1))
}
