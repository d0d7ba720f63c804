//! The closed forms of `optics` against independent computations.

use gonio_conformance::optics::{
    coat_radiance, diffuse_reflectance, fresnel, kubelka_munk, mitsuba_diffuse_reflectance,
};
use gonio_conformance::scene::COAT;

/// Fresnel's check values of docs/physics.md (n = 1.567 at 20°, 60°, 85°).
#[test]
fn fresnel_check_values() {
    for (deg, r) in [(20.0, 0.04908), (60.0, 0.10006), (85.0, 0.61915)] {
        let got = fresnel(f64::to_radians(deg).cos(), 1.567);
        assert!((got - r).abs() < 5e-6, "{deg}°: {got}");
    }
}

/// The hemispherical reflectances of a smooth interface of index 1.5: external 0.0918 and
/// internal 0.596 (Judd 1942's tables as quoted by Saunderson 1942 and later: 0.092 and 0.596),
/// and the energy balance `n²(1 − r_i) = 1 − r_e` that the coat's closed form relies on.
#[test]
fn diffuse_reflectances_of_an_interface() {
    let re = diffuse_reflectance(1.5);
    let ri = diffuse_reflectance(1.0 / 1.5);
    assert!((re - 0.0918).abs() < 5e-4, "r_e {re}");
    assert!((ri - 0.5963).abs() < 5e-4, "r_i {ri}");
    assert!((2.25 * (1.0 - ri) - (1.0 - re)).abs() < 1e-12, "{re} {ri}");
    // Mitsuba's fit is within 0.3% of the integral here (the loss the suite accounts for).
    let fit = mitsuba_diffuse_reflectance(1.0 / 1.5);
    assert!((fit / ri - 1.0).abs() < 3e-3, "fit {fit} against {ri}");
}

/// The Kubelka-Munk reflectance against gonio-coating's own (written independently).
#[test]
fn kubelka_munk_matches_gonio_coating() {
    let c = gonio_coating::kubelka_munk::Coefficients::new(COAT.k_per_um, COAT.s_per_um).unwrap();
    let theirs = c.reflectance(COAT.thickness_um, COAT.substrate);
    let ours = kubelka_munk(
        COAT.k_per_um,
        COAT.s_per_um,
        COAT.thickness_um,
        COAT.substrate,
    );
    assert!((ours - theirs).abs() < 1e-12, "{ours} {theirs}");
    // Thick: R∞ = 1 + K/S − √((K/S)² + 2K/S).
    let q: f64 = 0.1;
    let rinf = 1.0 + q - (q * q + 2.0 * q).sqrt();
    assert!((kubelka_munk(0.1, 1.0, 1e4, 0.5) - rinf).abs() < 1e-12);
}

/// The coat's closed form under a uniform sky against a numerical quadrature of the radiance:
/// `F(θv) L + ∫ f(θi, θv) L cos θi dω_i`, with f gonio-coating's body BRDF of the same coat (its description parsed, the base's
/// Kubelka-Munk reflectance its own)
/// (its series of internal reflections summed with its own internal reflectance), integrated
/// over the hemisphere by the midpoint rule on 20000 rings of μ = cos θi: within 1e-6.
#[test]
fn coat_closed_form_against_quadrature() {
    let bands = gonio_coating::system::default_bands();
    let stack = gonio_coating::description::parse(&COAT.description(), &bands)
        .unwrap()
        .clear_coat()
        .unwrap();
    let at = stack.at(550.0).unwrap();
    for deg in [0.0, 30.0, 60.0, 80.0] {
        let cv = f64::to_radians(deg).cos();
        let n = 20000;
        let body: f64 = (0..n)
            .map(|k| {
                let mu = (k as f64 + 0.5) / n as f64;
                at.brdf(mu, cv) * mu * 2.0 * std::f64::consts::PI / n as f64
            })
            .sum();
        let numeric = at.specular(cv) + body;
        let closed = coat_radiance(cv, COAT.index, COAT.base_reflectance(), 1.0);
        assert!(
            (numeric - closed).abs() < 1e-6,
            "{deg}°: {numeric} {closed}"
        );
    }
    // A white base is a white furnace at every angle.
    assert!((coat_radiance(0.3, 1.5, 1.0, 2.0) - 2.0).abs() < 1e-12);
}
