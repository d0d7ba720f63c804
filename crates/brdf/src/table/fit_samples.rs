//! A table's cells as samples for the least-squares fit ([`crate::fit::fit`]), weighted by
//! `cos theta_o` times the cell's measure in direction-pair space.
//!
//! With `wo = 2 (wi·h) h - wi`, `dwo = 4 (wi·h) dwh` (Walter et al. 2007, eq. 14) and `wi` a
//! rotation of the difference vector about `h`, the pair measure is
//! `dwi dwo = 4 cos(theta_d) dwh dwd` (Rusinkiewicz 1998). A cell covers half a node step on each
//! side of its node in every angle (clipped at the ends; the whole phi_h circle when isotropic),
//! so that the weights add up to about `∫∫ cos(theta_o) dwi dwo` over the pairs the cells cover.

use super::BrdfTable;
use crate::fit::FitSample;
use std::f64::consts::{FRAC_PI_2, TAU};

impl BrdfTable {
    /// The cells with data whose incidence and reflection angles are both at most `max_theta`
    /// (radians), as fit samples at the cells' direction pairs: value the mean of the channels
    /// ([`BrdfTable::scalar`]), weight `cos theta_o · dwi dwo` of the cell (sr²).
    pub fn fit_samples(&self, max_theta: f64) -> Vec<FitSample> {
        let res = self.resolution();
        let cos_max = max_theta.cos();
        let sqrt_spaced = |j: f64| FRAC_PI_2 * (j / res.theta_h as f64).powi(2);
        let linear = |j: f64| FRAC_PI_2 * j / res.theta_d as f64;
        // Node j covers [j - 1/2, j + 1/2] in index units, clipped to [0, n - 1].
        let span = |j: usize, n: usize| {
            (
                (j as f64 - 0.5).max(0.0),
                (j as f64 + 0.5).min((n - 1) as f64),
            )
        };
        let d_phi_h = if res.is_isotropic() {
            TAU
        } else {
            TAU / res.phi_h as f64
        };
        let d_phi_d = TAU / res.phi_d as f64;
        let mut buf = vec![0.0; self.channel_count()];
        let mut out = Vec::new();
        for cell in 0..res.cell_count() {
            let values = self.cell_values(cell);
            if values[0].is_nan() {
                continue;
            }
            let [_, th, td, _] = res.cell_indices(cell);
            let (wi, wo) = res.cell_angles(cell).to_dirs();
            if wi.z < cos_max || wo.z < cos_max {
                continue;
            }
            for (b, v) in buf.iter_mut().zip(values) {
                *b = f64::from(*v);
            }
            let (a, b) = span(th, res.theta_h);
            // ∫ sin(theta_h) dtheta_h over the cell.
            let h = sqrt_spaced(a).cos() - sqrt_spaced(b).cos();
            let (a, b) = span(td, res.theta_d);
            // ∫ cos(theta_d) sin(theta_d) dtheta_d over the cell.
            let d = 0.5 * (linear(b).sin().powi(2) - linear(a).sin().powi(2));
            out.push(FitSample {
                wi,
                wo,
                value: BrdfTable::scalar(&buf),
                weight: wo.z * 4.0 * h * d_phi_h * d * d_phi_d,
            });
        }
        out
    }
}
