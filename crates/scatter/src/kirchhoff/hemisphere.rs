//! Full-hemisphere BRDF tables by FFT.
//!
//! `E(vx, vy, vz) = Σ_j A_j exp(i vz h_j) exp(i (vx x_j + vy y_j))` is, at fixed `vz`, the 2D
//! discrete Fourier transform of `A_j exp(i vz h_j)`: one FFT gives `E` on the whole lattice of
//! `(vx, vy)` that the spot resolves (spacing `2π/L`, centred on the specular direction). Each
//! lattice point is an outgoing direction with its own `vz = -k (cos ti + cos to)`, so FFTs are
//! taken at `vz` nodes spaced `Δ = 0.5/H` (`H` the largest centred height in the spot) and `E` is
//! interpolated between them by 4-point Lagrange interpolation, whose error for the band-limited
//! `exp(i vz h)` with `H Δ ≤ 0.5` is below 0.2%. Every lattice point then adds its BRDF times its
//! solid angle to the hemisphere cell holding its direction, as a detector would.
//!
//! The FFT needs a plain sum over points, so here the surface is sampled at cell centres without
//! the facets' sinc factors, on a grid refined until the phase `vz h` advances by at most 2π/10
//! between neighbouring points (99.9th percentile of the slope, largest `|vz|`): about ten points
//! per wavelength of the phase, and far inside the Nyquist limit, so no scattered light aliases.
//!
//! Where the Rayleigh parameter is large the integral's cost grows as `g` (finer sampling, more
//! nodes) while its result tends to the stationary-phase limit (`geometric`): directions with
//! `g` above [`super::KirchhoffOptions::geometric_above`] take the limit, and the FFTs are
//! sampled only for the `|vz|` below it.

use super::aperture::{brdf_factor, lattice_spacing, outgoing};
use super::facets::FacetGrid;
use super::kernel::fill_row_sampled;
use super::shadowing::Shadowing;
use super::{Kirchhoff, MAX_REFINEMENT, Spot};
use crate::error::{Result, ScatterError};
use crate::geometry::Detector;
use crate::ray::{HemisphereGrid, HemisphereTable};
use glam::DVec3;
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::{PI, TAU};

/// Points per wavelength of the phase `vz h` on the sampled grid.
const POINTS_PER_WAVE: f64 = 10.0;

/// Cost of one sampled cell at one `vz` node (its term, its share of the row and column FFTs
/// and of the transpose), nanoseconds of one core. Measured on the project's 2-core machine with
/// the Kirchhoff table of the 805 nm epoxy map (1024², 550 nm): its integral's parts, 5.9·10⁹
/// cell-nodes, took about 66 of its 88 s of CPU; the 88° map alone 10.3 s for 0.7·10⁹.
pub const NODE_CELL_NS: f64 = 12.0;

/// Cost of one facet of the stationary-phase limit (its ray and its hemisphere cell),
/// nanoseconds of one core: 0.2 s for the 0.8 million facets of the 805 nm epoxy map's spot.
pub const FACET_NS: f64 = 250.0;

/// Cost of building one cell of a facet grid (the spline and its slopes at the cell's centre),
/// nanoseconds of one core: 2.5 s for the 16.8 million cells of the 805 nm epoxy map's grid
/// sampled 4 times finer than the map.
pub const BUILD_CELL_NS: f64 = 150.0;

/// One lattice point that lands above the surface.
struct Bin {
    /// Index into the transposed FFT output, `c * ny + q` (see [`SpectrumBuffers::spectrum`]).
    index: usize,
    /// Outgoing direction.
    wo: DVec3,
    /// First of the four `vz` nodes to interpolate from, and the position between them in
    /// node spacings (in [0, 3]).
    node: usize,
    t: f64,
    /// `R F² cos ti Δvx Δvy / (4π² cos to ∫∫W²)`: reflectance per `|E|²`.
    weight: f64,
}

impl Kirchhoff {
    /// Refinement of the sampled grid for FFTs at wave vectors up to `|vz| = vz_max`: the
    /// smallest that puts [`POINTS_PER_WAVE`] points on each wavelength of the phase `vz h`.
    pub(crate) fn sampling_refinement(&self, vz_max: f64) -> usize {
        let dx = self.spline.dx().max(self.spline.dy());
        (vz_max * self.slope * dx * POINTS_PER_WAVE / TAU)
            .ceil()
            .max(1.0) as usize
    }

