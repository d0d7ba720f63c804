//! The appearance readings a formulation is judged by, as numbers: specular gloss at 20°, 60° and
//! 85° (ISO 2813, GU), reflection haze (ASTM E430 method A at 30°, HU), distinctness of image
//! (ASTM E430), CIELAB L*, a*, b* at a multi-angle geometry (D65, 10°), Alman's flop index, and
//! the colour difference from a reference formulation (CIEDE2000, the mean over the standard's
//! geometries). Each is taken from one [`Reading`] of `instrument::coating_study`.

use crate::error::{FormulationError, Result};
use gonio_color::ciede2000;
use gonio_instrument::coating_study::Reading;
use gonio_instrument::gloss::GlossReport;
use gonio_instrument::multiangle::{Geometry, GeometryReading, MultiangleReading};

/// One appearance reading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Output {
    /// Specular gloss at this angle (20, 60 or 85°), GU.
    Gloss(u32),
    /// ASTM E430 method A narrow-angle reflection haze at 30° (±2°), HU.
    Haze,
    /// Distinctness of image (ASTM E430), 0–100.
    Doi,
    /// CIELAB L* at a geometry.
    L(Geometry),
    /// CIELAB a* at a geometry.
    A(Geometry),
    /// CIELAB b* at a geometry.
    B(Geometry),
    /// Alman's flop index from L* at 45as15, 45as45 and 45as110.
    Flop,
    /// CIEDE2000 from the reference formulation, the mean over the standard's geometries.
    De00,
}

impl Output {
    /// Read `gu20`, `gu60`, `gu85`, `haze`, `doi`, `flop`, `dE00` (any case), or `L@G`, `a@G`,
    /// `b@G` with G a geometry such as `45as15`.
    pub fn parse(s: &str) -> Result<Self> {
        let s = s.trim();
        if let Some((what, geometry)) = s.split_once('@') {
            let g = Geometry::parse(geometry)
                .map_err(|e| FormulationError::Invalid(format!("output '{s}': {e}")))?;
            return match what {
                "L" => Ok(Output::L(g)),
                "a" => Ok(Output::A(g)),
                "b" => Ok(Output::B(g)),
                _ => Err(FormulationError::Invalid(format!(
                    "output '{s}': L@, a@ or b@ before the geometry (CIELAB L*, a*, b*)"
                ))),
            };
        }
        Ok(match s.to_ascii_lowercase().as_str() {
            "gu20" => Output::Gloss(20),
            "gu60" => Output::Gloss(60),
            "gu85" => Output::Gloss(85),
            "haze" => Output::Haze,
            "doi" => Output::Doi,
            "flop" => Output::Flop,
            "de00" => Output::De00,
            _ => {
                return Err(FormulationError::Invalid(format!(
                    "output '{s}': one of gu20, gu60, gu85, haze, doi, flop, dE00, or L@G, a@G, \
                     b@G with G a geometry such as 45as15"
                )));
            }
        })
    }

    /// Read a comma-separated list of outputs.
    pub fn parse_list(s: &str) -> Result<Vec<Self>> {
        s.split(',')
            .filter(|p| !p.trim().is_empty())
            .map(Output::parse)
            .collect()
    }

    /// Every output for a standard's `geometries`: the gloss meter's five, L*, a* and b* at each
    /// geometry, the flop index when the geometries hold its three, and ΔE00.
    pub fn all(geometries: &[Geometry]) -> Vec<Self> {
        let mut all = vec![
            Output::Gloss(20),
            Output::Gloss(60),
            Output::Gloss(85),
            Output::Haze,
            Output::Doi,
        ];
        for &g in geometries {
            all.extend([Output::L(g), Output::A(g), Output::B(g)]);
        }
        if FLOP.iter().all(|g| geometries.contains(g)) {
            all.push(Output::Flop);
        }
        all.push(Output::De00);
        all
    }

    /// The short name [`Output::parse`] reads back (`gu60`, `L@45as15`, `dE00`).
    pub fn name(&self) -> String {
        match self {
            Output::Gloss(angle) => format!("gu{angle}"),
            Output::Haze => "haze".into(),
            Output::Doi => "doi".into(),
            Output::L(g) => format!("L@{g}"),
            Output::A(g) => format!("a@{g}"),
            Output::B(g) => format!("b@{g}"),
            Output::Flop => "flop".into(),
            Output::De00 => "dE00".into(),
        }
    }

    /// The output in words, for sentences.
    pub fn words(&self) -> String {
        match self {
            Output::Gloss(angle) => format!("{angle}° gloss"),
            Output::Haze => "haze".into(),
            Output::Doi => "DOI".into(),
            Output::L(g) => format!("L* at {g}"),
            Output::A(g) => format!("CIELAB a* at {g}"),
            Output::B(g) => format!("CIELAB b* at {g}"),
            Output::Flop => "the flop index".into(),
            Output::De00 => "ΔE00 from the base formulation".into(),
        }
    }

    /// [`Output::words`] starting with a capital, for a table's row or a title.
    pub fn title(&self) -> String {
        crate::sensitivity_report::capitalise(&self.words())
    }

    /// The multi-angle geometries this output needs besides the standard's.
    pub fn geometries(&self) -> Vec<Geometry> {
        match self {
            Output::L(g) | Output::A(g) | Output::B(g) => vec![*g],
            Output::Flop => FLOP.to_vec(),
            _ => vec![],
        }
    }

    /// The output's value in `reading`; ΔE00 against `reference` (read with the same settings)
    /// over `geometries`.
    pub fn value(
        &self,
        reading: &Reading,
        reference: &MultiangleReading,
        geometries: &[Geometry],
    ) -> Result<f64> {
        let at = |m: &'_ MultiangleReading, g: Geometry| -> Result<GeometryReading> {
            m.at(g).cloned().ok_or_else(|| {
                FormulationError::Invalid(format!("output {}: {g} was not read", self.name()))
            })
        };
        let gloss = &reading.gloss;
        Ok(match *self {
            Output::Gloss(angle) => gloss_at(gloss, angle)?,
            Output::Haze => gloss.haze,
            Output::Doi => gloss.doi,
            Output::L(g) => at(&reading.multiangle, g)?.lab.l,
            Output::A(g) => at(&reading.multiangle, g)?.lab.a,
            Output::B(g) => at(&reading.multiangle, g)?.lab.b,
            Output::Flop => reading.multiangle.flop_index().ok_or_else(|| {
                FormulationError::Invalid("flop: 45as15, 45as45 and 45as110 were not read".into())
            })?,
            Output::De00 => {
                let mut sum = 0.0;
                for &g in geometries {
                    sum += ciede2000(at(reference, g)?.lab, at(&reading.multiangle, g)?.lab);
                }
                sum / geometries.len() as f64
            }
        })
    }
}

/// The gloss meter's reading at `angle` (20, 60 or 85°), GU.
pub fn gloss_at(gloss: &GlossReport, angle: u32) -> Result<f64> {
    match angle {
        20 => Ok(gloss.gu20),
        60 => Ok(gloss.gu60),
        85 => Ok(gloss.gu85),
        _ => Err(FormulationError::Invalid(format!(
            "gloss at {angle}°: the gloss meter reads 20, 60 and 85°"
        ))),
    }
}

/// The geometries of Alman's flop index.
const FLOP: [Geometry; 3] = [
    Geometry::new(45.0, 15.0),
    Geometry::new(45.0, 45.0),
    Geometry::new(45.0, 110.0),
];
