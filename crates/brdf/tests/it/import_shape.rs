//! The shape of imported Cornell tables where the measurement is sparse: the specular
//! pole, a small ring about the specular direction, the cells beyond the measured domain, the
//! band-to-band smoothness of the albedo and the colour of a blue paint's highlight
//! (`cargo test -p gonio-brdf --test it import_shape -- --nocapture` prints the figures).
//! Data: tests/data/{cayman,krylon_blue}.astm (Cornell University Program of Computer Graphics
//! reflectance data).

use crate::common::{astm_fit, astm_table, cayman_path, krylon_blue_path};
use glam::DVec3;
use gonio_brdf::formats::astm::AstmFile;
use gonio_brdf::table::BrdfTable;
use gonio_brdf::table::coords::{HalfDiff, dir};

/// Band-mean of the table at (wi, wo).
fn band_mean(table: &BrdfTable, wi: DVec3, wo: DVec3) -> f64 {
    let mut out = vec![0.0; table.channel_count()];
    table.eval_channels(wo, wi, &mut out);
    out.iter().sum::<f64>() / out.len() as f64
}

/// The direction `delta` away from `w`, toward azimuth `psi` about it.
fn off(w: DVec3, delta: f64, psi: f64) -> DVec3 {
    let e2 = DVec3::Y;
    let e1 = w.cross(e2).normalize();
    (delta.cos() * w + delta.sin() * (psi.cos() * e1 + psi.sin() * e2)).normalize()
}

/// Per channel, the largest spread `(max - min) / max` over phi_d of the cells at theta_h = 0.
fn pole_spread(table: &BrdfTable) -> (f64, f64, f64) {
    let res = table.resolution();
    let nc = table.channel_count();
    let (mut spread, mut lo, mut hi) = (0.0f64, f64::INFINITY, 0.0f64);
    for td in 0..res.theta_d {
        for c in 0..nc {
            let v: Vec<f64> = (0..res.phi_d)
                .map(|pd| table.cell_values(res.cell_index(0, 0, td, pd))[c] as f64)
                .collect();
            let mx = v.iter().copied().fold(0.0, f64::max);
            let mn = v.iter().copied().fold(f64::INFINITY, f64::min);
            lo = lo.min(mn);
            hi = hi.max(mx);
            if mx > 0.0 {
                spread = spread.max((mx - mn) / mx);
            }
        }
    }
    (spread, lo, hi)
}

/// Band means of the table on a ring `delta` from the mirror direction of light at `theta_i`.
fn ring(table: &BrdfTable, theta_i: f64, delta: f64) -> Vec<f64> {
    let wi = dir(theta_i, 0.0);
    let wr = dir(theta_i, std::f64::consts::PI);
    (0..72)
        .map(|k| band_mean(table, wi, off(wr, delta, k as f64 * 5f64.to_radians())))
        .collect()
}

fn file_max(file: &AstmFile) -> f64 {
    file.samples
        .iter()
        .flat_map(|s| s.values.iter().copied())
        .fold(0.0, f64::max)
}

/// Directional albedo per band at the given incidence.
fn albedo(table: &BrdfTable, theta_i: f64) -> Vec<f64> {
    table.albedo(theta_i, 0.0)
}

/// max over bands of |second difference| / band mean.
fn second_difference(v: &[f64]) -> f64 {
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    v.windows(3)
        .map(|w| (w[0] - 2.0 * w[1] + w[2]).abs() / mean)
        .fold(0.0, f64::max)
}

/// Of the measured spectra whose band mean is above 1e-2 1/sr (ten times the noise floor) and
/// that lie in the plane of incidence, the largest [`second_difference`].
fn measured_second_difference(file: &AstmFile) -> f64 {
    file.samples
        .iter()
        .filter(|s| {
            let a = HalfDiff::from_dirs(s.wi, s.wo).unwrap();
            let m = s.values.iter().sum::<f64>() / s.values.len() as f64;
            a.phi_d.sin().abs() < 1e-3 && m > 1e-2
        })
        .map(|s| second_difference(&s.values))
        .fold(0.0, f64::max)
}

/// At theta_h = 0 every phi_d is the same pair of directions turned about the normal, so an
/// isotropic table must hold one value there.
#[test]
fn specular_pole_is_single_valued() {
    for path in [cayman_path(), krylon_blue_path()] {
        let (_, table) = astm_table(&path);
        let (spread, lo, hi) = pole_spread(table);
        println!(
            "{}: pole values {lo:.3}..{hi:.1}, largest spread {spread:.2e}",
            path.display()
        );
        // The cells are stored as f32: equal f64 values, or values a few f64 ulps apart from the
        // round-off of the directions, round to f32 values at most one f32 ulp (6e-8) apart.
        assert!(spread <= 1.2e-7, "spread over phi_d at the pole {spread}");
    }
}

