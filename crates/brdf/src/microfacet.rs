//! Microfacet normal distributions (Beckmann and GGX/Trowbridge-Reitz, isotropic or
//! anisotropic), their Smith masking, and sampling of the distribution and of the visible
//! normals; shared by the analytic models, the ray-method references and the samplers.
//!
//! Conventions (as in `docs/brdf-models.md`, "Parameter meanings and units"): for Beckmann, `m`
//! is the total rms slope (per-axis rms slope `m/√2`; a Gaussian random surface of rms height
//! `sigma` and correlation length `T` has `m = 2 sigma/T`) and
//! `D(th) = exp(-tan²th/m²) / (π m² cos⁴th)` (Beckmann & Spizzichino 1963), i.e. the roughness
//! `α` of the graphics literature equals `m`. Anisotropic forms take `α_x`, `α_y` along x and y
//! (E. Heitz, "Understanding the masking-shadowing function in microfacet-based BRDFs", JCGT
//! 3(2), 2014, eqs. 71 and 85):
//!
//! - Beckmann: `D = exp(-e) / (π α_x α_y cos⁴θ)`,
//!   `Λ = (erf(a) - 1)/2 + exp(-a²)/(2 a √π)` (eq. 72);
//! - GGX: `D = 1 / (π α_x α_y cos⁴θ (1 + e)²)`, `Λ = (-1 + √(1 + 1/a²))/2` (eq. 86);
//!
//! with `e = tan²θ (cos²φ/α_x² + sin²φ/α_y²)` and `a = 1/(α_φ tanθ)`,
//! `α_φ² = cos²φ α_x² + sin²φ α_y²`. Smith `G1 = 1/(1 + Λ)`; height-correlated
//! `G2 = 1/(1 + Λ(wi) + Λ(wo))` (Heitz 2014, eq. 99).

use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// Which microfacet normal distribution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Distribution {
    /// Gaussian slopes (Beckmann & Spizzichino 1963).
    Beckmann,
    /// Trowbridge-Reitz (1975), called GGX by Walter et al. (2007): long-tailed slopes.
    Ggx,
}

/// A microfacet distribution with its roughness along x and y (equal when isotropic).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Microfacet {
    /// The shape of the slope distribution.
    pub distribution: Distribution,
    /// Roughness `α` along x (Beckmann: `√2 ×` the rms slope along x).
    pub alpha_x: f64,
    /// Roughness `α` along y.
    pub alpha_y: f64,
}

impl Microfacet {
    /// Isotropic Beckmann distribution of total rms slope `m` (`α = m`).
    pub fn beckmann(m: f64) -> Self {
        Microfacet {
            distribution: Distribution::Beckmann,
            alpha_x: m,
            alpha_y: m,
        }
    }

    /// Isotropic GGX (Trowbridge-Reitz) distribution of roughness `alpha`.
    pub fn ggx(alpha: f64) -> Self {
        Microfacet {
            distribution: Distribution::Ggx,
            alpha_x: alpha,
            alpha_y: alpha,
        }
    }

    /// `e = tan²θ (cos²φ/α_x² + sin²φ/α_y²)` for the normal `h` (with `h.z > 0`).
    fn ellipse_tan2(&self, h: DVec3) -> f64 {
        ((h.x / self.alpha_x).powi(2) + (h.y / self.alpha_y).powi(2)) / (h.z * h.z)
    }

    /// The distribution of normals `D(h)` in 1/sr, normalised over projected area
    /// (`∫ D(h) cos θ_h dω_h = 1`); zero for normals facing down.
    pub fn d(&self, h: DVec3) -> f64 {
        if h.z <= 0.0 {
            return 0.0;
        }
        let e = self.ellipse_tan2(h);
        let c4 = (h.z * h.z).powi(2);
        let norm = PI * self.alpha_x * self.alpha_y * c4;
        match self.distribution {
            Distribution::Beckmann => (-e).exp() / norm,
            Distribution::Ggx => 1.0 / (norm * (1.0 + e).powi(2)),
        }
    }

    /// Smith's `Λ` for the direction `w`; infinite below the horizon.
    pub fn lambda(&self, w: DVec3) -> f64 {
        if w.z <= 0.0 {
            return f64::INFINITY;
        }
        // α_φ² tan²θ
        let a2t2 = ((self.alpha_x * w.x).powi(2) + (self.alpha_y * w.y).powi(2)) / (w.z * w.z);
        if a2t2 == 0.0 {
            return 0.0;
        }
        match self.distribution {
            Distribution::Beckmann => beckmann_lambda_a(1.0 / a2t2.sqrt()),
            Distribution::Ggx => 0.5 * ((1.0 + a2t2).sqrt() - 1.0),
        }
    }

