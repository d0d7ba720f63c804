//! The layered walks ([`Walk`]: from wo and from the light, joined by several strategies under
//! multiple importance sampling, Russian roulette, tabulated flake optics) against a
//! brute-force photon simulation of the same model,
//! written here from `docs/coatings.md` ("The general system") and the physics, not from the
//! walk's code: photons enter through the top, bounce between the flake layer and the top's
//! underside (total internal reflection included) and are counted when they escape into small
//! cones about chosen directions. No next-event estimation, no MIS, no tables: each event is
//! sampled as the light does it, and what leaves is tallied where it goes. SCATMECH
//! (`scatmech_oracle`) checks only the single-scattering part; this checks the rest too, which at
//! 45° illumination adds 7% (view 0°) to 40% (view 75°) to it.
//!
//! What the photons share with gonio is what is tested on its own elsewhere: Fresnel's
//! equations (`gonio_brdf::fresnel`, against their closed forms, and through the thin films
//! against the `tmm` package), the aluminium's tabulated index (data), and for the rough top the
//! interface's sampler (`Interface::sample`, tested against Walter et al.'s BTDF written out,
//! for energy, and against uniform sampling of the sphere in `interface`'s tests), which the
//! photons use as the interface's scattering: the rough case checks the walk's estimator with a
//! rough top, not the interface's model. The rest is written here independently: Snell's law;
//! the flakes' normals drawn from the Beckmann slope distribution (Gaussian slopes of variance
//! tan²σ/2 per axis) and weighted to the projected area a direction meets, `D(h) max(0, w·h)/N(w)`;
//! `N(w)` in closed form (the walk tabulates it from 32 × 32 stratified normals); the flake's
//! reflectance from Fresnel's equations at each event (the walk tabulates it on 1025 steps of
//! cos); masking `G1 = cos θ/N`; the base's Lambertian bounce and the flakes' undersides as events
//! (the walk sums them in closed form).
//!
//! The cone estimator. A photon from `wi` stands for unit power per unit area of the surface;
//! what escapes into the cap C of half-angle δ about a direction a has the expectation
//! `∫_C f(wi, w) cos θ dω`, and dividing by the cap's projected solid angle
//! `Ω = ∫_C cos θ dω = π sin²δ cos θa` (exact: cos θ = w·z is linear in w and the cap's mean
//! direction is a (1 + cos δ)/2) gives f averaged over C with the weight cos θ. The walks are
//! read over the same cap (each walk's `wo` drawn uniformly in C and weighted by
//! `cos θ / (cos θa (1 + cos δ)/2)`), so both sides estimate the same number whatever δ: the
//! comparison carries no bias from the cone. What the cap's average is against the BRDF at its
//! axis: expanding f and cos θ to second order in the tangent angles about a (the cap's first
//! moments vanish, its second are δ²/4 per axis), the average is
//! `f(a) [1 + δ² (∇f·∇cos θ/(4 f cos θa) + ∇²f/(8 f))]`. The flake lobe in air is close to a
//! Gaussian of width s per axis: the tilt's rms slope tan σ/√2 per axis (7.1° for σ = 10°),
//! doubled by the reflection and widened by the refraction out (n near the normal, more towards
//! grazing), s ≥ 0.37 rad. At the lobe's peak ∇²f/f = −2/s² = −15/rad², a bias of −0.5% for
//! δ = 3° (δ² = 2.7e-3); one s off the peak at a view of 80°, |∇f/f| |∇cos θ|/cos θa =
//! tan 80°/s = 15/rad, +1.0%. Measured with the walks (cap against axis, 128 000 walks each):
//! −0.6% to +1.3% over the views below (the largest at 15°, view −80°), against the photons'
//! standard errors of 0.5–10%: the cap's average is the BRDF the walks read at its axis, within
//! a third of the photons' error.
//!
//! Photons: the fraction escaping into a cap is `f Ω`, 2.7e-3 f at normal view for δ = 3° and
//! a quarter of that at 75°, so 4 million photons give a relative standard error of 1/√(N f Ω):
//! 0.5% at f = 1.7/sr on the lobe, 2% at f = 0.1/sr towards grazing, 10% at 0.005/sr far out
//! (the rough case, whose photons cost three times as much, runs half as many).
//!
//! Tolerance: each side's standard error from its own spread (the photons' per-photon variance,
//! the walks' over 32 independent batches); they must agree within 4 joint standard errors, a
//! bound a correct pair of estimators exceeds with probability 6e-5 per comparison (normal
//! errors; 4e-4 for the batches' t distribution of 31 degrees of freedom where the walks' error
//! dominates, which it does nowhere here), under 0.3% over the 43 comparisons.

