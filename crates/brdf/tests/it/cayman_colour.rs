//! The colour of the Cornell Cayman metallic paint (tests/data/cayman.astm, Cornell University
//! Program of Computer Graphics reflectance data) survives the NIST pipeline: measured spectra →
//! smoothing interpolation → spectral table → XYZ table. At every measured geometry the measured
//! spectrum, reduced to colour, and the XYZ table's value there are compared in CIEDE2000.
//!
//! Scaling, the same for both sides: CIELAB of the XYZ of the reflectance factor π·f (the BRDF
//! of the sample over that of the perfect reflecting diffuser, 1/π), relative to the white of
//! the perfect diffuser under the illuminant (Y = 100). Near the specular peak π·f exceeds 1 and
//! L* exceeds 100; CIELAB is still defined there and the comparison stays like for like.
//!
//! The acceptance comparison (median CIEDE2000 under 2) uses the table fitted to all geometries;
//! a second one fits every geometry but each tenth and compares at those held out (the colour a
//! table predicts where it was not measured).
//! A second test bins the geometries by aspecular angle and checks that the table keeps the
//! paint's colour travel. The figures are quoted in docs/color.md.

use crate::common::{HeldOut, cayman_held_out, cayman_path};
use glam::DVec3;
use gonio_brdf::formats::astm;
use gonio_brdf::formats::scattered::Sample;
use gonio_brdf::table::BrdfTable;
use gonio_brdf::table::colour::{ColourSpace, reduce};
use gonio_color::{Illuminant, Lab, Observer, SpectralToXyz, Xyz, ciede2000, white};
use std::f64::consts::PI;

/// The Cayman table as `gonio brdf import` makes it (through the library's import, not the
/// shared fit of `common`), imported once for both tests.
fn imported() -> &'static BrdfTable {
    static TABLE: std::sync::LazyLock<BrdfTable> = std::sync::LazyLock::new(|| {
        astm::import(&cayman_path(), astm::default_resolution())
            .unwrap()
            .0
    });
    &TABLE
}

/// Median, 90th percentile and maximum of CIEDE2000.
struct Quantiles {
    median: f64,
    p90: f64,
    max: f64,
}

impl std::fmt::Display for Quantiles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "CIEDE2000 median {:.3}, 90th percentile {:.3}, max {:.3}",
            self.median, self.p90, self.max
        )
    }
}

/// CIEDE2000 between each sample's measured colour and the colour of `spectral`'s XYZ table at
/// its geometry.
fn quantiles(
    spectral: &BrdfTable,
    samples: &[&Sample],
    wavelengths_nm: &[f64],
    illuminant: Illuminant,
    observer: Observer,
) -> Quantiles {
    let bands = SpectralToXyz::new(wavelengths_nm, illuminant, observer).unwrap();
    let table = reduce(spectral, ColourSpace::Xyz, illuminant, observer).unwrap();
    let w = white(illuminant, observer);
    let mut de: Vec<f64> = samples
        .iter()
        .map(|s| {
            let measured = bands.xyz(&s.values).unwrap().to_array().map(|v| PI * v);
            let mut t = [0.0; 3];
            table.eval_channels(s.wo, s.wi, &mut t);
            let tabulated = t.map(|v| 100.0 * PI * v);
            ciede2000(
                Xyz::from_array(measured).to_lab(w),
                Xyz::from_array(tabulated).to_lab(w),
            )
        })
        .collect();
    de.sort_by(f64::total_cmp);
    let q = |p: f64| de[((de.len() - 1) as f64 * p).round() as usize];
    Quantiles {
        median: q(0.5),
        p90: q(0.9),
        max: q(1.0),
    }
}

