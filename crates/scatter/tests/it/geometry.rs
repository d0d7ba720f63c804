//! Goniometer geometry: the STARR aperture's solid angle, the specular direction of an incidence.

use glam::DVec3;
use gonio_scatter::geometry::*;

/// A cone of half-angle alpha = 1.4° (the STARR aperture) subtends
/// `Omega = 2π(1 - cos alpha) = 1.8756e-3` sr.
#[test]
fn starr_aperture_solid_angle() {
    let omega = cone_solid_angle(1.4f64.to_radians());
    assert!((omega - 1.8756e-3).abs() < 5e-8, "{omega}");
}

#[test]
fn specular_of_incidence_is_positive_scatter() {
    let ti = 0.3;
    let wi = incidence_direction(ti);
    let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
    assert!((mirror - inplane_direction(ti)).length() < 1e-15);
    assert!((spherical_direction(ti, 0.0) - inplane_direction(ti)).length() < 1e-15);
}
