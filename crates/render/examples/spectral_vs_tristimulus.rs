//! Spectral rendering against the tristimulus shortcut on one scene: render it in both colour
//! modes, and compare the displayed pictures pixel by pixel with CIEDE2000 (what the shortcut
//! costs; results in `docs/color.md`, "Spectral rendering versus the tristimulus shortcut").
//!
//! ```text
//! cargo run --release -p gonio-render --features studies --example spectral_vs_tristimulus -- \
//!     examples/metallic.toml --spp 1024 --width 96 --out target/spectral-vs-tri \
//!     [--seed S] [--max-bounces N] [--grey-environment] [--json]
//! ```
//!
//! Each mode is rendered twice, with seeds S and S + 1 (`--spp` samples each). With the same seed
//! both modes trace the same directions, so the difference `d = spectral − tristimulus` of one
//! seed holds the systematic difference plus the spectral mode's wavelength noise only. The
//! comparison is between `T`, the mean of the two tristimulus renders, and `T + (d_S + d_S+1)/2`
//! (= the mean of the two spectral renders). As a noise reference of exactly the same noise and
//! no systematic part, the program also compares `T` with `T + (d_S − d_S+1)/2`: where the first
//! exceeds the second, the modes differ beyond noise.
//!
//! `--grey-environment` replaces every environment map by its luminance (pixel by pixel), so that
//! all light has the illuminant's spectrum (D65) in both modes: the modes then agree on paths
//! with one surface interaction, and what remains comes from light reflected by two or more
//! coloured surfaces.
//!
//! The colour compared is the colour shown: each linear sRGB pixel times the scene's exposure,
//! through its tone curve (what `gonio render -o x.png` writes, before 8-bit rounding), taken as
//! display-referred linear sRGB, turned into XYZ (IEC 61966-2-1) and CIELAB relative to the
//! display white (D65). The program prints the median, 95th percentile and maximum ΔE00 over
//! the image and per surface (the material and shape kind the pixel's centre ray meets first)
//! and the pixel of the maximum. It writes `tristimulus.png`, `spectral.png` (the means of the
//! two seeds) and `delta_e00.png` (ΔE00 0 → black, 2 or more → white) into `--out`, with `delta_e00.csv`
//! (one line per pixel: `x_px, y_px, surface, cos_view` (cosine between the view direction and
//! the shading normal at the centre hit), `delta_e00`, `noise_reference_delta_e00`).

use glam::DVec2;
use gonio_render::difference::{SeededComparison, Spread, heat_map, linear_display};
use gonio_render::geometry::Shape;
use gonio_render::light::luminance;
use gonio_render::scene::{LightDesc, PrimKind, SceneDesc};
use gonio_render::{ColourMode, Display, Image, RenderOptions, Scene, render};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

struct Args {
    scene: PathBuf,
    spp: u32,
    seed: u32,
    width: Option<usize>,
    max_bounces: Option<u32>,
    grey_environment: bool,
    out: PathBuf,
    json: bool,
}

fn parse_args() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let mut args = Args {
        scene: PathBuf::new(),
        spp: 256,
        seed: 0,
        width: None,
        max_bounces: None,
        grey_environment: false,
        out: PathBuf::from("spectral-vs-tristimulus"),
        json: false,
    };
    let value = |it: &mut dyn Iterator<Item = String>, flag: &str| {
        it.next().ok_or(format!("{flag} needs a value"))
    };
    while let Some(a) = it.next() {
        match a.as_str() {
            "--spp" => {
                args.spp = value(&mut it, "--spp")?
                    .parse()
                    .map_err(|e| format!("--spp: {e}"))?
            }
            "--seed" => {
                args.seed = value(&mut it, "--seed")?
                    .parse()
                    .map_err(|e| format!("--seed: {e}"))?
            }
            "--width" => {
                args.width = Some(
                    value(&mut it, "--width")?
                        .parse()
                        .map_err(|e| format!("--width (pixels): {e}"))?,
                )
            }
            "--max-bounces" => {
                args.max_bounces = Some(
                    value(&mut it, "--max-bounces")?
                        .parse()
                        .map_err(|e| format!("--max-bounces: {e}"))?,
                )
            }
            "--out" => args.out = PathBuf::from(value(&mut it, "--out")?),
            "--json" => args.json = true,
            "--grey-environment" => args.grey_environment = true,
            s if s.starts_with('-') => return Err(format!("unknown flag {s}")),
            s => args.scene = PathBuf::from(s),
        }
    }
    if args.scene.as_os_str().is_empty() {
        return Err(
            "usage: spectral_vs_tristimulus SCENE.toml [--spp N] [--seed S] [--width PX] \
             [--max-bounces N] [--grey-environment] [--out DIR] [--json]"
                .into(),
        );
    }
    Ok(args)
}