    /// The spots whose mean [`Kirchhoff::scattered`] (and the hemisphere and cone variants)
    /// returns for light of `wavelength` metres from `wi`: the engine's own spot, or the smaller
    /// spots that its bounding square is cut into when the whole spot's grid would exceed the
    /// facet limit. `cone`: the detector of [`Kirchhoff::scattered_in_cone`], `None` for the
    /// whole hemisphere (whose spots depend on the wavelength only, see
    /// [`Kirchhoff::scattered`]).
    pub fn sampling_spots_for(
        &self,
        wavelength: f64,
        wi: DVec3,
        cone: Option<&Detector>,
    ) -> Result<Vec<Spot>> {
        super::check_wavelength(wavelength)?;
        let k = TAU / wavelength;
        match cone {
            Some(detector) => {
                let r = self.cone_sampling_refinement(k, wi, detector);
                self.check_refinement(r, wavelength)?;
                Ok(self.sampling_spots(r))
            }
            None => Ok(self.hemisphere_spots(wavelength)),
        }
    }

    /// Refinement of the sampled grid for the lattice directions inside `detector`'s cone only:
    /// the full-hemisphere refinement, or less when that already keeps every image of the field
    /// off the cone. The sampled sum is the integral plus its images shifted by the grating
    /// vectors `2π (n/ax, m/ay)` (Poisson summation; no sinc factors attenuate them here). The
    /// field lies within `π/d + |vz| s` of specular along each axis (the map's band and the
    /// spread of the phase, `s` the 99.9th percentile slope), taken here with the slope doubled:
    /// for Gaussian slopes that is 7.4 standard deviations, where their density is e⁻²⁷ of its
    /// peak. So the cone (axis at `v⊥` from specular, wave vectors within `reach`) is clear, and
    /// inside the lattice, when `2π r/d ≥ |v⊥| + reach + 2 |vz| s + π/d` and
    /// `π r/d ≥ |v⊥| + reach` along each axis. A gloss meter's receptors, about specular, need
    /// about three times fewer points per map spacing than the whole hemisphere: at 20° and
    /// 550 nm, 4 instead of 13 on the demo's Sq 805 nm map.
    pub(crate) fn cone_sampling_refinement(&self, k: f64, wi: DVec3, detector: &Detector) -> usize {
        let full = self.sampling_refinement(k * (wi.z + 1.0));
        let v = -k * (wi + detector.direction.normalize());
        let reach = super::aperture::reach(k, detector.half_angle);
        let spread = 2.0 * k * (wi.z + 1.0) * self.slope;
        let axis = |d: f64, vt: f64| {
            let images = (d * (vt.abs() + reach + spread) + PI) / TAU;
            let lattice = d * (vt.abs() + reach) / PI;
            images.max(lattice).ceil()
        };
        let r = axis(self.spline.dx(), v.x)
            .max(axis(self.spline.dy(), v.y))
            .max(1.0) as usize;
        r.min(full)
    }

    /// Fails, in words a user can act on, when sampling the phase needs more than
    /// [`MAX_REFINEMENT`] points per spacing of the map.
    fn check_refinement(&self, r: usize, wavelength: f64) -> Result<()> {
        if r <= MAX_REFINEMENT {
            return Ok(());
        }
        let spacing = self.spline.dx().max(self.spline.dy());
        Err(ScatterError::Invalid(format!(
            "this surface is too steep for its sampling to be computed by the Kirchhoff method \
             at {:.0} nm: its slopes would need the map resampled {r} times finer than measured \
             (at most {MAX_REFINEMENT}). Use a map measured at a spacing of {:.3} µm or finer, a \
             longer wavelength, or the ray method, which suits surfaces this rough",
            wavelength * 1e9,
            spacing * MAX_REFINEMENT as f64 / r as f64 * 1e6
        )))
    }

