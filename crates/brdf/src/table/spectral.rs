//! A spectral table seen at any wavelengths, the [`SpectralBrdf`] view of a [`SampledTable`]
//! whose channels are spectral bands: the bands interpolated at the pair of directions (as
//! [`BrdfTable::eval_channels`]), then linearly between bands, the end bands held beyond them
//! (the convention of the tristimulus band weights, [`gonio_color::SpectralToXyz`], so that a
//! spectral renderer and the colour of [`crate::bxdf::Brdf::eval`] read the same spectrum).

use super::{Channels, SampledTable};
use crate::bxdf::SpectralBrdf;
use glam::{DVec2, DVec3};

impl SampledTable {
    /// The spectral view of the table; `None` unless its channels are spectral bands.
    pub(super) fn spectral_view(&self) -> Option<&dyn SpectralBrdf> {
        matches!(self.table().channels(), Channels::Spectral { .. })
            .then_some(self as &dyn SpectralBrdf)
    }
}

impl SpectralBrdf for SampledTable {
    fn eval_at(&self, wo: DVec3, wi: DVec3, wavelengths_nm: &[f64], out: &mut [f64]) {
        let table = self.table();
        let Channels::Spectral {
            wavelengths_nm: bands,
        } = table.channels()
        else {
            unreachable!("spectral_view admits spectral tables only");
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
        for (o, &w) in out.iter_mut().zip(wavelengths_nm) {
            *o = band_value(bands, values, w);
        }
    }

    fn sample_direction(&self, wo: DVec3, u: DVec2, constant_weight: f64) -> Option<(DVec3, f64)> {
        self.sampler()
            .sample_direction_compensated(wo, u, constant_weight)
    }
}

/// The value at `wavelength_nm` of a spectrum given at `bands`: linear between bands, the end
/// values held beyond them.
pub fn band_value(bands: &[f64], values: &[f64], wavelength_nm: f64) -> f64 {
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
    use crate::bxdf::Brdf;
    use crate::table::{BrdfTable, Resolution, TableBuilder};

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

    fn lambertian(channels: Channels, values: &[f64]) -> SampledTable {
        let mut b = TableBuilder::new(Resolution::isotropic(8, 8, 8), channels).unwrap();
        b.fill(|_, out| {
            for (o, v) in out.iter_mut().zip(values) {
                *o = *v;
            }
        });
        let table: BrdfTable = b.build().unwrap();
        SampledTable::new(table)
    }

    /// Only spectral tables have the view; it reads the bands between and beyond them, and
    /// samples the directions and densities of `Brdf::sample`.
    #[test]
    fn spectral_tables_are_seen_at_any_wavelength() {
        assert!(
            lambertian(Channels::Rgb, &[0.1, 0.2, 0.3])
                .spectral()
                .is_none()
        );
        let t = lambertian(
            Channels::Spectral {
                wavelengths_nm: vec![400.0, 500.0, 700.0],
            },
            &[0.1, 0.3, 0.2],
        );
        let view = t.spectral().expect("a spectral table has a spectrum");
        let (wo, wi) = (DVec3::new(0.3, 0.1, 0.95).normalize(), DVec3::Z);
        let mut out = [0.0; 4];
        view.eval_at(wo, wi, &[380.0, 450.0, 600.0, 800.0], &mut out);
        let expect = [0.1, 0.2, 0.25, 0.2];
        for (o, e) in out.iter().zip(expect) {
            assert!((o - e).abs() < 1e-6, "{out:?}");
        }
        let u = DVec2::new(0.3, 0.7);
        let s = t.sample(wo, u).unwrap();
        assert_eq!(view.sample_direction(wo, u, 1.0), Some((s.wi, s.pdf)));
    }
}
