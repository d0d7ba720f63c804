//! The ray method: the BRDF of a height map by geometric optics.
//!
//! Every interior grid point of the map is a facet with the normal the `surface` crate computes
//! (least-squares plane or bicubic spline). Under uniform illumination from `wi`, a facet
//! reflects `wr = 2(wi·n)n - wi` and carries the share `R(wi·n) (wi·n) / (n_z N cos ti)` of the
//! reflectance (`docs/ray-method.md`, "Method"), with the Fresnel reflectance `R` of a
//! dielectric or a metal at its local angle. Facets the source cannot see (shadowing) or whose
//! reflected ray meets the surface again (masking) are found by marching over the height field;
//! an optional second bounce follows masked rays one more reflection. Each lit facet of a
//! dielectric also refracts the rest of its share, `1 - R(wi·n)`, into the material by Snell's
//! law (`transmission`), masked when it meets the surface again from below.
//!
//! The engine is planned once per map ([`RayEngine::new`]: normals, facet table, height field)
//! and then queried per incidence: [`RayEngine::detect`] for any set of cone detectors (exact
//! cone test, O(N + D·k) through a direction index, `index`), [`RayEngine::detect_hemisphere`]
//! for a grid of cells that tiles the hemisphere, [`RayEngine::inplane`] for an in-plane curve;
//! [`RayEngine::transmit_hemisphere`] for the transmitted light on the mirrored grid below the
//! surface and [`RayEngine::energy_budget`] for where the incident power goes.
//! Results do not depend on the number of threads: every detector or cell sums its rays in a
//! fixed order.
//!
//! ```no_run
//! use gonio_scatter::ray::{RayEngine, RayOptions};
//! use gonio_scatter::{Goniometer, InplaneMethod};
//! let map = gonio_surface::io::read(std::path::Path::new("sample.x3p"))?;
//! let engine = RayEngine::new(&map, RayOptions::default())?;
//! // Incidence 20/45/60/70°, scatter -75..75° in 1° steps, 1.4° detectors.
//! let curves = engine.inplane_curves(&Goniometer::starr(), &[], &Default::default())?;
//! println!("specular BRDF at 20° {} 1/sr", curves[0].points[95].brdf_per_sr);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod hemisphere;
mod horizon;
mod index;
mod march;
mod reflected;
mod trace;
mod transmission;

#[cfg(test)]
mod tests;

pub use hemisphere::{HemisphereGrid, HemisphereTable, TransmissionTable};
pub use transmission::EnergyBudget;

use hemisphere::CellLocator;

use crate::error::{Result, ScatterError};
use crate::geometry::{
    CurvePoint, Detector, InplaneCurve, incidence_direction, inplane_direction, label_value,
};
use glam::DVec3;
use gonio_brdf::Ior;
use gonio_brdf::fresnel::Polarised;
use gonio_brdf::table::coords::turn_about_z;
use gonio_surface::HeightMap;
use gonio_surface::normals::{NormalMethod, facet_normals};
use index::{BinMask, DirectionIndex, Sums};
use march::HeightField;
use ndarray::Array2;
use rayon::prelude::*;
use reflected::Ray;
use std::sync::OnceLock;
use trace::{Facet, Tracer};

/// Options of the ray method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayOptions {
    /// Refractive index of the material under the surface.
    pub ior: Ior,
    /// How facet normals are estimated from the heights.
    pub normals: NormalMethod,
    /// Shadowing and masking by the height field (a facet counts only if the source sees it and
    /// its reflected ray leaves the surface). Off reproduces the original ray method, in which
    /// every facet facing the source reflects into the upper hemisphere unobstructed.
    pub shadowing: bool,
    /// Follow a masked ray through one more specular reflection (needs `shadowing`).
    pub second_bounce: bool,
    /// Number of azimuths of incidence to average over (1: none). The source is rotated about z
    /// in steps of `360°/azimuths` and the detectors with it, which averages an isotropic
    /// surface's BRDF over more facets; keep 1 for an anisotropic surface.
    pub azimuths: usize,
    /// Also track s- and p-polarised reflectance (relative to each facet's local plane of
    /// incidence). Slower: the Fresnel formula is evaluated in complex arithmetic.
    pub polarised: bool,
}

