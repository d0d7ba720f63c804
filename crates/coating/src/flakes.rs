//! Effect flakes at the bottom of the coat, over the base that shows between them: aluminium
//! (metallic) or TiO2-coated mica (interference, pearlescent) platelets lying nearly parallel
//! to the surface, with a distribution of tilts, seen from inside the coat.
//!
//! The flake layer (`docs/coatings.md`, "Flakes"). A fraction c (the coverage) of the base's area
//! is covered by flakes; their normals follow a Beckmann (Gaussian-slope) distribution of rms
//! slope `tan σ` about the coating's normal (σ the rms tilt). Light meeting a flake is reflected
//! specularly about the flake's normal with the flake's reflectance R at the local angle
//! (Fresnel's equations for a metal of complex index relative to the binder; the thin-film
//! reflectance of [`crate::thin_film::interference_flake`] for a pearlescent flake), and an
//! interference flake transmits the rest, `T = 1 − R` (its films do not absorb), undeviated (a
//! thin parallel platelet). Light from a direction w meets the flakes of normal h in
//! proportion to their projected area `D(h) max(0, w·h)`, in all `N(w)` (cos θ while every
//! flake faces w); as for a microfacet surface with Smith's shadowing and masking
//! `G1(w) = cos θ / N(w)` (flakes hiding each other at grazing angles), their reflection is
//! `c R(wo·h) D(h) / (4 N(wi) N(wo))`: reciprocal, and from wi it returns
//! `c R̃(wi)` (R̃ the flakes' reflectance averaged over those wi meets) less what grazing
//! outgoing directions lose to masking and what the flakes send below the horizon (for a tilt
//! spread of 12°, under 1% of it within 40° of the normal; the furnace test measures it).
//!
//! Between and through the flakes light reaches the base (a Lambertian of reflectance ρ): from a
//! direction w the fraction `a(w) = 1 − c + c T̃(w)` gets through, T̃ the flakes' transmittance
//! averaged over the flakes w meets (`T̃(w) = ∫ T(w·h) D(h) max(0, w·h) dω_h / N(w)`, so that
//! `R̃ + T̃ = 1` for lossless flakes). The base's diffuse light going up meets the
//! flakes' undersides, which send the fraction `c R̄` (R̄ the tilt-averaged reflectance over a
//! diffuse field) back down to the base; because the base forgets directions, those passes sum
//! exactly, and the diffuse part of the layer's BRDF is
//!
//! `f_d(wi, wo) = a(wi) a(wo) ρ / (π (1 − ρ c R̄))`.
//!
//! Not modelled: flakes shadowing each other and overlapping in depth (one layer of flakes),
//! flakes at different depths in the coat, the edges of the flakes (diffraction and their
//! sparkle), the flakes' own roughness.

use crate::basecoat::FlakeDepth;
use crate::error::{CoatingError, Result};
use crate::thin_film::interference_flake;
use glam::{DVec2, DVec3};
use gonio_brdf::fresnel::polarised;
use gonio_brdf::microfacet::Microfacet;
use gonio_brdf::quadrature::gauss_legendre_on;
use gonio_color::Spectrum;
use num_complex::Complex64;
use std::f64::consts::PI;

/// What the flakes are made of.
#[derive(Clone, Debug, PartialEq)]
pub enum FlakePigment {
    /// Metal platelets of complex index `n + iκ` (spectra; aluminium for a silver metallic).
    Metal { n: Spectrum, k: Spectrum },
    /// Mica platelets coated on both faces with rutile TiO2 (an interference pigment).
    Interference {
        tio2_nm: f64,
        mica_nm: f64,
        mica_index: f64,
    },
}

/// A layer of flakes: their pigment, the fraction of the base they cover, their rms tilt and
/// their size.
#[derive(Clone, Debug, PartialEq)]
pub struct Flakes {
    pub pigment: FlakePigment,
    /// Fraction of the base's area covered by flakes, 0 to 1.
    pub coverage: f64,
    /// rms tilt of the flakes' normals from the coating's normal, degrees.
    pub tilt_deg: f64,
    /// Mean diameter of the flakes, µm: the diameter of the circle of a flake's mean area
    /// ([`Flakes::DEFAULT_DIAMETER_UM`] unless given). The smooth BRDF does not depend on it;
    /// the renderer's discrete flakes (sparkle) do.
    pub diameter_um: f64,
    /// Where the flakes lie in a Kubelka-Munk basecoat ([`crate::basecoat`]); `None`: at the
    /// bottom of the clear coat, over the base (the flake layer of this module).
    pub depth: Option<FlakeDepth>,
}

