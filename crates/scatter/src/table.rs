//! Full tabulated BRDFs ([`BrdfTable`]) from a height map, by the ray method or the Kirchhoff
//! approximation: what `gonio brdf compute` runs.
//!
//! The table's cells (Rusinkiewicz half/difference nodes, see [`gonio_brdf::table::coords`])
//! each stand for a pair of directions with its own incidence, so the scattering engines are not
//! run per cell but per *incidence*: sources at `theta_i = k · 90° / n` (`k = 0 .. n - 1`), and,
//! for anisotropic tables, at azimuths `l · 360° / m`. For each source the reflected light is
//! binned over the half vector on nodes that are the table's own theta_h nodes (see `slice`:
//! tent weights and lumped measures, so that every node holds the BRDF averaged over its
//! neighbourhood, weighted by `cos theta_o`, and the slice keeps the reflected power exactly).
//! Each table cell then reads the slices of the incidences around its own `theta_i` (and
//! `phi_i`) at its half vector, interpolating linearly. Interpolating at a fixed half vector is
//! what makes few incidences enough: a specular lobe sits at the same `h` for every incidence,
//! and only its amplitude (Fresnel, shadowing) changes with `theta_i`.
//!
//! - Ray method: every ray the engine reflects is deposited as it is traced
//!   ([`RayEngine::fold_rays`]: fixed chunks of facets fill partial slices, added in order, so
//!   no ray is stored and the table is the same on any number of threads). A single specular
//!   reflection's half vector is its facet's normal (`wi + wo = 2 (wi·n) n`), so the
//!   half-vector coordinates of each facet are found once and serve every incidence; rays of a
//!   second bounce or of a turned source are binned from `wi + wo`.
//! - Kirchhoff: the full-hemisphere map [`Kirchhoff::hemisphere`] of each source and wavelength
//!   (cells of [`KIRCHHOFF_STEP_DEG`]) is deposited as if each cell were
//!   [`KIRCHHOFF_SPLIT`]² rays at its sub-cell centres, each carrying its share of the cell's
//!   reflectance. The table has one channel per wavelength.
//!
//! An isotropic table of a surface that is not isotropic must be the average over the azimuth
//! of incidence (the orientation of the sample under the instrument is arbitrary): each of its
//! incidences is run with the source turned about the normal to `incidence_azimuths` azimuths
//! (`l · 360° / m`), every ray turned back by the same angle into the frame of the unturned
//! source, and the slices of all turns averaged (then folded about the plane of incidence).
//! Turning source and rays together is turning the sample under a fixed instrument.
//!
//! Known limits: cells with `theta_i` beyond the last source take that source's slice; a lobe
//! narrower than the innermost theta_h node becomes a tent of that node's width (its power is
//! kept); a surface point between table cells reads the linear interpolation of the table.

pub mod cache;
mod slice;

use crate::error::{Result, ScatterError};
use crate::kirchhoff::{Kirchhoff, MethodSplit};
use crate::ray::{HemisphereGrid, HemisphereTable, RayEngine};
use glam::DVec3;
use gonio_brdf::table::coords::{TurnAboutZ, dir, theta_of, turn_about_z};
use gonio_brdf::table::{BrdfTable, Channels, Provenance, Resolution, TableBuilder};
use gonio_io::Progress;
use rayon::prelude::*;
use slice::{Slice, SliceGrid};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Cell size of the Kirchhoff hemisphere maps that are resampled into a table, degrees.
pub const KIRCHHOFF_STEP_DEG: f64 = 0.25;

/// Each Kirchhoff hemisphere cell is deposited as `KIRCHHOFF_SPLIT²` sub-cell rays.
pub const KIRCHHOFF_SPLIT: usize = 4;

/// Turns of the source an isotropic table of a moderately directional map (`Str` from
/// [`STR_ANISOTROPIC`] to [`STR_ISOTROPIC`], or unknown) averages over: 8, every 45°. The mean
/// of `m` equally spaced turns is exact for every azimuthal harmonic of order below `m`.
pub const MIXED_TURNS: usize = 8;

/// Turns for a map whose texture has a direction (`Str` below [`STR_ANISOTROPIC`]): 24, every
/// 15° as the default anisotropic table's azimuths. Cells near normal incidence read slices at
/// an azimuth that is arbitrary there, so the average must be nearly round: on a Gaussian map
/// with its y spacing stretched four times (tests/it/table.rs) the table's albedo at normal
/// incidence is 92% high from one turn, 8.6% from 8 and 0.6% from 24 (at 30° and 60° 8 and 24
/// turns agree to 0.1%).
pub const DIRECTIONAL_TURNS: usize = 24;

