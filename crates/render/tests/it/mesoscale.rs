//! Mesoscale height maps (orange peel) in pictures: the reflection of a straight edge in a
//! mirror-like panel wanders by what the map's slopes predict, and shows no seam where the map
//! repeats.
//!
//! The set-up: a horizontal mirror-like rectangle (a GGX conductor of α = 5e-5, a reflection blur
//! of about 0.2 pixel) at y = 0, a camera `HC` = 1 m above it looking straight down (image columns
//! along +x, rows along +z), and a large emitting rectangle facing down at height `D` = 3 m
//! covering x < 0, whose edge x = 0 runs along z. A camera ray at `(tx, −1, tz)` meets the mirror
//! at `(HC tx, 0, HC tz)`; tilted by the map's slope `h_x` its reflection is turned by `2 atan h_x`
//! about z (a reflection about a plane turned by α about an axis in it is the reflection turned
//! by 2α), so it meets the emitter's plane at `x = HC tx + D (tx − tan 2α)/(1 + tx tan 2α)`. The
//! edge is seen where that is 0: `W := (HC + D) tx = D tan 2α − HC tan 2α tx² ≈ 2 D h_x`, the
//! wander of the reflected edge at the light, 2 × slope × distance. The small-angle error is
//! about `(2 h_x)²` relative plus `HC tx²/D`: below 1e-5 here.

/// A bad mesoscale description is refused, naming the scene (or the map's file) and the
/// problem; a synthetic map builds, wrapped.
#[test]
fn mesoscale_descriptions_are_checked() {
    let scene = |meso: &str| {
        gonio_render::Scene::from_toml(
            &format!(
                "[camera]\nposition = [0.0, 1.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\n\
                 fov_deg = 6.0\nwidth = 4\nheight = 4\n\n[materials.m]\n\
                 brdf = {{ model = \"lambert\", albedo = 0.5 }}\nmesoscale = {meso}\n\n\
                 [[shapes]]\ntype = \"rectangle\"\nmaterial = \"m\"\n"
            ),
            std::path::Path::new("peel.toml"),
        )
    };
    let err = |meso: &str| scene(meso).err().expect("refused").to_string();
    let both = err("{ file = \"x.x3p\", sq_um = 1.0, corr_mm = 2.0 }");
    assert!(
        both.contains("peel.toml") && both.contains("either `file`"),
        "{both}"
    );
    let missing = err("{ file = \"missing.x3p\" }");
    assert!(missing.contains("missing.x3p"), "{missing}");
    let half = err("{ sq_um = 1.0 }");
    assert!(half.contains("`sq_um` and `corr_mm`"), "{half}");
    let scale = err("{ sq_um = 1.0, corr_mm = 2.0, points = 32, scale = -2.0 }");
    assert!(scale.contains("scale"), "{scale}");
    let built = scene("{ sq_um = 1.0, corr_mm = 2.0, points = 32 }").unwrap();
    let meso = built.materials[0].mesoscale.as_ref().unwrap();
    assert_eq!(meso.repeat(), gonio_render::mesoscale::Repeat::Wrap);
    assert!(built.projections.get(0).is_some());
}

/// The renders take seconds each.
mod slow {
    use glam::DVec2;
    use gonio_render::{ColourMode, Image, Scene, render};
    use gonio_surface::HeightMap;
    use ndarray::Array2;
    use std::f64::consts::TAU;
    use std::path::Path;

    use crate::common::opts;

    /// Camera height and the emitter's height above the mirror, m.
    const HC: f64 = 1.0;
    const D: f64 = 3.0;
    /// Samples per pixel.
    const SPP: u32 = 64;

    /// The scene, its map the file `map` beside it with `repeat`.
    fn scene(dir: &Path, map: &HeightMap, repeat: &str) -> Scene {
        gonio_surface::io::write(map, &dir.join("map.gsf")).unwrap();
        let text = format!(
            "[camera]\nposition = [0.0, {HC}, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\n\
             fov_deg = 6.0\nwidth = 64\nheight = 200\n\n\
             [materials.mirror]\nbrdf = {{ model = \"ggx\", alpha = 5e-5, index = [0.2, 3.0] }}\n\
             mesoscale = {{ file = \"map.gsf\", repeat = \"{repeat}\" }}\n\n\
             [[shapes]]\ntype = \"rectangle\"\nsize = [0.4, 0.4]\nrotate_deg = [-90.0, 0.0, 0.0]\n\
             material = \"mirror\"\n\n\
             [[lights]]\ntype = \"rectangle\"\nsize = [8.0, 8.0]\nrotate_deg = [90.0, 0.0, 0.0]\n\
             translate = [-4.0, {D}, 0.0]\nradiance = 1.0\n"
        );
        Scene::from_toml(&text, &dir.join("edge.toml")).unwrap()
    }