    /// Smith masking `G1(w) = 1/(1 + Λ(w))`.
    pub fn g1(&self, w: DVec3) -> f64 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking-shadowing `G2 = 1/(1 + Λ(wi) + Λ(wo))`.
    pub fn g2(&self, wi: DVec3, wo: DVec3) -> f64 {
        self.g2_with(self.lambda(wi), wo)
    }

    /// [`Microfacet::g2`] with `Λ(wi)` already evaluated (`lambda_wi`, from
    /// [`Microfacet::lambda`]): the same value to the bit, for loops over `wo` from one `wi`.
    pub fn g2_with(&self, lambda_wi: f64, wo: DVec3) -> f64 {
        1.0 / (1.0 + lambda_wi + self.lambda(wo))
    }

    /// Sample a normal with pdf `D(h) cos θ_h` (per steradian): draw the slope of the stretched
    /// isotropic α = 1 distribution and scale it (Walter et al., "Microfacet models for
    /// refraction through rough surfaces", EGSR 2007, eqs. 28, 35). Beckmann slope radius
    /// `√(-ln(1 - u))`; GGX `√(u/(1 - u))`.
    pub fn sample_d(&self, u: DVec2) -> DVec3 {
        let r = match self.distribution {
            Distribution::Beckmann => (-(1.0 - u.x).ln()).sqrt(),
            Distribution::Ggx => (u.x / (1.0 - u.x)).sqrt(),
        };
        let phi = 2.0 * PI * u.y;
        let slope = DVec2::new(self.alpha_x * r * phi.cos(), self.alpha_y * r * phi.sin());
        normal_from_slope(slope)
    }

    /// The pdf of [`Microfacet::sample_d`]: `D(h) cos θ_h`.
    pub fn pdf_d(&self, h: DVec3) -> f64 {
        self.d(h) * h.z.max(0.0)
    }

    /// Sample a normal visible from `w` (with `w.z > 0`), with pdf
    /// `D_w(h) = G1(w) max(0, w·h) D(h) / cos θ_w` ([`Microfacet::pdf_visible`]).
    ///
    /// GGX: E. Heitz, "Sampling the GGX distribution of visible normals", JCGT 7(4), 2018,
    /// listing 1. Beckmann: E. Heitz & E. d'Eon, "Importance sampling microfacet-based BSDFs
    /// using the distribution of visible normals", EGSR 2014, with the α = 1 slope sampler of
    /// W. Jakob, "An improved visible normal sampling routine for the Beckmann distribution"
    /// (2014, as in Mitsuba), solved here to f64 accuracy.
    pub fn sample_visible(&self, w: DVec3, u: DVec2) -> DVec3 {
        let stretched = self.stretched(w);
        match self.distribution {
            Distribution::Ggx => {
                let v = stretched;
                let lensq = v.x * v.x + v.y * v.y;
                let t1 = if lensq > 0.0 {
                    DVec3::new(-v.y, v.x, 0.0) / lensq.sqrt()
                } else {
                    DVec3::X
                };
                let t2 = v.cross(t1);
                let r = u.x.sqrt();
                let phi = 2.0 * PI * u.y;
                let p1 = r * phi.cos();
                let s = 0.5 * (1.0 + v.z);
                let p2 = (1.0 - s) * (1.0 - p1 * p1).sqrt() + s * r * phi.sin();
                let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * v;
                DVec3::new(self.alpha_x * nh.x, self.alpha_y * nh.y, nh.z.max(0.0)).normalize()
            }
            Distribution::Beckmann => {
                self.beckmann_visible_normal(stretched, beckmann_visible_slope_11(stretched.z, u))
            }
        }
    }

