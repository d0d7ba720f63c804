//! A smooth clear coat over a diffuse base (a solid colour, or a Kubelka-Munk pigmented layer
//! over a substrate), with every internal reflection counted: the body reflection of a glossy
//! solid-colour finish, spectral, as a BRDF and as a table.
//!
//! The model (`docs/coatings.md`, "Clear coat over a diffuse base"). Light arriving at θi from
//! the normal is reflected at the smooth air–coat interface with the Fresnel reflectance
//! `F(θi)` (the mirror reflection, a delta, kept apart from the table) and refracted into the
//! coat at θi' (`sin θi = n sin θi'`). Crossing the coat of thickness d absorbs by
//! Beer-Lambert, `A(θ') = exp(−σ d / cos θ')`. The base reflects diffusely (Lambertian) with
//! reflectance ρ; the upward light leaves through the interface with transmittance
//! `1 − F(θo)` and radiance divided by n², or is reflected back down with the interface's
//! internal reflectance `Fi(θ')` (total beyond the critical angle). Because the base forgets
//! directions, the series of passes sums exactly:
//!
//! `f(wi, wo) = (1 − F(θi)) (1 − F(θo)) A(θi') A(θo') ρ / (π n² (1 − ρ r̄))`,
//! `r̄ = ∫ Fi(θ') A(θ')² 2 cos θ' sin θ' dθ'` over the internal hemisphere,
//!
//! (for A = 1, the result used by Kelemen & Szirmay-Kalos 2001 and by Weidlich & Wilkie 2007 for
//! a Lambertian under a smooth dielectric; its directional-hemispherical reflectance is
//! `F(θi) + (1 − F(θi)) ρ (1 − F̄)/(1 − ρ F̄)` with F̄ the internal hemispherical Fresnel average).
//! `r̄` is computed by Gauss-Legendre quadrature split at the critical angle (see
//! `internal_return`). The formula is reciprocal by construction.
//!
//! Not modelled: scattering inside the coat, a rough top interface (the ray method will give
//! it), interference in a thin coat (coats are tens of micrometres: incoherent), the base's own
//! surface reflection (the base is taken index-matched to the coat's binder).

use crate::error::{CoatingError, Result};
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::quadrature::gauss_legendre_on;
use gonio_brdf::table::{BrdfTable, Channels, Provenance, Resolution, TableBuilder};
use gonio_color::Spectrum;
use std::f64::consts::PI;

/// The coat's refractive index as a function of wavelength.
#[derive(Clone, Debug, PartialEq)]
pub enum Dispersion {
    /// The same index at every wavelength.
    Constant(f64),
    /// Cauchy's formula `n = a + b / λ²`, λ in µm (e.g. a = 1.48, b = 0.0045 µm² for an acrylic
    /// clear coat: 1.508 at 400 nm, 1.489 at 700 nm).
    Cauchy { a: f64, b_um2: f64 },
    /// Sellmeier's formula `n² = 1 + Σ Bᵢ λ² / (λ² − Cᵢ)`, three terms, λ in µm (W. Sellmeier,
    /// Ann. Phys. Chem. 219, 272 (1871), in the form of glass makers' catalogues; e.g. Schott
    /// N-BK7: B = 1.03961212, 0.231792344, 1.01046945; C = 0.00600069867, 0.0200179144,
    /// 103.560653 µm², n = 1.5168 at 587.6 nm). The formula holds between the resonances Cᵢ;
    /// where it gives n² ≤ 0 (just above a resonance) it has no real index, and the coating's
    /// check refuses the wavelength.
    Sellmeier { b: [f64; 3], c_um2: [f64; 3] },
    /// A measured index, linear between its samples (the end value outside them).
    Measured(Spectrum),
}

impl Dispersion {
    /// The index at `wavelength_nm`.
    pub fn at(&self, wavelength_nm: f64) -> f64 {
        match self {
            Dispersion::Constant(n) => *n,
            Dispersion::Cauchy { a, b_um2 } => a + b_um2 / (wavelength_nm * 1e-3).powi(2),
            Dispersion::Sellmeier { b, c_um2 } => {
                let l2 = (wavelength_nm * 1e-3).powi(2);
                let terms: f64 = b.iter().zip(c_um2).map(|(b, c)| b * l2 / (l2 - c)).sum();
                let n2 = 1.0 + terms;
                if n2.is_finite() && n2 > 0.0 {
                    n2.sqrt()
                } else {
                    f64::NAN
                }
            }
            Dispersion::Measured(n) => n.value_at(wavelength_nm),
        }
    }
}

