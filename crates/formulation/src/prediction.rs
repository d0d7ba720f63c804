//! A formulation against a measurement, including what a match did not see
//! (`gonio coating predict`): CIEDE2000 at every geometry of a standard (the target read as the
//! match reads it, [`crate::target::read_target`]), grouped by the illumination angle so that
//! a match fitted at 45° is judged at 15°; and, for a measured BRDF in Cornell's ASTM text,
//! every measured sample ([`crate::measured_samples`]). The text and the JSON are composed here,
//! for every front end alike.

use crate::error::{FormulationError, Result};
use crate::measured_samples::{self, PEAK_DEG, SampleComparison, Summary};
use crate::target::read_target;
use gonio_brdf::formats::astm;
use gonio_coating::system::{Coating, default_bands};
use gonio_instrument::coating_study::multiangle_reading;
use gonio_instrument::multiangle::{Geometry, MultiangleReading};
use gonio_instrument::multiangle_target::Target;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// What a formulation predicts of a measurement.
#[derive(Clone, Debug)]
pub struct Prediction {
    pub target: Target,
    /// The formulation's multi-angle reading at the target's geometries (seed 0).
    pub reading: MultiangleReading,
    /// ΔE00 at each of the target's geometries, in its order.
    pub de00: Vec<f64>,
    /// Every measured sample, when the target is a measured BRDF (.astm).
    pub samples: Option<SampleComparison>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// Read `coating` against the measurement `path` at `geometries` (`walks` walks per geometry
/// and per measured sample), and, for a `.astm` file, at every measured sample.
pub fn predict(
    coating: &Coating,
    path: &Path,
    geometries: &[Geometry],
    walks: usize,
) -> Result<Prediction> {
    let start = Instant::now();
    let wavelengths = default_bands();
    let target = read_target(path, geometries)?;
    coating.check(&wavelengths)?;
    let evaluator = coating.evaluator(&wavelengths)?;
    let reading = multiangle_reading(&evaluator, &wavelengths, &target.geometries(), walks, 0)?;
    let de00 = target.de00(&reading)?;
    let is_astm = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("astm"));
    let samples = if is_astm {
        let file = astm::read(path)
            .map_err(|e| FormulationError::Invalid(format!("{}: {e}", path.display())))?;
        Some(measured_samples::compare(
            coating,
            &file.samples,
            &file.wavelengths_nm,
            walks,
            0,
        )?)
    } else {
        None
    };
    Ok(Prediction {
        target,
        reading,
        de00,
        samples,
        seconds: start.elapsed().as_secs_f64(),
    })
}

impl Prediction {
    /// Mean ΔE00 over the geometries lit at each illumination angle, in the order they first
    /// appear: `(θi, mean, count)`.
    pub fn by_illumination(&self) -> Vec<(f64, f64, usize)> {
        let mut groups: Vec<(f64, f64, usize)> = vec![];
        for ((g, _), d) in self.target.colours.iter().zip(&self.de00) {
            match groups.iter_mut().find(|(t, _, _)| *t == g.illumination_deg) {
                Some(group) => {
                    group.1 += d;
                    group.2 += 1;
                }
                None => groups.push((g.illumination_deg, *d, 1)),
            }
        }
        groups
            .into_iter()
            .map(|(t, sum, n)| (t, sum / n as f64, n))
            .collect()
    }

    /// Mean ΔE00 of the measured samples at each incidence (rounded to the degree), off the
    /// gloss peak: `(θi, mean, count)`, increasing θi.
    pub fn samples_by_incidence(&self) -> Vec<(f64, f64, usize)> {
        let Some(s) = &self.samples else {
            return vec![];
        };
        let mut groups: Vec<(f64, f64, usize)> = vec![];
        for r in s.samples.iter().filter(|r| r.theta_h_deg >= PEAK_DEG) {
            let t = r.theta_i_deg.round();
            match groups.iter_mut().find(|(u, _, _)| *u == t) {
                Some(group) => {
                    group.1 += r.de00;
                    group.2 += 1;
                }
                None => groups.push((t, r.de00, 1)),
            }
        }
        groups.sort_by(|a, b| a.0.total_cmp(&b.0));
        groups
            .into_iter()
            .map(|(t, sum, n)| (t, sum / n as f64, n))
            .collect()
    }

