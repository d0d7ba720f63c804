//! gonio's exports of the scenes' materials, which the peers render: each material tabulated
//! by gonio (a `gonio_brdf` table; the coat's body by `gonio_coating`'s closed form for a smooth
//! coat over a diffuse base, as `gonio coating compute` tabulates it) and written as Mitsuba 3's
//! tensor `.bsdf` for its `measured` plugin (`gonio_brdf::formats::mitsuba`) and as Radiance's
//! XML BSDF for its `BSDF` material (`gonio_brdf::formats::radiance_xml`, a tensor tree).
//!
//! What an export loses is computed, not asserted: [`table_error`] reads the exported file
//! back and evaluates it the way the renderer does (`TensorBrdf` as Mitsuba's `measured.cpp`,
//! `TensorTree::eval_xyz` as Radiance's `SDqueryTre`), integrates it under the scenes' uniform
//! sky at the view angles of the regions, and compares it with the model's own reflection
//! there. A table holds no delta: the smooth coat's mirror reflection and the mirror scene's
//! whole reflection are lost, which [`crate::loss`] reports as known losses.

use crate::error::{Error, Result};
use crate::metamer;
use crate::optics::{coat_radiance, fresnel};
use crate::scene::Material;
use glam::DVec3;
use gonio_brdf::formats::mitsuba::{MitsubaOptions, TensorBrdf};
use gonio_brdf::formats::radiance_xml::{self, TensorTree};
use gonio_brdf::table::{BrdfTable, Channels, Provenance, Resolution, TableBuilder};
use std::path::{Path, PathBuf};

/// The resolution of the Lambertian tables (constant: any resolution holds them exactly).
const LAMBERT_RESOLUTION: (usize, usize, usize) = (8, 8, 8);

/// The resolution of the coat's body table (`gonio coating compute`'s default grid).
const COAT_RESOLUTION: (usize, usize, usize) = (45, 45, 24);

fn bad(what: &str) -> impl Fn(gonio_brdf::BrdfError) -> Error + '_ {
    move |e| Error::Invalid(format!("{what}: {e}"))
}

fn constant_table(channels: Channels, values: &[f64], what: &str) -> Result<BrdfTable> {
    let (a, b, c) = LAMBERT_RESOLUTION;
    let mut builder = TableBuilder::new(Resolution::isotropic(a, b, c), channels)
        .map_err(bad(what))?
        .with_provenance(Provenance::new("gonio conformance", what));
    builder.fill(|_, out| out.copy_from_slice(values));
    builder.build().map_err(bad(what))
}

/// gonio's table of `material`'s BRDF without its delta (1/sr): a Lambertian's `ρ/π` (RGB, or
/// per wavelength at [`metamer::wavelengths_nm`]), the coat's body (monochrome: the coat is
/// grey), the mirror's black base.
pub fn table(material: &Material) -> Result<BrdfTable> {
    let pi = std::f64::consts::PI;
    match material {
        Material::Lambert { albedo } => {
            constant_table(Channels::Rgb, &albedo.map(|a| a / pi), "lambert")
        }
        Material::Spectral { reflectance } => {
            let values: Vec<f64> = reflectance.iter().map(|r| r / pi).collect();
            constant_table(
                Channels::Spectral {
                    wavelengths_nm: metamer::wavelengths_nm(),
                },
                &values,
                "spectral lambert",
            )
        }
        Material::Mirror { .. } => constant_table(Channels::Mono, &[0.0], "mirror's base"),
        Material::Coat(coat) => {
            let bands = gonio_coating::system::default_bands();
            let coating = gonio_coating::description::parse(&coat.description(), &bands)
                .map_err(|e| Error::Invalid(format!("coat: {e}")))?;
            let stack = coating.clear_coat().ok_or_else(|| {
                Error::Invalid("coat: not a smooth coat over a diffuse base".into())
            })?;
            let (a, b, c) = COAT_RESOLUTION;
            let res = Resolution::isotropic(a, b, c);
            // Two bands (the coat is grey: both hold the same values), the first kept.
            let spectral = stack
                .body_table(
                    res,
                    &[500.0, 600.0],
                    gonio_coating::clear_coat::body_provenance("gonio conformance coat"),
                )
                .map_err(|e| Error::Invalid(format!("coat: {e}")))?;
            BrdfTable::from_values(
                res,
                Channels::Mono,
                spectral.provenance().clone(),
                spectral.values().iter().step_by(2).copied().collect(),
            )
            .map_err(bad("coat table"))
        }
    }
}

/// Whether `material`'s table is black (the mirror's: its model is a delta over a black base).
pub fn is_black(material: &Material) -> bool {
    matches!(material, Material::Mirror { .. })
}

/// The file of object `object`'s Mitsuba export in `dir`.
pub fn mitsuba_file(dir: &Path, scene: &str, object: &str) -> PathBuf {
    dir.join(format!("{scene}_{object}.bsdf"))
}

/// The file of object `object`'s Radiance export in `dir`.
pub fn radiance_file(dir: &Path, scene: &str, object: &str) -> PathBuf {
    dir.join(format!("{scene}_{object}.xml"))
}

/// Write `material`'s table as a Mitsuba tensor file at `path` (the exporter's default
/// resolutions).
pub fn write_mitsuba(material: &Material, path: &Path) -> Result<()> {
    gonio_brdf::formats::mitsuba::write(&table(material)?, path, MitsubaOptions::default())
        .map_err(bad("Mitsuba export"))
}

