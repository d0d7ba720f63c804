//! The ray a facet sends out: what a facet's tracer ([`super::trace`]) produces and the
//! direction index ([`super::index`]) and the hemisphere tables sort, a leaf that they all use.

use glam::DVec3;

/// A ray leaving a facet, reflected or refracted, with its share of the incident power
/// (unpolarised, and for s and p polarisation when asked for).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ray {
    /// Unit direction in the detectors' frame: `z > 0` for a reflected ray, `z < 0` for a
    /// refracted one (until a transmission table mirrors it).
    pub d: DVec3,
    /// Unpolarised share carried (reflectance or transmittance).
    pub w: f64,
    /// Share carried for s polarisation (0 unless polarisation is tracked).
    pub ws: f64,
    /// Share carried for p polarisation (0 unless polarisation is tracked).
    pub wp: f64,
}