/// The band mean of the table at the mirror direction of light at `theta_i` (radians).
fn specular(table: &BrdfTable, theta_i: f64) -> f64 {
    band_mean(table, dir(theta_i, 0.0), dir(theta_i, std::f64::consts::PI))
}

/// Of the file's incidences, the steepest growth of the measured specular value with incidence:
/// per incidence the band mean of the geometry nearest the mirror direction, and the largest
/// |d ln f / d theta_i| (per radian) between neighbouring incidences.
fn measured_specular_growth(file: &AstmFile) -> f64 {
    let mut nearest: Vec<(f64, f64, f64)> = vec![]; // (theta_i, delta, band mean)
    for s in &file.samples {
        let mirror = DVec3::new(-s.wi.x, -s.wi.y, s.wi.z);
        let delta = mirror.dot(s.wo).clamp(-1.0, 1.0).acos();
        let ti = s.wi.z.acos();
        let m = s.values.iter().sum::<f64>() / s.values.len() as f64;
        match nearest.iter_mut().find(|n| (n.0 - ti).abs() < 1e-3) {
            Some(n) if delta < n.1 => *n = (ti, delta, m),
            Some(_) => {}
            None => nearest.push((ti, delta, m)),
        }
    }
    nearest.sort_by(|a, b| a.0.total_cmp(&b.0));
    nearest
        .windows(2)
        .map(|w| ((w[1].2 / w[0].2).ln() / (w[1].0 - w[0].0)).abs())
        .fold(0.0, f64::max)
}

/// About the specular direction the lobe is round where the data say nothing else.
///
/// A ring `δ` = 0.2° from the mirror direction of light at `θ_i` crosses incidences: its point
/// in the plane of incidence beyond the mirror direction is the pair (θ_i, θ_i + δ), whose
/// reciprocal partner is the same pair, so to first order a reciprocal BRDF there equals its
/// mirror value `P` at `θ_i + δ/2`, and on the ring (azimuth ψ about the mirror direction, ψ = 0
/// in the plane) `f(ψ) ≈ P(θ_i) (1 + a cos ψ)` with `a = (δ/2) d ln P / dθ`: the growth of the
/// peak with incidence, which the data do say (Cayman's specular samples grow 36-fold from 70°
/// to 80°), appears as this first harmonic. Round means the rest: `f(ψ) / (P̄ (1 + a cos ψ))`,
/// with `a` taken from the table's own mirror values at θ_i ± 0.5°, varies by less than 5% (the
/// issue's bound) around the ring. And the harmonic is no invented trend: `a` is at most
/// `(δ/2)` times the steepest growth of the measured specular value between neighbouring
/// incidences in the file.
#[test]
fn specular_peak_is_a_round_lobe() {
    let delta = 0.2f64.to_radians();
    for path in [cayman_path(), krylon_blue_path()] {
        let (file, table) = astm_table(&path);
        let growth = measured_specular_growth(file);
        for ti in [30.0f64, 45.0, 60.0, 75.0] {
            let r = ring(table, ti.to_radians(), delta);
            let mean = r.iter().sum::<f64>() / r.len() as f64;
            let slope = (specular(table, (ti + 0.5).to_radians()).ln()
                - specular(table, (ti - 0.5).to_radians()).ln())
                / 1f64.to_radians();
            let a = delta / 2.0 * slope;
            let round: Vec<f64> = r
                .iter()
                .enumerate()
                .map(|(k, v)| v / (mean * (1.0 + a * (k as f64 * 5f64.to_radians()).cos())))
                .collect();
            let spread = |v: &[f64]| {
                let mx = v.iter().copied().fold(f64::MIN, f64::max);
                let mn = v.iter().copied().fold(f64::MAX, f64::min);
                (mx - mn) / (v.iter().sum::<f64>() / v.len() as f64)
            };
            let (total, roundness) = (spread(&r), spread(&round));
            println!(
                "{}: ring 0.2° at {ti}°: median {:.4}, variation {total:.4}; reciprocity's \
                 harmonic a = {a:.4} (bound from the data {:.4}); without it {roundness:.4}",
                path.display(),
                mean,
                delta / 2.0 * growth
            );
            assert!(
                roundness < 0.05,
                "{ti}°: ring variation beyond the harmonic {roundness}"
            );
            assert!(
                a.abs() <= delta / 2.0 * growth,
                "{ti}°: the peak grows faster with incidence ({a}) than the data do"
            );
        }
    }
}

