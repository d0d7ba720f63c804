//! The lab's computations, each one library call (the same the CLI and the Python package
//! make): the readings of a formulation, its picture, its table's export, an uploaded
//! topography's statistics and a target's readings. This module only adapts their results to
//! JSON and bytes for the page.

use crate::error::{ApiError, refused};
use crate::state::Upload;
use gonio_coating::system::{Coating, default_bands};
use gonio_instrument::multiangle;
use gonio_io::Cancel;
use serde_json::{Value, json};
use std::path::Path;

/// What the readings are asked for.
#[derive(Clone, Debug)]
pub struct ReadingOptions {
    /// "E2194" or "E2539".
    pub standard: String,
    /// Incidence of the in-plane BRDF, degrees.
    pub incidence_deg: f64,
}

/// The geometries of the standard `name`, or the client's error.
fn geometries(name: &str) -> Result<&'static [multiangle::Geometry], ApiError> {
    multiangle::standard(name).map_err(|e| ApiError::BadRequest(e.to_string()))
}

/// The readings of `coating` as JSON, with ΔE00 against `target` when given.
pub fn readings(
    coating: &Coating,
    options: &ReadingOptions,
    target: Option<&Upload>,
    cancel: &Cancel,
) -> Result<Value, ApiError> {
    let geometries = geometries(&options.standard)?;
    let start = std::time::Instant::now();
    let reading = gonio_instrument::coating_study::read_coating(
        coating,
        geometries,
        &default_bands(),
        256,
        4,
        0,
    )
    .map_err(|e| refused(cancel, e))?;
    let mut value = json!({
        "gloss": {
            "gu20": reading.gloss.gu20, "gu60": reading.gloss.gu60, "gu85": reading.gloss.gu85,
            "haze": reading.gloss.haze, "haze_20_log": reading.gloss.haze_20_log,
            "doi": reading.gloss.doi, "doi_uncertainty": reading.gloss.doi_uncertainty,
        },
        "multiangle": {
            "standard": options.standard,
            "flop_index": reading.multiangle.flop_index(),
            "geometries": reading.multiangle.geometries.iter().map(|g| json!({
                "name": g.geometry.to_string(), "L": g.lab.l, "a": g.lab.a, "b": g.lab.b,
            })).collect::<Vec<_>>(),
        },
    });
    if let Some(target) = target {
        let t = gonio_formulation::target::read_target(&target.path, geometries).map_err(|e| {
            ApiError::BadRequest(
                e.to_string()
                    .replace(&target.path.display().to_string(), &target.name),
            )
        })?;
        let de = t
            .de00(&reading.multiangle)
            .map_err(|e| ApiError::BadRequest(e.to_string()))?;
        value["target"] = json!({ "name": target.name, "de00": de });
    }
    value["seconds"] = json!(start.elapsed().as_secs_f64());
    Ok(value)
}

/// The light settings of the pictures: `[{name, description}]`.
pub fn lightings() -> Value {
    json!([{ "name": "studio", "description": "a dark studio with two softboxes" }])
}

/// What a picture is asked for.
#[derive(Clone, Debug)]
pub struct PictureOptions {
    pub lighting: String,
    pub converged: bool,
}

impl PictureOptions {
    /// The options from the request's names (defaults: the first lighting, a preview).
    pub fn parse(
        lighting: Option<&str>,
        quality: Option<&str>,
    ) -> Result<PictureOptions, ApiError> {
        let converged = match quality.unwrap_or("preview") {
            "preview" => false,
            "converged" => true,
            other => {
                return Err(ApiError::BadRequest(format!(
                    "quality '{other}': give preview or converged"
                )));
            }
        };
        Ok(PictureOptions {
            lighting: lighting.unwrap_or("studio").to_string(),
            converged,
        })
    }
}

