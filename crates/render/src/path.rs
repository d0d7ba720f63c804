//! One light path from the camera: unidirectional path tracing with next-event estimation at
//! every surface interaction and multiple importance sampling of light and BRDF samples with the
//! power heuristic (Veach, "Robust Monte Carlo methods for light transport simulation", 1997,
//! §9.2.4, β = 2), BRDF sampling through [`Brdf::sample_compensated`] (with the table samplers'
//! constant part weighted down under an environment map, [`constant_weight`]), and Russian
//! roulette after three bounces (pbrt-v4 §14.5.4).
//!
//! The path is written once for both colour modes: a [`Shading`] says what a path carries (linear
//! sRGB, or the values at the path's wavelengths, [`crate::spectral`]), how a material is
//! evaluated and sampled, and how a light's RGB radiance becomes what the path carries. Every
//! random decision takes the next dimension of the path's [`Sampler`], in the same order in both
//! modes, so that the two modes trace the same directions from the same seed.

use crate::flakes::{FlakeField, MAX_BANDS};
use crate::geometry::{Hit, Ray};
use crate::light::Light;
use crate::material::Material;
use crate::scene::{PrimKind, Scene};
use crate::settings::{BrdfSampling, Settings};
use glam::{DVec2, DVec3, DVec4};
use gonio_brdf::sampling::{Frame, cosine_hemisphere, cosine_hemisphere_pdf};
use gonio_brdf::{Brdf, BrdfSample, Rgb};
use std::ops::{Add, AddAssign, DivAssign, Mul, MulAssign};

/// What a path carries: three colour channels ([`Rgb`]) or four wavelengths ([`DVec4`]).
pub(crate) trait Carried:
    Copy
    + PartialEq
    + Add<Output = Self>
    + AddAssign
    + Mul<Output = Self>
    + MulAssign
    + Mul<f64, Output = Self>
    + DivAssign<f64>
{
    const ZERO: Self;
    const ONE: Self;
    /// The largest component (for Russian roulette).
    fn max_component(self) -> f64;
    /// Every component at least 0.
    fn at_least_zero(self) -> Self;
}

impl Carried for Rgb {
    const ZERO: Self = Rgb::ZERO;
    const ONE: Self = Rgb::ONE;
    fn max_component(self) -> f64 {
        self.max_element()
    }
    fn at_least_zero(self) -> Self {
        self.max(Rgb::ZERO)
    }
}

impl Carried for DVec4 {
    const ZERO: Self = DVec4::ZERO;
    const ONE: Self = DVec4::ONE;
    fn max_component(self) -> f64 {
        self.max_element()
    }
    fn at_least_zero(self) -> Self {
        self.max(DVec4::ZERO)
    }
}

/// How a path evaluates materials and lights.
pub(crate) trait Shading {
    type C: Carried;
    /// A linear sRGB value (a light's radiance, an RGB BRDF value) as carried.
    fn carry_rgb(&self, rgb: Rgb) -> Self::C;
    /// The material's BRDF for the pair (`wo` toward the viewer, `wi` toward the light).
    fn eval(&self, material: &Material, wo: DVec3, wi: DVec3) -> Self::C;
    /// A spectrum given at the bands of `flakes`' glint (a flake's weights, [`Glint::flake`])
    /// as carried.
    ///
    /// [`Glint::flake`]: gonio_coating::glint::Glint::flake
    fn carry_bands(&self, flakes: &FlakeField, values: &[f64]) -> Self::C;
    /// A BRDF sample by `strategy`: the direction, the BRDF value and the pdf.
    fn sample(
        &self,
        material: &Material,
        wo: DVec3,
        u: DVec2,
        strategy: Strategy,
    ) -> Option<(DVec3, Self::C, f64)>;
}

/// The tristimulus shortcut: every material evaluated in linear sRGB (a spectral table through
/// its band weights under D65, [`gonio_brdf::table::BrdfTable::to_rgb`]), colours multiplied
/// channel by channel.
pub(crate) struct Tristimulus;

impl Shading for Tristimulus {
    type C = Rgb;

    fn carry_rgb(&self, rgb: Rgb) -> Rgb {
        rgb
    }

    fn eval(&self, material: &Material, wo: DVec3, wi: DVec3) -> Rgb {
        material.brdf.eval(wo, wi)
    }