/// The table to compute and the incidences to compute it from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableOptions {
    /// Nodes of the table (`phi_h == 1`: isotropic).
    pub resolution: Resolution,
    /// Polar angles of the sources: `theta_i = k · 90° / n`, `k = 0 .. n - 1`.
    pub incidence_polar: usize,
    /// Azimuths of the sources, `phi_i = l · 360° / m`: for an isotropic table the turns it
    /// averages over (1: the surface is taken as isotropic), for an anisotropic one the
    /// azimuths it interpolates between (at least 4).
    pub incidence_azimuths: usize,
}

impl TableOptions {
    /// The default isotropic table: 32 theta_h nodes (square-root spacing: 0.09°, 0.35°, 0.8°,
    /// 1.4°, ... from the specular direction, so a lobe of rms slope 0.067 (3.8° in theta_h)
    /// spans 6 nodes), 90 theta_d nodes (1°), 180 phi_d nodes (2°), from 45 incidences every 2°,
    /// with one azimuth of incidence (the surface taken as isotropic: for a given map choose the
    /// turns with [`isotropic_turns`]).
    /// Halving the theta_d and phi_d counts triples the table's albedo error at 60° incidence
    /// (0.45% to 1.5%; see the tests).
    pub fn isotropic() -> TableOptions {
        TableOptions::for_resolution(Resolution::isotropic(32, 90, 180))
    }

    /// The default anisotropic table: 32 × 45 × 90 nodes (theta_d 2°, phi_d 4°) and 36 phi_h
    /// nodes (10°), from 45 × 24 incidences (2° by 15°).
    pub fn anisotropic() -> TableOptions {
        TableOptions {
            incidence_azimuths: 24,
            ..TableOptions::for_resolution(Resolution::anisotropic(32, 45, 90, 36))
        }
    }

    /// Options for a given table: one incidence per two theta_d nodes (theta_d runs from 0 to
    /// 90° as theta_i does near the specular direction; between incidences a cell reads the
    /// slices at its own half vector, where the BRDF changes slowly with theta_i),
    /// one azimuth when isotropic (see [`isotropic_turns`] for a map that is not), else one per
    /// phi_h node.
    pub fn for_resolution(resolution: Resolution) -> TableOptions {
        TableOptions {
            resolution,
            incidence_polar: resolution.theta_d.div_ceil(2).max(2),
            incidence_azimuths: if resolution.is_isotropic() {
                1
            } else {
                resolution.phi_h
            },
        }
    }

    /// Check the options, saying what to change.
    pub fn validate(&self) -> Result<()> {
        self.resolution.validate().map_err(ScatterError::Invalid)?;
        if self.incidence_polar < 2 {
            return Err(ScatterError::Invalid(format!(
                "{} incidence angles: a table needs at least 2",
                self.incidence_polar
            )));
        }
        match (self.resolution.is_isotropic(), self.incidence_azimuths) {
            (true, m) if m >= 1 => Ok(()),
            (true, _) => Err(ScatterError::Invalid(
                "0 azimuths of incidence for an isotropic table: it needs at least 1".into(),
            )),
            (false, m) if m >= 4 => Ok(()),
            (false, m) => Err(ScatterError::Invalid(format!(
                "{m} azimuths of incidence for an anisotropic table: it needs at least 4"
            ))),
        }
    }

    /// Number of incidences (engine runs per wavelength).
    pub fn incidence_count(&self) -> usize {
        self.incidence_polar * self.incidence_azimuths
    }

    /// The source directions of the slices, polar angle slowest: for an isotropic table one
    /// per polar angle, at azimuth 0 (each run at every one of [`TableOptions::turns`]).
    pub fn incidences(&self) -> Vec<DVec3> {
        let (n, m) = (self.incidence_polar, self.slice_azimuths());
        (0..n * m)
            .map(|i| {
                dir(
                    FRAC_PI_2 * (i / m) as f64 / n as f64,
                    TAU * (i % m) as f64 / m as f64,
                )
            })
            .collect()
    }

    /// Azimuths of the slices: 1 for an isotropic table (its turns are averaged into one slice).
    fn slice_azimuths(&self) -> usize {
        if self.resolution.is_isotropic() {
            1
        } else {
            self.incidence_azimuths
        }
    }