/// The scene, its camera resized to `width` pixels (height in proportion) when given; with
/// `grey_environment`, every environment map replaced by its luminance (a grey copy written
/// into `out`), so that the environment's light has the illuminant's spectrum in both modes.
fn load(
    path: &Path,
    width: Option<usize>,
    grey_environment: bool,
    out: &Path,
) -> Result<Scene, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut desc: SceneDesc =
        toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    if let Some(w) = width {
        let c = &mut desc.camera;
        c.height = (c.height * w).div_ceil(c.width).max(1);
        c.width = w;
    }
    if grey_environment {
        let dir = path.parent().unwrap_or(Path::new("."));
        for (k, light) in desc.lights.iter_mut().enumerate() {
            if let LightDesc::Environment { file, .. } = light {
                let mut img = Image::read(&dir.join(&*file)).map_err(|e| e.to_string())?;
                for p in &mut img.pixels {
                    *p = [luminance(*p) as f32; 3];
                }
                let grey = std::path::absolute(out.join(format!("grey_environment_{k}.hdr")))
                    .map_err(|e| e.to_string())?;
                img.write(&grey, Display::default())
                    .map_err(|e| e.to_string())?;
                *file = grey;
            }
        }
    }
    Scene::build(&desc, path).map_err(|e| e.to_string())
}

/// What the centre ray of each pixel meets first: "MATERIAL SHAPE", "light" or "background",
/// and the cosine between the view direction and the shading normal there (NaN when nothing).
fn surfaces(scene: &Scene) -> Vec<(String, f64)> {
    let cam = &scene.camera;
    (0..cam.width * cam.height)
        .map(|i| {
            let ray = cam.ray(DVec2::new(
                (i % cam.width) as f64 + 0.5,
                (i / cam.width) as f64 + 0.5,
            ));
            let Some(hit) = scene.accel.intersect(&ray, 0.0, f64::INFINITY) else {
                return ("background".into(), f64::NAN);
            };
            let cos_view = hit.ns.dot(ray.dir).abs();
            match scene.prims[hit.prim] {
                PrimKind::Emitter(_) => ("light".into(), cos_view),
                PrimKind::Surface(m) => {
                    let kind = match scene.accel.shapes()[hit.prim] {
                        Shape::Sphere { .. } => "sphere",
                        Shape::Planar { .. } => "plane",
                        Shape::Triangle { .. } => "mesh",
                    };
                    (format!("{} {kind}", scene.materials[m].name), cos_view)
                }
            }
        })
        .collect()
}

/// One line per pixel: `x_px,y_px,surface,cos_view,delta_e00,noise_reference_delta_e00`.
fn csv(width: usize, labels: &[(String, f64)], de: &[f64], noise: &[f64]) -> String {
    let mut out = String::from("x_px,y_px,surface,cos_view,delta_e00,noise_reference_delta_e00\n");
    for (k, ((label, cos_view), (d, n))) in labels.iter().zip(de.iter().zip(noise)).enumerate() {
        out += &format!(
            "{},{},{label},{cos_view:.4},{d:.4},{n:.4}\n",
            k % width,
            k / width
        );
    }
    out
}

