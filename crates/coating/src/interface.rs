//! The top interface of a coating, air above and the coat's binder (index n) below, smooth or
//! rough: its reflection and transmission from either side, evaluated and sampled for the
//! random walk of [`crate::layered`].
//!
//! A rough interface is a microfacet surface (Beckmann or GGX normals, Smith masking). Its
//! reflection is Cook-Torrance's, its transmission the microfacet BTDF of B. Walter, S. R.
//! Marschner, H. Li & K. E. Torrance, "Microfacet models for refraction through rough surfaces",
//! EGSR 2007 (eqs. 20-21), written as M. Pharr, W. Jakob & G. Humphreys write it in *Physically
//! Based Rendering*, 4th ed., §9.7 (the generalised half vector `wm ∝ wi·η' + wo`, with η' the
//! ratio of the indices across the boundary, for both sides at once; visible-normal sampling).
//!
//! Conventions: directions point away from the surface in the local frame (z up, towards the
//! air); light flows from `wi` to `wo`. [`Transport::Radiance`] gives the BSDF `f(wo, wi)` of
//! light from `wi` to `wo` (for a transmission, Walter's eq. 21; radiance entering the binder
//! grows by n², its solid angle shrinking by as much); [`Transport::Importance`] its adjoint
//! `f*(wo, wi) = f(wi, wo)`, which differs for a transmission by η'² (generalised reciprocity,
//! `f(wi→wo)/η_o² = f(wo→wi)/η_i²`, E. Veach's thesis, 1997, §5.2). A smooth interface is a pair
//! of deltas: it only samples.

use glam::{DVec2, DVec3};
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;
use gonio_brdf::quadrature::gauss_legendre_on;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::{Arc, LazyLock, Mutex};

/// What a BSDF value carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transport {
    /// Radiance (light flowing from `wi` to `wo`).
    Radiance,
    /// Importance, the adjoint: power flowing from `wo` to `wi`.
    Importance,
}

impl Transport {
    /// The other one.
    pub fn adjoint(self) -> Self {
        match self {
            Transport::Radiance => Transport::Importance,
            Transport::Importance => Transport::Radiance,
        }
    }
}

/// Which lobes a sample may come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobes {
    Reflection,
    Transmission,
    Both,
}

impl Lobes {
    fn reflects(self) -> bool {
        self != Lobes::Transmission
    }
    fn transmits(self) -> bool {
        self != Lobes::Reflection
    }
}

/// A sampled direction: `wi`, the BSDF value `f` and the pdf (per steradian, or the discrete
/// probability for a delta, whose `f` is then the delta's weight divided by |cos θi|).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub wi: DVec3,
    pub f: f64,
    pub pdf: f64,
    pub specular: bool,
}

impl Sample {
    /// `f |cos θi| / pdf`: the factor by which the sample scales a path's throughput.
    pub fn weight(&self) -> f64 {
        self.f * self.wi.z.abs() / self.pdf
    }
}

/// The air–coat boundary: the coat's index relative to air and, for a rough interface, its
/// microfacet distribution and the lobes that give back what single scattering loses.
#[derive(Clone, Debug, PartialEq)]
pub struct Interface {
    /// The binder's index (air above: 1).
    pub eta: f64,
    /// `None` for a smooth (mirror) interface.
    pub roughness: Option<Microfacet>,
    /// Shared by every interface of the same index and roughness ([`Compensation::shared`]).
    compensation: Option<Arc<Compensation>>,
}

/// The light a microfacet interface scatters more than once (`docs/coatings.md`, "Rough top
/// interface"). Smith's single-scattering BSDF loses the light that meets a second microfacet:
/// from a direction of cosine μ above, the fraction `La(μ) = 1 − ∫ (f_r + f_t) |cos| dω`, and
/// `Lb(μ)` from below, where grazing light inside the coat loses most (at α = 0.05 about 1% of
/// a diffuse field per visit, which a white base under the coat multiplies by 2.4). That light
/// is not absorbed; as in C. Kulla & A. Conty, "Revisiting physically based shading at
/// Imageworks" (SIGGRAPH course, 2017), it is given back in diffuse lobes that conserve energy
/// from every direction and keep the interface reciprocal:
///
/// `f_ms(x → y) = k_xy L_x(μx) L_y(μy)` for light from side x to side y,
///
/// with `k_aa = (1 − s)/(π Āa)`, `k_ab = s/(π Āb)`, `k_ba = k_ab/n²` (reciprocity across the
/// boundary, `f(a→b)/n² = f(b→a)`), `k_bb = (1 − k_ba π Āa)/(π Āb)`, `Āx = ∫ Lx(μ) 2μ dμ`; s,
/// the share of the light lost above that ends below, is `1 − F̄` (F̄ the external
/// hemispherical Fresnel reflectance) as long as `k_bb ≥ 0` allows. The split is a model, not a
/// solution of the multiple scattering (E. Heitz et al., "Multiple-scattering microfacet BSDFs
/// with the Smith model", 2016, solve it by a random walk on the microsurface); what it keeps
/// exact is energy and reciprocity.
#[derive(Clone, Debug, PartialEq)]
struct Compensation {
    /// `La` and `Lb` on equal steps of μ from 0 to 1.
    above: Vec<f64>,
    below: Vec<f64>,
    /// How the lobes into each side are sampled.
    into_above: LobeSampler,
    into_below: LobeSampler,
    k_aa: f64,
    k_ab: f64,
    k_ba: f64,
    k_bb: f64,
}

