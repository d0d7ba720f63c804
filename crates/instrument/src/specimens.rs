//! Specimens computed from a height map: the light a surface scatters, as a cloud of outgoing
//! directions each carrying its share of the reflectance (the ray method's reflected rays), read
//! by the virtual meters of [`crate::gloss`] exactly: a window collects the shares that fall in it.

use crate::error::Result;
use crate::gloss::{Specimen, Window};
use glam::{DVec2, DVec3};
use gonio_scatter::Detector;
use gonio_scatter::kirchhoff::Kirchhoff;
use gonio_scatter::ray::RayEngine;

/// The ray method as a gloss-meter specimen: every reflected ray counts in the windows it falls
/// in. One trace per source direction serves every receptor window of a geometry.
pub struct RaySpecimen<'a> {
    pub engine: &'a RayEngine,
}

/// Patches per side of the grid a map is split into for the statistical uncertainty of its
/// readings (16 patches; for the demo's 512² epoxy maps each is 128 points, 64 µm, about ten
/// correlation lengths wide, so that the patches are nearly independent samples).
const PATCHES_PER_SIDE: usize = 4;

impl Specimen for RaySpecimen<'_> {
    fn reflectance_into(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<f64>> {
        let rays = self.engine.reflected_rays(wi)?;
        Ok(collect(&rays, windows))
    }

    /// The rays counted by the patch of the map (a 4 × 4 grid over its extent) whose facet
    /// reflected them.
    fn reflectance_by_patch(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<Vec<f64>>> {
        const P: usize = PATCHES_PER_SIDE;
        let engine = self.engine;
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for i in 0..engine.facet_count() {
            let p = engine.facet_position(i).truncate();
            (lo, hi) = (lo.min(p), hi.max(p));
        }
        let span = (hi - lo).max(DVec2::splat(f64::MIN_POSITIVE));
        let patch = |facet: usize| {
            let q = (engine.facet_position(facet).truncate() - lo) / span * P as f64;
            (q.y as usize).min(P - 1) * P + (q.x as usize).min(P - 1)
        };
        let partials = engine.fold_rays(
            wi,
            || vec![vec![0.0; windows.len()]; P * P],
            |parts, rays| {
                for r in rays {
                    let row = &mut parts[patch(r.facet)];
                    for (s, w) in row.iter_mut().zip(windows) {
                        if w.contains(r.direction) {
                            *s += r.share;
                        }
                    }
                }
            },
        )?;
        // Partials in chunk order: the same sums on any number of threads.
        let mut parts = vec![vec![0.0; windows.len()]; P * P];
        for partial in partials {
            for (row, add) in parts.iter_mut().zip(partial) {
                for (s, a) in row.iter_mut().zip(add) {
                    *s += a;
                }
            }
        }
        Ok(parts)
    }

    /// The ray method is exact in direction, so a 3 × 3 rule over the source aperture (nine
    /// traces per geometry) averages the source as well as a finer one would at a ninth of the
    /// cost of 8 × 8.
    fn source_order(&self) -> usize {
        3
    }
}

/// The Kirchhoff approximation at one wavelength as a gloss-meter specimen: the scattered light
/// on the lattice of directions the illuminated spot resolves (spacing about λ/L for a spot of
/// diameter L), each lattice direction counting in the windows it falls in. A window must hold
/// several lattice directions to be read well: the 0.1° DOI slit needs a spot of about 0.5 mm at
/// 550 nm.
pub struct KirchhoffSpecimen<'a> {
    pub engine: &'a Kirchhoff,
    /// Wavelength in metres.
    pub wavelength: f64,
}

impl Specimen for KirchhoffSpecimen<'_> {
    fn reflectance_into(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<f64>> {
        let cloud =
            self.engine
                .scattered_in_cone(self.wavelength, wi, &bounding_cone(wi, windows))?;
        Ok(collect(&cloud, windows))
    }

    /// Each source direction costs a set of full-map FFTs, so a 2 × 2 rule averages the source.
    fn source_order(&self) -> usize {
        2
    }
}

/// A cone about the mirror direction of `wi` that holds every window: the angle from the mirror
/// direction to each window's centre plus the window's half-diagonal, with a 10% margin.
fn bounding_cone(wi: DVec3, windows: &[Window]) -> Detector {
    let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
    let reach = windows
        .iter()
        .map(|w| {
            let centre = DVec3::new(w.centre.sin(), 0.0, w.centre.cos());
            let half_diagonal = 0.5 * w.aperture.in_plane.hypot(w.aperture.perpendicular);
            mirror.dot(centre).clamp(-1.0, 1.0).acos() + half_diagonal
        })
        .fold(0.0f64, f64::max);
    Detector {
        direction: mirror,
        half_angle: (1.1 * reach).min(std::f64::consts::FRAC_PI_2),
    }
}

