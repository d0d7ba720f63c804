//! The pinhole camera: the ray through a film point and the projection of a point back onto
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
