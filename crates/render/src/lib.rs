//! gonio-render: a Monte Carlo path tracer that turns BRDFs (analytic models, measured and
//! computed tables) into pictures, so that a person can judge the appearance a surface
//! topography predicts.
//!
//! A scene file (TOML, `docs/render.md`) names a camera, shapes with materials, and lights;
//! [`render_scene_file`] reads it, renders it and returns a linear RGB [`Image`], which
//! [`Image::write`] saves as OpenEXR, Radiance HDR or PNG.
//!
//! ```no_run
//! use gonio_render::{RenderOptions, render_scene_file};
//! let opts = RenderOptions { spp: Some(64), ..RenderOptions::default() };
//! let (image, display, stats) = render_scene_file("examples/plastic.toml".as_ref(), &opts)?;
//! image.write("plastic.png".as_ref(), display)?;
//! println!("{:.3e} rays/s", stats.rays_per_second());
//! # Ok::<(), gonio_render::RenderError>(())
//! ```

pub mod assets;
pub mod booth;
pub mod camera;
pub mod coating_material;
pub mod denoise;
pub mod difference;
mod env_guide;
pub mod error;
pub mod flakes;
pub mod geometry;
pub mod image;
pub mod integrator;
pub mod light;
pub mod material;
pub mod mesh;
pub mod mesoscale;
pub mod panel;
mod path;
pub mod picture;
pub mod scene;
pub mod settings;
pub mod spectral;
pub mod surface;
pub mod texture;
pub mod texture_glint;
pub mod texture_metrics;

pub use assets::Assets;
pub use error::{RenderError, Result};
pub use image::{Display, Image, ToneCurve};
pub use integrator::{
    Estimate, RenderOptions, RenderStats, render, render_estimate, render_estimate_on,
    render_picture,
};
pub use scene::Scene;
pub use settings::{BrdfSampling, ColourMode, Film};

use std::path::Path;

/// Read the scene file `path` and render it with `opts` (unset options come from the scene's
/// `[render]` table). Returns the image, the scene's display settings for PNG output, and
/// what the render cost.
pub fn render_scene_file(
    path: &Path,
    opts: &RenderOptions,
) -> Result<(Image, Display, RenderStats)> {
    let scene = Scene::from_file(path)?;
    let (image, stats) = render(&scene, opts)?;
    Ok((image, scene.display, stats))
}