    fn carry_bands(&self, flakes: &FlakeField, values: &[f64]) -> Rgb {
        flakes.to_rgb(values)
    }

    fn sample(
        &self,
        material: &Material,
        wo: DVec3,
        u: DVec2,
        strategy: Strategy,
    ) -> Option<(DVec3, Rgb, f64)> {
        sample_brdf(material.brdf.as_ref(), wo, u, strategy).map(|s| (s.wi, s.f, s.pdf))
    }
}

/// 32-bit finaliser of MurmurHash3 (Appleby), mixing the seed and the pixel index.
pub(crate) fn mix(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x85eb_ca6b);
    x ^= x >> 13;
    x = x.wrapping_mul(0xc2b2_ae35);
    x ^ (x >> 16)
}

/// The sample stream of one path: successive dimensions of one Owen-scrambled Sobol sample
/// (Burley 2020), drawn four dimensions at a time (`sobol_burley::sample_4d`, the same values
/// as four calls of `sample`, at about a third of their cost).
pub(crate) struct Sampler {
    /// The sample's index within its pixel.
    index: u32,
    /// The pixel's scramble seed.
    seed: u32,
    /// The next dimension.
    dim: u32,
    /// The set of four dimensions held in `values` (`u32::MAX`: none yet).
    set: u32,
    /// Dimensions `4 set .. 4 set + 4`.
    values: [f32; 4],
}

impl Sampler {
    /// The stream of sample `index` of the pixel scrambled by `seed`, from its first dimension.
    pub(crate) fn new(index: u32, seed: u32) -> Sampler {
        Sampler {
            index,
            seed,
            dim: 0,
            set: u32::MAX,
            values: [0.0; 4],
        }
    }

    /// The sample's index within its pixel.
    pub(crate) fn index(&self) -> u32 {
        self.index
    }

    /// The pixel's scramble seed.
    pub(crate) fn seed(&self) -> u32 {
        self.seed
    }

    pub(crate) fn next(&mut self) -> f64 {
        let d = self.dim;
        self.dim += 1;
        let set = d / 4;
        if set != self.set {
            // Past the 256 dimensions of the tables, continue with freshly seeded sequences.
            let seed = if d < sobol_burley::NUM_DIMENSIONS {
                self.seed
            } else {
                mix(self.seed ^ mix(d / sobol_burley::NUM_DIMENSIONS))
            };
            self.values = sobol_burley::sample_4d(
                self.index,
                set % sobol_burley::NUM_DIMENSION_SETS_4D,
                seed,
            );
            self.set = set;
        }
        f64::from(self.values[(d % 4) as usize])
    }

    pub(crate) fn next2(&mut self) -> DVec2 {
        DVec2::new(self.next(), self.next())
    }
}

/// The power heuristic with β = 2 for a sample of density `a` against a strategy of density `b`.
fn power(a: f64, b: f64) -> f64 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

/// The weight of a table's constant part against its lobe in the BRDF samples of a scene with
/// an environment map ([`Brdf::sample_compensated`]; 1 is sampling in proportion to `f cos θ`).
const COMPENSATED: f64 = 0.25;

/// How a path draws its BRDF samples: the settings' strategy, and the weight the table
/// samplers give their constant part ([`constant_weight`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Strategy {
    pub(crate) how: BrdfSampling,
    pub(crate) constant_weight: f64,
}

impl Strategy {
    /// Importance sampling in proportion to `f cos θ`, uncompensated.
    pub(crate) const IMPORTANCE: Strategy = Strategy {
        how: BrdfSampling::Importance,
        constant_weight: 1.0,
    };
}

