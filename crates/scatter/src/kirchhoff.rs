//! The scalar Kirchhoff approximation over a measured height map (P. Beckmann & A. Spizzichino,
//! *The Scattering of Electromagnetic Waves from Rough Surfaces*, 1963, ch. 3 and 5): with
//! `wi` toward the source, `wo` toward the detector, `k = 2π/λ` and `v = -k (wi + wo)`,
//!
//! ```text
//! E(v) = ∫∫ W(x, y) exp(i (vx x + vy y + vz h(x, y))) dx dy
//! f    = R(iota) k² cos ti |F E(v)|² / (4π² cos to ∫∫ W² dx dy)
//! ```
//!
//! `W` is the radial Schwartz window `exp(-1/(1 - (ρ/R)²))` over a circular spot (by default the
//! largest circle that fits the map), so a flat patch conserves energy and its lobe is the
//! window's diffraction pattern. Unlike the ray method the result depends on the wavelength and
//! shows the coherent specular spike of smooth surfaces.
//!
//! Discretisation: the surface is the bicubic spline through the map, cut into cells `r` times
//! finer than the map; on each cell it is replaced by its tangent plane at the cell centre and the
//! integral over the cell is done exactly (a product of two sinc factors). The refinement `r` is
//! chosen per direction from the data: the largest departure of the surface from a cell's tangent
//! plane, `C/(8 r²)` with `C` the 99.9th percentile of the map's second differences over the spot,
//! must keep the neglected phase `|vz| C/(8 r²)` below [`KirchhoffOptions::phase_tolerance`].
//! A detector's reading sums `|E|²` over the wave vectors its cone holds, on the lattice the spot
//! resolves (see `aperture`); pointwise BRDFs use the direct sum; full-hemisphere maps use FFTs
//! (see `hemisphere`). Shadowing and masking: Smith's function of the spot's own slopes, a
//! factor `G2(wi, wo)` on the BRDF (see `shadowing`). Method and accuracy: `docs/kirchhoff.md`.

mod aperture;
mod facets;
mod geometric;
mod hemisphere;
mod kernel;
mod shadowing;

pub use geometric::{GEOMETRIC_ABOVE_G, MethodSplit};
pub use hemisphere::{BUILD_CELL_NS, FACET_NS, NODE_CELL_NS};

use crate::error::{Result, ScatterError};
use crate::geometry::{
    CurvePoint, Detector, InplaneCurve, incidence_direction, inplane_direction, label_value,
};
use facets::FacetGrid;
use glam::DVec3;
use gonio_brdf::Ior;
use gonio_io::Progress;
use gonio_surface::HeightMap;
use gonio_surface::spline::BicubicSpline;
use rayon::prelude::*;
use shadowing::Shadowing;
use std::f64::consts::{PI, TAU};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

/// Largest refinement of the map's cells.
pub const MAX_REFINEMENT: usize = 16;

/// Default largest number of facets in one refined grid (16.8 million; 32 bytes each, so about
/// 540 MB per grid).
pub const MAX_FACETS: usize = 1 << 24;

/// A circular illuminated spot on the map: centre in the map's coordinates (point `(ix, iy)` at
/// `(ix·dx, iy·dy)`), metres, and diameter, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spot {
    pub center: (f64, f64),
    pub diameter: f64,
}

impl Spot {
    /// The largest circle that fits the map, centred on it.
    pub fn largest(map: &HeightMap) -> Spot {
        let (w, h) = map_extent(map);
        Spot {
            center: (0.5 * w, 0.5 * h),
            diameter: w.min(h),
        }
    }

    /// `count` spots of `diameter` metres on a square lattice of that pitch, centred on the map,
    /// taken row by row: non-overlapping spots for speckle averaging. Fails when fewer fit.
    pub fn tiled(map: &HeightMap, diameter: f64, count: usize) -> Result<Vec<Spot>> {
        let (w, h) = map_extent(map);
        let (cols, rows) = ((w / diameter) as usize, (h / diameter) as usize);
        if diameter.is_nan() || diameter <= 0.0 || count == 0 || cols * rows < count {
            return Err(ScatterError::Invalid(format!(
                "{count} spots of {:.1} µm do not fit side by side on a {:.1} × {:.1} µm map \
                 ({} fit); use a smaller spot or fewer spots",
                diameter * 1e6,
                w * 1e6,
                h * 1e6,
                cols * rows
            )));
        }
        let (x0, y0) = (
            0.5 * (w - cols as f64 * diameter),
            0.5 * (h - rows as f64 * diameter),
        );
        Ok((0..count)
            .map(|i| Spot {
                center: (
                    x0 + ((i % cols) as f64 + 0.5) * diameter,
                    y0 + ((i / cols) as f64 + 0.5) * diameter,
                ),
                diameter,
            })
            .collect())
    }
}

