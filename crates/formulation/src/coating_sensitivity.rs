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
use gonio_coating::system::Coating;
use gonio_instrument::coating_study::{self, Constituent, Reading};
use gonio_instrument::multiangle::{E2194, Geometry};
use ndarray::Array2;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

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

/// The sensitivity of `outputs` of `base` to the `varied` constituents by `method`, each point
/// read with `settings` (in parallel; the same result on any number of threads).
pub fn run(
    base: &Coating,
    varied: &[Varied],
    outputs: &[Output],
    method: Method,
    settings: &Settings,
) -> Result<Sensitivity> {
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
    let mut geometries = settings.geometries.clone();
    for g in outputs.iter().flat_map(Output::geometries) {
        if !geometries.contains(&g) {
            geometries.push(g);
        }
    }
    let read = |coating: &Coating, seed: u64| -> Result<Reading> {
        Ok(coating_study::read_coating(
            coating,
            &geometries,
            &settings.wavelengths_nm,
            settings.walks,
            settings.gloss_walks,
            seed,
        )?)
    };
    let reference = read(base, 0)?;
    let values_of = |reading: &Reading| -> Result<Vec<f64>> {
        outputs
            .iter()
            .map(|o| o.value(reading, &reference.multiangle, &settings.geometries))
            .collect()
    };
    let base_values = values_of(&reference)?;
    let model = |x: &[f64]| -> Result<Vec<f64>> {
        let mut coating = base.clone();
        for (v, &value) in varied.iter().zip(x) {
            coating = v.constituent.apply(&coating, value)?;
        }
        values_of(&read(&coating, 0)?)
    };
    let (points, indices, values) = match method {
        Method::Sobol { base } => {
            let points = sobol::sample(&problem, base, settings.seed as u32)?;
            let values = sensitivity::evaluate(&points, outputs.len(), model)?;
            let indices = Indices::Sobol(sobol::analyze(&problem, &values, settings.seed)?);
            (points, indices, values)
        }
        Method::Morris {
            trajectories,
            levels,
        } => {
            let points = morris::sample(&problem, trajectories, levels, settings.seed)?;
            let values = sensitivity::evaluate(&points, outputs.len(), model)?;
            let effects = morris::analyze(&problem, &points, &values, levels, settings.seed)?;
            (points, Indices::Morris { levels, effects }, values)
        }
    };
    let noise = if settings.noise_repeats == 0 {
        vec![0.0; outputs.len()]
    } else {
        let repeats = (1..=settings.noise_repeats as u64)
            .into_par_iter()
            .map(|seed| values_of(&read(base, seed)?))
            .collect::<Result<Vec<_>>>()?;
        (0..outputs.len())
            .map(|k| {
                let mut all: Vec<f64> = repeats.iter().map(|r| r[k]).collect();
                all.push(base_values[k]);
                sensitivity::sample_std(&all)
            })
            .collect()
    };
    Ok(Sensitivity {
        problem,
        outputs: outputs.to_vec(),
        points,
        values,
        indices,
        base: base_values,
        noise,
    })
}

impl Sensitivity {
    /// The variance of output `k` over the design (its units squared, n in the denominator).
    pub fn variance(&self, k: usize) -> f64 {
        let column = self.values.column(k);
        let mean = column.mean().unwrap_or(0.0);
        column.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / column.len() as f64
    }

