//! Which constituents of a coating drive which appearance reading: the global sensitivity
//! ([`crate::sensitivity`]) of gloss, haze, DOI, multi-angle colour, flop and ΔE00
//! ([`Output`]) to constituents varied over bounds (`instrument::coating_study::Constituent`:
//! top roughness, flake tilt and coverage, TiO2 thickness, a pigment's concentration, the coat's
//! thickness), every sample point read as the formulation study reads a variant
//! ([`coating_study::read_coating`]).
//!
//! Common random numbers. Every point is read with the same seed, so its walks draw the same
//! random numbers as every other point's (each estimate's streams are seeded by its geometry or
//! quadrature point and the seed, never by the point's values, its order or its thread): the
//! difference between two points is what the constituents change, and the noise enters as one
//! fixed, smooth error surface rather than independently at each point. Checked (tests): the
//! same point read twice is the same bit for bit, and the result does not depend on the number
//! of threads; over six seeds, the difference between the silver metallic at 12° and 12.12° of
//! flake tilt read with the same seed has a standard deviation 0.02 (60° gloss) to 0.52 (b* at
//! 45as110) times that of one reading, median 0.20 over 21 outputs, where independent readings
//! would give √2 (`crn_differences_are_smooth`).
//! The noise that remains is measured by reading the base formulation again with
//! [`Settings::noise_repeats`] other seeds ([`Sensitivity::noise`]); the summary says when it
//! is a notable share of an output's spread.

use crate::appearance::Output;
use crate::error::{FormulationError, Result};
use crate::sensitivity::morris::{self, MorrisEffects};
use crate::sensitivity::sobol::{self, SobolIndices};
use crate::sensitivity::{self, Input, Problem};
use crate::watch::{Progress, Watch};
use gonio_coating::system::Coating;
use gonio_instrument::coating_study::{self, Constituent, Reading};
use gonio_instrument::multiangle::{E2194, Geometry};
use ndarray::Array2;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// One varied constituent and its bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct Varied {
    /// The name it was given by (`tilt`, `concentration:red`), the input's name in the results.
    pub name: String,
    pub constituent: Constituent,
    pub lo: f64,
    pub hi: f64,
}

