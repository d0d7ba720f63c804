//! The multi-angle spectrophotometer that effect coatings are measured with: spectral reflectance
//! factors at a few in-plane geometries, each named by its illumination angle and its aspecular
//! angle (ASTM E2194 for metallic flakes, ASTM E2539 for interference pigments), turned into
//! CIELAB (D65 and the CIE 1964 10° observer unless asked otherwise), Alman's flop index, and
//! the colour differences between two samples geometry by geometry.
//!
//! Conventions (`docs/instruments.md`, "Multi-angle colour"):
//! - The illumination comes from polar angle θi in the plane of incidence (azimuth 0, on the +x
//!   side); the specular direction is at −θi.
//! - The aspecular angle γ is the detection direction's angle from the specular direction,
//!   positive towards the illuminator (through the normal): the detector is at the signed polar
//!   angle `θv = γ − θi`, positive on the illuminator's side. `45as15` is θv = −30°, `45as45` the
//!   normal, `45as110` θv = +65°; `45as-15` looks past the specular direction (θv = −60°).
//! - The reflectance factor is the sample's BRDF over that of the perfect reflecting diffuser
//!   (1/π): `R(λ) = π f(λ)`, averaged over the source's and the receptor's apertures (circular
//!   cones of the same half-angle; zero takes the directions themselves). Near the specular
//!   direction it exceeds 1 and L* exceeds 100, as real instruments report.
//! - XYZ by the band weights of ASTM E308 (linear between bands, `gonio_color::SpectralToXyz`),
//!   CIELAB relative to the perfect diffuser's white under the same illuminant and observer.

use crate::error::{InstrumentError, Result};
use glam::DVec3;
use gonio_brdf::bxdf::SpectralBrdf;
use gonio_brdf::quadrature::gauss_legendre_on;
use gonio_brdf::table::{BrdfTable, Channels};
use gonio_color::{Illuminant, Lab, Observer, SpectralToXyz, Xyz, ciede2000, white};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::fmt;

/// One in-plane measuring geometry: illumination angle and aspecular angle, in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// Polar angle of the illumination from the normal, degrees (0 ≤ θi < 90).
    pub illumination_deg: f64,
    /// Angle of the detector from the specular direction, positive towards the illuminator,
    /// degrees.
    pub aspecular_deg: f64,
}

/// ASTM E2194 (metallic flake pigments): 45° illumination, aspecular 15, 25, 45, 75 and 110°.
pub const E2194: [Geometry; 5] = [
    Geometry::new(45.0, 15.0),
    Geometry::new(45.0, 25.0),
    Geometry::new(45.0, 45.0),
    Geometry::new(45.0, 75.0),
    Geometry::new(45.0, 110.0),
];

/// gonio's set for ASTM E2539 (interference pigments): E2194's five with 45as-15 (past the
/// specular direction, where interference colours travel furthest), and 15° illumination at
/// aspecular −15, 15, 45 and 80° (the in-plane geometries of the multi-angle instruments built
/// for the standard). Compare with your edition of the standard; `--geometry` names any other.
pub const E2539: [Geometry; 10] = [
    Geometry::new(45.0, -15.0),
    Geometry::new(45.0, 15.0),
    Geometry::new(45.0, 25.0),
    Geometry::new(45.0, 45.0),
    Geometry::new(45.0, 75.0),
    Geometry::new(45.0, 110.0),
    Geometry::new(15.0, -15.0),
    Geometry::new(15.0, 15.0),
    Geometry::new(15.0, 45.0),
    Geometry::new(15.0, 80.0),
];

/// The geometries of the standard named `name`: `e2194` or `e2539` (any case).
pub fn standard(name: &str) -> Result<&'static [Geometry]> {
    Standard::parse(name).map(Standard::geometries)
}

/// A standard's set of geometries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Standard {
    /// [`E2194`].
    E2194,
    /// [`E2539`].
    E2539,
}

impl Standard {
    /// `e2194` or `e2539` (any case).
    pub fn parse(name: &str) -> Result<Standard> {
        match name.to_ascii_lowercase().as_str() {
            "e2194" => Ok(Standard::E2194),
            "e2539" => Ok(Standard::E2539),
            _ => Err(InstrumentError::Invalid(format!(
                "standard '{name}': e2194 (45° illumination) or e2539 (with 15° illumination)"
            ))),
        }
    }

    /// The standard's geometries.
    pub fn geometries(self) -> &'static [Geometry] {
        match self {
            Standard::E2194 => &E2194,
            Standard::E2539 => &E2539,
        }
    }

    /// `E2194` or `E2539`.
    pub fn name(self) -> &'static str {
        match self {
            Standard::E2194 => "E2194",
            Standard::E2539 => "E2539",
        }
    }
}