    /// The direction `(tx, tz)` (per unit of descent) of the camera ray through film point
    /// `film`.
    fn slope_of_ray(scene: &Scene, film: DVec2) -> DVec2 {
        let d = scene.camera.ray(film).dir;
        DVec2::new(d.x, d.z) / -d.y
    }

    /// Per image row: the mirror point `(x_m, z_m)` where the reflected edge is seen and the
    /// wander `W = (HC + D) tx` at the light. The edge's film position in the row is the sum of
    /// the pixels' coverage (each pixel's value over the row's lit value, the mean of its ten
    /// leftmost pixels, which see the emitter whole): lit left of the edge, dark right of it.
    fn wander(scene: &Scene, image: &Image) -> Vec<(DVec2, f64)> {
        let (w, h) = (scene.camera.width, scene.camera.height);
        let grey = |x: usize, y: usize| {
            image.pixels[y * w + x]
                .iter()
                .map(|&c| f64::from(c))
                .sum::<f64>()
                / 3.0
        };
        (0..h)
            .map(|y| {
                let lit = (0..10).map(|x| grey(x, y)).sum::<f64>() / 10.0;
                assert!(lit > 0.5, "row {y} sees no light on its left: {lit}");
                let edge = (0..w).map(|x| grey(x, y) / lit).sum::<f64>();
                assert!(
                    edge > 12.0 && edge < w as f64 - 4.0,
                    "row {y}: the edge at {edge} px is out of the picture"
                );
                let t = slope_of_ray(scene, DVec2::new(edge, y as f64 + 0.5));
                (HC * t, (HC + D) * t.x)
            })
            .collect()
    }

    /// The tolerance on W in one row, m: the edge's film position is found to within 4
    /// standard errors of the edge pixel's coverage (at most 0.5/√SPP pixel: a Bernoulli
    /// fraction of SPP samples) plus 0.05 pixel for the reflection blur's own noise and the
    /// edge's curvature within the row; one pixel spans the film's angle per pixel in tx and
    /// (HC + D) times that in W. On top, 1% of the largest wander for the slope's interpolation
    /// (central differences and bilinear interpolation at 64 points per wavelength: 0.2% and
    /// 0.12%) and the small-angle approximation (1e-5).
    fn tolerance(scene: &Scene, largest: f64) -> f64 {
        let pixel = slope_of_ray(scene, DVec2::new(33.0, 100.0)).x
            - slope_of_ray(scene, DVec2::new(32.0, 100.0)).x;
        let px = 4.0 * 0.5 / f64::from(SPP).sqrt() + 0.05;
        px * pixel * (HC + D) + 0.01 * largest
    }

    /// A map of `nx × ny` points at spacing `d` with heights `f(x, y)` (map coordinates, m).
    fn map(nx: usize, ny: usize, d: f64, f: impl Fn(f64, f64) -> f64) -> HeightMap {
        let h = Array2::from_shape_fn((ny, nx), |(j, i)| f(i as f64 * d, j as f64 * d));
        HeightMap::new(h, d, d).unwrap()
    }

    /// Render `scene` and compare each row's wander with `predicted(x_m, z_m)` (m); returns the
    /// largest difference over the tolerance and the rms of the measured wander.
    fn compare(scene: &Scene, predicted: impl Fn(DVec2) -> f64) -> (f64, f64) {
        let (image, _) = render(scene, &opts(SPP, 1, ColourMode::Tristimulus)).unwrap();
        let rows = wander(scene, &image);
        let largest = rows
            .iter()
            .map(|&(m, _)| predicted(m).abs())
            .fold(0.0, f64::max);
        let tol = tolerance(scene, largest);
        let mut worst = 0.0f64;
        for (y, &(m, w)) in rows.iter().enumerate() {
            let want = predicted(m);
            let off = (w - want).abs() / tol;
            assert!(
                off <= 1.0,
                "row {y} (z = {:.2} mm): wander {:.3} mm, predicted 2 D h_x = {:.3} mm, \
                 tolerance {:.3} mm",
                m.y * 1e3,
                w * 1e3,
                want * 1e3,
                tol * 1e3
            );
            worst = worst.max(off);
        }
        let rms = (rows.iter().map(|r| r.1 * r.1).sum::<f64>() / rows.len() as f64).sqrt();
        (worst, rms)
    }

