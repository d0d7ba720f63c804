//! In-plane curves of a surface by several methods at once: what `gonio inplane` and the Python
//! package's `gonio.inplane` compute, so that both give the same numbers from the same request.
//! A request names the goniometer (incidences, signed scattering angles and detector half-angle,
//! in degrees as the user gave them), the coating's index, the wavelengths, the methods on the
//! height map (the ray method and the scalar Kirchhoff integral) and the analytic models of a
//! Gaussian random surface; the result is the curves of every method in that order, labelled
//! with the user's own angles and wavelengths, and the warnings of the validity checks.

use crate::error::{InstrumentError, Result};
use crate::validity;
use gonio_brdf::Ior;
use gonio_io::Progress;
use gonio_scatter::analytic::{AnalyticModel, GaussianModel};
use gonio_scatter::geometry::label_value;
use gonio_scatter::inplane::AnalyticMethod;
use gonio_scatter::kirchhoff::{Kirchhoff, KirchhoffOptions, Spot, average_curves};
use gonio_scatter::ray::{RayEngine, RayOptions};
use gonio_scatter::{Goniometer, InplaneCurve, InplaneMethod};
use gonio_surface::HeightMap;

/// A scattering method on a height map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Geometric optics on the facets of the map (`docs/ray-method.md`).
    Ray,
    /// The scalar Kirchhoff integral over the map (`docs/kirchhoff.md`); needs wavelengths.
    Kirchhoff,
}

impl Method {
    /// `ray` or `kirchhoff`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Ray => "ray",
            Method::Kirchhoff => "kirchhoff",
        }
    }
}

/// What to compute.
#[derive(Debug, Clone)]
pub struct InplaneRequest {
    /// Methods on the height map, in the order their curves are returned.
    pub methods: Vec<Method>,
    /// Incidence angles from the normal, degrees.
    pub incidence_deg: Vec<f64>,
    /// Signed scattering angles, degrees (specular of incidence θ at +θ).
    pub scatter_deg: Vec<f64>,
    /// Detector half-angle, degrees.
    pub aperture_deg: f64,
    /// The coating's refractive index.
    pub ior: Ior,
    /// Wavelengths, nm: one Kirchhoff or wave-model curve per wavelength and incidence; the ray
    /// method writes a single one into its curves' label and judges its validity at the longest.
    pub wavelength_nm: Vec<f64>,
    /// Options of the ray method (its `ior` is replaced by the request's).
    pub ray: RayOptions,
    /// Kirchhoff: the spot diameter, µm (`None`: the largest circle that fits the map).
    pub spot_um: Option<f64>,
    /// Kirchhoff: how many non-overlapping spots of `spot_um` to average.
    pub spots: usize,
    /// Analytic models of a Gaussian random surface to add after the methods' curves.
    pub models: Vec<AnalyticModel>,
    /// The models' rms height Sq, nm.
    pub sq_nm: Option<f64>,
    /// The models' correlation length T of the autocorrelation exp(−r²/T²), µm.
    pub corr_um: Option<f64>,
}

impl InplaneRequest {
    /// The ray method at the NIST STARR geometry (20, 45, 60, 70°; −75..75° every 1°; 1.4°)
    /// over a coating of index 1.55, without models.
    pub fn starr() -> InplaneRequest {
        InplaneRequest {
            methods: vec![Method::Ray],
            incidence_deg: gonio_scatter::geometry::STARR_INCIDENCES_DEG.to_vec(),
            scatter_deg: (-75..=75).map(f64::from).collect(),
            aperture_deg: gonio_scatter::geometry::STARR_APERTURE_DEG,
            ior: Ior::Dielectric(1.55),
            wavelength_nm: Vec::new(),
            ray: RayOptions::default(),
            spot_um: None,
            spots: 1,
            models: Vec::new(),
            sq_nm: None,
            corr_um: None,
        }
    }

    /// The steps a computation on a height map reports: one per incidence for the ray method,
    /// one per spot, wavelength, incidence and detector for Kirchhoff.
    pub fn steps(&self) -> u64 {
        let incidences = self.incidence_deg.len();
        let per_method = |m: &Method| match m {
            Method::Ray => incidences,
            Method::Kirchhoff => {
                self.spots * self.wavelength_nm.len() * incidences * self.scatter_deg.len()
            }
        };
        self.methods.iter().map(per_method).sum::<usize>() as u64
    }

