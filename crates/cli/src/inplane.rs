//! `gonio inplane`: in-plane BRDF curves of a surface, as a goniometer sweeping the plane of
//! incidence would measure them, by one or more methods. The flags become an
//! [`InplaneRequest`] that [`gonio_instrument::inplane::compute`] answers (the Python package
//! asks the same); the curves of all methods are written to one CSV (and optionally plotted and
//! printed as JSON).

use anyhow::{Context, Result, bail, ensure};
use clap::{Args, ValueEnum};
use gonio_brdf::Ior;
use gonio_instrument::inplane::{self, InplaneRequest};
use gonio_report::plots::plot_curves;
use gonio_scatter::InplaneCurve;
use gonio_scatter::analytic::AnalyticModel;
use gonio_scatter::geometry::{STARR_APERTURE_DEG, STARR_INCIDENCES_DEG};
use gonio_scatter::ray::RayOptions;
use gonio_surface::normals::NormalMethod;
use num_complex::Complex64;
use std::io::Write;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct InplaneArgs {
    /// Height map file (X3P, SDF, GSF, Gwyddion ASCII, Zygo .dat, Wyko .opd, Sensofar .plu,
    /// Digital Surf .sur, Alicona .al3d); heights and spacings are read in metres from the file.
    /// Leave it out to compute only the analytic --model curves.
    surface: Option<PathBuf>,
    /// Methods, comma-separated. ray: geometric optics on the height map's facets; kirchhoff:
    /// the scalar Kirchhoff integral (wave optics, needs --wavelength-nm; docs/kirchhoff.md).
    #[arg(long, value_delimiter = ',', default_value = "ray")]
    method: Vec<Method>,
    /// Incidence angles in degrees from the surface normal, comma-separated (default: the NIST
    /// STARR geometry, 20,45,60,70).
    #[arg(long, value_delimiter = ',', default_value = crate::list_default(&STARR_INCIDENCES_DEG))]
    incidence_deg: Vec<f64>,
    /// Signed scattering angles in degrees, START:STOP:STEP (both ends included) or a
    /// comma-separated list. The specular direction of incidence ti is at +ti; negative angles
    /// lie on the source's side. Write `--scatter-deg=-75:75:1` (with `=`) for negative starts.
    #[arg(long, default_value = "-75:75:1", allow_hyphen_values = true)]
    scatter_deg: String,
    /// Detector half-angle in degrees (the cone each detector collects; NIST STARR: 1.4).
    #[arg(long, default_value_t = STARR_APERTURE_DEG)]
    aperture_deg: f64,
    /// Refractive index (real part) of the material under the surface.
    #[arg(long, default_value_t = 1.55)]
    index: f64,
    /// Extinction coefficient kappa (imaginary part of the index, n + i kappa) for metals.
    #[arg(long)]
    index_imag: Option<f64>,
    /// Ray method: ignore shadowing and masking by the height field (the original method).
    #[arg(long)]
    no_shadowing: bool,
    /// Ray method: follow rays that meet the surface again through one more reflection.
    #[arg(long)]
    second_bounce: bool,
    /// Ray method: facet normals from the least-squares plane through each point and its 8
    /// neighbours (plane) or from the bicubic spline through the heights (spline).
    #[arg(long, value_enum, default_value_t = Normals::Plane)]
    normals: Normals,
    /// Ray method: average over this many azimuths of incidence (isotropic surfaces only; the
    /// source and detectors turn together about the normal).
    #[arg(long, default_value_t = 1)]
    azimuths: usize,
    /// Wavelengths in nm, comma-separated (e.g. 500,550,600): one Kirchhoff or wave-model curve
    /// per wavelength and incidence. The ray method does not depend on it; a single value is
    /// written to its wavelength_nm column.
    #[arg(long, value_delimiter = ',')]
    wavelength_nm: Vec<f64>,
    /// Analytic models of a Gaussian random surface to add, comma-separated: beckmann
    /// (Beckmann-Spizzichino series with the coherent specular term), geometric (its
    /// geometric-optics limit), microfacet (Beckmann facets with Smith masking), smooth
    /// (first-order small-roughness limit). Needs --sq-nm and --corr-um; no SURFACE needed.
    #[arg(long, value_delimiter = ',')]
    model: Vec<Model>,
    /// Model: rms height Sq of the Gaussian surface, nm.
    #[arg(long)]
    sq_nm: Option<f64>,
    /// Model: correlation length T of its Gaussian autocorrelation exp(-r²/T²), µm.
    #[arg(long)]
    corr_um: Option<f64>,
    /// Kirchhoff: diameter of the illuminated spot in µm (default: the largest circle that fits
    /// the map). A detector of half-angle alpha averages about (alpha·D/λ)² speckle grains.
    #[arg(long)]
    spot_um: Option<f64>,
    /// Kirchhoff: average over this many non-overlapping spots of --spot-um (speckle averaging).
    #[arg(long, default_value_t = 1)]
    spots: usize,
    /// Output CSV: method,wavelength_nm,incidence_deg,scatter_deg,brdf_per_sr,reflectance,
    /// rel_uncertainty (see docs/ray-method.md). Without it the CSV goes to standard output, or,
    /// with --json, only the JSON does.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Also plot the BRDF curves on a log axis into this PNG.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Print the curves as JSON on standard output, with the warnings (as `warnings`).
    #[arg(long)]
    json: bool,
}

