//! A conformance scene's analytic reference picture and regions, computed by casting the
//! pixels' rays through the scene's geometry ([`crate::scene`]'s doc: 4 × 4 points per pixel,
//! a region's pixels wholly inside its rule).

use crate::geometry::Local;
use crate::metamer;
use crate::optics::{coat_radiance, fresnel, lambert_under_sky};
use crate::scene::{Geometry, Light, Material, Rule, SIZE, SUPERSAMPLE, Scene};
use glam::DVec3;
use gonio_color::LinearSrgb;

impl Scene {
    /// The analytic picture and regions.
    pub fn reference(&self) -> crate::Result<Reference> {
        self.reference_with(None)
    }

    /// The picture and regions with the coat's reflection under the sky taken from `coat`, the
    /// radiance under a sky of radiance 1 as a function of the cosine of the view to the normal,
    /// in place of the closed form (what a renderer holding the coat as a table shows,
    /// [`crate::loss`]).
    pub fn reference_with_coat(&self, coat: &dyn Fn(f64) -> f64) -> crate::Result<Reference> {
        self.reference_with(Some(coat))
    }

    fn reference_with(&self, coat: Option<&dyn Fn(f64) -> f64>) -> crate::Result<Reference> {
        let patch_rgb = self
            .objects
            .iter()
            .map(|o| match &o.material {
                Material::Spectral { reflectance } => {
                    let xyz = metamer::xyz(reflectance, self.cie_illuminant())?;
                    let c = LinearSrgb::from_xyz(xyz);
                    Ok([c.r, c.g, c.b])
                }
                _ => Ok([0.0; 3]),
            })
            .collect::<crate::Result<Vec<_>>>()?;
        // The colour of the sky seen directly: white, but in the metameric scenes the
        // illuminant's own colour (D65's is white).
        let sky_rgb = if self.is_spectral() {
            let n = metamer::wavelengths_nm().len();
            let c = LinearSrgb::from_xyz(metamer::xyz(&vec![1.0; n], self.cie_illuminant())?);
            [c.r, c.g, c.b]
        } else {
            [1.0; 3]
        };
        let mut rgb = vec![[0.0; 3]; SIZE * SIZE];
        let mut region = vec![None; SIZE * SIZE];
        let s = SUPERSAMPLE as f64;
        for y in 0..SIZE {
            for x in 0..SIZE {
                let mut sum = [0.0; 3];
                let mut inside: Vec<bool> = vec![true; self.regions.len()];
                for j in 0..SUPERSAMPLE {
                    for i in 0..SUPERSAMPLE {
                        let fx = x as f64 + (i as f64 + 0.5) / s;
                        let fy = y as f64 + (j as f64 + 0.5) / s;
                        let (value, member) = self.trace(fx, fy, &patch_rgb, sky_rgb, coat);
                        for c in 0..3 {
                            sum[c] += value[c] / (s * s);
                        }
                        for (k, m) in inside.iter_mut().enumerate() {
                            *m &= member == Some(k);
                        }
                    }
                }
                rgb[y * SIZE + x] = sum;
                region[y * SIZE + x] = inside.iter().position(|&m| m);
            }
        }
        Ok(Reference { rgb, region })
    }