impl Compensation {
    const STEPS: usize = 65;
    /// Stratified visible-normal samples per μ (128 × 128): the Fresnel reflectance jumps to
    /// 1 at total internal reflection, so the stratified mean converges like 1/N there; at
    /// 128² it is within 2e-3 of a fine quadrature of the BSDF (tested).
    const STRATA: usize = 128;

    fn lookup(table: &[f64], mu: f64) -> f64 {
        let x = mu.abs().clamp(0.0, 1.0) * (Self::STEPS - 1) as f64;
        let i = (x as usize).min(Self::STEPS - 2);
        let t = x - i as f64;
        table[i] + t * (table[i + 1] - table[i])
    }

    /// The loss of the single-scattering `interface` from the side of `w` at cosine |w.z|.
    fn loss(&self, w: DVec3) -> f64 {
        Self::lookup(if w.z > 0.0 { &self.above } else { &self.below }, w.z)
    }

    /// The constant of the lobe from the side of `from` to the side of `to`.
    fn k(&self, from: DVec3, to: DVec3) -> f64 {
        match (from.z > 0.0, to.z > 0.0) {
            (true, true) => self.k_aa,
            (true, false) => self.k_ab,
            (false, true) => self.k_ba,
            (false, false) => self.k_bb,
        }
    }

    /// Interfaces whose lobes [`Compensation::shared`] keeps: a formulation's readings build
    /// two evaluators (the gloss meter's band and the colour's bands) and a lab session or a
    /// study reads many formulations that share the top's index and roughness.
    const KEPT: usize = 32;

    /// The lobes of `single`, computed once per index and roughness and shared: the table
    /// costs 2 × 65 × 128² visible normals (about 0.1–0.2 s on one core), more than a
    /// formulation's readings at the lab's walks. The same values as [`Compensation::new`],
    /// bit for bit: it is what computes them, at the first request.
    fn shared(single: &Interface) -> Arc<Compensation> {
        type Kept = Vec<((u64, Microfacet), Arc<Compensation>)>;
        static KEPT: LazyLock<Mutex<Kept>> = LazyLock::new(Mutex::default);
        let key = (
            single.eta.to_bits(),
            single.roughness.expect("compensation of a rough interface"),
        );
        let lock = || KEPT.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some((_, c)) = lock().iter().find(|(k, _)| *k == key) {
            return Arc::clone(c);
        }
        let c = Arc::new(Compensation::new(single));
        let mut kept = lock();
        if !kept.iter().any(|(k, _)| *k == key) {
            if kept.len() == Self::KEPT {
                kept.remove(0);
            }
            kept.push((key, Arc::clone(&c)));
        }
        c
    }

