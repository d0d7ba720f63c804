//! Materials made from a coating description (`coating = "silver.toml"` in a scene): the
//! coating's spectral table computed when the scene is loaded (`gonio coating compute`'s
//! walks, at a panel picture's resolution, [`crate::panel::resolution`]), the mirror of a
//! smooth top added by its index, and, with `flakes = "discrete"`, the flakes drawn one by
//! one ([`crate::flakes`]) over the table that leaves their glint out.

use crate::error::{RenderError, Result};
use crate::flakes::FlakeField;
use crate::material::Material;
use crate::panel;
use gonio_coating::glint::Glint;
use gonio_coating::system::{Coating, default_bands};
use gonio_io::Cancel;
use serde::Deserialize;
use std::path::Path;

/// How a coating's flakes are drawn.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FlakeMode {
    /// As their average BRDF, in the table (no sparkle; the default).
    #[default]
    Smooth,
    /// One by one: each flake mirrors the light it catches (sparkle).
    Discrete,
}

/// The material `name` of the coating described in `path` (the scene file `scene` named in
/// errors), its flakes drawn as `mode` says and placed by `seed`.
pub fn material(
    name: &str,
    path: &Path,
    scene: &Path,
    mode: FlakeMode,
    seed: u64,
) -> Result<Material> {
    let bad = |p: String| RenderError::scene(scene, format!("material `{name}`: {p}"));
    let coating = gonio_coating::description::read(path, &default_bands())
        .map_err(|e| bad(format!("coating {}: {e}", path.display())))?;
    from_coating(name, &coating, &path.display().to_string(), mode, seed)
        .map_err(|e| bad(format!("coating {}: {e}", path.display())))
}

/// The material `name` of `coating` (described in `source`, for the table's provenance), its
/// flakes drawn as `mode` says and placed by `seed`.
pub fn from_coating(
    name: &str,
    coating: &Coating,
    source: &str,
    mode: FlakeMode,
    seed: u64,
) -> Result<Material> {
    let bands = default_bands();
    let glint = match mode {
        FlakeMode::Smooth => None,
        FlakeMode::Discrete => Some(Glint::new(coating, &bands)?.ok_or_else(|| {
            RenderError::Invalid(
                "flakes = \"discrete\" needs a coating with [flakes]; this one has none".into(),
            )
        })?),
    };
    let table = table(coating, source, glint.as_ref())?;
    let mut material = Material::from_table(name, table);
    if let Some(n) = panel::coat_index(coating) {
        material = material.with_coat(n);
    }
    if let Some(glint) = glint {
        material = material.with_flakes(FlakeField::new(glint, seed)?);
    }
    Ok(material)
}

/// `coating`'s table for a picture, without `glint` when given.
fn table(
    coating: &Coating,
    source: &str,
    glint: Option<&Glint>,
) -> gonio_coating::Result<gonio_brdf::table::BrdfTable> {
    let bands = default_bands();
    let provenance = coating.provenance(source, coating.method(panel::WALKS));
    let resolution = panel::resolution(coating);
    match glint {
        None => coating.table(resolution, &bands, panel::WALKS, provenance),
        Some(_) => coating.table_without_glint(
            resolution,
            &bands,
            panel::WALKS,
            provenance,
            &Cancel::default(),
        ),
    }
}
