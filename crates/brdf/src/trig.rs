//! Fast inverse trigonometric functions for the hot paths of table lookups and sampling: `atan2`
//! and `acos` within a few ulp of libm's, without its call (Cephes' `atan`). Used by the table's
//! coordinates ([`crate::table::coords`]), the table sampler's density and the renderer's
//! environment map lookups.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// `atan2(y, x)` in [-π, π], as `f64::atan2` to a few ulp, without the call into libm (about 140
/// instructions a call, a sixth of a table lookup): Cephes' `atan` (S. L. Moshier, *Methods and
/// Programs for Mathematical Functions*, 1989; the Cephes library's `atan.c`, peak relative error
/// 1.8e-16), i.e. `|y/x|` reduced to [0, 0.66] by `atan t = π/4 + atan((t-1)/(t+1))` or
/// `π/2 - atan(1/t)`, a rational function of degree 4/5 in `t²` there, and the quadrant from the
/// signs of `x` and `y`.
pub fn atan2(y: f64, x: f64) -> f64 {
    if x == 0.0 && y == 0.0 {
        return y.atan2(x);
    }
    let a = atan_non_negative(y.abs() / x.abs());
    let a = if x < 0.0 { PI - a } else { a };
    a.copysign(y)
}

/// `acos x` for `x` in [-1, 1], as `f64::acos` to a few ulp, without the call into libm:
/// `acos x = 2 atan √((1 - x)/(1 + x))` with [`atan2`]'s `atan`. `1 - x` (for x ≥ ½) and `1 + x`
/// (for x ≤ -½) are exact (Sterbenz), so the quotient is within 1.5 ulp even where the angle is
/// small; the square root halves that and adds half an ulp, `atan` passes the relative error of
/// its argument on at most unchanged and adds its own 1.8e-16, and doubling is exact: about
/// 3 ε relative in all. At `x = -1` the quotient is infinite and `atan` gives π/2, so π.
pub fn acos(x: f64) -> f64 {
    2.0 * atan_non_negative(((1.0 - x) / (1.0 + x)).sqrt())
}

/// `atan t` for `t` in [0, ∞] (see [`atan2`]).
fn atan_non_negative(t: f64) -> f64 {
    // π/2 = FRAC_PI_2 + MORE_BITS.
    const MORE_BITS: f64 = 6.123233995736766e-17;
    const TAN_3PI_8: f64 = 2.414213562373095;
    if t <= 0.66 {
        atan_reduced(t)
    } else if t > TAN_3PI_8 {
        FRAC_PI_2 - atan_reduced(1.0 / t) + MORE_BITS
    } else {
        FRAC_PI_4 + atan_reduced((t - 1.0) / (t + 1.0)) + 0.5 * MORE_BITS
    }
}

/// `atan x` for `|x|` <= 0.66: `x + x z P(z) / Q(z)`, `z = x²` (Cephes' coefficients).
fn atan_reduced(x: f64) -> f64 {
    // Cephes' values rounded to the nearest double.
    const P: [f64; 5] = [
        -0.8750608600031904,
        -16.157537187333652,
        -75.00855792314705,
        -122.88666844901361,
        -64.85021904942025,
    ];
    const Q: [f64; 5] = [
        24.858464901423062,
        165.02700983169885,
        432.88106049129027,
        485.3903996359137,
        194.5506571482614,
    ];
    let z = x * x;
    let p = (((P[0] * z + P[1]) * z + P[2]) * z + P[3]) * z + P[4];
    let q = ((((z + Q[0]) * z + Q[1]) * z + Q[2]) * z + Q[3]) * z + Q[4];
    x * (z * p / q) + x
}

#[cfg(test)]
mod tests {
    use super::{acos, atan2};

    /// [`acos`] against libm's over [-1, 1], densely near both ends (where the angle is small
    /// or near π). Tolerance: [`acos`]'s own 3 ε relative plus libm's ulp, 4 ε.
    #[test]
    fn acos_matches_libm() {
        let mut xs: Vec<f64> = (0..=200_000).map(|k| -1.0 + k as f64 / 100_000.0).collect();
        for e in 1..=52 {
            let d = 2f64.powi(-e);
            xs.extend([1.0 - d, -1.0 + d, d, -d]);
        }
        xs.extend([1.0, -1.0, 0.0, -0.0, 0.5, -0.5]);
        for x in xs {
            let (got, want) = (acos(x), x.acos());
            assert!(
                (got - want).abs() <= 4.0 * f64::EPSILON * want.abs(),
                "acos({x}): {got} vs {want}"
            );
        }
    }

    /// [`atan2`] against libm's over the circle and the axes. Tolerance: Cephes' `atan` is within
    /// 1.8e-16 relative; the quotient `y/x` adds half an ulp to `t`, which `atan` passes on at
    /// most unchanged in relative terms (`t atan'(t) / atan t <= 1`); `π - a` adds half an ulp
    /// of π; libm's own result is within an ulp: 4 ε relative in all.
    #[test]
    fn atan2_matches_libm() {
        let mut rng = 99u64;
        let mut next = || {
            rng = rng
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pairs: Vec<(f64, f64)> = (0..200_000)
            .map(|_| {
                let scale = 10f64.powf(-12.0 * next());
                (2.0 * next() - 1.0, (2.0 * next() - 1.0) * scale)
            })
            .flat_map(|(a, b)| [(a, b), (b, a)])
            .collect();
        pairs.extend([
            (0.0, 1.0),
            (1.0, 0.0),
            (0.0, -1.0),
            (-1.0, 0.0),
            (-0.0, -1.0),
        ]);
        pairs.extend([
            (1.0, 1.0),
            (0.66, 1.0),
            (2.414213562373095, 1.0),
            (0.0, 0.0),
        ]);
        for (y, x) in pairs {
            let (got, want) = (atan2(y, x), y.atan2(x));
            assert!(
                (got - want).abs() <= 4.0 * f64::EPSILON * want.abs(),
                "atan2({y}, {x}): {got} vs {want}"
            );
        }
    }
}