impl Varied {
    /// Read `NAME=LO:HI` (NAME as [`Constituent::parse`] reads it, e.g. `tilt=4:20`).
    pub fn parse(s: &str) -> Result<Self> {
        let invalid = |why: &str| {
            FormulationError::Invalid(format!(
                "'{s}': {why} (write NAME=LO:HI, e.g. tilt=4:20 or roughness=0.01:0.1)"
            ))
        };
        let (name, bounds) = s.split_once('=').ok_or_else(|| invalid("no '='"))?;
        let (lo, hi) = bounds
            .split_once(':')
            .ok_or_else(|| invalid("no ':' between the bounds"))?;
        let number = |v: &str| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| invalid(&format!("'{v}' is not a number")))
        };
        let name = name.trim();
        Ok(Varied {
            name: name.to_string(),
            constituent: Constituent::parse(name)?,
            lo: number(lo)?,
            hi: number(hi)?,
        })
    }

    /// Check that the bounds are finite and increasing and that `base` with the constituent at
    /// either bound is a valid coating at `wavelengths_nm`, so that a bad range fails before any
    /// reading; the error names the range.
    pub fn check(&self, base: &Coating, wavelengths_nm: &[f64]) -> Result<()> {
        let invalid = |why: String| {
            FormulationError::Invalid(format!("{}={}:{}: {why}", self.name, self.lo, self.hi))
        };
        if !(self.lo.is_finite() && self.hi.is_finite() && self.lo < self.hi) {
            return Err(invalid(
                "the lower bound must be below the upper one".into(),
            ));
        }
        for bound in [self.lo, self.hi] {
            self.constituent
                .apply(base, bound)
                .and_then(|c| Ok(c.check(wavelengths_nm)?))
                .map_err(|e| invalid(e.to_string()))?;
        }
        Ok(())
    }

    /// The bounds of `constituent` when none are given (`--vary tilt` without `=LO:HI` nor
    /// `--bounds`): a formulator's working range. The top's α 0.005–0.3 (a high-gloss to a satin
    /// clear coat: 60° gloss from about 90 to under 10 GU), flake tilt 2–40° (aligned to
    /// disordered), coverage 0.05–0.95, TiO2 40–300 nm (interference flakes' first orders
    /// across the visible), coat thickness 5–200 µm, basecoat thickness 5–60 µm (metallic
    /// basecoats are about 12–20 µm dry, solid colours up to about 40), a pigment's concentration from a tenth to
    /// four times its value in `base` (0.001–1 when it is 0).
    pub fn default_bounds(constituent: &Constituent, base: &Coating) -> Result<(f64, f64)> {
        Ok(match constituent {
            Constituent::Roughness => (0.005, 0.3),
            Constituent::FlakeTilt => (2.0, 40.0),
            Constituent::FlakeCoverage => (0.05, 0.95),
            Constituent::Tio2 => (40.0, 300.0),
            Constituent::CoatThickness => (5.0, 200.0),
            Constituent::BaseThickness => (5.0, 60.0),
            Constituent::Concentration(_) => {
                let c = constituent.value(base)?;
                if c > 0.0 {
                    (0.1 * c, 4.0 * c)
                } else {
                    (0.001, 1.0)
                }
            }
        })
    }

    /// Every constituent `base` has, named as [`Constituent::parse`] reads it, with its
    /// [`Varied::default_bounds`]: the top's roughness and the coat's thickness, the flakes'
    /// tilt and coverage (with flakes), the TiO2 thickness (interference flakes) and each
    /// pigment's concentration (a Kubelka-Munk base). What a front end offers to vary.
    pub fn available(base: &Coating) -> Result<Vec<Self>> {
        let mut names: Vec<String> = ["roughness", "tilt", "coverage", "tio2", "thickness"]
            .map(String::from)
            .to_vec();
        if let gonio_coating::clear_coat::Base::KubelkaMunk { pigments, .. } = &base.base {
            names.extend(pigments.iter().map(|p| format!("concentration:{}", p.name)));
        }
        let mut list = Vec::new();
        for name in names {
            let constituent = Constituent::parse(&name)?;
            // A constituent the coating does not have (no flakes, no interference) has no value.
            if constituent.value(base).is_err() {
                continue;
            }
            let (lo, hi) = Varied::default_bounds(&constituent, base)?;
            list.push(Varied {
                name,
                constituent,
                lo,
                hi,
            });
        }
        Ok(list)
    }

    /// The constituents of `vary` (comma-separated `NAME=LO:HI` or `NAME`) with their bounds:
    /// those written after the name, else those of `bounds` (comma-separated `NAME=LO:HI`, the
    /// CLI's `--bounds`), else [`Varied::default_bounds`] for `base`. Each is checked
    /// ([`Varied::check`]) against `base`.
    pub fn resolve_list(
        vary: &str,
        bounds: Option<&str>,
        base: &Coating,
        wavelengths_nm: &[f64],
    ) -> Result<Vec<Self>> {
        let given = bounds
            .map(Varied::parse_list)
            .transpose()?
            .unwrap_or_default();
        if let Some(extra) = given.iter().find(|b| {
            !vary
                .split(',')
                .any(|v| v.split('=').next().map(str::trim) == Some(b.name.as_str()))
        }) {
            return Err(FormulationError::Invalid(format!(
                "--bounds names {}, which is not varied (add it to --vary)",
                extra.name
            )));
        }
        let list = vary
            .split(',')
            .map(str::trim)
            .filter(|p| !p.is_empty())
            .map(|item| {
                if item.contains('=') {
                    return Varied::parse(item);
                }
                let constituent = Constituent::parse(item)?;
                let (lo, hi) = match given.iter().find(|b| b.name == item) {
                    Some(b) => (b.lo, b.hi),
                    None => Varied::default_bounds(&constituent, base)?,
                };
                Ok(Varied {
                    name: item.to_string(),
                    constituent,
                    lo,
                    hi,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        for v in &list {
            v.check(base, wavelengths_nm)?;
        }
        Ok(list)
    }

    /// Read a comma-separated list of `NAME=LO:HI`.
    pub fn parse_list(s: &str) -> Result<Vec<Self>> {
        s.split(',')
            .filter(|p| !p.trim().is_empty())
            .map(Varied::parse)
            .collect()
    }
}

/// The method and its sample size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Sobol indices from `base` points of Saltelli's design: `base (d + 2)` readings.
    Sobol { base: usize },
    /// Morris screening with `trajectories` trajectories on `levels` levels:
    /// `trajectories (d + 1)` readings.
    Morris { trajectories: usize, levels: usize },
}

impl Method {
    /// How many readings the method makes with `inputs` varied constituents.
    pub fn evaluations(&self, inputs: usize) -> usize {
        match *self {
            Method::Sobol { base } => base * (inputs + 2),
            Method::Morris { trajectories, .. } => trajectories * (inputs + 1),
        }
    }
}

impl Method {
    /// `sobol` or `morris` with `samples` base points or trajectories (default
    /// [`Settings::SOBOL_BASE`], [`Settings::MORRIS_TRAJECTORIES`] on [`morris::LEVELS`]).
    pub fn parse(name: &str, samples: Option<usize>) -> Result<Self> {
        match (name.to_ascii_lowercase().as_str(), samples) {
            ("sobol", None) => Ok(Method::default()),
            ("sobol", Some(base)) => Ok(Method::Sobol { base }),
            ("morris", None) => Ok(Method::morris()),
            ("morris", Some(trajectories)) => Ok(Method::Morris {
                trajectories,
                levels: morris::LEVELS,
            }),
            _ => Err(FormulationError::Invalid(format!(
                "method '{name}': sobol (variance-based indices) or morris (screening)"
            ))),
        }
    }

    /// The method's name: `sobol` or `morris`.
    pub fn name(&self) -> &'static str {
        match self {
            Method::Sobol { .. } => "sobol",
            Method::Morris { .. } => "morris",
        }
    }

    /// Morris with [`Settings::MORRIS_TRAJECTORIES`] trajectories on [`morris::LEVELS`] levels.
    pub fn morris() -> Self {
        Method::Morris {
            trajectories: Settings::MORRIS_TRAJECTORIES,
            levels: morris::LEVELS,
        }
    }
}

/// Sobol at [`Settings::SOBOL_BASE`] base points.
impl Default for Method {
    fn default() -> Self {
        Method::Sobol {
            base: Settings::SOBOL_BASE,
        }
    }
}

/// How each point is read.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// The standard's geometries (ΔE00 is the mean over them).
    pub geometries: Vec<Geometry>,
    /// The bands of the multi-angle colour, nm.
    pub wavelengths_nm: Vec<f64>,
    /// Walks per multi-angle geometry.
    pub walks: usize,
    /// Walks per quadrature point of the gloss meter.
    pub gloss_walks: usize,
    /// The seed of the design (the Sobol sequence's scramble takes its low 32 bits) and of the
    /// bootstrap resamples; the readings always use seed 0 (common random numbers).
    pub seed: u64,
    /// Readings of the base formulation with other seeds, whose spread is the noise.
    pub noise_repeats: usize,
}

