//! Light transport through a coating: the top interface (smooth or rough), the clear coat
//! (absorbing, not scattering) and the flake layer over the base, with every path between them
//! (internal reflection, total internal reflection, any number of passes), by the
//! position-free Monte Carlo estimator of Y. Guo, M. Hašan & S. Zhao, "Position-free Monte
//! Carlo simulation for arbitrary layered BSDFs", ACM TOG 37(6), 2018, in the form of pbrt-v4's
//! `LayeredBxDF` (Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed., §14.3.2).
//!
//! For a pair of directions `(wi, wo)` above the coating the estimator adds the top interface's
//! own reflection and, per sample, a random walk that enters the coat through the top interface
//! (sampled from `wo`), bounces between the flake layer and the underside of the top interface,
//! and at every visit of the flake layer connects to `wi` by next-event estimation: through a
//! direction sampled from the top interface's transmission seen from `wi` (the adjoint), and
//! through the direction the flake layer samples, the two weighted by the power heuristic
//! (Veach & Guibas 1995). Crossing the coat multiplies by `exp(−σ d / |cos θ|)`. The walk ends
//! by Russian roulette (unbiased) or after [`Walk::MAX_DEPTH`] events. The estimate converges
//! to the exact answer of the model as the number of samples grows; it is reciprocal in
//! expectation, and results do not depend on the thread count: each pair draws from its own
//! random stream, seeded from the pair's place in the table.
//!
//! All bands of one walk share the directions (the coat's index is the same for them); their
//! throughputs differ through the absorption, the flakes' optics and the base.

use crate::flakes::FlakeLayer;
use crate::interface::{Interface, Lobes, Transport};
use glam::{DVec2, DVec3};
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// One random-walk estimator over a set of bands sharing the coat's index.
#[derive(Clone, Debug)]
pub struct Walk {
    pub top: Interface,
    /// σ d per band: the coat's optical thickness at normal incidence.
    pub tau: Vec<f64>,
    pub bottom: FlakeLayer,
}

/// Scratch space for one thread's walks.
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    beta: Vec<f64>,
    f: Vec<f64>,
}

/// Two uniform numbers.
fn u2(rng: &mut Pcg64Mcg) -> DVec2 {
    DVec2::new(rng.random(), rng.random())
}

/// The power heuristic with exponent 2 for one sample from each of two strategies.
fn power_heuristic(pdf_a: f64, pdf_b: f64) -> f64 {
    let (a, b) = (pdf_a * pdf_a, pdf_b * pdf_b);
    if a.is_infinite() { 1.0 } else { a / (a + b) }
}

impl Walk {
    /// Events (interface or flake-layer visits) after which a walk stops. Russian roulette ends
    /// nearly every walk long before; a lossless coat over a white base (the slowest case: total
    /// internal reflection sends 60% of the base's light back at n = 1.5) keeps a fraction
    /// 0.6^(MAX_DEPTH/2) ≈ 1e-11 of its energy past it.
    pub const MAX_DEPTH: usize = 100;

    /// The number of bands.
    pub fn bands(&self) -> usize {
        self.tau.len()
    }

    /// The coat's transmittance in band `b` along a direction of cosine `mu` (1 for a clear
    /// coat, without the exponential).
    fn across(&self, b: usize, mu: f64) -> f64 {
        let t = self.tau[b];
        if t > 0.0 { (-t / mu).exp() } else { 1.0 }
    }

    /// Multiply `beta` by the coat's transmittance along `w`.
    fn attenuate(&self, beta: &mut [f64], w: DVec3) {
        let mu = w.z.abs();
        for (b, x) in beta.iter_mut().enumerate() {
            *x *= self.across(b, mu);
        }
    }

    /// The BRDF of the coating for light from `wi` to `wo` (both above), estimated with
    /// `samples` walks drawn from the stream `seed`, into `out` (one value per band, 1/sr).
    pub fn eval(
        &self,
        wo: DVec3,
        wi: DVec3,
        samples: usize,
        seed: u64,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        self.eval_body(wo, wi, samples, seed, scratch, out);
        let reflection = self.top.f(wo, wi, Transport::Radiance);
        for o in out.iter_mut() {
            *o += reflection;
        }
    }

