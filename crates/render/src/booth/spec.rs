//! The booth's description (`BoothSpec`, TOML): the light (a CIE illuminant or a measured
//! spectrum, the illuminance on the specimen, its diffuse and directional parts), the interior's
//! grey, the specimen, the views, the observer and the picture's size and samples. Every field
//! has a default, so an empty file is the standard booth; `docs/standard.md` says which values
//! the standard fixes and where each default comes from.
//!
//! Sources of the defaults:
//! - ASTM D1729-16, "Visual appraisal of colors and color differences of diffusely-illuminated
//!   opaque materials", and ISO 3668:2017, "Paints and varnishes — Visual comparison of colour of
//!   paints": a daylight simulator of CIE D65, a diffuse overhead source, a neutral grey interior
//!   of Munsell value 5 to 7, an illuminance on the specimen of about 1000 to 4000 lx (ISO 3668's
//!   range for its artificial-daylight cabinet; D1729 gives ranges by the specimen's lightness
//!   within it). The default 2000 lx lies inside both.
//! - ASTM D1535 (Munsell renotation): the luminous reflectance of Munsell N5, N6, N7 is 0.198,
//!   0.300, 0.431.
//! - ASTM E2194 (multi-angle colour of metallic finishes): the 45° illumination and the aspecular
//!   angles 15°, 45° and 110° of the three views.
//! - CIE 15:2004: the observers and illuminants.

use crate::error::{RenderError, Result};
use gonio_color::{Illuminant, Observer, Spectrum};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The whole booth description.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct BoothSpec {
    /// The light.
    pub light: LightSpec,
    /// The interior.
    pub interior: InteriorSpec,
    /// The specimen.
    pub specimen: SpecimenSpec,
    /// The views and their camera.
    pub camera: CameraSpec,
    /// The observer's field, degrees: 2 (CIE 1931) or 10 (CIE 1964, the default: the field of
    /// the colour the multi-angle standards report).
    pub observer_deg: u32,
    /// The picture's size and samples.
    pub render: RenderSpec,
    /// The directory relative paths (a measured spectrum) start from: the spec file's.
    #[serde(skip)]
    pub dir: PathBuf,
}

/// `[light]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct LightSpec {
    /// A CIE illuminant by name (`D65`, the default, or `A`); not with `spectrum`.
    pub illuminant: Option<String>,
    /// A measured relative spectral power: a CSV file `wavelength_nm,value` (relative to the
    /// spec's directory); not with `illuminant`.
    pub spectrum: Option<PathBuf>,
    /// The illuminance on the specimen's centre, lx (default 2000).
    pub illuminance_lux: f64,
    /// The part of that illuminance from the directional light, 0 to 1 (default 0.5); the rest
    /// comes from the diffuse booth (ceiling and interior).
    pub directional_fraction: f64,
    /// The directional light's polar angle from the specimen's normal, degrees, in the plane of
    /// incidence (default 45, the multi-angle standards' illumination).
    pub directional_deg: f64,
}

/// `[interior]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct InteriorSpec {
    /// The walls' and floor's neutral grey: `N5`, `N6` (default) or `N7`.
    pub munsell: String,
}

/// `[specimen]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct SpecimenSpec {
    /// `flat` (default) or `curved` (the bonnet-like panel of the panel pictures).
    pub shape: String,
    /// Width (along the plane of incidence), mm (default 150 flat, 300 curved).
    pub width_mm: Option<f64>,
    /// Depth (across the plane of incidence), mm (default 100 flat, 200 curved).
    pub height_mm: Option<f64>,
    /// The specimen's material: a coating description (`.toml`) or a spectral BRDF table
    /// (`.gbrdf`), relative to the spec's directory. A caller may give one instead
    /// ([`BoothSpec::material_path`]).
    pub material: Option<PathBuf>,
}

/// `[camera]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct CameraSpec {
    /// The views, by name: `near-specular`, `45`, `flank` (default all three).
    pub views: Vec<String>,
    /// `perspective` (default) or `orthographic` (a camera at infinity: every pixel sees the
    /// specimen at the view's angles).
    pub projection: String,
    /// The perspective camera's distance from the specimen's centre, mm (default 600).
    pub distance_mm: f64,
}