/// Aluminium's complex index at visible wavelengths: H.-J. Hagemann, W. Gudat & C. Kunz,
/// "Optical constants from the far infrared to the x-ray region: Mg, Al, Cu, Ag, Au, Bi, C, and
/// Al2O3", DESY report SR-74/7 (1974), table 3 (photon energies converted with
/// λ = 1239.84 nm eV / E). Returns `(n, κ)` as spectra.
pub fn aluminium() -> (Spectrum, Spectrum) {
    let nm = vec![310.0, 413.3, 495.9, 619.9, 688.8, 729.3, 774.9];
    let n = vec![0.298, 0.548, 0.771, 1.292, 1.731, 2.082, 2.588];
    let k = vec![3.70, 5.00, 5.91, 7.28, 7.96, 8.34, 8.55];
    (
        Spectrum::new(nm.clone(), n).expect("aluminium n table is valid"),
        Spectrum::new(nm, k).expect("aluminium κ table is valid"),
    )
}

impl Flakes {
    /// The flakes' mean diameter unless the description gives one, µm: aluminium effect
    /// pigments for automotive finishes have median diameters of roughly 10 to 35 µm, the fine
    /// "silky" grades at the low end and the coarse sparkling ones at the high end (P. Wißling,
    /// *Metallic Effect Pigments*, Vincentz 2006, ch. 2; G. Pfaff, *Special Effect Pigments*,
    /// 2nd ed., Vincentz 2008, ch. 2); 20 µm is a middle grade.
    pub const DEFAULT_DIAMETER_UM: f64 = 20.0;

    /// Check the coverage (0 to 1), the tilt (0 to 45°), the diameter (1 µm to 1 m) and the
    /// pigment's constants.
    pub fn check(&self) -> Result<()> {
        if !(1.0..=1e6).contains(&self.diameter_um) {
            return Err(CoatingError::Invalid(format!(
                "flake diameter {} µm: must be between 1 µm and 1 m (effect pigments are \
                 about 10–35 µm across)",
                self.diameter_um
            )));
        }
        if !(0.0..=1.0).contains(&self.coverage) {
            return Err(CoatingError::Invalid(format!(
                "flake coverage {}: must be between 0 and 1",
                self.coverage
            )));
        }
        if !(self.tilt_deg > 0.0 && self.tilt_deg <= 45.0) {
            return Err(CoatingError::Invalid(format!(
                "flake tilt {}°: must be above 0 and at most 45 (the rms tilt of the flakes' \
                 normals; 5–25° is usual)",
                self.tilt_deg
            )));
        }
        if let Some(depth) = self.depth {
            depth.check(self.coverage)?;
        }
        if let FlakePigment::Interference {
            tio2_nm,
            mica_nm,
            mica_index,
        } = self.pigment
        {
            if !(tio2_nm >= 0.0 && mica_nm >= 0.0 && tio2_nm.is_finite() && mica_nm.is_finite()) {
                return Err(CoatingError::Invalid(format!(
                    "interference flake: TiO2 {tio2_nm} nm and mica {mica_nm} nm must be finite \
                     and non-negative"
                )));
            }
            if !(mica_index.is_finite() && mica_index > 1.0) {
                return Err(CoatingError::Invalid(format!(
                    "interference flake: mica index {mica_index} must be above 1"
                )));
            }
        }
        Ok(())
    }

    /// The distribution of the flakes' normals: Beckmann, rms slope `tan σ`.
    pub fn orientation(&self) -> Microfacet {
        Microfacet::beckmann(self.tilt_deg.to_radians().tan())
    }

