//! The path tracer for Python: a scene (a TOML file, or its content as JSON text of the same
//! structure) rendered to a linear sRGB float32 array.

use crate::error::{Result, invalid};
use gonio_render::scene::SceneDesc;
use gonio_render::{ColourMode, RenderOptions, Scene};
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use std::path::PathBuf;

/// Render a scene file `path`, or a scene given as `json` text (relative paths then start in
/// `base_dir`); `spp`, `seed`, `max_bounces`, `denoise` override the scene's `[render]`;
/// `spectral` carries four wavelengths per path instead of RGB. Returns (height, width, 3)
/// float32 linear sRGB radiance.
#[pyfunction]
#[pyo3(signature = (path, json, base_dir, spp, seed, max_bounces, denoise, spectral, threads))]
#[allow(clippy::too_many_arguments)]
pub fn render_scene<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    json: Option<String>,
    base_dir: PathBuf,
    spp: Option<u32>,
    seed: Option<u32>,
    max_bounces: Option<u32>,
    denoise: Option<bool>,
    spectral: bool,
    threads: Option<usize>,
) -> Result<Bound<'py, PyArray3<f32>>> {
    let opts = RenderOptions {
        spp,
        seed,
        max_bounces,
        threads,
        colour: if spectral {
            ColourMode::Spectral
        } else {
            ColourMode::Tristimulus
        },
        denoise,
        ..RenderOptions::default()
    };
    let image = py.detach(move || -> Result<gonio_render::Image> {
        let scene = match (path, json) {
            (Some(path), None) => Scene::from_file(&path)?,
            (None, Some(text)) => {
                let desc: SceneDesc = serde_json::from_str(&text)
                    .map_err(|e| invalid(format!("scene: {e} (see docs/render.md)")))?;
                Scene::build(&desc, &base_dir.join("scene.toml"))?
            }
            _ => return Err(invalid("give a scene file or a scene dict")),
        };
        Ok(gonio_render::render(&scene, &opts)?.0)
    })?;
    let (h, w) = (image.height, image.width);
    let flat: Vec<f32> = image.pixels.into_iter().flatten().collect();
    Ok(PyArray1::from_vec(py, flat).reshape([h, w, 3])?)
}
