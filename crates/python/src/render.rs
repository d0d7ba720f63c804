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

/// The virtual viewing booth (docs/standard.md): `input` a booth spec, a coating description or
/// a `.gbrdf` table, `booth` a booth spec for a coating or table; `spp`, `seed` and `size`
/// (width, height) override the spec's `[render]`. Writes every view's files and the manifest
/// into `output_dir` and returns the summary as JSON text.
#[pyfunction]
#[pyo3(signature = (input, output_dir, booth, spp, seed, size, threads))]
#[allow(clippy::too_many_arguments)]
pub fn booth_json(
    py: Python<'_>,
    input: PathBuf,
    output_dir: PathBuf,
    booth: Option<PathBuf>,
    spp: Option<u32>,
    seed: Option<u32>,
    size: Option<(usize, usize)>,
    threads: Option<usize>,
) -> Result<String> {
    py.detach(move || -> Result<String> {
        let mut resolved = gonio_render::booth::Resolved::from_files(&input, booth.as_deref())?;
        let render = &mut resolved.spec.render;
        if let Some(spp) = spp {
            render.spp = spp;
        }
        if let Some(seed) = seed {
            render.seed = seed;
        }
        if let Some((w, h)) = size {
            render.width = w;
            render.height = h;
        }
        let run = gonio_render::booth::Run {
            threads,
            ..Default::default()
        };
        let summary = gonio_render::booth::write_booth(&resolved.job(), &output_dir, &run)?;
        Ok(summary.to_json().to_string())
    })
}
