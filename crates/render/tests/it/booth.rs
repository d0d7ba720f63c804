//! The viewing booth (`gonio_render::booth`): its spec's defaults and errors, pictures identical
//! for any number of threads, and the closure tests of `docs/standard.md`: a Lambertian panel's
//! luminance is ρE/π, and (slow) a flat panel under the collimated light seen by a distant camera
//! reads, averaged over its pixels, what the multi-angle instrument reads of the same table and
//! of the coating itself by random walks.

use gonio_brdf::models::Lambert;
use gonio_render::booth::{self, BoothSpec, Run};
use gonio_render::material::Material;
use std::path::Path;
use std::sync::Arc;

/// The spec of `text` (a file `booth.toml` in the working directory).
fn spec(text: &str) -> BoothSpec {
    BoothSpec::from_toml(text, Path::new("booth.toml")).unwrap()
}

/// The error of the spec `text`, as printed.
fn spec_error(text: &str) -> String {
    BoothSpec::from_toml(text, Path::new("booth.toml"))
        .unwrap_err()
        .to_string()
}

/// A grey Lambertian material of albedo `rho`.
fn lambert(rho: f64) -> Material {
    Material::new(
        "grey",
        Arc::new(Lambert {
            albedo: glam::DVec3::splat(rho),
        }),
    )
}

/// An empty spec is the standard booth: D65, 2000 lx, half of it directional from 45°, N6, a
/// flat panel 150 × 100 mm, the three views, the 10° observer.
#[test]
fn empty_spec_is_the_standard_booth() {
    let checked = spec("").check().unwrap();
    assert_eq!(checked.light.name, "D65");
    assert_eq!(checked.illuminance_lux, 2000.0);
    assert_eq!(checked.directional_fraction, 0.5);
    assert_eq!(checked.directional_deg, 45.0);
    assert_eq!(checked.interior_reflectance, 0.300);
    assert_eq!(checked.size_m, [0.150, 0.100]);
    let views: Vec<(String, f64)> = checked
        .views
        .iter()
        .map(|v| (v.name.clone(), v.aspecular_deg))
        .collect();
    assert_eq!(
        views,
        [
            ("near-specular".to_string(), 15.0),
            ("45".to_string(), 45.0),
            ("flank".to_string(), 110.0)
        ]
    );
    assert_eq!(checked.observer.field_deg(), 10);
    // The white: Y = E/π cd/m².
    let white = booth::white(&checked);
    assert!(
        (white[1] - 2000.0 / std::f64::consts::PI).abs() < 1e-9,
        "{white:?}"
    );
}

/// Bad specs are refused with the file and the field named.
#[test]
fn bad_specs_name_the_file_and_the_field() {
    for (text, field) in [
        ("[light]\nilluminant = \"F2\"\n", "[light] illuminant"),
        ("[light]\nilluminance_lux = -5\n", "[light] illuminance_lux"),
        (
            "[light]\ndirectional_fraction = 1.5\n",
            "directional_fraction",
        ),
        ("[interior]\nmunsell = \"N9\"\n", "[interior] munsell"),
        ("[specimen]\nshape = \"sphere\"\n", "[specimen] shape"),
        ("[camera]\nviews = [\"top\"]\n", "[camera] views"),
        ("[camera]\nviews = [\"as140\"]\n", "[camera] views"),
        ("observer_deg = 4\n", "observer_deg"),
        ("[render]\nspp = 0\n", "[render] spp"),
        ("[light]\nlux = 2000\n", "lux"),
        (
            "[light]\nilluminant = \"A\"\nspectrum = \"lamp.csv\"\n",
            "not both",
        ),
        (
            "[light]\nspectrum = \"no_such_lamp.csv\"\n",
            "[light] spectrum",
        ),
    ] {
        let e = spec_error(text);
        assert!(e.contains("booth.toml") && e.contains(field), "{text}: {e}");
    }
}