    /// [`Walk::eval`] without the top interface's own reflection: the light that has been
    /// inside the coat.
    pub fn eval_body(
        &self,
        wo: DVec3,
        wi: DVec3,
        samples: usize,
        seed: u64,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        self.estimate(wo, wi, samples, seed, Self::MAX_DEPTH, scratch, out);
    }

    /// The single-scattering part of [`Walk::eval_body`]: the light that met the flake layer
    /// once, entering and leaving through the top interface without an internal reflection
    /// (what single-scattering models of facets under an overcoat compute, such as SCATMECH's
    /// `Subsurface_Facet_BRDF_Model`). Under a smooth top each sample is exact, so one suffices.
    pub fn eval_single(
        &self,
        wo: DVec3,
        wi: DVec3,
        samples: usize,
        seed: u64,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        self.estimate(wo, wi, samples, seed, 1, scratch, out);
    }

    /// The walks behind [`Walk::eval_body`], stopped after `max_depth` events.
    #[allow(clippy::too_many_arguments)]
    fn estimate(
        &self,
        wo: DVec3,
        wi: DVec3,
        samples: usize,
        seed: u64,
        max_depth: usize,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) {
        let nb = self.bands();
        out.fill(0.0);
        if wo.z <= 0.0 || wi.z <= 0.0 || samples == 0 {
            return;
        }
        scratch.beta.resize(nb, 0.0);
        scratch.f.resize(nb, 0.0);
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let top = &self.top;
        let bottom = &self.bottom;
        for _ in 0..samples {
            let (uo, ui) = (u2(&mut rng), u2(&mut rng));
            let Some(wos) = top.sample(
                wo,
                rng.random(),
                uo,
                Transport::Radiance,
                Lobes::Transmission,
            ) else {
                continue;
            };
            let Some(wis) = top.sample(
                wi,
                rng.random(),
                ui,
                Transport::Importance,
                Lobes::Transmission,
            ) else {
                continue;
            };
            let (beta, f) = (&mut scratch.beta, &mut scratch.f);
            beta.fill(wos.weight());
            let mut w = wos.wi;
            // Where the walk is: false at the top interface (from inside), true at the flakes.
            let mut at_bottom = false;
            for depth in 0..max_depth {
                if depth > 3 {
                    let max = beta.iter().copied().fold(0.0, f64::max);
                    if max < 0.25 {
                        let q = (1.0 - max).max(0.0);
                        if rng.random::<f64>() < q {
                            break;
                        }
                        beta.iter_mut().for_each(|b| *b /= 1.0 - q);
                    }
                }
                self.attenuate(beta, w);
                at_bottom = !at_bottom;
                if !at_bottom {
                    // The underside of the top interface sends the walk back down.
                    let Some(s) = top.sample(
                        -w,
                        rng.random(),
                        u2(&mut rng),
                        Transport::Radiance,
                        Lobes::Reflection,
                    ) else {
                        break;
                    };
                    let weight = s.weight();
                    beta.iter_mut().for_each(|b| *b *= weight);
                    w = s.wi;
                    continue;
                }
                // At the flake layer: connect to wi through the direction sampled from it.
                let up = -wis.wi;
                bottom.f(-w, up, f);
                let mis = if top.is_smooth() {
                    1.0
                } else {
                    power_heuristic(wis.pdf, bottom.pdf(-w, up))
                };
                let connect = wis.weight() * mis;
                let mu = wis.wi.z.abs();
                for b in 0..nb {
                    out[b] += beta[b] * f[b] * self.across(b, mu) * connect;
                }
                // Sample the flake layer for the walk's next direction.
                let uc = rng.random();
                let Some((next, pdf)) = bottom.sample(-w, uc, u2(&mut rng), f) else {
                    break;
                };
                for b in 0..nb {
                    beta[b] *= f[b] * next.z / pdf;
                }
                w = next;
                if !top.is_smooth() {
                    // Connect through the sampled direction to wi.
                    let f_exit = top.f(-w, wi, Transport::Radiance);
                    if f_exit > 0.0 {
                        // The other strategy's density for the same segment: sampling -w
                        // from wi through the interface.
                        let mis = power_heuristic(pdf, top.pdf(wi, -w, Lobes::Transmission));
                        let mu = w.z.abs();
                        for b in 0..nb {
                            out[b] += beta[b] * self.across(b, mu) * f_exit * mis;
                        }
                    }
                }
            }
        }
        for o in out.iter_mut() {
            *o /= samples as f64;
        }
    }
}

#[cfg(test)]
mod tests;
