//! `gonio coating compute | info`: a coating described in TOML (a smooth or rough clear coat
//! over a diffuse or Kubelka-Munk base, with or without effect flakes; `docs/coatings.md`)
//! turned into a spectral BRDF table, and a summary of its optics and multi-angle colour
//! (`gonio_coating::system`, `gonio_instrument::multiangle`).

use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use gonio_coating::cell::CellWalks;
use gonio_coating::description;
use gonio_coating::layered::Scratch;
use gonio_coating::system::{Coating, Evaluator, Method};
use gonio_instrument::multiangle::{self, E2194, Geometry, MultiangleReading, Settings};
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Subcommand)]
pub enum CoatingCommand {
    /// Tabulate the coating's reflection as a spectral .gbrdf: `gonio coating compute
    /// COATING.toml -o T.gbrdf`. A smooth top's mirror reflection (a delta) is left out; a
    /// rough top's reflection is in the table.
    Compute(ComputeArgs),
    /// The coating's optics: coat index, base reflectance, the coat's mirror reflectance at the
    /// gloss angles, the directional-hemispherical reflectance, and its multi-angle colour
    /// (ASTM E2194, D65/10°).
    Info(InfoArgs),
    /// A formulation study: the coating's gloss, haze, DOI and multi-angle colour against one
    /// constituent at a time (`--vary roughness --values 0.01,0.05,0.1`), with plots.
    Study(StudyArgs),
}

