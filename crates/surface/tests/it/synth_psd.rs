//! Surfaces synthesised from a PSD: the requested Sq or rms slope exact, the same map for a seed
//! whatever the thread count, a table that tabulates a power law giving the power law's map, the
//! table format and its errors, impossible requests; and (slow) the wave-scan bands of an
//! orange peel against its PSD integrated with the bands' transmissions, and the log-log slope
//! of the realised radial PSD.

use gonio_surface::HeightMap;
use gonio_surface::gaussian_filter::transmission;
use gonio_surface::ops;
use gonio_surface::synth_psd::*;
use std::f64::consts::PI;
use std::path::Path;

fn power_law(exponent: f64, long: f64, short: f64, target: Target, n: usize) -> PsdSurface {
    PsdSurface {
        spectrum: Spectrum::PowerLaw {
            exponent,
            long,
            short,
        },
        target,
        nx: n,
        ny: n / 2,
        dx: 25e-6,
        dy: 25e-6,
        seed: 3,
    }
}

/// The rms slope along x after levelling, computed here from its definition: forward
/// differences within each row, less the least-squares plane's x slope.
fn slope_x(map: &HeightMap) -> f64 {
    let tilt = ops::fit_plane(map).unwrap().slope_x;
    let (mut sum, mut n) = (0.0, 0.0);
    for row in map.heights().rows() {
        for i in 0..row.len() - 1 {
            sum += ((row[i + 1] - row[i]) / map.dx() - tilt).powi(2);
            n += 1.0;
        }
    }
    (sum / n).sqrt()
}

fn sq(map: &HeightMap) -> f64 {
    let lev = ops::level(map).unwrap();
    (lev.heights().iter().map(|z| z * z).sum::<f64>() / lev.valid_count() as f64).sqrt()
}

#[test]
fn sq_and_slope_are_exact_and_a_seed_gives_one_map() {
    let by_sq = power_law(3.0, 3e-3, 0.2e-3, Target::Sq(0.8e-6), 256)
        .generate()
        .unwrap();
    assert!((sq(&by_sq) / 0.8e-6 - 1.0).abs() < 1e-9, "{}", sq(&by_sq));
    assert!(by_sq.heights().mean().unwrap().abs() < 1e-12 * 0.8e-6);
    let req = power_law(3.0, 3e-3, 0.2e-3, Target::SlopeX(1e-3), 256);
    let by_slope = req.generate().unwrap();
    assert!((slope_x(&by_slope) / 1e-3 - 1.0).abs() < 1e-9);
    assert!((rms_slope_x(&by_slope).unwrap() / 1e-3 - 1.0).abs() < 1e-9);
    // Sq and slope targets scale the same noise: the maps are proportional.
    let ratio = by_slope.heights()[[5, 7]] / by_sq.heights()[[5, 7]];
    assert!(
        by_slope
            .heights()
            .iter()
            .zip(by_sq.heights())
            .all(|(a, b)| (a - ratio * b).abs() <= 1e-9 * a.abs().max(1e-12))
    );
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| req.generate().unwrap())
    };
    assert_eq!(run(1).heights(), run(3).heights());
    let other = PsdSurface {
        seed: 4,
        ..req.clone()
    };
    assert_ne!(run(1).heights(), other.generate().unwrap().heights());
}

/// A table that samples `q^-3` at four points interpolates it exactly (log-log), so with the
/// power law's cutoffs (set between modes) it gives the power law's map to rounding; the
/// abscissa may be given as a wavelength or a spatial frequency.
#[test]
fn a_table_of_a_power_law_gives_the_power_laws_map() {
    // Grid 256 × 128 at 25 µm: modes every 2π/6.4 mm along x, 2π/3.2 mm along y. Cutoffs 3.1
    // and 0.21 mm fall between modes.
    let law = power_law(3.0, 3.1e-3, 0.21e-3, Target::SlopeX(1e-3), 256);
    let wavelengths_mm = [3.1, 1.0, 0.5, 0.21];
    let c = |l_mm: f64| (2.0 * PI / (l_mm * 1e-3)).powf(-3.0) * 1e-20;
    let by_wavelength = std::iter::once("# a power law\nwavelength_mm, psd_m4".to_string())
        .chain(wavelengths_mm.iter().map(|l| format!("{l}, {:e}", c(*l))))
        .collect::<Vec<_>>()
        .join("\n");
    let by_frequency = std::iter::once("frequency_per_mm psd_m4".to_string())
        .chain(
            wavelengths_mm
                .iter()
                .map(|l| format!("{} {:e}", 1.0 / l, c(*l))),
        )
        .collect::<Vec<_>>()
        .join("\n");
    let want = law.generate().unwrap();
    for text in [by_wavelength, by_frequency] {
        let table = RadialPsd::parse(&text, Path::new("t.csv")).unwrap();
        let got = PsdSurface {
            spectrum: Spectrum::Radial(table),
            ..law.clone()
        }
        .generate()
        .unwrap();
        let peak = want.heights().iter().fold(0.0f64, |m, z| m.max(z.abs()));
        let diff = want
            .heights()
            .iter()
            .zip(got.heights())
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(diff < 1e-9 * peak, "{diff:e} vs {peak:e}");
    }
}

