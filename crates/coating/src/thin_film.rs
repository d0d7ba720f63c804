//! Reflectance of a stack of thin films between two half-infinite media, for s and p
//! polarisation at any angle and wavelength: the coherent optics of interference pigments (a
//! mica platelet coated with TiO2, embedded in a binder) and of any other layered flake or film.
//!
//! Method: the Airy recursion (Born & Wolf, *Principles of Optics*, 7th ed., §1.6.4 for one film;
//! Heavens, *Optical Properties of Thin Solid Films*, 1955, §4.3 for its repetition layer by
//! layer). Media are numbered 0 (incidence medium, real index), 1..L (films), L + 1
//! (substrate). With complex indices `N = n + iκ` (κ ≥ 0 absorbing; time dependence e^{−iωt}) and
//! the conserved `n0 sin θ0`, each medium has `q_j = N_j cos θ_j = √(N_j² − n0² sin² θ0)`, the
//! root with Im q ≥ 0 (a wave that decays, or propagates forward, downwards). The interfaces'
//! amplitude reflection coefficients are
//! `r_s = (q_j − q_k)/(q_j + q_k)` and `r_p = (N_k² q_j − N_j² q_k)/(N_k² q_j + N_j² q_k)`,
//! a film's phase thickness `δ_j = 2π q_j d_j / λ`, and from the bottom up
//! `Γ_L = r_{L,L+1}`, `Γ_{j−1} = (r_{j−1,j} + Γ_j e^{2iδ_j}) / (1 + r_{j−1,j} Γ_j e^{2iδ_j})`;
//! the stack's reflectance is `|Γ_0|²`.

use crate::error::{CoatingError, Result};
use num_complex::Complex64;

/// Polarisation of the incident light relative to the plane of incidence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Polarisation {
    /// Electric field perpendicular to the plane of incidence (TE).
    S,
    /// Electric field in the plane of incidence (TM).
    P,
}

/// One film: its complex index `n + iκ` and its thickness in nm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Film {
    pub index: Complex64,
    pub thickness_nm: f64,
}

/// Films between an incidence medium of real index and a substrate.
#[derive(Clone, Debug, PartialEq)]
pub struct Stack {
    ambient: f64,
    films: Vec<Film>,
    substrate: Complex64,
}

impl Stack {
    /// The stack `ambient | films[0] | ... | substrate` (films from the top). Indices must have a
    /// positive real part and a non-negative imaginary part; the ambient medium is transparent;
    /// thicknesses are finite and non-negative.
    pub fn new(ambient: f64, films: Vec<Film>, substrate: Complex64) -> Result<Self> {
        let index_ok =
            |n: Complex64| n.re.is_finite() && n.im.is_finite() && n.re > 0.0 && n.im >= 0.0;
        if !(ambient.is_finite() && ambient > 0.0) {
            return Err(CoatingError::Invalid(format!(
                "incidence medium index {ambient}: must be a positive real number"
            )));
        }
        if !index_ok(substrate) {
            return Err(CoatingError::Invalid(format!(
                "substrate index {substrate}: needs n > 0 and κ ≥ 0"
            )));
        }
        for (i, f) in films.iter().enumerate() {
            if !index_ok(f.index) {
                return Err(CoatingError::Invalid(format!(
                    "film {}: index {} needs n > 0 and κ ≥ 0",
                    i + 1,
                    f.index
                )));
            }
            if !(f.thickness_nm.is_finite() && f.thickness_nm >= 0.0) {
                return Err(CoatingError::Invalid(format!(
                    "film {}: thickness {} nm must be finite and non-negative",
                    i + 1,
                    f.thickness_nm
                )));
            }
        }
        Ok(Self {
            ambient,
            films,
            substrate,
        })
    }

