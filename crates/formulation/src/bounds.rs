//! Bounded parameters for an unbounded optimiser: MINUIT's sine transform
//! `x = lo + (hi − lo)(1 + sin u)/2` (F. James & M. Roos, "MINUIT", Comput. Phys. Commun. 10,
//! 343, 1975; James, MINUIT Reference Manual, CERN D506, §1.3.1 "parameter limits"), its
//! inverse, and the rounding of a fitted value to a decimal that writes and reads back exactly.

use crate::coating_sensitivity::Varied;

/// Map an unbounded parameter into `[lo, hi]` (MINUIT's sine transform).
pub fn to_bounds(v: &Varied, u: f64) -> f64 {
    v.lo + (v.hi - v.lo) * (1.0 + u.sin()) / 2.0
}

/// The unbounded parameter of a value in `[lo, hi]` (clamped into it).
pub fn from_bounds(v: &Varied, x: f64) -> f64 {
    (2.0 * (x - v.lo) / (v.hi - v.lo) - 1.0)
        .clamp(-1.0, 1.0)
        .asin()
}

/// Round a fitted value to 1e-5 of its range (a decimal count that writes and reads back
/// exactly, far below any uncertainty a reading allows).
pub fn rounded(v: &Varied, x: f64) -> f64 {
    let decimals = (-((v.hi - v.lo) * 1e-5).log10()).ceil().clamp(0.0, 15.0) as usize;
    format!("{x:.decimals$}").parse().unwrap_or(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sine map covers the bounds and is inverted by `from_bounds`; rounding keeps a value
    /// within 1e-5 of the range and reads back exactly.
    #[test]
    fn bounds_transform_and_rounding() {
        let v = Varied::parse("tilt=4:20").unwrap();
        assert_eq!(to_bounds(&v, -std::f64::consts::FRAC_PI_2), 4.0);
        assert_eq!(to_bounds(&v, std::f64::consts::FRAC_PI_2), 20.0);
        for u in [-7.0, -1.0, 0.0, 0.3, 2.0, 11.0] {
            let x = to_bounds(&v, u);
            assert!((4.0..=20.0).contains(&x));
            assert!((to_bounds(&v, from_bounds(&v, x)) - x).abs() < 1e-12);
        }
        let x = rounded(&v, 12.345_678_9);
        assert!((x - 12.345_678_9).abs() <= 16.0 * 1e-5);
        assert_eq!(x.to_string().parse::<f64>().unwrap(), x);
        assert_eq!(x, 12.3457);
    }
}