    /// The angles (radians) the source of each slice is turned to and its rays turned back
    /// from: `l · 360° / m` for an isotropic table, none (0) for an anisotropic one.
    pub fn turns(&self) -> Vec<f64> {
        if self.resolution.is_isotropic() {
            let m = self.incidence_azimuths;
            (0..m).map(|l| TAU * l as f64 / m as f64).collect()
        } else {
            vec![0.0]
        }
    }

    /// The incidences around a source direction `(theta_i, phi_i)` and their weights of linear
    /// interpolation (clamped beyond the last polar angle, periodic in azimuth).
    fn incidence_weights(&self, theta_i: f64, phi_i: f64) -> [(usize, f64); 4] {
        let (n, m) = (self.incidence_polar, self.slice_azimuths());
        let p = theta_i / FRAC_PI_2 * n as f64;
        let (k, t) = if p >= (n - 1) as f64 {
            (n - 2, 1.0)
        } else {
            let k = p.max(0.0).floor() as usize;
            (k, p.max(0.0) - k as f64)
        };
        let (l, s) = if m == 1 {
            (0, 0.0)
        } else {
            let q = (phi_i / TAU * m as f64).rem_euclid(m as f64);
            let l = (q.floor() as usize).min(m - 1);
            (l, q - l as f64)
        };
        let l1 = (l + 1) % m;
        [
            (k * m + l, (1.0 - t) * (1.0 - s)),
            (k * m + l1, (1.0 - t) * s),
            ((k + 1) * m + l, t * (1.0 - s)),
            ((k + 1) * m + l1, t * s),
        ]
    }

    /// Node values of incidence `k`, averaged over each ring of half vectors (keeping the
    /// ring's power, `Σ value·M`) when the table is isotropic and the incidence is normal: an
    /// isotropic BRDF at normal incidence does not depend on the azimuth of `h`, and cells near
    /// normal incidence, whose source azimuth is ill-defined, would otherwise read one azimuth
    /// of the slice at random.
    fn symmetrise(
        &self,
        k: usize,
        values: Vec<f64>,
        grid: &SliceGrid,
        measure: &[f64],
    ) -> Vec<f64> {
        if self.resolution.is_isotropic() && k == 0 {
            grid.ring_average(&values, measure)
        } else {
            values
        }
    }

    /// The half-vector nodes of one incidence.
    fn slice_grid(&self) -> SliceGrid {
        let res = self.resolution;
        if res.is_isotropic() {
            SliceGrid::new(res.theta_h, res.phi_d / 2 + 1, true)
        } else {
            SliceGrid::new(res.theta_h, res.phi_d, false)
        }
    }
}

/// Below this texture aspect ratio (ISO 25178-2 `Str`, 0 for a texture with one direction, 1
/// for an isotropic one) a surface's appearance depends on its orientation: 0.3 is the value
/// below which a texture is commonly called strongly directional. The x3p-2.x3p sample (Str
/// 0.026) has an albedo at normal incidence of 0.062 with its lay along x and 0.040 across it.
pub const STR_ANISOTROPIC: f64 = 0.3;

/// From this texture aspect ratio up a texture is commonly called isotropic (the synthetic
/// Gaussian maps of the epoxy series have 0.93).
pub const STR_ISOTROPIC: f64 = 0.5;

/// The texture aspect ratio `Str` of a map (ISO 25178-2), `None` when it cannot be found.
pub fn texture_aspect_ratio(map: &gonio_surface::HeightMap) -> Option<f64> {
    gonio_surface::stats::statistics(map).ok()?.str
}

/// Turns of the source an isotropic table of a map of texture aspect ratio `str_ratio` averages
/// over: 1 for an isotropic texture (`Str` of at least [`STR_ISOTROPIC`]: the map's own
/// azimuths average it, and one turn keeps the table within 0.1-0.9% of the rays from 20° to
/// 60° on such a map, `tests/it/table.rs`), [`DIRECTIONAL_TURNS`] for a directional one (`Str`
/// below [`STR_ANISOTROPIC`]), [`MIXED_TURNS`] between them or when `Str` is unknown.
pub fn isotropic_turns(str_ratio: Option<f64>) -> usize {
    match str_ratio {
        Some(s) if s >= STR_ISOTROPIC => 1,
        Some(s) if s < STR_ANISOTROPIC => DIRECTIONAL_TURNS,
        _ => MIXED_TURNS,
    }
}

