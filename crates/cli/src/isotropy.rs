//! `gonio isotropy`: is this surface isotropic? The in-plane curves of a height map and of the
//! same map turned about its normal (by 90° exactly, or by any angle), their differences per
//! incidence (RMS of log10 reflectance, peak, FWHM), the rms slopes along and across the plane of
//! incidence of both, a plot and a CSV of the curves.

use crate::inplane::Method;
use anyhow::{Result, ensure};
use clap::Args;
use gonio_instrument::isotropy::{self, IsotropyConfig, Orientation, RotationCheck};
use gonio_report::isotropy_files::{plot_check, write_csv};
use gonio_scatter::Goniometer;
use gonio_scatter::geometry::{STARR_APERTURE_DEG, STARR_INCIDENCES_DEG};
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct IsotropyArgs {
    /// Height map file (any format `gonio surface` reads); heights and spacings in metres.
    surface: PathBuf,
    /// Angles to turn the map by, degrees counter-clockwise (from +x toward +y), comma-separated.
    /// Multiples of 90° are exact (no interpolation, whole map); other angles interpolate with the
    /// bicubic spline and compare both maps over the largest centred square inside the turned
    /// one.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "90",
        allow_hyphen_values = true
    )]
    angle_deg: Vec<f64>,
    /// ray: geometric optics on the map's facets; kirchhoff: the scalar Kirchhoff integral at
    /// --wavelength-nm over the largest spot that fits the map.
    #[arg(long, value_enum, default_value_t = Method::Ray)]
    method: Method,
    /// Wavelength for --method kirchhoff, nm.
    #[arg(long, default_value_t = 550.0)]
    wavelength_nm: f64,
    /// Incidence angles in degrees from the normal, comma-separated (NIST STARR: 20,45,60,70).
    /// Scatter angles are -75..75° in 1° steps.
    #[arg(long, value_delimiter = ',', default_value = crate::list_default(&STARR_INCIDENCES_DEG))]
    incidence_deg: Vec<f64>,
    /// Detector half-angle in degrees.
    #[arg(long, default_value_t = STARR_APERTURE_DEG)]
    aperture_deg: f64,
    /// Refractive index of the coating.
    #[arg(long, default_value_t = 1.55)]
    index: f64,
    /// Plot the reflectance curves of the original (lines) and turned (dots) map on a log axis
    /// into this PNG; with several angles, one PNG per angle named PLOT_rot<angle>.png.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Write the curves to this CSV: rotation_deg,orientation (original|rotated) followed by the
    /// columns of `gonio inplane`.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Print the differences and slopes as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: IsotropyArgs) -> Result<()> {
    check_args(&args)?;
    let map = crate::surface::read(&args.surface)?;
    let config = IsotropyConfig {
        angles_deg: args.angle_deg.clone(),
        ior: args.index,
        // STARR's scattering angles at the incidences and aperture given.
        goniometer: Goniometer {
            incidences: args.incidence_deg.iter().map(|t| t.to_radians()).collect(),
            half_angle: args.aperture_deg.to_radians(),
            ..Goniometer::starr()
        },
        method: match args.method {
            Method::Ray => isotropy::Method::Ray,
            Method::Kirchhoff => isotropy::Method::Kirchhoff {
                wavelength: args.wavelength_nm * 1e-9,
            },
        },
    };
    let bar = crate::progress::bar(config.angles_deg.len() as u64);
    let checks = isotropy::check(&map, &config, &crate::progress::reporting(&bar));
    bar.finish_and_clear();
    let checks = checks.map_err(|e| anyhow::anyhow!("{}: {e}", args.surface.display()))?;
    if let Some(csv) = &args.csv {
        write_csv(csv, &checks)?;
    }
    if let Some(png) = &args.output {
        for c in &checks {
            let path = if checks.len() == 1 {
                png.clone()
            } else {
                plot_path(png, c.angle_deg)
            };
            plot_check(&path, c)?;
            eprintln!("wrote {}", path.display());
        }
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&to_json(&args, &checks))?
        );
    } else {
        print_text(&checks);
    }
    Ok(())
}

fn check_args(args: &IsotropyArgs) -> Result<()> {
    for &a in &args.angle_deg {
        ensure!(a.is_finite(), "--angle-deg {a}: must be a finite angle");
    }
    crate::inplane::check_geometry(&args.incidence_deg, args.aperture_deg, args.index)?;
    ensure!(
        args.wavelength_nm.is_finite() && args.wavelength_nm > 0.0,
        "--wavelength-nm {}: must be positive",
        args.wavelength_nm
    );
    Ok(())
}

/// `plot.png` → `plot_rot45.png` for the turn by 45°.
fn plot_path(png: &Path, angle_deg: f64) -> PathBuf {
    let stem = png
        .file_stem()
        .map_or("isotropy".into(), |s| s.to_string_lossy());
    png.with_file_name(format!("{stem}_rot{angle_deg}.png"))
}

fn orientation_json(o: &Orientation) -> serde_json::Value {
    serde_json::json!({
        "nx": o.nx,
        "ny": o.ny,
        "rms_slope_x": o.rms_slope_x,
        "rms_slope_y": o.rms_slope_y,
        "str": o.str,
    })
}

fn to_json(args: &IsotropyArgs, checks: &[RotationCheck]) -> serde_json::Value {
    let checks: Vec<serde_json::Value> = checks
        .iter()
        .map(|c| {
            serde_json::json!({
                "angle_deg": c.angle_deg,
                "exact": c.exact,
                "original": orientation_json(&c.original),
                "rotated": orientation_json(&c.rotated),
                "comparisons": c.comparisons,
            })
        })
        .collect();
    serde_json::json!({
        "surface": args.surface.display().to_string(),
        "method": match args.method {
            Method::Ray => "ray",
            Method::Kirchhoff => "kirchhoff",
        },
        "wavelength_nm": (args.method == Method::Kirchhoff).then_some(args.wavelength_nm),
        "checks": checks,
    })
}

fn print_text(checks: &[RotationCheck]) {
    for c in checks {
        let (o, r) = (&c.original, &c.rotated);
        println!(
            "turned by {}° ({}; {} × {} points)",
            c.angle_deg,
            if c.exact {
                "exact quarter turns"
            } else {
                "spline rotation, both cropped to the inscribed square"
            },
            r.nx,
            r.ny
        );
        println!(
            "  rms slope along / across the plane of incidence: original {:.4} / {:.4}, \
             turned {:.4} / {:.4}; Str {} / {}",
            o.rms_slope_x,
            o.rms_slope_y,
            r.rms_slope_x,
            r.rms_slope_y,
            o.str.map_or("-".into(), |s| format!("{s:.3}")),
            r.str.map_or("-".into(), |s| format!("{s:.3}")),
        );
        crate::compare::print_table(&c.comparisons, "original", "turned");
    }
}
