//! The virtual viewing booth (issue 44, `docs/standard.md`): a normative scene after ASTM D1729
//! and ISO 3668 (a D65 or measured light at a stated illuminance on the specimen, diffuse from
//! a grey booth and directional from a collimated source, a flat or curved specimen, three
//! named views, a CIE observer) rendered as absolute CIE XYZ in cd/m² per pixel, so that a
//! picture is a measurement: the mean of a flat specimen's pixels under the collimated light is
//! what a multi-angle instrument reads (the closure tests, `tests/it/booth.rs` and
//! `tests/it/booth_doi.rs`).
//!
//! - [`spec`]: the description (TOML) and its checks.
//! - [`scene`]: the booth as a scene, its lights scaled to the illuminance, the views' cameras.
//! - [`mod@material`]: the specimen's material from a coating description or a `.gbrdf` table.
//! - [`closure`]: the picture's side of the closure against the multi-angle instrument (a flat
//!   panel's mean CIELAB at a geometry, with its noise bound).
//! - [`input`]: a booth spec, a coating or a table, told apart by its file.
//! - [`files`]: the whole booth written into a folder (pictures, masks, manifest) with a
//!   summary.
//!
//! Rendering is the path tracer's spectral mode with the absolute film
//! ([`crate::Film::Absolute`]), so the picture is identical for any number of threads
//! ([`crate::integrator`]) and reproducible from the spec, the material and the seed.

pub mod closure;
pub mod files;
pub mod input;
pub mod material;
pub mod scene;
pub mod spec;

pub use files::{BoothJob, BoothSummary, Specimen, ViewSummary, write_booth, write_booth_of};
pub use input::{BoothInput, Resolved};
pub use material::material;
pub use scene::ViewGeometry;
pub use spec::{BoothSpec, Checked, Projection, View};

use crate::error::Result;
use crate::material::Material;
use crate::settings::{ColourMode, Film};
use crate::{RenderOptions, render_estimate_on};
use gonio_color::{Observer, WeightingFactors};
use gonio_io::{Cancel, Progress};
use scene::BoothScene;
use std::f64::consts::PI;

/// A picture in absolute CIE XYZ: cd/m² (Y is the luminance), row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct XyzImage {
    pub width: usize,
    pub height: usize,
    pub xyz: Vec<[f32; 3]>,
}

/// One view of the booth.
#[derive(Debug, Clone, PartialEq)]
pub struct BoothView {
    /// `near-specular`, `45`, `flank` or `asG`.
    pub name: String,
    /// Where its camera is.
    pub camera: ViewGeometry,
    /// The picture.
    pub image: XyzImage,
    /// The variance of each pixel's Y (the samples' variance over their number), (cd/m²)².
    pub variance: Vec<f32>,
    /// Per pixel, whether the specimen covers it whole.
    pub specimen: Vec<bool>,
}

/// The booth's pictures and what a display or a reader of them needs.
#[derive(Debug, Clone, PartialEq)]
pub struct BoothPictures {
    /// The views, in the spec's order.
    pub views: Vec<BoothView>,
    /// The observer of the XYZ.
    pub observer: Observer,
    /// The white: the XYZ of the perfect reflecting diffuser at the specimen's centre under
    /// the booth's light, `E/π` cd/m² in Y (E the illuminance).
    pub white: [f64; 3],
    /// The illuminance on the specimen's centre, lx.
    pub illuminance_lux: f64,
    /// The light's name: `D65`, `A` or the measured spectrum's file.
    pub light: String,
}

/// How a booth render runs (none of it changes the pictures).
#[derive(Debug, Clone, Default)]
pub struct Run {
    /// Threads (`None`: all cores).
    pub threads: Option<usize>,
    /// Where to report progress (stage `booth`: views done; `rendering`: tiles of a view).
    pub progress: Progress,
    /// Raised, the render stops with [`crate::RenderError::Cancelled`].
    pub cancel: Cancel,
}

/// Render every view of the booth `spec` with `material` on its specimen.
pub fn render(spec: &BoothSpec, material: &Material, run: &Run) -> Result<BoothPictures> {
    let checked = spec.check()?;
    let mut booth = BoothScene::new(&checked, material.clone())?;
    let options = RenderOptions {
        spp: Some(spec.render.spp),
        seed: Some(spec.render.seed),
        max_bounces: Some(spec.render.max_bounces),
        threads: run.threads,
        colour: ColourMode::Spectral,
        denoise: Some(false),
        progress: run.progress.clone(),
        cancel: run.cancel.clone(),
        ..RenderOptions::default()
    };
    let film = Film::Absolute {
        light: checked.light.spectrum.clone(),
        observer: checked.observer,
    };
    let (w, h) = (spec.render.width, spec.render.height);
    let mut views = Vec::new();
    for (k, view) in checked.views.iter().enumerate() {
        let camera = booth.set_view(&checked, view, w, h);
        let estimate = render_estimate_on(&booth.scene, &options, &film)?;
        views.push(BoothView {
            name: view.name.clone(),
            camera,
            image: XyzImage {
                width: w,
                height: h,
                xyz: estimate.image.pixels,
            },
            variance: estimate.variance,
            specimen: booth.specimen_mask(),
        });
        run.progress
            .report("booth", k as u64 + 1, checked.views.len() as u64);
    }
    Ok(BoothPictures {
        views,
        observer: checked.observer,
        white: white(&checked),
        illuminance_lux: checked.illuminance_lux,
        light: checked.light.name.clone(),
    })
}

/// The perfect diffuser's XYZ under the booth's light at its illuminance E: the light's white
/// (the weighting factors' sums, Y = 100) scaled to `Y = E/π`.
pub fn white(spec: &Checked) -> [f64; 3] {
    let white = WeightingFactors::of_spectrum(&spec.light.spectrum, spec.observer).white();
    white
        .to_array()
        .map(|v| v / 100.0 * spec.illuminance_lux / PI)
}
