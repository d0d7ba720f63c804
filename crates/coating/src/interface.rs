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

use crate::compensation::Compensation;
use glam::{DVec2, DVec3};
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;
use std::sync::Arc;

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
    /// Shared by every interface of the same index and roughness (`Compensation::shared`).
    compensation: Option<Arc<Compensation>>,
}

/// Unpolarised Fresnel reflectance for a direction whose cosine with the (micro)normal is
/// `cos`: from above (cos > 0) into index `eta`, from below out of it (total internal
/// reflection past the critical angle).
pub(crate) fn fresnel(cos: f64, eta: f64) -> f64 {
    if cos >= 0.0 {
        dielectric(cos, eta)
    } else {
        dielectric(-cos, 1.0 / eta)
    }
}

/// `w` turned into the upper hemisphere by reversing it (the microfacet distribution is seen
/// the same way from both sides).
pub(crate) fn upper(w: DVec3) -> DVec3 {
    if w.z < 0.0 { -w } else { w }
}

/// Refract `w` (pointing away from the surface) through the boundary of normal `n` (upper
/// hemisphere) with index `eta` below it; `None` at total internal reflection. Returns the
/// refracted direction and η', the ratio of the index entered to the index left.
pub(crate) fn refract(w: DVec3, n: DVec3, eta: f64) -> Option<(DVec3, f64)> {
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
    /// single scattering and the lobes of `Compensation`.
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
    use gonio_brdf::quadrature::gauss_legendre_on;
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