    fn new(single: &Interface) -> Self {
        let m = single.roughness.expect("compensation of a rough interface");
        let strata = Self::STRATA;
        // Single-scattering albedo from a direction of cosine mu on either side: the mean of
        // G2/G1 over the visible normals, reflection and refraction weighted by Fresnel. The
        // normals at the strata and G1(w), Λ(w) are those of one direction, found once.
        let albedo = |w: DVec3| {
            let lambda_w = m.lambda(upper(w));
            let g1 = m.g1(upper(w));
            let mut sum = 0.0;
            for wm in m.sample_visible_stratified(upper(w), strata) {
                let r = fresnel(w.dot(wm), single.eta);
                let reflected = -w + 2.0 * w.dot(wm) * wm;
                if reflected.z * w.z > 0.0 {
                    sum += r * m.g2_with(lambda_w, upper(reflected)) / g1;
                }
                if let Some((t, _)) = refract(w, wm, single.eta)
                    && t.z * w.z < 0.0
                {
                    sum += (1.0 - r) * m.g2_with(lambda_w, upper(t)) / g1;
                }
            }
            sum / (strata * strata) as f64
        };
        // Each μ's albedo is its own sum, so computing them in parallel changes no bit.
        let table = |sign: f64| -> Vec<f64> {
            (0..Self::STEPS)
                .into_par_iter()
                .map(|i| {
                    let mu = (i as f64 / (Self::STEPS - 1) as f64).max(1e-4);
                    let w = DVec3::new((1.0 - mu * mu).sqrt(), 0.0, sign * mu);
                    (1.0 - albedo(w)).clamp(0.0, 1.0)
                })
                .collect()
        };
        let (above, below) = (table(1.0), table(-1.0));
        let mean = |t: &[f64]| {
            gauss_legendre_on(32, 0.0, 1.0)
                .into_iter()
                .map(|(mu, w)| w * Self::lookup(t, mu) * 2.0 * mu)
                .sum::<f64>()
        };
        let (a, b) = (mean(&above), mean(&below));
        let f_bar = gauss_legendre_on(64, 0.0, 1.0)
            .into_iter()
            .map(|(mu, w)| w * fresnel(mu, single.eta) * 2.0 * mu)
            .sum::<f64>();
        let n2 = single.eta * single.eta;
        let (k_aa, k_ab, k_ba, k_bb) = if a <= 0.0 || b <= 0.0 {
            (0.0, 0.0, 0.0, if b > 0.0 { 1.0 / (PI * b) } else { 0.0 })
        } else {
            let s = (1.0 - f_bar).min(n2 * b / a);
            let k_ab = s / (PI * b);
            let k_ba = k_ab / n2;
            (
                (1.0 - s) / (PI * a),
                k_ab,
                k_ba,
                (1.0 - k_ba * PI * a) / (PI * b),
            )
        };
        Compensation {
            into_above: LobeSampler::new(&above),
            into_below: LobeSampler::new(&below),
            above,
            below,
            k_aa: if a > 0.0 { k_aa } else { 0.0 },
            k_ab,
            k_ba,
            k_bb,
        }
    }

    /// The lobes' BSDF for light from `wi` to `wo` (radiance) or its adjoint.
    fn f(&self, wo: DVec3, wi: DVec3, mode: Transport) -> f64 {
        let (from, to) = match mode {
            Transport::Radiance => (wi, wo),
            Transport::Importance => (wo, wi),
        };
        self.k(from, to) * self.loss(from) * self.loss(to)
    }

    /// The sampler of the lobes into the side of `w`.
    fn into(&self, w: DVec3) -> &LobeSampler {
        if w.z > 0.0 {
            &self.into_above
        } else {
            &self.into_below
        }
    }

    /// The probability of sampling the lobes from `wo`, and the share of it on `wo`'s side.
    fn sampling(&self, wo: DVec3, lobes: Lobes) -> (f64, f64) {
        let same = match lobes {
            Lobes::Reflection => 1.0,
            Lobes::Transmission => 0.0,
            Lobes::Both => {
                let (same, other) = (self.k(wo, wo), self.k(wo, -wo));
                let (a, b) = (
                    Self::lookup(if wo.z > 0.0 { &self.above } else { &self.below }, 0.5),
                    Self::lookup(if wo.z > 0.0 { &self.below } else { &self.above }, 0.5),
                );
                if same * a + other * b > 0.0 {
                    same * a / (same * a + other * b)
                } else {
                    0.5
                }
            }
        };
        (self.loss(wo).min(0.5), same)
    }
}

/// The directions the lobes into one side are drawn from: the lobes go as `L(μ)` (times μ for
/// the projected solid angle), so μ is drawn with the density `L(μ) 2μ / Ā`, piecewise constant
/// over the steps of the loss table (each step's probability exact by 2-point Gauss-Legendre
/// quadrature, L being linear on it). The weights `f |cos θ| / pdf` then stay within a factor
/// of about 2 of their mean. Drawing cos θ/π instead let the lobes' growth towards grazing
/// angles into the weights: for α = 0.03 a light entering the coat at a grazing angle weighed
/// up to 14, and at 45° illumination and 65° view one walk in 10⁵ carried 1 400 times the
/// mean. A side that loses nothing (Ā = 0) is never sampled by weight; it keeps cos θ/π.
#[derive(Clone, Debug, PartialEq)]
struct LobeSampler {
    /// The cumulative probability at the table's steps of μ, or `None` for cos θ/π.
    cdf: Option<Vec<f64>>,
}