/// `[render]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSpec {
    /// Width, pixels (default 480).
    pub width: usize,
    /// Height, pixels (default 320).
    pub height: usize,
    /// Samples per pixel (default 64).
    pub spp: u32,
    /// Seed of the sample sequences (default 0).
    pub seed: u32,
    /// Longest path, in surface interactions (default 4).
    pub max_bounces: u32,
}

impl Default for BoothSpec {
    fn default() -> Self {
        BoothSpec {
            light: LightSpec::default(),
            interior: InteriorSpec::default(),
            specimen: SpecimenSpec::default(),
            camera: CameraSpec::default(),
            observer_deg: 10,
            render: RenderSpec::default(),
            dir: PathBuf::from("."),
        }
    }
}

impl Default for LightSpec {
    fn default() -> Self {
        LightSpec {
            illuminant: None,
            spectrum: None,
            illuminance_lux: 2000.0,
            directional_fraction: 0.5,
            directional_deg: 45.0,
        }
    }
}

impl Default for InteriorSpec {
    fn default() -> Self {
        InteriorSpec {
            munsell: "N6".into(),
        }
    }
}

impl Default for SpecimenSpec {
    fn default() -> Self {
        SpecimenSpec {
            shape: "flat".into(),
            width_mm: None,
            height_mm: None,
            material: None,
        }
    }
}

impl Default for CameraSpec {
    fn default() -> Self {
        CameraSpec {
            views: View::NAMED.iter().map(|(n, _)| n.to_string()).collect(),
            projection: "perspective".into(),
            distance_mm: 600.0,
        }
    }
}

impl Default for RenderSpec {
    fn default() -> Self {
        RenderSpec {
            width: 480,
            height: 320,
            spp: 64,
            seed: 0,
            max_bounces: 4,
        }
    }
}

/// A view: the camera in the plane of incidence of the directional light, at an aspecular angle
/// γ from the light's mirror direction, positive toward the light (through the normal), as the
/// multi-angle instruments name their geometries (ASTM E2194): the camera's polar angle from the
/// specimen's normal is `γ − θ_light`, positive on the light's side. Three are named:
///
/// - `near-specular`: γ = 15° (E2194's 45as15 under the 45° light): a metallic's bright face;
/// - `45`: γ = 45° (45as45: along the normal under the 45° light): the face colour;
/// - `flank`: γ = 110° (45as110: 65° from the normal on the light's side): the flop.
///
/// Any other is written `asG`, G the aspecular angle in degrees (`as25`, `as-15`): the
/// geometries of E2194 and E2539.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// Its name in the spec.
    pub name: String,
    /// The aspecular angle γ, degrees.
    pub aspecular_deg: f64,
}

impl View {
    /// The three named views: name and aspecular angle.
    pub const NAMED: [(&'static str, f64); 3] =
        [("near-specular", 15.0), ("45", 45.0), ("flank", 110.0)];

    /// The view called `name`: one of [`View::NAMED`] or `asG`.
    pub fn from_name(name: &str) -> Option<View> {
        let aspecular_deg = match View::NAMED.iter().find(|(n, _)| *n == name) {
            Some(&(_, g)) => g,
            None => name
                .strip_prefix("as")?
                .parse::<f64>()
                .ok()
                .filter(|g| g.is_finite())?,
        };
        Some(View {
            name: name.to_string(),
            aspecular_deg,
        })
    }
}

/// The specimen's shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// A flat rectangular panel.
    Flat,
    /// The curved, bonnet-like panel (`examples/panel.obj`), scaled to the size.
    Curved,
}

/// How the views project.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Projection {
    /// A pinhole at the camera's distance.
    Perspective,
    /// A camera at infinity.
    Orthographic,
}

/// The booth's light as the renderer takes it.
#[derive(Debug, Clone, PartialEq)]
pub struct LightSource {
    /// What it is, for the manifest and the docs: `D65`, `A` or the file's path.
    pub name: String,
    /// Its relative spectral power.
    pub spectrum: Arc<Spectrum>,
}