    /// The normals [`Microfacet::sample_visible`] returns from `w` at the `n × n` stratified
    /// points `u = ((i + ½)/n, (j + ½)/n)`, `i` slowest, each the same to the bit. Beckmann's
    /// visible slopes of the stretched α = 1 distribution are separable away from normal
    /// incidence (the slope in the plane of incidence depends on `u.x` alone, the other on `u.y`
    /// alone), so its grid takes `2n` slope inversions instead of `n²`.
    pub fn sample_visible_stratified(&self, w: DVec3, n: usize) -> Vec<DVec3> {
        let at = |k: usize| (k as f64 + 0.5) / n as f64;
        let stretched = self.stretched(w);
        if self.distribution == Distribution::Ggx || stretched.z > BECKMANN_NORMAL_INCIDENCE {
            return (0..n * n)
                .map(|k| self.sample_visible(w, DVec2::new(at(k / n), at(k % n))))
                .collect();
        }
        let xs: Vec<f64> = (0..n)
            .map(|i| beckmann_visible_slope_x(stretched.z, at(i)))
            .collect();
        let ys: Vec<f64> = (0..n).map(|j| beckmann_slope_y(at(j))).collect();
        xs.iter()
            .flat_map(|&x| {
                ys.iter()
                    .map(move |&y| self.beckmann_visible_normal(stretched, DVec2::new(x, y)))
            })
            .collect()
    }

    /// `w` in the frame where the distribution is isotropic with α = 1, normalised.
    fn stretched(&self, w: DVec3) -> DVec3 {
        DVec3::new(self.alpha_x * w.x, self.alpha_y * w.y, w.z).normalize()
    }

    /// The normal of the Beckmann facet whose α = 1 slope `slope` was drawn in the plane of
    /// incidence of the stretched direction `stretched`: the slope rotated to the frame and
    /// scaled by the roughness.
    fn beckmann_visible_normal(&self, stretched: DVec3, slope: DVec2) -> DVec3 {
        // Rotate from the plane of incidence of the stretched direction to the frame.
        let sin_t = (1.0 - stretched.z * stretched.z).max(0.0).sqrt();
        let (cos_p, sin_p) = if sin_t > 1e-12 {
            (stretched.x / sin_t, stretched.y / sin_t)
        } else {
            (1.0, 0.0)
        };
        let rotated = DVec2::new(
            cos_p * slope.x - sin_p * slope.y,
            sin_p * slope.x + cos_p * slope.y,
        );
        normal_from_slope(DVec2::new(
            self.alpha_x * rotated.x,
            self.alpha_y * rotated.y,
        ))
    }

    /// The GGX normal visible from `w` (with `w.z > 0`) at the point `p` of the unit disk: the
    /// steps of [`Microfacet::sample_visible`] after its uniform point on the disk (Heitz 2018,
    /// listing 1: the half-disk warp `p2 → (1 - s) √(1 - p1²) + s p2`, `s = (1 + v.z)/2`, the
    /// projection onto the hemisphere about the stretched `v = w`, and the unstretch). A uniform
    /// `p` gives normals with density [`Microfacet::pdf_visible`]; any area-preserving map of the
    /// square to the disk can feed it. Beckmann has no such disk; it gets `w`'s own normal, `+z`.
    pub fn visible_normal_on_disk(&self, w: DVec3, p: DVec2) -> DVec3 {
        if self.distribution != Distribution::Ggx {
            return DVec3::Z;
        }
        let v = self.stretched(w);
        let (t1, t2) = visible_frame(v);
        let s = 0.5 * (1.0 + v.z);
        let p2 = (1.0 - s) * (1.0 - p.x * p.x).max(0.0).sqrt() + s * p.y;
        let nh = p.x * t1 + p2 * t2 + (1.0 - p.x * p.x - p2 * p2).max(0.0).sqrt() * v;
        DVec3::new(self.alpha_x * nh.x, self.alpha_y * nh.y, nh.z.max(0.0)).normalize()
    }

    /// The inverse of [`Microfacet::visible_normal_on_disk`]: the point of the unit disk whose
    /// normal seen from `w` is `h`; `None` for Beckmann or a normal not visible from `w`. Stretch
    /// `h`, project it on the frame `(t1, t2)` about the stretched `w`, and undo the half-disk
    /// warp.
    pub fn visible_disk_point(&self, w: DVec3, h: DVec3) -> Option<DVec2> {
        if self.distribution != Distribution::Ggx || w.z <= 0.0 || w.dot(h) <= 0.0 {
            return None;
        }
        let v = self.stretched(w);
        let (t1, t2) = visible_frame(v);
        let nh = DVec3::new(h.x / self.alpha_x, h.y / self.alpha_y, h.z).try_normalize()?;
        let p1 = nh.dot(t1).clamp(-1.0, 1.0);
        let s = 0.5 * (1.0 + v.z);
        let p2 = (nh.dot(t2) - (1.0 - s) * (1.0 - p1 * p1).sqrt()) / s;
        let p = DVec2::new(p1, p2);
        let len = p.length();
        Some(if len > 1.0 { p / len } else { p })
    }

