//! Virtual gloss meters: specular gloss per ISO 2813 / ASTM D523 at 20, 60 and 85 degrees, and
//! reflection haze and distinctness of image after ASTM E430.
//!
//! A meter illuminates the specimen from a rectangular source aperture centred on the incidence
//! angle and collects the reflected flux in a rectangular receptor aperture centred on the
//! specular direction (ISO 2813 §5; the aperture sizes commonly quoted from ISO 2813 and ASTM
//! D523, tabulated in `docs/instruments.md`, "Gloss meter"). The reading is the reflectance
//! averaged over the source directions, weighted by their irradiance (`cos theta_i dω`). Gloss
//! units are `100 · rho_specimen / rho_standard`, where the primary standard is a perfectly smooth
//! black glass of index 1.567 (ISO 2813 §6.1).
//!
//! Angular coordinates of an aperture: a direction `w = (cos b sin a, sin b, cos b cos a)` has
//! the signed in-plane angle `a` (positive on the specular side, the source being at negative x,
//! as for the signed scattering angle of in-plane goniometers) and the perpendicular elevation
//! `b`; its solid-angle element is `cos b da db`.

use crate::error::Result;
use glam::DVec3;
use gonio_brdf::Ior;
use gonio_brdf::quadrature::gauss_legendre_on;
use rayon::prelude::*;

/// Refractive index of the black-glass primary standard of ISO 2813 / ASTM D523.
pub const STANDARD_INDEX: f64 = 1.567;

/// A rectangular angular aperture: full widths in radians, in the plane of incidence and
/// perpendicular to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aperture {
    pub in_plane: f64,
    pub perpendicular: f64,
}

impl Aperture {
    /// An aperture given by its full widths in degrees.
    pub fn from_deg(in_plane_deg: f64, perpendicular_deg: f64) -> Self {
        Aperture {
            in_plane: in_plane_deg.to_radians(),
            perpendicular: perpendicular_deg.to_radians(),
        }
    }
}

/// An aperture placed at the signed in-plane angle `centre` (radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    pub centre: f64,
    pub aperture: Aperture,
}

impl Window {
    /// Whether the unit direction `w` lies inside the window.
    pub fn contains(&self, w: DVec3) -> bool {
        let a = w.x.atan2(w.z);
        let b = w.y.clamp(-1.0, 1.0).asin();
        (a - self.centre).abs() <= 0.5 * self.aperture.in_plane
            && b.abs() <= 0.5 * self.aperture.perpendicular
    }

    /// Quadrature over the window: `n × n` Gauss-Legendre directions with solid-angle weights
    /// (steradians), summing to the window's solid angle.
    pub fn quadrature(&self, n: usize) -> Vec<(DVec3, f64)> {
        let ha = 0.5 * self.aperture.in_plane;
        let hb = 0.5 * self.aperture.perpendicular;
        let rule_a = gauss_legendre_on(n, self.centre - ha, self.centre + ha);
        let rule_b = gauss_legendre_on(n, -hb, hb);
        let mut out = Vec::with_capacity(n * n);
        for &(b, wb) in &rule_b {
            for &(a, wa) in &rule_a {
                let w = DVec3::new(b.cos() * a.sin(), b.sin(), b.cos() * a.cos());
                out.push((w, wa * wb * b.cos()));
            }
        }
        out
    }
}

