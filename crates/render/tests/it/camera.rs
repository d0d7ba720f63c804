//! The pinhole and orthographic cameras: the ray through a film point and the projection of a point back onto
//! the film.

use glam::{DVec2, DVec3};
use gonio_render::camera::Camera;

#[test]
fn centre_ray_looks_at_target_and_projection_inverts_rays() {
    let cam = Camera::new(
        DVec3::new(0.0, 1.0, 5.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::Y,
        40.0,
        200,
        100,
    )
    .unwrap();
    let r = cam.ray(DVec2::new(100.0, 50.0));
    assert!((r.dir - DVec3::NEG_Z).length() < 1e-12);
    // The top edge of the film is fov/2 above the axis.
    let top = cam.ray(DVec2::new(100.0, 0.0));
    assert!((top.dir.y.asin().to_degrees() - 20.0).abs() < 1e-9);
    let film = DVec2::new(37.5, 81.25);
    let r = cam.ray(film);
    let back = cam.project(r.origin + 3.0 * r.dir).unwrap();
    assert!((back - film).length() < 1e-9);
    assert!(Camera::new(DVec3::ZERO, DVec3::Y, DVec3::Y, 40.0, 1, 1).is_none());
}

/// The orthographic camera: every ray parallel to the view, the film's centre on the axis
/// through `look_at`, the top edge half the field above it, and projection inverts rays.
#[test]
fn orthographic_rays_are_parallel_and_projection_inverts_them() {
    let cam = Camera::orthographic(
        DVec3::new(0.0, 3.0, 0.0),
        DVec3::ZERO,
        DVec3::Z,
        0.5,
        40,
        20,
    )
    .unwrap();
    let centre = cam.ray(DVec2::new(20.0, 10.0));
    assert!((centre.origin - DVec3::new(0.0, 3.0, 0.0)).length() < 1e-12);
    for film in [DVec2::new(0.0, 0.0), DVec2::new(33.3, 7.1)] {
        let r = cam.ray(film);
        assert!((r.dir - DVec3::NEG_Y).length() < 1e-12);
        let back = cam.project(r.origin + 2.0 * r.dir).unwrap();
        assert!((back - film).length() < 1e-9);
    }
    // The top edge is 0.25 m above the axis (along +z), the right edge 0.5 m across.
    assert!((cam.ray(DVec2::new(20.0, 0.0)).origin.z - 0.25).abs() < 1e-12);
    assert!((cam.ray(DVec2::new(40.0, 10.0)).origin.x.abs() - 0.5).abs() < 1e-12);
    assert!(Camera::orthographic(DVec3::ZERO, DVec3::Y, DVec3::Z, 0.0, 1, 1).is_none());
}