/// A warning in plain words when an isotropic table is computed from a map whose texture has a
/// direction (`Str` below [`STR_ANISOTROPIC`]), saying what the table then is and how to make
/// the anisotropic one; `None` otherwise (or when `Str` is unknown).
pub fn anisotropy_warning(str_ratio: Option<f64>, options: &TableOptions) -> Option<String> {
    let str_ratio = str_ratio?;
    if !options.resolution.is_isotropic() || str_ratio >= STR_ANISOTROPIC {
        return None;
    }
    let what = match options.incidence_azimuths {
        1 => "taken with one azimuth of incidence (--incidence-azimuths 1), it holds one \
              orientation of the sample only"
            .to_string(),
        m => format!(
            "this isotropic table averages it over {m} azimuths of incidence, as for a sample \
             turned at random under the instrument"
        ),
    };
    Some(format!(
        "the surface's texture aspect ratio Str is {str_ratio:.3} (below {STR_ANISOTROPIC}: its \
         texture has a direction); {what}. For its appearance at a given orientation compute an \
         anisotropic table, e.g. --resolution 32,45,90,36"
    ))
}

/// The ray-method table of a planned engine: one monochrome channel (the ray method does not
/// depend on the wavelength). `progress` counts the engine runs (one per incidence and turn).
pub fn ray_table(
    engine: &RayEngine,
    options: &TableOptions,
    provenance: Provenance,
    progress: &Progress,
) -> Result<BrdfTable> {
    options.validate()?;
    let grid = options.slice_grid();
    let incidences = options.incidences();
    let mut slices = Vec::with_capacity(incidences.len());
    // A single reflection's half vector is its facet's normal: its coordinates, found once,
    // serve every incidence.
    let normals: Option<Vec<(f64, f64)>> = engine.half_vectors_are_normals().then(|| {
        (0..engine.facet_count())
            .into_par_iter()
            .map(|i| grid.coords(engine.facet_normal(i)))
            .collect()
    });
    let turns = options.turns();
    let runs = incidences.len() * turns.len();
    for (k, &wi) in incidences.iter().enumerate() {
        let mut partials = Vec::new();
        for (l, &turn) in turns.iter().enumerate() {
            partials.extend(ray_deposits(engine, &grid, wi, turn, normals.as_deref())?);
            progress.report("", (k * turns.len() + l + 1) as u64, runs as u64);
        }
        let measure = grid.measures(wi);
        let values = mean_of_turns(grid.values_from(&partials, &measure), turns.len());
        let values = options.symmetrise(k, values, &grid, &measure);
        slices.push(Slice::from_channels(&[values]));
    }
    fill(options, &grid, &slices, Channels::Mono, provenance)
}

/// Slice values summed over `turns` turns of the source, as their mean.
fn mean_of_turns(mut values: Vec<f64>, turns: usize) -> Vec<f64> {
    let inv = 1.0 / turns as f64;
    values.iter_mut().for_each(|v| *v *= inv);
    values
}

/// The partial deposits of every ray the engine reflects for a source in `wi` turned about the
/// normal by `turn`, each ray turned back by `turn` (so that the deposits are in the frame of
/// `wi`), one per chunk of facets in order. `normals`: the half-vector coordinates of every
/// facet's normal, which are those of each ray's half vector when the engine's rays are single
/// reflections ([`RayEngine::half_vectors_are_normals`]) and the source is not turned; else each
/// ray's half vector `wi + wo` is located.
fn ray_deposits(
    engine: &RayEngine,
    grid: &SliceGrid,
    wi: DVec3,
    turn: f64,
    normals: Option<&[(f64, f64)]>,
) -> Result<Vec<Vec<f64>>> {
    let source = turn_about_z(wi, turn);
    let back = TurnAboutZ::new(-turn);
    engine.fold_rays(
        source,
        || vec![0.0; grid.len()],
        |part, rays| match normals {
            Some(coords) if turn == 0.0 => {
                grid.deposit(part, rays.iter().map(|r| (coords[r.facet], r.share)));
            }
            _ => {
                let coords = rays
                    .iter()
                    .map(|r| (grid.coords(back.apply(source + r.direction)), r.share));
                grid.deposit(part, coords);
            }
        },
    )
}

