//! The panel pictures of the lab (`gonio lab`, #33), made in memory and progressively: a coarse
//! picture within a second of a change, finer ones while nothing changes, each a finished
//! picture. The table and the render are separate steps, so that a caller keeps a coating's
//! table and renders it again under another light ([`Lighting`]) without computing it again;
//! both stop when the caller's [`Cancel`] is raised (a newer formulation arrived).
//!
//! ```no_run
//! use gonio_render::panel::{Lighting, live::{Quality, live_table, picture}};
//! # fn f(coating: &gonio_coating::system::Coating) -> gonio_render::Result<()> {
//! let cancel = gonio_io::Cancel::new();
//! for quality in Quality::ALL {
//!     let table = live_table(coating, quality, &cancel)?;
//!     let shown = picture(&table, Lighting::Studio, quality, &cancel)?;
//!     std::fs::write(format!("{}.png", quality.name()), &shown.png).unwrap();
//! }
//! # Ok(()) }
//! ```
//!
//! The scene is the one [`super::scene`] writes for `gonio render` (one description of the
//! panel scene for both), built from memory ([`crate::Assets`]): the table just computed, the
//! embedded panel mesh, the lighting's map.

use super::{Lighting, MESH, Panel, Shot, coat_index, description, mesh};
use crate::error::{RenderError, Result};
use crate::scene::{PrimKind, SceneDesc};
use crate::{Assets, ColourMode, Display, Image, RenderOptions, Scene, render_picture};
use glam::DVec2;
use gonio_brdf::table::{Resolution, SampledTable};
use gonio_coating::system::{Coating, Method, default_bands};
use gonio_io::Cancel;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// How fine a picture is: its table's nodes, walks and bands, its size and samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Quality {
    /// Within a second of a change on two cores: a coarse table (12 × 12 × 8 nodes, 8 walks per
    /// cell, 16 bands of 20 nm), 192 × 128 pixels (a quarter of the converged picture's side), 16
    /// samples per pixel (fewer leave a smooth coat's mirror too rare a choice for the
    /// denoiser: 4 darkened the red's mirrored softbox by a fifth), denoised.
    Preview,
    /// Between the two, a few seconds after a change: the converged picture's table (the same
    /// table: a caller computes it once for both), 384 × 256 pixels (half the converged
    /// picture's side), 16 samples per pixel, denoised.
    Refined,
    /// The finished picture: 768 × 512 pixels, 16 samples per pixel, denoised; the table at
    /// [`super::resolution`]'s θh nodes (45, more for a very narrow rough top) × 24 θd × 16 φd
    /// with 32 walks per cell and the 31 bands of 10 nm: a third of the cells of the table of
    /// `gonio coating study`'s pictures (45 × 45 × 24), and the same picture (docs/render.md,
    /// "The converged table").
    Converged,
}

impl Quality {
    /// Every level, coarsest first: the order the lab shows them in.
    pub const ALL: [Quality; 3] = [Quality::Preview, Quality::Refined, Quality::Converged];

    /// Its name in the API (`"preview"`, `"refined"`, `"converged"`).
    pub fn name(self) -> &'static str {
        match self {
            Quality::Preview => "preview",
            Quality::Refined => "refined",
            Quality::Converged => "converged",
        }
    }

    /// The level called `name`.
    pub fn from_name(name: &str) -> Option<Quality> {
        Quality::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The nodes of the table of `coating` at this level.
    pub fn resolution(self, coating: &Coating) -> Resolution {
        match self {
            Quality::Preview => Resolution::isotropic(12, 12, 8),
            Quality::Refined | Quality::Converged => {
                Resolution::isotropic(super::resolution(coating).theta_h, 24, 16)
            }
        }
    }

    /// Random walks per table cell (unused by a coating computed exactly).
    pub fn walks(self) -> usize {
        match self {
            Quality::Preview => 8,
            Quality::Refined | Quality::Converged => super::WALKS,
        }
    }

    /// The table's bands, nm.
    pub fn bands(self) -> Vec<f64> {
        match self {
            Quality::Preview => (0..16).map(|i| 400.0 + 20.0 * i as f64).collect(),
            Quality::Refined | Quality::Converged => default_bands(),
        }
    }

    /// The picture's size and samples.
    fn shot(self) -> Shot {
        match self {
            Quality::Preview => Shot {
                height: 128,
                spp: 16,
            },
            Quality::Refined => Shot {
                height: 256,
                spp: 16,
            },
            Quality::Converged => Shot {
                height: 512,
                spp: 16,
            },
        }
    }
}

/// A coating's table for the lab's pictures, with what it cost.
#[derive(Clone)]
pub struct LiveTable {
    /// The table with its importance sampler.
    pub table: Arc<SampledTable>,
    /// The index of a smooth top, whose mirror the renderer adds (`None` for a rough top).
    pub coat_index: Option<f64>,
    /// The level it was computed for.
    pub quality: Quality,
    /// Random walks per cell (0: computed exactly, a smooth coat over a diffuse base).
    pub walks: usize,
    /// Wall-clock time, s (the sampler's construction included).
    pub seconds: f64,
}