/// A measured spectrum read from a file: the film's white is that light's (illuminant A's table
/// written as a CSV gives A's white).
#[test]
fn measured_spectrum_gives_its_white() {
    let dir = tempfile::tempdir().unwrap();
    let a = gonio_color::Illuminant::A.spd();
    let mut csv = String::from("wavelength_nm,value\n");
    for (w, v) in a.wavelengths_nm().iter().zip(a.values()) {
        csv.push_str(&format!("{w},{}\n", 3.0 * v));
    }
    std::fs::write(dir.path().join("lamp.csv"), csv).unwrap();
    let path = dir.path().join("booth.toml");
    let s = BoothSpec::from_toml("[light]\nspectrum = \"lamp.csv\"\n", &path).unwrap();
    let white = booth::white(&s.check().unwrap());
    let named = booth::white(&spec("[light]\nilluminant = \"A\"\n").check().unwrap());
    for c in 0..3 {
        assert!(
            (white[c] / named[c] - 1.0).abs() < 1e-12,
            "{white:?} {named:?}"
        );
    }
}

/// The same picture from one thread and from two.
#[test]
fn booth_picture_is_the_same_for_any_number_of_threads() {
    let s = spec("[render]\nwidth = 24\nheight = 16\nspp = 4\n[camera]\nviews = [\"flank\"]\n");
    let m = lambert(0.4);
    let one = booth::render(
        &s,
        &m,
        &Run {
            threads: Some(1),
            ..Run::default()
        },
    )
    .unwrap();
    let two = booth::render(
        &s,
        &m,
        &Run {
            threads: Some(2),
            ..Run::default()
        },
    )
    .unwrap();
    assert_eq!(one, two);
}

/// The booth's manifest lists among its inputs the files the specimen's coating description
/// names (here its coat's index table, beside it), each with its SHA-256, after the
/// description itself.
#[test]
fn manifest_names_the_files_a_coating_names() {
    let dir = tempfile::tempdir().unwrap();
    let coating = dir.path().join("coating.toml");
    std::fs::write(
        &coating,
        "[coat]\nindex = { file = \"index.csv\" }\nthickness_um = 40\n\
         [base]\nkind = \"diffuse\"\nreflectance = 0.3\n",
    )
    .unwrap();
    let index = dir.path().join("index.csv");
    std::fs::write(&index, "wavelength_nm,value\n380,1.52\n780,1.49\n").unwrap();
    let s = spec("[render]\nwidth = 8\nheight = 6\nspp = 1\n[camera]\nviews = [\"45\"]\n");
    let m = lambert(0.3);
    let specimen = booth::Specimen {
        material: &m,
        file: &coating,
        made: None,
    };
    let out = dir.path().join("out");
    let summary = booth::write_booth_of(&s, None, &specimen, &out, &Run::default()).unwrap();
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&summary.manifest).unwrap()).unwrap();
    let inputs: Vec<(&str, &str)> = manifest["inputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| (i["path"].as_str().unwrap(), i["sha256"].as_str().unwrap()))
        .collect();
    let sha = |p: &Path| gonio_render::picture::sha256_file(p).unwrap().0;
    assert_eq!(
        inputs,
        [
            (coating.to_str().unwrap(), sha(&coating).as_str()),
            (index.to_str().unwrap(), sha(&index).as_str())
        ]
    );
}

