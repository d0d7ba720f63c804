//! Whole-renderer checks against conservation laws and against independent renders: the white
//! furnace, a tabulated copy of an analytic BRDF, the pay-off of importance sampling and of
//! denoising, and determinism whatever the number of threads.

use glam::{DVec2, DVec3};
use gonio_brdf::models::{Lambert, Model, ModelSpec};
use gonio_brdf::table::{BrdfTable, Provenance, Resolution, SampledTable};
use gonio_brdf::{Brdf, Rgb};
use gonio_render::difference::relative_rmse;
use gonio_render::{BrdfSampling, ColourMode, Image, RenderOptions, Scene, render};
use std::path::Path;
use std::sync::Arc;

use crate::common::{FURNACE, opts, scene};

/// Pixels whose centre ray meets the sphere with `cos θo` above 0.2, and that cosine.
fn sphere_pixels(scene: &Scene) -> Vec<(usize, f64)> {
    let cam = &scene.camera;
    let mut out = vec![];
    for y in 0..cam.height {
        for x in 0..cam.width {
            let ray = cam.ray(DVec2::new(x as f64 + 0.5, y as f64 + 0.5));
            if let Some(hit) = scene.accel.intersect(&ray, 0.0, f64::INFINITY) {
                let mu = -hit.ns.dot(ray.dir);
                if mu > 0.2 {
                    out.push((y * cam.width + x, mu));
                }
            }
        }
    }
    out
}

fn mean_grey(img: &Image, pixels: &[(usize, f64)]) -> f64 {
    pixels
        .iter()
        .map(|&(i, _)| img.pixels[i].iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0)
        .sum::<f64>()
        / pixels.len() as f64
}

/// The albedo of an isotropic BRDF at `cos θo = mu`, by the midpoint quadrature of
/// `gonio_brdf::validate::albedo` (independent of any sampler), linearly interpolated from 41
/// nodes.
fn albedo_curve(brdf: &dyn Brdf) -> impl Fn(f64) -> f64 + use<> {
    let nodes: Vec<f64> = (0..=40)
        .map(|k| {
            let mu = 0.15 + 0.85 * k as f64 / 40.0;
            let wo = DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            let a = gonio_brdf::validate::albedo(brdf, wo, 160);
            (a.x + a.y + a.z) / 3.0
        })
        .collect();
    move |mu: f64| {
        let x = ((mu - 0.15) / 0.85 * 40.0).clamp(0.0, 40.0);
        let i = (x as usize).min(39);
        let f = x - i as f64;
        nodes[i] * (1.0 - f) + nodes[i + 1] * f
    }
}

/// Render the furnace with `brdf` on the sphere and compare the mean over the sphere with the
/// mean of the BRDF's albedo at the same pixels; returns the relative difference.
fn furnace_error(brdf: Arc<dyn Brdf>, spp: u32) -> f64 {
    let mut s = scene(FURNACE);
    let albedo = albedo_curve(brdf.as_ref());
    s.materials[0].brdf = brdf;
    let (img, _) = render(&s, &opts(spp, 1, ColourMode::Tristimulus)).unwrap();
    let pixels = sphere_pixels(&s);
    assert!(pixels.len() > 500, "{}", pixels.len());
    let expect = pixels.iter().map(|&(_, mu)| albedo(mu)).sum::<f64>() / pixels.len() as f64;
    (mean_grey(&img, &pixels) / expect - 1.0).abs()
}

#[test]
fn white_furnace_lambert_renders_as_the_environment() {
    let s = scene(FURNACE);
    let (img, _) = render(&s, &opts(64, 7, ColourMode::Tristimulus)).unwrap();
    let pixels = sphere_pixels(&s);
    let mean = mean_grey(&img, &pixels);
    assert!((mean - 1.0).abs() < 0.01, "mean over the sphere {mean}");
    // The background is the sky itself.
    assert!((f64::from(img.get(0, 0)[1]) - 1.0).abs() < 1e-6);
}

#[test]
fn white_furnace_analytic_models_render_their_albedo() {
    let specs = [
        r#"{"model": "ggx", "alpha": 0.3, "index": 1.5, "diffuse": 0.6}"#,
        r#"{"model": "beckmann", "m": 0.2, "index": [0.2, 3.0]}"#,
        r#"{"model": "ward", "specular": 0.3, "alpha": 0.15, "diffuse": 0.6}"#,
        r#"{"model": "phong", "specular": 0.5, "exponent": 30, "diffuse": 0.4}"#,
    ];
    for json in specs {
        let spec = ModelSpec::from_json(json).unwrap();
        let err = furnace_error(Arc::new(spec.build().unwrap()), 64);
        assert!(err < 0.01, "{json}: furnace off by {:.2}%", 100.0 * err);
    }
}