/// The weight of a table's constant part in the BRDF samples of a scene lit by `lights`:
/// [`COMPENSATED`] when one of them is an environment map, else 1.
///
/// A table's constant part `c` (the largest constant under it, [`gonio_brdf::table::sampler`])
/// reflects `c ∫ L cos θ dω`. An environment map's light sample draws directions in proportion
/// to `L cos θ` ([`crate::env_guide`]), which samples that exactly, while the BRDF's cosine law
/// sees the map's texture; the lobe's sharp reflections of the map's bright features are found
/// by the BRDF sample alone, which the uncompensated sampler sends there only in proportion to
/// the lobe's share of the energy. So with a map the BRDF samples go to the lobe more often
/// (MIS compensation, Karlík et al. 2019). Measured on the benchmark's sphere
/// (`crates/render/benches/versus_mitsuba.py`, 64 spp, two seeds, against a 4096-spp
/// reference), relative RMSE at weights 1 / 0.5 / 0.25 / 0.1: GGX α 0.05 over a coloured base
/// under the studio map 1.98% / 1.77% / 1.53% / 1.40%, α 0.2 1.41% / – / 1.23% / 1.19%, at the
/// same time per sample; in `gonio booth` (its light an environment map and a distant source;
/// 32 spp, four seeds, 240 × 160) at 0.25 the α 0.05 table's views (45°, near-specular, flank)
/// go 3.4%, 3.1%, 1.8% → 2.3%, 2.2%, 1.5%, the red solid's stay within 0.5% of theirs, and the
/// silver metallic's near-specular and 45° fall 4.0% → 2.7% and 4.6% → 4.0% while its flank
/// rises 5.0% → 5.7% (there the light sample was the better of the two over the flake lobe's
/// broad tail). 0.25 takes most of the gain at the smallest loss.
///
/// Not for other lights. Under a uniform sky the light sample and the BRDF's cosine law both
/// draw the cosine law, each exact for the constant part, so compensation only moves samples
/// away from it: the booth light
/// of the benchmark (a uniform sky and a distant source) went 0.42% → 0.65%. Area and point
/// lights light closed scenes, whose light from other surfaces only BRDF samples find.
pub(crate) fn constant_weight(lights: &[Light]) -> f64 {
    if lights.iter().any(|l| matches!(l, Light::Environment(_))) {
        COMPENSATED
    } else {
        1.0
    }
}

/// A BRDF sample by `strategy`.
pub(crate) fn sample_brdf(
    brdf: &dyn Brdf,
    wo: DVec3,
    u: DVec2,
    strategy: Strategy,
) -> Option<BrdfSample> {
    match strategy.how {
        BrdfSampling::Importance => brdf.sample_compensated(wo, u, strategy.constant_weight),
        BrdfSampling::Cosine => {
            let wi = cosine_hemisphere(u);
            let pdf = cosine_hemisphere_pdf(wi.z);
            (pdf > 0.0).then(|| BrdfSample {
                wi,
                f: brdf.eval(wo, wi),
                pdf,
            })
        }
    }
}

/// The density of [`sample_brdf`].
fn brdf_pdf(brdf: &dyn Brdf, wo: DVec3, wi: DVec3, strategy: Strategy) -> f64 {
    match strategy.how {
        BrdfSampling::Importance => brdf.pdf_compensated(wo, wi, strategy.constant_weight),
        BrdfSampling::Cosine => cosine_hemisphere_pdf(wi.z),
    }
}

/// Two-sided surfaces are shaded on the side a ray in direction `dir` arrives from: the hit's
/// geometric normal and its shading frame (z along the shading normal, x along the tangent),
/// both turned to that side (the geometric normal decides which side it is).
pub(crate) fn facing_frame(hit: &Hit, dir: DVec3) -> (DVec3, Frame) {
    let (ng, ns) = if hit.ng.dot(dir) > 0.0 {
        (-hit.ng, -hit.ns)
    } else {
        (hit.ng, hit.ns)
    };
    let frame = Frame {
        s: hit.tangent,
        t: ns.cross(hit.tangent),
        n: ns,
    };
    (ng, frame)
}

/// A point just off the surface on the side of `n`, so that a ray from it does not hit the
/// surface it leaves.
pub(crate) fn offset(p: DVec3, n: DVec3) -> DVec3 {
    p + n * (1e-7 * (1.0 + p.abs().max_element()))
}

/// What a light sample needs of the surface interaction it lights.
struct Interaction<'a, C> {
    /// The hit point.
    p: DVec3,
    /// The point rays leave from (off the surface on the side of `ng`).
    origin: DVec3,
    /// The geometric normal, on the side the path arrived from.
    ng: DVec3,
    /// The shading frame.
    frame: Frame,
    /// Toward the viewer, local frame.
    wo: DVec3,
    /// The material.
    material: &'a Material,
    /// The probability that the path continues by sampling the BRDF (1 − F under a smooth
    /// coat, whose mirror takes the rest; 1 without one).
    body_share: f64,
    /// Under discrete flakes, the share of the coating's light from inside that this point
    /// lets through to the viewer ([`gonio_coating::glint::Glint::body_scale`]): the base
    /// between the flakes, not through a metal flake.
    body_scale: Option<C>,
}

