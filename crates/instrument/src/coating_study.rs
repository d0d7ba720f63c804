//! The formulation study: a coating's appearance against one constituent at a time (the clear
//! coat's roughness, the flakes' tilt spread or coverage, the interference flakes' TiO2
//! thickness, a pigment's concentration, the coat's thickness), read by the instruments a
//! coatings laboratory uses: the gloss meter with haze and DOI (ISO 2813, ASTM E430) and the
//! multi-angle spectrophotometer (ASTM E2194, CIELAB D65/10°, flop index).
//!
//! Each variant's BRDF is evaluated where each instrument looks (`coating::system::Evaluator`,
//! the exact series or random walks), not through a table. The gloss meter reads the luminous
//! reflectance at 555 nm (the photopic peak; a coating's reflection near the specular direction
//! is nearly grey): the coat's mirror reflection for a smooth top (Fresnel at the binder's index)
//! and the BRDF integrated over the receptor (Gauss-Legendre, [`CoatingSpecimen`]).

use crate::error::{InstrumentError, Result};
use crate::gloss::{self, GlossReport, Specimen, Window};
use crate::multiangle::{self, Geometry, MultiangleReading, Settings};
use glam::DVec3;
use gonio_brdf::fresnel::dielectric;
use gonio_brdf::microfacet::Microfacet;
use gonio_coating::clear_coat::Base;
use gonio_coating::flakes::FlakePigment;
use gonio_coating::interface::Transport;
use gonio_coating::layered::Scratch;
use gonio_coating::system::{Coating, Evaluator};
use gonio_io::Cancel;
use rayon::prelude::*;

/// The constituent a study varies.
#[derive(Clone, Debug, PartialEq)]
pub enum Constituent {
    /// The top interface's roughness α (Beckmann rms slope unless the description names GGX);
    /// 0 is a smooth top.
    Roughness,
    /// The flakes' rms tilt, degrees.
    FlakeTilt,
    /// The fraction of the base the flakes cover.
    FlakeCoverage,
    /// The TiO2 thickness of interference flakes, nm.
    Tio2,
    /// The concentration of the named pigment of a Kubelka-Munk base.
    Concentration(String),
    /// The clear coat's thickness, µm.
    CoatThickness,
    /// The Kubelka-Munk basecoat's thickness, µm (with flakes inside it, `[flakes] depth`, the
    /// layer that holds them).
    BaseThickness,
}

impl Constituent {
    /// Parse `roughness`, `tilt`, `coverage`, `tio2`, `thickness` or `concentration:NAME`.
    pub fn parse(s: &str) -> Result<Self> {
        Ok(match s {
            "roughness" => Constituent::Roughness,
            "tilt" => Constituent::FlakeTilt,
            "coverage" => Constituent::FlakeCoverage,
            "tio2" => Constituent::Tio2,
            "thickness" => Constituent::CoatThickness,
            "base_thickness" => Constituent::BaseThickness,
            _ => match s.strip_prefix("concentration:") {
                Some(name) if !name.is_empty() => Constituent::Concentration(name.to_string()),
                _ => {
                    return Err(InstrumentError::Invalid(format!(
                        "'{s}': vary one of roughness, tilt, coverage, tio2, thickness, \
                         base_thickness or concentration:NAME (a pigment of the base)"
                    )));
                }
            },
        })
    }

    /// The name and unit of the varied quantity, for tables and plots.
    pub fn label(&self) -> String {
        match self {
            Constituent::Roughness => "top roughness α".into(),
            Constituent::FlakeTilt => "flake tilt spread, °".into(),
            Constituent::FlakeCoverage => "flake coverage".into(),
            Constituent::Tio2 => "TiO2 thickness, nm".into(),
            Constituent::Concentration(name) => format!("concentration of {name}"),
            Constituent::CoatThickness => "coat thickness, µm".into(),
            Constituent::BaseThickness => "basecoat thickness, µm".into(),
        }
    }

    /// The epoxy roughness series of the roughness study (`study`: Sq 3, 50, 150, 201, 400 and
    /// 805 nm, correlation length 6 µm) as Beckmann rms slopes `2 Sq / T`, for `Roughness`.
    pub fn epoxy_series() -> Vec<f64> {
        [3.0, 50.0, 150.0, 201.0, 400.0, 805.0]
            .iter()
            .map(|sq_nm| 2.0 * sq_nm * 1e-3 / 6.0)
            .collect()
    }