    /// The spots over which light from a sampled grid of refinement `r` is averaged: the spot
    /// itself when its grid fits the facet limit, otherwise its bounding square cut into `m × m`
    /// squares, each lit by the circle inscribed in it, with `m` the smallest number for which
    /// one of them fits. They cover the area the spot's bounding square covers, so the average
    /// holds as many independent speckle grains as one large spot would.
    pub(crate) fn sampling_spots(&self, r: usize) -> Vec<Spot> {
        let whole = self.spot.diameter;
        let m = (1..)
            .find(|&m| self.cells(whole / m as f64, r) <= self.max_facets)
            .expect("a spot of one cell fits");
        let d = whole / m as f64;
        let (x0, y0) = (
            self.spot.center.0 - 0.5 * whole,
            self.spot.center.1 - 0.5 * whole,
        );
        (0..m * m)
            .map(|i| Spot {
                center: (
                    x0 + ((i % m) as f64 + 0.5) * d,
                    y0 + ((i / m) as f64 + 0.5) * d,
                ),
                diameter: d,
            })
            .collect()
    }

    /// The BRDF over the whole hemisphere for light of `wavelength` metres from `wi`, binned into
    /// the cells of `grid`: each cell's reflectance `∫ f cos t dω` and the number of directions
    /// it holds, in `hits` (lattice points, i.e. speckle samples, where the integral is used;
    /// facets where its stationary-phase limit is, see [`Kirchhoff::scattered`]).
    pub fn hemisphere(
        &self,
        wavelength: f64,
        wi: DVec3,
        grid: &HemisphereGrid,
    ) -> Result<HemisphereTable> {
        let mut reflectance = vec![0.0; grid.len()];
        let mut hits = vec![0u64; grid.len()];
        for (wo, share) in self.scattered(wavelength, wi)? {
            let cell = grid.cell(wo);
            reflectance[cell] += share;
            hits[cell] += 1;
        }
        Ok(HemisphereTable {
            grid: *grid,
            reflectance,
            reflectance_sp: None,
            hits,
        })
    }

    /// The light scattered over the whole hemisphere for light of `wavelength` metres from `wi`,
    /// as a set of outgoing directions, each with its share of the reflectance (`f cos t dω` of
    /// its lattice cell, or a facet's share). A detector of any shape reads the sum of the
    /// shares that fall in it.
    ///
    /// Where the Rayleigh parameter `g = (k σ (cos ti + cos to))²` is at most
    /// [`super::KirchhoffOptions::geometric_above`] the directions are the lattice the spot
    /// resolves, from the integral (FFTs, sampled finely enough for the largest `|vz|` there);
    /// above it they are the facets' mirror directions of the stationary-phase limit
    /// ([`Kirchhoff::method_split`] says where; `docs/kirchhoff.md`, "Rough maps").
    ///
    /// When the sampled grid of the whole spot would exceed the facet limit
    /// ([`super::KirchhoffOptions::max_facets`]; rough maps need fine sampling), the spot's
    /// bounding square is cut into `m × m` smaller spots that fit, and the result is the mean
    /// over them: the lattices and facets of all spots, each share divided by `m²`. A real
    /// instrument averages speckle the same way over its large spot; every reading is then the
    /// mean of `m²` independent speckle patterns (see `docs/kirchhoff.md`, "Spot averaging").
    /// The spots are those the finest sampling at this wavelength needs
    /// ([`Kirchhoff::sampling_spots_for`]), the same for every incidence and for both methods:
    /// the surface is weighted alike in every direction of a table (the slopes of one part of a
    /// map differ from another's; on a 256 µm crop of the 805 nm epoxy map the lobe of 128 µm
    /// spots peaked 33% higher than that of the inscribed 256 µm spot).
    pub fn scattered(&self, wavelength: f64, wi: DVec3) -> Result<Vec<(DVec3, f64)>> {
        super::check_wavelength(wavelength)?;
        let k = TAU / wavelength;
        let split = self.method_split(wavelength);
        let refinement = self.hemisphere_refinement(wavelength, wi);
        if let Some(r) = refinement {
            self.check_refinement(r, wavelength)?;
        }
        let geometric = split.cos_sum() < wi.z + 1.0;
        let integral_part = |wo: DVec3| !split.is_geometric(wi, wo);
        let limit_part = |wo: DVec3| split.is_geometric(wi, wo);
        Ok(self.spot_mean(&self.hemisphere_spots(wavelength), |spot| {
            let mut out = Vec::new();
            let mut lit = false;
            if let Some(r) = refinement {
                self.with_grid(spot, r, |grid, shadowing| {
                    lit |= grid.w2_area > 0.0;
                    out.extend(self.scattered_on(grid, shadowing, k, wi, &integral_part));
                });
            }
            if geometric {
                self.with_grid(spot, 1, |grid, shadowing| {
                    lit |= grid.w2_area > 0.0;
                    out.extend(self.geometric_on(grid, shadowing, wi, &limit_part));
                });
            }
            lit.then_some(out)
        }))
    }

