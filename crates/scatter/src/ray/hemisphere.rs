//! Full-hemisphere detector grids: the hemisphere above the surface cut into cells of equal
//! polar and azimuthal width. Unlike cones, the cells tile the hemisphere, so every ray that
//! leaves the surface lands in exactly one cell and the table conserves the reflected power.
//! The same grid, mirrored in the mean plane, tiles the hemisphere below the surface for the
//! light transmitted into the material ([`TransmissionTable`]).

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

/// Finds the cell of a direction without `acos` and `atan2` per ray (a third of the time of a
/// hemisphere run with them): polynomial estimates of theta and phi (Abramowitz & Stegun 4.4.46
/// and 4.4.49, errors below 3e-8 rad) are corrected against the tabulated cell boundaries, so a
/// direction gets the cell whose boundaries `cos θ_{i+1} < z <= cos θ_i`, `φ_j <= φ < φ_{j+1}`
/// hold, as [`HemisphereGrid::cell`] gives (to the rounding of a direction lying on a boundary).
pub(crate) struct CellLocator {
    grid: HemisphereGrid,
    /// `cos(i Δθ)` for i = 0..=n_theta.
    cos_theta: Vec<f64>,
    /// `(cos φ_j, sin φ_j)` for j = 0..n_phi.
    phi_dirs: Vec<(f64, f64)>,
}

impl CellLocator {
    pub(crate) fn new(grid: HemisphereGrid) -> Self {
        CellLocator {
            grid,
            cos_theta: (0..=grid.n_theta)
                .map(|i| (i as f64 * grid.d_theta()).cos())
                .collect(),
            phi_dirs: (0..grid.n_phi)
                .map(|j| (j as f64 * grid.d_phi()).sin_cos())
                .map(|(s, c)| (c, s))
                .collect(),
        }
    }

    /// Index `i * n_phi + j` of the cell of unit direction `d` (`d.z > 0`).
    pub(crate) fn cell(&self, d: DVec3) -> usize {
        let (n_theta, n_phi) = (self.grid.n_theta, self.grid.n_phi);
        if n_phi < 4 {
            return self.grid.cell(d);
        }
        let z = d.z.clamp(0.0, 1.0);
        let mut i = ((acos_approx(z) / self.grid.d_theta()) as usize).min(n_theta - 1);
        while i > 0 && z > self.cos_theta[i] {
            i -= 1;
        }
        while i + 1 < n_theta && z <= self.cos_theta[i + 1] {
            i += 1;
        }
        if d.x == 0.0 && d.y == 0.0 {
            return i * n_phi;
        }
        let mut j = ((atan2_approx(d.y, d.x) / self.grid.d_phi()) as usize).min(n_phi - 1);
        // `d` lies counter-clockwise of (or on) boundary j when the cross product is >= 0.
        let after = |j: usize| {
            let (c, s) = self.phi_dirs[j % n_phi];
            c * d.y - s * d.x >= 0.0
        };
        for _ in 0..n_phi {
            if !after(j) {
                j = (j + n_phi - 1) % n_phi;
            } else if after(j + 1) {
                j = (j + 1) % n_phi;
            } else {
                break;
            }
        }
        i * n_phi + j
    }
}

/// `acos(x)` for x in [0, 1], error below 2e-8 (Abramowitz & Stegun 4.4.46).
fn acos_approx(x: f64) -> f64 {
    const A: [f64; 8] = [
        1.570_796_305_0,
        -0.214_598_801_6,
        0.088_978_987_4,
        -0.050_174_304_6,
        0.030_891_881_0,
        -0.017_088_125_6,
        0.006_670_090_1,
        -0.001_262_491_1,
    ];
    let poly = A.iter().rev().fold(0.0, |acc, &a| acc * x + a);
    (1.0 - x).sqrt() * poly
}

