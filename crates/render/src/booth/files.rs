//! The booth's files in one call (issue 44, point 1): render every view of a spec for a
//! material ([`super::render`]) and write into a folder each view's pictures
//! ([`crate::picture::write_view`]: the absolute XYZ OpenEXR, an sRGB and a Display P3 PNG with
//! their masks), the specimen's mask, and the manifest ([`crate::picture::write_manifest`]:
//! every input's and output's SHA-256, the files a coating description names among the inputs,
//! the seed and every setting), and return a summary that a
//! front end prints: per view the specimen's mean luminance and what each display could not
//! show.
//!
//! Every file is written atomically (a temporary file beside it, renamed), so a failed run
//! leaves no half-written file; the manifest is written last, so a folder with a manifest holds
//! a complete set. A view that cannot be written is named in the error.

use super::closure::specimen_mean;
use super::{BoothPictures, BoothSpec, Run, material, render};
use crate::error::{RenderError, Result};
use crate::material::Material;
use crate::picture::{ViewFiles, XyzPicture, write_manifest, write_view};
use gonio_io::extension;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// What the booth rendered from and how (the manifest's inputs and settings).
#[derive(Debug, Clone)]
pub struct BoothJob<'a> {
    /// The booth (its `dir` is where its relative paths start).
    pub spec: &'a BoothSpec,
    /// The spec's file, when the booth came from one (an input of the manifest).
    pub spec_file: Option<&'a Path>,
    /// The specimen's material, when given outside the spec; else the spec's
    /// `[specimen] material` ([`BoothSpec::material_path`]).
    pub material: Option<&'a Path>,
}

/// One view's summary.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewSummary {
    /// The view's name.
    pub name: String,
    /// Its aspecular angle, degrees.
    pub aspecular_deg: f64,
    /// The mean luminance Y of the pixels the specimen covers whole, cd/m² (NaN when it
    /// covers none).
    pub specimen_luminance: f64,
    /// How many pixels the specimen covers whole.
    pub specimen_pixels: usize,
    /// The view's picture files and, per display, the fractions of its pixels out of gamut
    /// and over range.
    pub files: ViewFiles,
    /// The specimen's mask: an 8-bit grey PNG, 255 where the specimen covers the pixel whole.
    pub specimen_mask: PathBuf,
}

/// What [`write_booth`] wrote and read off its pictures.
#[derive(Debug, Clone, PartialEq)]
pub struct BoothSummary {
    /// The views, in the spec's order.
    pub views: Vec<ViewSummary>,
    /// The manifest (JSON).
    pub manifest: PathBuf,
    /// The specimen's material file.
    pub material: PathBuf,
    /// The perfect diffuser's XYZ in the booth, cd/m² (the displays' white).
    pub white: [f64; 3],
    /// The illuminance on the specimen's centre, lx.
    pub illuminance_lux: f64,
    /// The light's name.
    pub light: String,
    /// The renderer's seed.
    pub seed: u32,
}

impl BoothSummary {
    /// The summary as JSON (paths as written, luminances in cd/m²).
    pub fn to_json(&self) -> Value {
        let views: Vec<Value> = self
            .views
            .iter()
            .map(|v| {
                let displays: Vec<Value> = v
                    .files
                    .displays
                    .iter()
                    .map(|d| {
                        json!({
                            "display": d.space.file_stem(),
                            "png": d.png,
                            "mask": d.mask,
                            "out_of_gamut_fraction": d.out_of_gamut_fraction,
                            "over_range_fraction": d.over_range_fraction,
                        })
                    })
                    .collect();
                json!({
                    "name": v.name,
                    "aspecular_deg": v.aspecular_deg,
                    "specimen_luminance_cd_m2": finite_or_null(v.specimen_luminance),
                    "specimen_pixels": v.specimen_pixels,
                    "exr": v.files.exr,
                    "specimen_mask": v.specimen_mask,
                    "displays": displays,
                })
            })
            .collect();
        json!({
            "manifest": self.manifest,
            "material": self.material,
            "light": self.light,
            "illuminance_lux": self.illuminance_lux,
            "white_xyz_cd_m2": self.white,
            "seed": self.seed,
            "views": views,
        })
    }
}

/// A number for JSON: NaN (no specimen pixel) as null.
fn finite_or_null(v: f64) -> Value {
    if v.is_finite() { json!(v) } else { Value::Null }
}

/// Render the booth of `job` and write its files into the folder `dir` (made if missing):
/// per view `NAME.exr`, `NAME-srgb.png`, `NAME-srgb-mask.png`, `NAME-p3.png`,
/// `NAME-p3-mask.png`, `NAME-specimen.png`, then `manifest.json`. The material is read from
/// its file ([`material()`]); [`write_booth_of`] takes one already made.
pub fn write_booth(job: &BoothJob, dir: &Path, run: &Run) -> Result<BoothSummary> {
    let file = job.spec.material_path(job.material)?;
    let made = material(&file)?;
    let specimen = Specimen {
        material: &made,
        file: &file,
        made: None,
    };
    write_booth_of(job.spec, job.spec_file, &specimen, dir, run)
}