/// Closure (a): a Lambertian panel of albedo ρ in the booth has the luminance ρE/π, E the
/// spec's illuminance, under the collimated light alone, the diffuse booth alone and the
/// default half and half, by the distant camera along the normal and by the perspective
/// camera at the flank view (a Lambertian panel under distant lights is equally bright from
/// everywhere).
///
/// Tolerance: the 1%. What the estimate owes to noise is held apart: the mean over the
/// panel's pixels must lie within 1% of ρE/π, and the noise must be small enough for that to
/// mean something (three standard errors of the mean, from the pixels' spread, under 0.3%).
/// The collimated light's part is exact but for the film's wavelength sampling; the diffuse
/// part's illuminance is the map's integrated over its pixels (error ~2e-6, `booth::scene`).
#[test]
fn lambertian_panel_luminance_is_rho_e_over_pi() {
    let rho = 0.5;
    for (fraction, projection, view) in [
        (1.0, "orthographic", "45"),
        (0.0, "orthographic", "45"),
        (0.5, "orthographic", "45"),
        (0.5, "perspective", "flank"),
    ] {
        let s = spec(&format!(
            "[light]\nilluminance_lux = 1500\ndirectional_fraction = {fraction}\n\
             [camera]\nprojection = \"{projection}\"\nviews = [\"{view}\"]\n\
             [render]\nwidth = 40\nheight = 30\nspp = 32\n"
        ));
        let pictures = booth::render(&s, &lambert(rho), &Run::default()).unwrap();
        let mean = booth::closure::specimen_mean(&pictures.views[0]);
        let (se, n) = (mean.standard_error, mean.pixels);
        let expected = rho * 1500.0 / std::f64::consts::PI;
        let ratio = mean.xyz[1] / expected;
        let noise = 3.0 * se[1] / expected;
        eprintln!(
            "Lambertian ρ {rho}, directional {fraction}, {projection} {view}: Y {:.3} cd/m² \
             against ρE/π {expected:.3}, ratio {ratio:.5}, 3σ {noise:.5}, {n} pixels",
            mean.xyz[1]
        );
        assert!(n > 200, "{n} pixels on the specimen");
        assert!(noise < 0.005, "{noise}");
        assert!((ratio - 1.0).abs() < 0.01, "{ratio}");
    }
}

/// Slow closure tests: coatings' tables computed for the test.
mod slow {
    use super::*;
    use gonio_brdf::table::{BrdfTable, Provenance, Resolution};
    use gonio_coating::system::default_bands;
    use gonio_color::{Lab, ciede2000};
    use gonio_instrument::multiangle::{self, E2539, Geometry, Settings};
    use gonio_render::booth::closure;

    /// The table of `examples/coatings/NAME.toml` at a test's resolution and walks, and the
    /// index of its smooth top.
    fn coating_table(name: &str) -> (BrdfTable, Option<f64>) {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/coatings")
            .join(format!("{name}.toml"));
        let coating = gonio_coating::description::read(&path, &default_bands()).unwrap();
        let table = coating
            .table(
                Resolution::isotropic(30, 30, 12),
                &default_bands(),
                8,
                Provenance::default(),
            )
            .unwrap();
        (table, gonio_render::panel::coat_index(&coating))
    }

    /// Closure (b): a flat panel of each coating's table in the booth, lit by the collimated
    /// light alone at each E2539 geometry's illumination (E2539's ten include E2194's five)
    /// and seen by the distant camera at its aspecular angle: its pixels averaged, as CIELAB
    /// against the perfect diffuser under the same light and observer (D65, 10°), are the
    /// multi-angle reading of the same table (`gonio multiangle`, point apertures) within
    /// 0.5 ΔE00 plus the noise bound.
    ///
    /// The noise bound: every pixel on the panel estimates the same XYZ (distant light and
    /// camera, flat panel), so the standard error of the mean of X, Y, Z follows from their
    /// spread over the pixels; the bound is the largest ΔE00 from the mean to the mean moved
    /// by three standard errors in X, Y or Z (either sign). The instrument's reading of a table
    /// has no noise of its own (it evaluates the table). The smooth top's mirror does not reach
    /// the camera at any of these geometries (none is specular), as it does not reach the
    /// instrument's detector.
    #[test]
    fn flat_panel_pixels_read_what_the_instrument_reads() {
        let settings = Settings::default();
        let mut worst: f64 = 0.0;
        for name in ["red_solid", "silver_metallic", "pearl_interference"] {
            let (table, coat) = coating_table(name);
            let reading = multiangle::read_table(&table, &E2539, &settings).unwrap();
            let mut material = Material::from_table("specimen", table);
            if let Some(n) = coat {
                material = material.with_coat(n);
            }
            for g in &E2539 {
                let Geometry {
                    illumination_deg,
                    aspecular_deg,
                } = *g;
                let read = closure::read_flat_panel(
                    &material,
                    illumination_deg,
                    aspecular_deg,
                    &closure::ClosurePicture::default(),
                    &Run::default(),
                )
                .unwrap();
                let (picture, noise, n) = (read.lab, read.noise_bound, read.mean.pixels);
                let instrument = reading.at(*g).unwrap().lab;
                let de = ciede2000(picture, instrument);
                eprintln!(
                    "{name} {g}: picture L* {:.2} a* {:.2} b* {:.2}, instrument L* {:.2} a* \
                     {:.2} b* {:.2}: ΔE00 {de:.3} (noise bound {noise:.3}, {n} pixels)",
                    picture.l, picture.a, picture.b, instrument.l, instrument.a, instrument.b
                );
                assert!(n > 150, "{n} pixels");
                assert!(de < 0.5 + noise, "{name} {g}: ΔE00 {de} (noise {noise})");
                worst = worst.max(de);
            }
        }
        eprintln!("largest ΔE00 {worst:.3}");
    }