    /// A periodic sine map, `h = A sin(kx (x − cx)) sin(kz y)` (one wavelength of 160 mm along
    /// x, 20 mm along y, 64 points per 20 mm): slope amplitude along x `A kx` = 2 mrad, at the
    /// map's centre (world x = 0) where the edge is seen. Its y axis runs along world −z (the
    /// rectangle is turned −90° about x), so the camera sees about five wavelengths and five
    /// tile boundaries along the rows. The wander follows 2 D h_x row by row: amplitude 12 mm at
    /// the light, about 6 pixels in the picture.
    #[test]
    fn reflected_edge_wanders_by_twice_slope_times_distance() {
        let dir = tempfile::tempdir().unwrap();
        let d = 20e-3 / 64.0;
        let (nx, ny) = (512, 64);
        let (kx, kz) = (TAU / (nx as f64 * d), TAU / (ny as f64 * d));
        let (cx, cy) = (0.5 * (nx - 1) as f64 * d, 0.5 * (ny - 1) as f64 * d);
        let a = 2e-3 / kx;
        let sine = map(nx, ny, d, |x, y| a * (kx * (x - cx)).sin() * (kz * y).sin());
        let scene = scene(dir.path(), &sine, "auto");
        // World (x, z) on the mirror is map (x + cx, −z + cy).
        let slope_x = |m: DVec2| a * kx * (kx * m.x).cos() * (kz * (cy - m.y)).sin();
        let (worst, rms) = compare(&scene, |m| 2.0 * D * slope_x(m));
        // A sine's rms is its amplitude over √2: 12 mm / √2 = 8.5 mm, within the rows' sampling.
        assert!(
            (rms / (12e-3 / 2f64.sqrt()) - 1.0).abs() < 0.05,
            "rms wander {rms}"
        );
        eprintln!(
            "sine: worst row {worst:.2} of the tolerance, rms wander {:.2} mm",
            rms * 1e3
        );
    }

    /// A map that is not periodic (the sine of the first test over 160 points along y, 2.5
    /// wavelengths, and a tilt of 4 mrad along x and 1 mrad along y): levelled and mirrored,
    /// its reflected edge follows the mirrored map across both mirror lines in view, row by row,
    /// and the tilt is gone (it would move the whole edge by 2 D · 4 mrad = 24 mm).
    #[test]
    fn no_seam_where_a_measured_map_is_mirrored() {
        let dir = tempfile::tempdir().unwrap();
        let d = 20e-3 / 64.0;
        // 160 points along y: 49.7 mm between mirror lines.
        let (nx, ny) = (512, 160);
        let (kx, kz) = (TAU / (nx as f64 * d), TAU / (64.0 * d));
        let (cx, cy) = (0.5 * (nx - 1) as f64 * d, 0.5 * (ny - 1) as f64 * d);
        let a = 2e-3 / kx;
        let f = |x: f64, y: f64| a * (kx * (x - cx)).sin() * (kz * y).sin();
        let tilted = map(nx, ny, d, |x, y| f(x, y) + 4e-3 * x + 1e-3 * y);
        let plane = gonio_surface::ops::fit_plane(&tilted).unwrap();
        let scene = scene(dir.path(), &tilted, "auto");
        let span = (ny - 1) as f64 * d;
        // The mirrored coordinate along y (period 2 span), and the slope along x there: the
        // sine's less the fitted plane's (levelling).
        let fold = |y: f64| {
            let m = y.rem_euclid(2.0 * span);
            if m <= span { m } else { 2.0 * span - m }
        };
        let slope_x = |m: DVec2| {
            let y = fold(cy - m.y);
            let x = m.x + cx;
            a * kx * (kx * (x - cx)).cos() * (kz * y).sin() + 4e-3
                - (plane.height(x + 1e-6, y) - plane.height(x - 1e-6, y)) / 2e-6
        };
        // The map's edges y = 0 and y = span lie at world z = cy = 24.8 mm and z = cy − span
        // = −24.8 mm: both mirror lines are in the view (z within ±52 mm).
        assert!(cy < 50e-3 && (cy - span).abs() < 50e-3);
        let (worst, rms) = compare(&scene, |m| 2.0 * D * slope_x(m));
        eprintln!(
            "mirrored: worst row {worst:.2} of the tolerance, rms wander {:.2} mm",
            rms * 1e3
        );
    }
}