/// Everything in a [`BoothSpec`] checked and resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct Checked {
    pub light: LightSource,
    pub illuminance_lux: f64,
    pub directional_fraction: f64,
    pub directional_deg: f64,
    /// The interior's luminous reflectance.
    pub interior_reflectance: f64,
    pub shape: Shape,
    /// Width and depth, m.
    pub size_m: [f64; 2],
    pub views: Vec<View>,
    pub projection: Projection,
    pub distance_m: f64,
    pub observer: Observer,
}

impl BoothSpec {
    /// The specimen's material file: `given` when there is one (a coating or table named
    /// outside the spec), else the spec's `[specimen] material` resolved against its directory.
    pub fn material_path(&self, given: Option<&Path>) -> Result<PathBuf> {
        match (given, &self.specimen.material) {
            (Some(path), _) => Ok(path.to_path_buf()),
            (None, Some(file)) if file.is_absolute() => Ok(file.clone()),
            (None, Some(file)) => Ok(self.dir.join(file)),
            (None, None) => Err(RenderError::Invalid(
                "[specimen] material: the booth has no specimen material; name one in the spec \
                 (`[specimen] material = \"coating.toml\"` or a `.gbrdf` table, relative to the \
                 spec's folder) or give the material as the input"
                    .into(),
            )),
        }
    }

    /// Read the booth spec file `path` (TOML).
    pub fn from_file(path: &Path) -> Result<BoothSpec> {
        let text = std::fs::read_to_string(path).map_err(|error| RenderError::Io {
            path: path.to_path_buf(),
            error,
        })?;
        BoothSpec::from_toml(&text, path)
    }

    /// Parse the TOML text of a booth spec; `path` names the file in errors (which quote the
    /// field, line and column) and its directory is where relative paths start.
    pub fn from_toml(text: &str, path: &Path) -> Result<BoothSpec> {
        let mut spec: BoothSpec =
            toml::from_str(text).map_err(|e| RenderError::scene(path, e.to_string()))?;
        spec.dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        spec.check().map_err(|e| match e {
            RenderError::Invalid(problem) => RenderError::scene(path, problem),
            other => other,
        })?;
        Ok(spec)
    }