/// `atan2(y, x)` mapped to [0, 2π), error below 3e-8 (Abramowitz & Stegun 4.4.49 on the first
/// octant).
fn atan2_approx(y: f64, x: f64) -> f64 {
    const A: [f64; 8] = [
        -0.333_331_452_8,
        0.199_935_508_5,
        -0.142_088_994_4,
        0.106_562_639_3,
        -0.075_289_640_0,
        0.042_909_613_8,
        -0.016_165_736_7,
        0.002_866_225_7,
    ];
    let (ax, ay) = (x.abs(), y.abs());
    let t = ax.min(ay) / ax.max(ay);
    let t2 = t * t;
    let mut a = t * (1.0 + t2 * A.iter().rev().fold(0.0, |acc, &c| acc * t2 + c));
    if ay > ax {
        a = FRAC_PI_2 - a;
    }
    if x < 0.0 {
        a = std::f64::consts::PI - a;
    }
    if y < 0.0 {
        a = TAU - a;
    }
    a.min(TAU - 1e-15)
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

/// What each cell of a hemisphere grid collected below the surface: the light refracted into
/// the material ([`super::RayEngine::transmit_hemisphere`]).
///
/// The cells are those of the grid mirrored in the mean plane: cell `(i, j)` holds the
/// transmitted directions `wt` at polar angle `theta ∈ [i Δθ, (i+1) Δθ)` from the inward
/// normal `-z` and azimuth `phi ∈ [j Δφ, (j+1) Δφ)` from +x (the forward side, where a smooth
/// surface refracts) toward +y, that is the direction `(wt_x, wt_y, -wt_z)` in the grid's cell.
///
/// The table is power-based: each cell holds the fraction of the power incident on the mean
/// plane that enters the material within the cell. Divided by the cell's projected solid angle
/// (about `-z`) it is the mean over the cell of `dΦ_t / (Φ_i |cos θt| dω_t)`, which is the
/// BTDF `f_t(i, o)` of Walter et al. (EGSR 2007, eq. 21, with `η_i = 1` in air and
/// `η_o = n` in the material) as written, `L_o = ∫ f_t L_i |cos θi| dω_i` with the radiance
/// `L_o` inside the material: its `η_o²` is the compression of solid angle by refraction, and
/// `∫ f_t |cos θt| dω_t` is the transmittance. Divide by `n²` for the BTDF of basic radiance
/// `L/n²`, the reciprocal form (`f_t(i, o)/η_o² = f_t(o, i)/η_i²`: Walter et al. 2007, §3;
/// E. Veach, PhD thesis, Stanford 1997, ch. 5), which is also the BTDF `f_t(o, i)` for light
/// leaving the material toward `i`.
#[derive(Debug, Clone, PartialEq)]
pub struct TransmissionTable {
    pub grid: HemisphereGrid,
    /// Transmittance per cell (fraction of the incident power), index `i * n_phi + j`.
    pub transmittance: Vec<f64>,
    /// s- and p-polarised transmittance per cell, when polarisation is tracked.
    pub transmittance_sp: Option<(Vec<f64>, Vec<f64>)>,
    /// Rays per cell.
    pub hits: Vec<u64>,
}

impl TransmissionTable {
    /// The table of a hemisphere table filled with mirrored transmitted directions.
    pub(crate) fn from_mirrored(table: HemisphereTable) -> Self {
        TransmissionTable {
            grid: table.grid,
            transmittance: table.reflectance,
            transmittance_sp: table.reflectance_sp,
            hits: table.hits,
        }
    }

    /// Mean power-based BTDF over cell `(i, j)` weighted by `|cos θt|`, 1/sr: the cell's
    /// transmittance over its projected solid angle (Walter's `f_t`, see the type's comment).
    pub fn btdf_per_sr(&self, i: usize, j: usize) -> f64 {
        self.transmittance[i * self.grid.n_phi + j] / self.grid.projected_solid_angle(i)
    }

    /// Total transmittance: the fraction of the incident power that enters the material and
    /// goes down into it without meeting the surface again.
    pub fn total_transmittance(&self) -> f64 {
        self.transmittance.iter().sum()
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

    /// The fast locator gives the cell of the definition for directions all over the
    /// hemisphere, on several grids (boundaries themselves excepted: none is drawn here).
    #[test]
    fn locator_matches_definition() {
        for (nt, np) in [(90, 360), (45, 180), (7, 13), (1, 4), (30, 2)] {
            let grid = HemisphereGrid::new(nt, np).unwrap();
            let loc = CellLocator::new(grid);
            let mut state = 0x2545_f491_4f6c_dd1d_u64;
            let mut next = || {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 11) as f64 / (1u64 << 53) as f64
            };
            for _ in 0..200_000 {
                let z = next().max(1e-12);
                let phi = TAU * next();
                let r = (1.0 - z * z).sqrt();
                let d = DVec3::new(r * phi.cos(), r * phi.sin(), z);
                assert_eq!(loc.cell(d), grid.cell(d), "{nt}×{np}: {d}");
            }
            assert_eq!(loc.cell(DVec3::Z), grid.cell(DVec3::Z));
        }
    }
}
