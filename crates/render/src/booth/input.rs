//! What a booth is rendered from, told apart by its file: a booth spec (`.toml` with the
//! booth's tables, [`BoothSpec`]), a coating description (`.toml` with `[coat]` and `[base]`,
//! `docs/coatings.md`) or a spectral BRDF table (`.gbrdf`). A coating or a table alone is put in
//! the standard booth (or a booth spec given beside it).

use super::BoothSpec;
use crate::error::{RenderError, Result};
use std::path::{Path, PathBuf};

/// The top-level keys of a booth spec.
pub const SPEC_KEYS: [&str; 6] = [
    "light",
    "interior",
    "specimen",
    "camera",
    "observer_deg",
    "render",
];

/// The top-level tables of a coating description.
pub const COATING_KEYS: [&str; 4] = ["top", "coat", "flakes", "base"];

/// A booth's input file, read and classified.
#[derive(Debug, Clone, PartialEq)]
pub enum BoothInput {
    /// A booth spec (read and checked); its specimen names the material.
    Spec(Box<BoothSpec>),
    /// A material file (a coating description or a `.gbrdf` table) for a booth given otherwise.
    Material(PathBuf),
}

impl BoothInput {
    /// Read `path` and tell what it is: a `.gbrdf` is a material; a `.toml` is a coating when
    /// it has a coating's tables (`[coat]`, `[base]`, `[top]`, `[flakes]`), a booth spec when
    /// every top-level key is a booth's (an empty file is the standard booth); anything else is
    /// an error that says which keys it found and what each kind of file holds.
    pub fn from_file(path: &Path) -> Result<BoothInput> {
        let ext = gonio_io::extension(path);
        match ext.as_str() {
            "gbrdf" => {
                if !path.is_file() {
                    return Err(RenderError::Io {
                        path: path.to_path_buf(),
                        error: std::io::Error::new(
                            std::io::ErrorKind::NotFound,
                            "no such file (a spectral BRDF table, .gbrdf)",
                        ),
                    });
                }
                Ok(BoothInput::Material(path.to_path_buf()))
            }
            "toml" => {
                let text = std::fs::read_to_string(path).map_err(|error| RenderError::Io {
                    path: path.to_path_buf(),
                    error,
                })?;
                let table: toml::Table =
                    toml::from_str(&text).map_err(|e| RenderError::scene(path, e.to_string()))?;
                let keys: Vec<&str> = table.keys().map(String::as_str).collect();
                if keys.iter().any(|k| COATING_KEYS.contains(k)) {
                    Ok(BoothInput::Material(path.to_path_buf()))
                } else if keys.iter().all(|k| SPEC_KEYS.contains(k)) {
                    Ok(BoothInput::Spec(Box::new(BoothSpec::from_toml(
                        &text, path,
                    )?)))
                } else {
                    Err(RenderError::scene(
                        path,
                        format!(
                            "neither a booth spec nor a coating description: its top-level keys \
                             are {}; a booth spec has only {} (docs/standard.md), a coating has \
                             [coat] and [base] (docs/coatings.md)",
                            keys.iter()
                                .map(|k| format!("`{k}`"))
                                .collect::<Vec<_>>()
                                .join(", "),
                            SPEC_KEYS
                                .iter()
                                .map(|k| format!("`{k}`"))
                                .collect::<Vec<_>>()
                                .join(", "),
                        ),
                    ))
                }
            }
            _ => Err(RenderError::scene(
                path,
                "the booth reads a booth spec or a coating description (.toml) or a spectral \
                 BRDF table (.gbrdf)",
            )),
        }
    }
}

/// A booth ready to render: the spec, its file (when there is one) and the material given
/// outside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolved {
    pub spec: BoothSpec,
    pub spec_file: Option<PathBuf>,
    pub material: Option<PathBuf>,
}

impl Resolved {
    /// The booth for `input` (a spec, a coating or a table, [`BoothInput::from_file`]) and an
    /// optional booth spec `booth` for a coating or table (default: the standard booth). A spec
    /// input with `booth` as well is an error; so is a spec that names no material.
    pub fn from_files(input: &Path, booth: Option<&Path>) -> Result<Resolved> {
        let resolved = match (BoothInput::from_file(input)?, booth) {
            (BoothInput::Spec(_), Some(b)) => {
                return Err(RenderError::scene(
                    input,
                    format!(
                        "a booth spec already; the booth spec {} is for a coating or table \
                         input (name the material in the spec's [specimen] material instead)",
                        b.display()
                    ),
                ));
            }
            (BoothInput::Spec(spec), None) => Resolved {
                spec: *spec,
                spec_file: Some(input.to_path_buf()),
                material: None,
            },
            (BoothInput::Material(path), Some(b)) => Resolved {
                spec: BoothSpec::from_file(b)?,
                spec_file: Some(b.to_path_buf()),
                material: Some(path),
            },
            (BoothInput::Material(path), None) => Resolved {
                spec: BoothSpec::default(),
                spec_file: None,
                material: Some(path),
            },
        };
        if resolved.material.is_none() {
            resolved.spec.material_path(None).map_err(|e| match e {
                RenderError::Invalid(problem) => RenderError::scene(input, problem),
                other => other,
            })?;
        }
        Ok(resolved)
    }

    /// The job for [`super::write_booth`].
    pub fn job(&self) -> super::BoothJob<'_> {
        super::BoothJob {
            spec: &self.spec,
            spec_file: self.spec_file.as_deref(),
            material: self.material.as_deref(),
        }
    }
}
