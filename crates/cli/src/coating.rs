//! `gonio coating compute | info`: a coating described in TOML (a smooth or rough clear coat
//! over a diffuse or Kubelka-Munk base, with or without effect flakes; `docs/coatings.md`)
//! turned into a spectral BRDF table, and a summary of its optics and multi-angle colour
//! (`gonio_coating::system`, `gonio_instrument::multiangle`).

use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use gonio_coating::cell::CellWalks;
use gonio_coating::description;
use gonio_coating::system::{Coating, Method, default_bands};
use gonio_instrument::coating_study_output;
use gonio_instrument::coating_summary::summarise;
use gonio_instrument::multiangle;
use gonio_render::panel;
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
    /// Which constituents drive which reading: variance-based global sensitivity (Sobol
    /// first-order and total indices) or Morris screening of gloss, haze, DOI, multi-angle
    /// colour, flop and ΔE00 against constituents varied within bounds (`--vary
    /// tilt=4:20,roughness=0.01:0.1`; docs/formulation.md).
    Sensitivity(SensitivityArgs),
    /// From a target back to a formulation: the values of the varied constituents, within
    /// their bounds, that minimise the rms difference of reflectance factors to a multi-angle
    /// target that gives them, else the mean CIEDE2000 (plus weighted gloss differences); writes the fitted description (`-o FITTED.toml`, the start's text
    /// with the values replaced) and prints the values with their uncertainties and ΔE00 per
    /// geometry before and after (docs/formulation.md). `--select N` also chooses up to N
    /// pigments of gonio's library: every combination screened, the best few matched in full.
    Match(MatchArgs),
    /// A formulation against a measurement, including what a match did not see: ΔE00 at every
    /// geometry of a standard (E2539 by default: lit at 45° and at 15°) and, for a measured BRDF
    /// (.astm), at every measured sample (docs/formulation.md).
    Predict(crate::coating_predict::PredictArgs),
}