impl Default for RayOptions {
    /// Index 1.55, plane-fit normals, shadowing and masking on, one bounce, no azimuthal
    /// averaging, unpolarised.
    fn default() -> Self {
        RayOptions {
            ior: Ior::Dielectric(1.55),
            normals: NormalMethod::Plane,
            shadowing: true,
            second_bounce: false,
            azimuths: 1,
            polarised: false,
        }
    }
}

/// A ray leaving the surface, as [`RayEngine::fold_rays`] hands it out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reflected {
    /// Index of the facet that reflected it (see [`RayEngine::facet_normal`]).
    pub facet: usize,
    /// Unit direction (`z > 0`) in the frame of the source direction.
    pub direction: DVec3,
    /// Share of the directional-hemispherical reflectance it carries.
    pub share: f64,
}

/// What one cone detector read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// Reflectance `rho` collected by the detector (unpolarised).
    pub reflectance: f64,
    /// BRDF averaged over the detector, `rho / (Omega cos ts)`, 1/sr.
    pub brdf_per_sr: f64,
    /// s- and p-polarised reflectance, when polarisation is tracked.
    pub polarised: Option<Polarised>,
    /// Number of rays that reached the detector (summed over azimuths).
    pub hits: u64,
}

impl Reading {
    /// Relative standard uncertainty of `reflectance` from counting statistics, `1/√hits`
    /// (infinite with no hit).
    pub fn rel_uncertainty(&self) -> f64 {
        1.0 / (self.hits as f64).sqrt()
    }
}

/// A planned ray-method engine for one height map: facets, normals and height field computed
/// once, then queried for any number of incidences and detector sets.
pub struct RayEngine {
    facets: Vec<Facet>,
    normals: Array2<DVec3>,
    field: HeightField,
    /// The height field seen from inside the material, for the masking of refracted rays
    /// (made when transmission is first asked for).
    below: OnceLock<HeightField>,
    options: RayOptions,
}

impl RayEngine {
    /// Plan the engine for the sample as an instrument sees it: the map less its least-squares
    /// plane (a goniometer or a gloss meter takes its angles from the sample's mean plane,
    /// while a profiler's file keeps the sample's tilt under the profiler: 0.44° in a confocal
    /// file of the test data, which turned every reflected ray by 0.9° and lost half the 20°
    /// gloss), then facet normals by `options.normals`, the facet table and the height field
    /// used for shadowing. [`RayEngine::from_normals`] takes a map as it is.
    pub fn new(map: &HeightMap, options: RayOptions) -> Result<Self> {
        Self::check_map(map)?;
        let levelled = gonio_surface::ops::level(map)?;
        let normals = facet_normals(&levelled, options.normals);
        Self::from_normals(&levelled, normals, options)
    }

    /// Plan the engine with given unit normals of shape `(ny, nx)` (NaN where a point is not a
    /// facet).
    pub fn from_normals(
        map: &HeightMap,
        normals: Array2<DVec3>,
        options: RayOptions,
    ) -> Result<Self> {
        Self::check_map(map)?;
        if normals.dim() != (map.ny(), map.nx()) {
            return Err(ScatterError::Invalid(format!(
                "normals of shape {:?} do not match the {} × {} map",
                normals.dim(),
                map.nx(),
                map.ny()
            )));
        }
        if options.azimuths == 0 {
            return Err(ScatterError::Invalid(
                "the number of azimuths must be at least 1".into(),
            ));
        }
        if options.second_bounce && !options.shadowing {
            return Err(ScatterError::Invalid(
                "a second bounce needs shadowing and masking on: without them no ray meets the \
                 surface again"
                    .into(),
            ));
        }
        let (nx, ny) = (map.nx(), map.ny());
        let heights: Vec<f64> = map.heights().iter().copied().collect();
        let field = HeightField::new(heights, nx, ny, map.dx(), map.dy());
        let facets: Vec<Facet> = normals
            .indexed_iter()
            .filter(|(_, n)| n.is_finite() && n.z > 0.0)
            .map(|((iy, ix), &n)| Facet {
                pos: field.point(ix, iy),
                n,
                index: iy * nx + ix,
            })
            .collect();
        if facets.is_empty() {
            return Err(ScatterError::Invalid(format!(
                "the {nx} × {ny} map has no interior point with a valid 3 × 3 neighbourhood"
            )));
        }
        Ok(RayEngine {
            facets,
            normals,
            field,
            below: OnceLock::new(),
            options,
        })
    }