/// No cell holds a phantom peak: none exceeds the largest measured value by more than the fit's
/// own rms relative residual at the measured points, and none is pinned at the file's maximum.
#[test]
fn no_phantom_peak() {
    for path in [cayman_path(), krylon_blue_path()] {
        let (file, table) = astm_table(&path);
        let mx = file_max(file);
        let at_max = table.values().iter().filter(|&&v| v == mx as f32).count();
        let top = table.values().iter().copied().fold(0.0f32, f32::max) as f64;
        let fit = astm_fit(&path);
        let rms = fit.residual(&file.samples).rms_relative;
        let model = fit.model();
        let lobes = |b: &gonio_brdf::formats::lobe_model::BandModel| {
            b.lobes
                .iter()
                .map(|l| format!("{:.3}×α{:.3}", l.weight, l.alpha))
                .collect::<Vec<_>>()
                .join(" + ")
        };
        let (first, middle) = (&model.bands[0], &model.bands[model.bands.len() / 2]);
        println!(
            "{}: model, first band ρ {:.4} + {}; middle band ρ {:.4} + {}",
            path.display(),
            first.rho,
            lobes(first),
            middle.rho,
            lobes(middle)
        );
        println!(
            "{}: file max {mx}, table max {top:.1}, cells at the file max {at_max}, fit rms {rms:.3}",
            path.display()
        );
        assert!(
            top <= mx * (1.0 + rms),
            "table max {top} against measured {mx}"
        );
    }
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// The blue paint's highlight is the colour of its measurement: at the specular cells nearer
    /// normal than any measured geometry (theta_d < 10°; the file starts at theta_i = 10°), the
    /// table's 700/440 nm ratio lies within the range of the measured near-specular
    /// (theta_h < 1°) ratios, widened by the two bands' fit residuals. A clamp to the file's
    /// maximum (measured at 80°, where the spectrum is not that of the 10° specular) shows up as a
    /// ratio outside the range.
    #[test]
    fn blue_highlight_keeps_its_measured_colour() {
        let (file, table) = astm_table(&krylon_blue_path());
        let wl = &file.wavelengths_nm;
        let c440 = wl.iter().position(|&w| w == 440.0).unwrap();
        let c700 = wl.iter().position(|&w| w == 700.0).unwrap();
        let ratios: Vec<f64> = file
            .samples
            .iter()
            .filter(|s| HalfDiff::from_dirs(s.wi, s.wo).unwrap().theta_h < 1f64.to_radians())
            .map(|s| s.values[c700] / s.values[c440])
            .collect();
        assert!(ratios.len() >= 5, "{ratios:?}");
        // Each band is reproduced at the measured points to its own residual, fitted separately: a
        // ratio of two bands may move by the sum of their median residuals beyond the measured
        // range (and by 1e-6 for the f32 cells).
        let fit = astm_fit(&krylon_blue_path());
        let per_band = fit.residual_per_band(&file.samples);
        let slack = per_band[c440] + per_band[c700] + 1e-6;
        println!(
            "median residual at 440 nm {:.4}, at 700 nm {:.4}",
            per_band[c440], per_band[c700]
        );
        let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min) * (1.0 - slack);
        let hi = ratios.iter().copied().fold(0.0, f64::max) * (1.0 + slack);
        let res = table.resolution();
        let (mut rmin, mut rmax, mut vmax) = (f64::INFINITY, 0.0f64, [0.0f64; 2]);
        for td in (0..res.theta_d).take_while(|&td| {
            res.cell_angles(res.cell_index(0, 0, td, 0)).theta_d < 10f64.to_radians()
        }) {
            for pd in 0..res.phi_d {
                let v = table.cell_values(res.cell_index(0, 0, td, pd));
                let (a, b) = (v[c440] as f64, v[c700] as f64);
                rmin = rmin.min(b / a);
                rmax = rmax.max(b / a);
                vmax = [vmax[0].max(a), vmax[1].max(b)];
            }
        }
        println!(
            "specular below 10°: 440 nm up to {:.3}, 700 nm up to {:.3}, ratio {rmin:.6}..{rmax:.6} (measured {lo:.6}..{hi:.6})",
            vmax[0], vmax[1]
        );
        assert!(
            rmin >= lo && rmax <= hi,
            "ratios {rmin}..{rmax} outside {lo}..{hi}"
        );
    }

    /// Band-to-band smoothness. The directional albedo is a positive weighted integral of f,
    /// `a_c = ∫ f_c w`, so `|Δ²a_c| <= ∫ |Δ²f_c| w <= B ∫ mean(f) w = B mean(a)` whenever every
    /// spectrum `f(·)` has `|Δ²f_c| <= B mean(f)`: the albedo may be no rougher across bands than
    /// the roughest measured spectrum, `B` taken over the measured in-plane spectra.
    #[test]
    fn band_albedo_is_as_smooth_as_the_measured_spectra() {
        for path in [cayman_path(), krylon_blue_path()] {
            let (file, table) = astm_table(&path);
            let b = measured_second_difference(file);
            for ti in [10.0f64, 30.0, 60.0] {
                let d = second_difference(&albedo(table, ti.to_radians()));
                println!(
                    "{}: albedo at {ti}°: {d:.4} (measured bound {b:.4})",
                    path.display()
                );
                assert!(d <= b, "albedo second difference {d} against {b} at {ti}°");
            }
        }
    }
}
