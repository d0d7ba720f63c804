//! `gonio multiangle`: what a multi-angle spectrophotometer (ASTM E2194, ASTM E2539) reads on a
//! spectral BRDF table or on a coating described in TOML (its BRDF evaluated at the geometries,
//! not through a table): CIELAB at each geometry, Alman's flop index, and the differences from
//! a reference geometry by geometry (`gonio_instrument::multiangle`).

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use gonio_color::{Illuminant, Observer};
use gonio_instrument::multiangle::{self, Difference, E2194, E2539, Geometry, MultiangleReading};
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct MultiangleArgs {
    /// A spectral BRDF table (.gbrdf: an imported measurement or a computed table), or a
    /// coating's description (.toml, as `gonio coating`), read at 400, 410, ..., 700 nm.
    table: PathBuf,
    /// The standard's set of geometries: e2194 (45° illumination; aspecular 15, 25, 45, 75,
    /// 110°) or e2539 (adds 45as-15 and 15° illumination at -15, 15, 45, 80°).
    #[arg(long, value_enum, default_value_t = Standard::E2194)]
    standard: Standard,
    /// Read these geometries instead, each as illumination and aspecular angle in degrees,
    /// e.g. `--geometry 45as15,45as-15,15as80`. The aspecular angle is measured from the
    /// specular direction, positive towards the illuminator.
    #[arg(long, value_delimiter = ',', value_parser = parse_geometry)]
    geometry: Vec<Geometry>,
    /// Half-angle of the source's and the receptor's circular apertures, degrees (0: the
    /// nominal directions).
    #[arg(long, default_value_t = 0.0)]
    aperture_deg: f64,
    /// Another spectral table or coating to compare with: prints ΔL*, Δa*, Δb*, ΔC*, ΔH*,
    /// ΔE*ab and ΔE00 (this one minus the reference) at each geometry.
    #[arg(long)]
    reference: Option<PathBuf>,
    /// For a coating (.toml) with a rough top or flakes: random walks per evaluation of its
    /// BRDF (the noise falls as 1/sqrt(samples); 16384 keeps L* within about 0.3).
    #[arg(long, default_value_t = 16384)]
    samples: usize,
    /// CIE illuminant: D65 (daylight) or A (tungsten).
    #[arg(long, default_value = "D65", value_parser = crate::color::parse_illuminant)]
    illuminant: Illuminant,
    /// CIE observer by field size in degrees: 10 (CIE 1964, the standards' choice) or 2.
    #[arg(long, default_value = "10", value_parser = crate::color::parse_observer)]
    observer: Observer,
    /// Also write the reflectance factors (π × BRDF; 1 = the perfect diffuser) to this CSV:
    /// one row per geometry, one column per wavelength.
    #[arg(long, value_name = "FILE.csv")]
    spectra: Option<PathBuf>,
    /// Print the readings as JSON: settings, geometries (name, illumination_deg,
    /// aspecular_deg, viewing_deg, L, a, b, C, h_deg, X, Y, Z), flop_index and differences.
    #[arg(long)]
    json: bool,
}

/// A standard's set of geometries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Standard {
    /// ASTM E2194, metallic flake pigments.
    E2194,
    /// ASTM E2539, interference pigments.
    E2539,
}

pub(crate) fn parse_geometry(s: &str) -> std::result::Result<Geometry, String> {
    Geometry::parse(s).map_err(|e| e.to_string())
}

pub fn run(args: MultiangleArgs) -> Result<()> {
    let geometries: Vec<Geometry> = if args.geometry.is_empty() {
        match args.standard {
            Standard::E2194 => E2194.to_vec(),
            Standard::E2539 => E2539.to_vec(),
        }
    } else {
        args.geometry.clone()
    };
    let settings = multiangle::Settings {
        illuminant: args.illuminant,
        observer: args.observer,
        aperture_deg: args.aperture_deg,
    };
    let read = |path: &Path| -> Result<MultiangleReading> {
        if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        {
            let wavelengths: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
            let coating = gonio_coating::description::read(path, &wavelengths)?;
            let evaluator = coating.evaluator(&wavelengths)?;
            let brdf = |wo, wi, out: &mut [f64]| {
                let mut scratch = gonio_coating::layered::Scratch::default();
                evaluator.eval(wo, wi, args.samples, 1, &mut scratch, out);
            };
            return multiangle::read(&brdf, &wavelengths, &geometries, &settings)
                .with_context(|| path.display().to_string());
        }
        let table = gonio_brdf::gbrdf::read(path)?;
        multiangle::read_table(&table, &geometries, &settings)
            .with_context(|| path.display().to_string())
    };
    let reading = read(&args.table)?;
    let differences = match &args.reference {
        Some(path) => Some(multiangle::differences(&reading, &read(path)?)?),
        None => None,
    };
    if let Some(path) = &args.spectra {
        write_spectra(path, &reading)?;
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&json(&reading, differences.as_deref()))?
        );
    } else {
        print_table(&reading, differences.as_deref(), &args);
    }
    Ok(())
}

