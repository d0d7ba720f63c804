//! The Cornell Cayman measurement (tests/data/cayman.astm, Cornell University Program of
//! Computer Graphics reflectance data) turned into a table by the smoothing interpolation
//! reproduces held-out measurements: every tenth geometry is left out of the fit, and the table
//! is evaluated there. Numbers are quoted in docs/brdf-tables.md.

use crate::common::{HeldOut, cayman_held_out};
use gonio_brdf::formats::scattered::{NOISE_FLOOR_PER_SR, residual_of};

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn held_out_geometries_are_reproduced() {
        let HeldOut {
            file,
            held,
            fit,
            table,
        } = cayman_held_out();
        assert_eq!(file.samples.len(), 1439);
        assert_eq!(file.wavelengths_nm.len(), 31);
        assert_eq!(held.len(), 144);

        // Per band, every value above the noise floor.
        let per_band = residual_of(held, NOISE_FLOOR_PER_SR, |s, out| {
            table.eval_channels(s.wo, s.wi, out)
        });
        // Per geometry, the mean over the 31 bands (every held-out geometry).
        let mut band_mean: Vec<f64> = held
            .iter()
            .map(|s| {
                let mut out = vec![0.0; s.values.len()];
                table.eval_channels(s.wo, s.wi, &mut out);
                let (m, p) = (s.values.iter().sum::<f64>(), out.iter().sum::<f64>());
                ((p - m) / m).abs()
            })
            .collect();
        band_mean.sort_by(f64::total_cmp);
        let band_mean_median = band_mean[band_mean.len() / 2];
        println!(
            "bandwidths {:?}; held-out per band {per_band:?}; band-mean median {band_mean_median}",
            fit.bandwidths()
        );
        assert!(per_band.count > 1000, "{per_band:?}");
        // No regression: the figures of the fit before its coordinates were made regular at the
        // specular direction (3.12% per band, 2.82% band mean; deterministic for any thread count)
        // rounded up to the next 0.1%. After it, on the 90 × 90 × 48 import grid: 2.98% and
        // 2.82%, as the fit evaluated directly at the held-out geometries (3.01%, 2.81%); the
        // 45 × 45 × 48 grid's smoothing happened to lower them (2.88%, 2.58%). With the smooth
        // pole (issue #35): 2.68% and 2.20%.
        assert!(per_band.median_relative <= 0.032, "{per_band:?}");
        assert!(
            band_mean_median <= 0.029,
            "band-mean median relative error {band_mean_median}"
        );
    }
}
