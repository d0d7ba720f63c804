//! Shapes and their intersection: spheres, planar patches (rectangles and disks, after any
//! affine transform a parallelogram or an ellipse) and triangles, gathered in a bounding volume
//! hierarchy (the compressed 8-wide BVH of the `obvhs` crate, Ylitie et al., "Efficient incoherent
//! ray traversal on GPUs through compressed wide BVHs", HPG 2017). Traversal runs in f32; every
//! intersection is computed in f64 from the exact primitive, so that hit points are precise.

use glam::{DAffine3, DMat3, DVec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as BvhRay, RayHit};

/// A ray `origin + t dir`, `dir` of unit length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
}

/// The geometric form of a primitive, in world space.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere { centre: DVec3, radius: f64 },
    /// The points `origin + a u + b v` with `|a|, |b| <= 1` (rectangle) or `a² + b² <= 1`
    /// (disk); its normal is `u × v` normalised.
    Planar {
        origin: DVec3,
        u: DVec3,
        v: DVec3,
        disk: bool,
    },
    /// A triangle, with optional vertex normals for smooth shading.
    Triangle {
        p: [DVec3; 3],
        n: Option<[DVec3; 3]>,
    },
}

/// What a ray hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f64,
    /// The point.
    pub p: DVec3,
    /// Geometric normal (unit, on the shape's front side).
    pub ng: DVec3,
    /// Shading normal (unit, same side as `ng`).
    pub ns: DVec3,
    /// A unit tangent perpendicular to `ns` (the first axis of anisotropic BRDFs).
    pub tangent: DVec3,
    /// Index of the primitive in the scene.
    pub prim: usize,
}