    /// The multi-angle reading of the coating `path` evaluated by random walks at the
    /// geometries (no table), as `gonio multiangle COATING.toml` reads it: 16384 walks per
    /// evaluation at 31 wavelengths 400–700 nm, with the walks' seed `seed`.
    fn walks_reading(path: &Path, seed: u64) -> multiangle::MultiangleReading {
        let wavelengths: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * f64::from(i)).collect();
        let coating = gonio_coating::description::read(path, &wavelengths).unwrap();
        let evaluator = coating.evaluator(&wavelengths).unwrap();
        let brdf = |wo, wi, out: &mut [f64]| {
            let mut scratch = gonio_coating::layered::Scratch::default();
            evaluator.eval(wo, wi, 16384, seed, &mut scratch, out);
        };
        multiangle::read(&brdf, &wavelengths, &E2539, &Settings::default()).unwrap()
    }

    /// Closure by walks: the coating itself in the booth (its material as `gonio booth` makes
    /// it, [`booth::material`]: the coating's table at the panel pictures' resolution, its
    /// smooth top's mirror kept apart) under the collimated light, seen by the distant camera
    /// at each E2539 geometry, averaged over its pixels, against the multi-angle reading of the
    /// coating's BRDF evaluated by random walks at the geometries (`gonio multiangle
    /// COATING.toml`, no table): within 0.5 ΔE00 plus the two noise bounds.
    ///
    /// - The picture's: three standard errors of the pixels' mean (as in the test above).
    /// - The walks': the reading is the mean of two with independent seeds, whose difference
    ///   has the standard deviation √2 σ for one reading's σ, so the mean's σ/√2 is half the
    ///   difference's; three of them are 1.5 times the ΔE00 between the two readings (its
    ///   largest over the geometries, as one difference is a single draw of that spread).
    ///
    /// Measured (2026-12-06, 24 × 24 pixels, 64 samples per pixel; docs/standard.md): the solid
    /// within 0.01 ΔE00 (its smooth coat evaluates exactly, without walks); the metallic and the
    /// pearlescent up to 0.45 next to the mirror direction (45as±15) and the pearlescent 0.51 at
    /// 15as80, the largest, under its bound of 0.54. Where the excess comes from (the table's
    /// angular resolution, `panel::resolution`, is the suspect near the mirror) is not yet
    /// traced.
    #[test]
    fn coating_pictures_read_what_the_walks_read() {
        let mut worst: f64 = 0.0;
        for name in ["red_solid", "silver_metallic", "pearl_interference"] {
            let path = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../examples/coatings")
                .join(format!("{name}.toml"));
            let material = booth::material(&path).unwrap();
            let (a, b) = (walks_reading(&path, 1), walks_reading(&path, 2));
            let walk_lab = |g: Geometry| {
                let (la, lb) = (a.at(g).unwrap().lab, b.at(g).unwrap().lab);
                let mean = Lab {
                    l: (la.l + lb.l) / 2.0,
                    a: (la.a + lb.a) / 2.0,
                    b: (la.b + lb.b) / 2.0,
                };
                (mean, ciede2000(la, lb))
            };
            let walks_noise = 1.5 * E2539.iter().map(|g| walk_lab(*g).1).fold(0.0, f64::max);
            // The picture at each geometry: 24 × 24 pixels at 64 samples, the collimated light
            // alone (`closure::read_flat_panel`, the library's closure picture).
            let picture = closure::ClosurePicture {
                size: 24,
                spp: 64,
                illuminance_lux: 2000.0,
            };
            for g in E2539 {
                let read = closure::read_flat_panel(
                    &material,
                    g.illumination_deg,
                    g.aspecular_deg,
                    &picture,
                    &Run::default(),
                )
                .unwrap();
                let (walks, _) = walk_lab(g);
                let de = ciede2000(read.lab, walks);
                let (noise, n) = (read.noise_bound, read.mean.pixels);
                eprintln!(
                    "{name} {g}: picture L* {:.2} a* {:.2} b* {:.2}, walks L* {:.2} a* \
                     {:.2} b* {:.2}: ΔE00 {de:.3} (noise: pixels {noise:.3}, walks \
                     {walks_noise:.3}; {n} pixels)",
                    read.lab.l, read.lab.a, read.lab.b, walks.l, walks.a, walks.b
                );
                assert!(n > 150, "{n} pixels");
                assert!(
                    de < 0.5 + noise + walks_noise,
                    "{name} {g}: ΔE00 {de} (noise: pixels {noise}, walks {walks_noise})"
                );
                worst = worst.max(de);
            }
        }
        eprintln!("largest ΔE00 by walks {worst:.3}");
    }
}

