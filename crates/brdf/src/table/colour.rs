//! Spectral tables reduced to colour tables, as the NIST work on rendering metallic paints did
//! (spectrogoniophotometric tables → CIE tristimulus values → a smoothing interpolation → a
//! renderer): every cell's spectrum becomes CIE XYZ or linear sRGB under a chosen illuminant and
//! observer, through the band weights of [`gonio_color::SpectralToXyz`] (ASTM E308-18 §7.3
//! construction with linear interpolation between bands).
//!
//! The reduction is linear and the table interpolation is linear, so a colour table evaluates
//! to exactly the colour of the spectral table's interpolated spectrum: only the f32 storage
//! rounds.

use super::{BrdfTable, Channels};
use crate::error::{BrdfError, Result};
use gonio_color::{Illuminant, Observer, SpectralToXyz};

/// What a spectral table is reduced to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColourSpace {
    /// CIE XYZ / 100 ([`Channels::Xyz`]): a perfectly white diffuser of BRDF 1/π gives
    /// Y = 1/π whatever the illuminant.
    Xyz,
    /// Linear sRGB ([`Channels::Rgb`]), white-balanced from the illuminant's white to the sRGB
    /// white (Bradford, [`gonio_color::display_matrix`]): a flat spectrum v gives about (v, v, v).
    LinearSrgb,
}

impl ColourSpace {
    /// `xyz` or `srgb`.
    pub fn name(self) -> &'static str {
        match self {
            ColourSpace::Xyz => "xyz",
            ColourSpace::LinearSrgb => "srgb",
        }
    }
}

impl std::str::FromStr for ColourSpace {
    type Err = BrdfError;

    fn from_str(s: &str) -> Result<Self> {
        match s.to_ascii_lowercase().as_str() {
            "xyz" => Ok(ColourSpace::Xyz),
            "srgb" | "linear-srgb" | "rgb" => Ok(ColourSpace::LinearSrgb),
            _ => Err(BrdfError::Invalid(format!(
                "unknown colour space '{s}': use xyz or srgb (linear sRGB)"
            ))),
        }
    }
}

/// The colour table of a spectral `table` under `illuminant`, seen by `observer`. Cells
/// without data stay without data; the provenance is kept, with a `colour` entry recording the
/// space, illuminant and observer.
pub fn reduce(
    table: &BrdfTable,
    space: ColourSpace,
    illuminant: Illuminant,
    observer: Observer,
) -> Result<BrdfTable> {
    let Channels::Spectral { wavelengths_nm } = table.channels() else {
        return Err(BrdfError::Invalid(format!(
            "only a spectral table reduces to colour; this one is {}",
            table.channels().describe()
        )));
    };
    let bands = SpectralToXyz::new(wavelengths_nm, illuminant, observer)
        .map_err(|e| BrdfError::Invalid(format!("spectral table: {e}")))?;
    let (weights, channels): (Vec<[f64; 3]>, Channels) = match space {
        ColourSpace::Xyz => (
            bands
                .xyz_weights()
                .iter()
                .map(|w| w.map(|v| v / 100.0))
                .collect(),
            Channels::Xyz,
        ),
        ColourSpace::LinearSrgb => (bands.rgb_weights().to_vec(), Channels::Rgb),
    };
    let values: Vec<f32> = table
        .values()
        .chunks_exact(weights.len())
        .flat_map(|cell| {
            if cell[0].is_nan() {
                return [f32::NAN; 3];
            }
            let mut sum = [0.0f64; 3];
            for (w, &v) in weights.iter().zip(cell) {
                for c in 0..3 {
                    sum[c] += w[c] * f64::from(v);
                }
            }
            sum.map(|v| v as f32)
        })
        .collect();
    let mut provenance = table.provenance().clone();
    provenance.extra.insert(
        "colour".into(),
        serde_json::json!({
            "space": space.name(),
            "illuminant": illuminant.name(),
            "observer_deg": observer.field_deg(),
            "from": table.channels().describe(),
        }),
    );
    BrdfTable::from_values(table.resolution(), channels, provenance, values)
}

/// Per-channel linear-sRGB weights of an XYZ/100 table: the columns of the XYZ → linear sRGB
/// matrix of IEC 61966-2-1 (no white balance: a table reduced under illuminant A renders with
/// A's yellowish white).
pub(crate) fn xyz_rgb_weights() -> Vec<[f64; 3]> {
    let m = gonio_color::srgb::xyz_to_linear_srgb_matrix();
    (0..3).map(|c| [m[0][c], m[1][c], m[2][c]]).collect()
}