#[derive(Args)]
pub struct MatchArgs {
    /// The start formulation (TOML; examples/coatings/): the first guess, and everything that
    /// is not varied.
    coating: PathBuf,
    /// The target: a CSV of CIELAB (geometry,L,a,b; D65/10°) or of reflectance factors
    /// (geometry,R_400nm,...,R_700nm) per geometry, holding every geometry of the standard; a
    /// measured BRDF (.astm, imported as `gonio brdf import` does); or a spectral table
    /// (.gbrdf). The last two are read at the standard's geometries.
    #[arg(long)]
    target: PathBuf,
    /// The constituents to fit, comma-separated, each NAME or NAME=LO:HI: roughness (the top's
    /// α), tilt (°), coverage (0–1), tio2 (nm), thickness (the coat's, µm), base_thickness
    /// (the Kubelka-Munk basecoat's, µm), concentration:PIGMENT. The search stays within the
    /// bounds (see --bounds). With --select, the selected pigments' concentrations are varied
    /// too (and --vary may be left out).
    #[arg(long, default_value = "")]
    vary: String,
    /// Select up to N pigments of gonio's library (`gonio pigments`) and add them to the
    /// start's base (which must be kind = "kubelka-munk"): every combination of 1 to N of the
    /// candidates is screened with its concentrations fitted (a fraction of the pigment's paint
    /// in the layer, 0.001–1; seconds), then the full match runs on the best --finalists, each
    /// concentration within a tenth to ten times its screened value (docs/formulation.md,
    /// "Colorant selection"). Formulation programs use 3.
    #[arg(long, value_name = "N")]
    select: Option<usize>,
    /// With --select: the candidates, library names comma-separated (default: the whole
    /// library, less the pigments already in the start's base).
    #[arg(long, value_name = "NAME,NAME,...", requires = "select")]
    from: Option<String>,
    /// With --select: how many of the screen's best combinations get the full match (each a
    /// match of its own: tens of seconds for a metallic).
    #[arg(long, value_name = "K", default_value_t = gonio_formulation::selection::FINALISTS, requires = "select")]
    finalists: usize,
    /// With --select and --json: how many of the screened combinations the JSON lists (best
    /// first; it gives their count too).
    #[arg(long, default_value_t = 20, requires = "select")]
    shown: usize,
    /// Bounds of constituents named in --vary without them, NAME=LO:HI comma-separated.
    /// Default: α 0.005–0.3, tilt 2–40°, coverage 0.05–0.95, tio2 40–300 nm, thickness
    /// 5–200 µm, base_thickness 5–60 µm, a concentration from 0.1 to 4 times the start's.
    #[arg(long)]
    bounds: Option<String>,
    /// The geometries matched: e2194 (45° illumination; aspecular 15, 25, 45, 75, 110°) or
    /// e2539 (adds 45as-15 and 15° illumination).
    #[arg(long, default_value = "e2194")]
    standard: String,
    /// Match these geometries instead of the standard's, each as illumination and aspecular
    /// angle in degrees, comma-separated (e.g. `--geometry 45as-15,45as15,45as25,45as45,45as75,
    /// 45as110`: E2539's geometries lit at 45°, leaving those lit at 15° for `gonio coating
    /// predict`). The target must hold each of them.
    #[arg(long, value_delimiter = ',', value_parser = crate::multiangle::parse_geometry)]
    geometry: Vec<multiangle::Geometry>,
    /// Gloss readings to match too, ANGLE=GU comma-separated (20, 60 or 85°; e.g. 20=85,60=92).
    #[arg(long)]
    target_gloss: Option<String>,
    /// ΔE00 units per gloss unit: the objective adds this × |ΔGU| for each --target-gloss.
    #[arg(long, default_value_t = gonio_formulation::matching::Settings::GLOSS_WEIGHT)]
    gloss_weight: f64,
    /// Random walks per multi-angle geometry of each reading (a rough top or flakes); the
    /// gloss meter takes 8 per quadrature point. Every reading draws the same streams (common
    /// random numbers), so the objective is smooth in the constituents.
    #[arg(long, default_value_t = gonio_formulation::coating_sensitivity::Settings::WALKS)]
    walks: usize,
    /// Nelder–Mead runs before the final one: from the start formulation, then from Sobol
    /// points of the bounds.
    #[arg(long, default_value_t = gonio_formulation::matching::Settings::STARTS)]
    starts: usize,
    /// What the match minimises: auto (spectral where the target gives reflectance factors —
    /// a CSV of R_...nm, a .astm, a .gbrdf — and no --target-gloss is given, de00 otherwise),
    /// de00 (the mean CIEDE2000 over the standard's geometries, plus the weighted gloss
    /// differences) or spectral (the rms difference of reflectance factors over the target's
    /// bands and geometries; no --target-gloss). A spectral match is not metameric; ΔE00 is
    /// reported either way.
    #[arg(long, default_value = "auto")]
    objective: gonio_formulation::match_objective::ObjectiveChoice,
    /// The fitted formulation (TOML): the start's text with the varied values replaced,
    /// comments kept (with --select, the chosen pigments added as `library = "NAME"`).
    #[arg(short, long)]
    output: PathBuf,
    /// Print the result as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
pub struct SensitivityArgs {
    /// The base formulation (TOML; examples/coatings/).
    coating: PathBuf,
    /// The constituents to vary, comma-separated, each NAME or NAME=LO:HI; NAME as `coating
    /// study --vary` takes it: roughness (the top's α), tilt (°), coverage (0–1), tio2 (nm),
    /// thickness (the coat's, µm), base_thickness (the Kubelka-Munk basecoat's, µm),
    /// concentration:PIGMENT.
    #[arg(long)]
    vary: String,
    /// Bounds of constituents named in --vary without them, NAME=LO:HI comma-separated.
    /// Default: α 0.005–0.3, tilt 2–40°, coverage 0.05–0.95, tio2 40–300 nm, thickness
    /// 5–200 µm, base_thickness 5–60 µm, a concentration from 0.1 to 4 times the base's.
    #[arg(long)]
    bounds: Option<String>,
    /// The readings to analyse, comma-separated: gu20, gu60, gu85 (ISO 2813 gloss, GU), haze
    /// (ASTM E430, HU), doi (0–100), flop (Alman's index), dE00 (mean CIEDE2000 from the base
    /// formulation over the standard's geometries), L@G, a@G, b@G (CIELAB D65/10° at geometry G,
    /// e.g. L@45as15). Default: all of them at the standard's geometries.
    #[arg(long)]
    outputs: Option<String>,
    /// sobol (variance-based: first-order S1 and total ST indices, 95% bootstrap intervals;
    /// N (d + 2) readings) or morris (elementary effects μ, μ*, σ; r (d + 1) readings, a
    /// cheaper screening).
    #[arg(long, default_value = "sobol")]
    method: String,
    /// The sample size: Sobol's base points N (default 32: 160 readings for 3 constituents,
    /// about a minute of 2 cores on a metallic), or Morris's trajectories r (default 20).
    #[arg(long)]
    samples: Option<usize>,
    /// The multi-angle geometries: e2194 (45° illumination) or e2539 (with 15° illumination).
    #[arg(long, default_value = "e2194")]
    standard: String,
    /// Random walks per multi-angle geometry of each reading (a rough top or flakes); the
    /// gloss meter takes 8 per quadrature point. Every reading draws the same streams (common
    /// random numbers), so the differences between readings are the formulation's.
    #[arg(long, default_value_t = gonio_formulation::coating_sensitivity::Settings::WALKS)]
    walks: usize,
    /// An input "matters" for an output in the summary when its total index ST is at least
    /// this (Sobol), or its μ* at least this share of the largest (Morris).
    #[arg(long, default_value_t = 0.1)]
    threshold: f64,
    /// Folder for sensitivity.csv, summary.txt and one bar chart per output (created if
    /// missing).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Print the indices as JSON.
    #[arg(long)]
    json: bool,
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
    /// is then three standard deviations). Cells with a direction more than 70° from the
    /// normal, which no multi-angle geometry reads (E2194/E2539 view at most 65° off it), are
    /// held to three times the target. 0 or inf: --samples walks in every cell.
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
        CoatingCommand::Sensitivity(a) => sensitivity(a),
        CoatingCommand::Match(a) => match_target(a),
        CoatingCommand::Predict(a) => crate::coating_predict::predict(a),
    }
}