/// A specimen's material made by the caller (a table computed at its own resolution, say),
/// and what the manifest records of it.
#[derive(Debug, Clone, Copy)]
pub struct Specimen<'a> {
    /// The material on the specimen.
    pub material: &'a Material,
    /// The file it was made from: an input of the manifest, with the files it names (a
    /// coating description's height map or index table,
    /// [`gonio_coating::description::referenced_files`]).
    pub file: &'a Path,
    /// How it was made from the file, when not as [`material()`] makes it (the manifest's
    /// setting `material_made`).
    pub made: Option<&'a Value>,
}

/// The booth `spec` (from the file `spec_file`, when it came from one) rendered with
/// `specimen` and written into `dir` as [`write_booth`] writes it.
pub fn write_booth_of(
    spec: &BoothSpec,
    spec_file: Option<&Path>,
    specimen: &Specimen,
    dir: &Path,
    run: &Run,
) -> Result<BoothSummary> {
    let checked = spec.check()?;
    std::fs::create_dir_all(dir).map_err(|error| RenderError::Io {
        path: dir.to_path_buf(),
        error,
    })?;
    let pictures = render(spec, specimen.material, run)?;
    let views = write_views(&pictures, dir, &checked.views)?;

    let mut inputs: Vec<PathBuf> = spec_file.map(Path::to_path_buf).into_iter().collect();
    if let Some(file) = &spec.light.spectrum {
        inputs.push(if file.is_absolute() {
            file.clone()
        } else {
            spec.dir.join(file)
        });
    }
    inputs.push(specimen.file.to_path_buf());
    if extension(specimen.file) == "toml" {
        inputs.extend(
            gonio_coating::description::referenced_files(specimen.file)
                .map_err(|e| RenderError::scene(specimen.file, e.to_string()))?,
        );
    }
    let mut outputs: Vec<&Path> = Vec::new();
    for v in &views {
        outputs.extend(v.files.paths());
        outputs.push(&v.specimen_mask);
    }
    let mut settings = json!({
        "booth": spec,
        "material": specimen.file,
        "light": pictures.light,
        "white_xyz_cd_m2": pictures.white,
        "render": {
            "colour": "spectral",
            "film": "absolute CIE XYZ, cd/m^2",
            "denoise": false,
        },
    });
    if let Some(made) = specimen.made {
        settings["material_made"] = made.clone();
    }
    let manifest = dir.join("manifest.json");
    let input_refs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    write_manifest(
        &manifest,
        &input_refs,
        u64::from(spec.render.seed),
        &settings,
        &outputs,
    )?;
    Ok(BoothSummary {
        views,
        manifest,
        material: specimen.file.to_path_buf(),
        white: pictures.white,
        illuminance_lux: pictures.illuminance_lux,
        light: pictures.light,
        seed: spec.render.seed,
    })
}

/// Write every view's files, naming the view that failed.
fn write_views(
    pictures: &BoothPictures,
    dir: &Path,
    views: &[super::View],
) -> Result<Vec<ViewSummary>> {
    pictures
        .views
        .iter()
        .zip(views)
        .map(|(view, spec_view)| {
            let failed = |e: RenderError| {
                RenderError::Invalid(format!("the booth's view `{}`: {e}", view.name))
            };
            let image = &view.image;
            let picture = XyzPicture::new(image.width, image.height, &image.xyz, pictures.observer)
                .map_err(failed)?;
            let files = write_view(dir, &view.name, &picture, pictures.white).map_err(failed)?;
            let specimen_mask = dir.join(format!("{}-specimen.png", view.name));
            write_grey_png(&specimen_mask, image.width, image.height, &view.specimen)
                .map_err(failed)?;
            let mean = specimen_mean(view);
            Ok(ViewSummary {
                name: view.name.clone(),
                aspecular_deg: spec_view.aspecular_deg,
                specimen_luminance: mean.xyz[1],
                specimen_pixels: mean.pixels,
                files,
                specimen_mask,
            })
        })
        .collect()
}

/// An 8-bit grey PNG, 255 where `inside`, 0 elsewhere, written atomically.
fn write_grey_png(path: &Path, width: usize, height: usize, inside: &[bool]) -> Result<()> {
    let bytes: Vec<u8> = inside.iter().map(|&i| if i { 255 } else { 0 }).collect();
    crate::picture::write_png(
        path,
        (width, height),
        &bytes,
        image::ExtendedColorType::L8,
        None,
    )
}