    /// The request's angles in radians.
    fn goniometer(&self) -> Goniometer {
        Goniometer::from_degrees(&self.incidence_deg, &self.scatter_deg, self.aperture_deg)
    }

    /// Check every value before any work is done.
    fn check(&self) -> Result<()> {
        let bad = |m: String| Err(InstrumentError::Invalid(m));
        if self.incidence_deg.is_empty() || self.scatter_deg.is_empty() {
            return bad("give at least one incidence and one scattering angle".into());
        }
        for &ti in &self.incidence_deg {
            if !(ti.is_finite() && (0.0..90.0).contains(&ti)) {
                return bad(format!("incidence {ti}°: must be in [0, 90) degrees"));
            }
        }
        for &ts in &self.scatter_deg {
            if !(ts.is_finite() && ts.abs() < 90.0) {
                return bad(format!(
                    "scattering angle {ts}°: not above the surface (|angle| < 90°)"
                ));
            }
        }
        if !(self.aperture_deg > 0.0 && self.aperture_deg < 90.0) {
            return bad(format!(
                "detector half-angle {}°: must be in (0, 90) degrees",
                self.aperture_deg
            ));
        }
        for &w in &self.wavelength_nm {
            if !(w.is_finite() && w > 0.0) {
                return bad(format!("wavelength {w} nm: must be positive"));
            }
        }
        for (what, v) in [
            ("rms height Sq (nm)", self.sq_nm),
            ("correlation length (µm)", self.corr_um),
            ("spot diameter (µm)", self.spot_um),
        ] {
            if let Some(v) = v
                && !(v.is_finite() && v > 0.0)
            {
                return bad(format!("{what} {v}: must be positive"));
            }
        }
        if self.spots == 0 {
            return bad("the number of Kirchhoff spots must be at least 1".into());
        }
        if self.ray.azimuths == 0 {
            return bad("the number of azimuths must be at least 1".into());
        }
        if self.ray.second_bounce && !self.ray.shadowing {
            return bad("the second bounce needs shadowing and masking".into());
        }
        Ok(())
    }

    /// The wavelengths in metres, or an error naming what needs them.
    fn wavelengths_m(&self, what: &str) -> Result<Vec<f64>> {
        if self.wavelength_nm.is_empty() {
            return Err(InstrumentError::Invalid(format!(
                "{what} depends on the wavelength: give wavelengths in nm, e.g. 500, 550, 600"
            )));
        }
        Ok(self.wavelength_nm.iter().map(|w| w * 1e-9).collect())
    }
}

/// Curves and the validity warnings.
#[derive(Debug, Clone)]
pub struct InplaneResult {
    /// Every method's curves, then every model's, each method's ordered as the method returns
    /// them (by wavelength, then incidence).
    pub curves: Vec<InplaneCurve>,
    /// Where a method cannot be trusted on this map at these angles (`validity`).
    pub warnings: Vec<String>,
}

/// The curves of `request` on `map` (`None`: the analytic models only). `progress` receives one
/// report per step the methods finish, [`InplaneRequest::steps`] in all.
pub fn compute(
    map: Option<&HeightMap>,
    request: &InplaneRequest,
    progress: &Progress,
) -> Result<InplaneResult> {
    request.check()?;
    let mut warnings = validity::check_index(match request.ior {
        Ior::Dielectric(n) => n,
        Ior::Conductor(n) => n.re,
    })?;
    let gonio = request.goniometer();
    let mut curves = Vec::new();
    if let Some(map) = map {
        for method in &request.methods {
            curves.extend(match method {
                Method::Ray => ray_curves(map, request, &gonio, progress, &mut warnings)?,
                Method::Kirchhoff => {
                    kirchhoff_curves(map, request, &gonio, progress, &mut warnings)?
                }
            });
        }
    } else if request.models.is_empty() {
        return Err(InstrumentError::Invalid(
            "nothing to compute: give a height map for the methods, or models with their Sq and \
             correlation length"
                .into(),
        ));
    }
    curves.extend(model_curves(request, &gonio)?);
    relabel(&mut curves, request, &gonio);
    Ok(InplaneResult { curves, warnings })
}

