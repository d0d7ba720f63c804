//! The scenes for Mitsuba 3: a scene dict (JSON, turned into Mitsuba's objects by the embedded
//! driver `mitsuba.py`), rendered by its `path` integrator with an `independent` sampler and a
//! box filter.
//!
//! Materials, two ways ([`crate::suite::Route`]). Through gonio's exports: every material is
//! gonio's table of it ([`crate::export::table`]) written as a tensor `.bsdf`
//! (`gonio_brdf::formats::mitsuba`) for Mitsuba's `measured` plugin; a table holds no delta,
//! so the coat's mirror reflection and the whole mirror are lost (the mirror's table is black,
//! which the exporter refuses: a black `diffuse` stands for it). Natively, for comparison:
//! a Lambertian is `diffuse`; the smooth coat over a diffuse base is `plastic` (`nonlinear =
//! true`, which divides the base's light by `1 − ρ r_i`, the series of internal reflections;
//! without it Mitsuba divides by `1 − r_i` whatever the base) with a fitted internal
//! reflectance (`optics::mitsuba_diffuse_reflectance`) and the Kubelka-Munk base reflectance
//! computed by gonio; the mirror is `plastic` with a black base. Either way the metameric
//! patches are spectral (the `scalar_spectral` variant: a spectral tensor file, or `diffuse`
//! with spectra), and the sky a `constant` emitter whose radiance is the illuminant's spectrum
//! (D65 or A): Mitsuba renders metamerism natively.

use crate::error::Result;
use crate::export;
use crate::metamer;
use crate::python;
use crate::scene::{Geometry, Light, Material, SIZE, Scene};
use crate::suite::Route;
use serde_json::{Value, json};
use std::path::Path;

/// The driver.
const DRIVER: &str = include_str!("mitsuba.py");

fn spectrum(values: &[f64]) -> Value {
    let pairs: Vec<[f64; 2]> = metamer::wavelengths_nm()
        .into_iter()
        .zip(values)
        .map(|(w, &v)| [w, v])
        .collect();
    json!({"type": "spectrum", "value": pairs})
}

/// The scene dict of `scene` at `spp` samples per pixel by `route`, writing the exported
/// tables it names into `dir`.
pub fn scene_dict(scene: &Scene, spp: u32, route: Route, dir: &Path) -> Result<Value> {
    let spectral = scene.is_spectral();
    let mut objects = serde_json::Map::new();
    for o in &scene.objects {
        let bsdf = if route == Route::Export && export::is_black(&o.material) {
            // gonio's exporter refuses a black table (no retro-reflection to derive the ndf
            // from); what the table would render is black.
            json!({"type": "diffuse", "reflectance": {"type": "rgb", "value": vec![0.0; 3]}})
        } else if route == Route::Export {
            let path = export::mitsuba_file(dir, scene.id.name(), &o.name);
            export::write_mitsuba(&o.material, &path)?;
            json!({"type": "measured", "filename": path.display().to_string()})
        } else {
            native(&o.material)
        };
        let shape = match o.geometry {
            Geometry::Sphere { center, radius } => {
                json!({"type": "sphere", "center": center, "radius": radius, "bsdf": bsdf})
            }
            Geometry::Rectangle {
                center,
                half,
                rotate_x_deg,
            } => json!({
                "type": "rectangle", "bsdf": bsdf,
                "to_world": {"translate": center, "rotate_x_deg": rotate_x_deg,
                             "scale": [half[0], half[1], 1.0]},
            }),
        };
        objects.insert(o.name.clone(), shape);
    }
    for (k, light) in scene.lights.iter().enumerate() {
        let value = match *light {
            Light::Sky { radiance } => {
                let radiance_value = if spectral {
                    let illuminant = scene.cie_illuminant();
                    let spd: Vec<f64> = metamer::wavelengths_nm()
                        .iter()
                        .map(|&w| radiance * illuminant.spd().value_at(w) / 100.0)
                        .collect();
                    spectrum(&spd)
                } else {
                    json!({"type": "rgb", "value": vec![radiance; 3]})
                };
                json!({"type": "constant", "radiance": radiance_value})
            }
            Light::Rectangle {
                center,
                half,
                rotate_x_deg,
                radiance,
            } => json!({
                "type": "rectangle",
                "to_world": {"translate": center, "rotate_x_deg": rotate_x_deg,
                             "scale": [half[0], half[1], 1.0]},
                "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": vec![0.0; 3]}},
                "emitter": {"type": "area", "radiance": {"type": "rgb", "value": vec![radiance; 3]}},
            }),
        };
        objects.insert(format!("light{k}"), value);
    }
    let c = &scene.camera;
    Ok(json!({
        "variant": if spectral { "scalar_spectral" } else { "scalar_rgb" },
        "size": SIZE, "spp": spp, "seed": 1,
        "sensor": {"origin": c.position, "target": c.look_at, "up": c.up, "fov": c.fov_deg},
        "objects": objects,
    }))
}

/// The native plugin standing for `material`.
fn native(material: &Material) -> Value {
    match material {
        Material::Lambert { albedo } => {
            json!({"type": "diffuse", "reflectance": {"type": "rgb", "value": albedo}})
        }
        Material::Spectral { reflectance } => {
            json!({"type": "diffuse", "reflectance": spectrum(reflectance)})
        }
        Material::Coat(coat) => json!({
            "type": "plastic", "int_ior": coat.index, "ext_ior": 1.0, "nonlinear": true,
            "diffuse_reflectance": {"type": "rgb", "value": vec![coat.base_reflectance(); 3]},
        }),
        Material::Mirror { index } => json!({
            "type": "plastic", "int_ior": index, "ext_ior": 1.0, "nonlinear": true,
            "diffuse_reflectance": {"type": "rgb", "value": vec![0.0; 3]},
        }),
    }
}

/// Mitsuba's picture of `scene` by `route` (files in `dir`), `None` when Mitsuba is missing.
pub fn render(scene: &Scene, dir: &Path, spp: u32, route: Route) -> Result<Option<Vec<[f64; 3]>>> {
    let name = format!("{}_{}", scene.id.name(), route.name());
    let spec = dir.join(format!("{name}.mitsuba.json"));
    let out = dir.join(format!("{name}.mitsuba.f32"));
    let text = serde_json::to_string_pretty(&scene_dict(scene, spp, route, dir)?)?;
    std::fs::write(&spec, text).map_err(|e| crate::Error::io(&spec.display().to_string(), e))?;
    if python::run("mitsuba_driver.py", DRIVER, dir, &[&spec, &out])?.is_none() {
        return Ok(None);
    }
    let v = python::read_f32(&out, SIZE * SIZE * 3)?;
    Ok(Some(
        v.chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]].map(f64::from))
            .collect(),
    ))
}