    fn check_map(map: &HeightMap) -> Result<()> {
        if map.nx() < 3 || map.ny() < 3 {
            return Err(ScatterError::Invalid(format!(
                "the map is {} × {} points; the ray method needs at least 3 × 3",
                map.nx(),
                map.ny()
            )));
        }
        Ok(())
    }

    /// The options the engine was planned with.
    pub fn options(&self) -> &RayOptions {
        &self.options
    }

    /// Number of facets N (grid points with a valid normal).
    pub fn facet_count(&self) -> usize {
        self.facets.len()
    }

    /// Position of facet `i` in metres (`x = ix dx`, `y = iy dy`, its height).
    pub fn facet_position(&self, i: usize) -> DVec3 {
        self.facets[i].pos
    }

    /// Unit normal of facet `i` (`0 <= i < facet_count()`, the order of [`Reflected::facet`]).
    pub fn facet_normal(&self, i: usize) -> DVec3 {
        self.facets[i].n
    }

    /// Whether every ray [`RayEngine::fold_rays`] hands out is one specular reflection at its
    /// facet, in the frame of the source: then its half vector with the source direction,
    /// `(wi + wo) / |wi + wo| = n` since `wi + wo = 2 (wi·n) n`, is the facet's normal, for
    /// every incidence. True with one azimuth of incidence and no second bounce.
    pub fn half_vectors_are_normals(&self) -> bool {
        self.options.azimuths == 1 && !self.options.second_bounce
    }

    /// Measured rms slopes `(sx, sy)` of the facets along x and y, `-n_x/n_z` and `-n_y/n_z`
    /// about their means: the per-axis rms slopes a facet model of this map should use.
    pub fn rms_slopes(&self) -> (f64, f64) {
        let n = self.facets.len() as f64;
        let (mut mx, mut my) = (0.0, 0.0);
        for f in &self.facets {
            mx += -f.n.x / f.n.z;
            my += -f.n.y / f.n.z;
        }
        let (mx, my) = (mx / n, my / n);
        let (mut vx, mut vy) = (0.0, 0.0);
        for f in &self.facets {
            vx += (-f.n.x / f.n.z - mx).powi(2);
            vy += (-f.n.y / f.n.z - my).powi(2);
        }
        ((vx / n).sqrt(), (vy / n).sqrt())
    }

    /// Mean Fresnel reflectance `R(wi·n)` over all facets (zero for those facing away): what a
    /// full hemisphere collects from a gently sloped surface without shadowing.
    pub fn mean_facet_reflectance(&self, wi: DVec3) -> Result<f64> {
        let wi = check_incidence(wi)?;
        let sum: f64 = self
            .facets
            .iter()
            .map(|f| {
                let c = wi.dot(f.n);
                if c > 0.0 {
                    self.options.ior.reflectance(c)
                } else {
                    0.0
                }
            })
            .sum();
        Ok(sum / self.facets.len() as f64)
    }

    /// The tracer for source direction `wi` turned to azimuth step `k`.
    fn tracer<'a>(&'a self, wi: DVec3, k: usize, wanted: Option<&'a BinMask>) -> Tracer<'a> {
        let phi = std::f64::consts::TAU * k as f64 / self.options.azimuths as f64;
        let (sin, cos) = phi.sin_cos();
        let wi_map = turn_about_z(wi, phi);
        // The horizon map the shadowing test reads, if the source lies along a grid axis (made
        // here, before the parallel loops, so that no worker waits for another to make it).
        let source_horizon = self
            .options
            .shadowing
            .then(|| self.field.horizon(wi_map))
            .flatten()
            .map(|h| {
                (
                    h,
                    wi_map.z / (wi_map.x * wi_map.x + wi_map.y * wi_map.y).sqrt(),
                )
            });
        Tracer {
            field: &self.field,
            normals: &self.normals,
            ior: self.options.ior,
            polarised: self.options.polarised,
            shadowing: self.options.shadowing,
            second_bounce: self.options.second_bounce,
            wi: wi_map,
            source_horizon,
            to_detector: (cos, -sin),
            scale: 1.0 / (self.facets.len() as f64 * wi.z),
            wanted,
        }
    }