impl LobeSampler {
    fn new(loss: &[f64]) -> Self {
        let steps = loss.len() - 1;
        let h = 1.0 / steps as f64;
        let nodes = [0.5 - 0.5 / 3f64.sqrt(), 0.5 + 0.5 / 3f64.sqrt()];
        let mut cdf = vec![0.0; steps + 1];
        for i in 0..steps {
            let bin: f64 = nodes
                .iter()
                .map(|t| {
                    let mu = (i as f64 + t) * h;
                    (loss[i] + t * (loss[i + 1] - loss[i])) * 2.0 * mu * 0.5 * h
                })
                .sum();
            cdf[i + 1] = cdf[i] + bin;
        }
        let total = cdf[steps];
        if total <= 0.0 {
            return LobeSampler { cdf: None };
        }
        cdf.iter_mut().for_each(|c| *c /= total);
        LobeSampler { cdf: Some(cdf) }
    }

    /// A direction's cosine and azimuth from `u`.
    fn sample(&self, u: DVec2) -> (f64, f64) {
        let phi = 2.0 * PI * u.y;
        let Some(cdf) = &self.cdf else {
            return ((1.0 - u.x).max(0.0).sqrt(), phi);
        };
        let steps = cdf.len() - 1;
        let i = (cdf.partition_point(|&c| c <= u.x).max(1) - 1).min(steps - 1);
        let width = cdf[i + 1] - cdf[i];
        let t = if width > 0.0 {
            ((u.x - cdf[i]) / width).clamp(0.0, 1.0)
        } else {
            0.5
        };
        ((i as f64 + t) / steps as f64, phi)
    }

    /// The density per steradian of a direction of cosine `mu` (of either sign).
    fn pdf(&self, mu: f64) -> f64 {
        let mu = mu.abs();
        let Some(cdf) = &self.cdf else {
            return mu / PI;
        };
        let steps = cdf.len() - 1;
        let i = ((mu * steps as f64) as usize).min(steps - 1);
        (cdf[i + 1] - cdf[i]) * steps as f64 / (2.0 * PI)
    }
}

/// Unpolarised Fresnel reflectance for a direction whose cosine with the (micro)normal is
/// `cos`: from above (cos > 0) into index `eta`, from below out of it (total internal
/// reflection past the critical angle).
fn fresnel(cos: f64, eta: f64) -> f64 {
    if cos >= 0.0 {
        dielectric(cos, eta)
    } else {
        dielectric(-cos, 1.0 / eta)
    }
}

/// `w` turned into the upper hemisphere by reversing it (the microfacet distribution is seen
/// the same way from both sides).
fn upper(w: DVec3) -> DVec3 {
    if w.z < 0.0 { -w } else { w }
}

/// Refract `w` (pointing away from the surface) through the boundary of normal `n` (upper
/// hemisphere) with index `eta` below it; `None` at total internal reflection. Returns the
/// refracted direction and η', the ratio of the index entered to the index left.
fn refract(w: DVec3, n: DVec3, eta: f64) -> Option<(DVec3, f64)> {
    let (mut cos_i, mut n, mut eta) = (n.dot(w), n, eta);
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((-w / eta + (cos_i / eta - cos_t) * n, eta))
}

impl Interface {
    /// A smooth interface (the roughness `None`) or a rough one.
    pub fn new(eta: f64, roughness: Option<Microfacet>) -> Self {
        let mut interface = Interface {
            eta,
            roughness,
            compensation: None,
        };
        if roughness.is_some() {
            interface.compensation = Some(Compensation::shared(&interface));
        }
        interface
    }

    /// Whether the interface is a mirror (its lobes are deltas: [`Interface::f`] is 0).
    pub fn is_smooth(&self) -> bool {
        self.roughness.is_none()
    }

    /// The generalised half vector of the pair and η' (1 for a reflection), or `None` where the
    /// pair has no microfacet (grazing, or a microfacet seen from behind).
    fn half_vector(&self, wo: DVec3, wi: DVec3) -> Option<(DVec3, f64)> {
        let (co, ci) = (wo.z, wi.z);
        if co == 0.0 || ci == 0.0 {
            return None;
        }
        let etap = if co * ci > 0.0 {
            1.0
        } else if co > 0.0 {
            self.eta
        } else {
            1.0 / self.eta
        };
        let wm = wi * etap + wo;
        if wm.length_squared() == 0.0 {
            return None;
        }
        let wm = upper(wm.normalize());
        if wm.dot(wi) * ci < 0.0 || wm.dot(wo) * co < 0.0 {
            return None;
        }
        Some((wm, etap))
    }