    /// The flake's reflectance and transmittance at `wavelength_nm` in a binder of index
    /// `binder`, tabulated against the cosine of the local angle.
    pub fn optics(&self, binder: f64, wavelength_nm: f64) -> Result<FlakeOptics> {
        let mu = |i: usize| i as f64 / (FlakeOptics::STEPS - 1) as f64;
        let (r, t): (Vec<f64>, Vec<f64>) = match &self.pigment {
            FlakePigment::Metal { n, k } => {
                let index =
                    Complex64::new(n.value_at(wavelength_nm), k.value_at(wavelength_nm)) / binder;
                if !(index.re > 0.0 && index.im >= 0.0) {
                    return Err(CoatingError::Invalid(format!(
                        "flake metal index {index} at {wavelength_nm} nm: needs n > 0 and κ ≥ 0"
                    )));
                }
                (0..FlakeOptics::STEPS)
                    .map(|i| (polarised(mu(i), index).unpolarised(), 0.0))
                    .unzip()
            }
            FlakePigment::Interference {
                tio2_nm,
                mica_nm,
                mica_index,
            } => {
                let stack =
                    interference_flake(*tio2_nm, *mica_nm, *mica_index, binder, wavelength_nm)?;
                (0..FlakeOptics::STEPS)
                    .map(|i| {
                        let r = stack.reflectance_unpolarised(mu(i).acos(), wavelength_nm);
                        (r, 1.0 - r)
                    })
                    .unzip()
            }
        };
        Ok(FlakeOptics::new(r, t, &Tilts::new(self.orientation())))
    }
}

/// The flakes' normals as a direction meets them: stratified samples of the tilt distribution
/// `D(h) cos θh` (32 × 32), from which the averages over what a direction of cosine μ sees are
/// tabulated on 65 equal steps of μ. A direction w meets the flakes of normal h in proportion to
/// their projected area `D(h) max(0, w·h)`, in all `N(w) = ∫ D(h) max(0, w·h) dω_h`, which is
/// cos θ while every flake faces w and more at grazing angles, where flakes face w more
/// squarely than the coating does.
#[derive(Clone, Debug)]
struct Tilts {
    normals: Vec<DVec3>,
}

impl Tilts {
    const STRATA: usize = 32;
    const STEPS: usize = 65;

    fn new(orientation: Microfacet) -> Self {
        let n = Self::STRATA;
        let normals = (0..n * n)
            .map(|k| {
                let u = DVec2::new(
                    ((k / n) as f64 + 0.5) / n as f64,
                    ((k % n) as f64 + 0.5) / n as f64,
                );
                orientation.sample_d(u)
            })
            .collect();
        Tilts { normals }
    }

    /// The cosine of table step `i` (kept off 0, where nothing is seen).
    fn mu(i: usize) -> f64 {
        (i as f64 / (Self::STEPS - 1) as f64).max(1e-3)
    }

    /// The direction of cosine `mu` in the xz plane (the distribution is isotropic).
    fn direction(mu: f64) -> DVec3 {
        DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu)
    }

    /// `N(w)` for the direction of cosine `mu`.
    fn projected_area(&self, mu: f64) -> f64 {
        let w = Self::direction(mu);
        self.normals
            .iter()
            .map(|h| w.dot(*h).max(0.0) / h.z)
            .sum::<f64>()
            / self.normals.len() as f64
    }

    /// The mean of `g(w·h)` over the flakes a direction of cosine `mu` meets, weighted by their
    /// projected area.
    fn average(&self, mu: f64, g: impl Fn(f64) -> f64) -> f64 {
        let w = Self::direction(mu);
        let (mut sum, mut area) = (0.0, 0.0);
        for h in &self.normals {
            let c = w.dot(*h);
            if c > 0.0 {
                sum += c / h.z * g(c);
                area += c / h.z;
            }
        }
        sum / area
    }
}

/// Where `mu` falls on a table of `len` equal steps of μ from 0 to 1: the step below it and
/// the weight of the one above (linear interpolation).
fn step(len: usize, mu: f64) -> (usize, f64) {
    let last = len - 1;
    let x = mu.clamp(0.0, 1.0) * last as f64;
    let i = (x as usize).min(last - 1);
    (i, x - i as f64)
}

/// The rows of a table of `nb` bands side by side (one row per step of μ) on either side of
/// `mu`, and the weight of the upper one.
fn row(rows: &[f64], nb: usize, mu: f64) -> (&[f64], &[f64], f64) {
    let (i, t) = step(rows.len() / nb, mu);
    (
        &rows[i * nb..(i + 1) * nb],
        &rows[(i + 1) * nb..(i + 2) * nb],
        t,
    )
}