/// Random walks per table cell before any are added, unless told otherwise (`compute
/// --samples`).
const TABLE_WALKS: usize = gonio_coating::system::TABLE_WALKS;

/// The standard error of a cell's L* above which walks are added, unless told otherwise
/// (`compute --target-dl`).
const TARGET_DL: f64 = gonio_coating::system::TARGET_DL;

/// The bands of a coating's tables and readings unless told otherwise, as `--bands` takes them
/// ([`gonio_coating::system::default_bands`]).
const DEFAULT_BANDS: &str = "400:700:10";

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

pub(crate) fn read(path: &Path, wavelengths: &[f64]) -> Result<Coating> {
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

fn info(a: InfoArgs) -> Result<()> {
    let wavelengths = default_bands();
    let coating = read(&a.coating, &wavelengths)?;
    let s = summarise(&coating, &wavelengths, a.samples)
        .with_context(|| a.coating.display().to_string())?;
    let index = |nm: f64| {
        s.coat_index
            .iter()
            .find(|(w, _)| *w == nm)
            .map_or(f64::NAN, |(_, n)| *n)
    };
    if a.json {
        let mut json = serde_json::json!({ "file": a.coating.display().to_string() });
        if let (Some(out), serde_json::Value::Object(fields)) = (json.as_object_mut(), s.to_json())
        {
            out.extend(fields);
        }
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
    let rho: Vec<String> = s
        .base_reflectance
        .iter()
        .filter(|(w, _)| (w - 400.0) % 50.0 == 0.0)
        .map(|(_, r)| format!("{r:.3}"))
        .collect();
    println!(
        "base reflectance at 400, 450, ..., 700 nm: {}",
        rho.join(" ")
    );
    let specular: Vec<f64> = s.specular.iter().map(|p| p.1).collect();
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
        use gonio_coating::basecoat::FlakeDepth;
        let place = match f.depth {
            None => "over the base".to_string(),
            Some(FlakeDepth::Spread) => "spread through the basecoat".to_string(),
            Some(FlakeDepth::Sheet(x)) => format!("in a sheet at {x} of the basecoat's depth"),
        };
        println!(
            "flakes: {} cover {:.0}% of the base, rms tilt {}°, {place}",
            match f.pigment {
                gonio_coating::flakes::FlakePigment::Metal { .. } => "metal",
                gonio_coating::flakes::FlakePigment::Interference { .. } => "interference",
            },
            100.0 * f.coverage,
            f.tilt_deg
        );
    }
    let albedo: Vec<f64> = s.albedo.iter().map(|p| p.1).collect();
    println!(
        "directional-hemispherical reflectance (550 nm) at 0 / 45 / 75°: {:.4} / {:.4} / {:.4}",
        albedo[0], albedo[1], albedo[2]
    );
    println!("multi-angle colour (ASTM E2194, D65/10°):");
    println!(
        "{:>9} {:>8} {:>8} {:>8} {:>8}",
        "geometry", "L*", "a*", "b*", "C*ab"
    );
    for g in &s.multiangle.geometries {
        println!(
            "{:>9} {:>8.2} {:>8.2} {:>8.2} {:>8.2}",
            g.geometry.to_string(),
            g.lab.l,
            g.lab.a,
            g.lab.b,
            g.lab.chroma()
        );
    }
    if let Some(fi) = s.multiangle.flop_index() {
        println!("flop index: {fi:.2}");
    }
    Ok(())
}

fn sensitivity(a: SensitivityArgs) -> Result<()> {
    use gonio_formulation::appearance::Output;
    use gonio_formulation::coating_sensitivity::{self, Indices, Method, Settings, Varied};
    let wavelengths = default_bands();
    let coating = read(&a.coating, &wavelengths)?;
    let varied = Varied::resolve_list(&a.vary, a.bounds.as_deref(), &coating, &wavelengths)
        .context("--vary")?;
    let geometries = multiangle::standard(&a.standard).context("--standard")?;
    let outputs = match &a.outputs {
        Some(list) => Output::parse_list(list).context("--outputs")?,
        None => Output::all(geometries),
    };
    let method = Method::parse(&a.method, a.samples).context("--method")?;
    let settings = Settings {
        geometries: geometries.to_vec(),
        walks: a.walks,
        ..Settings::default()
    };
    eprintln!(
        "{}: {} readings of {} outputs ({} constituents)",
        a.coating.display(),
        method.evaluations(varied.len()),
        outputs.len(),
        varied.len()
    );
    let s = coating_sensitivity::run(&coating, &varied, &outputs, method, &settings)
        .with_context(|| a.coating.display().to_string())?;
    if let Some(dir) = &a.output {
        let written = s.write(dir, a.threshold)?;
        eprintln!(
            "wrote {} files (sensitivity.csv, summary.txt, the bar charts) in {}",
            written.len(),
            dir.display()
        );
    }
    let names = s.input_names();
    if a.json {
        let mut json = serde_json::json!({ "file": a.coating.display().to_string() });
        if let (Some(out), serde_json::Value::Object(fields)) =
            (json.as_object_mut(), s.to_json(&varied, a.threshold))
        {
            out.extend(fields);
        }
        println!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(());
    }
    println!("{}", s.summary(a.threshold));
    let (index, conf) = match s.indices {
        Indices::Sobol(_) => ("ST", "95%"),
        Indices::Morris { .. } => ("mu*", "95%"),
    };
    print!("{:>12} {:>10} {:>8}", "output", "base", "noise");
    for n in &names {
        print!(" {:>18}", format!("{index} {n}"));
    }
    println!("   ({index} ± its {conf} interval)");
    for (k, o) in s.outputs.iter().enumerate() {
        print!("{:>12} {:>10.3} {:>8.3}", o.name(), s.base[k], s.noise[k]);
        let (bars, _) = s.bars(k);
        for n in &names {
            let (_, v, c) = bars.iter().find(|b| b.0 == *n).expect("a bar per input");
            print!(" {:>18}", format!("{v:.3} ± {c:.3}"));
        }
        println!();
    }
    Ok(())
}

fn match_target(a: MatchArgs) -> Result<()> {
    use gonio_formulation::coating_sensitivity::Varied;
    use gonio_formulation::matching::{self, Settings};
    use gonio_formulation::selection;
    use gonio_formulation::target::{GlossTarget, read_target};
    let wavelengths = default_bands();
    let coating = read(&a.coating, &wavelengths)?;
    let varied = Varied::resolve_list(&a.vary, a.bounds.as_deref(), &coating, &wavelengths)
        .context("--vary")?;
    let geometries: &[multiangle::Geometry] = if a.geometry.is_empty() {
        multiangle::standard(&a.standard).context("--standard")?
    } else {
        &a.geometry
    };
    let gloss = match &a.target_gloss {
        Some(s) => GlossTarget::parse_list(s).context("--target-gloss")?,
        None => vec![],
    };
    let candidates = match a.select {
        Some(_) => {
            let from: Option<Vec<String>> = a
                .from
                .as_ref()
                .map(|f| f.split(',').map(String::from).collect());
            let list = selection::candidates(&coating, from.as_deref())
                .with_context(|| format!("--select: {}", a.coating.display()))?;
            Some(list)
        }
        None => None,
    };
    let target = read_target(&a.target, geometries)?;
    let text =
        std::fs::read_to_string(&a.coating).with_context(|| a.coating.display().to_string())?;
    let settings = Settings {
        walks: a.walks,
        gloss_weight: a.gloss_weight,
        starts: a.starts,
        objective: a.objective.resolve(&target, gloss.len()),
        ..Settings::default()
    };
    if let (Some(n), Some(candidates)) = (a.select, candidates) {
        return select(
            &a,
            &coating,
            &text,
            &target,
            &gloss,
            &varied,
            &candidates,
            n,
            &settings,
        );
    }
    eprintln!(
        "{}: matching {} at {} geometries by {} ({} Nelder-Mead runs, objective {})",
        a.coating.display(),
        a.target.display(),
        geometries.len(),
        varied
            .iter()
            .map(|v| v.name.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        settings.starts + 1,
        settings.objective
    );
    let m = matching::run(&coating, &target, &gloss, &varied, &settings, &mut |line| {
        eprintln!("{line}")
    })
    .with_context(|| a.coating.display().to_string())?;
    let fitted =
        gonio_formulation::fitted_description::with_values(&text, &varied, &m.fitted.values)
            .with_context(|| a.coating.display().to_string())?;
    write_fitted(&a.output, &fitted)?;
    if a.json {
        print_json(&a, m.to_json(&target))?;
        return Ok(());
    }
    println!("{} matched to {}", a.coating.display(), a.target.display());
    print_match(&m, a.gloss_weight);
    println!(
        "{} readings in {:.1} s; wrote {}",
        m.evaluations,
        m.seconds,
        a.output.display()
    );
    Ok(())
}

/// The fitted description written to `path`.
fn write_fitted(path: &Path, text: &str) -> Result<()> {
    gonio_io::write_atomic(
        path,
        |w| std::io::Write::write_all(w, text.as_bytes()),
        std::convert::identity,
    )
    .with_context(|| path.display().to_string())
}

/// The match's (or selection's) JSON with the file names first.
fn print_json(a: &MatchArgs, result: serde_json::Value) -> Result<()> {
    let mut json = serde_json::json!({
        "file": a.coating.display().to_string(),
        "target": a.target.display().to_string(),
        "output": a.output.display().to_string(),
    });
    if let (Some(out), serde_json::Value::Object(fields)) = (json.as_object_mut(), result) {
        out.extend(fields);
    }
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}

/// `gonio coating match --select N`: the library's pigments selected and fitted
/// (`gonio_formulation::selection::run`), the screen's best, the finalists and the chosen
/// match printed.
#[allow(clippy::too_many_arguments)]
fn select(
    a: &MatchArgs,
    coating: &Coating,
    text: &str,
    target: &gonio_instrument::multiangle_target::Target,
    gloss: &[gonio_formulation::target::GlossTarget],
    varied: &[gonio_formulation::coating_sensitivity::Varied],
    candidates: &[&gonio_coating::pigment_library::LibraryPigment],
    n: usize,
    settings: &gonio_formulation::matching::Settings,
) -> Result<()> {
    use gonio_formulation::selection;
    eprintln!(
        "{}: selecting up to {n} of {} library pigments for {} (objective {}, {} finalists)",
        a.coating.display(),
        candidates.len(),
        a.target.display(),
        settings.objective,
        a.finalists
    );
    let s = selection::run(
        coating,
        target,
        gloss,
        varied,
        candidates,
        n,
        a.finalists,
        settings,
        &mut |line| eprintln!("{line}"),
        &gonio_io::Cancel::default(),
    )
    .context("--select")?;
    let fitted = s
        .fitted_description(text)
        .with_context(|| a.coating.display().to_string())?;
    write_fitted(&a.output, &fitted)?;
    if a.json {
        return print_json(a, s.to_json(target, a.shown));
    }
    let unit = match settings.objective {
        gonio_formulation::matching::Objective::De00 => "mean ΔE00",
        gonio_formulation::matching::Objective::Spectral => "rms ΔR",
    };
    println!(
        "{} combinations of up to {n} of {} pigments screened ({unit} at the fitted \
         concentrations, the other constituents at the start's); the best {}:",
        s.screen.tried.len(),
        s.screen.candidates.len(),
        s.screen.tried.len().min(10)
    );
    for t in s.screen.tried.iter().take(10) {
        println!("  {}", selection::describe(t));
    }
    let mean = |d: &[f64]| d.iter().sum::<f64>() / d.len() as f64;
    println!("finalists (full match; mean ΔE00, then ΔE00 per geometry):");
    for (k, f) in s.finalists.iter().enumerate() {
        let de = &f.result.fitted.de00;
        println!(
            "{} {}: {unit} {:.4}, mean ΔE00 {:.2} [{}]",
            if k == s.best { "*" } else { " " },
            f.screened.pigments.join(" + "),
            f.result.fitted.objective,
            mean(de),
            f.result
                .geometries
                .iter()
                .zip(de)
                .map(|(g, d)| format!("{g} {d:.2}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    println!(
        "chosen: {} ({} matched to {})",
        s.chosen().screened.pigments.join(" + "),
        a.coating.display(),
        a.target.display()
    );
    print_match(&s.chosen().result, a.gloss_weight);
    println!(
        "{:.1} s in all (screen {:.1} s); wrote {}",
        s.seconds,
        s.screen.seconds,
        a.output.display()
    );
    Ok(())
}

/// A match's table: the constituents with their uncertainties, ΔE00 per geometry, gloss and
/// the objective.
fn print_match(m: &gonio_formulation::matching::Match, gloss_weight: f64) {
    use gonio_formulation::matching::Objective;
    let varied = &m.varied;
    let sigma = |i: usize| m.sigma.as_ref().map(|s| s[i]);
    let mean = |d: &[f64]| d.iter().sum::<f64>() / d.len() as f64;
    println!(
        "{:>22} {:>10} {:>10} {:>10}   bounds",
        "constituent", "start", "fitted", "± 1 sd"
    );
    for (i, v) in varied.iter().enumerate() {
        println!(
            "{:>22} {:>10.4} {:>10.4} {:>10}   {}–{}{}",
            v.name,
            m.start.values[i],
            m.fitted.values[i],
            sigma(i).map_or("—".into(), |s| format!("{s:.2e}")),
            v.lo,
            v.hi,
            if m.at_bound(i) { " (at a bound)" } else { "" }
        );
    }
    println!("{:>9} {:>10} {:>10}", "geometry", "ΔE00 start", "fitted");
    for (k, g) in m.geometries.iter().enumerate() {
        println!(
            "{:>9} {:>10.2} {:>10.2}",
            g.to_string(),
            m.start.de00[k],
            m.fitted.de00[k]
        );
    }
    println!(
        "{:>9} {:>10.2} {:>10.2}",
        "mean",
        mean(&m.start.de00),
        mean(&m.fitted.de00)
    );
    let targets = |angle: u32| {
        m.gloss_targets
            .iter()
            .find(|t| t.angle == angle)
            .map_or(String::new(), |t| format!(" (target {:.1})", t.gu))
    };
    for (name, g) in [("start", &m.start.gloss), ("fitted", &m.fitted.gloss)] {
        println!(
            "gloss, {name}: 20° {:.1}, 60° {:.1}, 85° {:.1} GU; haze {:.1} HU; DOI {:.1}",
            g.gu20, g.gu60, g.gu85, g.haze, g.doi
        );
    }
    if !m.gloss_targets.is_empty() {
        println!("target gloss:{}{}{}", targets(20), targets(60), targets(85));
    }
    match m.objective {
        Objective::De00 => println!(
            "objective (mean ΔE00 + {} × |ΔGU|): {:.3} → {:.3}; residual sd {:.3} (CIELAB)",
            gloss_weight, m.start.objective, m.fitted.objective, m.residual_sd
        ),
        Objective::Spectral => println!(
            "objective (rms ΔR): {:.5} → {:.5}; residual sd {:.5} (reflectance factor)",
            m.start.objective, m.fitted.objective, m.residual_sd
        ),
    }
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
    let geometries = multiangle::standard(&a.standard).context("--standard")?;
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
    let file = a.coating.display().to_string();
    let json = coating_study_output::json(&file, &a.vary, &label, &rows);
    if let Some(dir) = &a.output {
        coating_study_output::write(dir, &json, &rows, &label, geometries)
            .with_context(|| dir.display().to_string())?;
        if !a.no_pictures {
            let source = a.coating.display().to_string();
            for r in &rows {
                let variant = constituent.apply(&coating, r.value)?;
                let name = format!("panel-{}", r.value);
                let panel = panel::table(&variant, &source, dir, &name)
                    .with_context(|| format!("{source}: the picture at {label} {}", r.value))?;
                let scene = panel::scene(dir, &name, &[panel])?;
                let (png, stats) = panel::render(&scene)?;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `--bands`' default, as the help shows it, is the libraries' default bands.
    #[test]
    fn default_bands_option_is_the_libraries_default() {
        assert_eq!(bands(DEFAULT_BANDS).unwrap(), default_bands());
    }
}
