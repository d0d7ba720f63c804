//! The TOML description of a coating (`examples/coatings/*.toml`, `docs/coatings.md`):
//! a top interface, a clear coat, optional effect flakes and a base, read into [`Coating`] with
//! errors that name the file and the field.
//!
//! ```toml
//! [top]                           # optional: a smooth top when left out
//! roughness = { distribution = "ggx", alpha = 0.05 }
//! # or { distribution = "beckmann", sq_um = 0.1, correlation_um = 5 }  (rms slope 2 Sq/T)
//! # or { map = "surface.x3p" }    (Beckmann, the map's rms slope Sdq; path beside this file)
//!
//! [coat]
//! index = 1.5                     # or { cauchy_a = 1.48, cauchy_b_um2 = 0.0045 }
//! # or { sellmeier_b = [b1, b2, b3], sellmeier_c_um2 = [c1, c2, c3] }
//! # or { nm = [...], values = [...] }, or { file = "index.csv" } (wavelength_nm,value; beside
//! #   this file)
//! thickness_um = 40
//! absorption_per_um = 0           # σ(λ), 1/µm: a number or { nm = [...], values = [...] }
//!
//! [base]
//! kind = "diffuse"                # or "kubelka-munk"
//! reflectance = { nm = [400, 500, 600, 700], values = [0.05, 0.05, 0.3, 0.7] }
//!
//! # kind = "kubelka-munk": thickness_um, substrate (a spectrum) and one or more
//! # [[base.pigment]] with name, concentration, k_per_um and s_per_um (spectra), or with
//! # library = "phthalo_blue_green_shade" (a pigment of gonio's library, [`crate::pigment_library`])
//! # and concentration (name optional: the library's name).
//!
//! [flakes]                        # optional: effect flakes at the bottom of the coat, or in
//!                                 # the basecoat (depth)
//! kind = "aluminium"              # or "metal" (with n and k spectra) or "interference"
//! coverage = 0.5                  # fraction of the base covered
//! tilt_deg = 15                   # rms tilt of the flakes
//! diameter_um = 20                # mean flake diameter (sparkle; default 20)
//! # depth = 0.5                   # inside a kubelka-munk basecoat: one sheet at this fraction
//! #                               # of its thickness below its top, or "spread" through it
//! #                               # (crate::basecoat); left out, the flakes lie over the base
//! # kind = "interference": tio2_nm, mica_nm (default 300), mica_index (default 1.58)
//! ```