/// Cost of depositing one sub-cell ray of a hemisphere map on a slice, nanoseconds of one core
/// (measured with the 805 nm epoxy map: about 0.3 s per map of 0.25° cells): the table's share
/// of each run's cost beside [`Kirchhoff::hemisphere_cost`].
const DEPOSIT_RAY_NS: f64 = 35.0;

/// The Kirchhoff table of a planned engine at the given wavelengths (nm, strictly increasing):
/// one channel per wavelength (a monochrome table for a single wavelength, which is then
/// recorded in the provenance as `wavelength_nm`). Where the Rayleigh parameter is large the
/// engine's hemisphere maps use the integral's stationary-phase limit ([`kirchhoff_methods`]
/// says where; recorded in the provenance as `kirchhoff_methods`). `progress` gets a report of
/// no step when the work begins, then one per hemisphere map (one per incidence, wavelength and
/// turn), its steps weighted by the expected cost of each map ([`Kirchhoff::hemisphere_cost`]),
/// so that the share done is the share of the time.
pub fn kirchhoff_table(
    engine: &Kirchhoff,
    wavelengths_nm: &[f64],
    options: &TableOptions,
    mut provenance: Provenance,
    progress: &Progress,
) -> Result<BrdfTable> {
    options.validate()?;
    let channels = match wavelengths_nm {
        [] => {
            return Err(ScatterError::Invalid(
                "the Kirchhoff method needs at least one wavelength".into(),
            ));
        }
        // A table needs two wavelengths to be spectral: one is a monochrome table, with the
        // wavelength in its provenance.
        [nm] => {
            provenance
                .extra
                .insert("wavelength_nm".into(), serde_json::json!(nm));
            Channels::Mono
        }
        _ => Channels::Spectral {
            wavelengths_nm: wavelengths_nm.to_vec(),
        },
    };
    channels.validate().map_err(ScatterError::Invalid)?;
    let methods: Vec<serde_json::Value> = kirchhoff_methods(engine, wavelengths_nm, options)?
        .iter()
        .map(KirchhoffMethods::to_json)
        .collect();
    provenance
        .extra
        .insert("kirchhoff_methods".into(), serde_json::json!(methods));
    provenance.extra.insert(
        "kirchhoff_shadowing".into(),
        serde_json::json!(engine.shadowing_enabled()),
    );
    let hemisphere = HemisphereGrid::with_step_deg(KIRCHHOFF_STEP_DEG)?;
    let grid = options.slice_grid();
    let incidences = options.incidences();
    let turns = options.turns();
    // The runs in the order they are made, with their expected costs (nanoseconds).
    let deposit = DEPOSIT_RAY_NS * (hemisphere.len() * KIRCHHOFF_SPLIT * KIRCHHOFF_SPLIT) as f64;
    let mut costs = Vec::with_capacity(incidences.len() * wavelengths_nm.len() * turns.len());
    for &wi in &incidences {
        for &nm in wavelengths_nm {
            for &turn in &turns {
                costs.push(engine.hemisphere_cost(nm * 1e-9, turn_about_z(wi, turn))? + deposit);
            }
        }
    }
    let total = costs.iter().sum::<f64>().ceil() as u64;
    progress.report("", 0, total);
    let mut done = 0.0;
    let mut run = 0;
    let mut slices = Vec::with_capacity(incidences.len());
    for (k, &wi) in incidences.iter().enumerate() {
        let measure = grid.measures(wi);
        let mut per_channel = Vec::with_capacity(wavelengths_nm.len());
        for &nm in wavelengths_nm {
            let mut partials = Vec::new();
            for &turn in &turns {
                let map = engine.hemisphere(nm * 1e-9, turn_about_z(wi, turn), &hemisphere)?;
                partials.extend(hemisphere_deposits(&grid, wi, turn, &map));
                done += costs[run];
                run += 1;
                let reported = if run == costs.len() {
                    total
                } else {
                    (done as u64).min(total)
                };
                progress.report("", reported, total);
            }
            let values = mean_of_turns(grid.values_from(&partials, &measure), turns.len());
            per_channel.push(options.symmetrise(k, values, &grid, &measure));
        }
        slices.push(Slice::from_channels(&per_channel));
    }
    fill(options, &grid, &slices, channels, provenance)
}