impl<C: Carried> Interaction<'_, C> {
    /// The material's BRDF `f` for the pair (`wo`, `wi`) as this point shows it: under
    /// discrete flakes, the top's own reflection as it is and the rest scaled by
    /// `body_scale` (kept non-negative where the table's interpolation dips under the top's
    /// exact reflection).
    fn shown<S: Shading<C = C>>(&self, shading: &S, f: C, wi: DVec3) -> C {
        match (&self.body_scale, &self.material.flakes) {
            (Some(scale), Some(flakes)) => {
                let top = shading.carry_rgb(Rgb::splat(flakes.glint().top_reflection(self.wo, wi)));
                ((f + top * -1.0) * *scale + top).at_least_zero()
            }
            _ => f,
        }
    }
}

/// Mixed into a pixel's scramble seed for the sampler of the coat's mirror split off at the
/// first interaction ([`radiance`]).
const MIRROR_STREAM: u32 = 0x6d69_7272;

/// The probability of following a discrete flake's mirror, where there is one, rather than
/// sampling the BRDF (of what a smooth coat's mirror leaves): a flake's glint and the body's
/// reflection are of the same order.
const GLINT_SHARE: f64 = 0.5;

/// The weight of a light's emission that a BRDF sample of density `brdf_pdf` found (`None`: a
/// camera ray, which no light sample could have found): the power heuristic against the light
/// sample that could have, of density `light_pdf()` (called only when needed).
fn emission_weight(brdf_pdf: Option<f64>, light_pdf: impl FnOnce() -> f64) -> f64 {
    brdf_pdf.map_or(1.0, |pdf| power(pdf, light_pdf()))
}

/// Next-event estimation (pbrt-v4's `SampleLd`): one light chosen uniformly, sampled toward the
/// interaction, its reflected radiance when unoccluded (before the path's throughput), weighted
/// against the BRDF sample that could have found it. `last`: no BRDF sample follows (the
/// longest path), so the light sample takes the full weight. Draws three dimensions of the
/// sampler whether or not the scene has lights, so that paths stay in step.
fn sample_ld<S: Shading>(
    scene: &Scene,
    shading: &S,
    at: &Interaction<S::C>,
    strategy: Strategy,
    last: bool,
    sampler: &mut Sampler,
    rays: &mut u64,
) -> S::C {
    let n_lights = scene.lights.len();
    if n_lights == 0 {
        sampler.next();
        sampler.next2();
        return S::C::ZERO;
    }
    let p_select = 1.0 / n_lights as f64;
    let k = ((sampler.next() * n_lights as f64) as usize).min(n_lights - 1);
    let u = sampler.next2();
    let Some(ls) = scene.lights[k].sample(at.p, at.frame.n, u, scene.accel.shapes()) else {
        return S::C::ZERO;
    };
    let wi = at.frame.to_local(ls.wi);
    if !(wi.z > 0.0 && ls.wi.dot(at.ng) > 0.0 && ls.li != Rgb::ZERO && ls.pdf > 0.0) {
        return S::C::ZERO;
    }
    let f = at.shown(shading, shading.eval(at.material, at.wo, wi), wi);
    if f == S::C::ZERO {
        return S::C::ZERO;
    }
    *rays += 1;
    let shadow = Ray {
        origin: at.origin,
        dir: ls.wi,
    };
    // Stop short of the light itself (the origin is offset too).
    let t_max = if ls.dist.is_finite() {
        ls.dist * (1.0 - 1e-5)
    } else {
        f64::INFINITY
    };
    if scene.accel.occluded(&shadow, 0.0, t_max) {
        return S::C::ZERO;
    }
    let pdf_l = p_select * ls.pdf;
    let w = if ls.delta || last {
        1.0
    } else {
        power(
            pdf_l,
            at.body_share * brdf_pdf(at.material.brdf.as_ref(), at.wo, wi, strategy),
        )
    };
    f * shading.carry_rgb(ls.li) * (wi.z * w / pdf_l)
}

