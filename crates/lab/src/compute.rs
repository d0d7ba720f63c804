//! The lab's computations, each one library call (the same the CLI and the Python package
//! make): the readings of a formulation, its picture, its table's export, an uploaded
//! topography's statistics and a target's readings. This module only adapts their results to
//! JSON and bytes for the page.

use crate::error::{ApiError, refused};
use crate::state::Upload;
use gonio_coating::system::{Coating, default_bands};
use gonio_formulation::lab_target::{self, LabTarget};
use gonio_instrument::coating_readings::{self, ReadingsRequest};
use gonio_instrument::multiangle::Standard;
use gonio_io::Cancel;
use serde_json::{Value, json};
use std::path::Path;

/// What the readings are asked for.
#[derive(Clone, Debug)]
pub struct ReadingOptions {
    pub standard: Standard,
    /// Incidence of the in-plane BRDF, degrees.
    pub incidence_deg: f64,
}

impl ReadingOptions {
    /// The options from the request's values (defaults: E2194, 45°).
    pub fn parse(
        standard: Option<&str>,
        incidence_deg: Option<f64>,
    ) -> Result<ReadingOptions, ApiError> {
        Ok(ReadingOptions {
            standard: Standard::parse(standard.unwrap_or("E2194"))
                .map_err(|e| ApiError::BadRequest(e.to_string()))?,
            incidence_deg: incidence_deg.unwrap_or(45.0),
        })
    }
}

/// The readings of `coating` as JSON (`Readings::to_json`, docs/instruments.md), with, given a
/// target, `target`: {`name`, `de00` [{`geometry`, `de00`}], `mean_de00`, `max_de00`, `read`
/// (the target's own readings at the same standard and incidence)} and `seconds`, the
/// computation's wall time.
pub fn readings(
    coating: &Coating,
    options: &ReadingOptions,
    target: Option<(&str, &LabTarget)>,
    cancel: &Cancel,
) -> Result<Value, ApiError> {
    let start = std::time::Instant::now();
    let request = ReadingsRequest {
        standard: options.standard,
        incidence_deg: options.incidence_deg,
        ..ReadingsRequest::default()
    };
    let readings =
        coating_readings::readings(coating, &request, cancel).map_err(|e| refused(cancel, e))?;
    let mut value = readings.to_json();
    if let Some((name, target)) = target {
        let de = target
            .de00(&readings)
            .map_err(|e| ApiError::BadRequest(e.to_string()))?;
        let mut comparison = lab_target::comparison_json(&de);
        comparison["name"] = json!(name);
        comparison["read"] = target.to_json();
        value["target"] = comparison;
    }
    value["seconds"] = json!(start.elapsed().as_secs_f64());
    Ok(value)
}

/// Read the uploaded target `upload` at `options`' standard and incidence (the reader's error,
/// naming the file by the client's name).
pub fn target(
    upload: &Upload,
    options: &ReadingOptions,
    cancel: &Cancel,
) -> Result<LabTarget, ApiError> {
    lab_target::read_lab_target(
        &upload.path,
        options.standard,
        options.incidence_deg,
        cancel,
    )
    .map_err(|e| {
        let e = refused(cancel, e);
        match e {
            ApiError::BadRequest(m) => {
                ApiError::BadRequest(m.replace(&upload.path.display().to_string(), &upload.name))
            }
            other => other,
        }
    })
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
