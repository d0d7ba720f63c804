//! The lobes a rough interface gives back the light its single scattering loses (Kulla & Conty
//! 2017; `docs/coatings.md`, "Rough top interface"): the loss tables per side, computed once per
//! index and roughness and shared, and the sampler of the lobes by their shape.

use crate::interface::{Interface, Lobes, Transport, fresnel, refract, upper};
use glam::{DVec2, DVec3};
use gonio_brdf::microfacet::Microfacet;
use gonio_brdf::quadrature::gauss_legendre_on;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::{Arc, LazyLock, Mutex};

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
pub(crate) struct Compensation {
    /// `La` and `Lb` on equal steps of μ from 0 to 1.
    pub(crate) above: Vec<f64>,
    pub(crate) below: Vec<f64>,
    /// How the lobes into each side are sampled.
    pub(crate) into_above: LobeSampler,
    pub(crate) into_below: LobeSampler,
    pub(crate) k_aa: f64,
    pub(crate) k_ab: f64,
    pub(crate) k_ba: f64,
    pub(crate) k_bb: f64,
}

impl Compensation {
    pub(crate) const STEPS: usize = 65;
    /// Stratified visible-normal samples per μ (128 × 128): the Fresnel reflectance jumps to
    /// 1 at total internal reflection, so the stratified mean converges like 1/N there; at
    /// 128² it is within 2e-3 of a fine quadrature of the BSDF (tested).
    pub(crate) const STRATA: usize = 128;

    pub(crate) fn lookup(table: &[f64], mu: f64) -> f64 {
        let x = mu.abs().clamp(0.0, 1.0) * (Self::STEPS - 1) as f64;
        let i = (x as usize).min(Self::STEPS - 2);
        let t = x - i as f64;
        table[i] + t * (table[i + 1] - table[i])
    }

    /// The loss of the single-scattering `interface` from the side of `w` at cosine |w.z|.
    pub(crate) fn loss(&self, w: DVec3) -> f64 {
        Self::lookup(if w.z > 0.0 { &self.above } else { &self.below }, w.z)
    }

    /// The constant of the lobe from the side of `from` to the side of `to`.
    pub(crate) fn k(&self, from: DVec3, to: DVec3) -> f64 {
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
    pub(crate) const KEPT: usize = 32;

    /// The lobes of `single`, computed once per index and roughness and shared: the table
    /// costs 2 × 65 × 128² visible normals (about 0.1–0.2 s on one core), more than a
    /// formulation's readings at the lab's walks. The same values as [`Compensation::new`],
    /// bit for bit: it is what computes them, at the first request.
    pub(crate) fn shared(single: &Interface) -> Arc<Compensation> {
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

    pub(crate) fn new(single: &Interface) -> Self {
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
    pub(crate) fn f(&self, wo: DVec3, wi: DVec3, mode: Transport) -> f64 {
        let (from, to) = match mode {
            Transport::Radiance => (wi, wo),
            Transport::Importance => (wo, wi),
        };
        self.k(from, to) * self.loss(from) * self.loss(to)
    }

    /// The sampler of the lobes into the side of `w`.
    pub(crate) fn into(&self, w: DVec3) -> &LobeSampler {
        if w.z > 0.0 {
            &self.into_above
        } else {
            &self.into_below
        }
    }

    /// The probability of sampling the lobes from `wo`, and the share of it on `wo`'s side.
    pub(crate) fn sampling(&self, wo: DVec3, lobes: Lobes) -> (f64, f64) {
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
pub(crate) struct LobeSampler {
    /// The cumulative probability at the table's steps of μ, or `None` for cos θ/π.
    cdf: Option<Vec<f64>>,
}

impl LobeSampler {
    pub(crate) fn new(loss: &[f64]) -> Self {
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
    pub(crate) fn sample(&self, u: DVec2) -> (f64, f64) {
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
    pub(crate) fn pdf(&self, mu: f64) -> f64 {
        let mu = mu.abs();
        let Some(cdf) = &self.cdf else {
            return mu / PI;
        };
        let steps = cdf.len() - 1;
        let i = ((mu * steps as f64) as usize).min(steps - 1);
        (cdf[i + 1] - cdf[i]) * steps as f64 / (2.0 * PI)
    }
}
