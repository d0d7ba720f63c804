//! The shape of imported Cornell tables where the measurement is sparse: the specular
//! pole, a small ring about the specular direction, the cells beyond the measured domain, the
//! band-to-band smoothness of the albedo and the colour of a blue paint's highlight
//! (`cargo test -p gonio-brdf --test it import_shape -- --nocapture` prints the figures).
//! Data: tests/data/{cayman,krylon_blue,garnet_red}.astm (Cornell University Program of Computer
//! Graphics reflectance data).

use crate::common::{astm_fit, astm_table, cayman_path, garnet_red_path, krylon_blue_path};
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

/// The ring of table cells at θ_h node `k` (every φ_d node) at θ_d node `td`, channel `c`; `None`
/// where a cell of it lies below the horizon (NaN by design).
fn table_ring(table: &BrdfTable, k: usize, td: usize, c: usize) -> Option<Vec<f64>> {
    let res = table.resolution();
    let ring: Vec<f64> = (0..res.phi_d)
        .map(|pd| table.cell_values(res.cell_index(0, k, td, pd))[c] as f64)
        .collect();
    ring.iter().all(|v| v.is_finite()).then_some(ring)
}

/// `(max - min) / mean` of `v`.
fn spread(v: &[f64]) -> f64 {
    let mx = v.iter().copied().fold(f64::MIN, f64::max);
    let mn = v.iter().copied().fold(f64::MAX, f64::min);
    (mx - mn) / (v.iter().sum::<f64>() / v.len() as f64)
}

/// The variation of a ring of table cells (uniform in φ_d) beyond `a + b cos 2φ_d`, the least
/// squares fit of its mean `a` and its second harmonic: the spread (max − min) of the residual,
/// relative to `a`.
fn beyond_second_harmonic(ring: &[f64]) -> f64 {
    let n = ring.len() as f64;
    let cos2 = |k: usize| (2.0 * std::f64::consts::TAU * k as f64 / n).cos();
    let a = ring.iter().sum::<f64>() / n;
    let b = 2.0
        * ring
            .iter()
            .enumerate()
            .map(|(k, v)| v * cos2(k))
            .sum::<f64>()
        / n;
    let rest: Vec<f64> = ring
        .iter()
        .enumerate()
        .map(|(k, v)| v - a - b * cos2(k))
        .collect();
    let (mn, mx) = (
        rest.iter().copied().fold(f64::MAX, f64::min),
        rest.iter().copied().fold(f64::MIN, f64::max),
    );
    (mx - mn) / a
}

/// The largest of a ring's values.
fn ring_max(ring: &[f64]) -> f64 {
    ring.iter().copied().fold(f64::MIN, f64::max)
}