/// The clear coat: index, thickness and absorption.
#[derive(Clone, Debug, PartialEq)]
pub struct Coat {
    pub index: Dispersion,
    pub thickness_um: f64,
    /// Absorption coefficient σ(λ), 1/µm (a constant 0 for a clear coat).
    pub absorption_per_um: Spectrum,
}

/// One pigment of a Kubelka-Munk layer: its concentration and its K and S spectra per unit
/// concentration, 1/µm.
#[derive(Clone, Debug, PartialEq)]
pub struct Pigment {
    pub name: String,
    pub concentration: f64,
    pub k_per_um: Spectrum,
    pub s_per_um: Spectrum,
}

/// What lies under the coat.
#[derive(Clone, Debug, PartialEq)]
pub enum Base {
    /// A diffuse (Lambertian) surface of this reflectance spectrum.
    Diffuse { reflectance: Spectrum },
    /// A pigmented layer (Kubelka-Munk, linear mixing of the pigments) of this thickness over a
    /// diffuse substrate.
    KubelkaMunk {
        pigments: Vec<Pigment>,
        thickness_um: f64,
        substrate: Spectrum,
    },
}

impl Base {
    /// The base's diffuse reflectance at `wavelength_nm`, seen from inside the coat.
    pub fn reflectance(&self, wavelength_nm: f64) -> Result<f64> {
        match self {
            Base::Diffuse { reflectance } => Ok(reflectance.value_at(wavelength_nm)),
            Base::KubelkaMunk {
                pigments,
                thickness_um,
                substrate,
            } => Ok(crate::basecoat::mixture_at(pigments, wavelength_nm)?
                .reflectance(*thickness_um, substrate.value_at(wavelength_nm))),
        }
    }
}

/// A smooth clear coat over a diffuse base.
#[derive(Clone, Debug, PartialEq)]
pub struct ClearCoatOverBase {
    pub coat: Coat,
    pub base: Base,
}

/// The optics of the stack at one wavelength: what the BRDF needs, computed once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AtWavelength {
    /// Coat index n.
    pub n: f64,
    /// σ d, the coat's optical thickness at normal incidence.
    pub tau: f64,
    /// Base reflectance ρ.
    pub rho: f64,
    /// r̄: the fraction of the base's diffuse light the interface sends back to the base.
    pub r_bar: f64,
}

impl ClearCoatOverBase {
    /// Check the description: a coat index above 1, a finite non-negative thickness,
    /// absorption and base reflectances that a material can have, at `wavelengths_nm`.
    pub fn check(&self, wavelengths_nm: &[f64]) -> Result<()> {
        let t = self.coat.thickness_um;
        if !(t.is_finite() && t >= 0.0) {
            return Err(CoatingError::Invalid(format!(
                "coat thickness {t} µm: must be finite and non-negative"
            )));
        }
        for &w in wavelengths_nm {
            let o = self.at(w)?;
            if o.n.is_nan() {
                return Err(CoatingError::Invalid(format!(
                    "coat index at {w} nm: the Sellmeier formula gives no real index there \
                     (n² ≤ 0: the wavelength is just above one of its resonances C)"
                )));
            }
            if !(o.n.is_finite() && o.n > 1.0) {
                return Err(CoatingError::Invalid(format!(
                    "coat index {} at {w} nm: must be above 1",
                    o.n
                )));
            }
            if !(o.tau.is_finite() && o.tau >= 0.0) {
                return Err(CoatingError::Invalid(format!(
                    "coat absorption at {w} nm: must be finite and non-negative"
                )));
            }
            if !(0.0..=1.0).contains(&o.rho) {
                return Err(CoatingError::Invalid(format!(
                    "base reflectance {} at {w} nm: must be between 0 and 1",
                    o.rho
                )));
            }
        }
        Ok(())
    }

    /// The stack's optics at `wavelength_nm`.
    pub fn at(&self, wavelength_nm: f64) -> Result<AtWavelength> {
        let n = self.coat.index.at(wavelength_nm);
        let tau = self.coat.absorption_per_um.value_at(wavelength_nm) * self.coat.thickness_um;
        let rho = self.base.reflectance(wavelength_nm)?;
        Ok(AtWavelength {
            n,
            tau,
            rho,
            r_bar: internal_return(n, tau),
        })
    }
}

/// The provenance of a body table made from the description at `source`: its method and what
/// the table leaves out.
pub fn body_provenance(source: impl Into<String>) -> Provenance {
    let mut provenance = Provenance::new(source, "coating:clear-coat-over-base");
    provenance.description = Some(
        "body reflection of a smooth clear coat over a diffuse base; the coat's mirror \
         reflection F(θi) is not in the table"
            .into(),
    );
    provenance
}

