//! How much each sample weighs in a scattered fit: the kernel (cut smoothly at 3.5 bandwidths),
//! the samples' images through the specular direction, and the soft cap at the largest value
//! measured nearby. Every weight is continuous in the query point, so the table has no steps.

use super::{Bandwidths, DIM};

/// The squared kernel distance `Σ ((x_k - y_k) / h_k)²` between two points.
#[inline]
pub(super) fn distance2(x: &[f64; DIM], y: &[f64; DIM], bw: &Bandwidths) -> f64 {
    let mut q = 0.0;
    for k in 0..DIM {
        let d = (x[k] - y[k]) / bw[k.min(2)];
        q += d * d;
    }
    q
}

/// The kernel's cut-off: 3.5 bandwidths, squared.
pub(super) const CUT2: f64 = 12.25;

/// Gaussian kernel weight cut at 3.5 bandwidths, less its tangent at the cut:
/// `exp(-q/2) - E (1 + (CUT2 - q)/2)` with `E = exp(-CUT2/2)` and `q` the squared distance in
/// bandwidths. It falls to 0 at the cut with a zero slope, so a sample's weight, and the fit,
/// change smoothly as a sample leaves the kernel's reach (cut where it was 0.0022, a sample
/// entering the reach with high leverage moved the Cayman peak by a factor 1.6 at once; cut
/// where it was 0 with a slope, the peak had a kink wherever a sample crossed the cut). The
/// Gaussian is convex in `q`, so it lies above its tangent: the weight is positive inside.
#[inline]
pub(super) fn kernel(x: &[f64; DIM], y: &[f64; DIM], bw: &Bandwidths) -> f64 {
    let q = distance2(x, y, bw);
    if q >= CUT2 {
        0.0
    } else {
        (-0.5 * q).exp() - KERNEL_AT_CUT * (1.0 + 0.5 * (CUT2 - q))
    }
}

/// The Gaussian at the cut, `exp(-CUT2 / 2)`.
pub(super) const KERNEL_AT_CUT: f64 = 0.002187491118182885;

/// The weight of the samples within the kernel's reach from which it is not widened (one sample
/// 2.45 bandwidths away).
pub(super) const WELL_WEIGHTED: f64 = 0.05;

/// The point of `y`'s image through the specular direction (module docs): `u` negated.
pub(super) fn through_pole(y: [f64; DIM]) -> [f64; DIM] {
    [-y[0], y[1], y[2], y[3]]
}

/// Whether `y` is within the kernel's reach of `x` (its weight is nonzero).
#[inline]
pub(super) fn within(x: &[f64; DIM], y: &[f64; DIM], bw: &Bandwidths) -> bool {
    distance2(x, y, bw) <= CUT2
}

/// `v` limited to `cap` with a smooth knee: unchanged up to 90% of the cap, then rising as
/// `tanh` toward the cap (slope 1 at the knee), so a capped peak keeps a rounded top instead of
/// a flat box and never exceeds the data's bound.
pub(super) fn soft_cap(v: f64, cap: f64) -> f64 {
    const KNEE: f64 = SOFT_CAP_KNEE;
    if cap <= 0.0 {
        return 0.0;
    }
    let x = v / cap;
    if x <= KNEE {
        v
    } else {
        cap * (KNEE + (1.0 - KNEE) * ((x - KNEE) / (1.0 - KNEE)).tanh())
    }
}

/// How far a sample at the squared distance `q` (in the doubled bandwidths) counts in the cap
/// of [`ScatteredFit::nearby_maximum`]: 1 within 2.5 bandwidths, 0 from the kernel's cut at
/// 3.5, between them the smoothstep `3s² − 2s³` of `s = 3.5 − sqrt(q)`, continuous with its
/// slope at both ends.
pub(super) fn cap_presence(q: f64) -> f64 {
    let s = (CUT2.sqrt() - q.sqrt()).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// The fraction of the cap up to which [`soft_cap`] leaves a value unchanged.
pub(super) const SOFT_CAP_KNEE: f64 = 0.9;