    /// The pdf (per steradian of `h`) of [`Microfacet::sample_visible`] from `w`.
    pub fn pdf_visible(&self, w: DVec3, h: DVec3) -> f64 {
        if w.z <= 0.0 {
            return 0.0;
        }
        self.g1(w) * w.dot(h).max(0.0) * self.d(h) / w.z
    }
}

/// Heitz's (2018) frame about the stretched view `v`: `t1` horizontal and normal to the plane
/// of incidence (`x` at normal incidence), `t2 = v × t1`.
fn visible_frame(v: DVec3) -> (DVec3, DVec3) {
    let lensq = v.x * v.x + v.y * v.y;
    let t1 = if lensq > 0.0 {
        DVec3::new(-v.y, v.x, 0.0) / lensq.sqrt()
    } else {
        DVec3::X
    };
    (t1, v.cross(t1))
}

/// The unit normal of a facet whose height slopes are `slope`: `(-sx, -sy, 1)/|·|`.
fn normal_from_slope(slope: DVec2) -> DVec3 {
    DVec3::new(-slope.x, -slope.y, 1.0).normalize()
}

/// Beckmann `Λ` as a function of `a = 1/(α_φ tan θ)`, written with `erfc` so that it keeps
/// its relative precision where `erf(a) → 1`; it underflows to 0 past `a = 26`.
fn beckmann_lambda_a(a: f64) -> f64 {
    if a > 26.0 {
        return 0.0;
    }
    -0.5 * libm::erfc(a) + (-a * a).exp() / (2.0 * a * PI.sqrt())
}

/// Above this cosine the direction is taken as normal incidence, where the visible slopes of
/// the α = 1 Beckmann distribution are its slopes (radius and azimuth drawn instead).
const BECKMANN_NORMAL_INCIDENCE: f64 = 1.0 - 1e-12;

/// Sample the slopes of the α = 1 Beckmann distribution visible from a direction at
/// `cos_theta` from the normal in the x-z plane (positive x): the x slope from its marginal
/// ([`beckmann_visible_slope_x`]) and the y slope, an independent Gaussian, from `u.y`.
fn beckmann_visible_slope_11(cos_theta: f64, u: DVec2) -> DVec2 {
    if cos_theta > BECKMANN_NORMAL_INCIDENCE {
        let r = (-(1.0 - u.x).ln()).sqrt();
        let phi = 2.0 * PI * u.y;
        return DVec2::new(r * phi.cos(), r * phi.sin());
    }
    DVec2::new(
        beckmann_visible_slope_x(cos_theta, u.x),
        beckmann_slope_y(u.y),
    )
}

