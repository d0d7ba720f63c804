//! What a scene names by file but its caller holds in memory: a table just computed, an
//! environment map drawn by the program, a mesh embedded in it. A scene description is built
//! the same way either way ([`crate::Scene::build_with`]): each file name it gives (`table`,
//! `file` of a mesh or an environment) is looked up here first, as written in the description,
//! and read from disk only when absent. So the pictures of [`crate::panel`] are made without a
//! folder, from the very description `gonio render` would read beside its files.

use crate::geometry::Shape;
use crate::image::Image;
use gonio_brdf::table::SampledTable;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Files held in memory, by the name a scene description gives them.
#[derive(Clone, Default)]
pub struct Assets {
    tables: BTreeMap<PathBuf, Arc<SampledTable>>,
    images: BTreeMap<PathBuf, Arc<Image>>,
    meshes: BTreeMap<PathBuf, Arc<Vec<Shape>>>,
}

impl Assets {
    /// No file in memory: every name is read from disk.
    pub fn new() -> Assets {
        Assets::default()
    }

    /// A material's `table = "NAME"` is `table` (its sampler already built, so that a
    /// caller rendering the same table again does not build it again).
    pub fn with_table(mut self, name: impl Into<PathBuf>, table: Arc<SampledTable>) -> Assets {
        self.tables.insert(name.into(), table);
        self
    }

    /// An environment light's `file = "NAME"` is `image` (linear, equirectangular).
    pub fn with_image(mut self, name: impl Into<PathBuf>, image: Arc<Image>) -> Assets {
        self.images.insert(name.into(), image);
        self
    }

    /// A mesh's `file = "NAME"` is `triangles` (as [`crate::mesh::parse_obj`] returns them).
    pub fn with_mesh(mut self, name: impl Into<PathBuf>, triangles: Arc<Vec<Shape>>) -> Assets {
        self.meshes.insert(name.into(), triangles);
        self
    }

    /// The table named `name`, if held.
    pub fn table(&self, name: &Path) -> Option<&Arc<SampledTable>> {
        self.tables.get(name)
    }

    /// The image named `name`, if held.
    pub fn image(&self, name: &Path) -> Option<&Arc<Image>> {
        self.images.get(name)
    }

    /// The mesh named `name`, if held.
    pub fn mesh(&self, name: &Path) -> Option<&Arc<Vec<Shape>>> {
        self.meshes.get(name)
    }
}
