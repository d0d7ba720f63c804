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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bxdf::Brdf;
    use crate::table::{Resolution, TableBuilder};
    use glam::DVec3;
    use gonio_color::{Xyz, white};

    fn bands() -> Vec<f64> {
        (0..31).map(|i| 400.0 + 10.0 * i as f64).collect()
    }

    /// A spectral table whose spectrum changes with theta_h (a reddish lobe over a bluish base).
    fn spectral_table() -> BrdfTable {
        let wl = bands();
        let channels = Channels::Spectral {
            wavelengths_nm: wl.clone(),
        };
        let mut b = TableBuilder::new(Resolution::isotropic(12, 8, 8), channels).unwrap();
        b.fill(|cell, out: &mut [f64]| {
            let lobe = (-(cell.angles.theta_h / 0.2).powi(2)).exp();
            for (o, w) in out.iter_mut().zip(&wl) {
                let t = (w - 400.0) / 300.0;
                *o = 0.05 * (1.0 - t) + 0.02 + 3.0 * lobe * t;
            }
        });
        b.build().unwrap()
    }

    fn dirs() -> Vec<(DVec3, DVec3)> {
        let d = |t: f64, p: f64| DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        (0..40)
            .map(|k| {
                let k = k as f64;
                (d(0.02 * k, 0.3 * k), d(1.3 - 0.03 * k, 3.0 + 0.1 * k))
            })
            .collect()
    }

    /// The colour tables give the colour of the spectral table's interpolated spectrum, computed
    /// here through the colour crate's own per-spectrum path.
    #[test]
    fn colour_tables_match_the_spectra_they_come_from() {
        let spectral = spectral_table();
        for illuminant in Illuminant::ALL {
            for observer in Observer::ALL {
                let xyz_t = reduce(&spectral, ColourSpace::Xyz, illuminant, observer).unwrap();
                let rgb_t =
                    reduce(&spectral, ColourSpace::LinearSrgb, illuminant, observer).unwrap();
                assert_eq!(xyz_t.channels(), &Channels::Xyz);
                assert_eq!(rgb_t.channels(), &Channels::Rgb);
                let bands = SpectralToXyz::new(&bands(), illuminant, observer).unwrap();
                for (wo, wi) in dirs() {
                    let mut s = vec![0.0; 31];
                    spectral.eval_channels(wo, wi, &mut s);
                    let want = bands.xyz(&s).unwrap().to_array();
                    let mut got = [0.0; 3];
                    xyz_t.eval_channels(wo, wi, &mut got);
                    let want_rgb = bands.linear_srgb(&s).unwrap();
                    let got_rgb = rgb_t.eval(wo, wi);
                    for c in 0..3 {
                        assert!((100.0 * got[c] - want[c]).abs() <= 1e-5 * want[c].abs().max(1.0));
                    }
                    let err = (got_rgb.x - want_rgb.r).abs()
                        + (got_rgb.y - want_rgb.g).abs()
                        + (got_rgb.z - want_rgb.b).abs();
                    assert!(err < 1e-5 * (1.0 + want_rgb.g.abs()), "{err}");
                }
            }
        }
    }

    /// A flat spectrum 1/π (the white diffuser) reduces to the illuminant's white / (100 π) in
    /// XYZ, and an XYZ table under D65 renders as the white-balanced sRGB table does, to the
    /// rounding of the sRGB white point.
    #[test]
    fn white_diffuser_gives_the_white_point() {
        let wl = bands();
        let channels = Channels::Spectral {
            wavelengths_nm: wl.clone(),
        };
        let mut b = TableBuilder::new(Resolution::isotropic(4, 4, 4), channels).unwrap();
        b.fill(|_, out: &mut [f64]| out.fill(std::f64::consts::FRAC_1_PI));
        let t = b.build().unwrap();
        let (wo, wi) = dirs()[5];
        for illuminant in Illuminant::ALL {
            let x = reduce(&t, ColourSpace::Xyz, illuminant, Observer::Cie1931TwoDegree).unwrap();
            let mut got = [0.0; 3];
            x.eval_channels(wo, wi, &mut got);
            let w = white(illuminant, Observer::Cie1931TwoDegree);
            let got = Xyz::from_array(got.map(|v| v * 100.0 * std::f64::consts::PI));
            assert!((got.y - 100.0).abs() < 1e-4, "{got:?}");
            assert!((got.x - w.x).abs() < 1e-4 && (got.z - w.z).abs() < 1e-4);
        }
        let d65 = Observer::Cie1931TwoDegree;
        let x = reduce(&t, ColourSpace::Xyz, Illuminant::D65, d65).unwrap();
        let r = reduce(&t, ColourSpace::LinearSrgb, Illuminant::D65, d65).unwrap();
        let (a, b) = (x.eval(wo, wi), r.eval(wo, wi));
        assert!(
            (a - b).abs().max_element() < 2e-3 * b.max_element(),
            "{a} vs {b}"
        );
    }

    #[test]
    fn non_spectral_tables_and_unknown_spaces_are_rejected() {
        let b = TableBuilder::new(Resolution::isotropic(4, 4, 4), Channels::Rgb).unwrap();
        let t = b.build().unwrap();
        let e = reduce(
            &t,
            ColourSpace::Xyz,
            Illuminant::D65,
            Observer::Cie1931TwoDegree,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("spectral") && e.contains("rgb"), "{e}");
        assert!("lab".parse::<ColourSpace>().is_err());
        assert_eq!(
            "sRGB".parse::<ColourSpace>().unwrap(),
            ColourSpace::LinearSrgb
        );
    }
}
