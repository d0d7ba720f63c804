//! The booth as a scene: the specimen at the origin with its normal at the centre along +y,
//! the diffuse booth (the ceiling diffuser and the grey interior as an environment map, drawn as
//! [`crate::panel::Lighting::Booth`]'s with the spec's grey) and the directional light (a
//! distant, collimated source, [`Light::Distant`]) in the x-y plane on the +x side, both scaled
//! so that the illuminance on the specimen's centre is the spec's, and each view's camera.
//!
//! Units: with the absolute film ([`crate::Film::Absolute`]) a grey light value v is a luminance
//! of v cd/m² (a radiance) or an illuminance of v lx on a plane facing it (the distant light's
//! irradiance). The illuminance that the map of ceiling value 1 gives on the centre,
//! `E_map = Σ_pixels L_pixel ∫_pixel max(0, n·ω) dω` (n the centre's normal), is integrated
//! over each pixel of the map as the renderer sees it (piecewise constant), by the midpoint rule
//! on a 16 × 16 grid in (θ, φ) within each pixel (error of order (1.4°/16)² ≈ 2e-6 relative).
//! The map is then scaled by `(1 − f) E / E_map` and the distant light given the irradiance
//! `f E / cos θ_light`, E the spec's illuminance and f its directional fraction. The specimen's
//! own shadow is left out of `E_map`: the flat panel sees its whole hemisphere, and the curved
//! panel's centre is its crest.
//!
//! The views: the camera lies in the plane of incidence (x-y) at the polar angle
//! `θ_v = γ − θ_light` from the normal (γ the view's aspecular angle, positive toward the
//! light), looking at the centre, the image's up along +z (the specimen's depth), so the plane of
//! incidence runs across the image and no view is turned against another.

use super::spec::{Checked, Projection, Shape as SpecimenShape, View};
use crate::camera::Camera;
use crate::error::{RenderError, Result};
use crate::geometry::{Accel, Ray, Shape};
use crate::image::Display;
use crate::light::{EnvMap, Light};
use crate::material::Material;
use crate::mesoscale::Projections;
use crate::scene::{PrimKind, RenderDesc, Scene};
use glam::{DAffine3, DQuat, DVec3};
use gonio_brdf::Rgb;
use std::f64::consts::PI;

/// Where a view's camera is and how it projects.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewGeometry {
    /// The view's name (`near-specular`, `45`, `flank`, `asG`).
    pub name: String,
    /// Its aspecular angle γ, degrees.
    pub aspecular_deg: f64,
    /// The camera's polar angle from the specimen's normal, degrees, positive on the light's
    /// side: `γ − θ_light`.
    pub viewing_deg: f64,
    /// The directional light's polar angle, degrees.
    pub light_deg: f64,
    /// The camera's position (perspective) or the centre of its plane (orthographic), m.
    pub position_m: [f64; 3],
    /// The point at the image's centre, m (the specimen's centre, the origin).
    pub look_at_m: [f64; 3],
    /// Toward the top of the image.
    pub up: [f64; 3],
    /// How it projects.
    pub projection: Projection,
    /// The vertical field: degrees (perspective) or metres (orthographic).
    pub field: f64,
}

/// The booth's scene, the camera set per view.
pub(crate) struct BoothScene {
    pub scene: Scene,
    /// The number of the specimen's primitives (the first in the scene).
    pub specimen_prims: usize,
}

/// The map's directions: `(sin θ cos φ, cos θ, sin θ sin φ)`, +y up ([`crate::light`]).
fn direction(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    )
}

/// The unit vector in the plane of incidence at polar angle `deg` from +y, positive toward +x.
fn in_plane(deg: f64) -> DVec3 {
    let t = deg.to_radians();
    DVec3::new(t.sin(), t.cos(), 0.0)
}

/// The illuminance on a plane of normal `n` from `map` (scale 1), as the module says.
fn map_illuminance(map: &crate::image::Image, n: DVec3) -> f64 {
    const SUB: usize = 16;
    let (w, h) = (map.width, map.height);
    let (dt, dp) = (PI / h as f64, 2.0 * PI / w as f64);
    let mut total = 0.0;
    for j in 0..h {
        for i in 0..w {
            let l = crate::light::luminance(map.get(i, j));
            if l == 0.0 {
                continue;
            }
            let mut sum = 0.0;
            for a in 0..SUB {
                let theta = dt * (j as f64 + (a as f64 + 0.5) / SUB as f64);
                for b in 0..SUB {
                    let phi = dp * (i as f64 + (b as f64 + 0.5) / SUB as f64);
                    sum += n.dot(direction(theta, phi)).max(0.0) * theta.sin();
                }
            }
            total += l * sum * (dt * dp) / (SUB * SUB) as f64;
        }
    }
    total
}

/// The specimen's primitives: a flat panel (normal +y, the width along x) or the curved panel
/// scaled to the size (its height with the width), turned so that its normal at the centre is
/// +y and moved so that the centre is the origin.
fn specimen(shape: SpecimenShape, size_m: [f64; 2]) -> Result<Vec<Shape>> {
    let [w, d] = size_m;
    match shape {
        SpecimenShape::Flat => Ok(vec![Shape::Planar {
            origin: DVec3::ZERO,
            u: DVec3::Z * (0.5 * d),
            v: DVec3::X * (0.5 * w),
            disk: false,
        }]),
        SpecimenShape::Curved => {
            // examples/panel.obj: 2.4 m along x, 1.6 m along z, its crest at the top (+y).
            let scale = DAffine3::from_scale(DVec3::new(w / 2.4, w / 2.4, d / 1.6));
            let scaled: Vec<Shape> = crate::panel::mesh()
                .iter()
                .map(|s| s.transformed(&scale).expect("a mesh takes any scale"))
                .collect();
            let accel = Accel::new(scaled.clone());
            let down = Ray {
                origin: DVec3::new(0.0, 10.0, 0.0),
                dir: DVec3::NEG_Y,
            };
            let hit = accel.intersect(&down, 0.0, f64::INFINITY).ok_or_else(|| {
                RenderError::Invalid("the curved panel has no surface at its centre".into())
            })?;
            let n = if hit.ns.y < 0.0 { -hit.ns } else { hit.ns };
            let place = DAffine3::from_quat(DQuat::from_rotation_arc(n, DVec3::Y))
                * DAffine3::from_translation(-hit.p);
            Ok(scaled
                .iter()
                .map(|s| {
                    s.transformed(&place)
                        .expect("a mesh takes any rigid motion")
                })
                .collect())
        }
    }
}