use glam::{DVec2, DVec3};
use gonio_brdf::fresnel::{dielectric, polarised};
use gonio_brdf::microfacet::Microfacet;
use gonio_coating::flakes::{FlakeLayer, FlakePigment, Flakes, aluminium};
use gonio_coating::interface::{Interface, Lobes, Transport};
use gonio_coating::layered::{Scratch, Walk};
use num_complex::Complex64;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// The complementary error function, W. H. Press et al., *Numerical Recipes* (2nd ed., §6.2,
/// `erfcc`): a Chebyshev fit with fractional error below 1.2e-7 everywhere.
pub(crate) fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * poly.exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// The coating as the photons meet it (docs/coatings.md): a smooth top (Fresnel and Snell) or
/// a rough one, a coat of optical thickness `tau`, metal flakes covering `coverage` of a
/// Lambertian base of reflectance `rho`, their normals Beckmann of rms slope `slope`.
#[derive(Clone)]
pub(crate) struct Stack {
    pub(crate) n: f64,
    pub(crate) tau: f64,
    pub(crate) rough: Option<Interface>,
    pub(crate) coverage: f64,
    slope: f64,
    /// The flakes' index relative to the binder.
    metal: Complex64,
    pub(crate) rho: f64,
    /// False for a mutant that loses the light the top's underside totally reflects.
    tir: bool,
}

impl Stack {
    /// `N(w) = ∫ D(h) max(0, w·h) dω_h`. With the slopes (x, y) Gaussian of variance
    /// slope²/2 each and h ∝ (−x, −y, 1), `D(h) cos θh dω_h` is the slopes' density and
    /// `w·h / cos θh = μ − s` with `s = −(x w.x + y w.y) ~ N(0, σ²)`, `σ = slope sin θ/√2`, so
    /// `N = E[max(0, μ − s)] = μ Φ(μ/σ) + σ φ(μ/σ)`.
    pub(crate) fn projected_area(&self, w: DVec3) -> f64 {
        let mu = w.z;
        let sigma = self.slope * (w.x * w.x + w.y * w.y).sqrt() * FRAC_1_SQRT_2;
        if sigma < 1e-12 {
            return mu.max(0.0);
        }
        let x = mu / sigma;
        mu * 0.5 * erfc(-x * FRAC_1_SQRT_2) + sigma * (-0.5 * x * x).exp() / (2.0 * PI).sqrt()
    }

    /// The coat's transmittance along `d`.
    pub(crate) fn across(&self, d: DVec3) -> f64 {
        if self.tau > 0.0 {
            (-self.tau / d.z.abs()).exp()
        } else {
            1.0
        }
    }

    /// A flake met from direction `w` (pointing away from the flake's face, w.z > 0): its
    /// normal drawn from `D(h) cos θh` and the weight that turns that into the projected area
    /// w meets, `D(h) max(0, w·h)/N(w)`; None for a flake w sees edge-on or from behind.
    pub(crate) fn meet_flake(&self, rng: &mut Pcg64Mcg, w: DVec3) -> Option<(DVec3, f64)> {
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let r = self.slope * (-(1.0 - u1).ln()).sqrt();
        let phi = 2.0 * PI * u2;
        let h = DVec3::new(-r * phi.cos(), -r * phi.sin(), 1.0).normalize();
        let c = w.dot(h);
        (c > 0.0).then(|| (h, c / h.z / self.projected_area(w)))
    }

    /// The flake's reflectance at the local cosine `c`.
    pub(crate) fn reflectance(&self, c: f64) -> f64 {
        polarised(c, self.metal).unpolarised()
    }