    /// The amplitude reflection coefficient for light arriving at `theta_rad` from the normal
    /// in the incidence medium, at vacuum wavelength `wavelength_nm`.
    pub fn amplitude(
        &self,
        polarisation: Polarisation,
        theta_rad: f64,
        wavelength_nm: f64,
    ) -> Complex64 {
        let beta = self.ambient * theta_rad.sin();
        let medium = |n: Complex64| {
            let mut q = (n * n - beta * beta).sqrt();
            if q.im < 0.0 || (q.im == 0.0 && q.re < 0.0) {
                q = -q;
            }
            (n, q)
        };
        let interface =
            |(nj, qj): (Complex64, Complex64), (nk, qk): (Complex64, Complex64)| match polarisation
            {
                Polarisation::S => (qj - qk) / (qj + qk),
                Polarisation::P => (nk * nk * qj - nj * nj * qk) / (nk * nk * qj + nj * nj * qk),
            };
        let media: Vec<(Complex64, Complex64)> = std::iter::once(Complex64::new(self.ambient, 0.0))
            .chain(self.films.iter().map(|f| f.index))
            .chain(std::iter::once(self.substrate))
            .map(medium)
            .collect();
        let last = media.len() - 1;
        let mut gamma = interface(media[last - 1], media[last]);
        for j in (1..last).rev() {
            let delta = 2.0 * std::f64::consts::PI * media[j].1 * self.films[j - 1].thickness_nm
                / wavelength_nm;
            let phase = (Complex64::i() * 2.0 * delta).exp();
            let r = interface(media[j - 1], media[j]);
            gamma = (r + gamma * phase) / (1.0 + r * gamma * phase);
        }
        gamma
    }

    /// The power reflectance `|r|²` for one polarisation.
    pub fn reflectance(
        &self,
        polarisation: Polarisation,
        theta_rad: f64,
        wavelength_nm: f64,
    ) -> f64 {
        self.amplitude(polarisation, theta_rad, wavelength_nm)
            .norm_sqr()
    }

    /// The reflectance of unpolarised light, `(Rs + Rp)/2`.
    pub fn reflectance_unpolarised(&self, theta_rad: f64, wavelength_nm: f64) -> f64 {
        0.5 * (self.reflectance(Polarisation::S, theta_rad, wavelength_nm)
            + self.reflectance(Polarisation::P, theta_rad, wavelength_nm))
    }
}

/// The ordinary refractive index of rutile TiO2 at `wavelength_nm`, by DeVore's Sellmeier fit
/// (J. R. DeVore, "Refractive indices of rutile and sphalerite", JOSA 41, 416 (1951)):
/// `n² = 5.913 + 0.2441 / (λ² − 0.0803)`, λ in µm, for 0.43–1.5 µm (2.81 at 450 nm, 2.61 at
/// 589 nm, 2.57 at 650 nm); below 430 nm it is extrapolated. Absorption (below about 410 nm) is not included.
pub fn rutile_ordinary(wavelength_nm: f64) -> f64 {
    let l2 = (wavelength_nm * 1e-3).powi(2);
    (5.913 + 0.2441 / (l2 - 0.0803)).sqrt()
}

/// An interference pigment's platelet in its binder: a mica core (`mica_nm` thick, index
/// `mica_index`, muscovite about 1.58) coated on both faces with rutile TiO2 (`tio2_nm` each,
/// [`rutile_ordinary`]), the binder (real index `binder_index`) above and below.
pub fn interference_flake(
    tio2_nm: f64,
    mica_nm: f64,
    mica_index: f64,
    binder_index: f64,
    wavelength_nm: f64,
) -> Result<Stack> {
    let tio2 = Film {
        index: Complex64::new(rutile_ordinary(wavelength_nm), 0.0),
        thickness_nm: tio2_nm,
    };
    let mica = Film {
        index: Complex64::new(mica_index, 0.0),
        thickness_nm: mica_nm,
    };
    Stack::new(
        binder_index,
        vec![tio2, mica, tio2],
        Complex64::new(binder_index, 0.0),
    )
}