    /// The BSDF in 1/sr for light from `wi` to `wo` (either side; 0 for a smooth interface):
    /// single scattering and the lobes of [`Compensation`].
    pub fn f(&self, wo: DVec3, wi: DVec3, mode: Transport) -> f64 {
        match &self.compensation {
            Some(c) if wo.z != 0.0 && wi.z != 0.0 => {
                self.f_single(wo, wi, mode) + c.f(wo, wi, mode)
            }
            _ => 0.0,
        }
    }

    /// The single-scattering BSDF (Cook-Torrance's reflection, Walter's transmission).
    fn f_single(&self, wo: DVec3, wi: DVec3, mode: Transport) -> f64 {
        let Some(m) = self.roughness else {
            return 0.0;
        };
        let Some((wm, etap)) = self.half_vector(wo, wi) else {
            return 0.0;
        };
        let fr = fresnel(wo.dot(wm), self.eta);
        let dg = m.d(wm) * m.g2(upper(wo), upper(wi));
        if wo.z * wi.z > 0.0 {
            return dg * fr / (4.0 * wi.z * wo.z).abs();
        }
        let denom = (wi.dot(wm) + wo.dot(wm) / etap).powi(2) * wi.z * wo.z;
        let ft = dg * (1.0 - fr) * (wi.dot(wm) * wo.dot(wm) / denom).abs();
        match mode {
            Transport::Radiance => ft / (etap * etap),
            Transport::Importance => ft,
        }
    }

    /// The pdf of [`Interface::sample`] from `wo` choosing `wi` (0 for a smooth interface).
    pub fn pdf(&self, wo: DVec3, wi: DVec3, lobes: Lobes) -> f64 {
        let Some(c) = &self.compensation else {
            return 0.0;
        };
        if wo.z == 0.0 || wi.z == 0.0 {
            return 0.0;
        }
        let (p_ms, same) = c.sampling(wo, lobes);
        let side = if wi.z * wo.z > 0.0 { same } else { 1.0 - same };
        (1.0 - p_ms) * self.pdf_single(wo, wi, lobes)
            + p_ms * side * Compensation::into(c, wi).pdf(wi.z)
    }

    /// The density of the visible-normal sampler of the single-scattering lobes.
    fn pdf_single(&self, wo: DVec3, wi: DVec3, lobes: Lobes) -> f64 {
        let Some(m) = self.roughness else {
            return 0.0;
        };
        let Some((wm, etap)) = self.half_vector(wo, wi) else {
            return 0.0;
        };
        let r = fresnel(wo.dot(wm), self.eta);
        let pr = if lobes.reflects() { r } else { 0.0 };
        let pt = if lobes.transmits() { 1.0 - r } else { 0.0 };
        if pr + pt == 0.0 {
            return 0.0;
        }
        let visible = m.pdf_visible(upper(wo), wm);
        if wo.z * wi.z > 0.0 {
            visible / (4.0 * wo.dot(wm).abs()) * pr / (pr + pt)
        } else {
            let dwm_dwi = wi.dot(wm).abs() / (wi.dot(wm) + wo.dot(wm) / etap).powi(2);
            visible * dwm_dwi * pt / (pr + pt)
        }
    }

