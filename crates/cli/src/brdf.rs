//! `gonio brdf`: tabulated BRDFs: summary, import, export, plots, tabulating an analytic model and
//! fitting a model to a table. The work is done by the gonio-brdf crate.

use crate::progress::spinner;
use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand, ValueEnum};
use glam::DVec3;
use gonio_brdf::Brdf;
use gonio_brdf::fit::{FitKind, FitOptions, fit};
use gonio_brdf::formats::{astm, csv, merl, mitsuba, pabopto, radiance_xml};
use gonio_brdf::gbrdf;
use gonio_brdf::models::ModelSpec;
use gonio_brdf::table::colour::{self, ColourSpace};
use gonio_brdf::table::coords::turn_about_z;
use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
use gonio_color::{Illuminant, Observer};
use gonio_plot::{self as plot, LinePlot, Series};
use gonio_scatter::geometry::{incidence_direction, inplane_direction};
use std::path::{Path, PathBuf};

/// Subcommands of `gonio brdf`.
#[derive(Subcommand)]
pub enum BrdfCommand {
    /// Summary of a .gbrdf table: resolution, channels, provenance, albedo at 0/30/60/80°,
    /// reciprocity error and peak value (1/sr).
    Info(InfoArgs),
    /// Import a measurement or another format into a .gbrdf table: Cornell ASTM text (.astm),
    /// MERL .binary, or CSV samples (theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,<values per sr>).
    Import(ImportArgs),
    /// Export a .gbrdf table to MERL .binary, the Mitsuba 3 / pbrt-v4 tensor .bsdf, Radiance's
    /// XML BSDF (a tensor tree, for the BSDF material), Radiance PAB-Opto data files (a
    /// directory, one file per incidence) or CSV.
    Export(ExportArgs),
    /// Plot a table: in-plane curves on a log scale and a polar lobe view, as PNG.
    Plot(PlotArgs),
    /// Tabulate an analytic model into a .gbrdf table.
    Tabulate(TabulateArgs),
    /// Fit an analytic model to a table (Levenberg-Marquardt, weighted by cos θo dω).
    Fit(FitArgs),
    /// Compute the table of a height map by the ray method or the Kirchhoff approximation
    /// (docs/brdf-tables.md, "Computing a table from a height map").
    Compute(crate::brdf_compute::ComputeArgs),
}

#[derive(Args)]
pub struct InfoArgs {
    /// The table (.gbrdf).
    table: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Formats `gonio brdf import` reads.
#[derive(Clone, Copy, ValueEnum)]
pub enum ImportFormat {
    /// From the file extension (.astm, .binary, .csv).
    Auto,
    Astm,
    Merl,
    Csv,
}

#[derive(Args)]
pub struct ImportArgs {
    /// The file to import.
    file: PathBuf,
    /// Output table (.gbrdf).
    #[arg(short, long)]
    output: PathBuf,
    /// Input format.
    #[arg(long, value_enum, default_value = "auto")]
    format: ImportFormat,
    /// Nodes of the table built from scattered samples (ASTM, CSV): theta_h,theta_d,phi_d
    /// (the default resolves a high-gloss paint's specular peak; docs/brdf-tables.md).
    #[arg(long, value_delimiter = ',', default_value = crate::list_default(&import_resolution()))]
    resolution: Vec<usize>,
    /// Make the table reciprocal (each pair f(wi, wo), f(wo, wi) replaced by its mean).
    #[arg(long)]
    enforce_reciprocity: bool,
    #[command(flatten)]
    colour: ColourArgs,
    /// Print the import summary as JSON.
    #[arg(long)]
    json: bool,
}

/// Reducing a spectral table to colour as it is written (`brdf import`, `coating compute`).
#[derive(Args)]
pub struct ColourArgs {
    /// Reduce a spectral table to colour: `xyz` (CIE XYZ / 100, each in 1/sr) or `srgb` (linear
    /// sRGB in 1/sr, white-balanced to D65 by Bradford), under --illuminant, seen by
    /// --observer (docs/color.md). Default: keep the spectra.
    #[arg(long, value_name = "SPACE",
          value_parser = |s: &str| s.parse::<ColourSpace>().map_err(|e| e.to_string()))]
    colour: Option<ColourSpace>,
    /// CIE illuminant for --colour: D65 (daylight) or A (tungsten).
    #[arg(long, default_value = "D65", value_parser = crate::color::parse_illuminant)]
    illuminant: Illuminant,
    /// CIE observer for --colour, by field size in degrees: 2 (CIE 1931) or 10 (CIE 1964).
    #[arg(long, value_name = "DEG", default_value = "2",
          value_parser = crate::color::parse_observer)]
    observer: Observer,
}