    /// The spots of the full-hemisphere maps at `wavelength` metres: those of the sampling for
    /// the largest `|vz|` the integral is used for at any incidence (at most
    /// [`MAX_REFINEMENT`] times finer than the map).
    fn hemisphere_spots(&self, wavelength: f64) -> Vec<Spot> {
        let k = TAU / wavelength;
        let vz = self.method_split(wavelength).vz().min(2.0 * k);
        self.sampling_spots(self.sampling_refinement(vz).min(MAX_REFINEMENT))
    }

    /// The mean over `spots` of the directions and shares `each` makes of a spot (`None` for a
    /// spot without a measured point): the shares divided by the number of spots that have one.
    fn spot_mean(
        &self,
        spots: &[Spot],
        mut each: impl FnMut(&Spot) -> Option<Vec<(DVec3, f64)>>,
    ) -> Vec<(DVec3, f64)> {
        let mut out = Vec::new();
        let mut count = 0;
        for spot in spots {
            if let Some(part) = each(spot) {
                out.extend(part);
                count += 1;
            }
        }
        if count > 1 {
            let share = 1.0 / count as f64;
            out.iter_mut().for_each(|(_, s)| *s *= share);
        }
        out
    }

    /// `f` of the facet grid of refinement `r` over `spot` and its shadowing: the engine's own
    /// grid (built once) for its own spot, else a grid built for this call and dropped after
    /// it, so that memory holds one grid of the smaller spots at a time.
    fn with_grid<T>(
        &self,
        spot: &Spot,
        r: usize,
        f: impl FnOnce(&FacetGrid, &Shadowing) -> T,
    ) -> T {
        if *spot == self.spot {
            f(self.grid(r), self.shadowing(r))
        } else {
            let grid = FacetGrid::build(&self.spline, spot, r);
            f(&grid, &self.shadowing_of(&grid, r))
        }
    }

    /// The expected cost of [`Kirchhoff::hemisphere`] for light of `wavelength` metres from
    /// `wi`, in nanoseconds of one core (calibrated on the project's machine; a progress
    /// display weighs the steps of a computation by it): [`NODE_CELL_NS`] per sampled cell and
    /// `vz` node of the integral's part, [`FACET_NS`] per facet of the stationary-phase limit,
    /// [`BUILD_CELL_NS`] per cell of the grids built for this map alone (those of smaller spots).
    pub fn hemisphere_cost(&self, wavelength: f64, wi: DVec3) -> Result<f64> {
        super::check_wavelength(wavelength)?;
        let k = TAU / wavelength;
        let split = self.method_split(wavelength);
        let spots = self.hemisphere_spots(wavelength);
        let cells = |r: usize| -> f64 {
            spots
                .iter()
                .map(|spot| self.cells(spot.diameter, r) as f64)
                .sum()
        };
        let built = if spots.len() > 1 { BUILD_CELL_NS } else { 0.0 };
        let mut cost = 0.0;
        if let Some(r) = self.hemisphere_refinement(wavelength, wi) {
            let span = split.vz().min(k * (wi.z + 1.0)) - k * wi.z;
            let nodes = (span * self.height_stats().1 / 0.5).ceil().max(3.0) + 1.0;
            cost += (NODE_CELL_NS * nodes + built) * cells(r);
        }
        if split.cos_sum() < wi.z + 1.0 {
            // The facets inside the spots' circles: π/4 of their grids' cells.
            cost += (FACET_NS * PI / 4.0 + built) * cells(1);
        }
        Ok(cost)
    }

    /// Refinement of the sampled grid of the integral's part of [`Kirchhoff::scattered`]: for
    /// the largest `|vz|` of the directions below the split, `None` when there are none (the
    /// stationary-phase limit covers the whole hemisphere).
    fn hemisphere_refinement(&self, wavelength: f64, wi: DVec3) -> Option<usize> {
        let k = TAU / wavelength;
        let split = self.method_split(wavelength).vz();
        (split > k * wi.z).then(|| self.sampling_refinement(split.min(k * (wi.z + 1.0))))
    }

