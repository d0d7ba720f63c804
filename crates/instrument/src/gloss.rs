//! Virtual gloss meters: specular gloss per ISO 2813 / ASTM D523 at 20, 60 and 85 degrees, and
//! reflection haze and distinctness of image after ASTM E430.
//!
//! A meter illuminates the specimen from a rectangular source aperture centred on the incidence
//! angle and collects the reflected flux in a rectangular receptor aperture centred on the
//! specular direction (ISO 2813 §5; apertures as quoted in `shared/docs/physics.md`). The reading
//! is the reflectance averaged over the source directions, weighted by their irradiance
//! (`cos theta_i dω`). Gloss units are `100 · rho_specimen / rho_standard`, where the primary
//! standard is a perfectly smooth black glass of index 1.567 (ISO 2813 §6.1).
//!
//! Angular coordinates of an aperture: a direction `w = (cos b sin a, sin b, cos b cos a)` has
//! the signed in-plane angle `a` (positive on the specular side, as in physics.md) and the
//! perpendicular elevation `b`; its solid-angle element is `cos b da db`.

use crate::error::Result;
use crate::quadrature::gauss_legendre_on;
use glam::DVec3;
use gonio_brdf::Ior;

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
    let source = Window {
        centre: -theta,
        aperture: source,
    };
    let mut sums = vec![0.0; receptors.len()];
    let mut norm = 0.0;
    for (wi, dw) in source.quadrature(specimen.source_order()) {
        let weight = wi.z * dw;
        for (s, r) in sums
            .iter_mut()
            .zip(specimen.reflectance_into(wi, receptors)?)
        {
            *s += weight * r;
        }
        norm += weight;
    }
    Ok(sums.into_iter().map(|s| s / norm).collect())
}

/// Specular gloss in gloss units at an ISO 2813 geometry.
pub fn gloss_units(specimen: &dyn Specimen, geometry: &Geometry) -> Result<f64> {
    let standard = Smooth(Ior::Dielectric(STANDARD_INDEX));
    Ok(100.0 * geometry.reading(specimen)? / geometry.reading(&standard)?)
}

/// The E430-style geometry gonio implements (ASTM E430, abridged goniophotometry at 30°):
/// incidence 30°, a narrow source slit 0.1° × 3.0°; the specular receptor 0.44° × 3.0° on the
/// specular direction; the distinctness-of-image receptors 0.1° × 3.0° at ±0.3° from specular;
/// the haze receptors 0.44° × 3.0° at ±2.0° from specular.
pub mod e430 {
    use super::Aperture;
    /// Incidence angle in degrees.
    pub const THETA_DEG: f64 = 30.0;
    /// Source slit.
    pub fn source() -> Aperture {
        Aperture::from_deg(0.1, 3.0)
    }
    /// Specular and haze receptor.
    pub fn receptor() -> Aperture {
        Aperture::from_deg(0.44, 3.0)
    }
    /// Distinctness-of-image receptor.
    pub fn doi_receptor() -> Aperture {
        Aperture::from_deg(0.1, 3.0)
    }
    /// Offset of the DOI receptors from specular, degrees.
    pub const DOI_OFFSET_DEG: f64 = 0.3;
    /// Offset of the haze receptors from specular, degrees.
    pub const HAZE_OFFSET_DEG: f64 = 2.0;
}

/// What a gloss meter and an E430 appearance meter read on a specimen.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GlossReport {
    /// Specular gloss at 20°, 60°, 85° in gloss units.
    pub gu20: f64,
    pub gu60: f64,
    pub gu85: f64,
    /// Reflection haze: `100 · rho(±2°) / rho_standard(30°)`, mean of both sides.
    pub haze: f64,
    /// Distinctness of image: `100 · (rho_s - rho(±0.3°)) / rho_s`, mean of both sides; 100 for
    /// a perfect mirror.
    pub doi: f64,
}