/// A flake's reflectance R and transmittance T against the cosine μ of the local angle, on
/// `STEPS` equal steps of μ (linear interpolation: the curves are smooth in μ, and the
/// tabulation agrees with the direct formulas to 1e-4 from μ = 0.05, tested), and the same
/// averaged over the flakes' tilts as seen from a direction of cosine μ to the coating's normal.
#[derive(Clone, Debug, PartialEq)]
pub struct FlakeOptics {
    r: Vec<f64>,
    t: Vec<f64>,
    r_tilted: Vec<f64>,
    t_tilted: Vec<f64>,
}

impl FlakeOptics {
    const STEPS: usize = 1025;

    fn lookup(table: &[f64], mu: f64) -> f64 {
        let (i, t) = step(table.len(), mu);
        table[i] + t * (table[i + 1] - table[i])
    }

    /// The tables from R and T against μ, with their averages over the flakes a direction
    /// meets ([`Tilts::average`]).
    fn new(r: Vec<f64>, t: Vec<f64>, tilts: &Tilts) -> Self {
        let mut optics = FlakeOptics {
            r,
            t,
            r_tilted: Vec::new(),
            t_tilted: Vec::new(),
        };
        let (r_tilted, t_tilted) = (0..Tilts::STEPS)
            .map(|i| {
                let mu = Tilts::mu(i);
                (
                    tilts.average(mu, |c| optics.reflectance(c)),
                    tilts.average(mu, |c| optics.transmittance(c)),
                )
            })
            .unzip();
        optics.r_tilted = r_tilted;
        optics.t_tilted = t_tilted;
        optics
    }

    /// R at local cosine `mu`.
    pub fn reflectance(&self, mu: f64) -> f64 {
        Self::lookup(&self.r, mu)
    }

    /// T at local cosine `mu`.
    pub fn transmittance(&self, mu: f64) -> f64 {
        Self::lookup(&self.t, mu)
    }

    /// The flakes' transmittance from a direction of cosine `mu` to the coating's normal,
    /// averaged over their tilts.
    pub fn tilted_transmittance(&self, mu: f64) -> f64 {
        Self::lookup(&self.t_tilted, mu)
    }

    /// R̄ = ∫ R̃(μ) 2μ dμ: the tilt-averaged reflectance for a diffuse field.
    pub fn diffuse_reflectance(&self) -> f64 {
        gauss_legendre_on(64, 0.0, 1.0)
            .into_iter()
            .map(|(mu, w)| w * Self::lookup(&self.r_tilted, mu) * 2.0 * mu)
            .sum()
    }
}

/// The flake layer over its base as one reflector seen from inside the coat, for a set of
/// wavelength bands at once (the bands of one [`crate::layered`] walk): its BRDF, and sampling.
#[derive(Clone, Debug)]
pub struct FlakeLayer {
    coverage: f64,
    orientation: Option<Microfacet>,
    /// `N(μ)` on [`Tilts::STEPS`] equal steps of μ.
    projected: Vec<f64>,
    /// [`FlakeLayer::share_at`] on the same steps.
    share: Vec<f64>,
    optics: Vec<FlakeOptics>,
    rho: Vec<f64>,
    /// `ρ / (π (1 − ρ c R̄))` per band.
    diffuse: Vec<f64>,
    /// The flake's R at each step of the local cosine, the bands side by side (one row per
    /// step), and `a(w) = 1 − c + c T̃(w)` at each step of cos θ: the tables of `optics`
    /// arranged so that [`FlakeLayer::f`] finds every band's values at one place (the
    /// evaluation of the layer, band by band through `optics`, was half of a table's time).
    reflectance_rows: Vec<f64>,
    through_rows: Vec<f64>,
    /// Whether the walks over this layer leave out the flakes' glint (light that meets the
    /// layer once and is mirrored by a flake: [`crate::glint`]), for a renderer that draws it
    /// flake by flake ([`FlakeLayer::without_glint`]).
    glint_left_out: bool,
}

