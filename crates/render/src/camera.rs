//! The camera: a position, a point it looks at, an up direction, and either a vertical field of
//! view (a pinhole) or the height of the field it sees (orthographic: a camera at infinity, every
//! ray parallel to the view direction, pbrt-v4 §5.1.4); rays through the film at continuous
//! pixel coordinates (x right, y down from the top-left corner).

use crate::geometry::Ray;
use glam::{DVec2, DVec3};

/// How a camera's film maps onto rays.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Projection {
    /// A pinhole: `tan(fov/2)`.
    Perspective { tan_half: f64 },
    /// Parallel rays from the plane through `position` normal to the view: half the height of
    /// the field seen, m.
    Orthographic { half_height: f64 },
}

/// A camera.
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
    /// How the film maps onto rays.
    projection: Projection,
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
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return None;
        }
        let tan_half = (0.5 * fov_deg.to_radians()).tan();
        Camera::with(
            position,
            look_at,
            up,
            Projection::Perspective { tan_half },
            width,
            height,
        )
    }

    /// An orthographic camera at `position` looking toward `look_at` along parallel rays, `up`
    /// toward the top of the image, seeing a field `field_height` m high (the width follows the
    /// image's aspect). `None` when the view direction is zero or parallel to `up`, or the field
    /// is not positive.
    pub fn orthographic(
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        field_height: f64,
        width: usize,
        height: usize,
    ) -> Option<Camera> {
        if !(field_height > 0.0 && field_height.is_finite()) {
            return None;
        }
        let projection = Projection::Orthographic {
            half_height: 0.5 * field_height,
        };
        Camera::with(position, look_at, up, projection, width, height)
    }

    fn with(
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        projection: Projection,
        width: usize,
        height: usize,
    ) -> Option<Camera> {
        let forward = (look_at - position).normalize_or_zero();
        let right = forward.cross(up).normalize_or_zero();
        if forward == DVec3::ZERO || right == DVec3::ZERO {
            return None;
        }
        Some(Camera {
            position,
            forward,
            right,
            up: right.cross(forward),
            projection,
            width,
            height,
        })
    }

    /// The unit viewing direction.
    pub fn forward(&self) -> DVec3 {
        self.forward
    }

    /// The ray through the film point `film` (pixels; (0, 0) is the top-left corner of the
    /// top-left pixel).
    pub fn ray(&self, film: DVec2) -> Ray {
        let (w, h) = (self.width as f64, self.height as f64);
        let sx = (2.0 * film.x / w - 1.0) * w / h;
        let sy = 1.0 - 2.0 * film.y / h;
        match self.projection {
            Projection::Perspective { tan_half } => Ray {
                origin: self.position,
                dir: (self.forward + tan_half * (sx * self.right + sy * self.up)).normalize(),
            },
            Projection::Orthographic { half_height } => Ray {
                origin: self.position + half_height * (sx * self.right + sy * self.up),
                dir: self.forward,
            },
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
        // The field's half-height at the point's depth.
        let half = match self.projection {
            Projection::Perspective { tan_half } => z * tan_half,
            Projection::Orthographic { half_height } => half_height,
        };
        let sx = d.dot(self.right) / (half * w / h);
        let sy = d.dot(self.up) / half;
        Some(DVec2::new((sx + 1.0) * 0.5 * w, (1.0 - sy) * 0.5 * h))
    }
}
