//! One incidence of a table under construction: the BRDF over the half vector `h` for a fixed
//! source direction, on nodes that match the table's own theta_h nodes.
//!
//! Nodes lie on rings `u_j = j/N` (`u = sqrt(theta_h / (π/2))`, the table's square-root
//! spacing) and, within ring `j`, at `n_j = min(n_phi, 2j + 1)` azimuths (one at the pole,
//! where azimuth means nothing). Light is deposited with tent (linear finite-element) weights:
//! a ray at `(u, phi)` gives its reflectance to the up to four nodes around it with the weights
//! of linear interpolation, and each node's value is its deposit divided by the same tent
//! integral of the projected solid angle, `M = ∫ tent(h) cos(theta_o) dwo` with
//! `dwo = 4 (wi·h) dwh` (Walter et al. 2007, "Microfacet models for refraction through rough
//! surfaces", eq. 14). This is the lumped-mass projection of finite elements: the linear
//! interpolant of the node values integrates to exactly the reflected power,
//! `Σ value·M = Σ reflectance`, however narrow the lobe (a mirror's delta lobe becomes the tent
//! of the innermost node), so a table read at these nodes keeps the albedo of the surface.
//!
//! Azimuths are measured from +x. Isotropic slices have their source in the x-z plane at
//! azimuth 0 and are folded about that plane: azimuths are mapped into `[0, π]` (nodes at both
//! ends) and the measure counts both halves. Anisotropic slices keep azimuths on `[0, 2π)`.

use glam::DVec3;
use gonio_brdf::table::coords::{dir, theta_of};
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Quadrature steps per ring interval in `u` for the node measures.
const MEASURE_U_STEPS: usize = 16;
/// Quadrature steps per node interval in azimuth for the node measures.
const MEASURE_PHI_STEPS: usize = 8;
/// Samples deposited per parallel chunk (each chunk fills its own partial sums, added in order).
const CHUNK: usize = 1 << 16;

/// The nodes of a slice.
#[derive(Debug, Clone)]
pub(crate) struct SliceGrid {
    /// Rings `u_j = j / n_u`, j = 0 .. n_u - 1 (the table's theta_h nodes).
    n_u: usize,
    /// Folded about the plane of incidence (isotropic) or periodic over 2π.
    folded: bool,
    /// Azimuth nodes per ring.
    ring_len: Vec<usize>,
    /// Index of each ring's first node.
    ring_start: Vec<usize>,
    len: usize,
}

/// Node indices and weights of a point: up to 2 rings × 2 azimuths.
type Stencil = [(usize, f64); 4];

impl SliceGrid {
    /// `n_u` rings (the table's theta_h count) with at most `n_phi` azimuth nodes.
    pub fn new(n_u: usize, n_phi: usize, folded: bool) -> SliceGrid {
        let ring_len: Vec<usize> = (0..n_u).map(|j| (2 * j + 1).min(n_phi).max(1)).collect();
        let mut ring_start = Vec::with_capacity(n_u);
        let mut len = 0;
        for n in &ring_len {
            ring_start.push(len);
            len += n;
        }
        SliceGrid {
            n_u,
            folded,
            ring_len,
            ring_start,
            len,
        }
    }

    /// An azimuth folded into `[0, π]` when the slice is folded, else wrapped into `[0, 2π)`.
    fn relative_azimuth(&self, phi: f64) -> f64 {
        let p = phi.rem_euclid(TAU);
        if self.folded && p > PI { TAU - p } else { p }
    }

    /// The nodes around `(u, phi)` (phi relative, already folded) with their tent weights.
    fn stencil(&self, u: f64, phi: f64) -> Stencil {
        let x = u * self.n_u as f64;
        let last = self.n_u - 1;
        let (j0, t) = if x.is_nan() || x >= last as f64 {
            (last, 0.0)
        } else {
            let j = x.floor() as usize;
            (j, x - j as f64)
        };
        let mut out = [(0usize, 0.0f64); 4];
        for (r, (j, wr)) in [(j0, 1.0 - t), ((j0 + 1).min(last), t)]
            .into_iter()
            .enumerate()
        {
            let [a, b] = self.ring_weights(j, phi);
            out[2 * r] = (a.0, a.1 * wr);
            out[2 * r + 1] = (b.0, b.1 * wr);
        }
        out
    }