impl Shape {
    /// Distance to the nearest intersection in `(t_min, t_max)`.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        match self {
            Shape::Sphere { centre, radius } => {
                // Numerically careful quadratic (pbrt-v4 §6.2.2 / Ray Tracing Gems ch. 7).
                let f = ray.origin - *centre;
                let b = -f.dot(ray.dir);
                let perp = f + b * ray.dir;
                let disc = radius * radius - perp.length_squared();
                if disc < 0.0 {
                    return None;
                }
                let s = disc.sqrt();
                let c = f.length_squared() - radius * radius;
                let q = b + s.copysign(b);
                if q == 0.0 {
                    return None;
                }
                let (t0, t1) = (c / q, q);
                let (t0, t1) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
                [t0, t1].into_iter().find(|&t| t > t_min && t < t_max)
            }
            Shape::Planar { origin, u, v, disk } => {
                let n = u.cross(*v);
                let denom = n.dot(ray.dir);
                if denom == 0.0 {
                    return None;
                }
                let t = (*origin - ray.origin).dot(n) / denom;
                if !(t > t_min && t < t_max) {
                    return None;
                }
                let (a, b) = planar_coords(*origin, *u, *v, ray.origin + t * ray.dir);
                let inside = if *disk {
                    a * a + b * b <= 1.0
                } else {
                    a.abs() <= 1.0 && b.abs() <= 1.0
                };
                inside.then_some(t)
            }
            Shape::Triangle { p, .. } => {
                // Möller & Trumbore, "Fast, minimum storage ray/triangle intersection", JGT 1997.
                let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
                let pv = ray.dir.cross(e2);
                let det = e1.dot(pv);
                if det.abs() < 1e-300 {
                    return None;
                }
                let inv = 1.0 / det;
                let tv = ray.origin - p[0];
                let a = tv.dot(pv) * inv;
                if !(0.0..=1.0).contains(&a) {
                    return None;
                }
                let qv = tv.cross(e1);
                let b = ray.dir.dot(qv) * inv;
                if b < 0.0 || a + b > 1.0 {
                    return None;
                }
                let t = e2.dot(qv) * inv;
                (t > t_min && t < t_max).then_some(t)
            }
        }
    }

    /// The hit record at distance `t` along `ray`.
    pub fn hit(&self, ray: &Ray, t: f64, prim: usize) -> Hit {
        let p = ray.origin + t * ray.dir;
        let (ng, ns, tangent_hint) = match self {
            Shape::Sphere { centre, .. } => {
                let n = (p - *centre).normalize();
                (n, n, DVec3::new(-n.z, 0.0, n.x))
            }
            Shape::Planar { u, v, .. } => {
                let n = u.cross(*v).normalize();
                (n, n, *u)
            }
            Shape::Triangle { p: v, n } => {
                let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
                let ng = e1.cross(e2).normalize();
                let ns = match n {
                    Some(n) => {
                        let (a, b) = barycentric(v, p);
                        let s = (1.0 - a - b) * n[0] + a * n[1] + b * n[2];
                        let s = s.normalize_or_zero();
                        if s == DVec3::ZERO {
                            ng
                        } else if s.dot(ng) < 0.0 {
                            -s
                        } else {
                            s
                        }
                    }
                    None => ng,
                };
                (ng, ns, e1)
            }
        };
        let t_perp = tangent_hint - ns * tangent_hint.dot(ns);
        let tangent = if t_perp.length_squared() > 1e-20 {
            t_perp.normalize()
        } else {
            gonio_brdf::sampling::Frame::from_z(ns).s
        };
        Hit {
            t,
            p,
            ng,
            ns,
            tangent,
            prim,
        }
    }

    /// Surface area in m².
    pub fn area(&self) -> f64 {
        match self {
            Shape::Sphere { radius, .. } => 4.0 * std::f64::consts::PI * radius * radius,
            Shape::Planar { u, v, disk, .. } => {
                let a = u.cross(*v).length();
                if *disk {
                    std::f64::consts::PI * a
                } else {
                    4.0 * a
                }
            }
            Shape::Triangle { p, .. } => 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length(),
        }
    }

    /// Axis-aligned bounds, padded so that the f32 traversal never misses a hit.
    pub(crate) fn bounds(&self) -> (DVec3, DVec3) {
        let (lo, hi) = match self {
            Shape::Sphere { centre, radius } => (*centre - *radius, *centre + *radius),
            Shape::Planar { origin, u, v, .. } => {
                let ext = u.abs() + v.abs();
                (*origin - ext, *origin + ext)
            }
            Shape::Triangle { p, .. } => (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2])),
        };
        let pad = 1e-5 * (1.0 + lo.abs().max(hi.abs()).max_element());
        (lo - pad, hi + pad)
    }

    /// The shape moved by `m` (a sphere needs a uniform scale: `None` otherwise).
    pub fn transformed(&self, m: &DAffine3) -> Option<Shape> {
        Some(match self {
            Shape::Sphere { centre, radius } => {
                let cols = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis];
                let s = cols[0].length();
                if cols.iter().any(|c| (c.length() - s).abs() > 1e-9 * s)
                    || (m.matrix3.x_axis.dot(m.matrix3.y_axis)).abs() > 1e-9 * s * s
                {
                    return None;
                }
                Shape::Sphere {
                    centre: m.transform_point3(*centre),
                    radius: radius * s,
                }
            }
            Shape::Planar { origin, u, v, disk } => Shape::Planar {
                origin: m.transform_point3(*origin),
                u: m.transform_vector3(*u),
                v: m.transform_vector3(*v),
                disk: *disk,
            },
            Shape::Triangle { p, n } => {
                let normal_m: DMat3 = m.matrix3.inverse().transpose();
                Shape::Triangle {
                    p: p.map(|q| m.transform_point3(q)),
                    n: n.map(|n| n.map(|q| (normal_m * q).normalize_or_zero())),
                }
            }
        })
    }
}

/// Coordinates `(a, b)` of `p` in the plane `origin + a u + b v` (through the dual basis).
pub fn planar_coords(origin: DVec3, u: DVec3, v: DVec3, p: DVec3) -> (f64, f64) {
    let n = u.cross(v);
    let n2 = n.length_squared();
    let q = p - origin;
    (q.dot(v.cross(n)) / n2, q.dot(n.cross(u)) / n2)
}

