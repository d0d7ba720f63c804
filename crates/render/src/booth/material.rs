//! The specimen's material from a file: a coating description (`.toml`, as `gonio coating`
//! takes it; its spectral table computed as for the panel pictures,
//! [`crate::coating_material::from_coating`], a smooth top's mirror added by its index) or a
//! spectral BRDF table (`.gbrdf`, used as it is: a smooth top's mirror that the table leaves out
//! is not added).

use crate::coating_material::{FlakeMode, from_coating};
use crate::error::{RenderError, Result};
use crate::material::{Material, read_table};
use gonio_coating::system::default_bands;
use std::path::Path;

/// The material in `path`: a coating description (`.toml`) or a `.gbrdf` table.
pub fn material(path: &Path) -> Result<Material> {
    let ext = gonio_io::extension(path);
    match ext.as_str() {
        "toml" => {
            let coating = gonio_coating::description::read(path, &default_bands())
                .map_err(|e| RenderError::scene(path, e.to_string()))?;
            from_coating(
                "specimen",
                &coating,
                &path.display().to_string(),
                FlakeMode::Smooth,
                1,
            )
            .map_err(|e| RenderError::scene(path, e.to_string()))
        }
        "gbrdf" => Ok(Material::from_table("specimen", read_table(path)?)),
        _ => Err(RenderError::scene(
            path,
            "the booth's material is a coating description (.toml) or a spectral table (.gbrdf)",
        )),
    }
}