    /// The rays that leave the surface for source direction `wi` at azimuth step `k`, rotated
    /// back into the detectors' frame, in facet order; only those in `wanted` bins if given.
    fn rays(&self, wi: DVec3, k: usize, wanted: Option<&BinMask>) -> Vec<Ray> {
        let tracer = self.tracer(wi, k, wanted);
        self.facets
            .par_iter()
            .filter_map(|f| tracer.trace(f))
            .collect()
    }

    /// Every ray that leaves the surface for a source in direction `wi` (unit, `z > 0`), as
    /// `(direction, reflectance carried)`, over all azimuths of incidence (rotated back into the
    /// frame of `wi`, each carrying its share divided by the number of azimuths), in a fixed
    /// order. The shares add up to the directional-hemispherical reflectance: the input of any
    /// binning other than cones or [`HemisphereGrid`] (for instance a tabulated BRDF's cells).
    pub fn reflected_rays(&self, wi: DVec3) -> Result<Vec<(DVec3, f64)>> {
        let wi = check_incidence(wi)?;
        let per_azimuth = 1.0 / self.options.azimuths as f64;
        let mut out = Vec::new();
        for k in 0..self.options.azimuths {
            out.extend(
                self.rays(wi, k, None)
                    .iter()
                    .map(|r| (r.d, r.w * per_azimuth)),
            );
        }
        Ok(out)
    }

    /// Fold every ray that leaves the surface for a source in direction `wi` (unit, `z > 0`)
    /// into partial results without storing the rays: each fixed chunk of facets (per azimuth
    /// of incidence) hands its rays, in facet order and in batches of up to [`RAY_BATCH`]
    /// facets' rays, to `fold` with a value of its own made by `init`, and the partials come
    /// back in chunk order (azimuth slowest). The chunks and batches are the same on any number
    /// of threads, so adding the partials in order gives the same result on any number of
    /// threads. Directions and shares are those of [`RayEngine::reflected_rays`]. (Batches let
    /// the caller's binning run over many independent rays at once instead of one ray between
    /// two traces.)
    pub fn fold_rays<T: Send>(
        &self,
        wi: DVec3,
        init: impl Fn() -> T + Sync,
        fold: impl Fn(&mut T, &[Reflected]) + Sync,
    ) -> Result<Vec<T>> {
        let wi = check_incidence(wi)?;
        let per_azimuth = 1.0 / self.options.azimuths as f64;
        Ok(self.fold_chunks(
            wi,
            FOLD_CHUNK,
            init,
            |tracer, facet, f| {
                tracer.trace(f).map(|ray| Reflected {
                    facet,
                    direction: ray.d,
                    share: ray.w * per_azimuth,
                })
            },
            fold,
        ))
    }

    /// What `visit` makes of each facet (with its index) for each fixed chunk of facets (per
    /// azimuth step; [`chunk_len`] facets, at most `max_chunk`), handed to `fold` in batches of
    /// up to [`RAY_BATCH`] facets' results, folded into one partial result per chunk, in chunk
    /// order.
    fn fold_chunks<T: Send, E>(
        &self,
        wi: DVec3,
        max_chunk: usize,
        init: impl Fn() -> T + Sync,
        visit: impl Fn(&Tracer, usize, &Facet) -> Option<E> + Sync,
        fold: impl Fn(&mut T, &[E]) + Sync,
    ) -> Vec<T> {
        let chunk = chunk_len(self.facets.len(), max_chunk);
        let mut out = Vec::new();
        for k in 0..self.options.azimuths {
            let tracer = self.tracer(wi, k, None);
            let partials: Vec<T> = self
                .facets
                .par_chunks(chunk)
                .enumerate()
                .map(|(c, facets)| {
                    let mut part = init();
                    let mut found = Vec::with_capacity(RAY_BATCH);
                    for (b, batch) in facets.chunks(RAY_BATCH).enumerate() {
                        let first = c * chunk + b * RAY_BATCH;
                        found.clear();
                        found.extend(
                            batch
                                .iter()
                                .enumerate()
                                .filter_map(|(i, f)| visit(&tracer, first + i, f)),
                        );
                        fold(&mut part, &found);
                    }
                    part
                })
                .collect();
            out.extend(partials);
        }
        out
    }

