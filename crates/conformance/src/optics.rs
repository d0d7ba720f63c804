//! The closed forms the scenes' references come from: Fresnel reflectance of a dielectric, the
//! internal diffuse reflectance of a smooth interface, Kubelka-Munk reflectance of a layer over a
//! substrate, and the radiance of a smooth coat over a diffuse base under a uniform sky.
//!
//! The Fresnel reflectance is gonio's own ([`gonio_brdf::fresnel::dielectric`]); the rest is
//! written here from the sources, not taken from `gonio-coating`, so that the references are an
//! independent computation of what the renderers must reproduce.

/// Unpolarised Fresnel reflectance of light arriving from a medium of index 1 onto a dielectric
/// of relative index `n` (`n < 1`: from inside a denser medium), `cos_i` the cosine of the angle
/// of incidence; 1 beyond the critical angle. It is gonio's one Fresnel formula
/// ([`gonio_brdf::fresnel::dielectric`], Born & Wolf §1.5.2; `docs/physics.md`, "Fresnel"),
/// which the brdf crate's tests hold against tmm: the references' independence lies in their
/// closed forms and quadratures, not in writing the same formula twice.
pub use gonio_brdf::fresnel::dielectric as fresnel;

/// Hemispherical (diffuse) reflectance of the smooth interface for Lambertian light arriving
/// from the medium of index 1 onto relative index `n`:
/// `r = ∫₀^{π/2} F(θ) 2 cos θ sin θ dθ = ∫₀¹ F(μ) 2μ dμ` (Judd 1942; Saunderson 1942 uses it
/// for k1/k2). For the internal reflectance of a coat of index n, pass `1/n`: the light then
/// meets the interface from inside and is totally reflected beyond the critical angle.
/// Composite Gauss-Legendre (8 points on each of 64 panels) in `s`, with `μ = μc + (1 − μc) s²`
/// from the critical cosine μc up: inside, F has a square-root edge at μc (the transmitted
/// cosine `√(μ² − μc²)/n`), which the substitution makes smooth. The balance `n²(1 − r_i) =
/// 1 − r_e` holds to 1e-12 (tested).
pub fn diffuse_reflectance(n: f64) -> f64 {
    let critical = if n < 1.0 { (1.0 - n * n).sqrt() } else { 0.0 };
    // Below the critical cosine F = 1 exactly: ∫₀^μc 2μ dμ = μc².
    let mut sum = critical * critical;
    let panels = 64;
    let h = 1.0 / panels as f64;
    let span = 1.0 - critical;
    for p in 0..panels {
        let a = p as f64 * h;
        for (x, w) in GAUSS8 {
            let t = a + 0.5 * h * (x + 1.0);
            let mu = critical + span * t * t;
            sum += 0.5 * h * w * fresnel(mu, n) * 2.0 * mu * 2.0 * span * t;
        }
    }
    sum
}

/// Nodes and weights of the 8-point Gauss-Legendre rule on [−1, 1] (Abramowitz & Stegun, table
/// 25.4).
const GAUSS8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887),
    (-0.183_434_642_495_65, 0.362_683_783_378_362),
    (0.183_434_642_495_65, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

/// Kubelka-Munk reflectance of a layer of absorption `k` and scattering `s` (per µm),
/// `x_um` thick, over a substrate of reflectance `rg` (Kubelka 1948, JOSA 38, 448, eq. 6):
/// `a = 1 + K/S`, `b = √(a² − 1)`,
/// `R = (1 − rg (a − b coth(bSX))) / (a − rg + b coth(bSX))`. Needs `s > 0`.
pub fn kubelka_munk(k: f64, s: f64, x_um: f64, rg: f64) -> f64 {
    let a = 1.0 + k / s;
    let b = (a * a - 1.0).sqrt();
    let bc = b / (b * s * x_um).tanh();
    (1.0 - rg * (a - bc)) / (a - rg + bc)
}

/// Radiance leaving a smooth coat of index `n` over a Lambertian base of reflectance `rb` (seen
/// from inside the coat), at `cos_v` from the normal, under a uniform sky of radiance `sky`:
///
/// `L(θv) = sky [F(θv) + (1 − F(θv)) rb (1 − r_i)/(1 − rb r_i)]`, `r_i = diffuse_reflectance(1/n)`.
///
/// Derivation (Saunderson, JOSA 32, 727 (1942), for the series of internal reflections; the
/// radiance relations of Judd 1942). The mirror reflects the sky: `F(θv) sky`. The irradiance
/// entering the coat is `π sky (1 − r_e)`, `r_e = diffuse_reflectance(n)`. Let `Lu` be the
/// (Lambertian) radiance going up inside the coat: the base reflects `rb` of the downward
/// irradiance, which is what entered plus what the interface sends back, `π r_i Lu`, so
/// `π Lu = rb (π sky (1 − r_e) + π r_i Lu)`, `Lu = rb sky (1 − r_e)/(1 − rb r_i)`. Leaving at θv
/// the radiance is multiplied by `(1 − F(θv))/n²` (the transmittance, and the cone widening by
/// Snell's law). Energy conservation at the interface for Lambertian light (`n²(1 − r_i) = 1 −
/// r_e`, Stokes' relations integrated over the hemisphere) turns `(1 − r_e)/n²` into `1 − r_i`.
/// Check: `rb = 1` gives `L = sky` at every angle (a white furnace), as it must.
pub fn coat_radiance(cos_v: f64, n: f64, rb: f64, sky: f64) -> f64 {
    let f = fresnel(cos_v, n);
    let ri = diffuse_reflectance(1.0 / n);
    sky * (f + (1.0 - f) * rb * (1.0 - ri) / (1.0 - rb * ri))
}

/// Mitsuba 3's fits of the diffuse Fresnel reflectance (`fresnel_diffuse_reflectance` in
/// `include/mitsuba/render/fresnel.h`), which its `plastic` plugin uses for the internal
/// reflectance (`eta` = 1/n) in place of the integral: for `η < 1` Egan & Hilgeman's (1973)
/// `0.0636/η + η (0.7099 − 1.4399 η) + 0.6681`, else d'Eon & Irving's (2011) polynomial in
/// `x = 1/η`, `0.919317 − 3.4793 x + 6.75335 x² − 7.80989 x³ + 4.98554 x⁴ − 1.36881 x⁵`.
pub fn mitsuba_diffuse_reflectance(eta: f64) -> f64 {
    if eta < 1.0 {
        0.0636 / eta + eta * (0.7099 - 1.4399 * eta) + 0.6681
    } else {
        let x = 1.0 / eta;
        [0.919317, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881]
            .iter()
            .rev()
            .fold(0.0, |acc, c| acc * x + c)
    }
}

/// The radiance of the Lambertian part of a uniform sky's reflection, `ρ sky`: a convex
/// Lambertian object of albedo ρ under a uniform sky of radiance `sky` receives `π sky` on every
/// element (it sees only sky) and reflects `ρ π sky / π` into every direction. The white
/// furnace (ρ = 1) is the classic check of energy conservation (e.g. pbrt-v4 §13.1).
pub fn lambert_under_sky(rho: f64, sky: f64) -> f64 {
    rho * sky
}
