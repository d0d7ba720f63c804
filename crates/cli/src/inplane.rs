//! `gonio inplane`: in-plane BRDF curves of a surface, as a goniometer sweeping the plane of
//! incidence would measure them, by one or more methods. Each method yields a list of
//! [`InplaneCurve`]s; the curves of all methods are written to one CSV (and optionally plotted
//! and printed as JSON). Adding a method is adding a [`Method`] variant and its branch in
//! [`run`].

use crate::plot::{self, LinePlot, Series};
use anyhow::{Context, Result, bail, ensure};
use clap::{Args, ValueEnum};
use gonio_brdf::Ior;
use gonio_scatter::InplaneCurve;
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_surface::normals::NormalMethod;
use indicatif::{ProgressBar, ProgressStyle};
use num_complex::Complex64;
use std::path::{Path, PathBuf};

#[derive(Args)]
pub struct InplaneArgs {
    /// Height map file (X3P, SDF, GSF, Gwyddion ASCII, Zygo .dat, Wyko .opd, Sensofar .plu,
    /// Digital Surf .sur, Alicona .al3d); heights and spacings are read in metres from the file.
    surface: Option<PathBuf>,
    /// Methods, comma-separated. ray: geometric optics on the height map's facets.
    #[arg(long, value_delimiter = ',', default_value = "ray")]
    method: Vec<Method>,
    /// Incidence angles in degrees from the surface normal, comma-separated (e.g. 20,45,60,70).
    #[arg(long, value_delimiter = ',', required = true)]
    incidence_deg: Vec<f64>,
    /// Signed scattering angles in degrees, START:STOP:STEP (both ends included) or a
    /// comma-separated list. The specular direction of incidence ti is at +ti; negative angles
    /// lie on the source's side. Write `--scatter-deg=-75:75:1` (with `=`) for negative starts.
    #[arg(long, default_value = "-75:75:1", allow_hyphen_values = true)]
    scatter_deg: String,
    /// Detector half-angle in degrees (the cone each detector collects; NIST STARR: 1.4).
    #[arg(long, default_value_t = 1.4)]
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
    /// Wavelength in nm at which the index applies; written to the wavelength_nm column.
    #[arg(long)]
    wavelength_nm: Option<f64>,
    /// Output CSV: method,wavelength_nm,incidence_deg,scatter_deg,brdf_per_sr,reflectance,
    /// rel_uncertainty (see docs/ray-method.md).
    #[arg(short, long)]
    output: PathBuf,
    /// Also plot the BRDF curves on a log axis into this PNG.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Print the curves as JSON on standard output.
    #[arg(long)]
    json: bool,
}

/// A way to compute in-plane curves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// Geometric optics on the facets of the height map (docs/ray-method.md).
    Ray,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Normals {
    Plane,
    Spline,
}

pub fn run(args: InplaneArgs) -> Result<()> {
    let scatter_deg = parse_angles(&args.scatter_deg)?;
    check_args(&args)?;
    let steps = args.method.len() * args.incidence_deg.len();
    let progress = progress_bar(steps as u64);
    let mut curves: Vec<InplaneCurve> = Vec::new();
    for method in &args.method {
        match method {
            Method::Ray => curves.extend(ray_curves(&args, &scatter_deg, &progress)?),
        }
    }
    progress.finish_and_clear();
    gonio_instrument::curves::write_csv(&args.output, &curves)?;
    if let Some(png) = &args.plot {
        plot_curves(png, &curves)?;
    }
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&curves_json(&curves, &args.output))?
        );
    } else {
        eprintln!("wrote {} curves to {}", curves.len(), args.output.display());
    }
    Ok(())
}

fn check_args(args: &InplaneArgs) -> Result<()> {
    for &ti in &args.incidence_deg {
        ensure!(
            ti.is_finite() && (0.0..90.0).contains(&ti),
            "--incidence-deg {ti}: incidence must be in [0, 90) degrees"
        );
    }
    ensure!(
        args.aperture_deg > 0.0 && args.aperture_deg < 90.0,
        "--aperture-deg {}: the detector half-angle must be in (0, 90) degrees",
        args.aperture_deg
    );
    ensure!(
        args.index.is_finite() && args.index > 0.0,
        "--index {}: the refractive index must be positive",
        args.index
    );
    if let Some(k) = args.index_imag {
        ensure!(
            k.is_finite() && k >= 0.0,
            "--index-imag {k}: kappa must be >= 0"
        );
    }
    if let Some(w) = args.wavelength_nm {
        ensure!(
            w.is_finite() && w > 0.0,
            "--wavelength-nm {w}: must be positive"
        );
    }
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

fn ray_curves(
    args: &InplaneArgs,
    scatter_deg: &[f64],
    progress: &ProgressBar,
) -> Result<Vec<InplaneCurve>> {
    let Some(path) = &args.surface else {
        bail!("--method ray needs a height map: gonio inplane SURFACE --method ray ...");
    };
    progress.set_message(format!("reading {}", path.display()));
    let map = gonio_surface::io::read(path)?;
    let options = RayOptions {
        ior: match args.index_imag {
            Some(k) if k > 0.0 => Ior::Conductor(Complex64::new(args.index, k)),
            _ => Ior::Dielectric(args.index),
        },
        normals: match args.normals {
            Normals::Plane => NormalMethod::Plane,
            Normals::Spline => NormalMethod::Spline,
        },
        shadowing: !args.no_shadowing,
        second_bounce: args.second_bounce,
        azimuths: args.azimuths,
        polarised: false,
    };
    progress.set_message("ray: facet normals");
    let engine = RayEngine::new(&map, options).with_context(|| format!("{}", path.display()))?;
    let mut curves = Vec::new();
    for &ti in &args.incidence_deg {
        progress.set_message(format!("ray: incidence {ti}°"));
        let mut curve = engine.inplane(ti, scatter_deg, args.aperture_deg.to_radians())?;
        curve.wavelength_nm = args.wavelength_nm;
        curves.push(curve);
        progress.inc(1);
    }
    Ok(curves)
}

/// A bar over the (method, incidence) steps on a terminal; hidden when stderr is a pipe.
fn progress_bar(steps: u64) -> ProgressBar {
    let bar = ProgressBar::new(steps);
    if let Ok(style) = ProgressStyle::with_template("{bar:30} {pos}/{len} {msg} {elapsed}") {
        bar.set_style(style);
    }
    bar
}

pub fn plot_curves(path: &Path, curves: &[InplaneCurve]) -> Result<()> {
    let series: Vec<Series> = curves
        .iter()
        .enumerate()
        .map(|(i, c)| Series {
            label: format!("{} {}°", c.method, c.incidence_deg),
            points: c
                .points
                .iter()
                .map(|p| (p.scatter_deg, p.brdf_per_sr))
                .collect(),
            colour: plot::palette(i),
            markers: false,
        })
        .collect();
    let plot = LinePlot {
        title: "In-plane BRDF",
        x_label: "scattering angle (deg)",
        y_label: "BRDF (1/sr)",
        log_y: true,
    };
    plot::line_plot_png(path, (900, 600), &plot, &series)
}

fn curves_json(curves: &[InplaneCurve], output: &Path) -> serde_json::Value {
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
    serde_json::json!({ "output": output.display().to_string(), "curves": curves })
}