/// Radiance along `ray`, as `shading` carries it: at each interaction a light sample
/// ([`sample_ld`]) and a BRDF sample that continues the path, whose emission found on the way is
/// weighted against the light sample ([`emission_weight`]).
///
/// At the camera ray's first interaction a smooth coat's mirror is split off rather than chosen
/// with probability F: its reflection is traced as a path of its own (from the same pixel
/// sample, on a sampler of its own) and added with weight F, and the path goes on by the lobes
/// beneath. Chosen with probability F, the mirror put the whole radiance of the mirrored
/// surroundings into a few samples per pixel: in the viewing booth, a red solid's pixels had
/// 17% luminance noise at 32 samples, and 2.6% with the mirror off (`docs/performance.md`).
/// Splitting is Russian roulette's opposite (Arvo & Kirk, "Particle transport and image
/// synthesis", SIGGRAPH 1990, §4): one more path per camera sample on coated surfaces.
pub(crate) fn radiance<S: Shading>(
    scene: &Scene,
    opts: &Settings,
    shading: &S,
    ray: Ray,
    sampler: &mut Sampler,
    rays: &mut u64,
) -> S::C {
    trace(scene, opts, shading, ray, sampler, rays, 0, true)
}

/// The path of [`radiance`] from interaction `first` on (the count Russian roulette and the
/// longest path go by), splitting a smooth coat's mirror off at its first interaction when
/// `split`.
#[allow(clippy::too_many_arguments)]
fn trace<S: Shading>(
    scene: &Scene,
    opts: &Settings,
    shading: &S,
    mut ray: Ray,
    sampler: &mut Sampler,
    rays: &mut u64,
    first: u32,
    split: bool,
) -> S::C {
    let shapes = scene.accel.shapes();
    let p_select = 1.0 / scene.lights.len().max(1) as f64;
    let strategy = Strategy {
        how: opts.sampling,
        constant_weight: constant_weight(&scene.lights),
    };
    let mut l = S::C::ZERO;
    let mut beta = S::C::ONE;
    // Density of the BRDF sample that produced `ray` (None: a camera ray).
    let mut prev_pdf: Option<f64> = None;
    let mut prev_p = ray.origin;
    // The shading normal there (the light samples' density depends on it).
    let mut prev_n = DVec3::Z;
    for bounce in first..=opts.max_bounces {
        *rays += 1;
        let Some(hit) = scene.accel.intersect(&ray, 0.0, f64::INFINITY) else {
            for light in scene.lights.iter().filter(|l| l.is_infinite()) {
                let le = shading.carry_rgb(light.le(ray.dir));
                let w = emission_weight(prev_pdf, || {
                    p_select * light.pdf(prev_p, prev_n, ray.dir, DVec3::ZERO, shapes)
                });
                l += beta * le * w;
            }
            break;
        };
        let material = match scene.prims[hit.prim] {
            PrimKind::Emitter(k) => {
                let light = &scene.lights[k];
                let le = shading.carry_rgb(light.emitted(hit.ng, ray.dir));
                let w = emission_weight(prev_pdf, || {
                    p_select * light.pdf(prev_p, prev_n, ray.dir, hit.p, shapes)
                });
                l += beta * le * w;
                break;
            }
            PrimKind::Surface(m) => &scene.materials[m],
        };
        let (ng, frame) = crate::mesoscale::shading_frame(scene, material, &hit, ray.dir);
        let wo = frame.to_local(-ray.dir);
        if wo.z <= 0.0 {
            break;
        }
        let last = bounce == opts.max_bounces;
        // The coat's mirror: split off here (the path goes on by the lobes beneath), or one of
        // the lobes the path chooses among.
        let coat_mirror = material.mirror(wo.z);
        let split_here = split && bounce == first && coat_mirror > 0.0 && !last;
        let mirror = if split_here { 0.0 } else { coat_mirror };
        // Discrete flakes: the flake under the point (or a gap), the direction it mirrors
        // and its weight (unless the field leaves its glint to the caller), and what the
        // point lets through of the light from inside.
        let mut glint = None;
        let mut body_scale = None;
        if let Some(flakes) = &material.flakes {
            let flake = flakes.flake_at(flakes.under(hit.p, &frame, wo));
            let mut bands = [0.0; MAX_BANDS];
            let bands = &mut bands[..flakes.glint().wavelengths_nm().len()];
            flakes
                .glint()
                .body_scale(wo, flake.map(|f| f.normal), bands);
            body_scale = Some(shading.carry_bands(flakes, bands));
            if let Some(flake) = flake.filter(|_| flakes.glints())
                && let Some(wi) = flakes.glint().flake(wo, flake.normal, bands)
            {
                glint = Some((wi, shading.carry_bands(flakes, bands)));
            }
        }
        let glint_share = if glint.is_some() {
            GLINT_SHARE * (1.0 - mirror)
        } else {
            0.0
        };
        let at = Interaction {
            p: hit.p,
            origin: offset(hit.p, ng),
            ng,
            frame,
            wo,
            material,
            body_share: 1.0 - mirror - glint_share,
            body_scale,
        };
        l += beta * sample_ld(scene, shading, &at, strategy, last, sampler, rays);
        if split_here {
            let wi = frame.to_world(DVec3::new(-wo.x, -wo.y, wo.z));
            if wi.dot(ng) > 0.0 {
                let mut own = Sampler::new(sampler.index(), mix(sampler.seed() ^ MIRROR_STREAM));
                let mirrored = Ray {
                    origin: at.origin,
                    dir: wi.normalize(),
                };
                let lm = trace(
                    scene,
                    opts,
                    shading,
                    mirrored,
                    &mut own,
                    rays,
                    bounce + 1,
                    false,
                );
                l += beta * lm * coat_mirror;
            }
        }
        if last {
            break;
        }

        // Continue the path: a smooth coat's mirror with probability F (its weight F / F = 1;
        // no light sample can find a delta, so the emission it meets takes the full weight),
        // a discrete flake's mirror with probability `glint_share` (its weight over that; a
        // delta too), else by sampling the BRDF beneath (its density scaled by the rest).
        // Only a coated or flaked material draws the lobe's number, so other paths keep their
        // random stream; it draws the BRDF sample's two whichever lobe it takes, so its paths
        // stay in step.
        let lobe = (material.coat.is_some() || material.flakes.is_some()).then(|| sampler.next());
        let u = sampler.next2();
        let (wi, pdf) = if lobe.is_some_and(|x| x < mirror) {
            (DVec3::new(-wo.x, -wo.y, wo.z), None)
        } else if let Some((wi, weight)) =
            glint.filter(|_| lobe.is_some_and(|x| x < mirror + glint_share))
        {
            beta *= weight * (1.0 / glint_share);
            (wi, None)
        } else {
            let Some((wi, f, pdf)) = shading.sample(material, wo, u, strategy) else {
                break;
            };
            let f = at.shown(shading, f, wi);
            let pdf = pdf * at.body_share;
            if pdf <= 0.0 {
                break;
            }
            beta *= f * (wi.z / pdf);
            (wi, Some(pdf))
        };
        let wi_world = frame.to_world(wi);
        if wi.z <= 0.0 || wi_world.dot(ng) <= 0.0 {
            break;
        }
        prev_pdf = pdf;
        prev_p = hit.p;
        prev_n = frame.n;
        ray = Ray {
            origin: at.origin,
            dir: wi_world.normalize(),
        };
        let u_rr = sampler.next();
        if bounce >= 3 {
            let q = beta.max_component().min(0.95);
            if u_rr >= q || q.is_nan() {
                break;
            }
            beta /= q;
        }
    }
    l
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stream drawn four dimensions at a time gives each dimension's own
    /// `sobol_burley::sample`, past the tables' 256 dimensions too (where each further 256 take
    /// a fresh seed).
    #[test]
    fn stream_by_fours_is_the_per_dimension_sample() {
        for (index, seed) in [(0, 1), (5, 0x1234_5678), (1023, 99)] {
            let mut s = Sampler::new(index, seed);
            for d in 0..700u32 {
                let seed = if d < sobol_burley::NUM_DIMENSIONS {
                    seed
                } else {
                    mix(seed ^ mix(d / sobol_burley::NUM_DIMENSIONS))
                };
                let own = sobol_burley::sample(index, d % sobol_burley::NUM_DIMENSIONS, seed);
                assert_eq!(s.next(), f64::from(own), "index {index} dimension {d}");
            }
        }
    }
}