    /// This constituent's value in `coating` (the inverse of [`Constituent::apply`]): the top's
    /// α (the larger of αx, αy; 0 for a smooth top), the flakes' tilt, coverage or TiO2
    /// thickness, the pigment's concentration, the coat's thickness.
    pub fn value(&self, coating: &Coating) -> Result<f64> {
        let no_flakes = || {
            InstrumentError::Invalid(
                "the coating has no [flakes] (add a [flakes] table to its description)".into(),
            )
        };
        Ok(match self {
            Constituent::Roughness => coating.roughness.map_or(0.0, |m| m.alpha_x.max(m.alpha_y)),
            Constituent::FlakeTilt => coating.flakes.as_ref().ok_or_else(no_flakes)?.tilt_deg,
            Constituent::FlakeCoverage => coating.flakes.as_ref().ok_or_else(no_flakes)?.coverage,
            Constituent::Tio2 => match coating.flakes.as_ref().map(|f| &f.pigment) {
                Some(FlakePigment::Interference { tio2_nm, .. }) => *tio2_nm,
                _ => {
                    return Err(InstrumentError::Invalid(
                        "tio2: the coating has no interference flakes".into(),
                    ));
                }
            },
            Constituent::Concentration(name) => match &coating.base {
                Base::KubelkaMunk { pigments, .. } => {
                    pigments
                        .iter()
                        .find(|p| &p.name == name)
                        .ok_or_else(|| {
                            InstrumentError::Invalid(format!(
                                "concentration:{name}: the base has no pigment of that name"
                            ))
                        })?
                        .concentration
                }
                Base::Diffuse { .. } => {
                    return Err(InstrumentError::Invalid(format!(
                        "concentration:{name}: the base is not a Kubelka-Munk layer of pigments"
                    )));
                }
            },
            Constituent::CoatThickness => coating.coat.thickness_um,
            Constituent::BaseThickness => match &coating.base {
                Base::KubelkaMunk { thickness_um, .. } => *thickness_um,
                Base::Diffuse { .. } => return Err(not_a_layer()),
            },
        })
    }

    /// `coating` with this constituent set to `value`.
    pub fn apply(&self, coating: &Coating, value: f64) -> Result<Coating> {
        let mut c = coating.clone();
        let no_flakes = || {
            InstrumentError::Invalid(
                "the coating has no [flakes] to vary (add a [flakes] table to its description)"
                    .into(),
            )
        };
        match self {
            Constituent::Roughness => {
                c.roughness = if value == 0.0 {
                    None
                } else {
                    Some(match c.roughness {
                        Some(Microfacet { distribution, .. }) => Microfacet {
                            distribution,
                            alpha_x: value,
                            alpha_y: value,
                        },
                        None => Microfacet::beckmann(value),
                    })
                }
            }
            Constituent::FlakeTilt => c.flakes.as_mut().ok_or_else(no_flakes)?.tilt_deg = value,
            Constituent::FlakeCoverage => c.flakes.as_mut().ok_or_else(no_flakes)?.coverage = value,
            Constituent::Tio2 => match c.flakes.as_mut().map(|f| &mut f.pigment) {
                Some(FlakePigment::Interference { tio2_nm, .. }) => *tio2_nm = value,
                _ => {
                    return Err(InstrumentError::Invalid(
                        "tio2: the coating has no interference flakes".into(),
                    ));
                }
            },
            Constituent::Concentration(name) => match &mut c.base {
                Base::KubelkaMunk { pigments, .. } => {
                    let p = pigments
                        .iter_mut()
                        .find(|p| &p.name == name)
                        .ok_or_else(|| {
                            InstrumentError::Invalid(format!(
                                "concentration:{name}: the base has no pigment of that name"
                            ))
                        })?;
                    p.concentration = value;
                }
                Base::Diffuse { .. } => {
                    return Err(InstrumentError::Invalid(format!(
                        "concentration:{name}: the base is not a Kubelka-Munk layer of pigments"
                    )));
                }
            },
            Constituent::CoatThickness => c.coat.thickness_um = value,
            Constituent::BaseThickness => match &mut c.base {
                Base::KubelkaMunk { thickness_um, .. } => *thickness_um = value,
                Base::Diffuse { .. } => return Err(not_a_layer()),
            },
        }
        Ok(c)
    }
}