impl Settings {
    /// Default walks per multi-angle geometry. With [`Settings::GLOSS_WALKS`] a reading of the
    /// silver metallic costs 0.82 s of CPU (134.6 s for the 165 readings of a default Sobol run
    /// of three constituents, 31 bands, E2194: about a minute on two free cores; measured on a
    /// loaded machine), and its noise, one standard deviation over seeds, is 0.03–0.09 in L*,
    /// 0.03 GU at 60°, 0.03 in DOI, 0.014 in flop (`docs/formulation.md`, "Cost and noise").
    pub const WALKS: usize = 1024;
    /// Default walks per quadrature point of the gloss meter (the meter's own quadrature of the
    /// top's lobe, fixed, is about two thirds of a reading's cost).
    pub const GLOSS_WALKS: usize = 8;
    /// Default Sobol base sample: N (d + 2) = 160 readings for three constituents. The
    /// dominant input's ST is then known to about ± 0.3 (95%), a negligible one's to ± 0.01–0.1.
    pub const SOBOL_BASE: usize = 32;
    /// Default Morris trajectories: r (d + 1) = 80 readings for three constituents, half a
    /// Sobol run's.
    pub const MORRIS_TRAJECTORIES: usize = 20;
}

/// E2194's geometries, 400–700 nm every 10 nm, [`Settings::WALKS`] and
/// [`Settings::GLOSS_WALKS`], seed 1, four noise repeats.
impl Default for Settings {
    fn default() -> Self {
        Settings {
            geometries: E2194.to_vec(),
            wavelengths_nm: (0..31).map(|k| 400.0 + 10.0 * k as f64).collect(),
            walks: Settings::WALKS,
            gloss_walks: Settings::GLOSS_WALKS,
            seed: 1,
            noise_repeats: 4,
        }
    }
}

/// The indices of every output, in the order of [`Sensitivity::outputs`].
#[derive(Clone, Debug, PartialEq)]
pub enum Indices {
    Sobol(Vec<SobolIndices>),
    Morris {
        levels: usize,
        effects: Vec<MorrisEffects>,
    },
}

/// A coating's sensitivity: the design, the readings and the indices.
#[derive(Clone, Debug)]
pub struct Sensitivity {
    pub problem: Problem,
    pub outputs: Vec<Output>,
    /// The design: one row per reading, one column per varied constituent.
    pub points: Array2<f64>,
    /// The readings: one row per point, one column per output.
    pub values: Array2<f64>,
    pub indices: Indices,
    /// Each output's value on the base formulation.
    pub base: Vec<f64>,
    /// Each output's noise: the standard deviation (n − 1) of the base formulation's readings
    /// with seed 0 and `noise_repeats` other seeds; 0 without repeats.
    pub noise: Vec<f64>,
}