impl ColourArgs {
    /// Whether a reduction to colour was asked for.
    pub fn reduces(&self) -> bool {
        self.colour.is_some()
    }

    /// `table` reduced to the colour space asked for, or as it is; `file` names the source in
    /// errors.
    pub fn apply(&self, table: BrdfTable, file: &Path) -> Result<BrdfTable> {
        match self.colour {
            Some(space) => colour::reduce(&table, space, self.illuminant, self.observer)
                .with_context(|| format!("{}: --colour", file.display())),
            None => Ok(table),
        }
    }
}

/// Formats `gonio brdf export` writes.
#[derive(Clone, Copy, ValueEnum)]
pub enum ExportFormat {
    Merl,
    Mitsuba,
    /// Radiance's XML BSDF, a tensor tree written from the table (docs/brdf-tables.md).
    RadianceXml,
    /// Radiance PAB-Opto files for pabopto2bsdf (a directory).
    Pabopto,
    Csv,
}

#[derive(Args)]
pub struct ExportArgs {
    /// The table (.gbrdf).
    table: PathBuf,
    /// Output format.
    #[arg(long, value_enum)]
    format: ExportFormat,
    /// Output file (a directory for pabopto).
    #[arg(short, long)]
    output: PathBuf,
    /// CSV: angular step of the grid in degrees.
    #[arg(long, default_value_t = 5.0)]
    step_deg: f64,
    /// pabopto: incidence angles in degrees, one file each.
    #[arg(long, value_delimiter = ',', default_value = crate::list_default(&pabopto::DEFAULT_THETA_I_DEG))]
    incidence_deg: Vec<f64>,
    /// mitsuba: nodes per axis of each incidence's value grid. The default 128 holds a sharply
    /// peaked measured paint's albedo to 3% (64: 7%, a quarter of the file size; enough for
    /// smooth lobes, within about 1%) (docs/brdf-tables.md).
    #[arg(long, default_value_t = 128, value_parser = clap::value_parser!(u16).range(8..=512))]
    value_grid: u16,
    /// radiance-xml: order of the tensor tree, 2^N cells per side (a cell is π/4^N of projected
    /// solid angle of the light's directions: 1.8° across at the pole for N = 6). Default 6 for
    /// a monochrome isotropic table (a TensorTree3, up to 8), 5 otherwise (a TensorTree4, up
    /// to 6; colour tables are TensorTree4 because Radiance drops the colour of a TensorTree3).
    #[arg(long, value_parser = clap::value_parser!(u32).range(2..=8))]
    tree_order: Option<u32>,
}

#[derive(Args)]
pub struct PlotArgs {
    /// The table (.gbrdf).
    table: PathBuf,
    /// Output PNG.
    #[arg(short, long)]
    output: PathBuf,
    /// Incidence angles of the in-plane curves, degrees.
    #[arg(long, value_delimiter = ',', default_value = "20,45,60,75")]
    incidence_deg: Vec<f64>,
    /// The measurement the table was imported from (.astm or .csv, same channels): its
    /// geometries in the plane of incidence at the plotted incidences (within 0.5°) are drawn
    /// as markers beside the curves.
    #[arg(long)]
    measured: Option<PathBuf>,
}

#[derive(Args)]
pub struct TabulateArgs {
    /// The model as JSON, inline or in a file, e.g. '{"model":"ward","specular":0.05,"alpha":0.1,
    /// "diffuse":0.3}' (fields in docs/brdf-models.md).
    #[arg(long)]
    model: String,
    /// Nodes theta_h,theta_d,phi_d (phi_d even).
    #[arg(long, value_delimiter = ',', default_value = "90,90,180")]
    resolution: Vec<usize>,
    /// One channel (the mean of R, G, B) instead of three.
    #[arg(long)]
    mono: bool,
    /// Output table (.gbrdf).
    #[arg(short, long)]
    output: PathBuf,
}