#[derive(Args)]
pub struct StudyArgs {
    /// The coating's description (TOML; examples/coatings/).
    coating: PathBuf,
    /// The constituent to vary: roughness (the top's α; 0 is smooth), tilt (the flakes' rms
    /// tilt, °), coverage (the flakes' share of the base), tio2 (interference flakes' TiO2, nm),
    /// thickness (the coat's, µm) or concentration:NAME (a pigment of a Kubelka-Munk base).
    #[arg(long)]
    vary: String,
    /// The values, comma-separated. Default for roughness: the epoxy roughness series of
    /// `gonio study` as Beckmann rms slopes 2 Sq/T (Sq 3, 50, 150, 201, 400, 805 nm; T 6 µm).
    #[arg(long, value_delimiter = ',')]
    values: Vec<f64>,
    /// The multi-angle geometries: e2194 (45° illumination) or e2539 (with 15° illumination).
    #[arg(long, default_value = "e2194")]
    standard: String,
    /// Random walks per multi-angle geometry (a rough top or flakes); the gloss meter uses a
    /// sixty-fourth of this per quadrature point.
    #[arg(long, default_value_t = 8192)]
    samples: usize,
    /// Folder for study.csv, study.json, the plots and the pictures (created if missing).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Leave out the pictures: with --output, each value's coating is otherwise drawn on a
    /// curved panel in a studio (panel-VALUE.png, from a 45 × 45 × 24 spectral table of 32
    /// walks per cell, panel-VALUE.gbrdf, and the scene panel-VALUE.toml that `gonio render`
    /// runs as written; a few seconds each).
    #[arg(long)]
    no_pictures: bool,
    /// Print the rows as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
pub struct ComputeArgs {
    /// The coating's description (TOML; examples/coatings/).
    coating: PathBuf,
    /// Output table (.gbrdf).
    #[arg(short, long)]
    output: PathBuf,
    /// Nodes theta_h,theta_d,phi_d of the table.
    #[arg(long, value_delimiter = ',', default_value = crate::list_default(&crate::brdf::import_resolution()))]
    resolution: Vec<usize>,
    /// Wavelengths of the table's channels, nm: first:last:step.
    #[arg(long, default_value = DEFAULT_BANDS)]
    bands: String,
    /// Random walks per table cell for a rough top or flakes, before any are added (the smooth
    /// coat over a diffuse base is computed exactly). The noise falls as 1/sqrt(walks).
    #[arg(long, default_value_t = TABLE_WALKS)]
    samples: usize,
    /// Target noise of a table cell, in CIELAB L* units (D65, 10° observer): one standard
    /// error of the cell's lightness, as the first --samples walks of the cells around it
    /// (two nodes either way along each angle) show it. A cell whose expected error is above
    /// the target takes more walks, in multiples of --samples (the error falls as
    /// 1/sqrt(walks)), at most 16 times --samples. A reading interpolates up to eight cells
    /// with weights that sum to 1, so cells within 1/3 L* keep a reading within 1/3 L* (1 L*
    /// is then three standard deviations). 0 or inf: --samples walks in every cell.
    /// [default: 1/3]
    #[arg(long, value_name = "L*", default_value_t = TARGET_DL, hide_default_value = true)]
    target_dl: f64,
    #[command(flatten)]
    colour: crate::brdf::ColourArgs,
}

#[derive(Args)]
pub struct InfoArgs {
    /// The coating's description (TOML).
    coating: PathBuf,
    /// Print JSON: coat_index, base_reflectance, specular (20/60/85°; 0 for a rough top, whose
    /// reflection is spread), albedo (0/45/75°, at 550 nm) and multiangle (as
    /// `gonio multiangle --json`'s geometries).
    #[arg(long)]
    json: bool,
    /// Random walks per evaluation for a rough top or flakes (the colour at each geometry uses
    /// this many; the albedo 16 times as many outgoing directions).
    #[arg(long, default_value_t = 4096)]
    samples: usize,
}

pub fn run(cmd: CoatingCommand) -> Result<()> {
    match cmd {
        CoatingCommand::Compute(a) => compute(a),
        CoatingCommand::Info(a) => info(a),
        CoatingCommand::Study(a) => study(a),
    }
}

/// Random walks per table cell before any are added, unless told otherwise (`compute
/// --samples`; the pictures' tables).
pub(crate) const TABLE_WALKS: usize = gonio_coating::system::TABLE_WALKS;

/// The standard error of a cell's L* above which walks are added, unless told otherwise
/// (`compute --target-dl`; the pictures' tables).
pub(crate) const TARGET_DL: f64 = gonio_coating::system::TARGET_DL;

/// The bands of a coating's tables and readings unless told otherwise, as `--bands` takes them.
const DEFAULT_BANDS: &str = "400:700:10";

/// The 31 bands 400, 410, ..., 700 nm.
pub(crate) fn default_bands() -> Vec<f64> {
    bands(DEFAULT_BANDS).expect("the default bands are valid")
}

/// The bands of `--bands first:last:step`.
fn bands(spec: &str) -> Result<Vec<f64>> {
    let parts: Vec<f64> = spec
        .split(':')
        .map(|p| p.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .with_context(|| format!("--bands {spec}: write first:last:step in nm, e.g. 400:700:10"))?;
    let [first, last, step] = parts[..] else {
        anyhow::bail!("--bands {spec}: write first:last:step in nm, e.g. 400:700:10");
    };
    anyhow::ensure!(
        first > 0.0 && last > first && step > 0.0 && ((last - first) / step) < 1000.0,
        "--bands {spec}: needs 0 < first < last and a positive step (at most 1000 bands)"
    );
    let n = ((last - first) / step + 1e-9).floor() as usize + 1;
    anyhow::ensure!(n >= 2, "--bands {spec}: needs at least two bands");
    Ok((0..n).map(|i| first + step * i as f64).collect())
}

fn read(path: &Path, wavelengths: &[f64]) -> Result<Coating> {
    Ok(description::read(path, wavelengths)?)
}

fn compute(a: ComputeArgs) -> Result<()> {
    let wavelengths = bands(&a.bands)?;
    let res = crate::brdf::resolution(&a.resolution)?;
    anyhow::ensure!(
        !a.target_dl.is_nan() && a.target_dl >= 0.0,
        "--target-dl {}: give the target noise in L* units (e.g. 0.33), or 0 or inf for a fixed \
         number of walks per cell",
        a.target_dl
    );
    let coating = read(&a.coating, &wavelengths)?;
    let walks = CellWalks::adaptive(a.samples, a.target_dl);
    let method = coating.method(walks);
    let provenance = coating.provenance(a.coating.display().to_string(), method);
    let (table, spent) = coating
        .table_cells(res, &wavelengths, walks, provenance, |_| true)
        .with_context(|| a.coating.display().to_string())?;
    let table = a.colour.apply(table, &a.coating)?;
    gonio_brdf::gbrdf::write(&table, &a.output)?;
    let what = match method {
        Method::ClosedForm => "body reflection, exact; the mirror reflection is not in the \
                               table"
            .to_string(),
        Method::RandomWalk(walks) => {
            let added = match walks.target_dl {
                Some(t) => format!(
                    "{} random walks per cell and more where a cell's L* would be noisier than \
                     {t:.2}: {}",
                    walks.base,
                    spent.describe()
                ),
                None => format!("{} random walks per cell", walks.base),
            };
            let reflects = if coating.roughness.is_some() {
                "everything the coating reflects"
            } else {
                "the mirror reflection is not in the table"
            };
            format!("{added}; {reflects}")
        }
    };
    let reduced = if a.colour.reduces() {
        format!(", reduced to {}", table.channels().describe())
    } else {
        String::new()
    };
    eprintln!(
        "{}: {} × {} × {} nodes, {} bands {}–{} nm{reduced} ({what})",
        a.output.display(),
        res.theta_h,
        res.theta_d,
        res.phi_d,
        wavelengths.len(),
        wavelengths[0],
        wavelengths[wavelengths.len() - 1]
    );
    Ok(())
}

/// The coating's multi-angle reading at `geometries` (a smooth top's mirror reflection is 15°
/// or more away from every standard geometry), D65/10°, with `samples` walks per geometry.
pub fn multiangle_reading(
    evaluator: &Evaluator,
    wavelengths: &[f64],
    geometries: &[Geometry],
    samples: usize,
) -> Result<MultiangleReading> {
    let body = |wo: glam::DVec3, wi: glam::DVec3, out: &mut [f64]| {
        evaluator.eval(wo, wi, samples, 1, &mut Scratch::default(), out);
    };
    Ok(multiangle::read(
        &body,
        wavelengths,
        geometries,
        &Settings::default(),
    )?)
}

fn info(a: InfoArgs) -> Result<()> {
    let wavelengths = default_bands();
    let coating = read(&a.coating, &wavelengths)?;
    let evaluator = coating.evaluator(&wavelengths)?;
    let band = |nm: f64| {
        wavelengths
            .iter()
            .position(|&w| w == nm)
            .expect("400, 450, ..., 700 nm are among the 10 nm bands")
    };
    let index = |nm: f64| coating.coat.index.at(nm);
    let rho = wavelengths
        .iter()
        .map(|&w| coating.base.reflectance(w))
        .collect::<gonio_coating::Result<Vec<_>>>()?;
    let at550 = band(550.0);
    let gloss_angles = [20.0f64, 60.0, 85.0];
    let specular: Vec<f64> = gloss_angles
        .iter()
        .map(|d| evaluator.mirror(d.to_radians().cos())[at550])
        .collect();
    let albedo_angles = [0.0f64, 45.0, 75.0];
    let albedo: Vec<f64> = albedo_angles
        .iter()
        .map(|d| evaluator.albedo(d.to_radians().cos(), 16 * a.samples)[at550])
        .collect();
    let reading = multiangle_reading(&evaluator, &wavelengths, &E2194, a.samples)?;
    if a.json {
        let json = serde_json::json!({
            "file": a.coating.display().to_string(),
            "coat_index": { "400": index(400.0), "550": index(550.0), "700": index(700.0) },
            "base_reflectance": wavelengths.iter().zip(&rho).map(|(w, r)| serde_json::json!({"nm": w, "reflectance": r})).collect::<Vec<_>>(),
            "specular": gloss_angles.iter().zip(&specular).map(|(d, r)| serde_json::json!({"theta_deg": d, "reflectance": r})).collect::<Vec<_>>(),
            "albedo": albedo_angles.iter().zip(&albedo).map(|(d, r)| serde_json::json!({"theta_i_deg": d, "albedo": r})).collect::<Vec<_>>(),
            "multiangle": reading.geometries.iter().map(|g| serde_json::json!({
                "name": g.geometry.to_string(), "L": g.lab.l, "a": g.lab.a, "b": g.lab.b,
                "C": g.lab.chroma(), "h_deg": g.lab.hue_deg(),
            })).collect::<Vec<_>>(),
            "flop_index": reading.flop_index(),
        });
        println!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(());
    }
    println!("{}", a.coating.display());
    println!(
        "coat: n {:.4} / {:.4} / {:.4} at 400 / 550 / 700 nm, {} µm",
        index(400.0),
        index(550.0),
        index(700.0),
        coating.coat.thickness_um
    );
    let rho: Vec<String> = [400.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0]
        .iter()
        .map(|&w| format!("{:.3}", rho[band(w)]))
        .collect();
    println!(
        "base reflectance at 400, 450, ..., 700 nm: {}",
        rho.join(" ")
    );
    match coating.roughness {
        None => println!(
            "mirror reflectance of the coat (550 nm) at 20 / 60 / 85°: {:.4} / {:.4} / {:.4}",
            specular[0], specular[1], specular[2]
        ),
        Some(m) => println!(
            "rough top: {:?} α {:.4} (rms slope {:.1}°); its reflection is spread, in the BRDF",
            m.distribution,
            m.alpha_x,
            m.alpha_x.atan().to_degrees()
        ),
    }
    if let Some(f) = &coating.flakes {
        println!(
            "flakes: {} cover {:.0}% of the base, rms tilt {}°",
            match f.pigment {
                gonio_coating::flakes::FlakePigment::Metal { .. } => "metal",
                gonio_coating::flakes::FlakePigment::Interference { .. } => "interference",
            },
            100.0 * f.coverage,
            f.tilt_deg
        );
    }
    println!(
        "directional-hemispherical reflectance (550 nm) at 0 / 45 / 75°: {:.4} / {:.4} / {:.4}",
        albedo[0], albedo[1], albedo[2]
    );
    println!("multi-angle colour (ASTM E2194, D65/10°):");
    println!(
        "{:>9} {:>8} {:>8} {:>8} {:>8}",
        "geometry", "L*", "a*", "b*", "C*ab"
    );
    for g in &reading.geometries {
        println!(
            "{:>9} {:>8.2} {:>8.2} {:>8.2} {:>8.2}",
            g.geometry.to_string(),
            g.lab.l,
            g.lab.a,
            g.lab.b,
            g.lab.chroma()
        );
    }
    if let Some(fi) = reading.flop_index() {
        println!("flop index: {fi:.2}");
    }
    Ok(())
}

fn study(a: StudyArgs) -> Result<()> {
    use gonio_instrument::coating_study::{self, Constituent};
    let wavelengths = default_bands();
    let coating = read(&a.coating, &wavelengths)?;
    let constituent = Constituent::parse(&a.vary)?;
    let values = match (&constituent, a.values.is_empty()) {
        (Constituent::Roughness, true) => Constituent::epoxy_series(),
        (_, true) => anyhow::bail!("--values: give the values of {} to study", a.vary),
        _ => a.values.clone(),
    };
    let geometries: &[Geometry] = match a.standard.as_str() {
        "e2194" => &E2194,
        "e2539" => &multiangle::E2539,
        other => anyhow::bail!("--standard {other}: e2194 or e2539"),
    };
    let rows = coating_study::run(
        &coating,
        &constituent,
        &values,
        geometries,
        &wavelengths,
        a.samples,
        (a.samples / 64).max(1),
    )
    .with_context(|| a.coating.display().to_string())?;
    let label = constituent.label();
    let json = serde_json::json!({
        "file": a.coating.display().to_string(),
        "vary": a.vary,
        "label": label,
        "rows": rows.iter().map(|r| serde_json::json!({
            "value": r.value,
            "gu20": r.gloss.gu20, "gu60": r.gloss.gu60, "gu85": r.gloss.gu85,
            "haze": r.gloss.haze, "haze_20_log": r.gloss.haze_20_log, "doi": r.gloss.doi,
            "flop_index": r.multiangle.flop_index(),
            "multiangle": r.multiangle.geometries.iter().map(|g| serde_json::json!({
                "name": g.geometry.to_string(), "L": g.lab.l, "a": g.lab.a, "b": g.lab.b,
                "C": g.lab.chroma(), "h_deg": g.lab.hue_deg(),
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    });
    if let Some(dir) = &a.output {
        std::fs::create_dir_all(dir).with_context(|| dir.display().to_string())?;
        let mut csv = String::from("value,gu20,gu60,gu85,haze,haze_20_log,doi,flop_index");
        for g in geometries {
            csv.push_str(&format!(",L_{g},a_{g},b_{g}"));
        }
        csv.push('\n');
        for r in &rows {
            csv.push_str(&format!(
                "{},{},{},{},{},{},{},{}",
                r.value,
                r.gloss.gu20,
                r.gloss.gu60,
                r.gloss.gu85,
                r.gloss.haze,
                r.gloss.haze_20_log,
                r.gloss.doi,
                r.multiangle
                    .flop_index()
                    .map_or(String::new(), |f| f.to_string())
            ));
            for g in &r.multiangle.geometries {
                csv.push_str(&format!(",{},{},{}", g.lab.l, g.lab.a, g.lab.b));
            }
            csv.push('\n');
        }
        crate::output::write_atomic(&dir.join("study.csv"), |w| Ok(w.write_all(csv.as_bytes())?))?;
        let text = serde_json::to_string_pretty(&json)?;
        crate::output::write_atomic(&dir.join("study.json"), |w| {
            Ok(w.write_all(text.as_bytes())?)
        })?;
        plot_study(dir, &label, &rows)?;
        if !a.no_pictures {
            let source = a.coating.display().to_string();
            for r in &rows {
                let variant = constituent.apply(&coating, r.value)?;
                let name = format!("panel-{}", r.value);
                let panel = crate::panel::table(&variant, &source, dir, &name)
                    .with_context(|| format!("{source}: the picture at {label} {}", r.value))?;
                let scene = crate::panel::scene(dir, &name, &[panel])?;
                let (png, stats) = crate::panel::render(&scene)?;
                eprintln!(
                    "{}: {label} {} ({:.0} s to render)",
                    png.display(),
                    r.value,
                    stats.seconds
                );
            }
        }
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(());
    }
    println!("{} against {label}", a.coating.display());
    print!(
        "{:>10} {:>7} {:>7} {:>7} {:>7} {:>7} {:>6}",
        "value", "GU20", "GU60", "GU85", "haze", "DOI", "flop"
    );
    for g in geometries {
        print!(" {:>9}", format!("L*{g}"));
    }
    println!();
    for r in &rows {
        print!(
            "{:>10.4} {:>7.1} {:>7.1} {:>7.1} {:>7.1} {:>7.1} {:>6}",
            r.value,
            r.gloss.gu20,
            r.gloss.gu60,
            r.gloss.gu85,
            r.gloss.haze,
            r.gloss.doi,
            r.multiangle
                .flop_index()
                .map_or("—".into(), |f| format!("{f:.1}"))
        );
        for g in &r.multiangle.geometries {
            print!(" {:>9.2}", g.lab.l);
        }
        println!();
    }
    if let Some(dir) = &a.output {
        eprintln!(
            "wrote study.csv, study.json, gloss.png and lightness.png in {}",
            dir.display()
        );
    }
    Ok(())
}

/// The study's plots: gloss (20/60/85°) and DOI against the varied constituent, and L* at each
/// multi-angle geometry against it.
fn plot_study(
    dir: &Path,
    label: &str,
    rows: &[gonio_instrument::coating_study::StudyRow],
) -> Result<()> {
    use crate::plot::{self, LinePlot, Series};
    let gloss: Vec<Series> = [("20°", 0), ("60°", 1), ("85°", 2), ("DOI", 3)]
        .into_iter()
        .map(|(name, i)| Series {
            label: if i == 3 {
                "DOI".into()
            } else {
                format!("gloss {name}")
            },
            points: rows
                .iter()
                .map(|r| {
                    (
                        r.value,
                        [r.gloss.gu20, r.gloss.gu60, r.gloss.gu85, r.gloss.doi][i],
                    )
                })
                .collect(),
            colour: plot::palette(i),
            markers: false,
        })
        .collect();
    plot::line_plot_png(
        &dir.join("gloss.png"),
        (900, 600),
        &LinePlot {
            title: &format!("Gloss (ISO 2813, GU) and DOI (ASTM E430) against {label}"),
            x_label: label,
            y_label: "GU / DOI",
            log_y: false,
        },
        &gloss,
    )?;
    let lightness: Vec<Series> = rows[0]
        .multiangle
        .geometries
        .iter()
        .enumerate()
        .map(|(k, g)| Series {
            label: g.geometry.to_string(),
            points: rows
                .iter()
                .map(|r| (r.value, r.multiangle.geometries[k].lab.l))
                .collect(),
            colour: plot::palette(k),
            markers: false,
        })
        .collect();
    plot::line_plot_png(
        &dir.join("lightness.png"),
        (900, 600),
        &LinePlot {
            title: &format!("Multi-angle lightness L* (D65/10°) against {label}"),
            x_label: label,
            y_label: "L*",
            log_y: false,
        },
        &lightness,
    )
}