    /// Sample the direction `wi` the light came from, given `wo`: a rough interface picks the
    /// multiple-scattering lobes or single scattering (`uc`), then reflection or transmission
    /// by the Fresnel reflectance (`uc` again) and the microfacet by its visible-normal
    /// distribution (`u`); a smooth one picks its mirror or Snell's direction by Fresnel.
    pub fn sample(
        &self,
        wo: DVec3,
        uc: f64,
        u: DVec2,
        mode: Transport,
        lobes: Lobes,
    ) -> Option<Sample> {
        if wo.z == 0.0 {
            return None;
        }
        let (Some(c), Some(m)) = (&self.compensation, self.roughness) else {
            return self.sample_mirror(wo, uc, mode, lobes);
        };
        let (p_ms, same) = c.sampling(wo, lobes);
        let wi = if uc < p_ms {
            // A direction on the side chosen, drawn from the lobes' shape there.
            let side = if uc / p_ms < same { 1.0 } else { -1.0 } * wo.z.signum();
            let (mu, phi) = Compensation::into(c, DVec3::Z * side).sample(u);
            let r = (1.0 - mu * mu).max(0.0).sqrt();
            DVec3::new(r * phi.cos(), r * phi.sin(), side * mu)
        } else {
            let uc = (uc - p_ms) / (1.0 - p_ms);
            let wm = m.sample_visible(upper(wo), u);
            let r = fresnel(wo.dot(wm), self.eta);
            let pr = if lobes.reflects() { r } else { 0.0 };
            let pt = if lobes.transmits() { 1.0 - r } else { 0.0 };
            if pr + pt == 0.0 {
                return None;
            }
            let reflect = uc < pr / (pr + pt);
            let wi = if reflect {
                -wo + 2.0 * wo.dot(wm) * wm
            } else {
                refract(wo, wm, self.eta)?.0
            };
            if (wi.z * wo.z > 0.0) != reflect {
                return None;
            }
            wi
        };
        if wi.z == 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi, lobes);
        if pdf == 0.0 {
            return None;
        }
        Some(Sample {
            wi,
            f: self.f(wo, wi, mode),
            pdf,
            specular: false,
        })
    }

    /// The interface's reflection of light from `wi` as `strata × strata` samples of its lobes
    /// ([`Interface::sample`], [`Transport::Importance`], reflection only): `u` on the centres
    /// of a stratified grid, `uc` spread over [0, 1) by a stride coprime with the count (7919),
    /// so that a sample's [`Sample::weight`] over `strata²` sums to the reflected fraction into
    /// the directions the samples land in (the gloss meter's windows, the albedo). Samples that
    /// miss (below the horizon) are left out.
    pub fn reflection_samples(
        &self,
        wi: DVec3,
        strata: usize,
    ) -> impl Iterator<Item = Sample> + '_ {
        let n = strata;
        (0..n * n).filter_map(move |k| {
            let u = DVec2::new(
                ((k / n) as f64 + 0.5) / n as f64,
                ((k % n) as f64 + 0.5) / n as f64,
            );
            let uc = ((k * 7919) % (n * n)) as f64 / (n * n) as f64;
            self.sample(wi, uc, u, Transport::Importance, Lobes::Reflection)
        })
    }

    /// A smooth interface's sample: the mirror direction with probability F, Snell's with
    /// 1 − F (within `lobes`).
    fn sample_mirror(&self, wo: DVec3, uc: f64, mode: Transport, lobes: Lobes) -> Option<Sample> {
        let r = fresnel(wo.z, self.eta);
        let pr = if lobes.reflects() { r } else { 0.0 };
        let pt = if lobes.transmits() { 1.0 - r } else { 0.0 };
        if pr + pt == 0.0 {
            return None;
        }
        let reflect = uc < pr / (pr + pt);
        let (wi, value, etap) = if reflect {
            (DVec3::new(-wo.x, -wo.y, wo.z), r, 1.0)
        } else {
            let (wi, etap) = refract(wo, DVec3::Z, self.eta)?;
            (wi, 1.0 - r, etap)
        };
        if wi.z == 0.0 {
            return None;
        }
        let scale = match mode {
            Transport::Radiance => 1.0 / (etap * etap),
            Transport::Importance => 1.0,
        };
        Some(Sample {
            wi,
            f: value * scale / wi.z.abs(),
            pdf: if reflect { pr } else { pt } / (pr + pt),
            specular: true,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use std::f64::consts::PI;

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    /// Walter et al. 2007, eq. 21, written out from the paper for light from `i` (air, above)
    /// refracted to `o` (below, index n):
    /// `|i·h||o·h| / (|i·n||o·n|) · n² (1 − F(i·h)) G(i, o) D(h) / ((i·h) + n (o·h))²`, with
    /// `h = −(i + n o)/|i + n o|`. Independent of the module's generalised half vector.
    fn walter_btdf(m: &Microfacet, n: f64, i: DVec3, o: DVec3) -> f64 {
        let mut h = -(i + n * o).normalize();
        if h.z < 0.0 {
            h = -h;
        }
        let (ih, oh) = (i.dot(h), o.dot(h));
        let g = 1.0 / (1.0 + m.lambda(i) + m.lambda(-o));
        ih.abs() * oh.abs() / (i.z.abs() * o.z.abs())
            * n
            * n
            * (1.0 - dielectric(ih, n))
            * g
            * m.d(h)
            / (ih + n * oh).powi(2)
    }

    #[test]
    fn transmission_is_walters_btdf() {
        for m in [Microfacet::ggx(0.3), Microfacet::beckmann(0.2)] {
            let s = Interface::new(1.5, Some(m));
            for (ti, to, p) in [
                (10.0, 170.0, 180.0),
                (40.0, 150.0, 170.0),
                (60.0, 140.0, 200.0),
            ] {
                let (i, o) = (dir(ti, 0.0), dir(to, p));
                let want = walter_btdf(&m, 1.5, i, o);
                let rad = s.f_single(o, i, Transport::Radiance);
                assert!((rad / want - 1.0).abs() < 1e-12, "{rad} vs {want}");
                // The adjoint with the roles swapped is the same transport.
                let adjoint = s.f_single(i, o, Transport::Importance);
                assert!((adjoint / want - 1.0).abs() < 1e-12);
                // Generalised reciprocity: f(i→o)/n_o² = f(o→i)/n_i², with the compensation
                // lobes too.
                let back = s.f_single(i, o, Transport::Radiance);
                assert!((rad / 2.25 / back - 1.0).abs() < 1e-12, "{rad} {back}");
                let (rad, back) = (
                    s.f(o, i, Transport::Radiance),
                    s.f(i, o, Transport::Radiance),
                );
                assert!((rad / 2.25 / back - 1.0).abs() < 1e-12, "{rad} {back}");
            }
        }
    }

    /// Energy: from above or below, ∫ (f_r + f_t) |cos| dω (importance, i.e. power) is 1 with
    /// the compensation lobes, and for a nearly smooth interface the reflected part is F(θ).
    /// The integrals by Monte Carlo with the interface's own sampler (weights f|cos|/pdf), and
    /// at α = 0.3 against uniform-sphere sampling (an independent estimator of the same
    /// integral, which checks the sampler's pdf).
    #[test]
    fn energy_and_sampling() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        for (alpha, theta) in [
            (0.02, 30.0),
            (0.3, 20.0),
            (0.3, 60.0),
            (0.3, 160.0),
            (0.1, 120.0),
        ] {
            let s = Interface::new(1.5, Some(Microfacet::ggx(alpha)));
            let wo = dir(theta, 0.0);
            let n = 200_000;
            let (mut sampled_r, mut sampled_t) = (0.0, 0.0);
            let (mut uniform_r, mut uniform_t) = (0.0, 0.0);
            for _ in 0..n {
                let u = DVec2::new(rng.random(), rng.random());
                if let Some(smp) = s.sample(wo, rng.random(), u, Transport::Importance, Lobes::Both)
                {
                    if smp.wi.z * wo.z > 0.0 {
                        sampled_r += smp.weight();
                    } else {
                        sampled_t += smp.weight();
                    }
                }
                let z: f64 = 2.0 * rng.random::<f64>() - 1.0;
                let phi = 2.0 * PI * rng.random::<f64>();
                let r = (1.0 - z * z).sqrt();
                let wi = DVec3::new(r * phi.cos(), r * phi.sin(), z);
                let v = s.f(wo, wi, Transport::Importance) * z.abs() * 4.0 * PI;
                if z * wo.z > 0.0 {
                    uniform_r += v
                } else {
                    uniform_t += v
                }
            }
            let (sr, st) = (sampled_r / n as f64, sampled_t / n as f64);
            let (ur, ut) = (uniform_r / n as f64, uniform_t / n as f64);
            // The weights are nearly constant (G2/G1 and the lobes' share): their standard
            // error is below 1e-3.
            assert!((sr + st - 1.0).abs() < 3e-3, "{alpha} {theta}: {sr} + {st}");
            if alpha == 0.02 {
                let f = fresnel(wo.z, 1.5);
                assert!((sr - f).abs() < 2e-3, "{sr} vs F {f}");
            } else if alpha == 0.3 {
                // The uniform estimator's relative standard error is a few per cent at α = 0.3
                // (the lobes cover ~1/20 of the sphere): 4σ ≈ 5% on each part.
                assert!(
                    (ur / sr - 1.0).abs() < 0.05,
                    "{alpha} {theta}: r {ur} vs {sr}"
                );
                assert!(
                    (ut / st - 1.0).abs() < 0.05,
                    "{alpha} {theta}: t {ut} vs {st}"
                );
            }
        }
    }

    /// The tabulated single-scattering loss against the integral of the single-scattering
    /// BSDF over the sphere by the midpoint rule (2000 steps of θ, 720 of φ: 0.09° × 0.5°
    /// cells across lobes some 17° wide: the rule's error is far below the 2e-3 allowed for
    /// the table's stratified estimate and its interpolation in μ).
    #[test]
    fn tabulated_loss_is_the_single_scattering_deficit() {
        let s = Interface::new(1.5, Some(Microfacet::beckmann(0.3)));
        let c = s.compensation.as_ref().unwrap();
        for theta in [0.0, 45.0, 75.0, 110.0, 150.0] {
            let wo = dir(theta, 0.0);
            let (nt, np) = (2000, 720);
            let (dt, dp) = (PI / nt as f64, 2.0 * PI / np as f64);
            let mut sum = 0.0;
            for i in 0..nt {
                let t = (i as f64 + 0.5) * dt;
                for j in 0..np {
                    let p = (j as f64 + 0.5) * dp;
                    let wi = DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
                    sum += s.f_single(wo, wi, Transport::Importance) * t.cos().abs() * t.sin();
                }
            }
            let loss = 1.0 - sum * dt * dp;
            assert!(
                (c.loss(wo) - loss).abs() < 1e-3,
                "{theta}: {} vs {loss}",
                c.loss(wo)
            );
        }
    }

    /// The lobes' sampler draws μ with the density it reports: over 400 000 draws, the count
    /// in each of 20 bins of μ within 4 binomial standard deviations of the density's integral
    /// over the bin (midpoint rule on 6 400 steps of μ, a multiple of the table's 64, so exact
    /// for the piecewise-constant density); the density integrates to 1 over the
    /// hemisphere; the weight `L(μ) μ / (π Ā pdf)` of every draw stays below 3.5 (measured
    /// 3.0 at α = 0.03, in the step where L rises fastest; cos θ/π sampling gave up to 14
    /// near grazing).
    #[test]
    fn lobes_are_sampled_by_their_shape() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(17);
        for alpha in [0.03, 0.3] {
            let s = Interface::new(1.5, Some(Microfacet::ggx(alpha)));
            let c = s.compensation.as_ref().unwrap();
            for (table, sampler) in [(&c.above, &c.into_above), (&c.below, &c.into_below)] {
                let mean = gauss_legendre_on(64, 0.0, 1.0)
                    .into_iter()
                    .map(|(mu, w)| w * Compensation::lookup(table, mu) * 2.0 * mu)
                    .sum::<f64>();
                let density = |mu: f64| sampler.pdf(mu) * 2.0 * PI;
                let integral = |a: f64, b: f64| {
                    let n = (6400.0 * (b - a)).round() as usize;
                    let h = (b - a) / n as f64;
                    (0..n)
                        .map(|k| density(a + (k as f64 + 0.5) * h) * h)
                        .sum::<f64>()
                };
                assert!((integral(0.0, 1.0) - 1.0).abs() < 1e-9);
                let (n, bins) = (400_000, 20);
                let mut counts = vec![0usize; bins];
                let mut hi = 0.0f64;
                for _ in 0..n {
                    let (mu, _) = sampler.sample(DVec2::new(rng.random(), rng.random()));
                    counts[((mu * bins as f64) as usize).min(bins - 1)] += 1;
                    let weight =
                        Compensation::lookup(table, mu) * mu / (PI * mean) / sampler.pdf(mu);
                    hi = hi.max(weight);
                }
                for (k, &count) in counts.iter().enumerate() {
                    let p = integral(k as f64 / bins as f64, (k + 1) as f64 / bins as f64);
                    let expected = p * n as f64;
                    let sd = (n as f64 * p * (1.0 - p)).sqrt();
                    assert!(
                        (count as f64 - expected).abs() < 4.0 * sd + 1.0,
                        "α {alpha} bin {k}: {count} vs {expected:.0} ± {sd:.0}"
                    );
                }
                assert!(hi < 3.5, "α {alpha}: weights up to {hi}");
            }
        }
    }

    /// A mirror reflects F and transmits 1 − F along Snell's direction.
    #[test]
    fn smooth_interface() {
        let s = Interface::new(1.5, None);
        let wo = dir(40.0, 30.0);
        let r = s
            .sample(wo, 0.0, DVec2::ZERO, Transport::Importance, Lobes::Both)
            .unwrap();
        assert!((r.weight() - 1.0).abs() < 1e-12 && r.wi.z > 0.0);
        let t = s
            .sample(
                wo,
                0.99,
                DVec2::ZERO,
                Transport::Importance,
                Lobes::Transmission,
            )
            .unwrap();
        let sin_t = (t.wi.x * t.wi.x + t.wi.y * t.wi.y).sqrt();
        assert!((sin_t * 1.5 - 40f64.to_radians().sin()).abs() < 1e-12);
        assert!((t.f * t.wi.z.abs() - (1.0 - dielectric(wo.z, 1.5))).abs() < 1e-12);
        // From inside past the critical angle: total internal reflection only.
        let inside = dir(180.0 - 50.0, 0.0);
        assert!(
            s.sample(
                inside,
                0.5,
                DVec2::ZERO,
                Transport::Radiance,
                Lobes::Transmission
            )
            .is_none()
        );
    }
}