#[test]
fn white_furnace_tabulated_brdfs_render_their_albedo() {
    let lambert = Model::Lambert(Lambert { albedo: Rgb::ONE });
    let res = Resolution::isotropic(32, 32, 32);
    let table = BrdfTable::from_brdf(&lambert, res, true, Provenance::default()).unwrap();
    let err = furnace_error(Arc::new(SampledTable::new(table)), 64);
    assert!(
        err < 0.01,
        "Lambert table: furnace off by {:.2}%",
        100.0 * err
    );
    let ward =
        ModelSpec::from_json(r#"{"model": "ward", "specular": 0.4, "alpha": 0.2, "diffuse": 0.5}"#)
            .unwrap();
    let res = Resolution::isotropic(64, 32, 48);
    let table =
        BrdfTable::from_brdf(&ward.build().unwrap(), res, true, Provenance::default()).unwrap();
    let err = furnace_error(Arc::new(SampledTable::new(table)), 64);
    assert!(err < 0.01, "Ward table: furnace off by {:.2}%", 100.0 * err);
}

#[test]
fn image_does_not_depend_on_the_thread_count() {
    let s = scene(&FURNACE.replace("lambert\", albedo = 1.0", "ggx\", alpha = 0.2, index = 1.5"));
    let one = RenderOptions {
        threads: Some(1),
        ..opts(8, 3, ColourMode::Tristimulus)
    };
    let two = RenderOptions {
        threads: Some(2),
        ..opts(8, 3, ColourMode::Tristimulus)
    };
    let (a, _) = render(&s, &one).unwrap();
    let (b, _) = render(&s, &two).unwrap();
    assert_eq!(a, b);
    let (c, _) = render(&s, &opts(8, 4, ColourMode::Tristimulus)).unwrap();
    assert_ne!(a, c, "another seed gives other noise");
}

/// An equirectangular sky: a gradient, a dim ground and a window 30° high in front, of
/// radiance `window`.
fn write_environment(dir: &Path, window: f64) -> std::path::PathBuf {
    let (w, h) = (128, 64);
    let mut img = Image::new(w, h);
    for j in 0..h {
        let theta = std::f64::consts::PI * (j as f64 + 0.5) / h as f64;
        for i in 0..w {
            let phi = std::f64::consts::TAU * (i as f64 + 0.5) / w as f64;
            let mut v = if theta < std::f64::consts::FRAC_PI_2 {
                [0.4 + 0.4 * theta.cos(), 0.5 + 0.4 * theta.cos(), 0.9]
            } else {
                [0.15, 0.12, 0.1]
            };
            // The window: around +z (phi = 90°), 60° from the zenith.
            if (phi - std::f64::consts::FRAC_PI_2).abs() < 0.25 && (theta - 1.05).abs() < 0.2 {
                v = [window, 0.95 * window, 0.9 * window];
            }
            img.pixels[j * w + i] = v.map(|c| c as f32);
        }
    }
    let path = dir.join("sky.exr");
    img.write(&path, gonio_render::Display::default()).unwrap();
    path
}

fn env_scene(env: &Path) -> Scene {
    let text = format!(
        r#"
[camera]
position = [0.0, 0.0, 4.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 30
width = 32
height = 32

[materials.m]
brdf = {{ model = "lambert", albedo = 0.5 }}

[[shapes]]
type = "sphere"
material = "m"

[[lights]]
type = "environment"
file = "{}"
"#,
        env.display()
    );
    scene(&text)
}

/// Relative RMS difference over the sphere's pixels.
fn rel_rmse(a: &Image, b: &Image, pixels: &[(usize, f64)]) -> f64 {
    let mut sq = 0.0;
    let mut norm = 0.0;
    for &(i, _) in pixels {
        for k in 0..3 {
            let (x, y) = (f64::from(a.pixels[i][k]), f64::from(b.pixels[i][k]));
            sq += (x - y) * (x - y);
            norm += y;
        }
    }
    let n = 3.0 * pixels.len() as f64;
    (sq / n).sqrt() / (norm / n)
}

/// The Ward model tabulated on 90 × 45 × 90 cells renders like the model itself. Two renders
/// of 1024 samples differ by their noise even for the same BRDF: each pixel's estimate has a
/// relative standard deviation s, so two independent renders differ by an rms of √2 s, and a
/// bias b of the table adds in quadrature, rms² = 2 s² + b². The noise floor is measured by
/// rendering the analytic model with a third seed, and what is left above it must be below 1%:
/// the table's linear interpolation of a lobe of width α = 0.15 rad, with θ_h nodes ≤ 1° (0.017
/// rad) across it, errs by about (h/α)²/8 ≈ 0.2% at the peak and less averaged over a pixel's
/// footprint, so 1% is five times the expected bias and a table misread (a transposed angle, a
/// wrong cell) would exceed it many times over.
#[test]
fn tabulated_ward_renders_like_the_analytic_ward() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = env_scene(&write_environment(dir.path(), 40.0));
    let ward = ModelSpec::from_json(
        r#"{"model": "ward", "specular": 0.3, "alpha": 0.15, "diffuse": 0.4}"#,
    )
    .unwrap();
    let model = ward.build().unwrap();
    let table = BrdfTable::from_brdf(
        &model,
        Resolution::isotropic(90, 45, 90),
        true,
        Provenance::default(),
    )
    .unwrap();
    s.materials[0].brdf = Arc::new(model);
    let (analytic, _) = render(&s, &opts(1024, 1, ColourMode::Tristimulus)).unwrap();
    let (analytic_again, _) = render(&s, &opts(1024, 3, ColourMode::Tristimulus)).unwrap();
    s.materials[0].brdf = Arc::new(SampledTable::new(table));
    let (tabulated, _) = render(&s, &opts(1024, 2, ColourMode::Tristimulus)).unwrap();
    let pixels = sphere_pixels(&s);
    let noise = rel_rmse(&analytic_again, &analytic, &pixels);
    let err = rel_rmse(&tabulated, &analytic, &pixels);
    let bias = (err * err - noise * noise).max(0.0).sqrt();
    eprintln!(
        "relative RMSE table vs analytic Ward {:.3}%, two analytic renders {:.3}%, bias {:.3}%",
        100.0 * err,
        100.0 * noise,
        100.0 * bias
    );
    assert!(bias < 0.01, "bias {:.2}%", 100.0 * bias);
}

/// A scene's surface file is read with its `channel` (a channel the file lacks is an error that
/// lists the file's channels), and a line profile is refused: a table needs an areal map.
#[test]
fn scene_surfaces_choose_a_channel_and_refuse_profiles() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../surface/tests/data");
    let dir = tempfile::tempdir().unwrap();
    let desc = |file: &str, channel: Option<&str>| gonio_render::surface::SurfaceDesc {
        file: Some(data.join(file)),
        channel: channel.map(str::to_string),
        epoxy_sq_nm: None,
        seed: None,
        points: None,
        method: None,
        index: None,
        azimuths: None,
    };
    let scene = Path::new("test.toml");
    let err = gonio_render::surface::table(&desc("opdx-3.opdx", None), dir.path(), scene, "p")
        .unwrap_err()
        .to_string();
    assert!(err.contains("line profile"), "{err}");
    let err = gonio_render::surface::table(
        &desc("nid-1.nid", Some("no such channel")),
        dir.path(),
        scene,
        "afm",
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("no such channel"), "{err}");
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn importance_sampling_of_the_epoxy_table_pays() {
        let dir = tempfile::tempdir().unwrap();
        // A window 5 times brighter than the sky: the lobe of the table, not the light, makes
        // the difference.
        let mut s = env_scene(&write_environment(dir.path(), 5.0));
        s.camera = gonio_render::camera::Camera::new(
            DVec3::new(0.0, 0.0, 4.0),
            DVec3::ZERO,
            DVec3::Y,
            30.0,
            24,
            24,
        )
        .unwrap();
        let desc = gonio_render::surface::SurfaceDesc {
            file: None,
            epoxy_sq_nm: Some(201.0),
            seed: Some(1),
            points: Some(128),
            method: None,
            index: None,
            azimuths: None,
            channel: None,
        };
        let t = std::time::Instant::now();
        let table =
            gonio_render::surface::table(&desc, dir.path(), Path::new("test.toml"), "epoxy")
                .unwrap();
        eprintln!("table {:.1} s", t.elapsed().as_secs_f64());
        s.materials[0].brdf = Arc::new(SampledTable::new(table));
        let (reference, _) = render(&s, &opts(1024, 99, ColourMode::Tristimulus)).unwrap();
        eprintln!("reference {:.1} s", t.elapsed().as_secs_f64());
        let pixels = sphere_pixels(&s);
        let rmse = |sampling: BrdfSampling| {
            let o = RenderOptions {
                sampling,
                ..opts(16, 5, ColourMode::Tristimulus)
            };
            let (img, _) = render(&s, &o).unwrap();
            rel_rmse(&img, &reference, &pixels)
        };
        let (alias, cosine) = (rmse(BrdfSampling::Importance), rmse(BrdfSampling::Cosine));
        eprintln!(
            "16 spp relative RMSE: alias {:.2}%, cosine {:.2}%, ratio {:.1}",
            100.0 * alias,
            100.0 * cosine,
            cosine / alias
        );
        assert!(cosine > 5.0 * alias, "alias {alias}, cosine {cosine}");
    }

    /// The denoiser on a picture with glossy and diffuse surfaces, shadows and a light's edge
    /// (`examples/plastic.toml` at 192 × 128 pixels): at 16 samples per pixel the denoised picture
    /// is much nearer a nearly converged one (256 samples, another seed) than the raw picture. The
    /// bound asks the denoising to do at least what four times the samples would do for the noise,
    /// halve the error (denoised < raw/2); the reference's own noise is 1/√16 = 25% of the raw
    /// picture's and enters both errors in quadrature. (On this scene, already smooth at 16
    /// samples, the filter's bias is most of what remains: measured 2.2% against the raw 5.4%. On
    /// smaller pictures the filter's 62-pixel reach meets edges everywhere and gains less: 3.4%
    /// against 6.0% at 96 × 64.)
    #[test]
    fn denoising_a_few_samples_comes_near_the_converged_picture() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plastic.toml");
        let text = std::fs::read_to_string(&path).unwrap();
        let mut desc = gonio_render::scene::SceneDesc::from_toml(&text, &path).unwrap();
        (desc.camera.width, desc.camera.height) = (192, 128);
        let s = Scene::build(&desc, &path).unwrap();
        let (reference, _) = render(&s, &opts(256, 7, ColourMode::Tristimulus)).unwrap();
        let few = opts(16, 1, ColourMode::Tristimulus);
        let (raw, stats) = render(&s, &few).unwrap();
        assert!(!stats.denoised, "denoising is not the default");
        let denoise = RenderOptions {
            denoise: Some(true),
            ..few
        };
        let (denoised, stats) = render(&s, &denoise).unwrap();
        assert!(stats.denoised);
        let (e_raw, e_denoised) = (
            relative_rmse(&raw, &reference),
            relative_rmse(&denoised, &reference),
        );
        eprintln!(
            "against 256 spp: raw 16 spp {:.2}%, denoised {:.2}%",
            100.0 * e_raw,
            100.0 * e_denoised
        );
        assert!(e_denoised < 0.5 * e_raw, "{e_denoised} vs raw {e_raw}");
    }
}

