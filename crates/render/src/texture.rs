//! The virtual texture camera: a coating's flakes rendered one by one ([`crate::flakes`]) in
//! the geometry of the multi-angle sparkle cameras, and sparkle and graininess read from the
//! pictures ([`crate::texture_metrics`]). The camera looks along the specimen's normal at a
//! square field; a lamp lights it from 15°, 45° and 75° off the normal (sparkle), and a uniform
//! hemisphere lights it (graininess). The instrument lives here rather than in the
//! `instrument` crate because it is made of renders, and the two crates sit side by side.
//!
//! The lamp is a disc 2° in radius (an LED a few centimetres away subtends degrees): the
//! share of flakes that catch it grows with its solid angle, so readings compare at one lamp.

use crate::coating_material::{FlakeMode, from_coating};
use crate::error::{RenderError, Result};
use crate::image::Image;
use crate::integrator::{RenderOptions, render};
use crate::material::Material;
use crate::scene::Scene;
use crate::settings::ColourMode;
use crate::texture_glint::glint_picture;
use crate::texture_metrics::{Sparkle, graininess, graininess_uncertainty, luminance, sparkle};
use gonio_coating::system::Coating;
use std::path::Path;
use std::sync::Arc;

/// The lamp's angles from the normal for sparkle, degrees.
pub const SPARKLE_ANGLES_DEG: [f64; 3] = [15.0, 45.0, 75.0];

/// The lamp's angular radius, degrees.
pub const LAMP_RADIUS_DEG: f64 = 2.0;

/// The surround's floor as a share of a white diffuser's luminance under the same light.
const SURROUND_FLOOR: f64 = 0.01;

/// The camera's field and sampling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextureCamera {
    /// Side of the square field, mm.
    pub field_mm: f64,
    /// Pixel footprint on the specimen, µm.
    pub pixel_um: f64,
    /// Samples per pixel.
    pub spp: u32,
    /// The seed that places the flakes.
    pub flake_seed: u64,
    /// Threads (`None`: all).
    pub threads: Option<usize>,
}

impl Default for TextureCamera {
    /// A field of 6 mm at 15 µm per pixel (400 × 400), 16 samples per pixel.
    fn default() -> Self {
        TextureCamera {
            field_mm: 6.0,
            pixel_um: 15.0,
            spp: 16,
            flake_seed: 1,
            threads: None,
        }
    }
}

impl TextureCamera {
    /// The picture's side in pixels.
    pub fn pixels(&self) -> usize {
        (self.field_mm * 1000.0 / self.pixel_um).round() as usize
    }

    fn check(&self) -> Result<()> {
        let px = self.field_mm * 1000.0 / self.pixel_um;
        if !(self.field_mm > 0.0 && self.pixel_um > 0.0 && (16.0..=4096.0).contains(&px)) {
            return Err(RenderError::Invalid(format!(
                "texture camera: a field of {} mm at {} µm per pixel is {px:.0} pixels a side; \
                 use 16 to 4096",
                self.field_mm, self.pixel_um
            )));
        }
        if self.spp == 0 {
            return Err(RenderError::Invalid(
                "texture camera: at least one sample per pixel".into(),
            ));
        }
        Ok(())
    }
}

/// One sparkle picture: the lamp's angle and what was read from it.
#[derive(Debug, Clone)]
pub struct SparkleShot {
    /// The lamp's angle from the normal, degrees.
    pub angle_deg: f64,
    pub sparkle: Sparkle,
    /// The picture (linear sRGB radiance for a lamp of radiance 1).
    pub image: Image,
}

/// What the texture camera reads.
#[derive(Debug, Clone)]
pub struct TextureReading {
    /// Sparkle at each lamp angle of [`SPARKLE_ANGLES_DEG`].
    pub sparkle: Vec<SparkleShot>,
    /// Graininess under the diffuse hemisphere, %.
    pub graininess: f64,
    /// The standard uncertainty of `graininess` from the pictures' noise, %.
    pub graininess_uncertainty: f64,
    /// The diffuse picture (the mean of the two renders).
    pub diffuse: Image,
}