/// Width and height of the map between its first and last points, metres.
fn map_extent(map: &HeightMap) -> (f64, f64) {
    (
        (map.nx() - 1) as f64 * map.dx(),
        (map.ny() - 1) as f64 * map.dy(),
    )
}

/// Settings of the Kirchhoff engine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KirchhoffOptions {
    /// Refractive index of the coating.
    pub ior: Ior,
    /// The illuminated spot; `None` for the largest circle that fits the map.
    pub spot: Option<Spot>,
    /// Largest phase, radians, by which the surface may depart from a facet's tangent plane
    /// (default 0.3).
    pub phase_tolerance: f64,
    /// Largest number of facets in one grid (default [`MAX_FACETS`]): the memory bound. A
    /// full-hemisphere or gloss computation whose sampled grid would be larger is done as the
    /// mean over smaller spots (see [`Kirchhoff::scattered`]).
    pub max_facets: usize,
    /// Rayleigh parameter `g = (k σ (cos ti + cos to))²` above which full-hemisphere maps
    /// ([`Kirchhoff::hemisphere`], [`Kirchhoff::scattered`]) use the stationary-phase limit of
    /// the integral instead of the integral (default [`GEOMETRIC_ABOVE_G`]; infinite: the
    /// integral everywhere). See [`MethodSplit`].
    pub geometric_above: f64,
    /// Shadowing and masking by the surface (default on): the BRDF times Smith's
    /// height-correlated `G2 = 1/(1 + Λ(wi) + Λ(wo))` with `Λ` from the spot's own slopes (see
    /// `docs/kirchhoff.md`, "Shadowing and masking"). Off: the integral as it stands, which
    /// lights and sees every point and so reflects more light than falls on a rough sample
    /// toward grazing incidence.
    pub shadowing: bool,
}

impl KirchhoffOptions {
    /// Default settings for a coating of index `ior`.
    pub fn new(ior: Ior) -> Self {
        KirchhoffOptions {
            ior,
            spot: None,
            phase_tolerance: 0.3,
            max_facets: MAX_FACETS,
            geometric_above: GEOMETRIC_ABOVE_G,
            shadowing: true,
        }
    }
}

/// The Kirchhoff engine for one spot of one height map: the spline, the spot and the facet grids
/// of each refinement used so far.
pub struct Kirchhoff {
    spline: BicubicSpline,
    spot: Spot,
    ior: Ior,
    phase_tolerance: f64,
    max_facets: usize,
    geometric_above: f64,
    shadowing: bool,
    curvature: f64,
    slope: f64,
    grids: Vec<OnceLock<FacetGrid>>,
    /// Smith's `Λ` of the facets of each grid of [`Kirchhoff::grids`], made on first use.
    shadowings: Vec<OnceLock<Shadowing>>,
    height_stats: OnceLock<(f64, f64)>,
}

