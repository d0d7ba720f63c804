//! `gonio surface gen`: synthesise a periodic Gaussian random surface, from an autocorrelation
//! (`gonio_surface::synth`) or a power spectral density (`gonio_surface::synth_psd`: a power law
//! between two wavelengths, by default an automotive clear coat's orange peel, or a measured PSD
//! table). docs/surface.md "Synthesis".

use crate::surface::{busy, write};
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use gonio_surface::synth::{Acf, GaussianSurface};
use gonio_surface::synth_psd::{self, PsdSurface, RadialPsd, Spectrum, Target};
use gonio_surface::{HeightMap, ops, stats};
use std::path::PathBuf;

use gonio_report::orange_peel::{
    DEFAULT_EXPONENT, DEFAULT_LONG_MM, DEFAULT_SHORT_MM, DEFAULT_SLOPE_MRAD,
};

#[derive(Clone, Copy, ValueEnum)]
enum AcfArg {
    /// sigma² exp(-r²/T²)
    Gaussian,
    /// sigma² exp(-r/T)
    Exponential,
}

/// The arguments of `gonio surface gen` (the kinds of surface: [`crate::surface::SurfaceCommand`]).
#[derive(Args)]
pub struct GenArgs {
    /// rms height Sq in nanometres, exact after plane levelling. Required with --corr-um.
    #[arg(long)]
    sq_nm: Option<f64>,
    /// rms profile slope along x in mrad after levelling (forward differences, exact), the
    /// quantity `surface waviness` band-passes. PSD surfaces only; the power law's default is 1
    /// mrad when --sq-nm is not given either.
    #[arg(long, conflicts_with_all = ["sq_nm", "corr_um"])]
    slope_mrad: Option<f64>,
    /// Correlation length T in micrometres: an ACF surface (Gaussian or exponential).
    #[arg(long, requires = "sq_nm", conflicts_with_all = ["psd_exponent", "long_mm", "short_mm", "psd"])]
    corr_um: Option<f64>,
    /// Shape of the autocorrelation function (with --corr-um) [default: gaussian].
    #[arg(long, value_enum, requires = "corr_um")]
    acf: Option<AcfArg>,
    /// Exponent n of the power-law areal PSD C(q) ∝ q^-n (q = 2π/λ) [default: 4].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "psd")]
    psd_exponent: Option<f64>,
    /// Longest wavelength of the power law in mm, at most the map's side [default: 10].
    #[arg(long, conflicts_with = "psd")]
    long_mm: Option<f64>,
    /// Shortest wavelength of the power law in mm, at least two spacings [default: 0.3].
    #[arg(long, conflicts_with = "psd")]
    short_mm: Option<f64>,
    /// A measured radial PSD: a text table, header `wavelength_mm,psd_m4` or
    /// `frequency_per_mm,psd_m4` (the areal isotropic PSD in m⁴, Jacobs et al. 2017), then one
    /// pair a line; `#` comments. Without --sq-nm or --slope-mrad the PSD's own magnitude holds.
    #[arg(long)]
    psd: Option<PathBuf>,
    /// Points along each side (the map is size × size).
    #[arg(long)]
    size: usize,
    /// Spacing between points in micrometres (both axes).
    #[arg(long)]
    dx_um: f64,
    /// Seed of the random numbers (same seed, same map on any machine).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output file, .x3p or .gsf.
    #[arg(short, long)]
    output: PathBuf,
}

/// Run `gonio surface gen`.
pub fn run(a: &GenArgs) -> Result<()> {
    let (dx, n) = (a.dx_um * 1e-6, a.size);
    let (map, what) = if let Some(corr_um) = a.corr_um {
        let sq_nm = a.sq_nm.context("--corr-um needs --sq-nm")?;
        let acf = match a.acf.unwrap_or(AcfArg::Gaussian) {
            AcfArg::Gaussian => Acf::Gaussian,
            AcfArg::Exponential => Acf::Exponential,
        };
        let request = GaussianSurface {
            sq: sq_nm * 1e-9,
            corr_length: corr_um * 1e-6,
            acf,
            nx: n,
            ny: n,
            dx,
            dy: dx,
            seed: a.seed,
        };
        let map = busy("synthesising", || request.generate()).context(
            "cannot synthesise the surface (check --sq-nm, --corr-um, --dx-um > 0 and --size >= 2)",
        )?;
        let name = format!("{acf:?}").to_lowercase();
        (map, format!("{name} ACF, T {corr_um} µm"))
    } else {
        let (spectrum, what) = match &a.psd {
            Some(path) => {
                let table = RadialPsd::read(path)?;
                let (s, l) = table.wavelengths();
                (
                    Spectrum::Radial(table),
                    format!(
                        "PSD of {} ({:.4}-{:.4} mm)",
                        path.display(),
                        s * 1e3,
                        l * 1e3
                    ),
                )
            }
            None => {
                let exponent = a.psd_exponent.unwrap_or(DEFAULT_EXPONENT);
                let long = a.long_mm.unwrap_or(DEFAULT_LONG_MM);
                let short = a.short_mm.unwrap_or(DEFAULT_SHORT_MM);
                (
                    Spectrum::PowerLaw {
                        exponent,
                        long: long * 1e-3,
                        short: short * 1e-3,
                    },
                    format!("PSD q^-{exponent} between {short} and {long} mm"),
                )
            }
        };
        let target = match (a.sq_nm, a.slope_mrad, &spectrum) {
            (Some(sq), _, _) => Target::Sq(sq * 1e-9),
            (None, Some(s), _) => Target::SlopeX(s * 1e-3),
            (None, None, Spectrum::PowerLaw { .. }) => Target::SlopeX(DEFAULT_SLOPE_MRAD * 1e-3),
            (None, None, Spectrum::Radial(_)) => Target::AsGiven,
        };
        let request = PsdSurface {
            spectrum,
            target,
            nx: n,
            ny: n,
            dx,
            dy: dx,
            seed: a.seed,
        };
        let map =
            busy("synthesising", || request.generate()).context("cannot synthesise the surface")?;
        (map, what)
    };
    write(&map, &a.output)?;
    let (sq, slope) = realised(&map)?;
    eprintln!(
        "wrote {}: {n} × {n} points at {} µm ({:.4} mm square), {what}: Sq {:.4} µm, rms slope \
         along x {:.4} mrad",
        a.output.display(),
        a.dx_um,
        n as f64 * a.dx_um * 1e-3,
        sq * 1e6,
        slope * 1e3
    );
    Ok(())
}

/// Sq and the rms slope along x of `map` after levelling.
fn realised(map: &HeightMap) -> Result<(f64, f64)> {
    let sq = stats::height_parameters(&ops::level(map)?).0;
    Ok((sq, synth_psd::rms_slope_x(map)?))
}