impl FlakeLayer {
    /// A Lambertian base of reflectance `rho` (per band), bare.
    pub fn bare(rho: Vec<f64>) -> Self {
        let diffuse = rho.iter().map(|r| r / PI).collect();
        FlakeLayer {
            coverage: 0.0,
            orientation: None,
            projected: Vec::new(),
            share: Vec::new(),
            optics: Vec::new(),
            rho,
            diffuse,
            reflectance_rows: Vec::new(),
            through_rows: Vec::new(),
            glint_left_out: false,
        }
    }

    /// `flakes` (their optics per band) over a Lambertian base of reflectance `rho` per band.
    pub fn new(flakes: &Flakes, optics: Vec<FlakeOptics>, rho: Vec<f64>) -> Self {
        let c = flakes.coverage;
        let diffuse = rho
            .iter()
            .zip(&optics)
            .map(|(r, o)| r / (PI * (1.0 - r * c * o.diffuse_reflectance())))
            .collect();
        let tilts = Tilts::new(flakes.orientation());
        let rows = |steps: usize, value: &dyn Fn(&FlakeOptics, usize) -> f64| -> Vec<f64> {
            (0..steps)
                .flat_map(|i| optics.iter().map(move |o| value(o, i)))
                .collect()
        };
        let reflectance_rows = rows(FlakeOptics::STEPS, &|o, i| o.r[i]);
        let through_rows = rows(Tilts::STEPS, &|o, i| 1.0 - c + c * o.t_tilted[i]);
        let mut layer = FlakeLayer {
            reflectance_rows,
            through_rows,
            coverage: c,
            orientation: Some(flakes.orientation()),
            share: Vec::new(),
            projected: (0..Tilts::STEPS)
                .map(|i| tilts.projected_area(Tilts::mu(i)))
                .collect(),
            optics,
            rho,
            diffuse,
            glint_left_out: false,
        };
        layer.share = (0..Tilts::STEPS)
            .map(|i| layer.share_at(Tilts::mu(i)))
            .collect();
        layer
    }

    /// The number of bands.
    pub fn bands(&self) -> usize {
        self.rho.len()
    }

    /// The fraction getting through the flakes from direction `w`, band `b`: `a(w)`, the mean
    /// over the layer's points of 1 between flakes and the flake's transmittance on them.
    pub fn through(&self, b: usize, w: DVec3) -> f64 {
        if self.orientation.is_none() {
            return 1.0;
        }
        let nb = self.bands();
        let (i, t) = step(Tilts::STEPS, w.z);
        let (lo, hi) = (
            self.through_rows[i * nb + b],
            self.through_rows[(i + 1) * nb + b],
        );
        lo + t * (hi - lo)
    }

    /// The probability of sampling the flakes' lobe rather than the diffuse one from `wo`
    /// ([`FlakeLayer::share_at`] tabulated against cos θo at construction).
    fn flake_share(&self, wo: DVec3) -> f64 {
        if self.orientation.is_none() {
            return 0.0;
        }
        FlakeOptics::lookup(&self.share, wo.z)
    }

    /// The flakes' and the diffuse lobe's shares of the reflected energy from a direction of
    /// cosine `mu`, averaged over the bands, as the probability of sampling the flakes (kept
    /// within 5–95% while both lobes reflect, so that neither goes unsampled).
    fn share_at(&self, mu: f64) -> f64 {
        let w = Tilts::direction(mu);
        let bands = self.bands() as f64;
        let flakes =
            self.coverage * self.optics.iter().map(|o| o.reflectance(mu)).sum::<f64>() / bands;
        let diffuse = (0..self.bands())
            .map(|b| self.through(b, w) * self.diffuse[b] * PI)
            .sum::<f64>()
            / bands;
        if flakes <= 0.0 {
            return 0.0;
        }
        if diffuse <= 0.0 {
            return 1.0;
        }
        (flakes / (flakes + diffuse)).clamp(0.05, 0.95)
    }

    /// The BRDF for light from `wi` to `wo` (both above the layer) into `out`, one per band.
    pub fn f(&self, wo: DVec3, wi: DVec3, out: &mut [f64]) {
        self.f_and_pdfs(wo, wi, out);
    }