/// The error of `base_thickness` on a base that is not a Kubelka-Munk layer.
fn not_a_layer() -> InstrumentError {
    InstrumentError::Invalid(
        "base_thickness: the base is not a Kubelka-Munk layer of pigments (kind = \"kubelka-munk\")"
            .into(),
    )
}

/// A coating as a gloss meter's specimen at one wavelength. The top interface's own reflection
/// is integrated over each window by sampling it where the lobe is narrower than an eighth of
/// the window (64 × 64 stratified visible normals: each sample's weight counts in the windows
/// that hold its direction) and by 32 × 32 Gauss-Legendre points of its BRDF where it is wider
/// (DOI's 0.1° slits); a smooth top's mirror reflection is Fresnel's at the binder's index; the
/// light that has been inside the coat, broad beside the receptor, by `order × order`
/// Gauss-Legendre points of `walks` walks each.
///
/// The walks' Monte Carlo error: the specimen's "patches" ([`Specimen::reflectance_by_patch`])
/// are [`CoatingSpecimen::BATCHES`] groups of the walks at every quadrature point (walks
/// `b n/B .. (b+1) n/B` of each point's stream, so that their sum is the estimate of all `n`),
/// and the top's and the mirror's reflection, computed without walks, shared equally among
/// them; the jackknife over the groups ([`gloss::jackknife`]) is then the walks' standard error
/// of DOI, at no extra cost. It treats the groups as independent, which the Sobol
/// stratification of a point's walks makes pessimistic (docs/instruments.md, "The lab's
/// readings", compares it with the spread over seeds).
pub struct CoatingSpecimen {
    evaluator: Evaluator,
    /// The binder's index when the top is smooth (its mirror reflection is a delta).
    mirror_index: Option<f64>,
    walks: usize,
    /// Gauss-Legendre order per axis over each receptor of the light from inside the coat.
    order: usize,
    /// Gauss-Legendre order per axis over the source.
    source_order: usize,
    /// Mixed into every quadrature point's stream (0: the study's streams).
    seed: u64,
    /// Checked before each source direction: a raised flag ends the reading with
    /// [`InstrumentError::Cancelled`].
    cancel: Cancel,
}

impl CoatingSpecimen {
    /// Strata per axis of the top reflection's samples.
    const STRATA: usize = 64;
    /// The most groups of walks the jackknife of DOI splits them into (fewer when there are
    /// fewer walks per quadrature point; one walk per point leaves DOI's uncertainty at 0, not
    /// estimated).
    pub const BATCHES: usize = 8;

    /// The specimen of `coating` at `wavelength_nm`.
    pub fn new(coating: &Coating, wavelength_nm: f64, walks: usize) -> Result<Self> {
        Ok(CoatingSpecimen {
            evaluator: coating.evaluator(&[wavelength_nm])?,
            mirror_index: coating
                .roughness
                .is_none()
                .then(|| coating.coat.index.at(wavelength_nm)),
            walks,
            order: 6,
            source_order: 4,
            seed: 0,
            cancel: Cancel::default(),
        })
    }

    /// The same specimen with its walks drawn from the streams `seed` (0 is [`CoatingSpecimen::new`]'s):
    /// another seed gives an independent estimate of the same reading.
    pub fn with_seed(self, seed: u64) -> Self {
        CoatingSpecimen { seed, ..self }
    }

    /// The same specimen with `source` × `source` directions over the source (4 unless told)
    /// and `receptor` × `receptor` points over each receptor for the light from inside the coat
    /// (6 unless told): fewer for a quick reading (the lab's), whose estimates then differ from
    /// the study's by the quadrature's error as well as by the walks' noise.
    pub fn with_orders(self, source: usize, receptor: usize) -> Result<Self> {
        if source == 0 || receptor == 0 {
            return Err(InstrumentError::Invalid(
                "the gloss meter's quadrature needs at least one point per axis".into(),
            ));
        }
        Ok(CoatingSpecimen {
            source_order: source,
            order: receptor,
            ..self
        })
    }