/// The absolute film needs the spectral mode: the tristimulus mode refuses it.
#[test]
fn absolute_film_needs_the_spectral_mode() {
    let scene = super::common::scene(super::common::FURNACE);
    let options = gonio_render::RenderOptions {
        spp: Some(1),
        ..gonio_render::RenderOptions::default()
    };
    let film = gonio_render::Film::Absolute {
        light: Arc::new(gonio_color::Illuminant::D65.spd().clone()),
        observer: gonio_color::Observer::Cie1931TwoDegree,
    };
    let e = gonio_render::render_estimate_on(&scene, &options, &film)
        .unwrap_err()
        .to_string();
    assert!(e.contains("spectral"), "{e}");
}

/// The curved panel stands with its crest at the centre and its normal there along +y: under
/// the collimated light alone, the pixels around the centre of the view along the normal show
/// a Lambertian panel at ρE/π. Tolerance: the four pixels around the image's centre lie within
/// about a pixel (field 1.2 × 300 mm over 60 pixels: 6 mm) of the crest, where the normal turns
/// by a few degrees; symmetric about the crest across the image, the change of cos θ cancels to
/// first order, and the second order (and the film's wavelength noise over 4 × 64 samples,
/// about 0.3%) stays within 1%.
#[test]
fn curved_panel_crest_faces_up() {
    let s = spec(
        "[light]\nilluminance_lux = 1000\ndirectional_fraction = 1\n\
         [specimen]\nshape = \"curved\"\n\
         [camera]\nprojection = \"orthographic\"\nviews = [\"45\"]\n\
         [render]\nwidth = 60\nheight = 40\nspp = 64\n",
    );
    let pictures = booth::render(&s, &lambert(0.5), &Run::default()).unwrap();
    let v = &pictures.views[0];
    let at = |x: usize, y: usize| f64::from(v.image.xyz[y * 60 + x][1]);
    let centre = (at(29, 19) + at(30, 19) + at(29, 20) + at(30, 20)) / 4.0;
    let expected = 0.5 * 1000.0 / std::f64::consts::PI;
    eprintln!("curved panel's crest: Y {centre:.3} against {expected:.3}");
    assert!(
        (centre / expected - 1.0).abs() < 0.01,
        "{centre} {expected}"
    );
    assert!(v.specimen[20 * 60 + 30] && !v.specimen[0]);
}

/// `examples/booth.toml` writes every default out: it is the empty spec's booth.
#[test]
fn example_spec_is_the_default_booth() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/booth.toml");
    let example = BoothSpec::from_file(&path).unwrap();
    assert_eq!(example.check().unwrap(), spec("").check().unwrap());
}