    /// [`FlakeLayer::f`], and the pdfs of [`FlakeLayer::sample`] from `wo` choosing `wi` and
    /// from `wi` choosing `wo`: the walk's connections need all three, which share the half
    /// vector and the flakes' distribution there.
    pub fn f_and_pdfs(&self, wo: DVec3, wi: DVec3, out: &mut [f64]) -> (f64, f64) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            out.fill(0.0);
            return (0.0, 0.0);
        }
        let Some(m) = self.orientation else {
            out.copy_from_slice(&self.diffuse);
            return (wi.z / PI, wo.z / PI);
        };
        let h = (wo + wi).normalize();
        let d = m.d(h);
        let (share_o, share_i) = (self.flake_share(wo), self.flake_share(wi));
        // Sampling a normal by D(h) cos θh and reflecting about it: the density of the
        // direction is D(h) cos θh / (4 w·h), the same either way (w·h is the same for both).
        let lobe_pdf = d * h.z / (4.0 * wo.dot(h));
        let pdfs = (
            (1.0 - share_o) * wi.z / PI + share_o * lobe_pdf,
            (1.0 - share_i) * wo.z / PI + share_i * lobe_pdf,
        );
        let area = |w: DVec3| FlakeOptics::lookup(&self.projected, w.z);
        let lobe = self.coverage * d / (4.0 * area(wo) * area(wi));
        let nb = self.bands();
        let (i0, i1, ti) = row(&self.through_rows, nb, wi.z);
        let (o0, o1, to) = row(&self.through_rows, nb, wo.z);
        for b in 0..nb {
            let through_i = i0[b] + ti * (i1[b] - i0[b]);
            let through_o = o0[b] + to * (o1[b] - o0[b]);
            out[b] = through_i * through_o * self.diffuse[b];
        }
        if lobe > 0.0 {
            self.add_reflectance(wo.dot(h), lobe, out);
        }
        pdfs
    }

    /// The flakes' lobe of [`FlakeLayer::f`] alone, `c R(wo·h) D(h) / (4 N(wi) N(wo))` per
    /// band into `out` (0 for a bare base): the light that one flake mirrors, without the base.
    pub fn lobe(&self, wo: DVec3, wi: DVec3, out: &mut [f64]) {
        out.fill(0.0);
        let Some(m) = self.orientation else { return };
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return;
        }
        let h = (wo + wi).normalize();
        let area = |w: DVec3| FlakeOptics::lookup(&self.projected, w.z);
        let lobe = self.coverage * m.d(h) / (4.0 * area(wo) * area(wi));
        self.add_reflectance(wo.dot(h), lobe, out);
    }

    /// One flake of normal `h` (unit, `h.z > 0`) seen from `wo`: the mirror direction `wi` about
    /// it and, per band into `out`, the weight `R(wo·h) (wo·h) / (h.z N(wo)) · wi.z / N(wi)`;
    /// `None` (and `out` 0) when the flake faces away from `wo` or mirrors it below the
    /// layer's plane.
    ///
    /// Why this weight: a point of the layer lies on a flake with probability c, whose normal
    /// is distributed as `D(h) h.z` over the layer's area (the plane area that flakes of
    /// normal h cover). Seen from `wo`, a flake's share of what the viewer sees is its
    /// projected area, `(wo·h) / h.z` per unit of plane area, over the layer's `N(wo)`; Smith's
    /// shadowing of the light adds `wi.z / N(wi)`. The mean of `weight · L(wi)` over points is
    /// then `c ∫ D(h) R (wo·h) wi.z / (N(wo) N(wi)) L(wi) dω_h`, and with
    /// `dω_h = dω_i / (4 wo·h)` it is `∫ lobe(wo, wi) L(wi) wi.z dω_i`: the flakes' lobe of
    /// the smooth layer ([`FlakeLayer::lobe`]), which the renderer's discrete flakes average to.
    pub fn mirror(&self, wo: DVec3, h: DVec3, out: &mut [f64]) -> Option<DVec3> {
        out.fill(0.0);
        let cos_h = wo.dot(h);
        if self.orientation.is_none() || wo.z <= 0.0 || h.z <= 0.0 || cos_h <= 0.0 {
            return None;
        }
        let wi = 2.0 * cos_h * h - wo;
        if wi.z <= 0.0 {
            return None;
        }
        let area = |w: DVec3| FlakeOptics::lookup(&self.projected, w.z);
        let weight = cos_h / (h.z * area(wo)) * wi.z / area(wi);
        self.add_reflectance(cos_h, weight, out);
        Some(wi)
    }

    /// `out[b] += scale · R_b(cos_h)`, the flake's reflectance per band at the local cosine.
    fn add_reflectance(&self, cos_h: f64, scale: f64, out: &mut [f64]) {
        let nb = self.bands();
        let (r0, r1, t) = row(&self.reflectance_rows, nb, cos_h);
        for b in 0..nb {
            out[b] += scale * (r0[b] + t * (r1[b] - r0[b]));
        }
    }

    /// A flake's reflectance per band at the local cosine `cos_h` into `out`.
    pub fn reflectances(&self, cos_h: f64, out: &mut [f64]) {
        out.fill(0.0);
        self.add_reflectance(cos_h, 1.0, out);
    }

    /// Whether the flakes transmit (interference flakes; metal ones do not).
    pub fn transmits(&self) -> bool {
        self.optics.iter().any(|o| o.t.iter().any(|&t| t > 0.0))
    }

    /// The flakes' transmittance in band `b` from a direction of cosine `mu` to the layer's
    /// normal, averaged over the tilts that direction meets (T̃; 0 for metal).
    pub fn tilted_transmittance(&self, b: usize, mu: f64) -> f64 {
        self.optics
            .get(b)
            .map_or(0.0, |o| o.tilted_transmittance(mu))
    }

    /// A flake's own transmittance in band `b` at the local cosine `cos_h` (0 for metal).
    pub fn flake_transmittance(&self, b: usize, cos_h: f64) -> f64 {
        self.optics[b].transmittance(cos_h)
    }

    /// The same layer, its walks leaving out the flakes' glint: where a path meets the layer
    /// once, the layer's BRDF there is taken without the flakes' lobe ([`FlakeLayer::lobe`]);
    /// paths that meet it more than once keep it.
    pub fn without_glint(self) -> Self {
        FlakeLayer {
            glint_left_out: true,
            ..self
        }
    }

    /// Whether the walks over this layer leave out the flakes' glint.
    pub fn glint_left_out(&self) -> bool {
        self.glint_left_out
    }

    /// The fraction of the base's area that flakes cover (0 for a bare base).
    pub fn coverage(&self) -> f64 {
        self.coverage
    }

    /// The rms slope of the flakes' normals (`tan σ`), `None` for a bare base.
    pub fn slope(&self) -> Option<f64> {
        self.orientation.map(|m| m.alpha_x)
    }

    /// The pdf of [`FlakeLayer::sample`] from `wo` choosing `wi`.
    pub fn pdf(&self, wo: DVec3, wi: DVec3) -> f64 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let share = self.flake_share(wo);
        let diffuse = (1.0 - share) * wi.z / PI;
        match self.orientation {
            Some(m) if share > 0.0 => {
                let h = (wo + wi).normalize();
                diffuse + share * m.pdf_d(h) / (4.0 * wo.dot(h))
            }
            _ => diffuse,
        }
    }

    /// Sample `wi` from `wo`: a flake normal by its distribution and the mirror direction about
    /// it, or a cosine-distributed direction; the BRDF per band goes to `f`, the pdf is
    /// returned with the direction, and the pdf of sampling `wo` from `wi`.
    pub fn sample(&self, wo: DVec3, uc: f64, u: DVec2, f: &mut [f64]) -> Option<(DVec3, f64, f64)> {
        if wo.z <= 0.0 {
            return None;
        }
        let share = self.flake_share(wo);
        let wi = match self.orientation {
            Some(m) if uc < share => {
                let h = m.sample_d(u);
                -wo + 2.0 * wo.dot(h) * h
            }
            _ => {
                let r = u.x.sqrt();
                let phi = 2.0 * PI * u.y;
                DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt())
            }
        };
        if wi.z <= 0.0 {
            return None;
        }
        let (pdf, back) = self.f_and_pdfs(wo, wi, f);
        (pdf > 0.0).then_some((wi, pdf, back))
    }
}