/// Sum the reflectance shares of `(direction, share)` pairs that fall in each window.
pub fn collect(cloud: &[(DVec3, f64)], windows: &[Window]) -> Vec<f64> {
    let mut sums = vec![0.0; windows.len()];
    for &(d, share) in cloud {
        for (s, w) in sums.iter_mut().zip(windows) {
            if w.contains(d) {
                *s += share;
            }
        }
    }
    sums
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gloss::{Smooth, measure};
    use gonio_brdf::Ior;
    use gonio_scatter::ray::RayOptions;
    use gonio_surface::HeightMap;
    use ndarray::Array2;

    /// A flat map through the ray method reads what the smooth-surface specimen reads: every
    /// facet mirrors the source, so gloss, haze and DOI agree to rounding.
    #[test]
    fn flat_map_reads_like_a_smooth_surface() {
        let map = HeightMap::new(Array2::zeros((32, 32)), 1e-6, 1e-6).unwrap();
        let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
        let ray = measure(&RaySpecimen { engine: &engine }).unwrap();
        let smooth = measure(&Smooth(Ior::Dielectric(1.55))).unwrap();
        for (a, b) in [
            (ray.gu20, smooth.gu20),
            (ray.gu60, smooth.gu60),
            (ray.gu85, smooth.gu85),
        ] {
            assert!((a - b).abs() < 1e-9 * b, "{a} vs {b}");
        }
        assert!((ray.gu60 - 97.3).abs() < 0.05);
        assert_eq!(ray.haze, 0.0);
        assert!((ray.doi - 100.0).abs() < 1e-9);
        // Every patch reads DOI 100; what is left is rounding.
        assert!(ray.doi_uncertainty < 1e-9, "{}", ray.doi_uncertainty);
    }

    /// A flat patch through the Kirchhoff approximation: the lobe is the spot's diffraction
    /// pattern, so the gloss is the smooth surface's within the energy the pattern puts outside
    /// the receptor. That pattern is about λ/(L cos θ) wide in the plane of incidence: for a
    /// 0.5 mm spot at 85° about 0.7°, well inside the 4° receptor (a 0.13 mm spot spreads it to
    /// 2.8° and reads 68 GU instead of 99.8: the demo's small maps are diffraction-limited at 85°).
    #[test]
    fn flat_patch_kirchhoff_gloss_is_smooth_gloss() {
        use gonio_scatter::kirchhoff::KirchhoffOptions;
        let map = HeightMap::new(Array2::zeros((512, 512)), 1e-6, 1e-6).unwrap();
        let engine = Kirchhoff::new(&map, KirchhoffOptions::new(Ior::Dielectric(1.55))).unwrap();
        let specimen = KirchhoffSpecimen {
            engine: &engine,
            wavelength: 550e-9,
        };
        let smooth = Smooth(Ior::Dielectric(1.55));
        for deg in [20, 60, 85] {
            let g = crate::gloss::Geometry::iso2813(deg).unwrap();
            let k = crate::gloss::gloss_units(&specimen, &g).unwrap();
            let s = crate::gloss::gloss_units(&smooth, &g).unwrap();
            assert!(
                (k / s - 1.0).abs() < 0.01,
                "{deg}°: Kirchhoff {k} GU vs smooth {s} GU"
            );
        }
    }

    /// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
    mod slow {
        use super::*;

        /// The DOI uncertainty the jackknife over the map's patches predicts is the spread DOI
        /// really has from one map of a surface to the next: eight maps of one Gaussian surface
        /// (Sq 201 nm, T 6 µm, 256² at 0.5 µm, the epoxy sample's statistics on a quarter of its
        /// area), whose 0.1° DOI slits catch few rays. The standard deviation of eight values is
        /// itself uncertain by about 1/√(2·7) = 27%, the mean jackknife estimate by a few per cent
        /// more; the bound, a factor 2 either way, is beyond three of those standard errors.
        #[test]
        fn doi_uncertainty_predicts_the_spread_between_maps() {
            use gonio_surface::synth::GaussianSurface;
            let (mut dois, mut predicted) = (Vec::new(), Vec::new());
            for seed in 1..=8 {
                let map = GaussianSurface::square(201e-9, 6e-6, 256, 0.5e-6, seed)
                    .generate()
                    .unwrap();
                let engine = RayEngine::new(&map, RayOptions::default()).unwrap();
                let r = measure(&RaySpecimen { engine: &engine }).unwrap();
                dois.push(r.doi);
                predicted.push(r.doi_uncertainty);
            }
            let mean = dois.iter().sum::<f64>() / 8.0;
            let spread = (dois.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / 7.0).sqrt();
            let u = predicted.iter().sum::<f64>() / 8.0;
            eprintln!("DOI {dois:.2?}: spread {spread:.2}, predicted {u:.2}");
            assert!(spread > 0.0 && u > 0.0);
            assert!(
                (0.5..=2.0).contains(&(spread / u)),
                "spread {spread} vs predicted {u}"
            );
        }
    }
}