fn print_table(
    reading: &MultiangleReading,
    differences: Option<&[Difference]>,
    args: &MultiangleArgs,
) {
    let s = &reading.settings;
    println!(
        "{} under {}, CIE {}° observer; apertures: {}",
        args.table.display(),
        s.illuminant.name(),
        s.observer.field_deg(),
        if s.aperture_deg > 0.0 {
            format!("±{}°", s.aperture_deg)
        } else {
            "points (the nominal directions)".into()
        }
    );
    println!(
        "{:>9} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>7}",
        "geometry", "θi °", "θv °", "L*", "a*", "b*", "C*ab", "hab °"
    );
    for g in &reading.geometries {
        println!(
            "{:>9} {:>7.1} {:>7.1} {:>8.2} {:>8.2} {:>8.2} {:>8.2} {:>7.1}",
            g.geometry.to_string(),
            g.geometry.illumination_deg,
            g.geometry.viewing_deg(),
            g.lab.l,
            g.lab.a,
            g.lab.b,
            g.lab.chroma(),
            g.lab.hue_deg()
        );
    }
    match reading.flop_index() {
        Some(fi) => println!("flop index (Alman, from L* at 45as15, 45as45, 45as110): {fi:.2}"),
        None => println!("flop index: needs 45as15, 45as45 and 45as110"),
    }
    if let (Some(ds), Some(reference)) = (differences, &args.reference) {
        println!(
            "differences from {} (this − reference):",
            reference.display()
        );
        println!(
            "{:>9} {:>7} {:>7} {:>7} {:>7} {:>7} {:>7} {:>7}",
            "geometry", "ΔL*", "Δa*", "Δb*", "ΔC*ab", "ΔH*ab", "ΔE*ab", "ΔE00"
        );
        for d in ds {
            println!(
                "{:>9} {:>7.2} {:>7.2} {:>7.2} {:>7.2} {:>7.2} {:>7.2} {:>7.2}",
                d.geometry.to_string(),
                d.dl,
                d.da,
                d.db,
                d.dc,
                d.dh,
                d.de_ab,
                d.de00
            );
        }
    }
}

fn json(reading: &MultiangleReading, differences: Option<&[Difference]>) -> serde_json::Value {
    let s = &reading.settings;
    let geometries: Vec<_> = reading
        .geometries
        .iter()
        .map(|g| {
            serde_json::json!({
                "name": g.geometry.to_string(),
                "illumination_deg": g.geometry.illumination_deg,
                "aspecular_deg": g.geometry.aspecular_deg,
                "viewing_deg": g.geometry.viewing_deg(),
                "L": g.lab.l, "a": g.lab.a, "b": g.lab.b,
                "C": g.lab.chroma(), "h_deg": g.lab.hue_deg(),
                "X": g.xyz.x, "Y": g.xyz.y, "Z": g.xyz.z,
            })
        })
        .collect();
    let differences = differences.map(|ds| {
        ds.iter()
            .map(|d| {
                serde_json::json!({
                    "name": d.geometry.to_string(),
                    "dL": d.dl, "da": d.da, "db": d.db, "dC": d.dc, "dH": d.dh,
                    "dE_ab": d.de_ab, "dE00": d.de00,
                })
            })
            .collect::<Vec<_>>()
    });
    serde_json::json!({
        "illuminant": s.illuminant.name(),
        "observer_deg": s.observer.field_deg(),
        "aperture_deg": s.aperture_deg,
        "geometries": geometries,
        "flop_index": reading.flop_index(),
        "differences": differences,
    })
}

/// The reflectance factors as CSV: `geometry,illumination_deg,aspecular_deg,R_400nm,...`.
fn write_spectra(path: &Path, reading: &MultiangleReading) -> Result<()> {
    Ok(gonio_report::output::write_atomic(path, |w| {
        write!(w, "geometry,illumination_deg,aspecular_deg")?;
        for wl in &reading.wavelengths_nm {
            write!(w, ",R_{wl}nm")?;
        }
        writeln!(w)?;
        for g in &reading.geometries {
            write!(
                w,
                "{},{},{}",
                g.geometry, g.geometry.illumination_deg, g.geometry.aspecular_deg
            )?;
            for r in &g.reflectance_factor {
                write!(w, ",{r}")?;
            }
            writeln!(w)?;
        }
        Ok(())
    })?)
}
