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