use crate::basecoat::FlakeDepth;
use crate::clear_coat::{Base, Coat, Dispersion, Pigment};
use crate::error::{CoatingError, Result};
use crate::flakes::{FlakePigment, Flakes, aluminium};
use crate::pigment_library;
use crate::system::Coating;
use gonio_brdf::microfacet::Microfacet;
use gonio_color::Spectrum;
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    #[serde(default)]
    top: Option<TopFields>,
    coat: CoatFields,
    #[serde(default)]
    flakes: Option<FlakeFields>,
    base: BaseFields,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TopFields {
    roughness: RoughnessFields,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RoughnessFields {
    #[serde(default)]
    distribution: Option<DistributionField>,
    #[serde(default)]
    alpha: Option<f64>,
    #[serde(default)]
    sq_um: Option<f64>,
    #[serde(default)]
    correlation_um: Option<f64>,
    #[serde(default)]
    map: Option<PathBuf>,
}

#[derive(Deserialize, Clone, Copy, PartialEq)]
#[serde(rename_all = "lowercase")]
enum DistributionField {
    Ggx,
    Beckmann,
}

#[derive(Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
enum FlakeFields {
    Aluminium {
        coverage: f64,
        tilt_deg: f64,
        #[serde(default = "default_diameter_um")]
        diameter_um: f64,
        #[serde(default)]
        depth: Option<DepthField>,
    },
    Metal {
        coverage: f64,
        tilt_deg: f64,
        #[serde(default = "default_diameter_um")]
        diameter_um: f64,
        #[serde(default)]
        depth: Option<DepthField>,
        n: SpectrumField,
        k: SpectrumField,
    },
    Interference {
        coverage: f64,
        tilt_deg: f64,
        #[serde(default = "default_diameter_um")]
        diameter_um: f64,
        #[serde(default)]
        depth: Option<DepthField>,
        tio2_nm: f64,
        #[serde(default = "default_mica_nm")]
        mica_nm: f64,
        #[serde(default = "default_mica_index")]
        mica_index: f64,
    },
}

/// `[flakes] depth`: a fraction of the basecoat's thickness, or `"spread"`.
#[derive(Deserialize)]
#[serde(untagged)]
enum DepthField {
    Fraction(f64),
    Word(String),
}

impl DepthField {
    fn depth(self) -> Result<FlakeDepth> {
        match self {
            DepthField::Fraction(f) => Ok(FlakeDepth::Sheet(f)),
            DepthField::Word(w) if w == "spread" => Ok(FlakeDepth::Spread),
            DepthField::Word(w) => Err(CoatingError::Invalid(format!(
                "flakes.depth '{w}': a fraction of the basecoat's thickness from 0 (its top) to 1 \
                 (the substrate), or \"spread\""
            ))),
        }
    }
}

/// Mica platelets of pearlescent pigments are a few hundred nanometres thick.
fn default_mica_nm() -> f64 {
    300.0
}

/// Muscovite mica's index in the visible, about 1.58.
fn default_mica_index() -> f64 {
    1.58
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CoatFields {
    index: IndexField,
    thickness_um: f64,
    #[serde(default)]
    absorption_per_um: Option<SpectrumField>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum IndexField {
    Constant(f64),
    Cauchy {
        cauchy_a: f64,
        cauchy_b_um2: f64,
    },
    Sellmeier {
        sellmeier_b: [f64; 3],
        sellmeier_c_um2: [f64; 3],
    },
    Sampled {
        nm: Vec<f64>,
        values: Vec<f64>,
    },
    /// A `wavelength_nm,value` CSV file, relative to the description's folder.
    File {
        file: PathBuf,
    },
}

#[derive(Deserialize)]
#[serde(untagged)]
enum SpectrumField {
    Constant(f64),
    Sampled { nm: Vec<f64>, values: Vec<f64> },
}

#[derive(Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
enum BaseFields {
    Diffuse {
        reflectance: SpectrumField,
    },
    KubelkaMunk {
        thickness_um: f64,
        substrate: SpectrumField,
        pigment: Vec<PigmentFields>,
    },
}

/// A `[[base.pigment]]`: K and S spelled out (with a name), or a pigment of the library.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PigmentFields {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    library: Option<String>,
    concentration: f64,
    #[serde(default)]
    k_per_um: Option<SpectrumField>,
    #[serde(default)]
    s_per_um: Option<SpectrumField>,
}

impl SpectrumField {
    fn spectrum(self, field: &str) -> Result<Spectrum> {
        let made = match self {
            SpectrumField::Constant(v) => Spectrum::constant(vec![380.0, 780.0], v),
            SpectrumField::Sampled { nm, values } => Spectrum::new(nm, values),
        };
        made.map_err(|e| CoatingError::Invalid(format!("{field}: {e}")))
    }
}

/// Read a coating description. Checks the values at `wavelengths_nm` (those the table will
/// hold); a height map named by the top's roughness is read relative to the file's folder.
pub fn read(path: &Path, wavelengths_nm: &[f64]) -> Result<Coating> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CoatingError::Invalid(format!("{}: {e}", path.display())))?;
    let folder = path.parent().unwrap_or(Path::new("."));
    parse_in(&text, folder, wavelengths_nm)
        .map_err(|e| CoatingError::Invalid(format!("{}: {e}", path.display())))
}

/// The files the coating description `path` names, each as [`read`] opens it (relative to the
/// description's folder): the top's height map (`top.roughness.map`) and the coat's index table
/// (`coat.index = { file = ... }`), so that a record of what a picture was made from (a
/// manifest) can list them. The description is parsed, not checked; nothing else is read.
pub fn referenced_files(path: &Path) -> Result<Vec<PathBuf>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CoatingError::Invalid(format!("{}: {e}", path.display())))?;
    let file: File = toml::from_str(&text)
        .map_err(|e| CoatingError::Invalid(format!("{}: {e}", path.display())))?;
    let folder = path.parent().unwrap_or(Path::new("."));
    let map = file.top.and_then(|t| t.roughness.map);
    let index = match file.coat.index {
        IndexField::File { file } => Some(file),
        _ => None,
    };
    Ok(map
        .into_iter()
        .chain(index)
        .map(|f| folder.join(f))
        .collect())
}