    /// The same specimen, whose readings stop with [`InstrumentError::Cancelled`] once `cancel`
    /// is raised (checked before each source direction of the meter).
    pub fn with_cancel(self, cancel: Cancel) -> Self {
        CoatingSpecimen { cancel, ..self }
    }
}

impl Specimen for CoatingSpecimen {
    fn reflectance_into(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<f64>> {
        Ok(gloss::column_sums(&self.reflectance_by_patch(wi, windows)?))
    }

    fn reflectance_by_patch(&self, wi: DVec3, windows: &[Window]) -> Result<Vec<Vec<f64>>> {
        if self.cancel.is_cancelled() {
            return Err(InstrumentError::Cancelled);
        }
        let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
        let mut into: Vec<f64> = windows
            .iter()
            .map(|w| match self.mirror_index {
                Some(n) if w.contains(mirror) => dielectric(wi.z, n),
                _ => 0.0,
            })
            .collect();
        if let Some(top) = self.evaluator.top() {
            // Windows much wider than the lobe: sample the lobe; the others (a lobe at least an
            // eighth of the window's width, e.g. DOI's 0.1° slits): quadrature of the BRDF.
            let lobe = 2.0
                * top
                    .roughness
                    .map_or(0.0, |m| m.alpha_x.max(m.alpha_y))
                    .atan();
            let (sampled, integrated): (Vec<usize>, Vec<usize>) =
                (0..windows.len()).partition(|&k| {
                    let a = windows[k].aperture;
                    lobe < a.in_plane.min(a.perpendicular) / 8.0
                });
            // No samples when every window takes the quadrature.
            let n = if sampled.is_empty() { 0 } else { Self::STRATA };
            for s in top.reflection_samples(wi, n) {
                for &w in &sampled {
                    if windows[w].contains(s.wi) {
                        into[w] += s.weight() / (n * n) as f64;
                    }
                }
            }
            for &w in &integrated {
                into[w] += windows[w]
                    .quadrature(32)
                    .into_iter()
                    .filter(|(wo, _)| wo.z > 0.0)
                    .map(|(wo, dw)| top.f(wo, wi, Transport::Radiance) * wo.z * dw)
                    .sum::<f64>();
            }
        }
        // The groups of walks ([`CoatingSpecimen`]): what needs no walks shared equally.
        let exact = matches!(self.evaluator, Evaluator::Exact(_));
        let batches = if exact {
            1
        } else {
            Self::BATCHES.min(self.walks).max(1)
        };
        let mut rows: Vec<Vec<f64>> = (0..batches)
            .map(|_| into.iter().map(|v| v / batches as f64).collect())
            .collect();
        let mut scratch = Scratch::default();
        let mut value = [0.0];
        for (k, window) in windows.iter().enumerate() {
            for (j, (wo, dw)) in window.quadrature(self.order).into_iter().enumerate() {
                if wo.z <= 0.0 {
                    continue;
                }
                let seed = (k * 4096 + j) as u64
                    ^ wi.x.to_bits().rotate_left(7)
                    ^ self.seed.wrapping_mul(GOLDEN);
                if exact || self.walks == 0 {
                    self.evaluator
                        .eval_body(wo, wi, self.walks, seed, &mut scratch, &mut value);
                    rows[0][k] += value[0] * wo.z * dw;
                    continue;
                }
                for (b, row) in rows.iter_mut().enumerate() {
                    value[0] = 0.0;
                    let walks = b * self.walks / batches..(b + 1) * self.walks / batches;
                    self.evaluator
                        .add_walks(wo, wi, walks, seed, &mut scratch, &mut value, None);
                    row[k] += value[0] / self.walks as f64 * wo.z * dw;
                }
            }
        }
        Ok(rows)
    }

    fn source_order(&self) -> usize {
        self.source_order
    }
}

/// Spreads a stream offset over all 64 bits (2⁶⁴/φ, odd), so that seeds 1, 2, 3 … select
/// unrelated streams.
const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// The multi-angle reading (D65/10°) of the coating `evaluator` evaluates, at `geometries`, with
/// `walks` walks per geometry (a rough top or flakes), from the streams of `seed` (see
/// [`read_coating`]: seed 0 is every study's and summary's, so that two formulations' readings
/// differ by their optics, not by their noise). A smooth top's mirror reflection is 15° or more
/// away from every standard geometry and is not in the reading.
pub fn multiangle_reading(
    evaluator: &Evaluator,
    wavelengths_nm: &[f64],
    geometries: &[Geometry],
    walks: usize,
    seed: u64,
) -> Result<MultiangleReading> {
    let brdf = walked_brdf(evaluator, walks, seed);
    multiangle::read(&brdf, wavelengths_nm, geometries, &Settings::default())
}

/// The coating's spectral BRDF as [`multiangle::read`] takes it, `walks` walks per evaluation
/// (a rough top or flakes) drawn from the streams of `seed`, the same streams at every pair of
/// directions (so that a geometry's reading does not depend on which others are read with it,
/// and neighbouring geometries' readings share their random numbers).
pub fn walked_brdf(
    evaluator: &Evaluator,
    walks: usize,
    seed: u64,
) -> impl Fn(DVec3, DVec3, &mut [f64]) + Sync + '_ {
    let stream = 1 ^ seed.wrapping_mul(GOLDEN);
    move |wo: DVec3, wi: DVec3, out: &mut [f64]| {
        evaluator.eval(wo, wi, walks, stream, &mut Scratch::default(), out);
    }
}