/// Write `material`'s table as a Radiance XML BSDF at `path` (the exporter's default order).
pub fn write_radiance(material: &Material, path: &Path) -> Result<()> {
    radiance_xml::write(&table(material)?, path, "gonio", None)
        .map(|_| ())
        .map_err(bad("Radiance export"))
}

/// Luminance weights of linear sRGB (IEC 61966-2-1, the Y row).
const Y_SRGB: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// Points per axis of the sky's quadrature: `∫ f cos θ dω = π E[f]` over cosine-distributed
/// directions, the midpoints of a 96 × 96 grid mapped by `(√u cos 2πv, √u sin 2πv, √(1 − u))`.
/// For a constant f it is exact; for the coat's body (smooth in the light's direction but for
/// its Fresnel factor's knee near grazing, where cos θ weighs little) halving the grid moves the
/// result by less than 1e-4 of it.
const SKY_POINTS: usize = 96;

/// `∫ f(v, l) cos θ_l dω_l` over the hemisphere of `l` (the reflection under a uniform sky of
/// radiance 1) for the viewer at `theta_v`, `f` giving the luminance BRDF.
pub fn under_sky(theta_v: f64, f: impl Fn(DVec3, DVec3) -> f64) -> f64 {
    let v = DVec3::new(theta_v.sin(), 0.0, theta_v.cos());
    let n = SKY_POINTS as f64;
    let mut sum = 0.0;
    for i in 0..SKY_POINTS {
        for j in 0..SKY_POINTS {
            let (u, w) = ((i as f64 + 0.5) / n, (j as f64 + 0.5) / n);
            let (s, c) = (2.0 * std::f64::consts::PI * w).sin_cos();
            let r = u.sqrt();
            let l = DVec3::new(r * c, r * s, (1.0 - u).sqrt());
            sum += f(v, l);
        }
    }
    std::f64::consts::PI * sum / (n * n)
}

/// The view angles at which an export is checked, degrees: every 5° from 0 to 70°, beyond the
/// spheres' regions (normal within 60° of the view) and the plate's (seen at about 37°).
const VIEW_DEG: std::ops::RangeInclusive<u32> = 0..=14;

/// The model's luminance under the uniform sky of radiance 1, without the delta, at `theta_v`.
fn model_under_sky(material: &Material, theta_v: f64) -> f64 {
    match material {
        Material::Lambert { albedo } => (0..3).map(|c| Y_SRGB[c] * albedo[c]).sum(),
        Material::Spectral { reflectance } => {
            reflectance.iter().sum::<f64>() / reflectance.len() as f64
        }
        Material::Mirror { .. } => 0.0,
        Material::Coat(coat) => {
            let cos_v = theta_v.cos();
            coat_radiance(cos_v, coat.index, coat.base_reflectance(), 1.0)
                - fresnel(cos_v, coat.index)
        }
    }
}

/// Which exported file [`table_error`] evaluates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Mitsuba's tensor `.bsdf`.
    Mitsuba,
    /// Radiance's XML BSDF.
    Radiance,
}

/// The largest relative error, over the view angles of `VIEW_DEG`, of the exported file at
/// `path` of `material` against the model (without its delta) under the uniform sky:
/// `max |a_file(θv) − a_model(θv)| / max a_model`, the luminances as above (a spectral patch's:
/// the mean over its wavelengths, in Mitsuba's file only; `None` in Radiance's, whose tree holds
/// XYZ, the patch's colour being checked as colour). Zero for a material whose model reflects
/// nothing but its delta (the mirror).
pub fn table_error(material: &Material, format: Format, path: &Path) -> Result<Option<f64>> {
    if is_black(material) {
        return Ok(Some(0.0));
    }
    if format == Format::Radiance && matches!(material, Material::Spectral { .. }) {
        return Ok(None);
    }
    let luminance: Box<dyn Fn(DVec3, DVec3) -> f64> = match format {
        Format::Mitsuba => {
            let file = TensorBrdf::read(path).map_err(bad("the Mitsuba export read back"))?;
            let spectral = matches!(material, Material::Spectral { .. });
            Box::new(move |v, l| {
                let mut out = vec![0.0; file.channel_count()];
                file.eval_channels(v, l, &mut out);
                if spectral {
                    out.iter().sum::<f64>() / out.len() as f64
                } else if out.len() == 3 {
                    (0..3).map(|c| Y_SRGB[c] * out[c]).sum()
                } else {
                    out[0]
                }
            })
        }
        Format::Radiance => {
            let tree = tree_of(material)?;
            Box::new(move |v, l| tree.eval_xyz(v, l)[1])
        }
    };
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for k in VIEW_DEG {
        let theta_v = (5.0 * f64::from(k)).to_radians();
        let model = model_under_sky(material, theta_v);
        worst = worst.max((under_sky(theta_v, &luminance) - model).abs());
        scale = scale.max(model);
    }
    Ok(Some(if scale > 0.0 { worst / scale } else { 0.0 }))
}

/// The tensor tree Radiance reads, made again from the table by the writer's own conversion
/// (the XML at `path` holds its cells, to the six digits it writes).
fn tree_of(material: &Material) -> Result<TensorTree> {
    let t = table(material)?;
    TensorTree::from_table(&t, radiance_xml::default_order(&t)).map_err(bad("Radiance export"))
}
