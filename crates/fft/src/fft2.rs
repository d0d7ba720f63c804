//! Two-dimensional real-to-complex FFTs of grids such as height maps (the synthesis of random
//! surfaces and the spectral statistics: autocorrelation, power spectral density), and the
//! cache-friendly parallel transpose they (and the spline's column passes) rely on.
//!
//! Rows are transformed with realfft, then columns with rustfft, each row or column in parallel
//! with rayon. Every row and column is an independent, identical computation, so the result does
//! not depend on the number of threads.

use ndarray::{Array2, ArrayView2};
use num_complex::Complex64;
use rayon::prelude::*;

/// Half spectrum of a real `(ny, nx)` grid, stored transposed: shape `(nx/2 + 1, ny)`, indexed
/// `[kx, ky]`, so that the column transforms run over contiguous memory.
pub struct HalfSpectrum {
    /// Coefficients `[kx, ky]`, unnormalised: `Σ h exp(-2πi (kx ix / nx + ky iy / ny))`.
    pub data: Array2<Complex64>,
    /// Number of grid points along x of the real grid.
    pub nx: usize,
}

/// Forward transform of a real grid of shape `(ny, nx)`.
pub fn forward(h: ArrayView2<f64>) -> HalfSpectrum {
    let (ny, nx) = h.dim();
    let nxh = nx / 2 + 1;
    let h = h.as_standard_layout();
    let src = h.as_slice().expect("standard layout is contiguous");
    let r2c = crate::plan_real_forward(nx);
    let mut rows = vec![Complex64::default(); ny * nxh];
    rows.par_chunks_mut(nxh)
        .zip(src.par_chunks(nx))
        .for_each_init(
            || (r2c.make_input_vec(), r2c.make_scratch_vec()),
            |(input, scratch), (out, row)| {
                input.copy_from_slice(row);
                r2c.process_with_scratch(input, out, scratch)
                    .expect("buffer lengths come from the plan");
            },
        );
    let mut cols = transpose(&rows, ny, nxh);
    let fft = crate::plan_forward(ny);
    cols.par_chunks_mut(ny).for_each_init(
        || vec![Complex64::default(); fft.get_inplace_scratch_len()],
        |scratch, col| fft.process_with_scratch(col, scratch),
    );
    HalfSpectrum {
        data: Array2::from_shape_vec((nxh, ny), cols).expect("shape matches the length"),
        nx,
    }
}

/// Inverse transform, normalised by `1/(nx ny)` so that `inverse(forward(h)) = h`. Returns the
/// real grid of shape `(ny, nx)`. The spectrum is taken to be that of a real grid (Hermitian);
/// the imaginary parts that a real grid cannot have are ignored.
pub fn inverse(spectrum: HalfSpectrum) -> Array2<f64> {
    let HalfSpectrum { data, nx } = spectrum;
    let (nxh, ny) = data.dim();
    let mut cols = data.into_raw_vec_and_offset().0;
    let fft = crate::plan_inverse(ny);
    cols.par_chunks_mut(ny).for_each_init(
        || vec![Complex64::default(); fft.get_inplace_scratch_len()],
        |scratch, col| fft.process_with_scratch(col, scratch),
    );
    let rows = transpose(&cols, nxh, ny);
    let c2r = crate::plan_real_inverse(nx);
    let norm = 1.0 / (nx as f64 * ny as f64);
    let mut out = vec![0.0; ny * nx];
    out.par_chunks_mut(nx)
        .zip(rows.par_chunks(nxh))
        .for_each_init(
            || (c2r.make_input_vec(), c2r.make_scratch_vec()),
            |(input, scratch), (dst, row)| {
                input.copy_from_slice(row);
                input[0].im = 0.0;
                if nx % 2 == 0 {
                    input[nxh - 1].im = 0.0;
                }
                c2r.process_with_scratch(input, dst, scratch)
                    .expect("buffer lengths come from the plan and the edge terms are real");
                dst.iter_mut().for_each(|v| *v *= norm);
            },
        );
    Array2::from_shape_vec((ny, nx), out).expect("shape matches the length")
}

/// Transpose a row-major `rows × cols` matrix, in parallel over bands of output rows and in
/// square tiles, so that both the reads and the writes stay in cache.
pub fn transpose<T: Copy + Default + Send + Sync>(src: &[T], rows: usize, cols: usize) -> Vec<T> {
    let mut dst = vec![T::default(); rows * cols];
    transpose_into(src, rows, cols, &mut dst);
    dst
}

/// [`transpose`] into a buffer of the caller's (`rows * cols` long), so that a computation that
/// transposes many grids of one size reuses one buffer instead of allocating each.
pub fn transpose_into<T: Copy + Send + Sync>(src: &[T], rows: usize, cols: usize, dst: &mut [T]) {
    const TILE: usize = 32;
    assert_eq!(
        src.len(),
        rows * cols,
        "the source holds rows × cols values"
    );
    assert_eq!(
        dst.len(),
        rows * cols,
        "the destination holds rows × cols values"
    );
    if rows == 0 || cols == 0 {
        return;
    }
    dst.par_chunks_mut(rows * TILE)
        .enumerate()
        .for_each(|(band, out)| {
            let c0 = band * TILE;
            let c1 = (c0 + TILE).min(cols);
            for r0 in (0..rows).step_by(TILE) {
                for r in r0..(r0 + TILE).min(rows) {
                    let line = &src[r * cols + c0..r * cols + c1];
                    for (dc, &v) in line.iter().enumerate() {
                        out[dc * rows + r] = v;
                    }
                }
            }
        });
}

/// The transpose of a 2D array, in standard (row-major) layout.
pub fn transposed<T: Copy + Default + Send + Sync>(a: ArrayView2<T>) -> Array2<T> {
    let (rows, cols) = a.dim();
    let a = a.as_standard_layout();
    let data = transpose(
        a.as_slice().expect("standard layout is contiguous"),
        rows,
        cols,
    );
    Array2::from_shape_vec((cols, rows), data).expect("shape matches the length")
}