/// A table's own magnitude: the PSD of a Gaussian ACF, `π σ² T² exp(−q² T²/4)` (stats module
/// docs), σ = 0.5 µm, T = 0.4 mm, tabulated densely; the map's Sq² is a sum over modes whose
/// relative standard deviation is `√(Σ p²)/Σ p` (each mode pair's power exponential, module
/// docs of synth_psd), computed here, and held to 4 of them (plus 1% for the table's log-linear
/// interpolation and the ACF's tail beyond the period).
#[test]
fn a_table_keeps_its_own_magnitude() {
    let (sigma, t) = (0.5e-6, 0.4e-3);
    let c = |q: f64| PI * sigma * sigma * t * t * (-q * q * t * t / 4.0).exp();
    let points: Vec<(f64, f64)> = (0..400)
        .map(|i| {
            let q = 2.0 * PI / 20e-3 * 1.02f64.powi(i);
            (q, c(q))
        })
        .collect();
    let table = RadialPsd::new(points).unwrap();
    let (nx, ny, d) = (512, 512, 25e-6);
    let map = PsdSurface {
        spectrum: Spectrum::Radial(table),
        target: Target::AsGiven,
        nx,
        ny,
        dx: d,
        dy: d,
        seed: 9,
    }
    .generate()
    .unwrap();
    let (dq, mut sum, mut sum2) = (2.0 * PI / (nx as f64 * d), 0.0, 0.0);
    for kx in 0..=nx / 2 {
        for ky in 0..ny {
            let fy = if ky <= ny / 2 {
                ky as f64
            } else {
                ky as f64 - ny as f64
            };
            if kx == 0 && ky == 0 {
                continue;
            }
            let p = c((kx as f64).hypot(fy) * dq);
            // Half plane: a mode with 0 < kx < nx/2 stands for its conjugate too.
            let w = if kx == 0 || kx == nx / 2 { 1.0 } else { 2.0 };
            sum += w * p;
            sum2 += w * p * p;
        }
    }
    let expected = (sum * dq * dq / (4.0 * PI * PI)).sqrt();
    assert!((expected / sigma - 1.0).abs() < 0.01, "{expected:e}");
    let rel_sd_power = sum2.sqrt() / sum;
    let got = sq(&map);
    assert!(
        ((got / sigma).powi(2) - 1.0).abs() < 4.0 * rel_sd_power + 0.01,
        "Sq {got:e} vs {sigma:e} (power ± {rel_sd_power})"
    );
}

#[test]
fn tables_that_cannot_be_read_say_where() {
    let path = Path::new("peel.csv");
    for (text, says) in [
        ("", "line 1"),
        (
            "lambda_mm,psd_m4\n1,2\n2,3",
            "wavelength_mm or frequency_per_mm",
        ),
        ("wavelength_mm,psd\n1,2\n2,3", "expected two columns"),
        ("wavelength_mm,psd_m4\n1,2", "at least two points"),
        ("wavelength_mm,psd_m4\n1,2\n1,3", "twice"),
        ("wavelength_mm,psd_m4\n1,2\n2,x", "line 3"),
        ("wavelength_mm,psd_m4\n1,2\n-2,3", "line 3"),
        ("wavelength_mm,psd_m4\n1,2\n2,-3", "PSD >= 0"),
    ] {
        let e = RadialPsd::parse(text, path).unwrap_err().to_string();
        assert!(e.contains("peel.csv") && e.contains(says), "{text:?}: {e}");
    }
    let missing = RadialPsd::read(Path::new("no-such-psd.csv")).unwrap_err();
    assert!(missing.to_string().contains("no-such-psd.csv"), "{missing}");
}

