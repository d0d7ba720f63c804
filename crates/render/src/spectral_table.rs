//! A spectral BRDF table seen at a path's wavelengths: the table's bands interpolated at the
//! pair of directions, then linearly between bands. A leaf that the materials hold and the
//! spectral mode ([`crate::spectral`]) evaluates.

use glam::{DVec3, DVec4};
use gonio_brdf::table::{BrdfTable, Channels, SampledTable};
use gonio_color::HERO_COUNT;
use std::sync::Arc;

/// A spectral table with its importance sampler, evaluated at a path's wavelengths.
#[derive(Clone)]
pub struct SpectralTable {
    sampled: Arc<SampledTable>,
}

impl SpectralTable {
    /// The spectral view of `sampled`; `None` unless its channels are spectral.
    pub fn new(sampled: Arc<SampledTable>) -> Option<SpectralTable> {
        matches!(sampled.table().channels(), Channels::Spectral { .. })
            .then_some(SpectralTable { sampled })
    }

    /// The table.
    pub fn table(&self) -> &BrdfTable {
        self.sampled.table()
    }

    /// The table with its importance sampler.
    pub fn sampled(&self) -> &SampledTable {
        &self.sampled
    }

    /// `f(wi, wo)` in 1/sr at each of `wavelengths_nm`: the table's channels interpolated at the
    /// pair of directions, then linearly between bands (end bands held beyond the range).
    pub fn eval(&self, wo: DVec3, wi: DVec3, wavelengths_nm: &[f64; HERO_COUNT]) -> DVec4 {
        let table = self.sampled.table();
        let Channels::Spectral {
            wavelengths_nm: bands,
        } = table.channels()
        else {
            unreachable!("SpectralTable::new admits spectral tables only");
        };
        let mut stack = [0.0f64; 64];
        let mut heap = Vec::new();
        let values = if bands.len() <= stack.len() {
            &mut stack[..bands.len()]
        } else {
            heap.resize(bands.len(), 0.0);
            &mut heap[..]
        };
        table.eval_channels(wo, wi, values);
        DVec4::from_array(wavelengths_nm.map(|w| band_value(bands, values, w)))
    }
}

/// The value at `wavelength_nm` of a spectrum given at `bands`: linear between bands, the end
/// values held beyond them.
fn band_value(bands: &[f64], values: &[f64], wavelength_nm: f64) -> f64 {
    let last = bands.len() - 1;
    if wavelength_nm <= bands[0] {
        return values[0];
    }
    if wavelength_nm >= bands[last] {
        return values[last];
    }
    let i = bands.partition_point(|&b| b <= wavelength_nm) - 1;
    let t = (wavelength_nm - bands[i]) / (bands[i + 1] - bands[i]);
    values[i] + t * (values[i + 1] - values[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_values_interpolate_and_hold_the_ends() {
        let bands = [400.0, 410.0, 430.0];
        let values = [1.0, 2.0, 4.0];
        assert_eq!(band_value(&bands, &values, 380.0), 1.0);
        assert_eq!(band_value(&bands, &values, 405.0), 1.5);
        assert_eq!(band_value(&bands, &values, 420.0), 3.0);
        assert_eq!(band_value(&bands, &values, 430.0), 4.0);
        assert_eq!(band_value(&bands, &values, 700.0), 4.0);
        assert_eq!(band_value(&[550.0], &[0.3], 700.0), 0.3);
    }
}