    /// One photon arriving from `wi`; `escape` receives the direction and weight of what
    /// leaves after having been inside the coat (the top's own reflection is not counted: the
    /// walks' `eval_body` leaves it out too).
    fn trace(&self, wi: DVec3, rng: &mut Pcg64Mcg, escape: &mut dyn FnMut(DVec3, f64)) {
        let (mut weight, mut d) = match &self.rough {
            None => (1.0 - dielectric(wi.z, self.n), snell(-wi, self.n)),
            Some(top) => {
                let u = DVec2::new(rng.random(), rng.random());
                match top.sample(wi, rng.random(), u, Transport::Importance, Lobes::Both) {
                    Some(s) if s.wi.z < 0.0 => (s.weight(), s.wi),
                    _ => return,
                }
            }
        };
        // A photon loses at least the flakes' absorption (over 8% for aluminium) at each
        // visit, and the top lets out at least 4% of what meets it below the critical angle:
        // after 2000 events what is left is far below the tallies' resolution.
        for _ in 0..2000 {
            // Down across the coat to the flake layer: a flake with probability c.
            weight *= self.across(d);
            if rng.random::<f64>() < self.coverage {
                let w = -d;
                let Some((h, area)) = self.meet_flake(rng, w) else {
                    return;
                };
                let c = w.dot(h);
                let r = 2.0 * c * h - w;
                if r.z <= 0.0 {
                    return;
                }
                // Reflected, and masked by the flakes on its way out (G1 = cos θ / N).
                weight *= area * self.reflectance(c) * r.z / self.projected_area(r);
                d = r;
            } else {
                // The base reflects diffusely; going up, the light meets a flake's underside
                // with probability c, which sends it back to the base.
                loop {
                    weight *= self.rho;
                    if weight == 0.0 {
                        return;
                    }
                    let (u1, u2): (f64, f64) = (rng.random(), rng.random());
                    let s = u1.sqrt();
                    d = DVec3::new(
                        s * (2.0 * PI * u2).cos(),
                        s * (2.0 * PI * u2).sin(),
                        (1.0 - u1).sqrt(),
                    );
                    if rng.random::<f64>() >= self.coverage {
                        break;
                    }
                    let Some((h, area)) = self.meet_flake(rng, d) else {
                        return;
                    };
                    weight *= area * self.reflectance(d.dot(h));
                }
            }
            // Up across the coat to the top's underside.
            weight *= self.across(d);
            match &self.rough {
                None => {
                    if self.n * self.n * (1.0 - d.z * d.z) >= 1.0 {
                        if !self.tir {
                            return;
                        }
                    } else if rng.random::<f64>() >= dielectric(d.z, 1.0 / self.n) {
                        escape(snell(d, 1.0 / self.n), weight);
                        return;
                    }
                    d.z = -d.z;
                }
                Some(top) => {
                    let u = DVec2::new(rng.random(), rng.random());
                    let Some(s) =
                        top.sample(-d, rng.random(), u, Transport::Importance, Lobes::Both)
                    else {
                        return;
                    };
                    weight *= s.weight();
                    if s.wi.z > 0.0 {
                        escape(s.wi, weight);
                        return;
                    }
                    d = s.wi;
                }
            }
        }
    }
}

/// A photon simulation: one photon from `wi`, what escapes after having been inside the coat
/// into `escape` (direction, weight).
pub(crate) trait Photon {
    fn photon(&self, wi: DVec3, rng: &mut Pcg64Mcg, escape: &mut dyn FnMut(DVec3, f64));
}

impl Photon for Stack {
    fn photon(&self, wi: DVec3, rng: &mut Pcg64Mcg, escape: &mut dyn FnMut(DVec3, f64)) {
        self.trace(wi, rng, escape);
    }
}

/// Snell's law at a horizontal interface: `d` (travelling) entering a medium of index `eta`
/// relative to the one it leaves; the caller has checked that it is not totally reflected.
pub(crate) fn snell(d: DVec3, eta: f64) -> DVec3 {
    let (x, y) = (d.x / eta, d.y / eta);
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    DVec3::new(x, y, z.copysign(d.z))
}

/// The in-plane direction at signed polar angle `deg` (positive towards +x, where the light
/// comes from).
pub(crate) fn in_plane(deg: f64) -> DVec3 {
    let t = deg.to_radians();
    DVec3::new(t.sin(), 0.0, t.cos())
}

/// A direction drawn uniformly over the cap of half-angle `delta` about `axis`, with the
/// weight `cos θ / (cos θa (1 + cos δ)/2)` that makes the mean of `f × weight` the cap's
/// projected-solid-angle average of f.
pub(crate) fn in_cone(axis: DVec3, delta: f64, u: DVec2) -> (DVec3, f64) {
    let cos_t = 1.0 - u.x * (1.0 - delta.cos());
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let e1 = DVec3::Y.cross(axis).normalize();
    let e2 = axis.cross(e1);
    let w = axis * cos_t + (e1 * phi.cos() + e2 * phi.sin()) * sin_t;
    (w, w.z / (axis.z * 0.5 * (1.0 + delta.cos())))
}

