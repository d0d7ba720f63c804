//! The conformance scenes' geometry: the pinhole camera and its pixels' rays, the shapes
//! (spheres and rectangles) and where a ray meets them, shared by the reference picture
//! ([`crate::reference`]) and every renderer's writer.

use crate::scene::SIZE;
use glam::DVec3;
use serde::Serialize;

/// The pinhole camera.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Camera {
    /// Where it is, m.
    pub position: [f64; 3],
    /// The point at the picture's centre, m.
    pub look_at: [f64; 3],
    /// Toward the picture's top.
    pub up: [f64; 3],
    /// Vertical (= horizontal) field of view, degrees.
    pub fov_deg: f64,
}

impl Camera {
    /// The unit direction through film point (fx, fy) (pixels, (0, 0) the top-left corner).
    pub fn ray(&self, fx: f64, fy: f64) -> DVec3 {
        let forward = (DVec3::from(self.look_at) - DVec3::from(self.position)).normalize();
        let right = forward.cross(DVec3::from(self.up)).normalize();
        let up = right.cross(forward);
        let t = (0.5 * self.fov_deg.to_radians()).tan();
        let n = SIZE as f64;
        let sx = (2.0 * fx / n - 1.0) * t;
        let sy = (1.0 - 2.0 * fy / n) * t;
        (forward + sx * right + sy * up).normalize()
    }
}

/// A shape.
#[derive(Debug, Clone, Copy, Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Geometry {
    /// A sphere.
    Sphere { center: [f64; 3], radius: f64 },
    /// A rectangle `2 half[0]` × `2 half[1]` in the x-y plane (normal +z), turned by
    /// `rotate_x_deg` about +x, then moved to `center`.
    Rectangle {
        center: [f64; 3],
        half: [f64; 2],
        rotate_x_deg: f64,
    },
}

impl Geometry {
    /// The distance along `dir` from `origin` to the first hit, with the local coordinates of
    /// the hit (a rectangle's (u, v) over its half sizes; a sphere's outward normal).
    pub(crate) fn hit(&self, origin: DVec3, dir: DVec3) -> Option<(f64, Local)> {
        match *self {
            Geometry::Sphere { center, radius } => {
                let oc = origin - DVec3::from(center);
                let b = oc.dot(dir);
                let disc = b * b - (oc.length_squared() - radius * radius);
                if disc <= 0.0 {
                    return None;
                }
                let t = -b - disc.sqrt();
                (t > 1e-9).then(|| {
                    let n = (oc + t * dir) / radius;
                    (t, Local::Sphere { normal: n })
                })
            }
            Geometry::Rectangle {
                center,
                half,
                rotate_x_deg,
            } => {
                let (ex, ey, n) = rect_frame(rotate_x_deg);
                let denom = dir.dot(n);
                if denom.abs() < 1e-12 {
                    return None;
                }
                let t = (DVec3::from(center) - origin).dot(n) / denom;
                if t <= 1e-9 {
                    return None;
                }
                let p = origin + t * dir - DVec3::from(center);
                let (u, v) = (p.dot(ex) / half[0], p.dot(ey) / half[1]);
                (u.abs() <= 1.0 && v.abs() <= 1.0).then_some((
                    t,
                    Local::Rectangle {
                        u,
                        v,
                        normal: n,
                        front: denom < 0.0,
                    },
                ))
            }
        }
    }
}

/// The frame of a rectangle turned by `deg` about +x: its first and second axes and normal.
pub fn rect_frame(deg: f64) -> (DVec3, DVec3, DVec3) {
    let (s, c) = deg.to_radians().sin_cos();
    (DVec3::X, DVec3::new(0.0, c, s), DVec3::new(0.0, -s, c))
}

/// Where a ray met a shape.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Local {
    Sphere {
        normal: DVec3,
    },
    Rectangle {
        u: f64,
        v: f64,
        normal: DVec3,
        front: bool,
    },
}