/// Compute `coating`'s table at `quality` (its nodes, walks and bands), stopping with
/// [`RenderError::Cancelled`] when `cancel` is raised.
pub fn live_table(coating: &Coating, quality: Quality, cancel: &Cancel) -> Result<LiveTable> {
    let start = Instant::now();
    let method = coating.method(quality.walks());
    let walks = match method {
        Method::ClosedForm => 0,
        Method::RandomWalk(_) => quality.walks(),
    };
    let table = coating.table_until(
        quality.resolution(coating),
        &quality.bands(),
        quality.walks(),
        coating.provenance("gonio lab", method),
        cancel,
    )?;
    let table = Arc::new(SampledTable::new(table));
    if cancel.is_cancelled() {
        return Err(RenderError::Cancelled);
    }
    Ok(LiveTable {
        table,
        coat_index: coat_index(coating),
        quality,
        walks,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// A finished picture of the lab.
#[derive(Clone, Debug)]
pub struct Picture {
    /// The PNG file (sRGB after the display settings).
    pub png: Vec<u8>,
    /// The linear sRGB radiance, W m⁻² sr⁻¹.
    pub image: Image,
    /// Its display settings (exposure, tone curve).
    pub display: Display,
    /// What it cost and how fine it is.
    pub figures: Figures,
}

/// What a picture cost and how fine it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Figures {
    /// The table's wall-clock time, s.
    pub table_seconds: f64,
    /// The picture's wall-clock time, s (scene, render, denoising, PNG).
    pub render_seconds: f64,
    /// Samples per pixel.
    pub spp: u32,
    /// Width × height, pixels.
    pub size: (usize, usize),
    /// The table's nodes.
    pub resolution: Resolution,
    /// The table's random walks per cell (0: exact).
    pub walks: usize,
    /// The table's bands.
    pub bands: usize,
    /// Rays traced.
    pub rays: u64,
}

/// Render `table` on the panel under `lighting` at `quality`'s size and samples, spectrally
/// (colour formed under D65 by the CIE 1931 observer), denoised; stops with
/// [`RenderError::Cancelled`] when `cancel` is raised. The same table, light and quality give
/// the same picture for any number of threads.
pub fn picture(
    table: &LiveTable,
    lighting: Lighting,
    quality: Quality,
    cancel: &Cancel,
) -> Result<Picture> {
    let start = Instant::now();
    let scene = scene(table, lighting, quality)?;
    let options = RenderOptions {
        colour: ColourMode::Spectral,
        cancel: cancel.clone(),
        ..Default::default()
    };
    let (image, estimate) = render_picture(&scene, &options)?;
    let png = image.png(scene.display)?;
    Ok(Picture {
        png,
        figures: Figures {
            table_seconds: table.seconds,
            render_seconds: start.elapsed().as_secs_f64(),
            spp: quality.shot().spp,
            size: (image.width, image.height),
            resolution: table.table.table().resolution(),
            walks: table.walks,
            bands: table.table.table().channels().count(),
            rays: estimate.stats.rays,
        },
        image,
        display: scene.display,
    })
}

/// The name of the panel's material in the scene of [`scene`].
pub const MATERIAL: &str = "coating0";

/// The scene [`picture`] renders: the panel of `table` (its material named [`MATERIAL`]) under
/// `lighting`, framed for `quality` (every quality frames it the same; the picture's size is
/// 1.5 times its height).
pub fn scene(table: &LiveTable, lighting: Lighting, quality: Quality) -> Result<Scene> {
    let path = Path::new("panel.toml");
    let file = format!("{MATERIAL}.gbrdf");
    let panel = Panel {
        table: file.clone(),
        coat_index: table.coat_index,
    };
    let text = description("panel", &[panel], lighting, quality.shot());
    let assets = Assets::new()
        .with_table(file, table.table.clone())
        .with_image(lighting.map_file(), lighting.map())
        .with_mesh(MESH, mesh());
    Scene::build_with(&SceneDesc::from_toml(&text, path)?, path, &assets)
}

/// The pixels of `scene` (made by [`scene`]) that show the panel alone: those whose four
/// corners, inset a tenth of a pixel, all see its material (no floor mixed in), row-major
/// indices. For statistics of the panel's colour.
pub fn panel_pixels(scene: &Scene) -> Vec<usize> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let on_panel = |x: f64, y: f64| {
        let ray = scene.camera.ray(DVec2::new(x, y));
        scene
            .accel
            .intersect(&ray, 0.0, f64::INFINITY)
            .is_some_and(|hit| {
                matches!(scene.prims[hit.prim], PrimKind::Surface(m)
                    if scene.materials[m].name == MATERIAL)
            })
    };
    (0..w * h)
        .filter(|&i| {
            let (x, y) = ((i % w) as f64, (i / w) as f64);
            [(0.1, 0.1), (0.9, 0.1), (0.1, 0.9), (0.9, 0.9)]
                .iter()
                .all(|(dx, dy)| on_panel(x + dx, y + dy))
        })
        .collect()
}