    /// Read a set of cone detectors for a source in direction `wi` (unit, `z > 0`).
    ///
    /// Each detector sums the rays inside its cone (`wo·d > cos alpha`); its reflectance is the
    /// sum of the rays' shares, and its BRDF `rho / (Omega cos theta)`.
    pub fn detect(&self, wi: DVec3, detectors: &[Detector]) -> Result<Vec<Reading>> {
        let wi = check_incidence(wi)?;
        let Some(min_half_angle) = check_detectors(detectors)? else {
            return Ok(Vec::new());
        };
        let g = bins_for(min_half_angle, self.facets.len());
        let wanted = BinMask::new(detectors, g);
        let mut totals = vec![Sums::default(); detectors.len()];
        for k in 0..self.options.azimuths {
            let index = DirectionIndex::new(&self.rays(wi, k, Some(&wanted)), g);
            let sums: Vec<Sums> = detectors.par_iter().map(|d| index.collect(d)).collect();
            for (t, s) in totals.iter_mut().zip(&sums) {
                t.add(s);
            }
        }
        Ok(detectors
            .iter()
            .zip(&totals)
            .map(|(d, s)| self.reading(d, s))
            .collect())
    }

    fn reading(&self, det: &Detector, sums: &Sums) -> Reading {
        let per_azimuth = 1.0 / self.options.azimuths as f64;
        let reflectance = sums.w * per_azimuth;
        Reading {
            reflectance,
            brdf_per_sr: reflectance / (det.solid_angle() * det.direction.z),
            polarised: self.options.polarised.then_some(Polarised {
                s: sums.ws * per_azimuth,
                p: sums.wp * per_azimuth,
            }),
            hits: sums.hits,
        }
    }

    /// Sum the light leaving the surface for a source in direction `wi` into the cells of a
    /// hemisphere grid. Every ray that leaves lands in exactly one cell.
    ///
    /// No ray is stored: each fixed chunk of facets fills its own partial table, and the
    /// partial tables are added in chunk order (the same order whatever the thread count).
    pub fn detect_hemisphere(&self, wi: DVec3, grid: &HemisphereGrid) -> Result<HemisphereTable> {
        let wi = check_incidence(wi)?;
        Ok(self.hemisphere_table(wi, grid, |tracer, f| tracer.trace(f)))
    }

    /// The hemisphere table of the rays `ray_of` makes of each facet (directions with `z > 0`),
    /// summed per fixed chunk of facets and added in chunk order.
    fn hemisphere_table(
        &self,
        wi: DVec3,
        grid: &HemisphereGrid,
        ray_of: impl Fn(&Tracer, &Facet) -> Option<Ray> + Sync,
    ) -> HemisphereTable {
        let locator = CellLocator::new(*grid);
        let partials = self.fold_chunks(
            wi,
            HEMISPHERE_CHUNK,
            || vec![Sums::default(); grid.len()],
            |tracer, _, f| ray_of(tracer, f),
            |part, rays| {
                for ray in rays {
                    part[locator.cell(ray.d)].add_ray(ray);
                }
            },
        );
        let mut sums = vec![Sums::default(); grid.len()];
        for part in &partials {
            for (s, p) in sums.iter_mut().zip(part) {
                s.add(p);
            }
        }
        let per_azimuth = 1.0 / self.options.azimuths as f64;
        HemisphereTable::from_sums(*grid, &sums, per_azimuth, self.options.polarised)
    }

