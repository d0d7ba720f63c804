//! The reflected ray: what a facet's tracer ([`super::trace`]) produces and the direction
//! index ([`super::index`]) sorts, a leaf that both use.

use glam::DVec3;

/// A reflected ray leaving the surface, with its share of the reflectance (unpolarised, and
/// for s and p polarisation when asked for).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ray {
    /// Unit direction, `z > 0`, in the detectors' frame.
    pub d: DVec3,
    /// Unpolarised reflectance carried.
    pub w: f64,
    /// Reflectance carried for s polarisation (0 unless polarisation is tracked).
    pub ws: f64,
    /// Reflectance carried for p polarisation (0 unless polarisation is tracked).
    pub wp: f64,
}
