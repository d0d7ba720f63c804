//! Kubelka-Munk layers: the finite layer against Kubelka's exponential form and his transmittance
//! relation, the limits, energy conservation without absorption, linear mixtures, Saunderson's
//! correction there and back.

use gonio_coating::kubelka_munk::*;

/// Kubelka's exponential form of the same solution (JOSA 38, 448, eq. 6 rearranged with
/// R∞): `R = [(Rg − R∞)/R∞ − R∞ (Rg − 1/R∞) e^{SX(1/R∞ − R∞)}] /
/// [(Rg − R∞) − (Rg − 1/R∞) e^{SX(1/R∞ − R∞)}]`, written here independently of the coth form.
fn exponential_form(k: f64, s: f64, x: f64, rg: f64) -> f64 {
    let q = k / s;
    let r_inf = 1.0 + q - (q * q + 2.0 * q).sqrt();
    let e = (s * x * (1.0 / r_inf - r_inf)).exp();
    ((rg - r_inf) / r_inf - r_inf * (rg - 1.0 / r_inf) * e)
        / ((rg - r_inf) - (rg - 1.0 / r_inf) * e)
}

#[test]
fn finite_layer_equals_kubelkas_exponential_form() {
    for (k, s) in [(0.01, 0.5), (0.2, 0.3), (1.0, 0.05), (0.05, 2.0)] {
        let c = Coefficients::new(k, s).unwrap();
        for x in [0.5, 5.0, 20.0] {
            for rg in [0.0, 0.3, 0.9] {
                let got = c.reflectance(x, rg);
                let want = exponential_form(k, s, x, rg);
                assert!(
                    (got - want).abs() < 1e-9,
                    "K {k} S {s} X {x} Rg {rg}: {got} vs {want}"
                );
            }
        }
    }
}

/// Thick layers reach R∞ = a − b whatever the substrate; no thickness shows the substrate.
#[test]
fn limits() {
    let c = Coefficients::new(0.2, 0.3).unwrap();
    let a: f64 = 1.0 + 0.2 / 0.3;
    let r_inf = a - (a * a - 1.0).sqrt();
    assert!((c.r_infinity() - r_inf).abs() < 1e-15);
    for rg in [0.0, 0.5, 1.0] {
        assert!((c.reflectance(500.0, rg) - r_inf).abs() < 1e-12);
        assert_eq!(c.reflectance(0.0, rg), rg);
    }
}

/// A non-absorbing layer over a black substrate: R = SX/(1 + SX) and T = 1/(1 + SX), which
/// conserve energy, R + T = 1; over a white one it stays white. An absorbing layer loses
/// light: R + T < 1. The series branch meets the coth branch continuously.
#[test]
fn non_absorbing_layer_conserves_energy() {
    let c = Coefficients::new(0.0, 0.4).unwrap();
    for x in [0.1, 1.0, 10.0] {
        let sx = 0.4 * x;
        let (r, t) = (c.reflectance(x, 0.0), c.transmittance(x));
        assert!((r - sx / (1.0 + sx)).abs() < 1e-15, "{r}");
        assert!((r + t - 1.0).abs() < 1e-15);
        assert!((c.reflectance(x, 1.0) - 1.0).abs() < 1e-15);
    }
    let absorbing = Coefficients::new(0.1, 0.4).unwrap();
    assert!(absorbing.reflectance(3.0, 0.0) + absorbing.transmittance(3.0) < 0.99);
    let tiny = Coefficients::new(1e-12, 0.4).unwrap();
    assert!((tiny.reflectance(2.0, 0.2) - c.reflectance(2.0, 0.2)).abs() < 1e-10);
}

/// The transmittance satisfies Kubelka's relation between R, T and R∞ for a layer over a
/// black substrate (JOSA 38, eq. 12c): `T² = (R∞ − R)(1/R∞ − R)`.
#[test]
fn transmittance_obeys_kubelkas_relation() {
    for (k, s, x) in [(0.1, 0.4, 3.0), (0.02, 1.0, 0.7), (0.5, 0.5, 2.0)] {
        let c = Coefficients::new(k, s).unwrap();
        let (r, t, ri) = (c.reflectance(x, 0.0), c.transmittance(x), c.r_infinity());
        assert!(
            (t * t - (ri - r) * (1.0 / ri - r)).abs() < 1e-12,
            "{k} {s} {x}"
        );
    }
}

#[test]
fn mixture_is_linear_and_bad_values_are_refused() {
    let white = Coefficients::new(0.001, 1.2).unwrap();
    let red = Coefficients::new(0.8, 0.1).unwrap();
    let m = Coefficients::mixture(&[(0.7, white), (0.3, red)]).unwrap();
    assert!((m.k - (0.7 * 0.001 + 0.3 * 0.8)).abs() < 1e-15);
    assert!((m.s - (0.7 * 1.2 + 0.3 * 0.1)).abs() < 1e-15);
    assert!(Coefficients::new(-1.0, 1.0).is_err());
    assert!(Coefficients::mixture(&[(f64::NAN, white)]).is_err());
}

#[test]
fn saunderson_round_trip() {
    for r in [0.0, 0.2, 0.7, 1.0] {
        let rm = saunderson(r, 0.04, 0.6);
        assert!((inverse_saunderson(rm, 0.04, 0.6) - r).abs() < 1e-14);
    }
    // A black layer reads the surface's own reflection; a white one reads 1.
    assert_eq!(saunderson(0.0, 0.04, 0.6), 0.04);
    assert!((saunderson(1.0, 0.04, 0.6) - 1.0).abs() < 1e-15);
    // Specular excluded: a black layer reads nothing, a white one all that entered (1 − k1).
    assert_eq!(saunderson_specular_excluded(0.0, 0.04, 0.6), 0.0);
    assert!((saunderson_specular_excluded(1.0, 0.04, 0.6) - 0.96).abs() < 1e-15);
}