/// Write the angles and wavelengths exactly as the user gave them (the library works in radians
/// and metres, and 60° → rad → deg is 59.99999999999999): each label the library wrote is
/// matched with the given value it came from.
fn relabel(curves: &mut [InplaneCurve], request: &InplaneRequest, gonio: &Goniometer) {
    let incidences = gonio.incidences_deg();
    let wavelengths: Vec<f64> = request
        .wavelength_nm
        .iter()
        .map(|w| label_value(w * 1e-9 * 1e9))
        .collect();
    for curve in curves {
        if let Some(k) = incidences.iter().position(|&t| t == curve.incidence_deg) {
            curve.incidence_deg = request.incidence_deg[k];
        }
        if let Some(k) = wavelengths
            .iter()
            .position(|&w| Some(w) == curve.wavelength_nm)
        {
            curve.wavelength_nm = Some(request.wavelength_nm[k]);
        }
        for (p, &ts) in curve.points.iter_mut().zip(&request.scatter_deg) {
            p.scatter_deg = ts;
        }
    }
}

fn ray_curves(
    map: &HeightMap,
    request: &InplaneRequest,
    gonio: &Goniometer,
    progress: &Progress,
    warnings: &mut Vec<String>,
) -> Result<Vec<InplaneCurve>> {
    // The ray curves are judged at the longest wavelength given (the smallest Rayleigh
    // roughness), 550 nm when none is.
    let wavelength = request
        .wavelength_nm
        .iter()
        .copied()
        .fold(None, |a: Option<f64>, w| Some(a.map_or(w, |a| a.max(w))))
        .map_or(validity::PHOTOMETRIC_WAVELENGTH, |w| w * 1e-9);
    let levelled = gonio_surface::ops::level(map)?;
    warnings.extend(validity::ray_warnings(
        gonio_surface::stats::height_parameters(&levelled).0,
        wavelength,
        &validity::inplane_readings(&request.incidence_deg, gonio.half_angle),
    ));
    let options = RayOptions {
        ior: request.ior,
        ..request.ray
    };
    let engine = RayEngine::new(map, options)?;
    let mut curves = engine.inplane_curves(gonio, &[], progress)?;
    for curve in &mut curves {
        curve.wavelength_nm = match request.wavelength_nm.as_slice() {
            [w] => Some(*w),
            _ => None,
        };
    }
    Ok(curves)
}

fn kirchhoff_curves(
    map: &HeightMap,
    request: &InplaneRequest,
    gonio: &Goniometer,
    progress: &Progress,
    warnings: &mut Vec<String>,
) -> Result<Vec<InplaneCurve>> {
    let wavelengths = request.wavelengths_m("the Kirchhoff method")?;
    let spots = match (request.spot_um, request.spots) {
        (None, 1) => vec![Spot::largest(map)],
        (None, n) => {
            return Err(InstrumentError::Invalid(format!(
                "averaging {n} Kirchhoff spots needs the diameter of each spot"
            )));
        }
        (Some(d), n) => Spot::tiled(map, d * 1e-6, n)?,
    };
    let longest = wavelengths.iter().copied().fold(0.0, f64::max);
    warnings.extend(validity::kirchhoff_warnings(
        spots[0].diameter,
        longest,
        &validity::inplane_readings(&request.incidence_deg, gonio.half_angle),
    ));
    let mut sets = Vec::new();
    for spot in &spots {
        let options = KirchhoffOptions {
            spot: Some(*spot),
            ..KirchhoffOptions::new(request.ior)
        };
        let engine = Kirchhoff::new(map, options)?;
        sets.push(engine.inplane_curves(gonio, &request.wavelength_nm, progress)?);
    }
    Ok(average_curves(&sets)?)
}

fn model_curves(request: &InplaneRequest, gonio: &Goniometer) -> Result<Vec<InplaneCurve>> {
    if request.models.is_empty() {
        return Ok(Vec::new());
    }
    let (Some(sq), Some(corr)) = (request.sq_nm, request.corr_um) else {
        return Err(InstrumentError::Invalid(
            "the analytic models need the surface's rms height Sq and correlation length".into(),
        ));
    };
    let model = GaussianModel::new(sq * 1e-9, corr * 1e-6, request.ior)?;
    let mut curves = Vec::new();
    for &kind in &request.models {
        // Ray-optics models do not depend on the wavelength: one curve per incidence.
        if kind.is_wave() {
            request.wavelengths_m(&format!("the {} model", kind.name()))?;
        }
        let method = AnalyticMethod {
            surface: &model,
            model: kind,
        };
        curves.extend(method.inplane_curves(gonio, &request.wavelength_nm, &Progress::silent())?);
    }
    Ok(curves)
}
