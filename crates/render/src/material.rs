//! Materials: what a surface's BRDF is made of. Three kinds: an analytic model of the `brdf`
//! crate (its [`ModelSpec`]), a tabulated BRDF read from a file (`.gbrdf`, Cornell `.astm`, MERL
//! `.binary`), importance-sampled by [`gonio_brdf::table::SampledTable`], or a height map
//! turned into a table by a scattering method (see [`crate::scene`]). A spectral table is seen
//! at the path's wavelengths in the spectral colour mode through its
//! [`gonio_brdf::SpectralBrdf`] view. Any of them may lie under a smooth clear coat
//! ([`Material::coat`]), whose mirror reflection is a delta lobe no table can hold. Any of them
//! may carry a mesoscale height map ([`Material::mesoscale`], orange peel), which tilts the
//! shading normal over the BRDF ([`crate::mesoscale`]).

use crate::error::{RenderError, Result};
use crate::flakes::FlakeField;
use crate::mesoscale::Mesoscale;
use gonio_brdf::formats::{astm, merl};
use gonio_brdf::models::ModelSpec;
use gonio_brdf::table::{BrdfTable, SampledTable};
use gonio_brdf::{Brdf, gbrdf};
use std::path::Path;
use std::sync::Arc;

/// A material: a BRDF shared by every primitive that uses it.
#[derive(Clone)]
pub struct Material {
    /// Its name in the scene file.
    pub name: String,
    /// The BRDF in the shading frame (z = shading normal, x = surface tangent), in linear sRGB;
    /// a spectral one ([`Brdf::spectral`]) is read at the path's wavelengths in the spectral
    /// mode.
    pub brdf: Arc<dyn Brdf>,
    /// The refractive index of a smooth clear coat over the BRDF, or `None`. Its mirror
    /// reflection `F(θ)` (Fresnel's unpolarised reflectance, the same at every wavelength) is
    /// added to the BRDF as a delta lobe, and `brdf` is then what the coat sends back from
    /// beneath it: the body table of a coating with a smooth top (`gonio coating compute`),
    /// which holds the coat's transmission both ways but not its mirror.
    pub coat: Option<f64>,
    /// A coating's flakes drawn one by one ([`FlakeField`]), whose glint the BRDF then leaves
    /// out; `None` for a material without discrete flakes.
    pub flakes: Option<Arc<FlakeField>>,
    /// A mesoscale height map whose slope tilts the shading normal ([`crate::mesoscale`]), or
    /// `None`.
    pub mesoscale: Option<Arc<Mesoscale>>,
}

impl Material {
    /// A material of an analytic model or any other BRDF in linear sRGB.
    pub fn new(name: impl Into<String>, brdf: Arc<dyn Brdf>) -> Material {
        Material {
            name: name.into(),
            brdf,
            coat: None,
            flakes: None,
            mesoscale: None,
        }
    }

    /// The same material with discrete flakes over its BRDF (which must leave their glint
    /// out: [`gonio_coating::system::Coating::table_without_glint`]).
    pub fn with_flakes(self, flakes: FlakeField) -> Material {
        Material {
            flakes: Some(Arc::new(flakes)),
            ..self
        }
    }

    /// The same material under a smooth clear coat of refractive index `index`.
    pub fn with_coat(self, index: f64) -> Material {
        Material {
            coat: Some(index),
            ..self
        }
    }

    /// The coat's mirror reflectance for a viewer at cosine `cos_o` to the shading normal (0
    /// without a coat).
    pub fn mirror(&self, cos_o: f64) -> f64 {
        self.coat
            .map_or(0.0, |n| gonio_brdf::fresnel::dielectric(cos_o, n))
    }

    /// A material of a tabulated BRDF, importance-sampled by its table sampler.
    pub fn from_table(name: impl Into<String>, table: BrdfTable) -> Material {
        Material::new(name, Arc::new(SampledTable::new(table)))
    }
}

impl std::fmt::Debug for Material {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Material")
            .field("name", &self.name)
            .field("coat", &self.coat)
            .field("flakes", &self.flakes.is_some())
            .field("mesoscale", &self.mesoscale.as_ref().map(|m| m.repeat()))
            .finish_non_exhaustive()
    }
}

/// The BRDF of an analytic model description; `scene` names the file in errors.
pub fn from_model(spec: &ModelSpec, scene: &Path, name: &str) -> Result<Arc<dyn Brdf>> {
    let model = spec
        .build()
        .map_err(|e| RenderError::scene(scene, format!("material `{name}`: {e}")))?;
    Ok(Arc::new(model))
}

/// Read a tabulated BRDF by extension: `.gbrdf` (gonio's format), `.astm` (Cornell, imported
/// through the smoothing fit onto the default resolution) or `.binary` (MERL).
pub fn read_table(path: &Path) -> Result<BrdfTable> {
    let ext = gonio_io::extension(path);
    let wrap = RenderError::Brdf;
    match ext.as_str() {
        "gbrdf" => gbrdf::read(path).map_err(wrap),
        "astm" => astm::import(path, astm::default_resolution())
            .map(|(t, _)| t)
            .map_err(wrap),
        "binary" => merl::read(path).map_err(wrap),
        _ => Err(RenderError::scene(
            path,
            "unknown BRDF table extension: use .gbrdf, .astm (Cornell) or .binary (MERL)",
        )),
    }
}