    /// The two azimuth nodes of ring `j` around `phi` and their weights.
    fn ring_weights(&self, j: usize, phi: f64) -> [(usize, f64); 2] {
        let (start, n) = (self.ring_start[j], self.ring_len[j]);
        if n == 1 {
            return [(start, 1.0), (start, 0.0)];
        }
        if self.folded {
            // Nodes at k π / (n - 1), both ends included.
            let y = (phi / PI * (n - 1) as f64).clamp(0.0, (n - 1) as f64);
            let k = (y.floor() as usize).min(n - 2);
            let t = y - k as f64;
            [(start + k, 1.0 - t), (start + k + 1, t)]
        } else {
            let y = (phi / TAU * n as f64).rem_euclid(n as f64);
            let k = (y.floor() as usize).min(n - 1);
            let t = y - k as f64;
            [(start + k, 1.0 - t), (start + (k + 1) % n, t)]
        }
    }

    /// Stencil of the half vector of `wi` and `wo`.
    fn stencil_of(&self, wi: DVec3, wo: DVec3) -> Option<Stencil> {
        let h = (wi + wo).try_normalize()?;
        let u = (theta_of(h) / FRAC_PI_2).sqrt();
        let phi = self.relative_azimuth(h.y.atan2(h.x));
        Some(self.stencil(u, phi))
    }

    /// Tent integrals `M = ∫ tent cos(theta_o) dwo` of every node for light from `wi`, by
    /// midpoint quadrature over `(u, phi)` of the half vector (`dwh = sin(theta_h) π u du dphi`).
    pub fn measures(&self, wi: DVec3) -> Vec<f64> {
        let n_phi_max = self.ring_len.iter().copied().max().unwrap_or(1);
        let (span, fold) = if self.folded { (PI, 2.0) } else { (TAU, 1.0) };
        let n_phi = MEASURE_PHI_STEPS * n_phi_max;
        let n_u = MEASURE_U_STEPS * self.n_u;
        let (du, dphi) = (1.0 / n_u as f64, span / n_phi as f64);
        let rows: Vec<Vec<(usize, f64)>> = (0..n_u)
            .into_par_iter()
            .map(|iu| {
                let u = (iu as f64 + 0.5) * du;
                let theta_h = FRAC_PI_2 * u * u;
                let d_omega_h = theta_h.sin() * PI * u * du * dphi;
                let mut row = Vec::with_capacity(4 * n_phi);
                for ip in 0..n_phi {
                    let phi = (ip as f64 + 0.5) * dphi;
                    let h = dir(theta_h, phi);
                    let c = wi.dot(h);
                    let wo = 2.0 * c * h - wi;
                    if c <= 0.0 || wo.z <= 0.0 {
                        continue;
                    }
                    let m = fold * wo.z * 4.0 * c * d_omega_h;
                    for (node, w) in self.stencil(u, phi) {
                        if w > 0.0 {
                            row.push((node, w * m));
                        }
                    }
                }
                row
            })
            .collect();
        let mut out = vec![0.0; self.len];
        for (node, m) in rows.into_iter().flatten() {
            out[node] += m;
        }
        out
    }

