//! The inner loop of the Kirchhoff sum: the contribution of each facet of one row to the field,
//! `A_j exp(i phi_j)`, with a branch-free polynomial sine and cosine that the compiler vectorises
//! (4 lanes with AVX2, selected at run time; 2 lanes with the baseline SSE2). Both paths perform
//! the same IEEE operations in the same order, so the result does not depend on the CPU.

use num_complex::Complex64;
use std::f64::consts::FRAC_2_PI;

/// Adding and subtracting 1.5·2⁵² rounds an f64 of magnitude below 2⁵¹ to the nearest integer
/// without a call to `round` (which the baseline x86-64 target cannot vectorise).
const ROUND_MAGIC: f64 = 6_755_399_441_055_744.0;

/// π/2 in three parts for Cody-Waite reduction (fdlibm's `pio2_1`, `pio2_2`, `pio2_3`): the first
/// two have 33 significant bits, so `q · part` is exact for |q| < 2²⁰ (phases up to 1.6·10⁶ rad).
const PIO2_1: f64 = 1.570_796_326_734_125_6;
const PIO2_2: f64 = 6.077_100_506_303_966e-11;
const PIO2_3: f64 = 2.022_266_248_711_166_5e-21;

/// Reduction of `x` to `r = x - q π/2` with |r| ≤ π/4 (Cody-Waite with three parts), and the
/// bits of `q + 1.5·2⁵²`, whose two lowest bits are `q mod 4` (also for negative `q`, as 2⁵¹ is a
/// multiple of 4). Everything after is integer masking, with no branch.
#[inline(always)]
fn reduce(x: f64) -> (f64, u64) {
    let t = x * FRAC_2_PI + ROUND_MAGIC;
    let q = t - ROUND_MAGIC;
    let r = ((x - q * PIO2_1) - q * PIO2_2) - q * PIO2_3;
    (r, t.to_bits())
}

/// `a` where the mask is all ones, `b` where it is zero.
#[inline(always)]
fn blend(mask: u64, a: f64, b: f64) -> f64 {
    f64::from_bits((a.to_bits() & mask) | (b.to_bits() & !mask))
}

/// `v` with its sign flipped when bit 1 of `q` is set.
#[inline(always)]
fn flip(v: f64, q: u64) -> f64 {
    f64::from_bits(v.to_bits() ^ ((q & 2) << 62))
}

/// Taylor polynomials of sine (degree 13) and cosine (degree 14) on |r| ≤ π/4, truncation errors
/// (π/4)¹⁵/15! ≈ 2·10⁻¹⁴ and (π/4)¹⁶/16! ≈ 10⁻¹⁵.
#[inline(always)]
fn sin_poly(r: f64) -> f64 {
    let r2 = r * r;
    r + r
        * r2
        * (-1.0 / 6.0
            + r2 * (1.0 / 120.0
                + r2 * (-1.0 / 5040.0
                    + r2 * (1.0 / 362_880.0
                        + r2 * (-1.0 / 39_916_800.0 + r2 * (1.0 / 6_227_020_800.0))))))
}

#[inline(always)]
fn cos_poly(r: f64) -> f64 {
    let r2 = r * r;
    1.0 + r2
        * (-0.5
            + r2 * (1.0 / 24.0
                + r2 * (-1.0 / 720.0
                    + r2 * (1.0 / 40_320.0
                        + r2 * (-1.0 / 3_628_800.0
                            + r2 * (1.0 / 479_001_600.0 + r2 * (-1.0 / 87_178_291_200.0)))))))
}

/// `(sin x, cos x)` to about 2·10⁻¹⁴ absolute for |x| < 1.6·10⁶: in quadrant `q` they are
/// `(±sin r, ±cos r)` or, for odd `q`, `(±cos r, ∓sin r)`.
#[inline(always)]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    let (r, q) = reduce(x);
    let (s, c) = (sin_poly(r), cos_poly(r));
    let odd = (q & 1).wrapping_neg();
    (
        flip(blend(odd, c, s), q),
        flip(blend(odd, s, c), q.wrapping_add(1)),
    )
}

/// `sin x` alone, as accurate as [`sin_cos`].
#[inline(always)]
fn sin(x: f64) -> f64 {
    let (r, q) = reduce(x);
    flip(blend((q & 1).wrapping_neg(), cos_poly(r), sin_poly(r)), q)
}

/// `sin(z)/z`, 1 at 0 (series below |z| = 10⁻³, where its error is below 10⁻¹⁸).
#[inline(always)]
pub(crate) fn sinc(z: f64) -> f64 {
    let z2 = z * z;
    let series = 1.0 - z2 * (1.0 / 6.0) * (1.0 - z2 * (1.0 / 20.0));
    let ratio = sin(z) / z;
    if z.abs() < 1e-3 { series } else { ratio }
}

/// One row of facets, structure-of-arrays: centred height, slopes and window weight per cell.
pub(crate) struct RowCells<'a> {
    pub h: &'a [f64],
    pub hx: &'a [f64],
    pub hy: &'a [f64],
    pub w: &'a [f64],
}

