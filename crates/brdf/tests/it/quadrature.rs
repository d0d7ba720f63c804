//! Gauss-Legendre quadrature is exact for polynomials of its degree.

use gonio_brdf::quadrature::*;
use std::f64::consts::PI;

/// An n-point rule integrates polynomials of degree 2n-1 exactly.
#[test]
fn exact_for_polynomials() {
    for n in [1, 2, 5, 16, 40] {
        let rule = gauss_legendre(n);
        let deg = 2 * n - 1;
        let sum: f64 = rule.iter().map(|&(x, w)| w * x.powi(deg as i32 - 1)).sum();
        let exact = if (deg - 1) % 2 == 0 {
            2.0 / deg as f64
        } else {
            0.0
        };
        assert!((sum - exact).abs() < 1e-13, "n={n}: {sum} vs {exact}");
    }
    let s: f64 = gauss_legendre_on(20, 0.0, PI)
        .iter()
        .map(|&(x, w)| w * x.sin())
        .sum();
    assert!((s - 2.0).abs() < 1e-13);
}
