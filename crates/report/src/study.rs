//! The roughness study's files: for a series of surfaces (the synthetic epoxy series or
//! files), the study of [`gonio_instrument::study`] run and written to a folder as CSV (curves,
//! peaks, gloss), JSON (the summary) and PNG (each sample's curves; gloss, peak and width
//! against roughness). `gonio study` and the demo's study section write the same files.

use crate::error::Context;
use crate::output::{create_dir, write_atomic};
use crate::{ReportError, Result};
use gonio_instrument::GlossReport;
use gonio_instrument::curves::write_csv;
use gonio_instrument::study::{self, PeakRow, Sample, SampleResult, StudyConfig};
use gonio_io::Progress;
use gonio_plot::{self as plot, LinePlot, Series};
use gonio_scatter::InplaneCurve;
use gonio_surface::synth::GaussianSurface;
use std::io::Write;
use std::path::{Path, PathBuf};

/// What a study wrote: the results and the files, with captions for a report.
pub struct StudyOutputs {
    pub results: Vec<SampleResult>,
    pub peaks: Vec<PeakRow>,
    /// (PNG path, caption)
    pub plots: Vec<(PathBuf, String)>,
    pub files: Vec<PathBuf>,
}

/// The synthetic series: one Gaussian surface per Sq (nm), all from the same seed.
pub fn synthetic_samples(
    sq_nm: &[f64],
    corr_length: f64,
    size: usize,
    dx: f64,
    seed: u64,
) -> Result<Vec<Sample>> {
    if sq_nm.is_empty() {
        return Err(ReportError::Invalid(
            "--sq-nm needs at least one value".into(),
        ));
    }
    sq_nm
        .iter()
        .map(|&sq| {
            let map = GaussianSurface::square(sq * 1e-9, corr_length, size, dx, seed)
                .generate()
                .with_context(|| format!("synthesising the Sq = {sq} nm surface"))?;
            Ok(Sample {
                label: format!("sq{sq}nm"),
                map,
            })
        })
        .collect()
}

/// Run the study and write its CSV, JSON and plots into `dir`; `progress` hears the study's
/// steps.
pub fn execute(
    samples: &[Sample],
    config: &StudyConfig,
    dir: &Path,
    progress: &Progress,
) -> Result<StudyOutputs> {
    create_dir(dir)?;
    let results = study::run(samples, config, progress)?;
    let mut files = Vec::new();
    let mut plots = Vec::new();
    for r in &results {
        let path = dir.join(format!("curves_{}.csv", r.label));
        write_csv(&path, &r.curves)?;
        files.push(path);
        let png = dir.join(format!("curves_{}.png", r.label));
        plot_sample(&png, r, config)?;
        plots.push((
            png,
            format!(
                "{}: in-plane BRDF by the ray method (lines) and Kirchhoff at {} nm (dots), Sq = {:.1} nm",
                r.label,
                kirchhoff_wavelength(config).unwrap_or(f64::NAN),
                r.statistics.sq * 1e9
            ),
        ));
    }
    let peaks: Vec<PeakRow> = results.iter().flat_map(|r| r.peaks()).collect();
    let csv = dir.join("peaks.csv");
    write_peaks_csv(&csv, &peaks)?;
    files.push(csv);
    let gloss_csv = dir.join("gloss.csv");
    write_gloss_csv(&gloss_csv, &results)?;
    files.push(gloss_csv);
    let gloss_png = dir.join("gloss_vs_roughness.png");
    plot_gloss(&gloss_png, &results)?;
    plots.push((
        gloss_png,
        "Gloss (ISO 2813, 20/60/85°) against roughness, by the ray method and the Kirchhoff approximation".to_string(),
    ));
    for (name, caption, value) in [
        (
            "peak_vs_roughness.png",
            "Specular peak reflectance against roughness",
            0usize,
        ),
        (
            "width_vs_roughness.png",
            "Full width at half maximum of the specular peak against roughness",
            1,
        ),
    ] {
        let png = dir.join(name);
        plot_peaks(&png, caption, &peaks, value, config)?;
        plots.push((png, caption.to_string()));
    }
    let outputs = StudyOutputs {
        results,
        peaks,
        plots,
        files,
    };
    let json = dir.join("study.json");
    write_atomic(&json, |w| {
        Ok(serde_json::to_writer_pretty(w, &summary_json(&outputs))?)
    })?;
    let mut outputs = outputs;
    outputs.files.push(json);
    Ok(outputs)
}