/// Constants of one row for one wave vector `v` (phase) and `vs` (the sinc factors).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowParams {
    /// `vz` of the phase.
    pub vz: f64,
    /// Phase of cell 0 from `vx x + vy y`.
    pub phase0: f64,
    /// Increment of that phase from one cell to the next (`vx · ax`).
    pub dphase: f64,
    /// Sinc arguments `(vsx + vsz hx) ax/2` = `sx0 + sx1 hx`, likewise along y.
    pub sx0: f64,
    pub sx1: f64,
    pub sy0: f64,
    pub sy1: f64,
    /// Cell area `ax · ay`.
    pub area: f64,
}

/// `out[n] = area · w[n] · sinc(sx0 + sx1 hx[n]) · sinc(sy0 + sy1 hy[n])
///           · exp(i (vz h[n] + phase0 + n dphase))`: the exact integral of the window-weighted
/// phase factor over facet `n`, taken as the tangent plane of the surface at its centre.
pub(crate) fn fill_row(cells: &RowCells, p: &RowParams, out: &mut [Complex64]) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the running CPU supports AVX2 (checked just above).
            unsafe { fill_row_avx2(cells, p, out) };
            return;
        }
    }
    fill_row_generic(cells, p, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn fill_row_avx2(cells: &RowCells, p: &RowParams, out: &mut [Complex64]) {
    fill_row_generic(cells, p, out);
}

/// Facet `c`'s contribution with the linear phase `linear` already formed.
#[inline(always)]
fn facet(cells: &RowCells, p: &RowParams, c: usize, linear: f64) -> Complex64 {
    let amplitude =
        p.area * cells.w[c] * sinc(p.sx0 + p.sx1 * cells.hx[c]) * sinc(p.sy0 + p.sy1 * cells.hy[c]);
    let (s, co) = sin_cos(p.vz * cells.h[c] + linear);
    Complex64::new(amplitude * co, amplitude * s)
}

/// Cells outside the spot (window `w` = 0) at both ends of a row contribute nothing: their terms
/// in `out` are set to zero, and the range `start..end` of the cells between them is returned.
#[inline(always)]
fn zero_outside_the_spot(w: &[f64], out: &mut [Complex64]) -> (usize, usize) {
    let n = out.len();
    let start = w[..n].iter().position(|&w| w > 0.0).unwrap_or(n);
    let end = w[..n]
        .iter()
        .rposition(|&w| w > 0.0)
        .map_or(start, |i| i + 1);
    out[..start].fill(Complex64::default());
    out[end..].fill(Complex64::default());
    (start, end)
}

#[inline(always)]
fn fill_row_generic(cells: &RowCells, p: &RowParams, out: &mut [Complex64]) {
    let (start, end) = zero_outside_the_spot(cells.w, out);
    // Blocks of four facets written as fixed-size arrays, which the compiler maps onto vector
    // registers; the linear phase advances by a constant per block instead of converting each
    // index to a float (which SSE2 and AVX2 cannot do packed).
    let body = start + (end - start) / 4 * 4;
    let step = [0.0, p.dphase, 2.0 * p.dphase, 3.0 * p.dphase];
    let (h, hx, hy, w) = (
        &cells.h[start..body],
        &cells.hx[start..body],
        &cells.hy[start..body],
        &cells.w[start..body],
    );
    let mut x0 = p.phase0 + start as f64 * p.dphase;
    for ((((o, h), hx), hy), w) in out[start..body]
        .chunks_exact_mut(4)
        .zip(h.chunks_exact(4))
        .zip(hx.chunks_exact(4))
        .zip(hy.chunks_exact(4))
        .zip(w.chunks_exact(4))
    {
        let mut re = [0.0; 4];
        let mut im = [0.0; 4];
        for j in 0..4 {
            let amplitude =
                p.area * w[j] * sinc(p.sx0 + p.sx1 * hx[j]) * sinc(p.sy0 + p.sy1 * hy[j]);
            let (s, c) = sin_cos(p.vz * h[j] + (x0 + step[j]));
            re[j] = amplitude * c;
            im[j] = amplitude * s;
        }
        for j in 0..4 {
            o[j] = Complex64::new(re[j], im[j]);
        }
        x0 += 4.0 * p.dphase;
    }
    for (c, o) in out.iter_mut().enumerate().take(end).skip(body) {
        *o = facet(cells, p, c, x0 + (c - body) as f64 * p.dphase);
    }
}

/// `out[n] = area · w[n] · exp(i vz h[n])`: the terms of the plain sampled sum that the
/// full-hemisphere FFTs transform (no linear phase, which the FFT supplies, and no sinc factors).
pub(crate) fn fill_row_sampled(h: &[f64], w: &[f64], vz: f64, area: f64, out: &mut [Complex64]) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the running CPU supports AVX2 (checked just above).
            unsafe { fill_row_sampled_avx2(h, w, vz, area, out) };
            return;
        }
    }
    fill_row_sampled_generic(h, w, vz, area, out);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn fill_row_sampled_avx2(h: &[f64], w: &[f64], vz: f64, area: f64, out: &mut [Complex64]) {
    fill_row_sampled_generic(h, w, vz, area, out);
}