impl Kirchhoff {
    /// Set up the engine for the map less its least-squares plane (the sample's mean plane is
    /// the instrument's reference, as for [`crate::ray::RayEngine::new`]). Fails if the spot does
    /// not lie on the map or holds fewer than 8 × 8 points, or the phase tolerance is not
    /// positive.
    pub fn new(map: &HeightMap, options: KirchhoffOptions) -> Result<Self> {
        let spot = options.spot.unwrap_or_else(|| Spot::largest(map));
        let (w, h) = map_extent(map);
        let r = 0.5 * spot.diameter;
        let (cx, cy) = spot.center;
        let eps = 1e-9 * w.max(h);
        if !(r > 0.0 && cx - r >= -eps && cy - r >= -eps && cx + r <= w + eps && cy + r <= h + eps)
        {
            return Err(ScatterError::Invalid(format!(
                "spot of diameter {:.2} µm at ({:.2}, {:.2}) µm does not lie on the \
                 {:.2} × {:.2} µm map; choose a smaller spot",
                spot.diameter * 1e6,
                cx * 1e6,
                cy * 1e6,
                w * 1e6,
                h * 1e6
            )));
        }
        if spot.diameter < 8.0 * map.dx().max(map.dy()) {
            return Err(ScatterError::Invalid(format!(
                "spot of diameter {:.3} µm spans fewer than 8 points of the map; the Kirchhoff \
                 integral needs a larger spot",
                spot.diameter * 1e6
            )));
        }
        if options.max_facets < 64 {
            return Err(ScatterError::Invalid(format!(
                "a facet limit of {} is too small: a spot needs at least 8 × 8 facets",
                options.max_facets
            )));
        }
        if options.phase_tolerance.is_nan() || options.phase_tolerance <= 0.0 {
            return Err(ScatterError::Invalid(format!(
                "phase tolerance {} rad must be positive",
                options.phase_tolerance
            )));
        }
        if options.geometric_above.is_nan() || options.geometric_above <= 0.0 {
            return Err(ScatterError::Invalid(format!(
                "the Rayleigh parameter {} above which the stationary-phase limit is used must \
                 be positive (infinite: never)",
                options.geometric_above
            )));
        }
        // The sample as an instrument sees it: angles from its mean plane (see RayEngine::new).
        let map = &gonio_surface::ops::level(map)?;
        let spline = BicubicSpline::from_map(map)?;
        let (curvature, slope) = facets::spot_percentiles(map.heights(), map.dx(), map.dy(), &spot);
        Ok(Kirchhoff {
            spline,
            spot,
            ior: options.ior,
            phase_tolerance: options.phase_tolerance,
            max_facets: options.max_facets,
            geometric_above: options.geometric_above,
            shadowing: options.shadowing,
            curvature,
            slope,
            grids: (0..MAX_REFINEMENT).map(|_| OnceLock::new()).collect(),
            shadowings: (0..MAX_REFINEMENT).map(|_| OnceLock::new()).collect(),
            height_stats: OnceLock::new(),
        })
    }

    /// The illuminated spot.
    pub fn spot(&self) -> Spot {
        self.spot
    }

    /// Whether the BRDF includes shadowing and masking ([`KirchhoffOptions::shadowing`]);
    /// tables record it in their provenance as `kirchhoff_shadowing`.
    pub fn shadowing_enabled(&self) -> bool {
        self.shadowing
    }

    /// Refinement (cells per map cell along each axis) for a wave vector of z component `vz`:
    /// the smallest `r` with `|vz| C/(8 r²) ≤ phase_tolerance`.
    pub fn refinement(&self, vz: f64) -> Result<usize> {
        let r = self.curvature_refinement(vz);
        self.check_size(r)?;
        Ok(r)
    }

    /// The smallest `r` with `|vz| C/(8 r²) ≤ phase_tolerance`.
    fn curvature_refinement(&self, vz: f64) -> usize {
        (vz.abs() * self.curvature / (8.0 * self.phase_tolerance))
            .sqrt()
            .ceil()
            .max(1.0) as usize
    }

    /// The smallest refinement whose facet grid puts no grating order on wave vectors within
    /// `reach` of `v` (see `docs/kirchhoff.md`, "Grating orders of the facets").
    ///
    /// Facets of pitch `a` sample the surface: the field of the facet surface at `v` holds, beside
    /// the true field, images of it shifted by the grating vectors `2π (n/ax, m/ay)`, which the
    /// facets' exact sinc integrals attenuate (by about `(a δ/2π)²` at a distance `δ` from the
    /// grating vector) but do not remove. The true field of a map of spacing `d` lies within
    /// `π/d + |vz| s` of the specular direction in each axis: the map's band plus the spread
    /// `vz ∇h` of the phase (`s` the 99.9th percentile slope). Its first image then clears `v` if
    /// `2π r/d - π/d - |vz| s ≥ |v⊥| + reach` along each axis, that is
    /// `r ≥ (d (|v⊥| + reach + |vz| s) + π)/(2π)`.
    fn grating_refinement(&self, v: DVec3, reach: f64) -> usize {
        let spread = reach + v.z.abs() * self.slope;
        let axis = |d: f64, vt: f64| ((d * (vt.abs() + spread) + PI) / TAU).ceil();
        axis(self.spline.dx(), v.x)
            .max(axis(self.spline.dy(), v.y))
            .max(1.0) as usize
    }

    /// Refinement of the facet grid for wave vectors within `reach` of `v`: fine enough both for
    /// the surface's curvature ([`Kirchhoff::refinement`]) and to keep the facets' grating orders
    /// off those wave vectors.
    fn facet_refinement(&self, v: DVec3, reach: f64) -> Result<usize> {
        let r = self
            .curvature_refinement(v.z)
            .max(self.grating_refinement(v, reach));
        self.check_size(r)?;
        Ok(r)
    }

