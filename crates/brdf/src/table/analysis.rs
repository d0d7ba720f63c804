//! Summaries of a table: directional albedo per incidence angle, reciprocity error, peak value,
//! and enforcing reciprocity.
//!
//! Albedo `a(wi) = ∫ f(wi, wo) cos(theta_o) dwo` is integrated over the half vector, where the
//! table's own grid lives: `wo = 2 (wi·h) h - wi` and `dwo = 4 (wi·h) dwh` (Walter et al. 2007,
//! "Microfacet models for refraction through rough surfaces", eq. 14). theta_h is stepped in
//! `u = sqrt(theta_h / (π/2))` like the table, so that a narrow specular lobe is resolved.

use super::BrdfTable;
use super::coords::dir;
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Albedo per channel at a list of incidence angles.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AlbedoCurve {
    /// Incidence polar angles in degrees.
    pub theta_i_deg: Vec<f64>,
    /// `albedo[k][c]`: albedo of channel c at `theta_i_deg[k]`.
    pub albedo: Vec<Vec<f64>>,
}

impl BrdfTable {
    /// Directional albedo `∫ f cos(theta_o) dwo` per channel for light from `wi` (unit, above
    /// the horizon), by midpoint quadrature over the half vector (`n_u` steps in the
    /// square-root theta_h coordinate, `n_phi` in phi_h).
    pub fn albedo_with(&self, wi: DVec3, n_u: usize, n_phi: usize) -> Vec<f64> {
        let nc = self.channel_count();
        if wi.z <= 0.0 {
            return vec![0.0; nc];
        }
        let du = 1.0 / n_u as f64;
        let dphi = TAU / n_phi as f64;
        let rows: Vec<Vec<f64>> = (0..n_u)
            .into_par_iter()
            .map(|iu| {
                let u = (iu as f64 + 0.5) * du;
                let theta_h = FRAC_PI_2 * u * u;
                // dω_h = sin θh dθh dφ with dθh = π u du.
                let d_omega_h = theta_h.sin() * PI * u * du * dphi;
                let mut acc = vec![0.0; nc];
                let mut f = vec![0.0; nc];
                for ip in 0..n_phi {
                    let h = dir(theta_h, (ip as f64 + 0.5) * dphi);
                    let c = wi.dot(h);
                    if c <= 0.0 {
                        continue;
                    }
                    let wo = 2.0 * c * h - wi;
                    if wo.z <= 0.0 {
                        continue;
                    }
                    self.eval_channels(wo, wi, &mut f);
                    let w = wo.z * 4.0 * c * d_omega_h;
                    for (a, v) in acc.iter_mut().zip(&f) {
                        *a += w * v;
                    }
                }
                acc
            })
            .collect();
        let mut total = vec![0.0; nc];
        for r in rows {
            for (t, v) in total.iter_mut().zip(r) {
                *t += v;
            }
        }
        total
    }

    /// Albedo per channel for light at polar angle `theta_i` (radians) and azimuth `phi_i`, with
    /// a quadrature fine enough for the table (4 steps per theta_h node, 1° in phi_h).
    pub fn albedo(&self, theta_i: f64, phi_i: f64) -> Vec<f64> {
        let n_u = (4 * self.resolution().theta_h).max(256);
        self.albedo_with(dir(theta_i, phi_i), n_u, 360)
    }

    /// Albedo at several incidence angles (degrees), light in the x-z plane (phi_i = 0).
    pub fn albedo_curve(&self, theta_i_deg: &[f64]) -> AlbedoCurve {
        AlbedoCurve {
            theta_i_deg: theta_i_deg.to_vec(),
            albedo: theta_i_deg
                .iter()
                .map(|t| self.albedo(t.to_radians(), 0.0))
                .collect(),
        }
    }

    /// Relative reciprocity error `Σ |f(c) - f(c')| / Σ (f(c) + f(c'))` over every pair of cells
    /// c, c' = (wi, wo) and (wo, wi) that both hold data, all channels: 0 for a reciprocal
    /// table, 1 when every pair has one side zero.
    pub fn reciprocity_error(&self) -> f64 {
        let res = self.resolution();
        let nc = self.channel_count();
        let data = self.values();
        let (num, den) = (0..res.cell_count())
            .into_par_iter()
            .map(|cell| {
                let other = res.reciprocal_cell(cell);
                if other <= cell {
                    return (0.0, 0.0);
                }
                let (a, b) = (&data[cell * nc..][..nc], &data[other * nc..][..nc]);
                if a[0].is_nan() || b[0].is_nan() {
                    return (0.0, 0.0);
                }
                a.iter().zip(b).fold((0.0, 0.0), |(n, d), (x, y)| {
                    (
                        n + f64::from((x - y).abs()),
                        d + f64::from(x.abs() + y.abs()),
                    )
                })
            })
            .reduce(|| (0.0, 0.0), |p, q| (p.0 + q.0, p.1 + q.1));
        if den > 0.0 { num / den } else { 0.0 }
    }

    /// Make the table reciprocal: each pair of reciprocal cells gets the mean of the two. A cell
    /// whose partner has no data is left as it is.
    pub fn enforce_reciprocity(&mut self) {
        let res = self.resolution();
        let nc = self.channel_count();
        let data = self.values_mut();
        for cell in 0..res.cell_count() {
            let other = res.reciprocal_cell(cell);
            if other <= cell || data[cell * nc].is_nan() || data[other * nc].is_nan() {
                continue;
            }
            for c in 0..nc {
                let m = 0.5 * (data[cell * nc + c] + data[other * nc + c]);
                data[cell * nc + c] = m;
                data[other * nc + c] = m;
            }
        }
    }

    /// The largest value of any channel in any cell (1/sr), and the cell that holds it.
    pub fn peak(&self) -> (f64, usize) {
        let nc = self.channel_count();
        let mut best = (0.0f64, 0usize);
        for (i, v) in self.values().iter().enumerate() {
            if f64::from(*v) > best.0 {
                best = (f64::from(*v), i / nc);
            }
        }
        best
    }
}