/// A specimen a virtual meter can measure.
pub trait Specimen: Sync {
    /// For light arriving from the unit direction `wi` (toward the source), the fraction of its
    /// flux that leaves the specimen within each of `windows`.
    fn reflectance_into(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<f64>>;

    /// The same fractions split into the parts that separate patches of the specimen reflect
    /// (one row per patch, one column per window; the rows add up to
    /// [`Specimen::reflectance_into`]), so that the statistical uncertainty of a reading from a
    /// finite map can be estimated from the patch-to-patch spread ([`jackknife`]). The default
    /// is one patch: a specimen computed exactly has no such uncertainty.
    fn reflectance_by_patch(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<Vec<f64>>> {
        Ok(vec![self.reflectance_into(wi, windows)?])
    }

    /// Gauss-Legendre order (per axis) over the source aperture; specimens that are costly to
    /// query (a ray trace per source direction) use fewer directions.
    fn source_order(&self) -> usize {
        8
    }
}

/// A perfectly smooth surface: mirror reflection with the Fresnel reflectance of `ior`.
#[derive(Debug, Clone, Copy)]
pub struct Smooth(pub Ior);

impl Specimen for Smooth {
    fn reflectance_into(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<f64>> {
        let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
        let r = self.0.reflectance(wi.z);
        Ok(windows
            .iter()
            .map(|w| if w.contains(mirror) { r } else { 0.0 })
            .collect())
    }
}

/// A specimen described by a BRDF `f(wi, wo)` in 1/sr, integrated over the receptor window by
/// Gauss-Legendre quadrature of `order × order` points.
pub struct BrdfSpecimen<F> {
    pub brdf: F,
    pub order: usize,
}

impl<F: Fn(DVec3, DVec3) -> f64 + Sync> BrdfSpecimen<F> {
    /// A specimen from `brdf(wi, wo)` with a quadrature order that resolves lobes down to about
    /// a tenth of the aperture width.
    pub fn new(brdf: F) -> Self {
        BrdfSpecimen { brdf, order: 32 }
    }
}

impl<F: Fn(DVec3, DVec3) -> f64 + Sync> Specimen for BrdfSpecimen<F> {
    fn reflectance_into(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<f64>> {
        Ok(windows
            .iter()
            .map(|window| {
                window
                    .quadrature(self.order)
                    .into_iter()
                    .filter(|(wo, _)| wo.z > 0.0)
                    .map(|(wo, dw)| (self.brdf)(wi, wo) * wo.z * dw)
                    .sum()
            })
            .collect())
    }
}

/// A gloss or appearance geometry: incidence angle, source aperture, and receptor aperture
/// centred at a signed in-plane angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Incidence angle (radians).
    pub theta: f64,
    pub source: Aperture,
    pub receptor: Window,
}

impl Geometry {
    /// The ISO 2813 / ASTM D523 geometry at 20, 60 or 85 degrees: source image 0.75° × 2.5°,
    /// receptor 1.80° × 3.6° (20°), 4.4° × 11.7° (60°) or 4.0° × 6.0° (85°), in-plane × perpendicular.
    pub fn iso2813(angle_deg: u32) -> Option<Self> {
        let receptor = match angle_deg {
            20 => Aperture::from_deg(1.80, 3.6),
            60 => Aperture::from_deg(4.4, 11.7),
            85 => Aperture::from_deg(4.0, 6.0),
            _ => return None,
        };
        let theta = (angle_deg as f64).to_radians();
        Some(Geometry {
            theta,
            source: Aperture::from_deg(0.75, 2.5),
            receptor: Window {
                centre: theta,
                aperture: receptor,
            },
        })
    }

    /// The reading of the meter: reflectance into the receptor averaged over the source
    /// aperture.
    pub fn reading(&self, specimen: &dyn Specimen) -> Result<f64> {
        Ok(readings(self.theta, self.source, &[self.receptor], specimen)?[0])
    }
}

/// Readings of several receptor windows lit by one source: the reflectance into each window
/// averaged over the source aperture centred on incidence `theta` (Gauss-Legendre of the
/// specimen's order per axis, weighted by the irradiance `cos theta_i dω`).
pub fn readings(
    theta: f64,
    source: Aperture,
    receptors: &[Window],
    specimen: &dyn Specimen,
) -> Result<Vec<f64>> {
    let mut rows = source_average(theta, source, specimen, |wi| {
        Ok(vec![specimen.reflectance_into(wi, receptors)?])
    })?;
    Ok(rows.pop().unwrap_or_else(|| vec![0.0; receptors.len()]))
}

/// [`readings`] split by the specimen's patches ([`Specimen::reflectance_by_patch`]): one row
/// per patch, whose sum over rows ([`column_sums`]) is the readings.
pub fn readings_by_patch(
    theta: f64,
    source: Aperture,
    receptors: &[Window],
    specimen: &dyn Specimen,
) -> Result<Vec<Vec<f64>>> {
    source_average(theta, source, specimen, |wi| {
        specimen.reflectance_by_patch(wi, receptors)
    })
}

/// The rows `query(wi)` returns (one row per patch, one value per receptor) averaged over the
/// source aperture centred on incidence `theta`, as [`readings`] describes.
fn source_average(
    theta: f64,
    source: Aperture,
    specimen: &dyn Specimen,
    query: impl Fn(DVec3) -> Result<Vec<Vec<f64>>> + Sync,
) -> Result<Vec<Vec<f64>>> {
    let source = Window {
        centre: -theta,
        aperture: source,
    };
    let mut sums: Vec<Vec<f64>> = Vec::new();
    let mut norm = 0.0;
    // The source directions in parallel, their rows summed in order: the same sums on any
    // number of threads.
    let directions = source.quadrature(specimen.source_order());
    let all = directions
        .par_iter()
        .map(|&(wi, _)| query(wi))
        .collect::<Result<Vec<_>>>()?;
    for ((wi, dw), rows) in directions.into_iter().zip(all) {
        let weight = wi.z * dw;
        if sums.is_empty() {
            sums = rows.iter().map(|row| vec![0.0; row.len()]).collect();
        }
        for (sum, row) in sums.iter_mut().zip(rows) {
            for (s, r) in sum.iter_mut().zip(row) {
                *s += weight * r;
            }
        }
        norm += weight;
    }
    Ok(sums
        .into_iter()
        .map(|row| row.into_iter().map(|s| s / norm).collect())
        .collect())
}

/// The sums over the rows of `parts` (rows of equal length), column by column.
pub fn column_sums(parts: &[Vec<f64>]) -> Vec<f64> {
    let width = parts.first().map_or(0, Vec::len);
    (0..width)
        .map(|k| parts.iter().map(|p| p[k]).sum())
        .collect()
}

/// The jackknife standard error of a quantity `f(readings)` computed from readings split into
/// independent patches `parts` (rows: patches; their sum the readings): each patch left out in
/// turn, the others scaled up to the whole, `σ² = (B−1)/B Σ_b (f_(b) − f̄)²` over the B
/// patches (Efron & Tibshirani, *An Introduction to the Bootstrap*, 1993, §11.2, eq. 11.5).
/// It treats the patches as independent samples of the surface, which holds where they are
/// much larger than its correlation length. 0 with fewer than two patches.
pub fn jackknife(parts: &[Vec<f64>], f: impl Fn(&[f64]) -> f64) -> f64 {
    let b = parts.len();
    if b < 2 {
        return 0.0;
    }
    let total = column_sums(parts);
    let scale = b as f64 / (b - 1) as f64;
    let values: Vec<f64> = parts
        .iter()
        .map(|p| {
            let left: Vec<f64> = total.iter().zip(p).map(|(t, x)| (t - x) * scale).collect();
            f(&left)
        })
        .collect();
    let mean = values.iter().sum::<f64>() / b as f64;
    let ss: f64 = values.iter().map(|v| (v - mean).powi(2)).sum();
    ((b - 1) as f64 / b as f64 * ss).sqrt()
}

/// Specular gloss in gloss units at an ISO 2813 geometry.
pub fn gloss_units(specimen: &dyn Specimen, geometry: &Geometry) -> Result<f64> {
    let standard = Smooth(Ior::Dielectric(STANDARD_INDEX));
    Ok(100.0 * geometry.reading(specimen)? / geometry.reading(&standard)?)
}

/// The appearance geometries of ASTM E430 (abridged goniophotometry) that gonio implements.
///
/// Angles confirmed from the standard's summary (E430-11 §1.1 and its test methods as
/// summarised in "Haze (optics)", Wikipedia/wikimili, citing E430):
/// - Test Method A, specular angle 30°: narrow-angle reflection haze at 28° and 32° (±2° from
///   specular), wide-angle reflection haze at 25° and 35° (±5°);
/// - Test Method B, specular angle 20°: narrow-angle haze at 18.1° and 21.9° (±1.9°), the
///   geometry ISO 13803 also uses;
/// - distinctness of image at 30°: `DOI = 100 · (Rs − R0.3) / Rs`, Rs read on the specular
///   direction and R0.3 at 0.3° from it through an equal aperture (Hunter & Harold, *The
///   Measurement of Appearance*, 2nd ed., Wiley 1987, §14, the Hunter Dorigon geometry).
///
/// The aperture widths are gonio's choice (the standard's table of widths was not available to
/// check): a 0.1° × 3.0° source slit at 30°, narrow enough that a mirror's image (±0.05°) stays
/// out of the DOI slits; equal 0.1° × 3.0° slits for Rs and R0.3; 0.44° × 3.0° haze receptors at
/// 30°; at 20° the ISO 2813 source (0.75° × 2.5°) and 0.44° × 3.6° haze receptors.
pub mod e430 {
    use super::Aperture;
    /// Incidence angle of Test Method A and of DOI, degrees.
    pub const THETA_DEG: f64 = 30.0;
    /// Source slit at 30°.
    pub fn source() -> Aperture {
        Aperture::from_deg(0.1, 3.0)
    }
    /// Haze receptor at 30° (at ±2° and ±5° from specular).
    pub fn receptor() -> Aperture {
        Aperture::from_deg(0.44, 3.0)
    }
    /// The equal receptors of DOI: Rs on specular, R0.3 at ±0.3°.
    pub fn doi_receptor() -> Aperture {
        Aperture::from_deg(0.1, 3.0)
    }
    /// Offset of the R0.3 receptors from specular, degrees.
    pub const DOI_OFFSET_DEG: f64 = 0.3;
    /// Offset of the narrow-angle haze receptors of Test Method A, degrees.
    pub const HAZE_OFFSET_DEG: f64 = 2.0;
    /// Offset of the wide-angle haze receptors of Test Method A, degrees.
    pub const WIDE_HAZE_OFFSET_DEG: f64 = 5.0;
    /// Incidence angle of Test Method B (and ISO 13803), degrees.
    pub const B_THETA_DEG: f64 = 20.0;
    /// Offset of the haze receptors of Test Method B (and ISO 13803), degrees.
    pub const B_HAZE_OFFSET_DEG: f64 = 1.9;
    /// Haze receptor of Test Method B; the source is the ISO 2813 20° source.
    pub fn b_receptor() -> Aperture {
        Aperture::from_deg(0.44, 3.6)
    }
}

/// What a gloss meter and an E430 appearance meter read on a specimen.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GlossReport {
    /// Specular gloss at 20°, 60°, 85° in gloss units (ISO 2813).
    pub gu20: f64,
    pub gu60: f64,
    pub gu85: f64,
    /// ASTM E430 Test Method A narrow-angle reflection haze at 30°:
    /// `100 · rho(±2°) / rho_standard(specular)`, mean of both sides.
    pub haze: f64,
    /// ASTM E430 Test Method A wide-angle reflection haze at 30°, `100 · rho(±5°) /
    /// rho_standard(specular)`, mean of both sides.
    pub haze_wide: f64,
    /// Reflection haze at 20° (ASTM E430 Test Method B, the ISO 13803 geometry),
    /// `100 · rho(±1.9°) / rho_standard(specular, 20° gloss receptor)`, mean of both sides.
    pub haze_20: f64,
    /// `haze_20` on the logarithmic scale of haze meters ([`log_haze`]), HU.
    pub haze_20_log: f64,
    /// ASTM D4039 haze index: 60° gloss − 20° gloss, GU.
    pub haze_d4039: f64,
    /// Distinctness of image (ASTM E430): `100 · (Rs − R0.3) / Rs` through equal apertures,
    /// R0.3 the mean of both sides; 100 for a mirror, 0 where Rs = R0.3.
    pub doi: f64,
    /// Standard uncertainty of `doi`: from the finite map (the jackknife over 16 patches of a
    /// height map read by the ray method, [`jackknife`]) or from a coating's random walks (the
    /// jackknife over groups of them, `coating_study::CoatingSpecimen`); 0 for a specimen
    /// computed exactly.
    pub doi_uncertainty: f64,
}

/// The logarithmic haze of gloss-haze meters (ISO 13803 haze meters display it) from the
/// linear haze `linear` (HU): `K · log10(linear / 20 + 1)`, with K chosen so that a linear haze
/// of 100 reads 1000, K = 1000 / log10 6 = 1285.1 (BYK-Gardner micro-haze plus manual,
/// "Messprinzip": "Die Konstante (K=1285,1) wurde so bemessen, dass sich bei einem linearen
/// Haze von 100 ein logarithmischer Wert von 1000 ergibt"). The scale is steep for small haze,
/// where high-gloss finishes differ, and flat for large.
pub fn log_haze(linear: f64) -> f64 {
    1000.0 / 6f64.log10() * (linear.max(0.0) / 20.0 + 1.0).log10()
}

/// Distinctness of image after ASTM E430 from the readings `rs` on specular and `r_plus`,
/// `r_minus` at ±0.3° through equal receptors: `100 · (Rs − R0.3) / Rs` with R0.3 the mean of
/// both sides (Hunter & Harold 1987, §14); 0 when the specimen reflects nothing into Rs.
pub fn doi(rs: f64, r_plus: f64, r_minus: f64) -> f64 {
    if rs > 0.0 {
        100.0 * (rs - 0.5 * (r_plus + r_minus)) / rs
    } else {
        0.0
    }
}

/// Measure gloss at 20/60/85°, the haze of E430 Test Methods A (±2° and ±5° at 30°) and B
/// (±1.9° at 20°), the D4039 haze index, and DOI. Receptors that share a source are read from
/// one pass over it (one ray trace or Kirchhoff evaluation per source direction): the 20° gloss
/// and Method B haze receptors, and the seven 30° receptors of DOI and Method A.
pub fn measure(specimen: &dyn Specimen) -> Result<GlossReport> {
    let standard = Smooth(Ior::Dielectric(STANDARD_INDEX));
    let mean = |a: f64, b: f64| 0.5 * (a + b);

    // 20°: the ISO 2813 receptor and the Method B haze receptors under the ISO source. The
    // standard's specular flux is read through the 1.8° gloss receptor, which holds all of the
    // 0.75° source image (the 0.44° haze receptor would not).
    let g20 = Geometry::iso2813(20).expect("ISO 2813 angle");
    let b = |sign: f64| Window {
        centre: g20.theta + sign * e430::B_HAZE_OFFSET_DEG.to_radians(),
        aperture: e430::b_receptor(),
    };
    let r20 = readings(
        g20.theta,
        g20.source,
        &[g20.receptor, b(1.0), b(-1.0)],
        specimen,
    )?;
    let standard20 = g20.reading(&standard)?;
    let gu20 = 100.0 * r20[0] / standard20;
    let gu = |deg| gloss_units(specimen, &Geometry::iso2813(deg).expect("ISO 2813 angle"));
    let (gu60, gu85) = (gu(60)?, gu(85)?);

    // 30°: Rs and R0.3 through equal slits, and the Method A haze receptors. The standard's
    // specular flux is read through a haze-sized receptor, which holds its 0.1° slit image.
    let theta = e430::THETA_DEG.to_radians();
    let at = |offset_deg: f64, aperture: Aperture| Window {
        centre: theta + offset_deg.to_radians(),
        aperture,
    };
    let (d, h, w) = (
        e430::DOI_OFFSET_DEG,
        e430::HAZE_OFFSET_DEG,
        e430::WIDE_HAZE_OFFSET_DEG,
    );
    let (slit, receptor) = (e430::doi_receptor(), e430::receptor());
    let windows = [
        at(0.0, slit),
        at(d, slit),
        at(-d, slit),
        at(h, receptor),
        at(-h, receptor),
        at(w, receptor),
        at(-w, receptor),
    ];
    let parts = readings_by_patch(theta, e430::source(), &windows, specimen)?;
    let r = column_sums(&parts);
    let standard30 = readings(theta, e430::source(), &[at(0.0, receptor)], &standard)?[0];
    let haze_20 = 100.0 * mean(r20[1], r20[2]) / standard20;
    Ok(GlossReport {
        gu20,
        gu60,
        gu85,
        haze: 100.0 * mean(r[3], r[4]) / standard30,
        haze_wide: 100.0 * mean(r[5], r[6]) / standard30,
        haze_20,
        haze_20_log: log_haze(haze_20),
        haze_d4039: gu60 - gu20,
        doi: doi(r[0], r[1], r[2]),
        doi_uncertainty: jackknife(&parts, |r| doi(r[0], r[1], r[2])),
    })
}