    /// The in-plane curve at incidence `theta_i` for detectors at the signed scattering angles
    /// `scatter` (specular at `+theta_i`, negative on the source's side, as on in-plane
    /// goniometers) with cone half-angle `half_angle`, all in radians like the other methods'
    /// (the [`crate::InplaneMethod`] of a [`crate::Goniometer`] calls it per incidence).
    pub fn inplane(&self, theta_i: f64, scatter: &[f64], half_angle: f64) -> Result<InplaneCurve> {
        let detectors: Vec<Detector> = scatter
            .iter()
            .map(|&ts| Detector {
                direction: inplane_direction(ts),
                half_angle,
            })
            .collect();
        let readings = self.detect(incidence_direction(theta_i), &detectors)?;
        Ok(InplaneCurve {
            method: "ray".into(),
            wavelength_nm: None,
            incidence_deg: label_value(theta_i.to_degrees()),
            points: scatter
                .iter()
                .zip(&readings)
                .map(|(&ts, r)| CurvePoint {
                    scatter_deg: label_value(ts.to_degrees()),
                    brdf_per_sr: r.brdf_per_sr,
                    reflectance: r.reflectance,
                    rel_uncertainty: Some(r.rel_uncertainty()),
                })
                .collect(),
        })
    }
}

/// The unit source direction, or an error if `wi` is not a finite direction above the surface.
fn check_incidence(wi: DVec3) -> Result<DVec3> {
    let len = wi.length();
    if !(len.is_finite() && len > 0.0 && wi.z / len > 1e-9) {
        return Err(ScatterError::Invalid(format!(
            "source direction {wi} must point above the surface (z > 0); incidence must be \
             below 90°"
        )));
    }
    Ok(wi / len)
}

/// Check every detector; returns the smallest half-angle, or `None` for an empty set.
fn check_detectors(detectors: &[Detector]) -> Result<Option<f64>> {
    for (i, d) in detectors.iter().enumerate() {
        if !(d.half_angle > 0.0 && d.half_angle < std::f64::consts::FRAC_PI_2) {
            return Err(ScatterError::Invalid(format!(
                "detector {i}: half-angle {}° must be in (0°, 90°)",
                d.half_angle.to_degrees()
            )));
        }
        if !((d.direction.length() - 1.0).abs() < 1e-9 && d.direction.z > 0.0) {
            return Err(ScatterError::Invalid(format!(
                "detector {i}: direction {} must be a unit vector above the surface (z > 0)",
                d.direction
            )));
        }
    }
    Ok(detectors.iter().map(|d| d.half_angle).reduce(f64::min))
}

/// Facets per chunk of a hemisphere run: each chunk fills one partial table (of up to a few
/// MB, so not too many of them).
const HEMISPHERE_CHUNK: usize = 1 << 16;

/// Facets traced before their rays are handed on together by [`RayEngine::fold_rays`].
pub const RAY_BATCH: usize = 256;

/// Most facets per chunk of [`RayEngine::fold_rays`], whose partial results are small (a
/// table's slice): 2¹⁴ facets keep the tail of a parallel run short (64 chunks for a 1024² map).
const FOLD_CHUNK: usize = 1 << 14;

/// Fewest chunks a run is cut into (per azimuth step) where its facets allow: a map of 128²
/// points in chunks of the largest size would be one chunk, traced on one thread.
const MIN_CHUNKS: usize = 16;

/// Fewest facets per chunk: four batches of [`RAY_BATCH`], so that a chunk's partial result is
/// worth its cost.
const MIN_CHUNK: usize = 4 * RAY_BATCH;

/// Facets per chunk of a run over `facets` facets whose chunks hold at most `max`: at least
/// [`MIN_CHUNKS`] chunks, of at least [`MIN_CHUNK`] facets. It depends on the map alone, never on
/// the thread count, so the partials, added in chunk order, give the same result on any number
/// of threads; maps of `16 max` facets or more keep chunks of `max`.
fn chunk_len(facets: usize, max: usize) -> usize {
    facets.div_ceil(MIN_CHUNKS).clamp(MIN_CHUNK, max)
}

/// Bins per axis of the direction index: about one smallest half-angle wide, so that a
/// detector visits a few bins, but no more bins than rays.
fn bins_for(min_half_angle: f64, rays: usize) -> usize {
    let by_angle = (2.0 / min_half_angle).ceil();
    let by_count = (rays as f64).sqrt().ceil();
    by_angle.min(by_count).clamp(1.0, 4096.0) as usize
}
