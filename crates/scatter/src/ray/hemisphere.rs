//! Full-hemisphere detector grids: the hemisphere above the surface cut into cells of equal
//! polar and azimuthal width. Unlike cones, the cells tile the hemisphere, so every ray that
//! leaves the surface lands in exactly one cell and the table conserves the reflected power.

use super::index::Sums;
use crate::error::{Result, ScatterError};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Cells `theta ∈ [i Δθ, (i+1) Δθ)`, `phi ∈ [j Δφ, (j+1) Δφ)` with `Δθ = 90° / n_theta`,
/// `Δφ = 360° / n_phi`; phi from +x (the specular side) toward +y.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HemisphereGrid {
    pub n_theta: usize,
    pub n_phi: usize,
}

impl HemisphereGrid {
    /// A grid of `n_theta × n_phi` cells; both must be at least 1.
    pub fn new(n_theta: usize, n_phi: usize) -> Result<Self> {
        if n_theta == 0 || n_phi == 0 {
            return Err(ScatterError::Invalid(format!(
                "hemisphere grid {n_theta} × {n_phi}: both counts must be at least 1"
            )));
        }
        Ok(HemisphereGrid { n_theta, n_phi })
    }

    /// A grid with cells of `step_deg` degrees in both theta and phi (1° gives 90 × 360).
    pub fn with_step_deg(step_deg: f64) -> Result<Self> {
        if !(step_deg > 0.0 && step_deg <= 90.0) {
            return Err(ScatterError::Invalid(format!(
                "hemisphere grid step {step_deg}°: must be in (0, 90]"
            )));
        }
        Self::new(
            (90.0 / step_deg).round() as usize,
            (360.0 / step_deg).round() as usize,
        )
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.n_theta * self.n_phi
    }

    /// Whether the grid has no cells (never, for a grid built by [`HemisphereGrid::new`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn d_theta(&self) -> f64 {
        FRAC_PI_2 / self.n_theta as f64
    }

    fn d_phi(&self) -> f64 {
        TAU / self.n_phi as f64
    }

    /// Index `i * n_phi + j` of the cell holding the unit direction `d` (`d.z > 0`).
    pub fn cell(&self, d: DVec3) -> usize {
        let theta = d.z.clamp(-1.0, 1.0).acos();
        let mut phi = d.y.atan2(d.x);
        if phi < 0.0 {
            phi += TAU;
        }
        let i = ((theta / self.d_theta()) as usize).min(self.n_theta - 1);
        let j = ((phi / self.d_phi()) as usize).min(self.n_phi - 1);
        i * self.n_phi + j
    }

    /// Polar and azimuthal centre of cell `(i, j)`, radians.
    pub fn centre(&self, i: usize, j: usize) -> (f64, f64) {
        (
            (i as f64 + 0.5) * self.d_theta(),
            (j as f64 + 0.5) * self.d_phi(),
        )
    }

    /// Projected solid angle `∫ cos theta dω = Δφ (sin²θ1 - sin²θ0) / 2` of a cell in ring `i`,
    /// steradians: the factor between a cell's reflectance and its mean BRDF.
    pub fn projected_solid_angle(&self, i: usize) -> f64 {
        let (t0, t1) = (i as f64 * self.d_theta(), (i + 1) as f64 * self.d_theta());
        0.5 * self.d_phi() * (t1.sin().powi(2) - t0.sin().powi(2))
    }
}

/// What each cell of a hemisphere grid collected.
#[derive(Debug, Clone, PartialEq)]
pub struct HemisphereTable {
    pub grid: HemisphereGrid,
    /// Reflectance per cell, index `i * n_phi + j`.
    pub reflectance: Vec<f64>,
    /// s- and p-polarised reflectance per cell, when polarisation is tracked.
    pub reflectance_sp: Option<(Vec<f64>, Vec<f64>)>,
    /// Rays per cell.
    pub hits: Vec<u64>,
}

impl HemisphereTable {
    pub(crate) fn from_sums(
        grid: HemisphereGrid,
        sums: &[Sums],
        scale: f64,
        polarised: bool,
    ) -> Self {
        HemisphereTable {
            grid,
            reflectance: sums.iter().map(|s| s.w * scale).collect(),
            reflectance_sp: polarised.then(|| {
                (
                    sums.iter().map(|s| s.ws * scale).collect(),
                    sums.iter().map(|s| s.wp * scale).collect(),
                )
            }),
            hits: sums.iter().map(|s| s.hits).collect(),
        }
    }

    /// Mean BRDF over cell `(i, j)` weighted by cos theta, 1/sr.
    pub fn brdf_per_sr(&self, i: usize, j: usize) -> f64 {
        self.reflectance[i * self.grid.n_phi + j] / self.grid.projected_solid_angle(i)
    }

    /// Total reflectance over the hemisphere (the directional-hemispherical reflectance).
    pub fn total_reflectance(&self) -> f64 {
        self.reflectance.iter().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_tile_the_hemisphere() {
        let g = HemisphereGrid::with_step_deg(1.0).unwrap();
        assert_eq!((g.n_theta, g.n_phi), (90, 360));
        let total: f64 = (0..g.n_theta)
            .map(|i| g.projected_solid_angle(i) * g.n_phi as f64)
            .sum();
        assert!((total - std::f64::consts::PI).abs() < 1e-12, "{total}");
        let (t, p) = g.centre(30, 45);
        let d = DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        assert_eq!(g.cell(d), 30 * 360 + 45);
        assert!(HemisphereGrid::new(0, 3).is_err());
    }
}