    /// Check every field and resolve the names (errors name the field).
    pub fn check(&self) -> Result<Checked> {
        let bad =
            |field: &str, problem: String| RenderError::Invalid(format!("{field}: {problem}"));
        let l = &self.light;
        let light = match (&l.illuminant, &l.spectrum) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    "[light]",
                    "give `illuminant` (a CIE illuminant) or `spectrum` (a measured CSV), not both"
                        .into(),
                ));
            }
            (None, Some(file)) => {
                let path = if file.is_absolute() {
                    file.clone()
                } else {
                    self.dir.join(file)
                };
                let spectrum = Spectrum::read_csv(&path)
                    .map_err(|e| bad("[light] spectrum", e.to_string()))?;
                if spectrum.values().iter().any(|v| !v.is_finite() || *v < 0.0)
                    || spectrum.values().iter().all(|v| *v == 0.0)
                {
                    return Err(bad(
                        "[light] spectrum",
                        format!(
                            "{}: a relative spectral power must be non-negative and not all zero",
                            path.display()
                        ),
                    ));
                }
                LightSource {
                    name: path.display().to_string(),
                    spectrum: Arc::new(spectrum),
                }
            }
            (name, None) => {
                let name = name.as_deref().unwrap_or("D65");
                let illuminant = Illuminant::from_name(name).ok_or_else(|| {
                    bad(
                        "[light] illuminant",
                        format!(
                            "`{name}` is not a CIE illuminant gonio has: {}",
                            Illuminant::ALL.map(|i| i.name()).join(", ")
                        ),
                    )
                })?;
                LightSource {
                    name: illuminant.name().into(),
                    spectrum: Arc::new(illuminant.spd().clone()),
                }
            }
        };
        if !(l.illuminance_lux > 0.0 && l.illuminance_lux.is_finite()) {
            return Err(bad(
                "[light] illuminance_lux",
                format!(
                    "{} must be positive (the standards ask about 1000 to 4000 lx)",
                    l.illuminance_lux
                ),
            ));
        }
        if !(0.0..=1.0).contains(&l.directional_fraction) {
            return Err(bad(
                "[light] directional_fraction",
                format!("{} must be between 0 and 1", l.directional_fraction),
            ));
        }
        if !(0.0..90.0).contains(&l.directional_deg) {
            return Err(bad(
                "[light] directional_deg",
                format!(
                    "{}° must be in [0°, 90°) from the normal",
                    l.directional_deg
                ),
            ));
        }
        let interior_reflectance = match self.interior.munsell.as_str() {
            "N5" => 0.198,
            "N6" => 0.300,
            "N7" => 0.431,
            other => {
                return Err(bad(
                    "[interior] munsell",
                    format!("`{other}`: the standards' interior is N5, N6 or N7"),
                ));
            }
        };
        let (shape, default_mm) = match self.specimen.shape.as_str() {
            "flat" => (Shape::Flat, [150.0, 100.0]),
            "curved" => (Shape::Curved, [300.0, 200.0]),
            other => {
                return Err(bad(
                    "[specimen] shape",
                    format!("`{other}`: `flat` or `curved`"),
                ));
            }
        };
        let size_mm = [
            self.specimen.width_mm.unwrap_or(default_mm[0]),
            self.specimen.height_mm.unwrap_or(default_mm[1]),
        ];
        for (field, v) in ["width_mm", "height_mm"].iter().zip(size_mm) {
            if !(v > 0.0 && v < 1e4) {
                return Err(bad(
                    &format!("[specimen] {field}"),
                    format!("{v} mm must be positive (and under 10 m)"),
                ));
            }
        }
        if self.camera.views.is_empty() {
            return Err(bad("[camera] views", "name at least one view".into()));
        }
        let views = self
            .camera
            .views
            .iter()
            .map(|name| {
                View::from_name(name).ok_or_else(|| {
                    bad(
                        "[camera] views",
                        format!(
                            "`{name}` is not a view: {}, or asG for an aspecular angle of G \
                             degrees (as25, as-15)",
                            View::NAMED.map(|(n, _)| n).join(", ")
                        ),
                    )
                })
            })
            .collect::<Result<Vec<View>>>()?;
        for v in &views {
            let polar = v.aspecular_deg - l.directional_deg;
            if polar.abs() >= 89.0 {
                return Err(bad(
                    "[camera] views",
                    format!(
                        "`{}` under a light at {}° puts the camera {polar}° from the normal, at \
                         or below the specimen's horizon",
                        v.name, l.directional_deg
                    ),
                ));
            }
        }
        let projection = match self.camera.projection.as_str() {
            "perspective" => Projection::Perspective,
            "orthographic" => Projection::Orthographic,
            other => {
                return Err(bad(
                    "[camera] projection",
                    format!("`{other}`: `perspective` or `orthographic`"),
                ));
            }
        };
        let diagonal_mm = size_mm[0].hypot(size_mm[1]);
        if !(self.camera.distance_mm > diagonal_mm && self.camera.distance_mm.is_finite()) {
            return Err(bad(
                "[camera] distance_mm",
                format!(
                    "{} mm must exceed the specimen's diagonal ({diagonal_mm:.0} mm)",
                    self.camera.distance_mm
                ),
            ));
        }
        let observer = Observer::from_field_deg(self.observer_deg).ok_or_else(|| {
            bad(
                "observer_deg",
                format!("{}: 2 (CIE 1931) or 10 (CIE 1964)", self.observer_deg),
            )
        })?;
        let r = &self.render;
        if r.width == 0 || r.height == 0 || r.width > 1 << 15 || r.height > 1 << 15 {
            return Err(bad(
                "[render] width, height",
                format!("{} × {}: 1 to 32768 pixels each", r.width, r.height),
            ));
        }
        if r.spp == 0 || r.spp > 1 << 16 {
            return Err(bad("[render] spp", format!("{}: 1 to 65536", r.spp)));
        }
        Ok(Checked {
            light,
            illuminance_lux: l.illuminance_lux,
            directional_fraction: l.directional_fraction,
            directional_deg: l.directional_deg,
            interior_reflectance,
            shape,
            size_m: size_mm.map(|v| v / 1000.0),
            views,
            projection,
            distance_m: self.camera.distance_mm / 1000.0,
            observer,
        })
    }
}