impl BoothScene {
    /// The booth of `spec` with `material` on the specimen.
    pub fn new(spec: &Checked, material: Material) -> Result<BoothScene> {
        let shapes = specimen(spec.shape, spec.size_m)?;
        let specimen_prims = shapes.len();
        let mut projections = Projections::default();
        for _ in 0..specimen_prims {
            projections.push_prim(None);
        }
        let map = crate::panel::booth_map(spec.interior_reflectance);
        let map_illuminance = map_illuminance(&map, DVec3::Y);
        let e = spec.illuminance_lux;
        let f = spec.directional_fraction;
        let mut lights = Vec::new();
        if f < 1.0 {
            lights.push(Light::Environment(EnvMap::new(
                map,
                (1.0 - f) * e / map_illuminance,
                0.0,
            )));
        }
        if f > 0.0 {
            lights.push(Light::Distant {
                direction: in_plane(spec.directional_deg),
                irradiance: Rgb::splat(f * e / spec.directional_deg.to_radians().cos()),
            });
        }
        let camera = Camera::new(DVec3::Y, DVec3::ZERO, DVec3::Z, 30.0, 1, 1)
            .expect("a placeholder camera looking down");
        Ok(BoothScene {
            scene: Scene {
                camera,
                display: Display::default(),
                render: RenderDesc::default(),
                accel: Accel::new(shapes),
                prims: vec![PrimKind::Surface(0); specimen_prims],
                materials: vec![material],
                lights,
                projections,
            },
            specimen_prims,
        })
    }

    /// Point the camera for `view` of `spec` (`width` × `height` pixels), returning its
    /// geometry.
    pub fn set_view(
        &mut self,
        spec: &Checked,
        view: &View,
        width: usize,
        height: usize,
    ) -> ViewGeometry {
        let viewing_deg = view.aspecular_deg - spec.directional_deg;
        let toward = in_plane(viewing_deg);
        let up = DVec3::Z;
        let right = (-toward).cross(up);
        // The specimen's extent across and along the image, m: its bounds' corners.
        let (lo, hi) = self
            .scene
            .accel
            .shapes()
            .iter()
            .take(self.specimen_prims)
            .map(Shape::bounds)
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), (a, b)| {
                (l.min(a), h.max(b))
            });
        let corners = (0..8).map(|k| {
            DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        });
        let aspect = width as f64 / height as f64;
        // A fifth to spare around the specimen.
        const MARGIN: f64 = 1.2;
        let (position, projection, field, camera) = match spec.projection {
            Projection::Perspective => {
                let position = spec.distance_m * toward;
                let tan_half = corners
                    .map(|c| {
                        let d = c - position;
                        let z = d.dot(-toward);
                        (d.dot(up) / z).abs().max((d.dot(right) / z).abs() / aspect)
                    })
                    .fold(0.0, f64::max)
                    * MARGIN;
                let fov = 2.0 * tan_half.atan().to_degrees();
                let camera = Camera::new(position, DVec3::ZERO, up, fov, width, height);
                (position, Projection::Perspective, fov, camera)
            }
            Projection::Orthographic => {
                // The camera's plane clear of the specimen.
                let position = toward * (1.0 + 2.0 * (hi - lo).length());
                let half = corners
                    .map(|c| c.dot(up).abs().max(c.dot(right).abs() / aspect))
                    .fold(0.0, f64::max)
                    * MARGIN;
                let camera =
                    Camera::orthographic(position, DVec3::ZERO, up, 2.0 * half, width, height);
                (position, Projection::Orthographic, 2.0 * half, camera)
            }
        };
        self.scene.camera = camera.expect("the view direction lies in x-y, across +z");
        ViewGeometry {
            name: view.name.clone(),
            aspecular_deg: view.aspecular_deg,
            viewing_deg,
            light_deg: spec.directional_deg,
            position_m: position.to_array(),
            look_at_m: [0.0; 3],
            up: up.to_array(),
            projection,
            field,
        }
    }

    /// Per pixel of the current camera, whether the specimen covers it whole: the rays through
    /// its four corners all meet the specimen.
    pub fn specimen_mask(&self) -> Vec<bool> {
        let cam = &self.scene.camera;
        let (w, h) = (cam.width, cam.height);
        let hits = |x: usize, y: usize| {
            let ray = cam.ray(glam::DVec2::new(x as f64, y as f64));
            self.scene
                .accel
                .intersect(&ray, 0.0, f64::INFINITY)
                .is_some_and(|hit| hit.prim < self.specimen_prims)
        };
        let corners: Vec<bool> = (0..=h)
            .flat_map(|y| (0..=w).map(move |x| (x, y)))
            .map(|(x, y)| hits(x, y))
            .collect();
        let at = |x: usize, y: usize| corners[y * (w + 1) + x];
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| at(x, y) && at(x + 1, y) && at(x, y + 1) && at(x + 1, y + 1))
            .collect()
    }
}