/// The texture camera's readings of `coating` (described in `source`): its flakes drawn one by
/// one (a coating without flakes is drawn as it is: no sparkle). `progress` is told the
/// picture that starts (1 to 5) and its name.
pub fn measure(
    coating: &Coating,
    source: &str,
    camera: &TextureCamera,
    progress: &dyn Fn(usize, &str),
) -> Result<TextureReading> {
    camera.check()?;
    let mode = if coating.flakes.is_some() {
        FlakeMode::Discrete
    } else {
        FlakeMode::Smooth
    };
    let mut material = from_coating("coating", coating, source, mode, camera.flake_seed)?;
    // The flakes' glint is added to each picture exactly (`texture_glint`), not sampled.
    material.flakes = material
        .flakes
        .map(|f| Arc::new(Arc::unwrap_or_clone(f).without_glint()));
    let options = |seed: u32| RenderOptions {
        spp: Some(camera.spp),
        seed: Some(seed),
        threads: camera.threads,
        colour: ColourMode::Tristimulus,
        denoise: Some(false),
        max_bounces: Some(4),
        ..RenderOptions::default()
    };
    let pixel_mm = camera.pixel_um / 1000.0;
    let mut shots = Vec::new();
    for (k, &angle) in SPARKLE_ANGLES_DEG.iter().enumerate() {
        progress(k + 1, &format!("lamp at {angle}°"));
        let scene = scene(camera, Some(angle), &material)?;
        let image = picture(&scene, &options(1), &glint_picture(&scene, camera.threads)?)?;
        // A white diffuser's luminance under the lamp: E / π with E = L Ω cos θ, L = 1.
        let omega = std::f64::consts::TAU * (1.0 - LAMP_RADIUS_DEG.to_radians().cos());
        let white = omega * angle.to_radians().cos() / std::f64::consts::PI;
        let y: Vec<f64> = image.pixels.iter().map(|&p| luminance(p)).collect();
        shots.push(SparkleShot {
            angle_deg: angle,
            sparkle: sparkle(&y, image.width, pixel_mm, SURROUND_FLOOR * white),
            image,
        });
    }
    progress(4, "diffuse light");
    let scene = scene(camera, None, &material)?;
    let glint = glint_picture(&scene, camera.threads)?;
    let a = picture(&scene, &options(1), &glint)?;
    progress(5, "diffuse light, independent samples");
    let b = picture(&scene, &options(2), &glint)?;
    let ya: Vec<f64> = a.pixels.iter().map(|&p| luminance(p)).collect();
    let yb: Vec<f64> = b.pixels.iter().map(|&p| luminance(p)).collect();
    let mut diffuse = a.clone();
    for (d, p) in diffuse.pixels.iter_mut().zip(&b.pixels) {
        for c in 0..3 {
            d[c] = 0.5 * (d[c] + p[c]);
        }
    }
    Ok(TextureReading {
        sparkle: shots,
        graininess: graininess(&ya, &yb),
        graininess_uncertainty: graininess_uncertainty(&ya, &yb),
        diffuse,
    })
}

/// `scene`'s picture: the coating without its flakes' glint rendered with `options`, and
/// `glint`, the glint integrated over each pixel, added.
fn picture(scene: &Scene, options: &RenderOptions, glint: &Image) -> Result<Image> {
    let (mut image, _) = render(scene, options)?;
    for (p, g) in image.pixels.iter_mut().zip(&glint.pixels) {
        for c in 0..3 {
            p[c] += g[c];
        }
    }
    Ok(image)
}

/// The camera's scene: the specimen (a plane of `material`) seen along its normal from 1 m
/// over the field, lit by the lamp at `lamp_deg` from the normal (radiance 1, 100 m away) or,
/// for `None`, by a uniform hemisphere of radiance 1.
fn scene(camera: &TextureCamera, lamp_deg: Option<f64>, material: &Material) -> Result<Scene> {
    let px = camera.pixels();
    let field = camera.field_mm / 1000.0;
    let fov = 2.0 * (field / 2.0).atan().to_degrees();
    let light = match lamp_deg {
        Some(a) => {
            let (s, c) = a.to_radians().sin_cos();
            format!(
                "[[lights]]\ntype = \"sphere\"\ncenter = [{}, 0.0, {}]\nradius = {}\nradiance = 1.0\n",
                100.0 * s,
                100.0 * c,
                100.0 * LAMP_RADIUS_DEG.to_radians().sin()
            )
        }
        None => "[[lights]]\ntype = \"sky\"\nradiance = 1.0\n".to_string(),
    };
    let text = format!(
        "[camera]\nposition = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = {fov}\n\
         width = {px}\nheight = {px}\n\
         [materials.specimen]\nbrdf = {{ model = \"lambert\", albedo = 0.0 }}\n\
         [[shapes]]\ntype = \"rectangle\"\nsize = [0.1, 0.1]\nmaterial = \"specimen\"\n{light}"
    );
    let mut scene = Scene::from_toml(&text, Path::new("texture camera"))?;
    scene.materials[0] = Material {
        name: "specimen".into(),
        ..material.clone()
    };
    Ok(scene)
}