impl Geometry {
    /// The geometry `illumination_deg`as`aspecular_deg`.
    pub const fn new(illumination_deg: f64, aspecular_deg: f64) -> Self {
        Self {
            illumination_deg,
            aspecular_deg,
        }
    }

    /// Read a name such as `45as15` or `45as-15` (illumination, then aspecular angle, degrees).
    pub fn parse(name: &str) -> Result<Self> {
        let invalid = |why: &str| {
            InstrumentError::Invalid(format!(
                "geometry '{name}': {why} (write the illumination and aspecular angles in \
                 degrees, e.g. 45as15 or 45as-15)"
            ))
        };
        let (i, a) = name
            .trim()
            .split_once("as")
            .ok_or_else(|| invalid("no 'as' between the two angles"))?;
        let parse = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| invalid(&format!("'{s}' is not a number")))
        };
        let g = Self::new(parse(i)?, parse(a)?);
        g.check()?;
        Ok(g)
    }

    /// Refuse a geometry whose illumination or detection is not above the surface.
    pub fn check(&self) -> Result<()> {
        let (i, v) = (self.illumination_deg, self.viewing_deg());
        if !(i.is_finite() && (0.0..90.0).contains(&i)) {
            return Err(InstrumentError::Invalid(format!(
                "geometry {self}: the illumination angle must be in [0°, 90°)"
            )));
        }
        if !(v.is_finite() && v.abs() < 90.0) {
            return Err(InstrumentError::Invalid(format!(
                "geometry {self}: the detector would be at {v}° from the normal, below the \
                 surface (the aspecular angle must be between {}° and {}°)",
                i - 90.0,
                i + 90.0
            )));
        }
        Ok(())
    }

    /// Signed polar angle of the detector from the normal, degrees, positive on the
    /// illuminator's side: `γ − θi`.
    pub fn viewing_deg(&self) -> f64 {
        self.aspecular_deg - self.illumination_deg
    }

    /// Unit vectors towards the light and towards the detector, `(wi, wo)`, in the xz plane.
    pub fn directions(&self) -> (DVec3, DVec3) {
        (
            in_plane(self.illumination_deg),
            in_plane(self.viewing_deg()),
        )
    }
}

impl fmt::Display for Geometry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}as{}", self.illumination_deg, self.aspecular_deg)
    }
}

/// The in-plane unit vector at signed polar angle `deg` (positive towards +x).
fn in_plane(deg: f64) -> DVec3 {
    let t = deg.to_radians();
    DVec3::new(t.sin(), 0.0, t.cos())
}

/// What the instrument computes colour with, and its apertures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub illuminant: Illuminant,
    pub observer: Observer,
    /// Half-angle of the source's and the receptor's circular apertures, degrees; 0 evaluates
    /// the BRDF at the nominal directions.
    pub aperture_deg: f64,
}

impl Default for Settings {
    /// D65, the CIE 1964 10° observer (the standards' choice for the reported colour) and point
    /// apertures.
    fn default() -> Self {
        Self {
            illuminant: Illuminant::D65,
            observer: Observer::Cie1964TenDegree,
            aperture_deg: 0.0,
        }
    }
}

/// The reading at one geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct GeometryReading {
    pub geometry: Geometry,
    /// Reflectance factor `π f` at each of the reading's wavelengths (1 = the perfect diffuser).
    pub reflectance_factor: Vec<f64>,
    /// Tristimulus values, 0–100 scale (Y = 100 for the perfect diffuser).
    pub xyz: Xyz,
    pub lab: Lab,
}

/// A multi-angle reading: one [`GeometryReading`] per geometry, in the order asked.
#[derive(Clone, Debug, PartialEq)]
pub struct MultiangleReading {
    pub wavelengths_nm: Vec<f64>,
    pub settings: Settings,
    pub geometries: Vec<GeometryReading>,
}

impl MultiangleReading {
    /// The reading at `geometry`, if it was measured.
    pub fn at(&self, geometry: Geometry) -> Option<&GeometryReading> {
        self.geometries.iter().find(|g| g.geometry == geometry)
    }

    /// Alman's flop index from L* at 45as15, 45as45 and 45as110 (see [`flop_index`]); `None`
    /// when one of the three was not measured.
    pub fn flop_index(&self) -> Option<f64> {
        let l = |a| self.at(Geometry::new(45.0, a)).map(|g| g.lab.l);
        Some(flop_index(l(15.0)?, l(45.0)?, l(110.0)?))
    }
}

