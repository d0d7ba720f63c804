//! The pinhole camera: a position, a point it looks at, an up direction and a vertical field of
//! view; rays through the film at continuous pixel coordinates (x right, y down from the top-left
//! corner).

use crate::geometry::Ray;
use glam::{DVec2, DVec3};

/// A pinhole camera.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// Centre of projection, m.
    pub position: DVec3,
    /// Unit viewing direction.
    forward: DVec3,
    /// Unit vector to the right of the image.
    right: DVec3,
    /// Unit vector to the top of the image.
    up: DVec3,
    /// `tan(fov/2)`.
    tan_half: f64,
    /// Image size in pixels.
    pub width: usize,
    pub height: usize,
}

impl Camera {
    /// A camera at `position` looking at `look_at`, with `up` toward the top of the image and a
    /// vertical field of view `fov_deg`. `None` when the view direction is zero or parallel to
    /// `up`, or the field of view is not in (0, 180)°.
    pub fn new(
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        fov_deg: f64,
        width: usize,
        height: usize,
    ) -> Option<Camera> {
        let forward = (look_at - position).normalize_or_zero();
        let right = forward.cross(up).normalize_or_zero();
        if forward == DVec3::ZERO || right == DVec3::ZERO || !(fov_deg > 0.0 && fov_deg < 180.0) {
            return None;
        }
        Some(Camera {
            position,
            forward,
            right,
            up: right.cross(forward),
            tan_half: (0.5 * fov_deg.to_radians()).tan(),
            width,
            height,
        })
    }

    /// The ray through the film point `film` (pixels; (0, 0) is the top-left corner of the
    /// top-left pixel).
    pub fn ray(&self, film: DVec2) -> Ray {
        let (w, h) = (self.width as f64, self.height as f64);
        let sx = (2.0 * film.x / w - 1.0) * self.tan_half * w / h;
        let sy = (1.0 - 2.0 * film.y / h) * self.tan_half;
        Ray {
            origin: self.position,
            dir: (self.forward + sx * self.right + sy * self.up).normalize(),
        }
    }

    /// The film point that `p` projects to, `None` behind the camera.
    pub fn project(&self, p: DVec3) -> Option<DVec2> {
        let d = p - self.position;
        let z = d.dot(self.forward);
        if z <= 0.0 {
            return None;
        }
        let (w, h) = (self.width as f64, self.height as f64);
        let sx = d.dot(self.right) / z / (self.tan_half * w / h);
        let sy = d.dot(self.up) / z / self.tan_half;
        Some(DVec2::new((sx + 1.0) * 0.5 * w, (1.0 - sy) * 0.5 * h))
    }
}