    /// As [`Kirchhoff::scattered`], for the lattice directions inside the cone of `detector`
    /// only, all from the integral. FFTs are needed only at the `vz` nodes that the cone spans,
    /// so a narrow cone (a gloss meter's receptors about the specular direction) costs a few
    /// FFTs instead of dozens.
    pub fn scattered_in_cone(
        &self,
        wavelength: f64,
        wi: DVec3,
        detector: &Detector,
    ) -> Result<Vec<(DVec3, f64)>> {
        super::check_wavelength(wavelength)?;
        let cos_alpha = detector.half_angle.cos();
        let axis = detector.direction.normalize();
        let k = TAU / wavelength;
        let r = self.cone_sampling_refinement(k, wi, detector);
        self.check_refinement(r, wavelength)?;
        let keep = |wo: DVec3| wo.dot(axis) >= cos_alpha;
        Ok(self.spot_mean(&self.sampling_spots(r), |spot| {
            self.with_grid(spot, r, |grid, shadowing| {
                (grid.w2_area > 0.0).then(|| self.scattered_on(grid, shadowing, k, wi, &keep))
            })
        }))
    }

    /// The lattice of outgoing directions that `keep` accepts, with their shares of the
    /// reflectance (times `G2(wi, wo)` of `shadowing`), from the sampled grid `facets`.
    fn scattered_on(
        &self,
        facets: &FacetGrid,
        shadowing: &Shadowing,
        k: f64,
        wi: DVec3,
        keep: &(impl Fn(DVec3) -> bool + Sync),
    ) -> Vec<(DVec3, f64)> {
        let height = facets
            .h
            .iter()
            .zip(&facets.w)
            .filter(|(_, w)| **w > 0.0)
            .fold(0.0f64, |m, (h, _)| m.max(h.abs()));
        let (dvx, dvy) = lattice_spacing(facets);
        let (nx, ny) = (facets.nx, facets.ny);
        // Signed lattice indices whose directions can lie above the surface (`|wo.x| ≤ 1` with
        // `vx = -k (wi.x + wo.x)`), within the lattice: the columns to transform.
        let range = |n: usize, dv: f64, w: f64| {
            let (lo, hi) = (-(n as isize / 2), (n as isize - 1) / 2);
            let first = ((-k * (1.0 + w) / dv).floor() as isize).max(lo);
            let last = ((k * (1.0 - w) / dv).ceil() as isize).min(hi);
            first..=last
        };
        let (ps, qs) = (range(nx, dvx, wi.x), range(ny, dvy, wi.y));
        // Directions of the lattice points and the vz range they span.
        let points: Vec<(isize, isize, DVec3)> = ps
            .clone()
            .into_par_iter()
            .flat_map_iter(|p| {
                qs.clone().filter_map(move |q| {
                    outgoing(k, wi, p as f64 * dvx, q as f64 * dvy)
                        .filter(|&wo| keep(wo))
                        .map(|wo| (p, q, wo))
                })
            })
            .collect();
        if points.is_empty() {
            return Vec::new();
        }
        let vz_of = |wo: DVec3| -k * (wi.z + wo.z);
        let (lo, hi) = points.iter().fold(
            (f64::INFINITY, f64::NEG_INFINITY),
            |(lo, hi), &(_, _, wo)| (lo.min(vz_of(wo)), hi.max(vz_of(wo))),
        );
        let p_first = points.iter().map(|&(p, _, _)| p).min().unwrap_or(0);
        let p_last = points.iter().map(|&(p, _, _)| p).max().unwrap_or(0);
        let columns = Columns {
            first: p_first,
            count: (p_last - p_first + 1) as usize,
        };
        let nodes = (((hi - lo) * height / 0.5).ceil() as usize + 1).max(4);
        let step = (hi - lo) / (nodes - 1) as f64;
        let norm = dvx * dvy * wi.z / (4.0 * PI * PI * facets.w2_area);
        let lambda_wi = shadowing.lambda_exact(wi);
        let mut bins: Vec<Bin> = points
            .iter()
            .map(|&(p, q, wo)| {
                let x = if step > 0.0 {
                    (vz_of(wo) - lo) / step
                } else {
                    0.0
                };
                let node = (x.floor() as usize).saturating_sub(1).min(nodes - 4);
                Bin {
                    index: (p - p_first) as usize * ny + q.rem_euclid(ny as isize) as usize,
                    wo,
                    node,
                    t: x - node as f64,
                    weight: shadowing.g2(lambda_wi, wo) * brdf_factor(self.ior, wi, wo) * norm
                        / wo.z,
                }
            })
            .collect();
        bins.sort_by_key(|b| b.node);
        // Each node's transform is added into the fields of the bins it serves (those whose
        // four nodes include it) as soon as it is made, so one transform is held at a time, in
        // buffers reused from node to node: no grid-sized allocation per node.
        let mut fields = vec![Complex64::default(); bins.len()];
        let mut buffers = SpectrumBuffers::new(ny, columns);
        for node in 0..nodes {
            let spectrum = buffers.spectrum(facets, lo + node as f64 * step);
            let first = bins.partition_point(|b| b.node + 3 < node);
            let last = bins.partition_point(|b| b.node <= node);
            fields[first..last]
                .par_iter_mut()
                .zip(&bins[first..last])
                .for_each(|(e, b)| *e += spectrum[b.index] * lagrange4(b.t)[node - b.node]);
        }
        bins.iter()
            .zip(&fields)
            .map(|(b, e)| (b.wo, b.weight * e.norm_sqr()))
            .collect()
    }
}