/// About the specular direction the lobe is round where the data say nothing else, and its top
/// has no pit.
///
/// **Through the table's interpolation, band mean.** A ring `δ` = 0.2° from the mirror
/// direction of light at `θ_i` crosses incidences: its point in the plane of incidence beyond
/// the mirror direction is the pair (θ_i, θ_i + δ), whose reciprocal partner is the same pair,
/// so to first order a reciprocal BRDF there equals its mirror value `P` at `θ_i + δ/2`, and on
/// the ring (azimuth ψ about the mirror direction, ψ = 0 in the plane) `f(ψ) ≈ P(θ_i) (1 + a
/// cos ψ)` with `a = (δ/2) d ln P / dθ`: the growth of the peak with incidence, which the data
/// do say (Cayman's specular samples grow 36-fold from 70° to 80°), appears as this first
/// harmonic. Round means the rest: `f(ψ) / (P̄ (1 + a cos ψ))`, with `a` taken from the table's
/// own mirror values at θ_i ± 0.5°, varies by less than 5% (the bound) around the ring.
/// And the harmonic is no invented trend: `a` is at most `(δ/2)` times the steepest growth of
/// the measured specular value between neighbouring incidences in the file. (That bound is met
/// with equality by a table whose log peak is quadratic in θ_i between two measured incidences,
/// the slope at the midpoint being the secant's, so it has no margin by construction: Cayman
/// at 75° is at 0.03576 against 0.03582. Garnet red, whose table's peak at 75° grows 10%
/// faster than the secant of its 70° and 80° measurements, is left out of this part.)
///
/// **The table's own rings, every θ_d node and every band** (issue #35, point 3). At θ_h = 0
/// (the pole) every φ_d is the same pair of directions; the rings about it are the cells at the
/// θ_h nodes 1, 2 and 3 (0.011°, 0.044°, 0.1°), all φ_d, the same θ_d. They lie in the import's
/// round core (δ < 2°), where the fit is a function of δ and θ_d alone (coordinates
/// `(u(δ), t, 0, 0)`, a model round about the mirror direction), so around a ring the table
/// varies only through δ(φ_d). δ is unchanged by φ_d → −φ_d (the mirror image about the plane
/// of the normal and the half vector) and by φ_d → φ_d + 180° (wi and wo exchanged:
/// reciprocity), so it is an even, π-periodic function of φ_d; to first order in θ_h,
/// `δ² = 2θ_h² (1 + cos²θ_d + sin²θ_d cos 2φ_d)`. A smooth lobe, a function of δ², therefore
/// varies around the ring as `a + b cos 2φ_d` (reciprocity's harmonic on this grid) up to the
/// lobe's curvature over the ring's range of δ² (at most (0.2°)², against the fit's kernel
/// width of about 1° in δ); the rest must stay under 5%. Before the fix the Cayman ring at
/// 0.044° fell in steps from 54 to 33 to 20 1/sr near φ_d = 90° at θ_d 69–71°.
///
/// No pole below its first rings (1 to 3, each against the next): where the data show no peak
/// the pole may be a smooth minimum, but not a pit. A smooth top changes from the pole as δ²,
/// and δ on ring `k` is proportional to θ_h ∝ k², so the rise of ring `k` (its largest cell)
/// over the pole is `(k/(k+1))⁴` of the rise of ring `k + 1`; twice that is allowed for the
/// higher orders, plus 0.5% of the pole: a third of the measurement's own scatter (the fit
/// meets the measured values to a median 1.3-1.7%), finer than the data can show (the fit's
/// clamp on extrapolating planes leaves kinks: Krylon blue at θ_d 30°, 610 nm, has a bump of
/// 0.15% at ring 3). A pit fails: before the fix the Cayman pole at θ_d 69° (400 nm) was 20.2
/// 1/sr, level with ring 1, and ring 2 rose 167% above it where a smooth top allows
/// 2·(2/3)⁴ = 0.40 of ring 3's rise (166%), 66%. So does a cone, whose rises grow as δ ∝ k²,
/// beyond the 0.5%: rings 1 and 2 exceed the allowance by factors (k+1)²/(2k²) = 2 and 1.1.
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
            let (total, roundness) = (spread(&r), spread(&round));
            println!(
                "{}: ring 0.2° at {ti}°: median {:.4}, variation {total:.4}; reciprocity's \
                 harmonic a = {a:.5} (bound from the data {:.5}); without it {roundness:.4}",
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
    let mut failures = vec![];
    for path in [cayman_path(), krylon_blue_path(), garnet_red_path()] {
        let (file, table) = astm_table(&path);
        let res = table.resolution();
        let wavelengths = &file.wavelengths_nm;
        // Per ring: the largest variation beyond the second harmonic, and where (θ_d, band).
        let mut worst_round = [(0.0f64, 0usize, 0usize); 3];
        // Per ring 1 to 3: the largest rise of the ring over the pole beyond what a smooth top
        // allows, relative to the pole, and where.
        let mut worst_pit = [(f64::MIN, 0usize, 0usize); 3];
        let mut rings_checked = 0;
        for td in 0..res.theta_d {
            for c in 0..table.channel_count() {
                let Some(rings) = (1..=4)
                    .map(|k| table_ring(table, k, td, c))
                    .collect::<Option<Vec<_>>>()
                else {
                    continue;
                };
                rings_checked += 1;
                for (k, ring) in rings.iter().take(3).enumerate() {
                    let r = beyond_second_harmonic(ring);
                    if r > worst_round[k].0 {
                        worst_round[k] = (r, td, c);
                    }
                }
                let pole = table.cell_values(res.cell_index(0, 0, td, 0))[c] as f64;
                let rise = |k: usize| ring_max(&rings[k - 1]) / pole - 1.0;
                for k in 1..=3 {
                    let allowed =
                        2.0 * (k as f64 / (k + 1) as f64).powi(4) * rise(k + 1).max(0.0) + 5e-3;
                    let excess = rise(k) - allowed;
                    if excess > worst_pit[k - 1].0 {
                        worst_pit[k - 1] = (excess, td, c);
                    }
                }
            }
        }
        // Every θ_d node whose rings lie above the horizon: all but the last few before 90°.
        assert!(
            rings_checked > 80 * table.channel_count(),
            "{rings_checked} rings"
        );
        let node = |td: usize, c: usize, k: usize| {
            let pole = table.cell_values(res.cell_index(0, 0, td, 0))[c];
            let ring = table_ring(table, k, td, c).unwrap_or_default();
            let (mn, mx) = (
                ring.iter().copied().fold(f64::MAX, f64::min),
                ring_max(&ring),
            );
            format!(
                "θ_d {td}°, {} nm: pole {pole:.4}, ring {k} {mn:.4}..{mx:.4}",
                wavelengths[c]
            )
        };
        for (k, &(r, td, c)) in worst_round.iter().enumerate() {
            println!(
                "{}: rings at θ_h node {} ({rings_checked} of them): largest variation beyond \
                 a + b cos 2φ_d {r:.4} at {}",
                path.display(),
                k + 1,
                node(td, c, k + 1)
            );
        }
        for (k, &(e, td, c)) in worst_pit.iter().enumerate() {
            println!(
                "{}: ring {} over the pole beyond a smooth top's allowance: largest excess \
                 {e:.2e} of the pole (≤ 0 passes) at {}; ring {} {}",
                path.display(),
                k + 1,
                node(td, c, k + 1),
                k + 2,
                node(td, c, k + 2)
            );
        }
        for (k, &(r, td, c)) in worst_round.iter().enumerate() {
            if r >= 0.05 {
                failures.push(format!(
                    "{}: ring {} varies by {r:.4} beyond a + b cos 2φ_d at {}",
                    path.display(),
                    k + 1,
                    node(td, c, k + 1)
                ));
            }
        }
        for (k, &(e, td, c)) in worst_pit.iter().enumerate() {
            if e > 0.0 {
                failures.push(format!(
                    "{}: the pole lies below ring {} by more than a smooth top allows at {}; \
                     ring {} {}",
                    path.display(),
                    k + 1,
                    node(td, c, k + 1),
                    k + 2,
                    node(td, c, k + 2)
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
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