/// What the tristimulus shortcut (render in linear sRGB, multiply colours at each bounce) costs
/// against spectral transport for paths that meet the Cayman paint twice: for pairs of measured
/// geometries, the colour of the product of the two spectra (π f_a · π f_b) against the product
/// of their linear sRGB colours, both through the same white-balanced D65 reduction. One bounce
/// is exact (the reduction is linear), and so is a second bounce on a grey surface.
#[test]
fn tristimulus_shortcut_error_on_two_bounces() {
    let path = cayman_path();
    let file = astm::read(&path).unwrap();
    let bands = SpectralToXyz::new(
        &file.wavelengths_nm,
        Illuminant::D65,
        Observer::Cie1931TwoDegree,
    )
    .unwrap();
    let w = gonio_color::srgb::srgb_white();
    let lab = |c: gonio_color::LinearSrgb| c.to_xyz().to_lab(w);
    let rgb = |v: &[f64]| bands.linear_srgb(v).unwrap();
    let spectra: Vec<Vec<f64>> = file
        .samples
        .iter()
        .step_by(7)
        .map(|s| s.values.iter().map(|v| PI * v).collect())
        .collect();
    let mut de = Vec::new();
    for a in &spectra {
        let ca = rgb(a);
        let grey: Vec<f64> = a.iter().map(|v| 0.4 * v).collect();
        let shortcut = gonio_color::LinearSrgb {
            r: 0.4 * ca.r,
            g: 0.4 * ca.g,
            b: 0.4 * ca.b,
        };
        assert!(ciede2000(lab(rgb(&grey)), lab(shortcut)) < 1e-9);
        for b in &spectra {
            let cb = rgb(b);
            let product: Vec<f64> = a.iter().zip(b).map(|(x, y)| x * y).collect();
            let shortcut = gonio_color::LinearSrgb {
                r: ca.r * cb.r,
                g: ca.g * cb.g,
                b: ca.b * cb.b,
            };
            de.push(ciede2000(lab(rgb(&product)), lab(shortcut)));
        }
    }
    de.sort_by(f64::total_cmp);
    let q = |p: f64| de[((de.len() - 1) as f64 * p).round() as usize];
    println!(
        "two Cayman bounces, {} pairs: shortcut vs spectral CIEDE2000 median {:.2}, 90th \
         percentile {:.2}, max {:.2}",
        de.len(),
        q(0.5),
        q(0.9),
        q(1.0)
    );
    assert!(de.iter().all(|d| d.is_finite()));
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// Colour travel: the Cayman colour, averaged (in CIELAB) over the geometries in bins of
    /// aspecular angle (between the detector and the mirror direction of the light), turns from
    /// turquoise near the specular direction to blue far from it. The table keeps each bin's mean
    /// colour within 1 ΔE00 and the hue travel within 3°.
    #[test]
    fn colour_travel_is_kept() {
        let path = cayman_path();
        let file = astm::read(&path).unwrap();
        let spectral = imported();
        let (illuminant, observer) = (Illuminant::D65, Observer::Cie1931TwoDegree);
        let bands = SpectralToXyz::new(&file.wavelengths_nm, illuminant, observer).unwrap();
        let table = reduce(spectral, ColourSpace::Xyz, illuminant, observer).unwrap();
        let w = white(illuminant, observer);
        let lab_of = |xyz_0_100: [f64; 3]| Xyz::from_array(xyz_0_100.map(|v| PI * v)).to_lab(w);
        let edges = [10.0, 20.0, 35.0, 50.0, 70.0, 180.0];
        let mut hues = Vec::new();
        for pair in edges.windows(2) {
            let (mut measured, mut tabulated, mut n) = ([0.0; 3], [0.0; 3], 0.0);
            for s in &file.samples {
                let mirror = DVec3::new(-s.wi.x, -s.wi.y, s.wi.z);
                let aspecular_deg = mirror.dot(s.wo).clamp(-1.0, 1.0).acos().to_degrees();
                if aspecular_deg < pair[0] || aspecular_deg >= pair[1] {
                    continue;
                }
                let mut x = [0.0; 3];
                table.eval_channels(s.wo, s.wi, &mut x);
                let m = lab_of(bands.xyz(&s.values).unwrap().to_array());
                let t = lab_of(x.map(|v| 100.0 * v));
                for (acc, lab) in [(&mut measured, m), (&mut tabulated, t)] {
                    acc[0] += lab.l;
                    acc[1] += lab.a;
                    acc[2] += lab.b;
                }
                n += 1.0;
            }
            let mean = |a: [f64; 3]| Lab {
                l: a[0] / n,
                a: a[1] / n,
                b: a[2] / n,
            };
            let (m, t) = (mean(measured), mean(tabulated));
            println!(
                "aspecular {}-{}°: {n} geometries; measured L* {:.1} C* {:.1} h {:.1}°; table L* {:.1} \
                 C* {:.1} h {:.1}°",
                pair[0],
                pair[1],
                m.l,
                m.chroma(),
                m.hue_deg(),
                t.l,
                t.chroma(),
                t.hue_deg()
            );
            assert!(ciede2000(m, t) < 1.0, "{m:?} vs {t:?}");
            hues.push((m.hue_deg(), t.hue_deg()));
        }
        let (first, last) = (hues[0], hues[hues.len() - 1]);
        let travel = (last.0 - first.0, last.1 - first.1);
        println!(
            "hue travel: measured {:.1}°, table {:.1}°",
            travel.0, travel.1
        );
        assert!(travel.0 > 20.0, "the data's hue travel {:.1}°", travel.0);
        assert!((travel.0 - travel.1).abs() < 3.0, "{travel:?}");
    }

    #[test]
    fn measured_and_tabulated_cayman_colours_agree() {
        let path = cayman_path();
        let file = astm::read(&path).unwrap();
        let spectral = imported();
        let all: Vec<&Sample> = file.samples.iter().collect();
        for (illuminant, observer) in [
            (Illuminant::D65, Observer::Cie1931TwoDegree),
            (Illuminant::A, Observer::Cie1964TenDegree),
        ] {
            let de = quantiles(spectral, &all, &file.wavelengths_nm, illuminant, observer);
            println!(
                "{illuminant} {observer}, all {} geometries: {de}",
                all.len()
            );
            assert!(de.median < 2.0, "median CIEDE2000 {}", de.median);
        }

        let HeldOut { held, table, .. } = cayman_held_out();
        let held: Vec<&Sample> = held.iter().collect();
        let (illuminant, observer) = (Illuminant::D65, Observer::Cie1931TwoDegree);
        let de = quantiles(table, &held, &file.wavelengths_nm, illuminant, observer);
        println!(
            "{illuminant} {observer}, {} held-out geometries: {de}",
            held.len()
        );
        assert!(de.median < 2.0, "held-out median CIEDE2000 {}", de.median);
    }
}