/// Mean and standard error.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Estimate {
    pub(crate) mean: f64,
    pub(crate) se: f64,
}

/// The photons' estimate of the BRDF averaged over the cones of half-angle `delta` about
/// `views`, for light from `wi`: `photons` photons in 64 chunks of their own random streams
/// (the sum does not depend on the thread count).
pub(crate) fn photons(
    stack: &(impl Photon + Sync),
    wi: DVec3,
    views: &[DVec3],
    delta: f64,
    photons: usize,
) -> Vec<Estimate> {
    let cos_delta = delta.cos();
    let chunks = 64;
    let per = photons / chunks;
    let tallies: Vec<Vec<(f64, f64)>> = (0..chunks)
        .into_par_iter()
        .map(|c| {
            let mut rng = Pcg64Mcg::seed_from_u64(1_000 + c as u64);
            let mut t = vec![(0.0, 0.0); views.len()];
            for _ in 0..per {
                stack.photon(wi, &mut rng, &mut |e, w| {
                    for (k, a) in views.iter().enumerate() {
                        if e.dot(*a) >= cos_delta {
                            t[k].0 += w;
                            t[k].1 += w * w;
                        }
                    }
                });
            }
            t
        })
        .collect();
    let total = (per * chunks) as f64;
    views
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let (s, s2) = tallies
                .iter()
                .fold((0.0, 0.0), |acc, t| (acc.0 + t[k].0, acc.1 + t[k].1));
            let mean = s / total;
            let se = ((s2 / total - mean * mean).max(0.0) / total).sqrt();
            let omega = PI * delta.sin().powi(2) * a.z;
            Estimate {
                mean: mean / omega,
                se: se / omega,
            }
        })
        .collect()
}

/// The walks' estimate of the same averages: `batches` batches of `per_batch` walks, each
/// walk with its own `wo` drawn over the cone ([`in_cone`]) and its own random stream.
pub(crate) fn walks(
    walk: &Walk,
    wi: DVec3,
    views: &[DVec3],
    delta: f64,
    batches: usize,
    per_batch: usize,
) -> Vec<Estimate> {
    views
        .par_iter()
        .enumerate()
        .map(|(k, &axis)| {
            let mut rng = Pcg64Mcg::seed_from_u64(7 + k as u64);
            let mut scratch = Scratch::default();
            let mut out = [0.0];
            let (mut s, mut s2) = (0.0, 0.0);
            for b in 0..batches {
                let mut batch = 0.0;
                for j in 0..per_batch {
                    let (wo, weight) = in_cone(axis, delta, DVec2::new(rng.random(), rng.random()));
                    let seed = ((k * batches + b) * per_batch + j) as u64;
                    walk.eval_body(wo, wi, 1, seed, &mut scratch, &mut out);
                    batch += out[0] * weight;
                }
                let batch = batch / per_batch as f64;
                s += batch;
                s2 += batch * batch;
            }
            let m = batches as f64;
            let mean = s / m;
            Estimate {
                mean,
                se: ((s2 / m - mean * mean).max(0.0) / (m - 1.0)).sqrt(),
            }
        })
        .collect()
}

/// The deviations of the photons from the walks in joint standard errors, printed.
pub(crate) fn compare(
    what: &str,
    ti: f64,
    views: &[f64],
    photons: &[Estimate],
    walks: &[Estimate],
) -> Vec<f64> {
    views
        .iter()
        .zip(photons.iter().zip(walks))
        .map(|(v, (p, w))| {
            let joint = (p.se * p.se + w.se * w.se).sqrt();
            let z = (p.mean - w.mean) / joint;
            eprintln!(
                "{what} θi {ti}° view {v}°: photons {:.5} ± {:.5}, walks {:.5} ± {:.5}: {:+.2}% ({z:+.2}σ)",
                p.mean,
                p.se,
                w.mean,
                w.se,
                100.0 * (p.mean / w.mean - 1.0)
            );
            z
        })
        .collect()
}