    /// The prediction as JSON: `geometries` [{name, illumination_deg, de00, target {L, a, b},
    /// model {L, a, b}}], `by_illumination` [{illumination_deg, mean_de00, count}], `samples`
    /// (null unless the target is a .astm file) {peak_deg, off_peak, peak, all (each {count,
    /// mean_de00, median_de00, p90_de00, median_abs_log10_y}), by_incidence [{theta_i_deg,
    /// mean_de00, count}]}, `seconds`.
    pub fn to_json(&self) -> serde_json::Value {
        let lab = |l: gonio_color::Lab| serde_json::json!({"L": l.l, "a": l.a, "b": l.b});
        let geometries: Vec<_> = self
            .target
            .colours
            .iter()
            .zip(&self.de00)
            .map(|((g, target), d)| {
                serde_json::json!({
                    "name": g.to_string(), "illumination_deg": g.illumination_deg, "de00": d,
                    "target": lab(*target), "model": self.reading.at(*g).map(|r| lab(r.lab)),
                })
            })
            .collect();
        let summary = |s: &Summary| {
            serde_json::json!({
                "count": s.count, "mean_de00": s.mean_de00, "median_de00": s.median_de00,
                "p90_de00": s.p90_de00, "median_abs_log10_y": s.median_abs_log10_y,
            })
        };
        let groups = |g: Vec<(f64, f64, usize)>, key: &str| -> Vec<serde_json::Value> {
            g.into_iter()
                .map(|(t, m, n)| serde_json::json!({key: t, "mean_de00": m, "count": n}))
                .collect()
        };
        serde_json::json!({
            "target": self.target.source,
            "geometries": geometries,
            "by_illumination": groups(self.by_illumination(), "illumination_deg"),
            "samples": self.samples.as_ref().map(|s| serde_json::json!({
                "peak_deg": PEAK_DEG,
                "off_peak": summary(&s.off_peak),
                "peak": summary(&s.peak),
                "all": summary(&s.all),
                "by_incidence": groups(self.samples_by_incidence(), "theta_i_deg"),
            })),
            "seconds": self.seconds,
        })
    }

    /// The prediction as text: a table per geometry, the means per illumination, and the
    /// samples' summaries.
    pub fn report(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{:>9} {:>22} {:>22} {:>7}",
            "geometry", "measured L* a* b*", "model L* a* b*", "ΔE00"
        );
        for ((g, t), d) in self.target.colours.iter().zip(&self.de00) {
            let m = self.reading.at(*g).map(|r| r.lab);
            let model = m.map_or("–".into(), |m| {
                format!("{:6.2} {:6.2} {:6.2}", m.l, m.a, m.b)
            });
            let _ = writeln!(
                s,
                "{:>9} {:>8.2} {:6.2} {:6.2} {:>22} {:7.2}",
                g.to_string(),
                t.l,
                t.a,
                t.b,
                model,
                d
            );
        }
        for (t, m, n) in self.by_illumination() {
            let _ = writeln!(s, "lit at {t}°: mean ΔE00 {m:.2} over {n} geometries");
        }
        if let Some(c) = &self.samples {
            let line = |name: &str, x: &Summary| {
                format!(
                    "{name}: {} samples, ΔE00 mean {:.2}, median {:.2}, 90% {:.2}; luminance \
                     within a factor {:.2} (median)",
                    x.count,
                    x.mean_de00,
                    x.median_de00,
                    x.p90_de00,
                    10f64.powf(x.median_abs_log10_y)
                )
            };
            let _ = writeln!(
                s,
                "{}",
                line(
                    &format!("measured BRDF, half vector {PEAK_DEG}° or more from the normal"),
                    &c.off_peak
                )
            );
            let _ = writeln!(
                s,
                "{}",
                line(&format!("the gloss peak (within {PEAK_DEG}°)"), &c.peak)
            );
            let per: Vec<String> = self
                .samples_by_incidence()
                .into_iter()
                .map(|(t, m, _)| format!("{t}° {m:.2}"))
                .collect();
            let _ = writeln!(
                s,
                "off the peak, mean ΔE00 by incidence: {}",
                per.join(", ")
            );
        }
        let _ = writeln!(s, "{:.1} s", self.seconds);
        s
    }
}