/// Parse the text of a coating description (see [`read`]); maps relative to the current folder.
pub fn parse(text: &str, wavelengths_nm: &[f64]) -> Result<Coating> {
    parse_in(text, Path::new("."), wavelengths_nm)
}

/// The top interface's microfacet distribution from its fields.
fn roughness(r: RoughnessFields, folder: &Path) -> Result<Microfacet> {
    let given = [
        r.alpha.is_some(),
        r.sq_um.is_some() || r.correlation_um.is_some(),
        r.map.is_some(),
    ];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(CoatingError::Invalid(
            "top.roughness: give one of alpha, sq_um with correlation_um, or map".into(),
        ));
    }
    let alpha = match (r.alpha, r.sq_um, r.correlation_um, &r.map) {
        (Some(a), ..) => a,
        (None, Some(sq), Some(t), _) => {
            if !(sq > 0.0 && t > 0.0 && sq.is_finite() && t.is_finite()) {
                return Err(CoatingError::Invalid(format!(
                    "top.roughness: sq_um {sq} and correlation_um {t} must be positive"
                )));
            }
            2.0 * sq / t
        }
        (None, _, _, Some(map)) => {
            if r.distribution == Some(DistributionField::Ggx) {
                return Err(CoatingError::Invalid(
                    "top.roughness: a map gives a Beckmann distribution (its rms slope); leave                      out distribution"
                        .into(),
                ));
            }
            let path = folder.join(map);
            let heights = gonio_surface::io::read(&path)
                .map_err(|e| CoatingError::Invalid(format!("top.roughness.map: {e}")))?;
            gonio_surface::stats::statistics(&heights)
                .map_err(|e| CoatingError::Invalid(format!("top.roughness.map: {e}")))?
                .sdq
        }
        _ => {
            return Err(CoatingError::Invalid(
                "top.roughness: sq_um needs correlation_um (and the other way round)".into(),
            ));
        }
    };
    Ok(
        match r.distribution.unwrap_or(DistributionField::Beckmann) {
            DistributionField::Ggx => Microfacet::ggx(alpha),
            DistributionField::Beckmann => Microfacet::beckmann(alpha),
        },
    )
}

fn default_diameter_um() -> f64 {
    Flakes::DEFAULT_DIAMETER_UM
}

/// The flakes from their fields.
fn flakes(f: FlakeFields) -> Result<Flakes> {
    Ok(match f {
        FlakeFields::Aluminium {
            coverage,
            tilt_deg,
            diameter_um,
            depth,
        } => {
            let (n, k) = aluminium();
            Flakes {
                pigment: FlakePigment::Metal { n, k },
                coverage,
                tilt_deg,
                diameter_um,
                depth: depth.map(DepthField::depth).transpose()?,
            }
        }
        FlakeFields::Metal {
            coverage,
            tilt_deg,
            diameter_um,
            depth,
            n,
            k,
        } => Flakes {
            pigment: FlakePigment::Metal {
                n: n.spectrum("flakes.n")?,
                k: k.spectrum("flakes.k")?,
            },
            coverage,
            tilt_deg,
            diameter_um,
            depth: depth.map(DepthField::depth).transpose()?,
        },
        FlakeFields::Interference {
            coverage,
            tilt_deg,
            diameter_um,
            depth,
            tio2_nm,
            mica_nm,
            mica_index,
        } => Flakes {
            pigment: FlakePigment::Interference {
                tio2_nm,
                mica_nm,
                mica_index,
            },
            coverage,
            tilt_deg,
            diameter_um,
            depth: depth.map(DepthField::depth).transpose()?,
        },
    })
}

