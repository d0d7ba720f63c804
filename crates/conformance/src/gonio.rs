//! The scenes for gonio's own renderer: a scene TOML (`docs/render.md`) with the files it names
//! (a coating description for the coat, spectral `.gbrdf` tables for the metameric patches),
//! rendered in memory by `gonio_render`.
//!
//! What each material is in gonio: a Lambertian is the `lambert` model; the coat is a coating
//! description (a smooth clear coat over a Kubelka-Munk layer: its body table computed on
//! loading, its Fresnel mirror added as a delta by its index); the mirror is a black `lambert`
//! under `coat_index`; a metameric patch is a spectral table of `ρ(λ)/π` rendered spectrally
//! (`--spectral`). gonio's lights are linear sRGB, a white light standing for D65 (the film's
//! white), so illuminant A is applied by multiplying the patches' spectra by `A(λ)/D65(λ)`:
//! for a plate under a uniform sky, whose light is reflected once, the radiance `ρ A` is then
//! exact.

use crate::error::{Error, Result};
use crate::scene::{Geometry, Light, Material, SIZE, Scene};
use gonio_brdf::table::{Channels, Provenance, Resolution, TableBuilder};
use gonio_color::Illuminant;
use gonio_render::{ColourMode, RenderOptions};
use std::fmt::Write as _;
use std::path::Path;

/// The scene's TOML for `gonio render`, writing the files it names into `dir`.
pub fn scene_toml(scene: &Scene, dir: &Path) -> Result<String> {
    let c = &scene.camera;
    let mut t = format!(
        "# {}\n[camera]\nposition = {:?}\nlook_at = {:?}\nup = {:?}\nfov_deg = {}\nwidth = {SIZE}\nheight = {SIZE}\n\n",
        scene.title, c.position, c.look_at, c.up, c.fov_deg
    );
    let fold = if scene.cie_illuminant() == Illuminant::A {
        Some(Illuminant::A)
    } else {
        None
    };
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
            Material::Spectral { reflectance } => {
                let file = format!("{name}.gbrdf");
                write_lambert_table(reflectance, fold, &dir.join(&file))?;
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

/// A Lambertian's spectral table, `ρ(λ)/π` at every pair of directions, times `A(λ)/D65(λ)`
/// when `fold` is illuminant A, written as `.gbrdf` to `path`.
fn write_lambert_table(reflectance: &[f64], fold: Option<Illuminant>, path: &Path) -> Result<()> {
    let wl = crate::metamer::wavelengths_nm();
    let values: Vec<f64> = wl
        .iter()
        .zip(reflectance)
        .map(|(&w, &r)| {
            let ratio = fold.map_or(1.0, |i| {
                i.spd().value_at(w) / Illuminant::D65.spd().value_at(w)
            });
            r * ratio / std::f64::consts::PI
        })
        .collect();
    let bad = |e: gonio_brdf::BrdfError| Error::Invalid(format!("spectral table: {e}"));
    let mut builder = TableBuilder::new(
        Resolution::isotropic(4, 4, 4),
        Channels::Spectral {
            wavelengths_nm: wl.clone(),
        },
    )
    .map_err(bad)?
    .with_provenance(Provenance::new("gonio conformance", "lambert"));
    builder.fill(|_, out| {
        for (o, &v) in out.iter_mut().zip(&values) {
            *o = v;
        }
    });
    let table = builder.build().map_err(bad)?;
    gonio_brdf::gbrdf::write(&table, path).map_err(bad)
}

/// gonio's picture of `scene` at `spp` samples per pixel (its files in `dir`): linear sRGB per
/// pixel, rows from the top.
pub fn render(scene: &Scene, dir: &Path, spp: u32) -> Result<Vec<[f64; 3]>> {
    let text = scene_toml(scene, dir)?;
    let path = dir.join(format!("{}.toml", scene.id.name()));
    std::fs::write(&path, &text).map_err(|e| Error::io(&path.display().to_string(), e))?;
    let built = gonio_render::Scene::from_toml(&text, &path)?;
    let options = RenderOptions {
        spp: Some(spp),
        seed: Some(1),
        colour: if scene.is_spectral() {
            ColourMode::Spectral
        } else {
            ColourMode::Tristimulus
        },
        ..RenderOptions::default()
    };
    let estimate = gonio_render::render_estimate(&built, &options)?;
    let image = &estimate.image;
    Ok((0..SIZE * SIZE)
        .map(|k| image.get(k % SIZE, k / SIZE).map(f64::from))
        .collect())
}