/// A smooth clear coat over a BRDF (`coat_index`): in the white furnace (a convex sphere under a
/// uniform sky of radiance 1, so every path sees the sky after one reflection) each pixel is the
/// coat's mirror reflectance F(θo) (Fresnel, n 1.5) plus the albedo of the BRDF beneath. The
/// mirror is split off at the first interaction (its reflection of the sky, weight F, has no
/// variance); the bound still allows for a mirror chosen with probability F and weighing 1
/// (its part of a sample 1 or 0, standard error sqrt(⟨F(1 − F)⟩ / N) over N samples): four of
/// those plus the BRDF's own 1% (as above), looser than the split needs. Over black the mirror
/// is alone; over a GGX lobe the light samples and the BRDF samples must still weigh to one, or
/// the lobe's part is off.
#[test]
fn white_furnace_coated_materials_render_mirror_plus_albedo() {
    let n = 1.5;
    let spp = 128;
    for json in [
        r#"{"model": "lambert", "albedo": 0.0}"#,
        r#"{"model": "lambert", "albedo": 0.7}"#,
        r#"{"model": "ggx", "alpha": 0.3, "index": 1.5, "diffuse": 0.5}"#,
    ] {
        let spec = ModelSpec::from_json(json).unwrap();
        let brdf: Arc<dyn Brdf> = Arc::new(spec.build().unwrap());
        let mut s = scene(FURNACE);
        let albedo = albedo_curve(brdf.as_ref());
        s.materials[0].brdf = brdf;
        s.materials[0] = s.materials[0].clone().with_coat(n);
        let (img, _) = render(&s, &opts(spp, 3, ColourMode::Tristimulus)).unwrap();
        let pixels = sphere_pixels(&s);
        let fresnel = |mu: f64| gonio_brdf::fresnel::dielectric(mu, n);
        let count = pixels.len() as f64;
        let expect = pixels
            .iter()
            .map(|&(_, mu)| fresnel(mu) + albedo(mu))
            .sum::<f64>()
            / count;
        let bernoulli = pixels
            .iter()
            .map(|&(_, mu)| fresnel(mu) * (1.0 - fresnel(mu)))
            .sum::<f64>()
            / count;
        let se = (bernoulli / (count * f64::from(spp))).sqrt();
        let got = mean_grey(&img, &pixels);
        let lobe = expect - pixels.iter().map(|&(_, mu)| fresnel(mu)).sum::<f64>() / count;
        assert!(
            (got - expect).abs() < 4.0 * se + 0.01 * lobe,
            "{json} under a coat: mean {got:.5}, expected {expect:.5} (standard error {se:.1e})"
        );
    }
}