/// Alman's flop index, `2.69 (L*15 − L*110)^1.11 / L*45^0.86` (D. H. Alman, "Directional color
/// measurement of metallic flake finishes", Proc. ISCC Williamsburg Conference on Appearance,
/// 1987; the index X-Rite's and BYK's instruments report): about 0 for a solid colour, above 10
/// for a silver metallic. When the far-from-specular geometry is the lighter one (not an effect
/// finish) the power is taken of the magnitude and the sign kept, so that the index is negative
/// rather than undefined.
pub fn flop_index(l15: f64, l45: f64, l110: f64) -> f64 {
    let d = l15 - l110;
    2.69 * d.signum() * d.abs().powf(1.11) / l45.powf(0.86)
}

/// Read a spectral BRDF at `geometries`, at the wavelengths `wavelengths_nm` (nm, increasing).
pub fn read_spectral(
    brdf: &dyn SpectralBrdf,
    wavelengths_nm: &[f64],
    geometries: &[Geometry],
    settings: &Settings,
) -> Result<MultiangleReading> {
    read(
        &|wo, wi, out| brdf.eval_at(wo, wi, wavelengths_nm, out),
        wavelengths_nm,
        geometries,
        settings,
    )
}

/// Read a spectral BRDF given as `brdf(wo, wi, out)`, which writes `f(wo, wi)` in 1/sr at each
/// of `wavelengths_nm` (nm, increasing) into `out`, at `geometries`.
pub fn read(
    brdf: &(dyn Fn(DVec3, DVec3, &mut [f64]) + Sync),
    wavelengths_nm: &[f64],
    geometries: &[Geometry],
    settings: &Settings,
) -> Result<MultiangleReading> {
    let a = settings.aperture_deg;
    if !(a.is_finite() && (0.0..=10.0).contains(&a)) {
        return Err(InstrumentError::Invalid(format!(
            "aperture half-angle {a}°: must be between 0° and 10°"
        )));
    }
    let to_xyz = SpectralToXyz::new(wavelengths_nm, settings.illuminant, settings.observer)
        .map_err(|e| InstrumentError::Invalid(format!("wavelengths of the BRDF: {e}")))?;
    let white = white(settings.illuminant, settings.observer);
    let cone = Cone::new(a.to_radians());
    // The geometries in parallel, each reading independent of the others and of the order.
    let readings = geometries
        .par_iter()
        .map(|&geometry| {
            geometry.check()?;
            let (wi, wo) = geometry.directions();
            let reflectance_factor = cone.average(brdf, wi, wo, wavelengths_nm);
            let xyz = to_xyz
                .xyz(&reflectance_factor)
                .map_err(|e| InstrumentError::Invalid(e.to_string()))?;
            Ok(GeometryReading {
                geometry,
                xyz,
                lab: xyz.to_lab(white),
                reflectance_factor,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(MultiangleReading {
        wavelengths_nm: wavelengths_nm.to_vec(),
        settings: *settings,
        geometries: readings,
    })
}

/// Read a Lambertian surface of reflectance `reflectance[k]` at `wavelengths_nm[k]` (a bare
/// base, a white tile) at `geometries`: its BRDF ρ/π, the same at every geometry, so its colour
/// is the reflectance's whatever the angles.
pub fn read_lambertian(
    reflectance: &[f64],
    wavelengths_nm: &[f64],
    geometries: &[Geometry],
    settings: &Settings,
) -> Result<MultiangleReading> {
    if reflectance.len() != wavelengths_nm.len() {
        return Err(InstrumentError::Invalid(format!(
            "{} reflectances for {} wavelengths",
            reflectance.len(),
            wavelengths_nm.len()
        )));
    }
    read(
        &|_, _, out: &mut [f64]| {
            for (o, r) in out.iter_mut().zip(reflectance) {
                *o = r / std::f64::consts::PI;
            }
        },
        wavelengths_nm,
        geometries,
        settings,
    )
}

/// Read a spectral table at `geometries` (at the table's own wavelengths). Tables of RGB, XYZ
/// or one channel are refused: an instrument's colour needs the spectrum.
pub fn read_table(
    table: &BrdfTable,
    geometries: &[Geometry],
    settings: &Settings,
) -> Result<MultiangleReading> {
    let Channels::Spectral { wavelengths_nm } = table.channels() else {
        return Err(InstrumentError::Invalid(format!(
            "a multi-angle reading needs a spectral table; this one is {} (import the \
             measurement without --colour, or compute the table with --spectral)",
            table.channels().describe()
        )));
    };
    read(
        &|wo, wi, out| table.eval_channels(wo, wi, out),
        wavelengths_nm,
        geometries,
        settings,
    )
}

/// The differences of a sample from a reference at one geometry (sample − reference), CIE 15:2004
/// section 8.2.1 and 8.3.1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Difference {
    pub geometry: Geometry,
    pub dl: f64,
    pub da: f64,
    pub db: f64,
    /// Chroma difference ΔC*ab.
    pub dc: f64,
    /// Hue difference ΔH*ab = 2 √(C1 C2) sin(Δh/2), signed by the hue angle's turn.
    pub dh: f64,
    /// ΔE*ab (CIE 1976).
    pub de_ab: f64,
    /// CIEDE2000 with kL = kC = kH = 1.
    pub de00: f64,
}

/// The colour differences of `sample` from `reference`, geometry by geometry. Both must have
/// been read at the same geometries with the same settings.
pub fn differences(
    sample: &MultiangleReading,
    reference: &MultiangleReading,
) -> Result<Vec<Difference>> {
    let same_geometries = sample.geometries.len() == reference.geometries.len()
        && sample
            .geometries
            .iter()
            .zip(&reference.geometries)
            .all(|(s, r)| s.geometry == r.geometry);
    if !same_geometries || sample.settings != reference.settings {
        return Err(InstrumentError::Invalid(
            "the sample and the reference were read at different geometries or settings".into(),
        ));
    }
    Ok(sample
        .geometries
        .iter()
        .zip(&reference.geometries)
        .map(|(s, r)| {
            let (c1, c2) = (r.lab.chroma(), s.lab.chroma());
            let mut dhue = (s.lab.hue_deg() - r.lab.hue_deg()).to_radians();
            if dhue > PI {
                dhue -= 2.0 * PI;
            } else if dhue < -PI {
                dhue += 2.0 * PI;
            }
            let (dl, da, db) = (s.lab.l - r.lab.l, s.lab.a - r.lab.a, s.lab.b - r.lab.b);
            Difference {
                geometry: s.geometry,
                dl,
                da,
                db,
                dc: c2 - c1,
                dh: 2.0 * (c1 * c2).sqrt() * (0.5 * dhue).sin(),
                de_ab: (dl * dl + da * da + db * db).sqrt(),
                de00: ciede2000(r.lab, s.lab),
            }
        })
        .collect())
}

/// Uniform averaging over a circular cone of half-angle `a` about a direction: Gauss-Legendre
/// nodes in the polar angle within the cone (weight sin ψ), equally spaced azimuths.
struct Cone {
    /// `(ψ, φ, weight)`, weights summing to 1; one node at the axis for a point aperture.
    nodes: Vec<(f64, f64, f64)>,
}

impl Cone {
    /// Polar nodes and azimuths for a cone of half-angle `a` radians. Six polar nodes and twelve
    /// azimuths integrate a lobe a few apertures wide to well under 0.1%.
    fn new(a: f64) -> Self {
        if a == 0.0 {
            return Self {
                nodes: vec![(0.0, 0.0, 1.0)],
            };
        }
        const AZIMUTHS: usize = 12;
        let polar = gauss_legendre_on(6, 0.0, a);
        let norm: f64 = polar.iter().map(|&(p, w)| w * p.sin()).sum::<f64>() * AZIMUTHS as f64;
        let mut nodes = Vec::with_capacity(polar.len() * AZIMUTHS);
        for &(p, w) in &polar {
            for k in 0..AZIMUTHS {
                let phi = 2.0 * PI * (k as f64 + 0.5) / AZIMUTHS as f64;
                nodes.push((p, phi, w * p.sin() / norm));
            }
        }
        Self { nodes }
    }

    /// The direction at cone angle `psi` and azimuth `phi` about the in-plane unit vector `axis`.
    fn direction(axis: DVec3, psi: f64, phi: f64) -> DVec3 {
        // Perpendiculars to an in-plane axis: the other in-plane direction and +y.
        let u = DVec3::new(axis.z, 0.0, -axis.x);
        axis * psi.cos() + (u * phi.cos() + DVec3::Y * phi.sin()) * psi.sin()
    }

    /// The aperture-averaged reflectance factor `π f̄(λ)` for the nominal directions `wi`, `wo`
    /// (`brdf` as in [`read`]).
    fn average(
        &self,
        brdf: &dyn Fn(DVec3, DVec3, &mut [f64]),
        wi: DVec3,
        wo: DVec3,
        wavelengths_nm: &[f64],
    ) -> Vec<f64> {
        let mut sum = vec![0.0; wavelengths_nm.len()];
        let mut f = vec![0.0; wavelengths_nm.len()];
        for &(ps, fs, ws) in &self.nodes {
            let i = Self::direction(wi, ps, fs);
            for &(pr, fr, wr) in &self.nodes {
                let o = Self::direction(wo, pr, fr);
                brdf(o, i, &mut f);
                for (s, v) in sum.iter_mut().zip(&f) {
                    *s += ws * wr * v;
                }
            }
        }
        sum.iter_mut().for_each(|s| *s *= PI);
        sum
    }
}