/// A sensitivity run taken apart, so that its readings can be spread over many machines (the
/// Python package's Dask client): the checks and the base formulation's reading
/// ([`Plan::new`]), the design ([`Plan::design`]), the reading of any rows of it
/// ([`Plan::read_point`], each row the same whatever reads it and wherever), the noise
/// ([`Plan::noise`]) and the indices ([`Plan::analyze`]). [`run`] does the four in a row.
pub struct Plan {
    base: Coating,
    varied: Vec<Varied>,
    outputs: Vec<Output>,
    method: Method,
    settings: Settings,
    problem: Problem,
    /// The standard's geometries and those the outputs name.
    geometries: Vec<Geometry>,
    reference: Reading,
    base_values: Vec<f64>,
}

impl Plan {
    /// Check the run ([`check`]) and read the base formulation.
    pub fn new(
        base: &Coating,
        varied: &[Varied],
        outputs: &[Output],
        method: Method,
        settings: &Settings,
    ) -> Result<Plan> {
        let problem = check(base, varied, outputs, method, settings)?;
        let mut geometries = settings.geometries.clone();
        for g in outputs.iter().flat_map(Output::geometries) {
            if !geometries.contains(&g) {
                geometries.push(g);
            }
        }
        let reference = read(base, &geometries, settings, 0)?;
        let mut plan = Plan {
            base: base.clone(),
            varied: varied.to_vec(),
            outputs: outputs.to_vec(),
            method,
            settings: settings.clone(),
            problem,
            geometries,
            reference,
            base_values: Vec::new(),
        };
        plan.base_values = plan.values_of(&plan.reference)?;
        Ok(plan)
    }

    /// The outputs' names, in order.
    pub fn outputs(&self) -> &[Output] {
        &self.outputs
    }

    fn read(&self, coating: &Coating, seed: u64) -> Result<Reading> {
        read(coating, &self.geometries, &self.settings, seed)
    }

    fn values_of(&self, reading: &Reading) -> Result<Vec<f64>> {
        self.outputs
            .iter()
            .map(|o| {
                o.value(
                    reading,
                    &self.reference.multiangle,
                    &self.settings.geometries,
                )
            })
            .collect()
    }

    /// The design: one row per reading, one column per varied constituent (physical units).
    pub fn design(&self) -> Result<Array2<f64>> {
        match self.method {
            Method::Sobol { base } => sobol::sample(&self.problem, base, self.settings.seed as u32),
            Method::Morris {
                trajectories,
                levels,
            } => morris::sample(&self.problem, trajectories, levels, self.settings.seed),
        }
    }

    /// The outputs at the point `x` (one value per varied constituent), read with seed 0.
    pub fn read_point(&self, x: &[f64]) -> Result<Vec<f64>> {
        let mut coating = self.base.clone();
        for (v, &value) in self.varied.iter().zip(x) {
            coating = v.constituent.apply(&coating, value)?;
        }
        self.values_of(&self.read(&coating, 0)?)
    }

    /// Each output's noise: the standard deviation of the base formulation's readings with seed
    /// 0 and [`Settings::noise_repeats`] other seeds (0 without repeats).
    pub fn noise(&self) -> Result<Vec<f64>> {
        if self.settings.noise_repeats == 0 {
            return Ok(vec![0.0; self.outputs.len()]);
        }
        let repeats = (1..=self.settings.noise_repeats as u64)
            .into_par_iter()
            .map(|seed| self.values_of(&self.read(&self.base, seed)?))
            .collect::<Result<Vec<_>>>()?;
        Ok((0..self.outputs.len())
            .map(|k| {
                let mut all: Vec<f64> = repeats.iter().map(|r| r[k]).collect();
                all.push(self.base_values[k]);
                sensitivity::sample_std(&all)
            })
            .collect())
    }

