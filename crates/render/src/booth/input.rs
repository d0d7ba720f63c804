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
    Spec(BoothSpec),
    /// A material file (a coating description or a `.gbrdf` table) for a booth given otherwise.
    Material(PathBuf),
}

impl BoothInput {
    /// Read `path` and tell what it is: a `.gbrdf` is a material; a `.toml` is a coating when
    /// it has a coating's tables (`[coat]`, `[base]`, `[top]`, `[flakes]`), a booth spec when
    /// every top-level key is a booth's (an empty file is the standard booth); anything else is
    /// an error that says which keys it found and what each kind of file holds.
    pub fn from_file(path: &Path) -> Result<BoothInput> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
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
                    Ok(BoothInput::Spec(BoothSpec::from_toml(&text, path)?))
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