/// Where a Kirchhoff table at one wavelength uses the integral and where its stationary-phase
/// limit (see [`Kirchhoff::method_split`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KirchhoffMethods {
    /// The split: the limit where `g = (k σ (cos ti + cos to))²` exceeds its threshold.
    pub split: MethodSplit,
    /// The share of the table's pairs of directions that the limit covers: the mean over the
    /// computed incidences of [`MethodSplit::geometric_share`].
    pub geometric_share: f64,
    /// The first computed incidence (degrees) at which the integral is used for some outgoing
    /// directions; `None` when it never is.
    pub integral_from_deg: Option<f64>,
}

impl KirchhoffMethods {
    /// In words: which method, where.
    pub fn describe(&self) -> String {
        let s = &self.split;
        let head = format!(
            "{:.0} nm (rms height of the spot {:.0} nm)",
            s.wavelength * 1e9,
            s.rms_height * 1e9
        );
        let g = format!(
            "g = (2π σ (cos θi + cos θo)/λ)² > {}, i.e. cos θi + cos θo > {:.3}",
            s.geometric_above,
            s.cos_sum()
        );
        match self.integral_from_deg {
            _ if self.geometric_share <= 0.0 => {
                format!(
                    "{head}: the full Kirchhoff integral everywhere (g ≤ {})",
                    s.geometric_above
                )
            }
            None => format!("{head}: the stationary-phase (geometric) limit everywhere ({g})"),
            Some(from) => format!(
                "{head}: the stationary-phase (geometric) limit where {g}, {:.0}% of the table's \
                 directions; the full integral elsewhere (incidences from {from:.0}°, outgoing \
                 toward grazing)",
                100.0 * self.geometric_share
            ),
        }
    }

    /// As recorded in a table's provenance.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "wavelength_nm": self.split.wavelength * 1e9,
            "rms_height_nm": self.split.rms_height * 1e9,
            "geometric_above_g": if self.split.geometric_above.is_finite() {
                serde_json::json!(self.split.geometric_above)
            } else {
                serde_json::Value::Null
            },
            "geometric_where_cos_sum_above": if self.split.cos_sum().is_finite() {
                serde_json::json!(self.split.cos_sum())
            } else {
                serde_json::Value::Null
            },
            "geometric_share": self.geometric_share,
            "integral_from_incidence_deg": self.integral_from_deg,
            "description": self.describe(),
        })
    }
}

/// Where the Kirchhoff table of `engine` at these wavelengths (nm) with these options uses the
/// integral and where its stationary-phase limit, one entry per wavelength.
pub fn kirchhoff_methods(
    engine: &Kirchhoff,
    wavelengths_nm: &[f64],
    options: &TableOptions,
) -> Result<Vec<KirchhoffMethods>> {
    let incidences = options.incidences();
    wavelengths_nm
        .iter()
        .map(|&nm| {
            let split = engine.method_split(nm * 1e-9);
            if !(nm > 0.0 && nm.is_finite()) {
                return Err(ScatterError::Invalid(format!(
                    "wavelength {nm} nm must be positive and finite"
                )));
            }
            let shares: Vec<f64> = incidences
                .iter()
                .map(|&wi| split.geometric_share(wi))
                .collect();
            Ok(KirchhoffMethods {
                split,
                geometric_share: shares.iter().sum::<f64>() / shares.len().max(1) as f64,
                integral_from_deg: incidences
                    .iter()
                    .zip(&shares)
                    .find(|(_, s)| **s < 1.0)
                    .map(|(wi, _)| theta_of(*wi).to_degrees()),
            })
        })
        .collect()
}

