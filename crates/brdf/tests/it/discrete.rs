//! Piecewise-constant distributions: the 1D and 2D densities invert their distributions.

use glam::DVec2;
use gonio_brdf::sampling::discrete::*;

const WEIGHTS: [f64; 6] = [0.5, 3.0, 0.0, 1.25, 2.0, 0.25];

/// The 1D density integrates to 1, is proportional to the weights, and its inversion puts
/// the fraction `w_i / Σw` of stratified uniforms into bin `i`, at positions inside it.
#[test]
fn the_1d_density_inverts_its_distribution() {
    let d = PiecewiseConstant1D::new(&WEIGHTS);
    let n = d.len();
    let integral: f64 = (0..n).map(|i| d.density(i) / n as f64).sum();
    assert!((integral - 1.0).abs() < 1e-12);
    let total: f64 = WEIGHTS.iter().sum();
    assert_eq!(d.total(), total);
    let samples = 60_000;
    let mut counts = [0usize; WEIGHTS.len()];
    for k in 0..samples {
        let (i, x) = d.sample((k as f64 + 0.5) / samples as f64);
        assert!(x >= i as f64 / n as f64 && x < (i + 1) as f64 / n as f64);
        counts[i] += 1;
    }
    for (c, w) in counts.iter().zip(WEIGHTS) {
        assert!((*c as f64 / samples as f64 - w / total).abs() <= 1.0 / samples as f64);
    }
}

/// The 2D density integrates to 1 and equals the normalised weight times the cell count.
#[test]
fn the_2d_density_is_the_normalised_weights() {
    let (w, h) = (3, 2);
    let d = PiecewiseConstant2D::new(&WEIGHTS, w);
    let total: f64 = WEIGHTS.iter().sum();
    let mut integral = 0.0;
    for j in 0..h {
        for i in 0..w {
            let want = WEIGHTS[j * w + i] / total * (w * h) as f64;
            assert!((d.density(i, j) - want).abs() < 1e-12);
            integral += d.density(i, j) / (w * h) as f64;
        }
    }
    assert!((integral - 1.0).abs() < 1e-12);
    let ((i, j), p) = d.sample(DVec2::new(0.7, 0.4));
    assert!(d.density(i, j) > 0.0);
    assert_eq!(
        ((p.x * w as f64) as usize, (p.y * h as f64) as usize),
        (i, j)
    );
}
