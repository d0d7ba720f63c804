//! `gonio compare`: measured against computed in-plane curves, per incidence: RMS difference of
//! log reflectance, peak position, height and FWHM of both, and a plot on a log axis.

use anyhow::{Context, Result, bail};
use clap::Args;
use gonio_instrument::compare::{Comparison, compare};
use gonio_instrument::curves::read_csv;
use gonio_report::plots::plot_pairs;
use gonio_scatter::InplaneCurve;
use gonio_scatter::geometry::{STARR_APERTURE_DEG, cone_solid_angle};
use std::path::PathBuf;

#[derive(Args)]
pub struct CompareArgs {
    /// Measured curves: CSV with the columns `gonio inplane` writes, or simply
    /// `incidence_deg,scatter_deg,reflectance`.
    measured: PathBuf,
    /// Computed curves (same layouts).
    computed: PathBuf,
    /// Use only the computed curves of this method (e.g. ray, kirchhoff, beckmann).
    #[arg(long)]
    method: Option<String>,
    /// Use only the computed curves at this wavelength (nm).
    #[arg(long)]
    wavelength_nm: Option<f64>,
    /// Detector half-angle in degrees, to derive the BRDF of files that give only reflectance.
    #[arg(long, default_value_t = STARR_APERTURE_DEG)]
    aperture_deg: f64,
    /// Plot both sets of curves on a log axis into this PNG.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Print the comparison as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: CompareArgs) -> Result<()> {
    let omega = Some(cone_solid_angle(args.aperture_deg.to_radians()));
    let measured = read_csv(&args.measured, omega)?;
    let computed: Vec<InplaneCurve> = read_csv(&args.computed, omega)?
        .into_iter()
        .filter(|c| args.method.as_ref().is_none_or(|m| &c.method == m))
        .filter(|c| {
            args.wavelength_nm
                .is_none_or(|w| c.wavelength_nm.is_some_and(|cw| (cw - w).abs() < 1e-9))
        })
        .collect();
    let mut pairs = Vec::new();
    for m in &measured {
        let matches: Vec<&InplaneCurve> = computed
            .iter()
            .filter(|c| (c.incidence_deg - m.incidence_deg).abs() < 1e-9)
            .filter(|c| match (m.wavelength_nm, c.wavelength_nm) {
                (Some(a), Some(b)) => (a - b).abs() < 1e-9,
                _ => true,
            })
            .collect();
        match matches.as_slice() {
            [] => continue,
            [c] => pairs.push((m, *c)),
            _ => bail!(
                "{}: several curves at incidence {}° (methods/wavelengths); choose one with --method and --wavelength-nm",
                args.computed.display(),
                m.incidence_deg
            ),
        }
    }
    if pairs.is_empty() {
        bail!(
            "no incidence angle is common to {} and {}",
            args.measured.display(),
            args.computed.display()
        );
    }
    let comparisons: Vec<Comparison> = pairs
        .iter()
        .map(|(m, c)| {
            compare(m, c).with_context(|| {
                format!(
                    "incidence {}°: a curve has no positive reflectance",
                    m.incidence_deg
                )
            })
        })
        .collect::<Result<_>>()?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&comparisons)?);
    } else {
        print_table(&comparisons, "measured", "computed");
    }
    if let Some(out) = &args.output {
        plot_pairs(
            out,
            "In-plane reflectance: measured (dots) and computed (lines)",
            &pairs,
            |c, _| format!("{} {}°", c.method, c.incidence_deg),
        )?;
        eprintln!("wrote {}", out.display());
    }
    Ok(())
}

/// The comparisons as a table, curve `a` (called `left`) on the left, `b` on the right.
pub fn print_table(rows: &[Comparison], left: &str, right: &str) {
    println!(
        "{:>9} {:>10} {:>6} | {:>8} {:>11} {:>8} | {:>8} {:>11} {:>8}",
        "incid_deg",
        "rms_log10",
        "points",
        "peak_deg",
        "peak_rho",
        "fwhm_deg",
        "peak_deg",
        "peak_rho",
        "fwhm_deg"
    );
    let fwhm = |v: Option<f64>| v.map_or("-".to_string(), |w| format!("{w:.2}"));
    for c in rows {
        println!(
            "{:>9} {:>10.4} {:>6} | {:>8.1} {:>11.4e} {:>8} | {:>8.1} {:>11.4e} {:>8}",
            c.incidence_deg,
            c.rms_log10,
            c.common_points,
            c.peak_a.position_deg,
            c.peak_a.reflectance,
            fwhm(c.peak_a.fwhm_deg),
            c.peak_b.position_deg,
            c.peak_b.reflectance,
            fwhm(c.peak_b.fwhm_deg),
        );
    }
    println!("(left: {left}, right: {right})");
}