/// A way to compute in-plane curves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// Geometric optics on the facets of the height map (docs/ray-method.md).
    Ray,
    /// Scalar Kirchhoff integral over the height map (docs/kirchhoff.md).
    Kirchhoff,
}

/// An analytic model of a Gaussian random surface (docs/kirchhoff.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Model {
    Beckmann,
    Geometric,
    Microfacet,
    Smooth,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Normals {
    Plane,
    Spline,
}

pub fn run(args: InplaneArgs) -> Result<()> {
    let scatter_deg = parse_angles(&args.scatter_deg)?;
    check_args(&args)?;
    let request = request(&args, scatter_deg);
    let map = match &args.surface {
        Some(path) => Some(crate::surface::read(path)?),
        None if args.model.is_empty() => bail!(
            "give a height map (gonio inplane SURFACE --method ray ...) or analytic models \
             (--model beckmann --sq-nm 100 --corr-um 5 ...)"
        ),
        None => None,
    };
    let progress = crate::progress::bar(request.steps());
    let computed = inplane::compute(map.as_ref(), &request, &crate::progress::ticking(&progress))
        .with_context(|| match &args.surface {
        Some(path) => path.display().to_string(),
        None => "analytic models".to_string(),
    })?;
    let (curves, warnings) = (computed.curves, computed.warnings);
    progress.finish_and_clear();
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    match &args.output {
        Some(path) => gonio_instrument::curves::write_csv(path, &curves)?,
        None if !args.json => {
            let mut out = std::io::BufWriter::new(std::io::stdout().lock());
            gonio_instrument::curves::write_csv_to(&mut out, &curves)?;
            out.flush()?;
        }
        None => {}
    }
    if let Some(png) = &args.plot {
        plot_curves(png, &curves)?;
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&curves_json(&curves, args.output.as_deref(), &warnings))?
        );
    } else if let Some(path) = &args.output {
        eprintln!(
            "wrote {} to {}",
            gonio_report::units::count(curves.len(), "curve"),
            path.display()
        );
    }
    Ok(())
}

/// The checks of the goniometer flags every in-plane command shares: `--incidence-deg`,
/// `--aperture-deg` and `--index`.
pub fn check_geometry(incidence_deg: &[f64], aperture_deg: f64, index: f64) -> Result<()> {
    for &ti in incidence_deg {
        ensure!(
            ti.is_finite() && (0.0..90.0).contains(&ti),
            "--incidence-deg {ti}: incidence must be in [0, 90) degrees"
        );
    }
    ensure!(
        aperture_deg > 0.0 && aperture_deg < 90.0,
        "--aperture-deg {aperture_deg}: the detector half-angle must be in (0, 90) degrees"
    );
    ensure!(
        index.is_finite() && index > 0.0,
        "--index {index}: the refractive index must be positive"
    );
    Ok(())
}