    /// Fails if a grid of refinement `r` over the spot would exceed [`MAX_REFINEMENT`] or the
    /// facet limit ([`KirchhoffOptions::max_facets`]).
    fn check_size(&self, r: usize) -> Result<()> {
        let cells = self.cells(self.spot.diameter, r);
        if r > MAX_REFINEMENT || cells > self.max_facets {
            return Err(ScatterError::Invalid(format!(
                "this map is too coarse for the Kirchhoff method in this direction: its surface \
                 would have to be cut into pieces {r} times smaller than the measured spacing \
                 ({cells} pieces over the spot; the limits are {MAX_REFINEMENT} times and {} \
                 pieces). Use a smaller spot, a longer wavelength, a map measured at a finer \
                 spacing, or the ray method",
                self.max_facets
            )));
        }
        Ok(())
    }

    /// Cells of a grid of refinement `r` over a spot of `diameter` metres.
    fn cells(&self, diameter: f64, r: usize) -> usize {
        let n = |d: f64| facets::cells_across(diameter, d / r as f64);
        n(self.spline.dx()) * n(self.spline.dy())
    }

    /// The facet grid of refinement `r`, built on first use.
    fn grid(&self, r: usize) -> &FacetGrid {
        self.grids[r - 1].get_or_init(|| FacetGrid::build(&self.spline, &self.spot, r))
    }

    /// Smith's `Λ` of the facets of a grid of refinement `r` (every `r`-th cell along each axis:
    /// as many facets as the map has points over the spot), or none when shadowing is off.
    fn shadowing_of(&self, grid: &FacetGrid, r: usize) -> Shadowing {
        if self.shadowing {
            Shadowing::of(grid, r)
        } else {
            Shadowing::none()
        }
    }

    /// [`Kirchhoff::shadowing_of`] the engine's own grid of refinement `r`, made once.
    fn shadowing(&self, r: usize) -> &Shadowing {
        self.shadowings[r - 1].get_or_init(|| self.shadowing_of(self.grid(r), r))
    }

    /// The facet grid for wave vectors within `reach` of `v`.
    fn grid_for(&self, v: DVec3, reach: f64) -> Result<&FacetGrid> {
        Ok(self.grid(self.facet_refinement(v, reach)?))
    }

    /// The facet grid for `detector` lit from `wi` at wave number `k`.
    fn detector_grid(&self, k: f64, wi: DVec3, detector: &Detector) -> Result<&FacetGrid> {
        self.grid_for(
            -k * (wi + detector.direction.normalize()),
            aperture::reach(k, detector.half_angle),
        )
    }

    /// Facets of the spot left out because they touch non-measured points (at refinement 1).
    pub fn invalid_facets(&self) -> usize {
        self.grid(1).invalid_cells
    }