    /// Which inputs drive each output, in words, one line per output: the inputs whose total
    /// index (Sobol) is at least `threshold`, or whose μ* is at least `threshold` times the
    /// largest (Morris), strongest first, then those that do not matter. An output that does
    /// not vary says so, and an output whose noise variance is above a tenth of its variance
    /// says how much of it is noise. E.g. "60° gloss is driven by roughness (ST 0.93 ± 0.05);
    /// tilt and coverage do not matter (ST < 0.02)."
    pub fn summary(&self, threshold: f64) -> String {
        let names: Vec<&str> = self
            .problem
            .inputs()
            .iter()
            .map(|i| i.name.as_str())
            .collect();
        let mut text = String::new();
        for (k, output) in self.outputs.iter().enumerate() {
            let what = capitalise(&output.words());
            let variance = self.variance(k);
            if variance == 0.0 {
                let _ = writeln!(text, "{what} does not vary over these ranges.");
                continue;
            }
            // (input, measure, its half-width) for each input, and how the measure is named.
            let (label, measure): (&str, Vec<(usize, f64, f64)>) = match &self.indices {
                Indices::Sobol(s) => (
                    "ST",
                    (0..names.len())
                        .map(|i| (i, s[k].st[i], s[k].st_conf[i]))
                        .collect(),
                ),
                Indices::Morris { effects, .. } => (
                    "μ*",
                    (0..names.len())
                        .map(|i| (i, effects[k].mu_star[i], effects[k].mu_star_conf[i]))
                        .collect(),
                ),
            };
            let cut = match self.indices {
                Indices::Sobol(_) => threshold,
                Indices::Morris { .. } => {
                    threshold * measure.iter().map(|m| m.1).fold(0.0, f64::max)
                }
            };
            let mut strong: Vec<_> = measure.iter().filter(|m| m.1 >= cut).copied().collect();
            strong.sort_by(|a, b| b.1.total_cmp(&a.1));
            let weak: Vec<_> = measure.iter().filter(|m| m.1 < cut).copied().collect();
            let list = |items: &[(usize, f64, f64)]| {
                join(
                    &items
                        .iter()
                        .map(|m| names[m.0].to_string())
                        .collect::<Vec<_>>(),
                )
            };
            let mut sentence = if strong.is_empty() {
                let top = measure.iter().max_by(|a, b| a.1.total_cmp(&b.1)).copied();
                let (i, v, _) = top.expect("at least one input");
                format!(
                    "{what}: no input reaches {label} {} (the largest, {}, has {label} {})",
                    figure(cut),
                    names[i],
                    figure(v)
                )
            } else {
                format!(
                    "{what} is driven by {}",
                    join(
                        &strong
                            .iter()
                            .map(|m| format!(
                                "{} ({label} {} ± {})",
                                names[m.0],
                                figure(m.1),
                                figure(m.2)
                            ))
                            .collect::<Vec<_>>()
                    )
                )
            };
            if !weak.is_empty() && !strong.is_empty() {
                let largest = weak.iter().map(|m| m.1).fold(f64::NEG_INFINITY, f64::max);
                let verb = if weak.len() == 1 { "does" } else { "do" };
                let _ = write!(
                    sentence,
                    "; {} {verb} not matter ({label} ≤ {})",
                    list(&weak),
                    figure(largest.max(0.0))
                );
            }
            let noise_share = self.noise[k] * self.noise[k] / variance;
            if noise_share > 0.1 {
                let _ = write!(
                    sentence,
                    " (its noise, sd {}, is {:.0}% of its variance over the design: read with \
                     more walks)",
                    figure(self.noise[k]),
                    100.0 * noise_share
                );
            }
            let _ = writeln!(text, "{sentence}.");
        }
        text
    }

    /// Write the index table as CSV: one row per output and input, with the output's variance
    /// over the design, its value on the base formulation and its noise; the Sobol columns
    /// `s1, s1_conf, st, st_conf` or the Morris ones `mu, mu_star, sigma, mu_star_conf`
    /// (confidences are 95% half-widths).
    pub fn write_csv_to<W: std::io::Write>(&self, writer: W) -> csv::Result<()> {
        let mut w = csv::Writer::from_writer(writer);
        let method: [&str; 4] = match self.indices {
            Indices::Sobol(_) => ["s1", "s1_conf", "st", "st_conf"],
            Indices::Morris { .. } => ["mu", "mu_star", "sigma", "mu_star_conf"],
        };
        let mut header = vec!["output", "input", "variance", "base", "noise"];
        header.extend(method);
        w.write_record(&header)?;
        for (k, output) in self.outputs.iter().enumerate() {
            for (i, input) in self.problem.inputs().iter().enumerate() {
                let figures = match &self.indices {
                    Indices::Sobol(s) => {
                        let s = &s[k];
                        [s.s1[i], s.s1_conf[i], s.st[i], s.st_conf[i]]
                    }
                    Indices::Morris { effects, .. } => {
                        let e = &effects[k];
                        [e.mu[i], e.mu_star[i], e.sigma[i], e.mu_star_conf[i]]
                    }
                };
                let mut record = vec![
                    output.name(),
                    input.name.clone(),
                    self.variance(k).to_string(),
                    self.base[k].to_string(),
                    self.noise[k].to_string(),
                ];
                record.extend(figures.iter().map(f64::to_string));
                w.write_record(&record)?;
            }
        }
        w.flush()?;
        Ok(())
    }