/// Barycentric weights `(b1, b2)` of vertices 1 and 2 at the point `p` of the triangle.
fn barycentric(v: &[DVec3; 3], p: DVec3) -> (f64, f64) {
    let (e1, e2, q) = (v[1] - v[0], v[2] - v[0], p - v[0]);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (q1, q2) = (q.dot(e1), q.dot(e2));
    let det = d11 * d22 - d12 * d12;
    if det == 0.0 {
        return (0.0, 0.0);
    }
    ((d22 * q1 - d12 * q2) / det, (d11 * q2 - d12 * q1) / det)
}

struct Bounded(Aabb);

impl obvhs::Boundable for Bounded {
    fn aabb(&self) -> Aabb {
        self.0
    }
}

/// The primitives of a scene with their BVH (none for a scene of at most [`LINEAR_MAX`]
/// primitives, which are tested one by one).
pub struct Accel {
    shapes: Vec<Shape>,
    bvh: Option<CwBvh>,
}

/// The most primitives a scene tests one by one instead of through a BVH: on a scene of one
/// sphere the traversal cost about 470 instructions a ray beyond the sphere's own test, about
/// 120 (callgrind, `crates/render/benches/versus_mitsuba.py`'s scene), so a handful of tests
/// costs less than one traversal.
const LINEAR_MAX: usize = 4;

impl Accel {
    /// Build the hierarchy over `shapes`.
    pub fn new(shapes: Vec<Shape>) -> Accel {
        let bvh = (shapes.len() > LINEAR_MAX).then(|| {
            let boxes: Vec<Bounded> = shapes
                .iter()
                .map(|s| {
                    let (lo, hi) = s.bounds();
                    Bounded(Aabb::new(lo.as_vec3a(), hi.as_vec3a()))
                })
                .collect();
            obvhs::cwbvh::builder::build_cwbvh(
                &boxes,
                obvhs::BvhBuildParams::medium_build(),
                &mut std::time::Duration::default(),
            )
        });
        Accel { shapes, bvh }
    }

    /// The primitives, in the order given to [`Accel::new`].
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    fn bvh_ray(ray: &Ray, t_min: f64, t_max: f64) -> BvhRay {
        BvhRay::new(
            ray.origin.as_vec3a(),
            Vec3A::from(ray.dir.as_vec3()),
            t_min as f32,
            if t_max.is_finite() {
                (t_max * (1.0 + 1e-5)) as f32 + 1e-5
            } else {
                f32::INFINITY
            },
        )
    }

    /// The nearest hit in `(t_min, t_max)`.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let mut best: Option<(f64, usize)> = None;
        let Some(bvh) = self.bvh.as_ref() else {
            for (prim, shape) in self.shapes.iter().enumerate() {
                let limit = best.map_or(t_max, |b| b.0);
                if let Some(t) = shape.intersect(ray, t_min, limit) {
                    best = Some((t, prim));
                }
            }
            return best.map(|(t, prim)| self.shapes[prim].hit(ray, t, prim));
        };
        let mut hit = RayHit::none();
        bvh.ray_traverse(Self::bvh_ray(ray, t_min, t_max), &mut hit, |_, id| {
            let prim = bvh.primitive_indices[id] as usize;
            let limit = best.map_or(t_max, |b| b.0);
            match self.shapes[prim].intersect(ray, t_min, limit) {
                Some(t) => {
                    best = Some((t, prim));
                    t as f32
                }
                None => f32::INFINITY,
            }
        });
        best.map(|(t, prim)| self.shapes[prim].hit(ray, t, prim))
    }

    /// Whether anything lies on the ray in `(t_min, t_max)`.
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return self
                .shapes
                .iter()
                .any(|s| s.intersect(ray, t_min, t_max).is_some());
        };
        !bvh.ray_traverse_miss(Self::bvh_ray(ray, t_min, t_max), |_, id| {
            let prim = bvh.primitive_indices[id] as usize;
            match self.shapes[prim].intersect(ray, t_min, t_max) {
                Some(_) => f32::NEG_INFINITY,
                None => f32::INFINITY,
            }
        })
    }
}
