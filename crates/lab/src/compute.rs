//! The lab's computations, each one library call (the same the CLI and the Python package
//! make): the readings of a formulation, its picture, its table's export, an uploaded
//! topography's statistics and a target's readings. This module only adapts their results to
//! JSON and bytes for the page.

use crate::error::{ApiError, refused};
use crate::state::Upload;
use gonio_coating::system::Coating;
use gonio_formulation::lab_target::{self, LabTarget};
use gonio_instrument::coating_readings::{self, ReadingsRequest};
use gonio_instrument::multiangle::Standard;
use gonio_io::Cancel;
use gonio_render::panel::Lighting;
use gonio_render::panel::live::{self, LiveTable, Quality};
use serde_json::{Value, json};

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
    .map_err(|e| upload.named(refused(cancel, e)))
}

/// The light settings of the pictures: `[{name, description}]`.
pub fn lightings() -> Value {
    Value::Array(
        Lighting::ALL
            .iter()
            .map(|l| json!({ "name": l.name(), "description": l.description() }))
            .collect(),
    )
}

/// What a picture is asked for.
#[derive(Clone, Copy, Debug)]
pub struct PictureOptions {
    pub lighting: Lighting,
    pub quality: Quality,
}

impl PictureOptions {
    /// The options from the request's names (defaults: the first lighting, a preview).
    pub fn parse(
        lighting: Option<&str>,
        quality: Option<&str>,
    ) -> Result<PictureOptions, ApiError> {
        let names = |all: Vec<&str>| all.join(", ");
        Ok(PictureOptions {
            lighting: match lighting {
                None => Lighting::ALL[0],
                Some(name) => Lighting::from_name(name).ok_or_else(|| {
                    ApiError::BadRequest(format!(
                        "lighting '{name}': give one of {}",
                        names(Lighting::ALL.iter().map(|l| l.name()).collect())
                    ))
                })?,
            },
            quality: match quality {
                None => Quality::Preview,
                Some(name) => Quality::from_name(name).ok_or_else(|| {
                    ApiError::BadRequest(format!(
                        "quality '{name}': give one of {}",
                        names(Quality::ALL.iter().map(|q| q.name()).collect())
                    ))
                })?,
            },
        })
    }
}

/// A picture: the PNG and the figures sent beside it as headers.
pub struct Picture {
    pub png: Vec<u8>,
    pub figures: Vec<(&'static str, String)>,
}

/// The picture of the coating whose table at the picture's quality is `table` (see
/// [`crate::Lab::table`]), on the panel under the options' light.
pub fn picture(
    table: &LiveTable,
    options: &PictureOptions,
    cancel: &Cancel,
) -> Result<Picture, ApiError> {
    let shown = live::picture(table, options.lighting, options.quality, cancel)
        .map_err(|e| refused(cancel, e))?;
    let f = shown.figures;
    let r = f.resolution;
    Ok(Picture {
        png: shown.png,
        figures: vec![
            ("x-gonio-quality", options.quality.name().to_string()),
            ("x-gonio-table-seconds", format!("{:.3}", f.table_seconds)),
            ("x-gonio-render-seconds", format!("{:.3}", f.render_seconds)),
            ("x-gonio-spp", f.spp.to_string()),
            ("x-gonio-size", format!("{}x{}", f.size.0, f.size.1)),
            (
                "x-gonio-table",
                format!(
                    "{}x{}x{} nodes, {} walks, {} bands",
                    r.theta_h, r.theta_d, r.phi_d, f.walks, f.bands
                ),
            ),
        ],
    })
}

/// The table of `coating` for pictures at `quality` (its nodes, walks and bands).
pub fn table(coating: &Coating, quality: Quality, cancel: &Cancel) -> Result<LiveTable, ApiError> {
    live::live_table(coating, quality, cancel).map_err(|e| refused(cancel, e))
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
                "no export '{other}': give gbrdf (gonio's spectral table) or mitsuba (a Mitsuba 3 \
                 tensor)"
            ))),
        }
    }
}

/// `table` (a coating's converged picture table) written in `format`: the bytes and a file name.
pub fn export(table: &LiveTable, format: ExportFormat) -> Result<(Vec<u8>, String), ApiError> {
    let dir =
        tempfile::tempdir().map_err(|e| ApiError::Internal(format!("a temporary folder: {e}")))?;
    let (name, written) = match format {
        ExportFormat::Gbrdf => {
            let name = "coating.gbrdf";
            (
                name,
                gonio_brdf::gbrdf::write(table.table.table(), &dir.path().join(name)),
            )
        }
        ExportFormat::Mitsuba => {
            let name = "coating_mitsuba.bsdf";
            let options = gonio_brdf::formats::mitsuba::MitsubaOptions::default();
            (
                name,
                gonio_brdf::formats::mitsuba::write(
                    table.table.table(),
                    &dir.path().join(name),
                    options,
                ),
            )
        }
    };
    written.map_err(|e| ApiError::Internal(format!("writing the table: {e}")))?;
    let bytes = std::fs::read(dir.path().join(name))
        .map_err(|e| ApiError::Internal(format!("reading the table back: {e}")))?;
    Ok((bytes, name.to_string()))
}

/// The statistics of an uploaded topography (ISO 25178 after levelling); the reader's errors
/// name the client's file.
pub fn topography(upload: &Upload) -> Result<Value, ApiError> {
    let refused = |e: &dyn std::fmt::Display| upload.named(ApiError::BadRequest(e.to_string()));
    let map = gonio_surface::io::read(&upload.path).map_err(|e| refused(&e))?;
    let s = gonio_surface::stats::statistics(&map).map_err(|e| refused(&e))?;
    Ok(json!({
        "nx": map.nx(), "ny": map.ny(), "dx_um": map.dx() * 1e6, "dy_um": map.dy() * 1e6,
        "sq_um": s.sq * 1e6, "sa_um": s.sa * 1e6, "ssk": s.ssk, "sku": s.sku, "sdq": s.sdq,
        "sal_um": s.sal.map(|v| v * 1e6),
    }))
}