/// Measure gloss at 20/60/85°, haze and DOI.
pub fn measure(specimen: &dyn Specimen) -> Result<GlossReport> {
    let gu = |deg| gloss_units(specimen, &Geometry::iso2813(deg).expect("ISO 2813 angle"));
    let theta = e430::THETA_DEG.to_radians();
    let at = |offset_deg: f64, aperture: Aperture| Window {
        centre: theta + offset_deg.to_radians(),
        aperture,
    };
    let (doi, haze) = (e430::DOI_OFFSET_DEG, e430::HAZE_OFFSET_DEG);
    let windows = [
        at(0.0, e430::receptor()),
        at(doi, e430::doi_receptor()),
        at(-doi, e430::doi_receptor()),
        at(haze, e430::receptor()),
        at(-haze, e430::receptor()),
    ];
    let r = readings(theta, e430::source(), &windows, specimen)?;
    let standard = readings(
        theta,
        e430::source(),
        &windows[..1],
        &Smooth(Ior::Dielectric(STANDARD_INDEX)),
    )?[0];
    let (specular, near, far) = (r[0], 0.5 * (r[1] + r[2]), 0.5 * (r[3] + r[4]));
    Ok(GlossReport {
        gu20: gu(20)?,
        gu60: gu(60)?,
        gu85: gu(85)?,
        haze: 100.0 * far / standard,
        doi: if specular > 0.0 {
            100.0 * (specular - near) / specular
        } else {
            0.0
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// physics.md: a perfectly smooth n = 1.55 surface reads 95.4, 97.3 and 99.8 GU.
    #[test]
    fn smooth_surface_gloss() {
        let r = measure(&Smooth(Ior::Dielectric(1.55))).unwrap();
        assert!((r.gu20 - 95.4).abs() < 0.05, "{}", r.gu20);
        assert!((r.gu60 - 97.3).abs() < 0.05, "{}", r.gu60);
        assert!((r.gu85 - 99.8).abs() < 0.05, "{}", r.gu85);
        assert_eq!(r.haze, 0.0);
        assert_eq!(r.doi, 100.0);
        let std = measure(&Smooth(Ior::Dielectric(STANDARD_INDEX))).unwrap();
        assert!((std.gu60 - 100.0).abs() < 1e-12);
    }

    /// The microfacet model of physics.md (Beckmann D, height-correlated Smith G2, Fresnel at
    /// the local angle), f in 1/sr.
    fn microfacet(m: f64, n: f64) -> impl Fn(DVec3, DVec3) -> f64 + Sync {
        move |wi: DVec3, wo: DVec3| {
            let h = (wi + wo).normalize();
            let r = gonio_brdf::fresnel::dielectric(wi.dot(h), n);
            let d = gonio_brdf::microfacet::beckmann_d(h.z, m);
            let g = gonio_brdf::microfacet::smith_g2(wi.z, wo.z, m);
            r * d * g / (4.0 * wi.z * wo.z)
        }
    }

    /// Independent check of the meter's Gauss-Legendre integration: a plain midpoint rule on a
    /// fine grid over both apertures, written out here from the definitions (irradiance-weighted
    /// mean over the source of `∫ f cos dω` over the receptor). The ISO receptors are wide
    /// compared with these lobes' curvature, so a 100 × 100 midpoint grid is accurate to ~1e-3.
    fn midpoint_reading(f: &dyn Fn(DVec3, DVec3) -> f64, g: &Geometry) -> f64 {
        let dir = |a: f64, b: f64| DVec3::new(b.cos() * a.sin(), b.sin(), b.cos() * a.cos());
        let grid = |centre: f64, width: f64, n: usize| -> Vec<f64> {
            (0..n)
                .map(|i| centre - 0.5 * width + (i as f64 + 0.5) * width / n as f64)
                .collect()
        };
        let (ns, nr) = (8, 100);
        let (mut sum, mut norm) = (0.0, 0.0);
        for bs in grid(0.0, g.source.perpendicular, ns) {
            for a_s in grid(-g.theta, g.source.in_plane, ns) {
                let wi = dir(a_s, bs);
                let weight = wi.z * bs.cos();
                let mut rho = 0.0;
                for br in grid(0.0, g.receptor.aperture.perpendicular, nr) {
                    for ar in grid(g.receptor.centre, g.receptor.aperture.in_plane, nr) {
                        let wo = dir(ar, br);
                        rho += f(wi, wo) * wo.z * br.cos();
                    }
                }
                let cell = g.receptor.aperture.in_plane * g.receptor.aperture.perpendicular
                    / (nr * nr) as f64;
                sum += weight * rho * cell;
                norm += weight;
            }
        }
        sum / norm
    }

    /// Issue 8: gloss of analytic Beckmann surfaces of several roughnesses agrees with an
    /// independent numerical integration of the microfacet model over the apertures within 1%.
    #[test]
    fn beckmann_gloss_matches_independent_integration() {
        let standard =
            |g: &Geometry| gonio_brdf::fresnel::dielectric(g.theta.cos(), STANDARD_INDEX);
        for m in [0.02, 0.05, 0.15] {
            let f = microfacet(m, 1.55);
            let specimen = BrdfSpecimen::new(microfacet(m, 1.55));
            for deg in [20, 60, 85] {
                let g = Geometry::iso2813(deg).unwrap();
                let ours = gloss_units(&specimen, &g).unwrap();
                // The smooth standard's reading is R at each source direction's own angle; the
                // source is 0.75° wide, so R(theta) differs from it by far less than 0.1%.
                let reference = 100.0 * midpoint_reading(&f, &g) / standard(&g);
                assert!(
                    (ours / reference - 1.0).abs() < 0.01,
                    "m = {m}, {deg}°: {ours} GU vs {reference} GU"
                );
                assert!(ours > 0.0 && ours < 100.0);
            }
        }
    }

    /// A Lambertian specimen of albedo 1: each reading is `(1/π) ∫ cos dω` over the receptor,
    /// which for small apertures is `cos(theta) Ω / π`.
    #[test]
    fn lambertian_reading_is_projected_solid_angle() {
        let lambert = BrdfSpecimen::new(|_wi: DVec3, _wo: DVec3| std::f64::consts::FRAC_1_PI);
        let g = Geometry::iso2813(60).unwrap();
        let omega =
            g.receptor.aperture.in_plane * 2.0 * (0.5 * g.receptor.aperture.perpendicular).sin();
        let expect = g.theta.cos() * omega / std::f64::consts::PI;
        let got = g.reading(&lambert).unwrap();
        assert!((got / expect - 1.0).abs() < 2e-3, "{got} vs {expect}");
    }
}