fn check_args(args: &InplaneArgs) -> Result<()> {
    check_geometry(&args.incidence_deg, args.aperture_deg, args.index)?;
    if let Some(k) = args.index_imag {
        ensure!(
            k.is_finite() && k >= 0.0,
            "--index-imag {k}: kappa must be >= 0"
        );
    }
    for &w in &args.wavelength_nm {
        ensure!(
            w.is_finite() && w > 0.0,
            "--wavelength-nm {w}: must be positive"
        );
    }
    for (flag, v) in [
        ("--sq-nm", args.sq_nm),
        ("--corr-um", args.corr_um),
        ("--spot-um", args.spot_um),
    ] {
        if let Some(v) = v {
            ensure!(v.is_finite() && v > 0.0, "{flag} {v}: must be positive");
        }
    }
    ensure!(args.spots >= 1, "--spots must be at least 1");
    ensure!(args.azimuths >= 1, "--azimuths must be at least 1");
    ensure!(
        !(args.second_bounce && args.no_shadowing),
        "--second-bounce needs shadowing and masking: drop --no-shadowing"
    );
    Ok(())
}

/// Angles in degrees from `START:STOP:STEP` (inclusive) or a comma-separated list.
fn parse_angles(spec: &str) -> Result<Vec<f64>> {
    let number = |s: &str| -> Result<f64> {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .with_context(|| format!("--scatter-deg '{spec}': '{s}' is not a number"))
    };
    let angles = if spec.contains(':') {
        let parts: Vec<&str> = spec.split(':').collect();
        let [start, stop, step] = parts.as_slice() else {
            bail!("--scatter-deg '{spec}': write START:STOP:STEP, e.g. -75:75:1");
        };
        let (start, stop, step) = (number(start)?, number(stop)?, number(step)?);
        ensure!(
            step > 0.0 && stop >= start,
            "--scatter-deg '{spec}': need STEP > 0 and STOP >= START"
        );
        let n = ((stop - start) / step + 1e-9).floor() as usize + 1;
        ensure!(
            n <= 1_000_000,
            "--scatter-deg '{spec}': {n} angles is too many"
        );
        (0..n).map(|i| start + i as f64 * step).collect()
    } else {
        spec.split(',').map(number).collect::<Result<Vec<f64>>>()?
    };
    for &a in &angles {
        ensure!(
            a.abs() < 90.0,
            "--scatter-deg '{spec}': angle {a} is not above the surface (|angle| < 90)"
        );
    }
    Ok(angles)
}

/// The library's request from the command line.
fn request(args: &InplaneArgs, scatter_deg: Vec<f64>) -> InplaneRequest {
    InplaneRequest {
        methods: args
            .method
            .iter()
            .map(|m| match m {
                Method::Ray => inplane::Method::Ray,
                Method::Kirchhoff => inplane::Method::Kirchhoff,
            })
            .collect(),
        incidence_deg: args.incidence_deg.clone(),
        scatter_deg,
        aperture_deg: args.aperture_deg,
        ior: match args.index_imag {
            Some(k) if k > 0.0 => Ior::Conductor(Complex64::new(args.index, k)),
            _ => Ior::Dielectric(args.index),
        },
        wavelength_nm: args.wavelength_nm.clone(),
        ray: RayOptions {
            normals: match args.normals {
                Normals::Plane => NormalMethod::Plane,
                Normals::Spline => NormalMethod::Spline,
            },
            shadowing: !args.no_shadowing,
            second_bounce: args.second_bounce,
            azimuths: args.azimuths,
            ..RayOptions::default()
        },
        spot_um: args.spot_um,
        spots: args.spots,
        models: args
            .model
            .iter()
            .map(|m| match m {
                Model::Beckmann => AnalyticModel::Beckmann,
                Model::Geometric => AnalyticModel::Geometric,
                Model::Microfacet => AnalyticModel::Microfacet,
                Model::Smooth => AnalyticModel::Smooth,
            })
            .collect(),
        sq_nm: args.sq_nm,
        corr_um: args.corr_um,
    }
}

fn curves_json(
    curves: &[InplaneCurve],
    output: Option<&Path>,
    warnings: &[String],
) -> serde_json::Value {
    let curves: Vec<serde_json::Value> = curves
        .iter()
        .map(|c| {
            serde_json::json!({
                "method": c.method,
                "wavelength_nm": c.wavelength_nm,
                "incidence_deg": c.incidence_deg,
                "points": c.points.iter().map(|p| serde_json::json!({
                    "scatter_deg": p.scatter_deg,
                    "brdf_per_sr": p.brdf_per_sr,
                    "reflectance": p.reflectance,
                    "rel_uncertainty": p.rel_uncertainty.filter(|u| u.is_finite()),
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    serde_json::json!({
        "output": output.map(|p| p.display().to_string()),
        "curves": curves,
        "warnings": warnings,
    })
}
