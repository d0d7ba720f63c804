//! The two-dimensional transforms against their definition: a round trip returns the grid, and a
//! single Fourier mode lands in its one coefficient with the energy the DFT's definition gives.

use gonio_fft::fft2::{forward, inverse, transpose};
use ndarray::Array2;

#[test]
fn round_trip_and_single_mode() {
    for (ny, nx) in [(6, 8), (5, 7), (1, 4), (4, 1)] {
        let h = Array2::from_shape_fn((ny, nx), |(iy, ix)| {
            ((ix * 7 + iy * 3) % 5) as f64 - 0.3 * iy as f64
        });
        let back = inverse(forward(h.view()));
        for (a, b) in h.iter().zip(back.iter()) {
            assert!((a - b).abs() < 1e-12, "{nx}×{ny}: {a} vs {b}");
        }
    }
    // cos(2π (2 ix / 8 + 1 iy / 6)) has its energy at (kx, ky) = (2, 1) only: nx ny / 2.
    let (ny, nx) = (6, 8);
    let h = Array2::from_shape_fn((ny, nx), |(iy, ix)| {
        (2.0 * std::f64::consts::PI * (2.0 * ix as f64 / 8.0 + iy as f64 / 6.0)).cos()
    });
    let s = forward(h.view());
    for ((kx, ky), v) in s.data.indexed_iter() {
        let expect = if (kx, ky) == (2, 1) { 24.0 } else { 0.0 };
        assert!((v.norm() - expect).abs() < 1e-9, "({kx}, {ky}): {v}");
    }
}

#[test]
fn transpose_of_ragged_tiles() {
    // 70 × 45 is not a multiple of the 32-element tile in either direction.
    let (rows, cols) = (70, 45);
    let src: Vec<usize> = (0..rows * cols).collect();
    let dst = transpose(&src, rows, cols);
    for r in 0..rows {
        for c in 0..cols {
            assert_eq!(dst[c * rows + r], src[r * cols + c]);
        }
    }
}

#[test]
fn one_dimensional_plans_invert_each_other() {
    let n = 12;
    let x: Vec<gonio_fft::Complex64> = (0..n)
        .map(|i| gonio_fft::Complex64::new(i as f64, (i * i % 5) as f64))
        .collect();
    let mut y = x.clone();
    gonio_fft::plan_forward(n).process(&mut y);
    // X_1 = Σ x_n exp(-2πi n / 12), summed directly.
    let direct: gonio_fft::Complex64 = x
        .iter()
        .enumerate()
        .map(|(i, v)| {
            v * gonio_fft::Complex64::from_polar(1.0, -std::f64::consts::TAU * i as f64 / n as f64)
        })
        .sum();
    assert!((y[1] - direct).norm() < 1e-12, "{} vs {direct}", y[1]);
    gonio_fft::plan_inverse(n).process(&mut y);
    for (a, b) in x.iter().zip(&y) {
        assert!((a - b / n as f64).norm() < 1e-12);
    }
}