fn run() -> Result<(), String> {
    let args = parse_args()?;
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    let scene = load(&args.scene, args.width, args.grey_environment, &args.out)?;
    let display = scene.display;
    let opts = |colour, seed| RenderOptions {
        spp: Some(args.spp),
        seed: Some(seed),
        max_bounces: args.max_bounces,
        colour,
        ..RenderOptions::default()
    };
    let go = |o: RenderOptions| render(&scene, &o).map_err(|e| e.to_string());
    let seed_b = args.seed.wrapping_add(1);
    let (tri_a, tri_stats) = go(opts(ColourMode::Tristimulus, args.seed))?;
    let (spec_a, spec_stats) = go(opts(ColourMode::Spectral, args.seed))?;
    let (tri_b, _) = go(opts(ColourMode::Tristimulus, seed_b))?;
    let (spec_b, _) = go(opts(ColourMode::Spectral, seed_b))?;
    let SeededComparison {
        first: tri,
        second: spec,
        delta_e00: de,
        noise_reference: noise,
    } = SeededComparison::new([&tri_a, &tri_b], [&spec_a, &spec_b], display);
    let labels = surfaces(&scene);
    let mut by_surface: BTreeMap<&str, (Vec<f64>, Vec<f64>)> = BTreeMap::new();
    for (((l, _), d), n) in labels.iter().zip(&de).zip(&noise) {
        let e = by_surface.entry(l.as_str()).or_default();
        e.0.push(*d);
        e.1.push(*n);
    }
    let (imax, _) = de
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .expect("an image has pixels");
    let (w, h) = (tri.width, tri.height);
    let write = |img: &Image, name: &str, d: Display| {
        img.write(&args.out.join(name), d)
            .map_err(|e| e.to_string())
    };
    write(&tri, "tristimulus.png", display)?;
    write(&spec, "spectral.png", display)?;
    write(&heat_map(&de, w, h, 2.0), "delta_e00.png", linear_display())?;
    let csv_path = args.out.join("delta_e00.csv");
    std::fs::write(&csv_path, csv(w, &labels, &de, &noise))
        .map_err(|e| format!("{}: {e}", csv_path.display()))?;

    let stats = |v: &[f64]| {
        let s = Spread::of(v).expect("an image has pixels");
        [s.median, s.p95, s.max]
    };
    let [med, p95, max] = stats(&de);
    let [n_med, n_p95, n_max] = stats(&noise);
    if args.json {
        let surfaces: serde_json::Map<String, serde_json::Value> = by_surface
            .iter()
            .map(|(k, (d, n))| {
                let [a, b, c] = stats(d);
                let [x, y, z] = stats(n);
                (
                    k.to_string(),
                    serde_json::json!({
                        "pixels": d.len(),
                        "delta_e00": {"median": a, "p95": b, "max": c},
                        "noise_reference_delta_e00": {"median": x, "p95": y, "max": z},
                    }),
                )
            })
            .collect();
        let out = serde_json::json!({
            "scene": args.scene,
            "width_px": w,
            "height_px": h,
            "spp_per_render": args.spp,
            "seeds": [args.seed, seed_b],
            "max_bounces": args.max_bounces,
            "grey_environment": args.grey_environment,
            "delta_e00": {"median": med, "p95": p95, "max": max},
            "noise_reference_delta_e00": {"median": n_med, "p95": n_p95, "max": n_max},
            "max_pixel": {"x": imax % w, "y": imax / w, "surface": labels[imax].0},
            "surfaces": surfaces,
            "tristimulus_rays_per_second": tri_stats.rays_per_second(),
            "spectral_rays_per_second": spec_stats.rays_per_second(),
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?
        );
    } else {
        println!(
            "{}: {w} × {h} px, {} spp per render, seeds {} and {seed_b}",
            args.scene.display(),
            args.spp,
            args.seed
        );
        println!(
            "spectral vs tristimulus: ΔE00 median {med:.2}, 95th pct {p95:.2}, max {max:.2} at \
             pixel ({}, {}) on {}",
            imax % w,
            imax / w,
            labels[imax].0
        );
        println!(
            "noise reference (same noise, no systematic part): ΔE00 median {n_med:.2}, \
             95th pct {n_p95:.2}, max {n_max:.2}"
        );
        for (k, (d, n)) in &by_surface {
            let [a, b, c] = stats(d);
            let [x, y, _] = stats(n);
            println!(
                "  {k:<16} {:>6} px: ΔE00 median {a:.2}, 95th {b:.2}, max {c:.2}   \
                 (noise median {x:.2}, 95th {y:.2})",
                d.len()
            );
        }
        println!(
            "rays/s: tristimulus {:.3e}, spectral {:.3e}; pictures in {}",
            tri_stats.rays_per_second(),
            spec_stats.rays_per_second(),
            args.out.display()
        );
    }
    Ok(())
}

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}
