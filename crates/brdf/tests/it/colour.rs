//! Colour tables from spectral tables: the colour of each cell is the colour of its spectrum
//! (colour-science's tables), a white diffuser gives the white point, bad inputs are refused.

use glam::DVec3;
use gonio_brdf::bxdf::Brdf;
use gonio_brdf::table::colour::*;
use gonio_brdf::table::{BrdfTable, Channels, Resolution, TableBuilder};
use gonio_color::{Illuminant, Observer, SpectralToXyz, Xyz, white};

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
            let rgb_t = reduce(&spectral, ColourSpace::LinearSrgb, illuminant, observer).unwrap();
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
