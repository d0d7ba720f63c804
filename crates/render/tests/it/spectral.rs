//! The spectral colour mode (`ColourMode::Spectral`) against conservation laws, against the
//! tristimulus mode where the two must agree, against the colour crate's own spectrum → XYZ →
//! sRGB, and for independence of the thread count.

use glam::DVec2;
use gonio_brdf::table::{BrdfTable, Channels, Resolution, TableBuilder};
use gonio_color::{Colorimetry, Illuminant, Observer, Spectrum};
use gonio_render::material::Material;
use gonio_render::{ColourMode, Image, RenderOptions, Scene, render};
use std::f64::consts::FRAC_1_PI;

use crate::common::{FURNACE, opts, scene};

/// Grey materials (a GGX dielectric over a grey diffuse base, a grey floor) under coloured
/// lights: a warm rectangle and a blue sky.
const GREY_SCENE: &str = r#"
[camera]
position = [0.0, 1.2, 4.0]
look_at = [0.0, 0.5, 0.0]
fov_deg = 35
width = 40
height = 30

[render]
max_bounces = 4

[materials.grey]
brdf = { model = "ggx", alpha = 0.25, index = 1.5, diffuse = 0.5 }

[materials.floor]
brdf = { model = "lambert", albedo = 0.4 }

[[shapes]]
type = "sphere"
center = [0.0, 0.6, 0.0]
radius = 0.6
material = "grey"

[[shapes]]
type = "rectangle"
size = [20.0, 20.0]
rotate_deg = [-90.0, 0.0, 0.0]
material = "floor"

[[lights]]
type = "rectangle"
size = [1.5, 1.5]
rotate_deg = [90.0, 0.0, 0.0]
translate = [-1.5, 3.0, 1.5]
radiance = [9.0, 5.0, 2.0]

[[lights]]
type = "sky"
radiance = [0.1, 0.2, 0.4]
"#;

/// Pixels whose whole footprint (centre and corners) sees the sphere: background shows in no
/// sample of them.
fn sphere_pixels(scene: &Scene) -> Vec<usize> {
    let cam = &scene.camera;
    let hits = |x: f64, y: f64| {
        let ray = cam.ray(DVec2::new(x, y));
        scene.accel.intersect(&ray, 0.0, f64::INFINITY).is_some()
    };
    let mut out = vec![];
    for y in 0..cam.height {
        for x in 0..cam.width {
            let (fx, fy) = (x as f64, y as f64);
            let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)];
            if corners.iter().all(|(dx, dy)| hits(fx + dx, fy + dy)) {
                out.push(y * cam.width + x);
            }
        }
    }
    out
}

/// Mean linear sRGB over `pixels`.
fn mean_rgb(img: &Image, pixels: &[usize]) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for &i in pixels {
        for (s, v) in sum.iter_mut().zip(img.pixels[i]) {
            *s += f64::from(v) / pixels.len() as f64;
        }
    }
    sum
}

/// A Lambertian spectral table of reflectance `rho`, sampled at `rho`'s wavelengths.
fn lambert_table(rho: &Spectrum) -> BrdfTable {
    let channels = Channels::Spectral {
        wavelengths_nm: rho.wavelengths_nm().to_vec(),
    };
    let mut b = TableBuilder::new(Resolution::isotropic(4, 4, 4), channels).unwrap();
    b.fill(|_, out: &mut [f64]| {
        for (o, v) in out.iter_mut().zip(rho.values()) {
            *o = v * FRAC_1_PI;
        }
    });
    b.build().unwrap()
}

/// Energy conservation: a white Lambertian sphere in a uniform sky of radiance 1 (the white
/// furnace) renders as the sky, within 1%, whether the white comes from an analytic model
/// (upsampled to a flat spectrum) or from a flat spectral table; the sky seen directly (the top
/// row, 32 pixels of 64 samples) is 1 within 1e-3, a few times its wavelength noise.
#[test]
fn grey_furnace_conserves_energy_in_the_spectral_mode() {
    let mut s = scene(FURNACE);
    let pixels = sphere_pixels(&s);
    assert!(pixels.len() > 300, "{}", pixels.len());
    let spectral = opts(64, 7, ColourMode::Spectral);
    let (img, _) = render(&s, &spectral).unwrap();
    for (c, v) in mean_rgb(&img, &pixels).into_iter().enumerate() {
        assert!((v - 1.0).abs() < 0.01, "analytic Lambert, channel {c}: {v}");
    }
    let top_row: Vec<usize> = (0..s.camera.width).collect();
    for (c, v) in mean_rgb(&img, &top_row).into_iter().enumerate() {
        assert!((v - 1.0).abs() < 1e-3, "sky, channel {c}: {v}");
    }
    let flat = Spectrum::constant((0..31).map(|i| 400.0 + 10.0 * i as f64).collect(), 1.0).unwrap();
    s.materials[0] = Material::from_table("flat", lambert_table(&flat));
    let (img, _) = render(&s, &spectral).unwrap();
    for (c, v) in mean_rgb(&img, &pixels).into_iter().enumerate() {
        assert!(
            (v - 1.0).abs() < 0.01,
            "flat spectral table, channel {c}: {v}"
        );
    }
}

