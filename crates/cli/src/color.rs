//! `gonio color`: colorimetry of spectra. `gonio color xyz` reads a reflectance spectrum and
//! prints its CIE XYZ, xyY, CIELAB and sRGB under a CIE illuminant.

use anyhow::Result;
use clap::{Args, Subcommand};
use gonio_color::{Colorimetry, Illuminant, Observer, Spectrum};
use serde_json::json;
use std::path::PathBuf;

#[derive(Args)]
pub struct ColorArgs {
    #[command(subcommand)]
    command: ColorCommand,
}

#[derive(Subcommand)]
enum ColorCommand {
    /// Colour of a surface from its spectral reflectance: CIE XYZ (Y = 100 for the perfect
    /// reflecting diffuser), chromaticity xyY, CIELAB (white = the illuminant), linear and encoded
    /// sRGB in [0, 1], white-balanced by a Bradford adaptation from the illuminant's white to D65.
    Xyz(XyzArgs),
}

#[derive(Args)]
struct XyzArgs {
    /// Spectral reflectance (0–1): CSV with the header `wavelength_nm,value` and one sample per
    /// line, wavelengths in nm, increasing. Outside its range the end values are held (CIE 15).
    #[arg(long, value_name = "FILE.csv")]
    spectrum: PathBuf,
    /// CIE standard illuminant lighting the surface: D65 (daylight) or A (tungsten).
    #[arg(long, default_value = "D65", value_parser = parse_illuminant)]
    illuminant: Illuminant,
    /// CIE standard observer by field size in degrees: 2 (CIE 1931) or 10 (CIE 1964).
    #[arg(long, value_name = "DEG", default_value = "2", value_parser = parse_observer)]
    observer: Observer,
    /// Print the result as JSON.
    #[arg(long)]
    json: bool,
}

pub(crate) fn parse_illuminant(name: &str) -> Result<Illuminant, String> {
    Illuminant::from_name(name).ok_or_else(|| format!("unknown illuminant `{name}`; use D65 or A"))
}

pub(crate) fn parse_observer(deg: &str) -> Result<Observer, String> {
    deg.trim()
        .parse()
        .ok()
        .and_then(Observer::from_field_deg)
        .ok_or_else(|| format!("unknown observer `{deg}`; use 2 (CIE 1931) or 10 (CIE 1964)"))
}

pub fn run(args: ColorArgs) -> Result<()> {
    match args.command {
        ColorCommand::Xyz(args) => xyz(args),
    }
}

fn xyz(args: XyzArgs) -> Result<()> {
    let spectrum = Spectrum::read_csv(&args.spectrum)?;
    let c = Colorimetry::of_reflectance(&spectrum, args.illuminant, args.observer);
    let (lo, hi) = spectrum.range_nm();
    let rgb = c.linear_srgb;
    if args.json {
        let out = json!({
            "spectrum_file": args.spectrum.display().to_string(),
            "spectrum_samples": spectrum.len(),
            "spectrum_range_nm": [lo, hi],
            "illuminant": c.illuminant.name(),
            "observer_deg": c.observer.field_deg(),
            "xyz_scale": "Y = 100 for the perfect reflecting diffuser",
            "xyz": { "x": c.xyz.x, "y": c.xyz.y, "z": c.xyz.z },
            "chromaticity": c.xyy.map(|v| json!({ "x": v.x, "y": v.y })),
            "white_xyz": { "x": c.white.x, "y": c.white.y, "z": c.white.z },
            "cielab": { "l_star": c.lab.l, "a_star": c.lab.a, "b_star": c.lab.b },
            "chroma_ab": c.lab.chroma(),
            "hue_ab_deg": c.lab.hue_deg(),
            "srgb_white_balance": "Bradford, illuminant white to sRGB white (D65)",
            "linear_srgb": { "r": rgb.r, "g": rgb.g, "b": rgb.b },
            "srgb_in_gamut": rgb.in_gamut(),
            "srgb_encoded_clipped": { "r": c.srgb.r, "g": c.srgb.g, "b": c.srgb.b },
            "srgb_8bit": c.srgb.to_u8(),
            "srgb_hex": c.srgb.to_hex(),
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    println!(
        "spectrum     {} ({} samples, {lo}–{hi} nm)",
        args.spectrum.display(),
        spectrum.len()
    );
    println!(
        "viewing      illuminant {}, {} observer; Y = 100 for the perfect reflecting diffuser",
        c.illuminant, c.observer
    );
    println!(
        "XYZ          {:.4}  {:.4}  {:.4}",
        c.xyz.x, c.xyz.y, c.xyz.z
    );
    match c.xyy {
        Some(v) => println!("xyY          {:.5}  {:.5}  {:.4}", v.x, v.y, v.big_y),
        None => println!("xyY          (black: chromaticity undefined)"),
    }
    println!(
        "CIELAB       L* {:.3}  a* {:.3}  b* {:.3}  (C*ab {:.3}, h_ab {:.2}°; white XYZ {:.3} {:.3} {:.3})",
        c.lab.l,
        c.lab.a,
        c.lab.b,
        c.lab.chroma(),
        c.lab.hue_deg(),
        c.white.x,
        c.white.y,
        c.white.z
    );
    println!(
        "linear sRGB  {:.4}  {:.4}  {:.4}  (white-balanced: illuminant white -> D65, Bradford)",
        rgb.r, rgb.g, rgb.b
    );
    let gamut = if rgb.in_gamut() {
        ""
    } else {
        " (outside the sRGB gamut: clipped)"
    };
    println!(
        "sRGB         {:.4}  {:.4}  {:.4}  {}{gamut}",
        c.srgb.r,
        c.srgb.g,
        c.srgb.b,
        c.srgb.to_hex()
    );
    if lo > 380.0 || hi < 780.0 {
        println!(
            "note         the spectrum covers only {lo}–{hi} nm; its end values are held beyond that"
        );
    }
    Ok(())
}