#[test]
fn impossible_requests_are_errors_that_say_why() {
    // 256 × 128 at 25 µm: 6.4 × 3.2 mm.
    let ok = power_law(3.0, 3e-3, 0.2e-3, Target::SlopeX(1e-3), 256);
    assert!(ok.generate().is_ok());
    let with = |spectrum: Spectrum, target: Target| PsdSurface {
        spectrum,
        target,
        ..ok.clone()
    };
    let law = |exponent: f64, long: f64, short: f64| Spectrum::PowerLaw {
        exponent,
        long,
        short,
    };
    let far = RadialPsd::new(vec![(1.0, 1e-20), (2.0, 1e-20)]).unwrap();
    for (request, says) in [
        (
            with(law(3.0, 5e-3, 0.2e-3), Target::SlopeX(1e-3)),
            "exceeds the map's shorter side, 3.2 mm",
        ),
        (
            with(law(3.0, 3e-3, 0.04e-3), Target::SlopeX(1e-3)),
            "under two spacings (0.05 mm)",
        ),
        (
            with(law(3.0, 1e-3, 2e-3), Target::SlopeX(1e-3)),
            "short one below the long one",
        ),
        (
            with(law(f64::NAN, 3e-3, 0.2e-3), Target::SlopeX(1e-3)),
            "exponent",
        ),
        (
            with(law(3.0, 3e-3, 0.2e-3), Target::AsGiven),
            "no magnitude of its own",
        ),
        (
            with(law(3.0, 3e-3, 0.2e-3), Target::Sq(-1.0)),
            "positive and finite",
        ),
        (
            with(Spectrum::Radial(far), Target::AsGiven),
            "no power at the wavelengths",
        ),
    ] {
        let e = request.generate().unwrap_err().to_string();
        assert!(e.contains(says), "{request:?}: {e}");
    }
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;
    use gonio_surface::stats::{Window, radial_psd};
    use gonio_surface::waviness::{BANDS, Direction, Quantity, waviness};

    /// An orange peel, `q^-3.5` between 0.15 and 10 mm on a 2048 × 512 map at 25 µm (51.2 ×
    /// 12.8 mm), rms slope along x 1 mrad: each wave-scan band's mean square slope over four
    /// seeds equals the PSD integrated against the band's transmission.
    ///
    /// Expected value, computed here from the formulas: a profile along x sees every mode
    /// `(qx, qy)` of the periodic map with power ∝ `C(|q|)`; the forward difference multiplies
    /// its slope's power by `D(qx) = (2 sin(qx dx/2)/dx)²` and the band by
    /// `T(qx)² = (H(λ; λs) − H(λ; λc))²`, λ = 2π/|qx| (ISO 16610-21's transmission). The total is
    /// set to (1 mrad)², so the band's mean square is `(1 mrad)² Σ C D T² / Σ C D` over the modes.
    ///
    /// Statistical error: each independent mode's power is exponential (variance = mean²), so
    /// over the whole periodic map a sum `Σ p_k` has the relative standard deviation
    /// `1/√N`, `N = (Σ p_k)² / Σ p_k²` (the modes' effective number, counted here). The band is
    /// read only on the part `f` of each row that its filter leaves (the run less a long cutoff
    /// at each end), which resolves modes `1/f` times more coarsely along x: `N f` independent
    /// modes. The ratio to the total adds at most the total's own `1/√N_total`. Over four seeds
    /// the mean is held to 4 of its standard deviations,
    /// `4 (1/√(N f) + 1/√N_total) / √4`.
    #[test]
    fn wave_scan_bands_of_an_orange_peel_follow_its_psd() {
        let (nx, ny, d, n, long, short) = (2048usize, 512usize, 25e-6, 3.5, 10e-3, 0.15e-3);
        let target = 1e-3;
        let req = |seed| PsdSurface {
            spectrum: Spectrum::PowerLaw {
                exponent: n,
                long,
                short,
            },
            target: Target::SlopeX(target),
            nx,
            ny,
            dx: d,
            dy: d,
            seed,
        };
        let (dqx, dqy) = (2.0 * PI / (nx as f64 * d), 2.0 * PI / (ny as f64 * d));
        let c = |q: f64| {
            if q >= 2.0 * PI / long * (1.0 - 1e-9) && q <= 2.0 * PI / short * (1.0 + 1e-9) {
                q.powf(-n)
            } else {
                0.0
            }
        };
        // Every mode of the half plane, with the weight of its conjugate: (qx, C, weight).
        let mut modes = Vec::new();
        for kx in 0..=nx / 2 {
            for ky in 0..ny {
                let fy = if ky <= ny / 2 {
                    ky as f64
                } else {
                    ky as f64 - ny as f64
                };
                let (qx, qy) = (kx as f64 * dqx, fy * dqy);
                let p = c(qx.hypot(qy));
                if p > 0.0 {
                    let w = if kx == 0 || kx == nx / 2 { 1.0 } else { 2.0 };
                    modes.push((qx, p, w));
                }
            }
        }
        let fd = |qx: f64| (2.0 * (qx * d / 2.0).sin() / d).powi(2);
        let effective = |f: &dyn Fn(f64) -> f64| {
            let (s, s2) = modes.iter().fold((0.0, 0.0), |(s, s2), &(qx, p, w)| {
                let v = p * f(qx);
                (s + w * v, s2 + w * v * v)
            });
            (s, s * s / s2)
        };
        let (total, n_total) = effective(&fd);
        let seeds = 4;
        let mut mean_square = vec![0.0; BANDS.len()];
        for seed in 0..seeds {
            let map = req(seed).generate().unwrap();
            for (m, r) in mean_square
                .iter_mut()
                .zip(waviness(&map, Direction::X, Quantity::Slope).unwrap())
            {
                *m += r.rms.map_or(f64::NAN, |s| s * s) / seeds as f64;
            }
        }
        let length = (nx - 2) as f64 * d;
        for (b, got) in BANDS.iter().zip(&mean_square) {
            let t = |qx: f64| {
                if qx == 0.0 {
                    return 0.0;
                }
                let l = 2.0 * PI / qx;
                (transmission(l, b.short_m) - transmission(l, b.long_m)).powi(2)
            };
            let (band, n_band) = effective(&|qx| fd(qx) * t(qx));
            let want = target * target * band / total;
            let f = (length - 2.0 * b.long_m) / length;
            if f <= 0.0 {
                assert!(
                    got.is_nan(),
                    "{}: a band too long for the map reads",
                    b.name
                );
                continue;
            }
            let sd = (1.0 / (n_band * f).sqrt() + 1.0 / n_total.sqrt()) / (seeds as f64).sqrt();
            eprintln!(
                "{}: {:.4} vs {:.4} mrad (rel. sd of the mean square {sd:.3}, N {n_band:.0}, f \
                 {f:.2})",
                b.name,
                got.sqrt() * 1e3,
                want.sqrt() * 1e3
            );
            assert!(
                (got / want - 1.0).abs() < 4.0 * sd,
                "{}: mean square {got:e} vs {want:e} (± {sd})",
                b.name
            );
        }
    }

    /// The radially averaged PSD of a `q^-3` surface (1024² at 25 µm, 0.15–10 mm) falls with
    /// log-log slope −3. Fit: least squares of ln C on ln q over the rings from 16 Δq to 0.8 of
    /// the short cutoff (clear of both cutoffs), each weighted by its independent modes `m/2`
    /// (a ring counts each mode and its conjugate), since the log of the mean of `m/2`
    /// exponential powers has the variance `2/m`; the slope's standard error is
    /// `1/√(Σ (m/2)(x − x̄)²)`. Allowed: 4 standard errors plus 0.01 for the two biases of the
    /// estimate, both below that from 16 Δq on: the log of a mean of `m/2` exponentials is low
    /// by `1/m` (varying from 0.01 to 0.001 across the fit, a slope error < 0.005), and a
    /// ring's mean of `q^-3` exceeds `q̄^-3` by `n(n+1)/24 / b²` at ring b (< 0.002).
    #[test]
    fn the_realised_psd_falls_as_the_power_law() {
        let (n, d, exponent) = (1024usize, 25e-6, 3.0);
        let map = PsdSurface {
            spectrum: Spectrum::PowerLaw {
                exponent,
                long: 10e-3,
                short: 0.15e-3,
            },
            target: Target::Sq(1e-6),
            nx: n,
            ny: n,
            dx: d,
            dy: d,
            seed: 11,
        }
        .generate()
        .unwrap();
        let dq = 2.0 * PI / (n as f64 * d);
        let bins: Vec<_> = radial_psd(&map, Window::None)
            .unwrap()
            .into_iter()
            .filter(|b| b.q >= 16.0 * dq && b.q <= 0.8 * 2.0 * PI / 0.15e-3)
            .collect();
        let w: Vec<f64> = bins.iter().map(|b| b.modes as f64 / 2.0).collect();
        let x: Vec<f64> = bins.iter().map(|b| b.q.ln()).collect();
        let y: Vec<f64> = bins.iter().map(|b| b.psd.ln()).collect();
        let sw: f64 = w.iter().sum();
        let xm = w.iter().zip(&x).map(|(w, x)| w * x).sum::<f64>() / sw;
        let ym = w.iter().zip(&y).map(|(w, y)| w * y).sum::<f64>() / sw;
        let sxx: f64 = w.iter().zip(&x).map(|(w, x)| w * (x - xm).powi(2)).sum();
        let sxy: f64 = (0..x.len()).map(|i| w[i] * (x[i] - xm) * (y[i] - ym)).sum();
        let slope = sxy / sxx;
        let se = 1.0 / sxx.sqrt();
        eprintln!(
            "log-log slope {slope:.4} ± {se:.4} over {} rings",
            bins.len()
        );
        assert!(
            (slope + exponent).abs() < 4.0 * se + 0.01,
            "{slope} vs {} (se {se})",
            -exponent
        );
    }
}