/// The cells of a hemisphere map deposited on the slice's nodes as rays: [`KIRCHHOFF_SPLIT`]²
/// per cell that holds light, at the centres of its sub-cells (equal steps in theta and phi),
/// sharing its reflectance by the sub-cells' projected solid angles. The map is that of the
/// source `wi` turned by `turn`; its directions are turned back into the frame of `wi`. Each row
/// of cells is one parallel work item with its own partial deposit; the partials come back in
/// row order.
fn hemisphere_deposits(
    grid: &SliceGrid,
    wi: DVec3,
    turn: f64,
    map: &HemisphereTable,
) -> Vec<Vec<f64>> {
    let g = map.grid;
    let s = KIRCHHOFF_SPLIT;
    let (dt, dp) = (FRAC_PI_2 / g.n_theta as f64, TAU / g.n_phi as f64);
    // Sub-cell azimuths (j + (b + 1/2)/s) dp - turn, for cell j and sub-column b, as (sin, cos).
    let azimuths: Vec<(f64, f64)> = (0..g.n_phi * s)
        .map(|q| ((q as f64 + 0.5) / s as f64 * dp - turn).sin_cos())
        .collect();
    map.reflectance
        .par_chunks(g.n_phi)
        .enumerate()
        .map(|(i, row)| {
            let mut part = vec![0.0; grid.len()];
            let t0 = i as f64 * dt;
            // Projected solid angle of sub-ring a ∝ sin²(t_(a+1)) - sin²(t_a).
            let edge = |a: usize| (t0 + a as f64 * dt / s as f64).sin().powi(2);
            let whole = edge(s) - edge(0);
            let rings: Vec<(f64, f64, f64)> = (0..s)
                .map(|a| {
                    let (st, ct) = (t0 + (a as f64 + 0.5) * dt / s as f64).sin_cos();
                    (st, ct, (edge(a + 1) - edge(a)) / whole / s as f64)
                })
                .collect();
            let azimuths = &azimuths;
            let rays = row
                .iter()
                .enumerate()
                .filter(|&(_, &r)| r != 0.0)
                .flat_map(|(j, &r)| {
                    rings.iter().flat_map(move |&(st, ct, share)| {
                        azimuths[j * s..(j + 1) * s]
                            .iter()
                            .map(move |&(sp, cp)| (DVec3::new(st * cp, st * sp, ct), r * share))
                    })
                });
            grid.deposit(&mut part, rays.map(|(wo, w)| (grid.coords(wi + wo), w)));
            part
        })
        .collect()
}

/// Fill every cell of the table from the slices of the incidences around its own.
fn fill(
    options: &TableOptions,
    grid: &SliceGrid,
    slices: &[Slice],
    channels: Channels,
    provenance: Provenance,
) -> Result<BrdfTable> {
    let invalid = |e: gonio_brdf::BrdfError| ScatterError::Invalid(e.to_string());
    let isotropic = options.resolution.is_isotropic();
    let mut builder = TableBuilder::new(options.resolution, channels)
        .map_err(invalid)?
        .with_provenance(provenance);
    builder.fill(|cell, out| {
        let wi = cell.wi;
        let phi_i = wi.y.atan2(wi.x);
        let u = (cell.angles.theta_h / FRAC_PI_2).sqrt();
        // Isotropic slices have their source at azimuth 0: turn the cell so that its source is.
        let phi_h = cell.angles.phi_h - if isotropic { phi_i } else { 0.0 };
        let mut used = 0.0;
        for (incidence, w) in options.incidence_weights(theta_of(wi), phi_i) {
            if w > 0.0 {
                used += grid.accumulate(&slices[incidence], u, phi_h, w, out);
            }
        }
        if used > 0.0 {
            out.iter_mut().for_each(|o| *o /= used);
        } else {
            out.fill(f64::NAN);
        }
    });
    builder.build().map_err(invalid)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::RayOptions;
    use gonio_surface::synth::GaussianSurface;

    /// Binning each facet's precomputed normal gives the deposits of binning each ray's half
    /// vector `wi + wo`, to rounding, at normal, oblique and grazing incidence.
    #[test]
    fn facet_normals_are_the_half_vectors() {
        let map = GaussianSurface::square(0.3e-6, 6e-6, 96, 0.5e-6, 5)
            .generate()
            .unwrap();
        let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
        assert!(engine.half_vectors_are_normals());
        let grid = TableOptions::isotropic().slice_grid();
        let normals: Vec<(f64, f64)> = (0..engine.facet_count())
            .map(|i| grid.coords(engine.facet_normal(i)))
            .collect();
        for ti in [0.0f64, 35.0, 80.0] {
            let wi = dir(ti.to_radians(), 0.0);
            let add = |parts: Vec<Vec<f64>>| {
                parts.iter().fold(vec![0.0; grid.len()], |mut a, p| {
                    a.iter_mut().zip(p).for_each(|(a, p)| *a += p);
                    a
                })
            };
            let cached = add(ray_deposits(&engine, &grid, wi, 0.0, Some(&normals)).unwrap());
            let direct = add(ray_deposits(&engine, &grid, wi, 0.0, None).unwrap());
            let total: f64 = direct.iter().sum();
            assert!(total > 0.0);
            for (a, b) in cached.iter().zip(&direct) {
                assert!((a - b).abs() <= 1e-12 * total, "{ti}°: {a} vs {b}");
            }
        }
    }
}