    /// BRDF (1/sr) for light of `wavelength` (metres) from `wi` into `wo`, unit vectors away from
    /// the surface: the direct sum at exactly this pair of directions, with its speckle.
    pub fn brdf(&self, wavelength: f64, wi: DVec3, wo: DVec3) -> Result<f64> {
        check_wavelength(wavelength)?;
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return Ok(0.0);
        }
        let k = TAU / wavelength;
        let v = -k * (wi + wo);
        let grid = self.grid_for(v, 0.0)?;
        let e = grid.field([v.x, v.y, v.z], [v.x, v.y, v.z]);
        let shadowing = self.shadowing(1);
        let g2 = 1.0 / (1.0 + shadowing.lambda_exact(wi) + shadowing.lambda_exact(wo));
        Ok(
            g2 * aperture::brdf_factor(self.ior, wi, wo) * k * k * wi.z * e.norm_sqr()
                / (4.0 * PI * PI * wo.z * grid.w2_area),
        )
    }

    /// Reflectance `∫_cone f cos t dω` collected by `detector` for light of `wavelength` metres
    /// from `wi`.
    pub fn reflectance(&self, wavelength: f64, wi: DVec3, detector: &Detector) -> Result<f64> {
        check_wavelength(wavelength)?;
        if !(detector.half_angle > 0.0 && detector.half_angle < 0.5 * PI) {
            return Err(ScatterError::Invalid(format!(
                "detector half-angle {}° must lie in (0, 90)",
                detector.half_angle.to_degrees()
            )));
        }
        let k = TAU / wavelength;
        let grid = self.detector_grid(k, wi, detector)?;
        let shadowing = self.shadowing(1);
        let lambda_wi = shadowing.lambda_exact(wi);
        aperture::cone_reflectance(grid, self.ior, k, wi, detector, |wo| {
            shadowing.g2(lambda_wi, wo)
        })
    }

    /// In-plane curves for every wavelength (metres) and incidence (radians), in that order, with
    /// detectors of half-angle `half_angle` at signed scatter angles `scatter` (radians). The
    /// detectors run in parallel; `progress` counts them as they finish.
    pub fn inplane(
        &self,
        wavelengths: &[f64],
        incidences: &[f64],
        scatter: &[f64],
        half_angle: f64,
        progress: &Progress,
    ) -> Result<Vec<InplaneCurve>> {
        let jobs: Vec<(f64, f64, f64)> = wavelengths
            .iter()
            .flat_map(|&l| {
                incidences
                    .iter()
                    .flat_map(move |&ti| scatter.iter().map(move |&ts| (l, ti, ts)))
            })
            .collect();
        // Build the grids first, in order, so that parallel jobs never wait on one another.
        let detector = |ts: f64| Detector {
            direction: inplane_direction(ts),
            half_angle,
        };
        for &(l, ti, ts) in &jobs {
            self.detector_grid(TAU / l, incidence_direction(ti), &detector(ts))?;
        }
        self.shadowing(1);
        let done = AtomicU64::new(0);
        let readings: Vec<f64> = jobs
            .par_iter()
            .map(|&(l, ti, ts)| {
                let detector = detector(ts);
                let rho = self.reflectance(l, incidence_direction(ti), &detector);
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress.report("", finished, jobs.len() as u64);
                rho
            })
            .collect::<Result<_>>()?;
        let omega = crate::geometry::cone_solid_angle(half_angle);
        Ok(readings
            .chunks(scatter.len().max(1))
            .zip(jobs.chunks(scatter.len().max(1)))
            .map(|(rho, job)| InplaneCurve {
                method: "kirchhoff".into(),
                wavelength_nm: Some(label_value(job[0].0 * 1e9)),
                incidence_deg: label_value(job[0].1.to_degrees()),
                points: rho
                    .iter()
                    .zip(job)
                    .map(|(&rho, &(_, _, ts))| CurvePoint {
                        scatter_deg: label_value(ts.to_degrees()),
                        brdf_per_sr: rho / (omega * ts.cos()),
                        reflectance: rho,
                        rel_uncertainty: None,
                    })
                    .collect(),
            })
            .collect())
    }
}

/// Fails unless `wavelength` (metres) is positive and finite.
fn check_wavelength(wavelength: f64) -> Result<()> {
    if wavelength > 0.0 && wavelength.is_finite() {
        Ok(())
    } else {
        Err(ScatterError::Invalid(format!(
            "wavelength {wavelength} m must be positive and finite"
        )))
    }
}

/// Average several sets of curves point by point (speckle averaging over spots or realisations):
/// every set must hold the same curves at the same angles.
pub fn average_curves(sets: &[Vec<InplaneCurve>]) -> Result<Vec<InplaneCurve>> {
    let Some(first) = sets.first() else {
        return Err(ScatterError::Invalid("no curves to average".into()));
    };
    let same = |a: &InplaneCurve, b: &InplaneCurve| {
        a.wavelength_nm == b.wavelength_nm
            && a.incidence_deg == b.incidence_deg
            && a.points.len() == b.points.len()
            && a.points
                .iter()
                .zip(&b.points)
                .all(|(p, q)| p.scatter_deg == q.scatter_deg)
    };
    if sets
        .iter()
        .any(|s| s.len() != first.len() || !s.iter().zip(first).all(|(a, b)| same(a, b)))
    {
        return Err(ScatterError::Invalid(
            "curves to average differ in wavelength, incidence or angles".into(),
        ));
    }
    let n = sets.len() as f64;
    Ok(first
        .iter()
        .enumerate()
        .map(|(c, curve)| InplaneCurve {
            points: curve
                .points
                .iter()
                .enumerate()
                .map(|(i, p)| CurvePoint {
                    brdf_per_sr: sets.iter().map(|s| s[c].points[i].brdf_per_sr).sum::<f64>() / n,
                    reflectance: sets.iter().map(|s| s[c].points[i].reflectance).sum::<f64>() / n,
                    ..*p
                })
                .collect(),
            ..curve.clone()
        })
        .collect())
}

#[cfg(test)]
mod tests;