    /// [`Sensitivity::write_csv_to`] into the file `path`, atomically ([`gonio_io::write_atomic`]:
    /// the old file or the whole new one, never half a file).
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        gonio_io::write_atomic(
            path,
            |w| self.write_csv_to(w).map_err(std::io::Error::other),
            std::convert::identity,
        )
        .map_err(|error| FormulationError::Io {
            path: path.display().to_string(),
            error,
        })
    }

    /// The bars of output `k`: each input's total index ST with its 95% interval (Sobol), or its
    /// μ* with its interval (Morris), largest first; and what the bars measure.
    pub fn bars(&self, k: usize) -> (Vec<(String, f64, f64)>, &'static str) {
        let names = self.problem.inputs().iter().map(|i| i.name.clone());
        let (mut bars, what): (Vec<(String, f64, f64)>, _) = match &self.indices {
            Indices::Sobol(s) => (
                names
                    .zip(s[k].st.iter().zip(&s[k].st_conf))
                    .map(|(n, (v, c))| (n, *v, *c))
                    .collect(),
                "total Sobol index ST (95% bootstrap interval)",
            ),
            Indices::Morris { effects, .. } => (
                names
                    .zip(effects[k].mu_star.iter().zip(&effects[k].mu_star_conf))
                    .map(|(n, (v, c))| (n, *v, *c))
                    .collect(),
                "Morris mu* (output units; 95% bootstrap interval)",
            ),
        };
        bars.sort_by(|a, b| b.1.total_cmp(&a.1));
        (bars, what)
    }

    /// Write `sensitivity.csv` ([`Sensitivity::write_csv`]), `summary.txt` (the summary in
    /// words at `threshold`) and one bar chart per output, `sensitivity-NAME.png`, into `dir`
    /// (created if missing). Returns the files written.
    pub fn write(&self, dir: &Path, threshold: f64) -> Result<Vec<std::path::PathBuf>> {
        let io = |path: &Path| {
            let path = path.display().to_string();
            move |error| FormulationError::Io { path, error }
        };
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let csv = dir.join("sensitivity.csv");
        self.write_csv(&csv)?;
        let summary = dir.join("summary.txt");
        let text = self.summary(threshold);
        gonio_io::write_atomic(
            &summary,
            |w| std::io::Write::write_all(w, text.as_bytes()),
            std::convert::identity,
        )
        .map_err(io(&summary))?;
        let mut written = vec![csv, summary];
        for (k, output) in self.outputs.iter().enumerate() {
            let (bars, what) = self.bars(k);
            let bars: Vec<gonio_plot::Bar> = bars
                .into_iter()
                .map(|(label, value, error)| gonio_plot::Bar {
                    label,
                    value,
                    error,
                })
                .collect();
            let name = output.name().replace(['@', '/'], "_");
            let png = dir.join(format!("sensitivity-{name}.png"));
            let title = format!("What drives {}", output.words());
            if let Err(e) = gonio_plot::bar_chart_png(
                &png,
                (700, 120 + 50 * bars.len() as u32),
                &title,
                what,
                &bars,
            ) {
                match e {
                    // An output that does not vary over the design has no bars to draw; the
                    // summary says so.
                    gonio_plot::PlotError::Data(_) => continue,
                    other => {
                        return Err(FormulationError::Invalid(format!(
                            "{}: {other}",
                            png.display()
                        )));
                    }
                }
            }
            written.push(png);
        }
        Ok(written)
    }
}

/// Two significant figures, with an exponent below 0.001 (one figure: "1e-6").
fn figure(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if v.abs() < 1e-3 {
        return format!("{v:.0e}");
    }
    let digits = (1 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

/// "a", "a and b", "a, b and c".
fn join(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// The sentence's first letter in upper case.
fn capitalise(s: &str) -> String {
    let mut chars = s.chars();
    chars
        .next()
        .map(|c| c.to_uppercase().chain(chars).collect())
        .unwrap_or_default()
}