/// Model families `gonio brdf fit` fits.
#[derive(Clone, Copy, ValueEnum)]
pub enum FitModel {
    Ward,
    Beckmann,
    Ggx,
    Phong,
}

#[derive(Args)]
pub struct FitArgs {
    /// The table (.gbrdf).
    table: PathBuf,
    /// Model family.
    #[arg(long, value_enum)]
    model: FitModel,
    /// Add a Lambert term.
    #[arg(long)]
    diffuse: bool,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Also plot table and fit in the plane of incidence (PNG).
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// Run a `gonio brdf` subcommand.
pub fn run(cmd: BrdfCommand) -> Result<()> {
    match cmd {
        BrdfCommand::Info(a) => info(a),
        BrdfCommand::Import(a) => import(a),
        BrdfCommand::Export(a) => export(a),
        BrdfCommand::Plot(a) => plot_table(a),
        BrdfCommand::Tabulate(a) => tabulate(a),
        BrdfCommand::Fit(a) => fit_table(a),
        BrdfCommand::Compute(a) => crate::brdf_compute::run(a),
    }
}

fn load(path: &Path) -> Result<BrdfTable> {
    gbrdf::open_mapped(path)
        .context("cannot read the table (write one with `gonio brdf import` or `tabulate`)")
}

/// The library's resolution of imported tables, as `--resolution` takes it.
pub(crate) fn import_resolution() -> Vec<usize> {
    let r = astm::default_resolution();
    vec![r.theta_h, r.theta_d, r.phi_d]
}

pub(crate) fn resolution(v: &[usize]) -> Result<Resolution> {
    if v.len() != 3 {
        bail!("--resolution takes three node counts theta_h,theta_d,phi_d, e.g. 90,90,180");
    }
    let r = Resolution::isotropic(v[0], v[1], v[2]);
    r.validate()
        .map_err(|e| anyhow::anyhow!("--resolution: {e}"))?;
    Ok(r)
}

/// The in-plane plots' x axis, in words and unit.
const SCATTER_AXIS: &str = "scattering angle θs (degrees from the normal, + on the specular side)";
/// The in-plane plots' y axis, in words and unit.
const BRDF_AXIS: &str = "BRDF f (1/sr), mean of the channels";

fn info(a: InfoArgs) -> Result<()> {
    let t = load(&a.table)?;
    let angles = [0.0, 30.0, 60.0, 80.0];
    let albedo = t.albedo_curve(&angles);
    let reciprocity = t.reciprocity_error();
    let (peak, cell) = t.peak();
    let (wi, wo) = t.resolution().cell_angles(cell).to_dirs();
    let deg = |d: DVec3| {
        (
            d.z.clamp(-1.0, 1.0).acos().to_degrees(),
            d.y.atan2(d.x).to_degrees(),
        )
    };
    if a.json {
        let rows: Vec<_> = albedo
            .theta_i_deg
            .iter()
            .zip(&albedo.albedo)
            .map(|(t, a)| serde_json::json!({"theta_i_deg": t, "albedo": a}))
            .collect();
        let out = serde_json::json!({
            "file": a.table.display().to_string(),
            "resolution": t.resolution(),
            "isotropic": t.resolution().is_isotropic(),
            "channels": t.channels(),
            "provenance": t.provenance(),
            "albedo": rows,
            "reciprocity_error": reciprocity,
            "peak_per_sr": peak,
            "peak_theta_i_deg": deg(wi).0, "peak_phi_i_deg": deg(wi).1,
            "peak_theta_o_deg": deg(wo).0, "peak_phi_o_deg": deg(wo).1,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    println!("table        {}", a.table.display());
    println!(
        "resolution   {} ({})",
        t.resolution().describe(),
        if t.resolution().is_isotropic() {
            "isotropic"
        } else {
            "anisotropic"
        }
    );
    println!("channels     {}", t.channels().describe());
    let p = t.provenance();
    for (k, v) in [
        ("source", &p.source),
        ("method", &p.method),
        ("date", &p.date),
        ("description", &p.description),
    ] {
        if let Some(v) = v {
            println!("{k:<12} {v}");
        }
    }
    for (th, a) in albedo.theta_i_deg.iter().zip(&albedo.albedo) {
        let mean = a.iter().sum::<f64>() / a.len() as f64;
        println!("albedo {th:>3}°  {mean:.4} (mean of channels)");
    }
    println!(
        "reciprocity  {reciprocity:.4}: swapping light and viewer changes the BRDF by {:.1}% of \
         its value, summed over the table (Σ|f(wi,wo) - f(wo,wi)| / Σ(f(wi,wo) + f(wo,wi)));\n\
         {:13}0 for a reciprocal (physical) BRDF, 1 when one of every swapped pair is zero",
        100.0 * reciprocity,
        ""
    );
    let (ti, pi) = deg(wi);
    let (to, po) = deg(wo);
    println!(
        "peak         {peak:.4e} 1/sr at theta_i {ti:.2}°, phi_i {pi:.1}°, theta_o {to:.2}°, phi_o {po:.1}°"
    );
    Ok(())
}

fn import(a: ImportArgs) -> Result<()> {
    let ext = gonio_io::extension(&a.file);
    let format = match (a.format, ext.as_str()) {
        (ImportFormat::Auto, "astm") => ImportFormat::Astm,
        (ImportFormat::Auto, "binary") => ImportFormat::Merl,
        (ImportFormat::Auto, "csv") => ImportFormat::Csv,
        (ImportFormat::Auto, _) => bail!(
            "{}: cannot tell the format from the extension; give --format astm|merl|csv",
            a.file.display()
        ),
        (f, _) => f,
    };
    let res = resolution(&a.resolution)?;
    let pb = spinner("fitting and resampling");
    let (mut table, residual) = match format {
        ImportFormat::Astm => astm::import(&a.file, res).map(|(t, r)| (t, Some(r)))?,
        ImportFormat::Csv => csv::import(&a.file, res).map(|(t, r)| (t, Some(r)))?,
        ImportFormat::Merl => (merl::read(&a.file)?, None),
        ImportFormat::Auto => unreachable!("resolved above"),
    };
    pb.finish_and_clear();
    if a.enforce_reciprocity {
        table.enforce_reciprocity();
    }
    let table = a.colour.apply(table, &a.file)?;
    gbrdf::write(&table, &a.output)?;
    if a.json {
        let out = serde_json::json!({
            "output": a.output.display().to_string(),
            "resolution": table.resolution(),
            "channels": table.channels(),
            "fit_residual": residual,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        println!(
            "wrote {} ({}, {})",
            a.output.display(),
            table.resolution().describe(),
            table.channels().describe()
        );
        if let Some(r) = residual {
            println!(
                "fit residual at the {} measured values above 1e-3 1/sr: median {:.1}%, rms {:.1}%",
                r.count,
                100.0 * r.median_relative,
                100.0 * r.rms_relative
            );
        }
    }
    Ok(())
}

fn export(a: ExportArgs) -> Result<()> {
    let t = load(&a.table)?;
    let pb = spinner("exporting");
    match a.format {
        ExportFormat::Merl => {
            let report = merl::write(&t, &a.output)?;
            if report.out_of_gamut > 0 {
                pb.suspend(|| {
                    eprintln!(
                        "warning: {}: {} of {} cells are outside the sRGB gamut, which MERL files \
                         cannot hold (a negative value means \"not measured\" to their \
                         readers); they were moved toward grey at constant luminance until in \
                         gamut (docs/brdf-tables.md)",
                        a.output.display(),
                        report.out_of_gamut,
                        report.cells
                    )
                });
            }
        }
        ExportFormat::Mitsuba => {
            let opts = mitsuba::MitsubaOptions {
                values: usize::from(a.value_grid),
                ..Default::default()
            };
            mitsuba::write(&t, &a.output, opts)?
        }
        ExportFormat::Csv => csv::write(&t, &a.output, a.step_deg)?,
        ExportFormat::RadianceXml => {
            let name = gonio_brdf::formats::radiance_name(&a.table);
            let tree = radiance_xml::write(&t, &a.output, name, a.tree_order)?;
            pb.finish_and_clear();
            println!(
                "wrote {} (TensorTree{} of order {}{})",
                a.output.display(),
                tree.rank(),
                tree.order(),
                if tree.has_colour() {
                    ", Y and CIE u′ v′"
                } else {
                    ", Y"
                }
            );
            return Ok(());
        }
        ExportFormat::Pabopto => {
            let name = gonio_brdf::formats::radiance_name(&a.table);
            let files = pabopto::write(&t, &a.output, name, &a.incidence_deg)?;
            pb.finish_and_clear();
            println!(
                "wrote {} into {}",
                gonio_report::units::count(files.len(), "file"),
                a.output.display()
            );
            return Ok(());
        }
    }
    pb.finish_and_clear();
    println!("wrote {}", a.output.display());
    Ok(())
}

/// In-plane curves (mean of channels) of any BRDF at the given incidences.
fn in_plane(brdf: &dyn Brdf, incidence_deg: &[f64], label: &str, markers: bool) -> Vec<Series> {
    incidence_deg
        .iter()
        .enumerate()
        .map(|(k, &ti)| Series {
            label: format!("{label}{ti}°"),
            points: (-89..=89)
                .map(|ts| {
                    let f = brdf.eval(
                        inplane_direction((ts as f64).to_radians()),
                        incidence_direction(ti.to_radians()),
                    );
                    (ts as f64, (f.x + f.y + f.z) / 3.0)
                })
                .collect(),
            colour: plot::palette(k),
            markers,
        })
        .collect()
}

/// The in-plane samples of a measurement at each plotted incidence (within 0.5°), as marker
/// series of the table's colours: signed scattering angle (+ on the specular side) and the mean
/// of the table's RGB of each measured spectrum, as the curves are drawn.
fn measured_in_plane(table: &BrdfTable, path: &Path, incidence_deg: &[f64]) -> Result<Vec<Series>> {
    let ext = gonio_io::extension(path);
    let samples = match ext.as_str() {
        "astm" => astm::read(path)?.samples,
        "csv" => csv::read_samples(path)?.1,
        _ => bail!(
            "{}: --measured takes a Cornell .astm or a .csv of samples",
            path.display()
        ),
    };
    if samples
        .first()
        .is_some_and(|s| s.values.len() != table.channel_count())
    {
        bail!(
            "{}: the measurement has {} channels and the table {}; plot the table imported from \
             it without --colour",
            path.display(),
            samples[0].values.len(),
            table.channel_count()
        );
    }
    let tolerance = 0.5f64.to_radians();
    Ok(incidence_deg
        .iter()
        .enumerate()
        .map(|(k, &ti)| {
            let points = samples
                .iter()
                .filter(|s| (s.wi.z.acos() - ti.to_radians()).abs() < tolerance)
                .filter_map(|s| {
                    // Turn the pair so that the source is at azimuth 180°, as `source` has it.
                    let wo = turn_about_z(s.wo, std::f64::consts::PI - s.wi.y.atan2(s.wi.x));
                    (wo.y.abs() < tolerance.sin()).then(|| {
                        let rgb = table.to_rgb(&s.values);
                        (wo.x.atan2(wo.z).to_degrees(), (rgb.x + rgb.y + rgb.z) / 3.0)
                    })
                })
                .collect();
            Series {
                label: format!("measured {ti}°"),
                points,
                colour: plot::palette(k),
                markers: true,
            }
        })
        // An incidence the file did not measure gets no legend entry.
        .filter(|s| !s.points.is_empty())
        .collect())
}

fn plot_table(a: PlotArgs) -> Result<()> {
    let t = load(&a.table)?;
    let mut curves = in_plane(&t, &a.incidence_deg, "theta_i ", false);
    let measured = match &a.measured {
        Some(path) => measured_in_plane(&t, path, &a.incidence_deg)?,
        None => vec![],
    };
    // Polar lobe view: f cos θo, normalised per curve, in the plane of incidence.
    let lobes: Vec<Series> = curves
        .iter()
        .zip(&a.incidence_deg)
        .map(|(c, ti)| {
            let max = c
                .points
                .iter()
                .map(|(ts, f)| f * ts.to_radians().cos())
                .fold(0.0, f64::max);
            Series {
                label: format!("theta_i {ti}°"),
                points: c
                    .points
                    .iter()
                    .map(|(ts, f)| {
                        let r = if max > 0.0 {
                            f * ts.to_radians().cos() / max
                        } else {
                            0.0
                        };
                        (r * ts.to_radians().sin(), r * ts.to_radians().cos())
                    })
                    .collect(),
                colour: c.colour,
                markers: false,
            }
        })
        .collect();
    let title = a
        .table
        .file_name()
        .and_then(|s| s.to_str())
        .unwrap_or("table")
        .to_string();
    curves.extend(measured);
    plot::render_png(&a.output, (1400, 600), |root| {
        let (left, right) = root.split_horizontally(800);
        plot::draw_line_plot(
            &left,
            &LinePlot {
                title: &format!("{title}: in-plane BRDF"),
                x_label: SCATTER_AXIS,
                y_label: BRDF_AXIS,
                log_y: true,
            },
            &curves,
        )?;
        plot::draw_line_plot(
            &right,
            &LinePlot {
                title: "lobes: f cos(theta_s), normalised",
                x_label: "f·cos θs, normalised: along the surface (+ on the specular side)",
                y_label: "f·cos θs, normalised: along the normal",
                log_y: false,
            },
            &lobes,
        )
    })?;
    println!("wrote {}", a.output.display());
    Ok(())
}

fn tabulate(a: TabulateArgs) -> Result<()> {
    let text = if Path::new(&a.model).is_file() {
        std::fs::read_to_string(&a.model).with_context(|| format!("{}: cannot read", a.model))?
    } else {
        a.model.clone()
    };
    let spec = ModelSpec::from_json(&text).map_err(|e| {
        anyhow::anyhow!(
            "--model: {e}; e.g. '{{\"model\":\"ward\",\"specular\":0.05,\"alpha\":0.1}}'"
        )
    })?;
    let model = spec.build()?;
    let res = resolution(&a.resolution)?;
    let pb = spinner("tabulating");
    let table = BrdfTable::from_brdf(&model, res, a.mono, Provenance::new(text.trim(), "model"))?;
    pb.finish_and_clear();
    gbrdf::write(&table, &a.output)?;
    println!(
        "wrote {} ({}, {})",
        a.output.display(),
        table.resolution().describe(),
        table.channels().describe()
    );
    Ok(())
}

fn fit_table(a: FitArgs) -> Result<()> {
    let t = load(&a.table)?;
    let kind = match a.model {
        FitModel::Ward => FitKind::Ward,
        FitModel::Beckmann => FitKind::Beckmann,
        FitModel::Ggx => FitKind::Ggx,
        FitModel::Phong => FitKind::Phong,
    };
    let samples = t.fit_samples(80f64.to_radians());
    let pb = spinner("fitting");
    let result = fit(
        kind,
        &samples,
        FitOptions {
            diffuse: a.diffuse,
            ..FitOptions::default()
        },
    )?;
    pb.finish_and_clear();
    if let Some(path) = &a.plot {
        let model = result.spec.build()?;
        let inc = [20.0, 45.0, 70.0];
        let mut series = in_plane(&t, &inc, "table ", true);
        series.extend(in_plane(&model, &inc, "fit ", false));
        plot::line_plot_png(
            path,
            (900, 600),
            &LinePlot {
                title: &format!("{} fit of {}", kind.name(), a.table.display()),
                x_label: SCATTER_AXIS,
                y_label: BRDF_AXIS,
                log_y: true,
            },
            &series,
        )?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&result)?);
        return Ok(());
    }
    println!(
        "model        {}{} (fitted to the mean of the channels)",
        kind.name(),
        if a.diffuse { " + lambert" } else { "" }
    );
    for p in &result.parameters {
        println!("{:<12} {:.6} ± {:.6}", p.name, p.value, p.uncertainty);
    }
    println!(
        "residual     {:.2}% (weighted rms relative to the data)",
        100.0 * result.residual_rms_relative
    );
    println!(
        "converged    {} ({} evaluations, {} samples)",
        result.converged,
        result.evaluations,
        samples.len()
    );
    println!("spec         {}", serde_json::to_string(&result.spec)?);
    Ok(())
}