/// A `[[base.pigment]]` from its fields: its own K and S, or the library's scaled by
/// [`pigment_library::SCALE_PER_UM`] (named as in the library unless `name` is given).
fn pigment_of(p: PigmentFields) -> Result<Pigment> {
    match (p.library, p.k_per_um, p.s_per_um) {
        (Some(library), None, None) => {
            let mut pigment = pigment_library::find(&library)
                .and_then(|l| l.pigment(p.concentration))
                .map_err(|e| CoatingError::Invalid(format!("base.pigment library: {e}")))?;
            if let Some(name) = p.name {
                pigment.name = name;
            }
            Ok(pigment)
        }
        (None, Some(k), Some(s)) => {
            let name = p.name.ok_or_else(|| {
                CoatingError::Invalid(
                    "base.pigment: a pigment with k_per_um and s_per_um needs a name".into(),
                )
            })?;
            let field = |f: &str| format!("base.pigment '{name}'.{f}");
            Ok(Pigment {
                concentration: p.concentration,
                k_per_um: k.spectrum(&field("k_per_um"))?,
                s_per_um: s.spectrum(&field("s_per_um"))?,
                name,
            })
        }
        (library, ..) => Err(CoatingError::Invalid(format!(
            "base.pigment '{}': give either library (a pigment of gonio's library) or both \
             k_per_um and s_per_um",
            p.name.or(library).unwrap_or_default()
        ))),
    }
}

/// Parse the text of a coating description, with the files it names (a top's height map)
/// relative to `folder`.
pub fn parse_in(text: &str, folder: &Path, wavelengths_nm: &[f64]) -> Result<Coating> {
    let file: File = toml::from_str(text).map_err(|e| CoatingError::Invalid(e.to_string()))?;
    let roughness = file
        .top
        .map(|t| roughness(t.roughness, folder))
        .transpose()?;
    let flakes = file.flakes.map(flakes).transpose()?;
    let index = match file.coat.index {
        IndexField::Constant(n) => Dispersion::Constant(n),
        IndexField::Cauchy {
            cauchy_a,
            cauchy_b_um2,
        } => Dispersion::Cauchy {
            a: cauchy_a,
            b_um2: cauchy_b_um2,
        },
        IndexField::Sellmeier {
            sellmeier_b,
            sellmeier_c_um2,
        } => Dispersion::Sellmeier {
            b: sellmeier_b,
            c_um2: sellmeier_c_um2,
        },
        IndexField::Sampled { nm, values } => {
            Dispersion::Measured(SpectrumField::Sampled { nm, values }.spectrum("coat.index")?)
        }
        IndexField::File { file } => {
            let path = folder.join(file);
            Dispersion::Measured(
                Spectrum::read_csv(&path)
                    .map_err(|e| CoatingError::Invalid(format!("coat.index: {e}")))?,
            )
        }
    };
    let coat = Coat {
        index,
        thickness_um: file.coat.thickness_um,
        absorption_per_um: file
            .coat
            .absorption_per_um
            .unwrap_or(SpectrumField::Constant(0.0))
            .spectrum("coat.absorption_per_um")?,
    };
    let base = match file.base {
        BaseFields::Diffuse { reflectance } => Base::Diffuse {
            reflectance: reflectance.spectrum("base.reflectance")?,
        },
        BaseFields::KubelkaMunk {
            thickness_um,
            substrate,
            pigment,
        } => {
            if !(thickness_um.is_finite() && thickness_um >= 0.0) {
                return Err(CoatingError::Invalid(format!(
                    "base.thickness_um {thickness_um}: must be finite and non-negative"
                )));
            }
            if pigment.is_empty() {
                return Err(CoatingError::Invalid(
                    "base: a kubelka-munk base needs at least one [[base.pigment]]".into(),
                ));
            }
            Base::KubelkaMunk {
                thickness_um,
                substrate: substrate.spectrum("base.substrate")?,
                pigments: pigment
                    .into_iter()
                    .map(pigment_of)
                    .collect::<Result<Vec<_>>>()?,
            }
        }
    };
    let coating = Coating {
        roughness,
        coat,
        flakes,
        base,
    };
    coating.check(wavelengths_nm)?;
    Ok(coating)
}

#[cfg(test)]
mod tests;
