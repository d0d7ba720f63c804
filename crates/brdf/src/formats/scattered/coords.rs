//! The regression coordinates of a scattered fit (the module docs of [`super`]): regular at the
//! specular direction and round within its core.

use super::DIM;
use crate::table::HalfDiff;
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI};

/// The `(u, t, s cos p, s sin p)` coordinates of a pair of directions (module docs).
pub fn coordinates(wi: DVec3, wo: DVec3) -> Option<[f64; DIM]> {
    let a = HalfDiff::from_dirs(wi, wo)?;
    Some(coordinates_of(&a, mirror_angle(wi, wo)))
}

/// The angle between `wo` and the mirror direction of `wi` (radians; the same with `wi` and
/// `wo` exchanged, the mirror being an isometry and its own inverse).
pub fn mirror_angle(wi: DVec3, wo: DVec3) -> f64 {
    let wr = DVec3::new(-wi.x, -wi.y, wi.z);
    wo.cross(wr).length().atan2(wo.dot(wr))
}

pub(super) fn coordinates_of(a: &HalfDiff, delta: f64) -> [f64; DIM] {
    let mut p = a.phi_d.rem_euclid(2.0 * PI);
    if p > PI {
        p = 2.0 * PI - p;
    }
    let t = a.theta_d / FRAC_PI_2;
    let d = delta.max(0.0);
    let u = ((d + ROUND_CORE) / PI).sqrt() - (ROUND_CORE / PI).sqrt();
    let s = ((d - ROUND_CORE) / PI).max(0.0) * t;
    [u, t, s * p.cos(), s * p.sin()]
}

/// Angle from the mirror direction (radians) below which the fit cannot depend on `phi_d`: the
/// core of the specular peak is round. 2°: the Cornell paint files have one geometry per
/// incidence within 2° of the specular direction (in the plane of incidence, on one side of
/// the peak), so nothing in them tells the azimuths about it apart; and a peak narrower than
/// the instrument's circular aperture is measured as the aperture's round image.
pub const ROUND_CORE: f64 = 2.0 * PI / 180.0;