/// Aluminium flakes (Hagemann et al.'s index at 550 nm) covering `coverage` of a base of
/// reflectance `rho`, tilt `tilt_deg`, in a binder of index n under `top`, as the photons and
/// as the walk.
pub(crate) fn system(
    top: Option<Microfacet>,
    tau: f64,
    coverage: f64,
    tilt_deg: f64,
    rho: f64,
) -> (Stack, Walk) {
    let (n, lambda) = (1.5, 550.0);
    let (al_n, al_k) = aluminium();
    let flakes = Flakes {
        pigment: FlakePigment::Metal {
            n: al_n.clone(),
            k: al_k.clone(),
        },
        coverage,
        tilt_deg,
        diameter_um: Flakes::DEFAULT_DIAMETER_UM,
        depth: None,
    };
    let interface = Interface::new(n, top);
    let stack = Stack {
        n,
        tau,
        rough: top.map(|_| interface.clone()),
        coverage,
        slope: tilt_deg.to_radians().tan(),
        metal: Complex64::new(al_n.value_at(lambda), al_k.value_at(lambda)) / n,
        rho,
        tir: true,
    };
    let walk = Walk {
        top: interface,
        tau: vec![tau],
        bottom: FlakeLayer::new(&flakes, vec![flakes.optics(n, lambda).unwrap()], vec![rho]),
        basecoat: None,
    };
    (stack, walk)
}

mod slow {
    use super::*;

    const DELTA_DEG: f64 = 3.0;

    /// NIST's SCATMECH configuration of `scatmech_oracle` (aluminium flakes, full coverage,
    /// 10° tilt, n 1.5 over black, smooth top), now with every internal reflection: at 15°,
    /// 45° and 60° illumination, in the plane over the lobe, towards grazing and at the
    /// E2194/E2539 aspecular angles.
    #[test]
    fn smooth_top_walks_equal_the_photons() {
        let (stack, walk) = system(None, 0.0, 1.0, 10.0, 0.0);
        let delta = DELTA_DEG.to_radians();
        for (ti, views) in [
            (
                15.0,
                vec![-80.0, -75.0, -60.0, -45.0, -30.0, -15.0, 0.0, 30.0, 65.0],
            ),
            (
                45.0,
                vec![-80.0, -75.0, -60.0, -30.0, -20.0, 0.0, 30.0, 65.0],
            ),
            (
                60.0,
                vec![-80.0, -75.0, -70.0, -60.0, -45.0, -30.0, 0.0, 30.0],
            ),
        ] {
            let wi = in_plane(ti);
            let axes: Vec<DVec3> = views.iter().map(|&v| in_plane(v)).collect();
            let p = photons(&stack, wi, &axes, delta, 4_000_000);
            let w = walks(&walk, wi, &axes, delta, 32, 1000);
            let z = compare("smooth", ti, &views, &p, &w);
            assert!(z.iter().all(|z| z.abs() < 4.0), "θi {ti}°: {z:?}");
            if ti == 45.0 {
                // The comparison's power: photons that lose what the top totally reflects
                // (as a single-scattering model does) miss the walks by far.
                let mutant = Stack {
                    tir: false,
                    ..stack.clone()
                };
                let p = photons(&mutant, wi, &axes, delta, 4_000_000);
                let z = compare("without TIR", ti, &views, &p, &w);
                let worst = z.iter().fold(0.0f64, |a, z| a.max(z.abs()));
                assert!(worst > 10.0, "the mutant passes: {z:?}");
            }
        }
    }

    /// A rough top (GGX α 0.1, the photons scattered by the interface's own sampler), an
    /// absorbing coat, and flakes over a grey base as in the silver metallic: the walks'
    /// next-event connections through the rough top and their MIS weights, the base's diffuse
    /// light and the flakes' undersides.
    #[test]
    fn rough_top_walks_equal_the_photons() {
        let (stack, walk) = system(Some(Microfacet::ggx(0.1)), 0.05, 0.6, 12.0, 0.25);
        let delta = DELTA_DEG.to_radians();
        for (ti, views) in [
            (15.0, vec![-75.0, -45.0, -15.0, 0.0, 30.0, 65.0]),
            (45.0, vec![-75.0, -60.0, -30.0, -20.0, 0.0, 30.0, 65.0]),
            (60.0, vec![-75.0, -60.0, -30.0, 0.0, 30.0]),
        ] {
            let wi = in_plane(ti);
            let axes: Vec<DVec3> = views.iter().map(|&v| in_plane(v)).collect();
            let p = photons(&stack, wi, &axes, delta, 2_000_000);
            let w = walks(&walk, wi, &axes, delta, 32, 1000);
            let z = compare("rough", ti, &views, &p, &w);
            assert!(z.iter().all(|z| z.abs() < 4.0), "θi {ti}°: {z:?}");
        }
    }
}