#[inline(always)]
fn fill_row_sampled_generic(h: &[f64], w: &[f64], vz: f64, area: f64, out: &mut [Complex64]) {
    let (start, end) = zero_outside_the_spot(w, out);
    // Blocks of four, as in `fill_row_generic`, for the vector registers.
    let body = start + (end - start) / 4 * 4;
    for ((o, h), w) in out[start..body]
        .chunks_exact_mut(4)
        .zip(h[start..body].chunks_exact(4))
        .zip(w[start..body].chunks_exact(4))
    {
        let mut re = [0.0; 4];
        let mut im = [0.0; 4];
        for j in 0..4 {
            let (s, c) = sin_cos(vz * h[j]);
            re[j] = area * w[j] * c;
            im[j] = area * w[j] * s;
        }
        for j in 0..4 {
            o[j] = Complex64::new(re[j], im[j]);
        }
    }
    for c in body..end {
        let (s, co) = sin_cos(vz * h[c]);
        out[c] = Complex64::new(area * w[c] * co, area * w[c] * s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_matches_std() {
        let mut worst: f64 = 0.0;
        for i in 0..200_001 {
            let x = (i as f64 - 100_000.0) * 0.0137 + 1e-3 * (i % 7) as f64;
            let (s, c) = sin_cos(x);
            worst = worst.max((s - x.sin()).abs()).max((c - x.cos()).abs());
        }
        for x in [0.0, 1e-300, -1e-8, 1e5 + 0.3, -1.2e6] {
            let (s, c) = sin_cos(x);
            worst = worst.max((s - x.sin()).abs()).max((c - x.cos()).abs());
        }
        assert!(worst < 3e-14, "{worst}");
    }

    #[test]
    fn sinc_is_continuous() {
        for z in [0.0, 1e-9, 0.999e-3, 1.001e-3, 0.5, -3.0, 40.0] {
            let exact = if z == 0.0 { 1.0 } else { f64::sin(z) / z };
            assert!((sinc(z) - exact).abs() < 1e-15, "{z}");
        }
    }

    /// The sampled row equals the general row with no linear phase and no sinc factors.
    #[test]
    fn sampled_row_is_the_row_without_sinc_factors() {
        let n = 23;
        let h: Vec<f64> = (0..n).map(|i| 1e-7 * (i as f64 * 0.7).sin()).collect();
        let zero = vec![0.0; n];
        let w: Vec<f64> = (0..n)
            .map(|i| if i < 3 { 0.0 } else { 1.0 / i as f64 })
            .collect();
        let p = RowParams {
            vz: -2.2e7,
            phase0: 0.0,
            dphase: 0.0,
            sx0: 0.0,
            sx1: 0.0,
            sy0: 0.0,
            sy1: 0.0,
            area: 2.5e-13,
        };
        let (mut general, mut sampled) =
            (vec![Complex64::default(); n], vec![Complex64::default(); n]);
        let cells = RowCells {
            h: &h,
            hx: &zero,
            hy: &zero,
            w: &w,
        };
        fill_row(&cells, &p, &mut general);
        fill_row_sampled(&h, &w, p.vz, p.area, &mut sampled);
        for (a, b) in general.iter().zip(&sampled) {
            assert!((a - b).norm() <= 1e-15 * p.area, "{a} vs {b}");
        }
    }

    /// The vectorised row equals a scalar evaluation with std's trigonometry.
    #[test]
    fn row_matches_scalar_formula() {
        let n = 37;
        let h: Vec<f64> = (0..n).map(|i| 1e-7 * (i as f64 * 0.7).sin()).collect();
        let hx: Vec<f64> = (0..n).map(|i| 0.2 * (i as f64 * 0.3).cos()).collect();
        let hy: Vec<f64> = (0..n).map(|i| -0.1 * (i as f64 * 1.1).sin()).collect();
        let w: Vec<f64> = (0..n).map(|i| 1.0 / (1.0 + i as f64)).collect();
        let p = RowParams {
            vz: -2.2e7,
            phase0: 31.0,
            dphase: 1.7,
            sx0: 0.4,
            sx1: -2.0,
            sy0: 0.0,
            sy1: 3.0,
            area: 2.5e-13,
        };
        let mut out = vec![Complex64::default(); n];
        fill_row(
            &RowCells {
                h: &h,
                hx: &hx,
                hy: &hy,
                w: &w,
            },
            &p,
            &mut out,
        );
        let exact_sinc = |z: f64| if z == 0.0 { 1.0 } else { z.sin() / z };
        for i in 0..n {
            let a = p.area
                * w[i]
                * exact_sinc(p.sx0 + p.sx1 * hx[i])
                * exact_sinc(p.sy0 + p.sy1 * hy[i]);
            let e = Complex64::from_polar(a, p.vz * h[i] + p.phase0 + i as f64 * p.dphase);
            assert!(
                (out[i] - e).norm() < 1e-13 * p.area,
                "{i}: {} vs {e}",
                out[i]
            );
        }
    }
}