/// A spectrally flat scene (grey materials) under coloured lights gives the tristimulus image:
/// the RGB upsampling returns each light's colour exactly, and grey reflections do not change
/// it. With the same seed both modes trace the same paths, so the per-pixel difference is the
/// wavelength noise alone, independent from pixel to pixel and of mean zero: the test asks, per
/// channel, for the same mean colour within 1% and for a mean difference within 4 standard
/// errors of zero, over the image and over the sphere.
#[test]
fn spectrally_flat_scene_renders_as_in_the_tristimulus_mode() {
    let s = scene(GREY_SCENE);
    let (tri, _) = render(&s, &opts(32, 1, ColourMode::Tristimulus)).unwrap();
    let (spec, _) = render(&s, &opts(32, 1, ColourMode::Spectral)).unwrap();
    let all: Vec<usize> = (0..tri.pixels.len()).collect();
    for (region, pixels) in [("image", all), ("sphere", sphere_pixels(&s))] {
        let (a, b) = (mean_rgb(&tri, &pixels), mean_rgb(&spec, &pixels));
        for c in 0..3 {
            assert!(
                (b[c] / a[c] - 1.0).abs() < 0.01,
                "{region}, channel {c}: {b:?} vs {a:?}"
            );
            let d: Vec<f64> = pixels
                .iter()
                .map(|&i| f64::from(spec.pixels[i][c]) - f64::from(tri.pixels[i][c]))
                .collect();
            let n = d.len() as f64;
            let mean = d.iter().sum::<f64>() / n;
            let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            let z = mean / (var / n).sqrt();
            assert!(
                z.abs() < 4.0,
                "{region}, channel {c}: mean difference {mean}, z = {z}"
            );
        }
    }
}

/// The ColorChecker patches as Lambertian spectral tables in the white furnace: the sphere's
/// mean colour is the patch's linear sRGB under D65 (CIE 1931 2°, white-balanced) that the
/// colour crate computes from the spectrum by its 1 nm summation. Tolerance: 0.5% of the value
/// plus 3e-4, a few times the wavelength noise of the mean over the sphere at 64 samples.
#[test]
fn colorchecker_tables_render_to_their_colour() {
    let text = include_str!("../../../color/data/MacbethColorChecker.dat");
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|f| f.trim().parse().unwrap()).collect())
        .collect();
    let wavelengths: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let mut s = scene(FURNACE);
    let pixels = sphere_pixels(&s);
    // Dark skin, orange, blue, green, red, cyan.
    for patch in [1, 7, 13, 14, 15, 18] {
        let rho =
            Spectrum::new(wavelengths.clone(), rows.iter().map(|r| r[patch]).collect()).unwrap();
        let want = Colorimetry::of_reflectance(&rho, Illuminant::D65, Observer::Cie1931TwoDegree)
            .linear_srgb;
        s.materials[0] = Material::from_table("patch", lambert_table(&rho));
        let (img, _) = render(&s, &opts(64, 3, ColourMode::Spectral)).unwrap();
        let got = mean_rgb(&img, &pixels);
        for (c, want) in [want.r, want.g, want.b].into_iter().enumerate() {
            assert!(
                (got[c] - want).abs() < 0.005 * want + 3e-4,
                "patch {patch}, channel {c}: {got:?} vs {want}"
            );
        }
    }
}

/// A table whose spectrum changes with angle (a reddish lobe over a bluish base) renders the
/// the same bit for bit with 1 and 2 threads in the spectral mode.
#[test]
fn spectral_image_does_not_depend_on_the_thread_count() {
    let wl: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
    let channels = Channels::Spectral {
        wavelengths_nm: wl.clone(),
    };
    let mut b = TableBuilder::new(Resolution::isotropic(16, 8, 8), channels).unwrap();
    b.fill(|cell, out: &mut [f64]| {
        let lobe = (-(cell.angles.theta_h / 0.2).powi(2)).exp();
        for (o, w) in out.iter_mut().zip(&wl) {
            let t = (w - 400.0) / 300.0;
            *o = 0.05 * (1.0 - t) + 0.02 + 3.0 * lobe * t;
        }
    });
    let table = b.build().unwrap();
    let mut s = scene(GREY_SCENE);
    let k = s.materials.iter().position(|m| m.name == "grey").unwrap();
    s.materials[k] = Material::from_table("travel", table);
    let one = RenderOptions {
        threads: Some(1),
        ..opts(8, 3, ColourMode::Spectral)
    };
    let two = RenderOptions {
        threads: Some(2),
        ..one.clone()
    };
    let (a, _) = render(&s, &one).unwrap();
    let (b, _) = render(&s, &two).unwrap();
    assert_eq!(a, b);
    let (c, _) = render(&s, &opts(8, 4, ColourMode::Spectral)).unwrap();
    assert_ne!(a, c, "another seed gives other noise");
}

/// With a single surface interaction (`max_bounces = 0`) no BRDF sample follows the light
/// sample, which must then carry the whole direct light: the white furnace still renders as the
/// sky (within 1%), in both colour modes.
#[test]
fn last_interaction_takes_the_whole_light_sample() {
    let s = scene(FURNACE);
    let pixels = sphere_pixels(&s);
    for colour in [ColourMode::Tristimulus, ColourMode::Spectral] {
        let o = RenderOptions {
            max_bounces: Some(0),
            ..opts(64, 5, colour)
        };
        let (img, _) = render(&s, &o).unwrap();
        for (c, v) in mean_rgb(&img, &pixels).into_iter().enumerate() {
            assert!((v - 1.0).abs() < 0.01, "{colour:?}, channel {c}: {v}");
        }
    }
}
