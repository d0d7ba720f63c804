//! What a coating's sensitivity says, for every front end alike: which constituents drive each
//! reading in words ([`Sensitivity::summary`]), the index table as CSV, and a bar chart per
//! output ([`Sensitivity::write`]).

use crate::coating_sensitivity::{Indices, Sensitivity, Varied};
use crate::error::{FormulationError, Result};
use std::fmt::Write as _;
use std::path::Path;

impl Sensitivity {
    /// The varied constituents' names, in the design's column order.
    pub fn input_names(&self) -> Vec<&str> {
        self.problem
            .inputs()
            .iter()
            .map(|i| i.name.as_str())
            .collect()
    }

    /// The run as JSON, as `gonio coating sensitivity --json` prints it (without the file's
    /// name): `method`, `readings`, `inputs` [{name, lo, hi}] (`varied`, in order), `summary`
    /// (in words at `threshold`), and `outputs` [{output, base, noise, variance, indices}] with
    /// `indices` {s1, s1_conf, st, st_conf} (Sobol) or {mu, mu_star, sigma, mu_star_conf}
    /// (Morris), each a map from input name to value.
    pub fn to_json(&self, varied: &[Varied], threshold: f64) -> serde_json::Value {
        let names = self.input_names();
        let per_input = |v: &[f64]| -> serde_json::Value {
            names
                .iter()
                .zip(v)
                .map(|(n, x)| (n.to_string(), serde_json::json!(x)))
                .collect::<serde_json::Map<_, _>>()
                .into()
        };
        let outputs: Vec<serde_json::Value> = self
            .outputs
            .iter()
            .enumerate()
            .map(|(k, o)| {
                let indices = match &self.indices {
                    Indices::Sobol(i) => serde_json::json!({
                        "s1": per_input(&i[k].s1), "s1_conf": per_input(&i[k].s1_conf),
                        "st": per_input(&i[k].st), "st_conf": per_input(&i[k].st_conf),
                    }),
                    Indices::Morris { effects, .. } => serde_json::json!({
                        "mu": per_input(&effects[k].mu),
                        "mu_star": per_input(&effects[k].mu_star),
                        "sigma": per_input(&effects[k].sigma),
                        "mu_star_conf": per_input(&effects[k].mu_star_conf),
                    }),
                };
                serde_json::json!({
                    "output": o.name(), "base": self.base[k], "noise": self.noise[k],
                    "variance": self.variance(k), "indices": indices,
                })
            })
            .collect();
        serde_json::json!({
            "method": match self.indices {
                Indices::Sobol(_) => "sobol",
                Indices::Morris { .. } => "morris",
            },
            "readings": self.points.nrows(),
            "inputs": varied
                .iter()
                .map(|v| serde_json::json!({"name": v.name, "lo": v.lo, "hi": v.hi}))
                .collect::<Vec<_>>(),
            "summary": self.summary(threshold),
            "outputs": outputs,
        })
    }

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
        let names = self.input_names();
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
pub(crate) fn capitalise(s: &str) -> String {
    let mut chars = s.chars();
    chars
        .next()
        .map(|c| c.to_uppercase().chain(chars).collect())
        .unwrap_or_default()
}