impl ClearCoatOverBase {
    /// The body reflection tabulated at `resolution` with one channel per wavelength of
    /// `wavelengths_nm` (a spectral table), stamped with `provenance`. The mirror reflection of
    /// the top interface, a delta, is not in the table ([`AtWavelength::specular`]).
    pub fn body_table(
        &self,
        resolution: Resolution,
        wavelengths_nm: &[f64],
        provenance: Provenance,
    ) -> Result<BrdfTable> {
        self.check(wavelengths_nm)?;
        let optics = wavelengths_nm
            .iter()
            .map(|&w| self.at(w))
            .collect::<Result<Vec<_>>>()?;
        let channels = Channels::Spectral {
            wavelengths_nm: wavelengths_nm.to_vec(),
        };
        let table_error = |e: gonio_brdf::BrdfError| CoatingError::Invalid(e.to_string());
        let mut builder = TableBuilder::new(resolution, channels)
            .map_err(table_error)?
            .with_provenance(provenance);
        builder.fill(|cell, out| {
            for (o, at) in out.iter_mut().zip(&optics) {
                *o = at.brdf(cell.wi.z, cell.wo.z);
            }
        });
        builder.build().map_err(table_error)
    }
}

impl AtWavelength {
    /// The mirror reflection of the top interface, `F(θi)`, for `cos_i` the cosine of the angle
    /// of incidence (a delta at the specular direction; not part of [`AtWavelength::brdf`]).
    pub fn specular(&self, cos_i: f64) -> f64 {
        dielectric(cos_i, self.n)
    }

    /// The body reflection's directional-hemispherical reflectance for light arriving at
    /// `cos_i`: `2π ∫ f μo dμo` (64-point Gauss-Legendre; the integrand is smooth in μo). The
    /// stack's whole reflectance adds [`AtWavelength::specular`].
    pub fn body_albedo(&self, cos_i: f64) -> f64 {
        gauss_legendre_on(64, 0.0, 1.0)
            .into_iter()
            .map(|(mu, w)| w * self.brdf(cos_i, mu) * mu)
            .sum::<f64>()
            * 2.0
            * PI
    }

    /// The body reflection's BRDF in 1/sr for light arriving at `cos_i` and leaving at `cos_o`
    /// (cosines from the normal; the body reflection does not depend on azimuth).
    pub fn brdf(&self, cos_i: f64, cos_o: f64) -> f64 {
        if cos_i <= 0.0 || cos_o <= 0.0 {
            return 0.0;
        }
        let n2 = self.n * self.n;
        let pass = |c: f64| {
            let inside = (1.0 - (1.0 - c * c) / n2).sqrt();
            (1.0 - dielectric(c, self.n)) * (-self.tau / inside).exp()
        };
        pass(cos_i) * pass(cos_o) * self.rho / (PI * n2 * (1.0 - self.rho * self.r_bar))
    }
}

/// r̄ = ∫ Fi(θ') exp(−2τ/cos θ') 2 cos θ' sin θ' dθ' over the internal hemisphere: in
/// μ = cos θ', `∫_0^1 Fi(μ) e^{−2τ/μ} 2μ dμ`, with Fi = 1 below the critical μc = √(1 − 1/n²).
/// Above μc, Fi falls from 1 like `√(μ − μc)`; the substitution `μ = μc + (1 − μc) s²` makes the
/// integrand smooth in s, and 64-point Gauss-Legendre rules on [0, μc] and in s on [0, 1] then
/// agree with a 200 000-step midpoint rule to 1e-9.
fn internal_return(n: f64, tau: f64) -> f64 {
    let mu_c = (1.0 - 1.0 / (n * n)).sqrt();
    let absorbed = |mu: f64| {
        if tau == 0.0 {
            1.0
        } else {
            (-2.0 * tau / mu).exp()
        }
    };
    let total: f64 = gauss_legendre_on(64, 0.0, mu_c)
        .into_iter()
        .map(|(mu, w)| w * absorbed(mu) * 2.0 * mu)
        .sum();
    let partial: f64 = gauss_legendre_on(64, 0.0, 1.0)
        .into_iter()
        .map(|(s, w)| {
            let mu = mu_c + (1.0 - mu_c) * s * s;
            let jacobian = 2.0 * (1.0 - mu_c) * s;
            w * jacobian * dielectric(mu, 1.0 / n) * absorbed(mu) * 2.0 * mu
        })
        .sum();
    total + partial
}
