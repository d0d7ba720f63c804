//! Fresnel reflectance of a smooth interface seen from air: dielectrics of real index and
//! absorbing media (metals) of complex index `n + iκ`, for s and p polarisation and unpolarised.
//!
//! Formulas: Born & Wolf, *Principles of Optics*, §1.5.2 and §14.2: with `c = cos(iota)`, the
//! cosine of the local angle of incidence, and `ct = sqrt(1 - (1 - c²)/n²)`,
//! `rs = (c - n ct)/(c + n ct)`, `rp = (n c - ct)/(n c + ct)`, `R = (|rs|² + |rp|²)/2`.

use num_complex::Complex64;

/// Refractive index of the medium below the surface (the medium above is air, n = 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ior {
    /// A transparent dielectric of real index `n`.
    Dielectric(f64),
    /// An absorbing medium of complex index `n + iκ` (metals).
    Conductor(Complex64),
}

impl Ior {
    /// Unpolarised reflectance at local incidence `cos_i` (cosine of the angle between the ray
    /// and the facet normal, in [0, 1]).
    pub fn reflectance(&self, cos_i: f64) -> f64 {
        match *self {
            Ior::Dielectric(n) => dielectric(cos_i, n),
            Ior::Conductor(n) => polarised(cos_i, n).unpolarised(),
        }
    }

    /// Reflectance for s and p polarisation at local incidence `cos_i`.
    pub fn polarised(&self, cos_i: f64) -> Polarised {
        match *self {
            Ior::Dielectric(n) => polarised(cos_i, Complex64::new(n, 0.0)),
            Ior::Conductor(n) => polarised(cos_i, n),
        }
    }
}

/// Power reflectances for s (TE) and p (TM) polarisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Polarised {
    /// `|rs|²`
    pub s: f64,
    /// `|rp|²`
    pub p: f64,
}

impl Polarised {
    /// The reflectance of unpolarised light, `(Rs + Rp)/2`.
    pub fn unpolarised(&self) -> f64 {
        0.5 * (self.s + self.p)
    }
}

/// Unpolarised reflectance of a dielectric of real index `n` at local incidence `cos_i`.
/// For `n < 1` (light leaving a denser medium) total internal reflection gives 1.
pub fn dielectric(cos_i: f64, n: f64) -> f64 {
    let c = cos_i.clamp(0.0, 1.0);
    let st2 = (1.0 - c * c) / (n * n);
    if st2 >= 1.0 {
        return 1.0;
    }
    let ct = (1.0 - st2).sqrt();
    let rs = (c - n * ct) / (c + n * ct);
    let rp = (n * c - ct) / (n * c + ct);
    0.5 * (rs * rs + rp * rp)
}

/// s and p reflectances for a complex index `n` at local incidence `cos_i`.
pub fn polarised(cos_i: f64, n: Complex64) -> Polarised {
    let c = cos_i.clamp(0.0, 1.0);
    let s2 = Complex64::new(1.0 - c * c, 0.0);
    let ct = (Complex64::new(1.0, 0.0) - s2 / (n * n)).sqrt();
    let rs = (c - n * ct) / (c + n * ct);
    let rp = (n * c - ct) / (n * c + ct);
    Polarised {
        s: rs.norm_sqr(),
        p: rp.norm_sqr(),
    }
}
