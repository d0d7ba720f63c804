//! gonio-fft: the discrete Fourier transforms gonio uses, in double precision. One-dimensional
//! complex plans (the Kirchhoff engine's grid sums), real-to-complex plans, and the
//! two-dimensional transforms of grids ([`fft2`]).
//!
//! Every plan is made here, by a non-generic function returning a shared trait object, so that
//! rustfft's planner and its algorithms are compiled for `f64` once, in this crate, rather than
//! again in each crate (and each unit-test build) that plans a transform. The transforms
//! themselves are rustfft's and realfft's; nothing numerical is written here.

pub mod fft2;

pub use num_complex::Complex64;
pub use realfft::{ComplexToReal, RealToComplex};
pub use rustfft::Fft;

use std::sync::Arc;

/// A plan for the unnormalised forward complex transform of length `len`,
/// `X_k = Σ_n x_n exp(-2πi k n / len)`.
pub fn plan_forward(len: usize) -> Arc<dyn Fft<f64>> {
    rustfft::FftPlanner::new().plan_fft_forward(len)
}

/// A plan for the unnormalised inverse complex transform of length `len`,
/// `x_n = Σ_k X_k exp(+2πi k n / len)` (no `1/len`).
pub fn plan_inverse(len: usize) -> Arc<dyn Fft<f64>> {
    rustfft::FftPlanner::new().plan_fft_inverse(len)
}

/// A plan for the forward transform of `len` real values into their `len/2 + 1` lowest complex
/// coefficients (unnormalised).
pub fn plan_real_forward(len: usize) -> Arc<dyn RealToComplex<f64>> {
    realfft::RealFftPlanner::new().plan_fft_forward(len)
}

/// A plan for the inverse of [`plan_real_forward`]'s transform (unnormalised: a round trip
/// multiplies by `len`).
pub fn plan_real_inverse(len: usize) -> Arc<dyn ComplexToReal<f64>> {
    realfft::RealFftPlanner::new().plan_fft_inverse(len)
}