/// The x slope (in the plane of incidence) of the α = 1 Beckmann distribution visible from a
/// direction at `cos_theta` (below [`BECKMANN_NORMAL_INCIDENCE`]), from its marginal, whose cdf
/// is `C(x) = (1 + erf x + tanθ/√π e^(-x²)) / (1 + erf(cot θ) + tanθ/√π e^(-cot²θ))` on
/// `x < cot θ`, at `ux`: inverted by Newton steps safeguarded by bisection from Jakob's (2014)
/// fitted first guess.
fn beckmann_visible_slope_x(cos_theta: f64, ux: f64) -> f64 {
    let sin_theta = (1.0 - cos_theta * cos_theta).sqrt();
    let tan_theta = sin_theta / cos_theta;
    let cot_theta = cos_theta / sin_theta;
    let inv_sqrt_pi = 1.0 / PI.sqrt();
    let target = ux.clamp(1e-16, 1.0 - 1e-16);
    let erf_cot = libm::erf(cot_theta);
    let norm = 1.0 / (1.0 + erf_cot + inv_sqrt_pi * tan_theta * (-cot_theta * cot_theta).exp());
    let theta = cos_theta.acos();
    let fit = 1.0 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
    let (mut lo, mut hi) = (-ERFINV_MAX, cot_theta);
    // Jakob's fit is a first guess to a few per cent: erfinv's refinement to double precision
    // would be wasted on it, the Newton steps below refine it.
    let mut x = erfinv_estimate(erf_cot - (1.0 + erf_cot) * (1.0 - target).powf(fit)).clamp(lo, hi);
    for _ in 0..100 {
        let e = (-x * x).exp();
        let value = norm * (1.0 + libm::erf(x) + inv_sqrt_pi * tan_theta * e) - target;
        if value.abs() < 1e-14 {
            break;
        }
        if value > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let step = x - value / (norm * 2.0 * inv_sqrt_pi * e * (1.0 - x * tan_theta));
        x = if step > lo && step < hi {
            step
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo < 1e-14 {
            break;
        }
    }
    x
}

/// The y slope of the visible α = 1 Beckmann distribution at `uy`: a Gaussian of variance ½,
/// independent of the direction.
fn beckmann_slope_y(uy: f64) -> f64 {
    erfinv(2.0 * uy.clamp(1e-300, 1.0 - 1e-16) - 1.0)
}

/// Where [`erfinv`] saturates: `erf(5.9)` rounds to 1 in double precision.
const ERFINV_MAX: f64 = 5.9;

/// Inverse error function on (-1, 1): M. Giles' single-precision approximation ("Approximating
/// the erfinv function", GPU Computing Gems, 2011) refined by two Newton steps on `libm::erf`
/// to double precision. Saturates at ±5.9 (where `erf` rounds to ±1).
pub fn erfinv(y: f64) -> f64 {
    if y <= -1.0 || y >= 1.0 {
        // Saturated.
        return erfinv_estimate(y);
    }
    let mut x = erfinv_estimate(y);
    for _ in 0..2 {
        let err = libm::erf(x) - y;
        x -= err / (2.0 / PI.sqrt() * (-x * x).exp());
    }
    x
}

/// Giles' approximation of [`erfinv`] alone (relative error about 1e-7): a starting point for
/// a solver that refines it anyway.
fn erfinv_estimate(y: f64) -> f64 {
    if y <= -1.0 {
        return -ERFINV_MAX;
    }
    if y >= 1.0 {
        return ERFINV_MAX;
    }
    let w = -((1.0 - y) * (1.0 + y)).ln();
    if w < 5.0 {
        let w = w - 2.5;
        let mut p = 2.810_226_36e-08;
        for c in [
            3.432_739_39e-07,
            -3.523_387_7e-06,
            -4.391_506_54e-06,
            0.000_218_580_87,
            -0.001_253_725_03,
            -0.004_177_681_64,
            0.246_640_727,
            1.501_409_41,
        ] {
            p = c + p * w;
        }
        p * y
    } else {
        let w = w.sqrt() - 3.0;
        let mut p = -0.000_200_214_257;
        for c in [
            0.000_100_950_558,
            0.001_349_343_22,
            -0.003_673_428_44,
            0.005_739_507_73,
            -0.007_622_461_3,
            0.009_438_870_47,
            1.001_674_06,
            2.832_976_82,
        ] {
            p = c + p * w;
        }
        p * y
    }
}

/// Beckmann distribution of normals `D(h)` in 1/sr (projected-area normalised:
/// `∫ D(h) cos th dh = 1`) for a normal at `cos_th` from the macroscopic normal; isotropic
/// total rms slope `m`.
pub fn beckmann_d(cos_th: f64, m: f64) -> f64 {
    Microfacet::beckmann(m).d(in_plane(cos_th))
}

/// Smith's `Λ` for the isotropic Beckmann distribution, for a direction at `cos_t` from the
/// normal.
pub fn beckmann_lambda(cos_t: f64, m: f64) -> f64 {
    Microfacet::beckmann(m).lambda(in_plane(cos_t))
}

/// Smith masking `G1 = 1/(1 + Λ)` of one direction (isotropic Beckmann).
pub fn smith_g1(cos_t: f64, m: f64) -> f64 {
    Microfacet::beckmann(m).g1(in_plane(cos_t))
}

/// Height-correlated masking-shadowing `G2 = 1/(1 + Λ(wi) + Λ(wo))` (isotropic Beckmann).
pub fn smith_g2(cos_i: f64, cos_o: f64, m: f64) -> f64 {
    Microfacet::beckmann(m).g2(in_plane(cos_i), in_plane(cos_o))
}

/// The unit vector in the x-z plane at `cos_t` from +z.
fn in_plane(cos_t: f64) -> DVec3 {
    let c = cos_t.clamp(-1.0, 1.0);
    DVec3::new((1.0 - c * c).sqrt(), 0.0, c)
}