/// The columns of the lattice a transform needs: signed `p` from `first` on, `count` of them.
#[derive(Debug, Clone, Copy)]
struct Columns {
    first: isize,
    count: usize,
}

/// The buffers of [`SpectrumBuffers::spectrum`], made once per facet grid: the needed columns of
/// the row transforms, row by row and then transposed.
struct SpectrumBuffers {
    columns: Columns,
    rows: Vec<Complex64>,
    transposed: Vec<Complex64>,
}

impl SpectrumBuffers {
    fn new(ny: usize, columns: Columns) -> SpectrumBuffers {
        SpectrumBuffers {
            columns,
            rows: vec![Complex64::default(); columns.count * ny],
            transposed: vec![Complex64::default(); columns.count * ny],
        }
    }

    /// The 2D transform `Σ_j A_j exp(i vz h_j) exp(i (vx x_j + vy y_j))` on the lattice columns
    /// of [`Columns`], transposed: element `c * ny + q` holds
    /// `(vx, vy) = ((first + c) Δvx, q Δvy)` (`q` modulo the grid size). Each row is
    /// transformed whole and its needed columns kept; those are then transformed. Rows and
    /// columns run in parallel, each a fixed computation, so the result does not depend on the
    /// thread count.
    fn spectrum(&mut self, facets: &FacetGrid, vz: f64) -> &[Complex64] {
        let (nx, ny) = (facets.nx, facets.ny);
        let Columns { first, count } = self.columns;
        let area = facets.ax * facets.ay;
        self.rows.par_chunks_mut(count).enumerate().for_each_init(
            || {
                let scratch = facets.row_fft.get_inplace_scratch_len();
                (
                    vec![Complex64::default(); nx],
                    vec![Complex64::default(); scratch],
                )
            },
            |(row, scratch), (m, kept)| {
                let cells = facets.row(m);
                fill_row_sampled(cells.h, cells.w, vz, area, row);
                facets.row_fft.process_with_scratch(row, scratch);
                for (c, out) in kept.iter_mut().enumerate() {
                    *out = row[(first + c as isize).rem_euclid(nx as isize) as usize];
                }
            },
        );
        gonio_fft::fft2::transpose_into(&self.rows, ny, count, &mut self.transposed);
        self.transposed.par_chunks_mut(ny).for_each_init(
            || vec![Complex64::default(); facets.col_fft.get_inplace_scratch_len()],
            |scratch, column| facets.col_fft.process_with_scratch(column, scratch),
        );
        &self.transposed
    }
}

/// Lagrange weights of the nodes 0, 1, 2, 3 at position `t`.
fn lagrange4(t: f64) -> [f64; 4] {
    [
        -(t - 1.0) * (t - 2.0) * (t - 3.0) / 6.0,
        t * (t - 2.0) * (t - 3.0) / 2.0,
        -t * (t - 1.0) * (t - 3.0) / 2.0,
        t * (t - 1.0) * (t - 2.0) / 6.0,
    ]
}