/// The wavelength whose Kirchhoff curves the plots show: 550 nm when computed, else the first.
fn kirchhoff_wavelength(config: &StudyConfig) -> Option<f64> {
    if !config.kirchhoff {
        return None;
    }
    config
        .wavelengths_nm
        .iter()
        .copied()
        .find(|&w| (w - 550.0).abs() < 1e-9)
        .or(config.wavelengths_nm.first().copied())
}

/// Whether two wavelengths (nm) are the same, allowing for the rounding of a nm → m → nm trip.
pub fn same_wavelength(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() < 1e-6,
        _ => false,
    }
}

fn shown(c: &InplaneCurve, config: &StudyConfig) -> bool {
    c.method == "ray" || same_wavelength(c.wavelength_nm, kirchhoff_wavelength(config))
}

fn plot_sample(path: &Path, r: &SampleResult, config: &StudyConfig) -> Result<()> {
    let incidences = &config.goniometer.incidences_deg();
    let series: Vec<Series> = r
        .curves
        .iter()
        .filter(|c| shown(c, config))
        .map(|c| {
            let i = incidences
                .iter()
                .position(|&t| t == c.incidence_deg)
                .unwrap_or(0);
            Series {
                label: if c.method == "ray" {
                    format!("{}°", c.incidence_deg)
                } else {
                    String::new()
                },
                points: c
                    .points
                    .iter()
                    .map(|p| (p.scatter_deg, p.brdf_per_sr))
                    .collect(),
                colour: plot::palette(i),
                markers: c.method != "ray",
            }
        })
        .collect();
    let title = format!("{}: ray (lines) and Kirchhoff (dots)", r.label);
    let spec = LinePlot {
        title: &title,
        x_label: "scattering angle (deg)",
        y_label: "BRDF (1/sr)",
        log_y: true,
    };
    Ok(plot::line_plot_png(path, (900, 600), &spec, &series)?)
}

fn plot_peaks(
    path: &Path,
    title: &str,
    peaks: &[PeakRow],
    value: usize,
    config: &StudyConfig,
) -> Result<()> {
    let mut series = Vec::new();
    for (i, &ti) in config.goniometer.incidences_deg().iter().enumerate() {
        for method in ["ray", "kirchhoff"] {
            let points: Vec<(f64, f64)> = peaks
                .iter()
                .filter(|p| p.method == method && p.incidence_deg == ti)
                .filter(|p| {
                    method == "ray"
                        || same_wavelength(p.wavelength_nm, kirchhoff_wavelength(config))
                })
                .filter_map(|p| {
                    let y = if value == 0 {
                        Some(p.peak.reflectance)
                    } else {
                        p.peak.fwhm_deg
                    };
                    Some((p.sq_m * 1e9, y?))
                })
                .collect();
            let points = by_sq(points);
            if !points.is_empty() {
                series.push(Series {
                    label: format!(
                        "{} {ti}°",
                        if method == "ray" { "ray" } else { "Kirchhoff" }
                    ),
                    points,
                    colour: plot::palette(i),
                    markers: method != "ray",
                });
            }
        }
    }
    let spec = LinePlot {
        title,
        x_label: "Sq (nm)",
        y_label: if value == 0 {
            "peak reflectance per detector"
        } else {
            "FWHM (deg)"
        },
        log_y: true,
    };
    Ok(plot::line_plot_png_x(
        path,
        (900, 600),
        &spec,
        &sample_axis(peaks_marks(peaks)),
        &series,
    )?)
}

/// Points in order of Sq, so that a line joins the samples from smooth to rough whatever the
/// order they were given in.
fn by_sq(mut points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    points
}

/// A logarithmic Sq axis (nm) with each sample's name written at its Sq.
fn sample_axis(marks: Vec<(f64, String)>) -> plot::XAxis {
    plot::XAxis { log: true, marks }
}

fn peaks_marks(peaks: &[PeakRow]) -> Vec<(f64, String)> {
    let mut marks: Vec<(f64, String)> = Vec::new();
    for p in peaks {
        if !marks.iter().any(|(_, l)| *l == p.label) {
            marks.push((p.sq_m * 1e9, p.label.clone()));
        }
    }
    marks
}