/// A picture: the PNG and the figures sent beside it as headers.
pub struct Picture {
    pub png: Vec<u8>,
    pub figures: Vec<(&'static str, String)>,
}

/// The picture of `coating` on the panel.
pub fn picture(
    coating: &Coating,
    options: &PictureOptions,
    cancel: &Cancel,
) -> Result<Picture, ApiError> {
    let _ = (options, cancel);
    let dir = tempfile::tempdir().map_err(|e| ApiError::Internal(e.to_string()))?;
    let bands = default_bands();
    let table = coating
        .table(
            gonio_brdf::table::Resolution::isotropic(12, 12, 6),
            &bands,
            4,
            gonio_brdf::table::Provenance::default(),
        )
        .map_err(|e| refused(cancel, e))?;
    gonio_brdf::gbrdf::write(&table, &dir.path().join("c.gbrdf"))
        .map_err(|e| ApiError::Internal(e.to_string()))?;
    let panel = gonio_render::panel::Panel {
        table: "c.gbrdf".into(),
        coat_index: coating
            .roughness
            .is_none()
            .then(|| coating.coat.index.at(550.0)),
    };
    let scene = gonio_render::panel::scene(dir.path(), "lab", &[panel])
        .map_err(|e| ApiError::Internal(e.to_string()))?;
    let (image, display, stats) =
        gonio_render::panel::render_image(&scene).map_err(|e| refused(cancel, e))?;
    Ok(Picture {
        png: png(&image, display)?,
        figures: vec![("x-gonio-seconds", format!("{:.3}", stats.seconds))],
    })
}

/// `image` tone-mapped for `display`, as PNG bytes.
fn png(image: &gonio_render::Image, display: gonio_render::Display) -> Result<Vec<u8>, ApiError> {
    let rgb = image::RgbImage::from_raw(
        image.width as u32,
        image.height as u32,
        image.to_srgb8(display),
    )
    .ok_or_else(|| ApiError::Internal("a picture of the wrong size".into()))?;
    let mut out = std::io::Cursor::new(Vec::new());
    rgb.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| ApiError::Internal(format!("PNG: {e}")))?;
    Ok(out.into_inner())
}

/// A table export's format.
#[derive(Clone, Copy, Debug)]
pub enum ExportFormat {
    Gbrdf,
    Mitsuba,
}

impl ExportFormat {
    pub fn parse(name: &str) -> Result<ExportFormat, ApiError> {
        match name {
            "gbrdf" => Ok(ExportFormat::Gbrdf),
            "mitsuba" => Ok(ExportFormat::Mitsuba),
            other => Err(ApiError::NotFound(format!(
                "no export '{other}': give gbrdf or mitsuba"
            ))),
        }
    }
}

/// The table of `coating` (described by `text`) written in `format`: the bytes and a file name.
pub fn export(
    coating: &Coating,
    text: &str,
    format: ExportFormat,
    cancel: &Cancel,
) -> Result<(Vec<u8>, String), ApiError> {
    let _ = (coating, text, format, cancel);
    Err(ApiError::Internal("export: not yet".into()))
}

/// The statistics of an uploaded topography (ISO 25178 after levelling).
pub fn topography(path: &Path) -> Result<Value, ApiError> {
    let map = gonio_surface::io::read(path).map_err(|e| ApiError::BadRequest(e.to_string()))?;
    let s =
        gonio_surface::stats::statistics(&map).map_err(|e| ApiError::BadRequest(e.to_string()))?;
    Ok(json!({
        "nx": map.nx(), "ny": map.ny(), "dx_um": map.dx() * 1e6, "dy_um": map.dy() * 1e6,
        "sq_um": s.sq * 1e6, "sa_um": s.sa * 1e6, "ssk": s.ssk, "sku": s.sku, "sdq": s.sdq,
        "sal_um": s.sal.map(|v| v * 1e6),
    }))
}

/// The readings of an uploaded target at the standard's geometries.
pub fn target(path: &Path, standard: &str, cancel: &Cancel) -> Result<Value, ApiError> {
    let _ = cancel;
    let t = gonio_formulation::target::read_target(path, geometries(standard)?)
        .map_err(|e| ApiError::BadRequest(e.to_string()))?;
    Ok(json!({ "source": t.source }))
}