    /// Deposit weighted outgoing directions (`(wo, reflectance carried)`) for light from `wi`
    /// and turn the deposits into mean BRDF values (1/sr) per node, dividing by the node
    /// `measure`s; NaN where a measure vanishes. The sum is taken in fixed chunks, added in
    /// order, so the result does not depend on the number of threads.
    pub fn values(&self, wi: DVec3, samples: &[(DVec3, f64)], measure: &[f64]) -> Vec<f64> {
        let partials: Vec<Vec<f64>> = samples
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut part = vec![0.0; self.len];
                for &(wo, w) in chunk {
                    if let Some(st) = self.stencil_of(wi, wo) {
                        for (node, t) in st {
                            part[node] += t * w;
                        }
                    }
                }
                part
            })
            .collect();
        let mut deposit = vec![0.0; self.len];
        for part in &partials {
            for (d, p) in deposit.iter_mut().zip(part) {
                *d += p;
            }
        }
        deposit
            .iter()
            .zip(measure)
            .map(|(d, &m)| if m > 0.0 { d / m } else { f64::NAN })
            .collect()
    }

    /// Each ring's nodes replaced by their measure-weighted mean, so that `Σ value·M` over the
    /// ring is unchanged (nodes without data stay without).
    pub fn ring_average(&self, values: &[f64], measure: &[f64]) -> Vec<f64> {
        let mut out = values.to_vec();
        for (&start, &n) in self.ring_start.iter().zip(&self.ring_len) {
            let ring = start..start + n;
            let (mut power, mut m) = (0.0, 0.0);
            for i in ring.clone().filter(|&i| measure[i] > 0.0) {
                power += values[i] * measure[i];
                m += measure[i];
            }
            for i in ring.filter(|&i| measure[i] > 0.0) {
                out[i] = power / m;
            }
        }
        out
    }

    /// Interpolated value of `slice` at `(u, phi)` (phi from +x, folded here if need be),
    /// scaled by `weight` and added to `out`; returns the weight actually used (the nodes
    /// without data are skipped).
    pub fn accumulate(&self, slice: &Slice, u: f64, phi: f64, weight: f64, out: &mut [f64]) -> f64 {
        let mut used = 0.0;
        for (node, t) in self.stencil(u, self.relative_azimuth(phi)) {
            let w = t * weight;
            let v = &slice.values[node * slice.nc..(node + 1) * slice.nc];
            if w > 0.0 && !v[0].is_nan() {
                used += w;
                for (o, x) in out.iter_mut().zip(v) {
                    *o += w * x;
                }
            }
        }
        used
    }
}

/// Mean BRDF per node and channel of one incidence (NaN: no data).
#[derive(Debug, Clone)]
pub(crate) struct Slice {
    nc: usize,
    values: Vec<f64>,
}

impl Slice {
    /// A slice from one vector of node values per channel.
    pub fn from_channels(channels: &[Vec<f64>]) -> Slice {
        let nc = channels.len();
        let nodes = channels.first().map_or(0, Vec::len);
        let values = (0..nodes)
            .flat_map(|i| channels.iter().map(move |c| c[i]))
            .collect();
        Slice { nc, values }
    }

    /// `Σ value·M` per channel: the reflectance the slice's linear interpolant holds.
    #[cfg(test)]
    pub fn reflectance(&self, measure: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.nc];
        for (v, m) in self.values.chunks(self.nc).zip(measure) {
            if !v[0].is_nan() {
                for (o, x) in out.iter_mut().zip(v) {
                    *o += x * m;
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tent measures of all nodes add up to the projected solid angle of the hemisphere, π,
    /// at every incidence (the tents are a partition of unity).
    #[test]
    fn measures_tile_the_hemisphere() {
        for folded in [true, false] {
            let g = SliceGrid::new(24, 30, folded);
            for ti in [0.0f64, 30.0, 70.0, 85.0] {
                let wi = dir(ti.to_radians(), 0.0);
                let total: f64 = g.measures(wi).iter().sum();
                let tol = if ti > 80.0 { 5e-3 } else { 1e-3 };
                assert!(
                    (total / PI - 1.0).abs() < tol,
                    "{ti}°, folded {folded}: {total}"
                );
            }
        }
    }

    /// A mirror's delta lobe lands on the innermost node, and the node value times its measure
    /// is exactly the reflectance deposited.
    #[test]
    fn delta_lobe_keeps_its_power() {
        let g = SliceGrid::new(16, 20, true);
        let wi = dir(40f64.to_radians(), 0.0);
        let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
        let m = g.measures(wi);
        let s = Slice::from_channels(&[g.values(wi, &[(mirror, 0.04)], &m)]);
        assert!((s.reflectance(&m)[0] - 0.04).abs() < 1e-12);
        // (Rounding in the half vector leaves at most a trace on the next ring.)
        let rest = s.values[1..]
            .iter()
            .filter(|v| !v.is_nan())
            .fold(0.0f64, |a, v| a.max(*v));
        assert!(
            s.values[0] > 0.0 && rest < 1e-6 * s.values[0],
            "{:?}",
            &s.values[..4]
        );
    }
}