fn plot_gloss(path: &Path, results: &[SampleResult]) -> Result<()> {
    let mut series = Vec::new();
    for (i, label) in ["20°", "60°", "85°"].into_iter().enumerate() {
        let pick = |g: &GlossReport| [g.gu20, g.gu60, g.gu85][i];
        let x = |r: &SampleResult| r.statistics.sq * 1e9;
        series.push(Series {
            label: format!("ray {label}"),
            points: by_sq(results.iter().map(|r| (x(r), pick(&r.gloss_ray))).collect()),
            colour: plot::palette(i),
            markers: false,
        });
        let kirchhoff: Vec<(f64, f64)> = results
            .iter()
            .filter_map(|r| Some((x(r), pick(r.gloss_kirchhoff.as_ref()?))))
            .collect();
        if !kirchhoff.is_empty() {
            series.push(Series {
                label: format!("Kirchhoff 550 nm {label}"),
                points: kirchhoff,
                colour: plot::palette(i),
                markers: true,
            });
        }
    }
    let spec = LinePlot {
        title: "Specular gloss against roughness: ray (lines), Kirchhoff (dots)",
        x_label: "Sq (nm)",
        y_label: "gloss units (GU)",
        log_y: false,
    };
    let marks = results
        .iter()
        .map(|r| (r.statistics.sq * 1e9, r.label.clone()))
        .collect();
    Ok(plot::line_plot_png_x(
        path,
        (900, 600),
        &spec,
        &sample_axis(marks),
        &series,
    )?)
}

fn write_gloss_csv(path: &Path, results: &[SampleResult]) -> Result<()> {
    let mut s = String::from(
        "sample,sq_m,sdq,method,gu20,gu60,gu85,haze,haze_wide,haze_20,haze_d4039,doi,\
         haze_20_log,doi_uncertainty\n",
    );
    for r in results {
        let methods = [
            ("ray", Some(&r.gloss_ray)),
            ("kirchhoff_550nm", r.gloss_kirchhoff.as_ref()),
        ];
        for (method, g) in methods {
            let Some(g) = g else { continue };
            s.push_str(&format!(
                "{},{:.6e},{:.6},{method},{:.3},{:.3},{:.3},{:.4},{:.4},{:.4},{:.3},{:.3},{:.1},{:.3}\n",
                r.label,
                r.statistics.sq,
                r.statistics.sdq,
                g.gu20,
                g.gu60,
                g.gu85,
                g.haze,
                g.haze_wide,
                g.haze_20,
                g.haze_d4039,
                g.doi,
                g.haze_20_log,
                g.doi_uncertainty
            ));
        }
    }
    write_atomic(path, |w| w.write_all(s.as_bytes()))
}

fn write_peaks_csv(path: &Path, peaks: &[PeakRow]) -> Result<()> {
    let mut s = String::from(
        "sample,sq_m,method,wavelength_nm,incidence_deg,peak_deg,peak_reflectance,fwhm_deg\n",
    );
    for p in peaks {
        s.push_str(&format!(
            "{},{:.6e},{},{},{},{},{:.6e},{}\n",
            p.label,
            p.sq_m,
            p.method,
            p.wavelength_nm.map_or(String::new(), |w| w.to_string()),
            p.incidence_deg,
            p.peak.position_deg,
            p.peak.reflectance,
            p.peak.fwhm_deg.map_or(String::new(), |w| format!("{w:.4}")),
        ));
    }
    write_atomic(path, |w| w.write_all(s.as_bytes()))
}

/// The study's summary as `study.json` holds it and `gonio study --json` prints it.
pub fn summary_json(out: &StudyOutputs) -> serde_json::Value {
    let samples: Vec<serde_json::Value> = out
        .results
        .iter()
        .map(|r| {
            serde_json::json!({
                "label": r.label,
                "sq_m": r.statistics.sq,
                "sa_m": r.statistics.sa,
                "sdq": r.statistics.sdq,
                "sal_m": r.statistics.sal,
                "gloss_ray": r.gloss_ray,
                "gloss_kirchhoff_550nm": r.gloss_kirchhoff,
                "notes": r.notes,
                "warnings": r.warnings,
            })
        })
        .collect();
    serde_json::json!({ "samples": samples, "peaks": out.peaks })
}
