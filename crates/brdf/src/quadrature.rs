//! Gauss-Legendre quadrature on an interval, used to integrate BRDFs over instrument apertures,
//! detector cones and hemispheres.
//!
//! Nodes are the roots of the Legendre polynomial P_n found by Newton's iteration from the
//! Tricomi initial guess; weights `2 / ((1 - x²) P_n'(x)²)` (Abramowitz & Stegun 25.4.29).

use std::f64::consts::PI;

/// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1].
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (p, d) = legendre(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() < 1e-15 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// Nodes and weights mapped to [a, b].
pub fn gauss_legendre_on(n: usize, a: f64, b: f64) -> Vec<(f64, f64)> {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    gauss_legendre(n)
        .into_iter()
        .map(|(x, w)| (mid + half * x, half * w))
        .collect()
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    (p1, n as f64 * (x * p1 - p0) / (x * x - 1.0))
}
