//! The scenes for gonio's own renderer: a scene TOML (`docs/render.md`) with the files it names
//! (a coating description for the coat, spectral `.gbrdf` tables for the metameric patches),
//! rendered in memory by `gonio_render`.
//!
//! What each material is in gonio: a Lambertian is the `lambert` model; the coat is a coating
//! description (a smooth clear coat over a Kubelka-Munk layer: its body table computed on
//! loading, its Fresnel mirror added as a delta by its index); the mirror is a black `lambert`
//! under `coat_index`; a metameric patch is a spectral table of `ρ(λ)/π` rendered spectrally
//! on the absolute film (`gonio_render::Film::Absolute`) whose light is the scene's illuminant
//! (D65 or A): the sky's grey value then emits that illuminant's spectrum, seen directly and on
//! the patches alike, and the film records CIE XYZ, turned into linear sRGB here like the
//! reference's.

use crate::error::{Error, Result};
use crate::scene::{Geometry, Light, Material, SIZE, Scene};
use gonio_color::{LinearSrgb, Observer, Xyz};
use gonio_render::{ColourMode, Film, RenderOptions};
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;

/// The scene's TOML for `gonio render`, writing the files it names into `dir`.
pub fn scene_toml(scene: &Scene, dir: &Path) -> Result<String> {
    let c = &scene.camera;
    let mut t = format!(
        "# {}\n[camera]\nposition = {:?}\nlook_at = {:?}\nup = {:?}\nfov_deg = {}\nwidth = {SIZE}\nheight = {SIZE}\n\n",
        scene.title, c.position, c.look_at, c.up, c.fov_deg
    );
    for o in &scene.objects {
        let name = &o.name;
        let _ = writeln!(t, "[materials.{name}]");
        match &o.material {
            Material::Lambert { albedo } => {
                let _ = writeln!(t, "brdf = {{ model = \"lambert\", albedo = {albedo:?} }}");
            }
            Material::Mirror { index } => {
                let _ = writeln!(
                    t,
                    "brdf = {{ model = \"lambert\", albedo = 0.0 }}\ncoat_index = {index}"
                );
            }
            Material::Coat(coat) => {
                let file = format!("{name}.coating.toml");
                let text = coat.description();
                std::fs::write(dir.join(&file), text).map_err(|e| Error::io(&file, e))?;
                let _ = writeln!(t, "coating = \"{file}\"");
            }
            Material::Spectral { .. } => {
                let file = format!("{name}.gbrdf");
                let table = crate::export::table(&o.material)?;
                let path = dir.join(&file);
                gonio_brdf::gbrdf::write(&table, &path)
                    .map_err(|e| Error::Invalid(format!("{}: {e}", path.display())))?;
                let _ = writeln!(t, "table = \"{file}\"");
            }
        }
        let _ = writeln!(t);
    }
    for o in &scene.objects {
        let _ = writeln!(t, "[[shapes]]");
        match o.geometry {
            Geometry::Sphere { center, radius } => {
                let _ = writeln!(
                    t,
                    "type = \"sphere\"\ncenter = {center:?}\nradius = {radius:?}"
                );
            }
            Geometry::Rectangle {
                center,
                half,
                rotate_x_deg,
            } => {
                let _ = writeln!(
                    t,
                    "type = \"rectangle\"\nsize = [{:?}, {:?}]\nrotate_deg = [{rotate_x_deg:?}, 0.0, 0.0]\ntranslate = {center:?}",
                    2.0 * half[0],
                    2.0 * half[1]
                );
            }
        }
        let _ = writeln!(t, "material = \"{}\"\n", o.name);
    }
    for light in &scene.lights {
        let _ = writeln!(t, "[[lights]]");
        match *light {
            Light::Sky { radiance } => {
                let _ = writeln!(t, "type = \"sky\"\nradiance = {radiance:?}\n");
            }
            Light::Rectangle {
                center,
                half,
                rotate_x_deg,
                radiance,
            } => {
                let _ = writeln!(
                    t,
                    "type = \"rectangle\"\nsize = [{:?}, {:?}]\nrotate_deg = [{rotate_x_deg:?}, 0.0, 0.0]\ntranslate = {center:?}\nradiance = {radiance:?}\n",
                    2.0 * half[0],
                    2.0 * half[1]
                );
            }
        }
    }
    Ok(t)
}

/// gonio's picture of `scene` at `spp` samples per pixel (its files in `dir`): linear sRGB per
/// pixel, rows from the top. A spectral scene is rendered on the absolute film under its
/// illuminant and its XYZ turned into linear sRGB (`LinearSrgb::from_xyz`, as the reference's;
/// the film's absolute scale is left to the suite, which scales to the white patch).
pub fn render(scene: &Scene, dir: &Path, spp: u32) -> Result<Vec<[f64; 3]>> {
    let text = scene_toml(scene, dir)?;
    let path = dir.join(format!("{}.toml", scene.id.name()));
    std::fs::write(&path, &text).map_err(|e| Error::io(&path.display().to_string(), e))?;
    let built = gonio_render::Scene::from_toml(&text, &path)?;
    let spectral = scene.is_spectral();
    let options = RenderOptions {
        spp: Some(spp),
        seed: Some(1),
        colour: if spectral {
            ColourMode::Spectral
        } else {
            ColourMode::Tristimulus
        },
        ..RenderOptions::default()
    };
    let film = if spectral {
        Film::Absolute {
            light: Arc::new(scene.cie_illuminant().spd().clone()),
            observer: Observer::Cie1931TwoDegree,
        }
    } else {
        Film::Display
    };
    let estimate = gonio_render::render_estimate_on(&built, &options, &film)?;
    let image = &estimate.image;
    Ok((0..SIZE * SIZE)
        .map(|k| {
            let c = image.get(k % SIZE, k / SIZE).map(f64::from);
            if spectral {
                let rgb = LinearSrgb::from_xyz(Xyz {
                    x: c[0],
                    y: c[1],
                    z: c[2],
                });
                [rgb.r, rgb.g, rgb.b]
            } else {
                c
            }
        })
        .collect())
}