/// What the instruments read on one coating.
#[derive(Clone, Debug)]
pub struct Reading {
    pub gloss: GlossReport,
    pub multiangle: MultiangleReading,
}

/// Read `coating` as a study reads each variant: gloss, haze and DOI ([`gloss::measure`] on a
/// [`CoatingSpecimen`], `gloss_walks` walks per quadrature point) and the multi-angle colour at
/// `geometries` (`walks` per geometry), over `wavelengths_nm`.
///
/// Common random numbers: every call with the same `seed` draws the same random numbers (each
/// estimate's streams are seeded by its geometry or quadrature point and by `seed`, never by the
/// coating, the order of the calls or the thread), so that two readings of nearby coatings
/// differ by what the coatings change, not by independent noise. Seed 0 is the study's
/// ([`run`]); another seed gives an independent reading of the same coating, whose spread is the
/// reading's noise.
pub fn read_coating(
    coating: &Coating,
    geometries: &[Geometry],
    wavelengths_nm: &[f64],
    walks: usize,
    gloss_walks: usize,
    seed: u64,
) -> Result<Reading> {
    coating.check(wavelengths_nm)?;
    let gloss =
        gloss::measure(&CoatingSpecimen::new(coating, 555.0, gloss_walks)?.with_seed(seed))?;
    let evaluator = coating.evaluator(wavelengths_nm)?;
    let multiangle = multiangle_reading(&evaluator, wavelengths_nm, geometries, walks, seed)?;
    Ok(Reading { gloss, multiangle })
}

/// What the instruments read on one variant.
#[derive(Clone, Debug)]
pub struct StudyRow {
    /// The varied constituent's value.
    pub value: f64,
    pub gloss: GlossReport,
    pub multiangle: MultiangleReading,
}

/// Read every variant of `coating` with `constituent` at `values`: gloss, haze and DOI
/// ([`gloss::measure`] on a [`CoatingSpecimen`], `gloss_walks` walks per point) and the
/// multi-angle colour at `geometries` (`walks` per geometry), over `wavelengths_nm`.
pub fn run(
    coating: &Coating,
    constituent: &Constituent,
    values: &[f64],
    geometries: &[Geometry],
    wavelengths_nm: &[f64],
    walks: usize,
    gloss_walks: usize,
) -> Result<Vec<StudyRow>> {
    if values.is_empty() {
        return Err(InstrumentError::Invalid(
            "a study needs at least one value".into(),
        ));
    }
    values
        .par_iter()
        .map(|&value| {
            let variant = constituent.apply(coating, value)?;
            let Reading { gloss, multiangle } =
                read_coating(&variant, geometries, wavelengths_nm, walks, gloss_walks, 0)?;
            Ok(StudyRow {
                value,
                gloss,
                multiangle,
            })
        })
        .collect()
}