    /// The analytic radiance along the ray through film point (fx, fy) (`sky_rgb` the colour of
    /// the sky seen directly; `coat` the coat's reflection under a unit sky by the cosine of the
    /// view, the closed form when `None`), and the region the point belongs to.
    fn trace(
        &self,
        fx: f64,
        fy: f64,
        patch_rgb: &[[f64; 3]],
        sky_rgb: [f64; 3],
        coat_under_sky: Option<&dyn Fn(f64) -> f64>,
    ) -> ([f64; 3], Option<usize>) {
        let origin = DVec3::from(self.camera.position);
        let dir = self.camera.ray(fx, fy);
        let nearest = self
            .objects
            .iter()
            .enumerate()
            .filter_map(|(k, o)| o.geometry.hit(origin, dir).map(|(t, l)| (t, k, l)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let sky: f64 = self
            .lights
            .iter()
            .map(|l| match l {
                Light::Sky { radiance } => *radiance,
                Light::Rectangle { .. } => 0.0,
            })
            .sum();
        let Some((t, k, local)) = nearest else {
            let e = self.emitted(origin, dir, sky);
            return (sky_rgb.map(|c| c * e), None);
        };
        let object = &self.objects[k];
        let (value, facing) = match (&object.material, local) {
            (Material::Lambert { albedo }, _) => (albedo.map(|a| lambert_under_sky(a, sky)), true),
            (Material::Spectral { .. }, _) => (patch_rgb[k].map(|c| c * sky), true),
            (Material::Coat(coat), Local::Sphere { normal }) => {
                let cos = normal.dot(-dir);
                let v = match coat_under_sky {
                    Some(f) => f(cos) * sky,
                    None => coat_radiance(cos, coat.index, coat.base_reflectance(), sky),
                };
                ([v; 3], true)
            }
            (Material::Coat(_), Local::Rectangle { .. }) => ([0.0; 3], false),
            (Material::Mirror { index }, local) => {
                let n = match local {
                    Local::Sphere { normal } => normal,
                    Local::Rectangle { normal, .. } => normal,
                };
                let n = if n.dot(dir) > 0.0 { -n } else { n };
                let cos = n.dot(-dir);
                let reflected = dir + 2.0 * cos * n;
                let p = origin + t * dir;
                let le = self.emitted(p, reflected, sky);
                ([fresnel(cos, *index) * le; 3], le > 0.0)
            }
        };
        let member = self.regions.iter().position(|r| {
            r.object == k
                && match (r.rule, local) {
                    (Rule::Facing { max_deg }, Local::Sphere { normal }) => {
                        normal.dot(-dir) >= max_deg.to_radians().cos()
                    }
                    (Rule::Interior { fraction }, Local::Rectangle { u, v, front, .. }) => {
                        front && u.abs() <= fraction && v.abs() <= fraction
                    }
                    (
                        Rule::Mirrored {
                            fraction,
                            emitter_fraction,
                        },
                        Local::Rectangle {
                            u,
                            v,
                            front,
                            normal,
                            ..
                        },
                    ) => {
                        let cos = normal.dot(-dir);
                        let reflected = dir + 2.0 * cos * normal;
                        front
                            && facing
                            && u.abs() <= fraction
                            && v.abs() <= fraction
                            && self.emitter_within(origin + t * dir, reflected, emitter_fraction)
                    }
                    _ => false,
                }
        });
        (value, member)
    }

    /// The radiance of the lights seen along `dir` from `origin` (the sky where no emitter is
    /// in the way; an emitter's back is black).
    fn emitted(&self, origin: DVec3, dir: DVec3, sky: f64) -> f64 {
        for light in &self.lights {
            if let Light::Rectangle {
                center,
                half,
                rotate_x_deg,
                radiance,
            } = *light
            {
                let g = Geometry::Rectangle {
                    center,
                    half,
                    rotate_x_deg,
                };
                if let Some((_, Local::Rectangle { front, .. })) = g.hit(origin, dir) {
                    return if front { radiance } else { 0.0 };
                }
            }
        }
        sky
    }

    /// Whether the ray meets a rectangular emitter's front within `fraction` of its half sizes.
    fn emitter_within(&self, origin: DVec3, dir: DVec3, fraction: f64) -> bool {
        self.lights.iter().any(|light| {
            if let Light::Rectangle {
                center,
                half,
                rotate_x_deg,
                ..
            } = *light
            {
                let g = Geometry::Rectangle {
                    center,
                    half,
                    rotate_x_deg,
                };
                matches!(g.hit(origin, dir), Some((_, Local::Rectangle { u, v, front: true, .. }))
                    if u.abs() <= fraction && v.abs() <= fraction)
            } else {
                false
            }
        })
    }
}

/// A scene's analytic picture (linear sRGB, row by row from the top) and the region of each
/// pixel.
#[derive(Debug, Clone)]
pub struct Reference {
    pub rgb: Vec<[f64; 3]>,
    pub region: Vec<Option<usize>>,
}