    /// The indices of the readings `values` (one row per row of `points`, which must be
    /// [`Plan::design`]'s), with each output's `noise`.
    pub fn analyze(
        &self,
        points: Array2<f64>,
        values: Array2<f64>,
        noise: Vec<f64>,
    ) -> Result<Sensitivity> {
        if points != self.design()? || values.dim() != (points.nrows(), self.outputs.len()) {
            return Err(FormulationError::Invalid(format!(
                "the readings are not those of the plan's design: {} × {} values for {} points \
                 and {} outputs",
                values.nrows(),
                values.ncols(),
                points.nrows(),
                self.outputs.len()
            )));
        }
        if let Some(bad) = values.iter().find(|v| !v.is_finite()) {
            return Err(FormulationError::Invalid(format!(
                "a reading is not a finite number ({bad})"
            )));
        }
        let indices = match self.method {
            Method::Sobol { .. } => {
                Indices::Sobol(sobol::analyze(&self.problem, &values, self.settings.seed)?)
            }
            Method::Morris { levels, .. } => Indices::Morris {
                levels,
                effects: morris::analyze(
                    &self.problem,
                    &points,
                    &values,
                    levels,
                    self.settings.seed,
                )?,
            },
        };
        Ok(Sensitivity {
            problem: self.problem.clone(),
            outputs: self.outputs.clone(),
            points,
            values,
            indices,
            base: self.base_values.clone(),
            noise,
        })
    }
}

/// Check a sensitivity run before it reads anything: at least one output and the standard's
/// geometries, the inputs' bounds increasing and valid for `base` ([`Varied::check`]), and
/// the method's design possible (e.g. Morris needs two trajectories or more). Returns the
/// problem. [`Plan::new`] makes these checks first; a front end calls this to refuse a bad
/// request at once.
pub fn check(
    base: &Coating,
    varied: &[Varied],
    outputs: &[Output],
    method: Method,
    settings: &Settings,
) -> Result<Problem> {
    if outputs.is_empty() {
        return Err(FormulationError::Invalid(
            "a sensitivity needs at least one output".into(),
        ));
    }
    if settings.geometries.is_empty() {
        return Err(FormulationError::Invalid(
            "a sensitivity needs the standard's geometries".into(),
        ));
    }
    if settings.walks == 0 {
        return Err(FormulationError::Invalid(
            "a sensitivity needs at least one walk per geometry".into(),
        ));
    }
    let problem = Problem::new(
        varied
            .iter()
            .map(|v| Input::new(&v.name, v.lo, v.hi))
            .collect(),
    )?;
    // Every bound must make a valid coating, so that a bad range fails before the readings.
    for v in varied {
        v.check(base, &settings.wavelengths_nm)?;
    }
    // The design is cheap (no reading): drawing it checks the method's sample size.
    match method {
        Method::Sobol { base } => sobol::sample(&problem, base, settings.seed as u32)?,
        Method::Morris {
            trajectories,
            levels,
        } => morris::sample(&problem, trajectories, levels, settings.seed)?,
    };
    Ok(problem)
}

/// `coating` read at `geometries` as `settings` say, from the streams of `seed`.
fn read(
    coating: &Coating,
    geometries: &[Geometry],
    settings: &Settings,
    seed: u64,
) -> Result<Reading> {
    Ok(coating_study::read_coating(
        coating,
        geometries,
        &settings.wavelengths_nm,
        settings.walks,
        settings.gloss_walks,
        seed,
    )?)
}

/// The sensitivity of `outputs` of `base` to the `varied` constituents by `method`, each point
/// read with `settings` (in parallel; the same result on any number of threads).
pub fn run(
    base: &Coating,
    varied: &[Varied],
    outputs: &[Output],
    method: Method,
    settings: &Settings,
) -> Result<Sensitivity> {
    run_watched(base, varied, outputs, method, settings, Watch::default())
}

/// [`run`] under `watch`: told the readings made of the run's total (the base formulation, the
/// design's points, the noise repeats) after every reading, and stopped
/// (`InstrumentError::Cancelled`) before the next reading once its flag is raised.
pub fn run_watched(
    base: &Coating,
    varied: &[Varied],
    outputs: &[Output],
    method: Method,
    settings: &Settings,
    watch: Watch,
) -> Result<Sensitivity> {
    let total = method.evaluations(varied.len()) + 1 + settings.noise_repeats;
    let done = AtomicUsize::new(0);
    let tick = || {
        watch.report(Progress {
            readings: done.fetch_add(1, Ordering::Relaxed) + 1,
            total: Some(total),
            best: None,
        })
    };
    watch.check()?;
    let plan = Plan::new(base, varied, outputs, method, settings)?;
    tick();
    let points = plan.design()?;
    let values = sensitivity::evaluate(&points, outputs.len(), |x| {
        watch.check()?;
        let y = plan.read_point(x)?;
        tick();
        Ok(y)
    });
    // A cancelled point is reported as the point's error: say it was cancelled.
    watch.check()?;
    let values = values?;
    let noise = plan.noise()?;
    watch.check()?;
    for _ in 0..settings.noise_repeats {
        tick();
    }
    plan.analyze(points, values, noise)
}
