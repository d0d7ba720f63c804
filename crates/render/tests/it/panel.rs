//! The lab's panel pictures (`gonio_render::panel::live`): cancellation of the table and of
//! the render, the preview against the converged picture, the same picture for any number of
//! threads, and each lighting.

use glam::DVec2;
use gonio_coating::system::Coating;
use gonio_io::Cancel;
use gonio_render::panel::Lighting;
use gonio_render::panel::live::{self, LiveTable, Quality, live_table, panel_pixels, picture};
use gonio_render::{ColourMode, RenderError, RenderOptions, render_estimate};
use std::f64::consts::PI;
use std::path::Path;
use std::time::{Duration, Instant};

/// The coating of `examples/coatings/NAME.toml` at `quality`'s bands.
fn coating(name: &str, quality: Quality) -> Coating {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/coatings")
        .join(format!("{name}.toml"));
    gonio_coating::description::read(&path, &quality.bands()).unwrap()
}

/// Every lighting and quality is found by its name, and says what it is in one line.
#[test]
fn lightings_and_qualities_go_by_their_names() {
    for l in Lighting::ALL {
        assert_eq!(Lighting::from_name(l.name()), Some(l));
        assert!(!l.description().is_empty() && !l.description().contains('\n'));
    }
    for q in Quality::ALL {
        assert_eq!(Quality::from_name(q.name()), Some(q));
    }
    assert_eq!(Lighting::from_name("disco"), None);
}

/// A flag raised before the computation starts stops it at once, with the table's error turned
/// into the render's; the same table not cancelled is the same bit for bit as
/// `Coating::table`'s (the cancellable loop is the only loop).
#[test]
fn a_raised_flag_stops_before_any_work_and_an_unraised_one_changes_nothing() {
    let q = Quality::Preview;
    let silver = coating("silver_metallic", q);
    let raised = Cancel::new();
    raised.cancel();
    assert!(matches!(
        live_table(&silver, q, &raised),
        Err(RenderError::Cancelled)
    ));
    let res = q.resolution(&silver);
    let provenance = gonio_brdf::table::Provenance::default();
    let plain = silver
        .table(res, &q.bands(), q.walks(), provenance.clone())
        .unwrap();
    let until = silver
        .table_until(res, &q.bands(), q.walks(), provenance, &Cancel::new())
        .unwrap();
    assert!(
        bits(plain.values()) == bits(until.values()),
        "the tables differ"
    );
    let table = live_table(&silver, q, &Cancel::new()).unwrap();
    assert!(matches!(
        picture(&table, Lighting::Studio, q, &raised),
        Err(RenderError::Cancelled)
    ));
}

/// The bits of a table's values (cells below the horizon hold NaN, which `==` never matches).
fn bits(values: &[f32]) -> Vec<u32> {
    values.iter().map(|v| v.to_bits()).collect()
}

/// Mean luminance of `image` over `pixels`.
fn mean_luminance(image: &gonio_render::Image, pixels: &[usize]) -> f64 {
    pixels
        .iter()
        .map(|&i| gonio_render::light::luminance(image.pixels[i]))
        .sum::<f64>()
        / pixels.len() as f64
}

/// The luminance of a table's directional albedo at incidence `theta_deg` (light in the x-z
/// plane), by the table's own half-vector quadrature.
fn albedo_luminance(table: &LiveTable, theta_deg: f64) -> f64 {
    let t = table.table.table();
    let values = t.albedo(theta_deg.to_radians(), 0.0);
    let rgb = t.to_rgb(&values);
    gonio_render::light::luminance(rgb.as_vec3().to_array())
}

mod slow {
    use super::*;

    /// Raise the flag `after` into `work` on another thread; returns what `work` returned and
    /// how long after the flag it did.
    fn cancel_after<T: Send>(
        after: Duration,
        work: impl FnOnce(&Cancel) -> T + Send,
    ) -> (T, Duration) {
        let cancel = Cancel::new();
        // The work runs on a thread pool of its own: on the global pool, the jobs of the other
        // tests of this binary, running at the same time, are queued with its own, and the flag
        // is seen only when its jobs get a thread (this test took 2.96 s and 3.88 s to stop
        // in full test runs at load 7–9, and 12–45 ms alone at load 4).
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        std::thread::scope(|s| {
            let handle = s.spawn(|| {
                let out = pool.install(|| work(&cancel));
                (out, Instant::now())
            });
            std::thread::sleep(after);
            let raised = Instant::now();
            cancel.cancel();
            let (out, done) = handle.join().unwrap();
            (out, done.saturating_duration_since(raised))
        })
    }

    /// A table and a converged picture stop within 2 s of the flag: the silver's table at the
    /// converged nodes with 128 walks per cell (four times the converged table's walks, about
    /// 11 s of CPU time uncancelled), the converged table (2.7 s) and the converged picture
    /// (about 17 s; docs/render.md). 2 s is generous: a cell's walks take under a millisecond,
    /// a 16 × 16 tile at 16 samples per pixel about 10 ms of one core, and the machine is
    /// shared, so a thread may wait for a core.
    #[test]
    fn cancelled_table_and_render_stop_promptly() {
        let q = Quality::Converged;
        let silver = coating("silver_metallic", q);
        let (out, latency) = cancel_after(Duration::from_millis(300), |c| {
            silver.table_until(
                q.resolution(&silver),
                &q.bands(),
                128,
                gonio_brdf::table::Provenance::default(),
                c,
            )
        });
        eprintln!("table (128 walks per cell): stopped {latency:?} after the flag");
        assert!(matches!(out, Err(gonio_coating::CoatingError::Cancelled)));
        assert!(latency < Duration::from_secs(2), "{latency:?}");

        let (out, latency) =
            cancel_after(Duration::from_millis(300), |c| live_table(&silver, q, c));
        eprintln!("live table (converged): stopped {latency:?} after the flag");
        assert!(matches!(out, Err(RenderError::Cancelled)));
        assert!(latency < Duration::from_secs(2), "{latency:?}");

        let preview = live_table(&silver, Quality::Preview, &Cancel::new()).unwrap();
        for delay in [300, 3000] {
            let (out, latency) = cancel_after(Duration::from_millis(delay), |c| {
                picture(&preview, Lighting::Studio, q, c)
            });
            eprintln!("converged picture, flag at {delay} ms: stopped {latency:?} after it");
            assert!(matches!(out, Err(RenderError::Cancelled)));
            assert!(latency < Duration::from_secs(2), "{latency:?}");
        }
    }

    /// The same table and picture, bit for bit, with 1 and 2 threads (the table's cells and
    /// the picture's pixels each depend only on their index and seed).
    #[test]
    fn same_picture_for_one_and_two_threads() {
        let q = Quality::Preview;
        let silver = coating("silver_metallic", q);
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| {
                    let table = live_table(&silver, q, &Cancel::new()).unwrap();
                    let shown = picture(&table, Lighting::Booth, q, &Cancel::new()).unwrap();
                    (bits(table.table.table().values()), shown.png, shown.image)
                })
        };
        let (one, two) = (run(1), run(2));
        assert!(one.0 == two.0, "the tables differ");
        assert!(one.2 == two.2, "the pictures differ");
        assert_eq!(one.1, two.1);
    }

    /// The raw estimate of `table`'s panel at `quality` with `spp` samples per pixel: the mean
    /// luminance over the panel pixels and its standard error (from each pixel's variance).
    fn raw_panel(table: &LiveTable, lighting: Lighting, quality: Quality, spp: u32) -> (f64, f64) {
        let scene = live::scene(table, lighting, quality).unwrap();
        let mask = panel_pixels(&scene);
        let opts = RenderOptions {
            spp: Some(spp),
            colour: ColourMode::Spectral,
            ..RenderOptions::default()
        };
        let estimate = render_estimate(&scene, &opts).unwrap();
        let n = mask.len() as f64;
        let var: f64 = mask.iter().map(|&i| f64::from(estimate.variance[i])).sum();
        (mean_luminance(&estimate.image, &mask), var.sqrt() / n)
    }

    /// The preview is the converged picture, coarser: the same framing (a preview pixel's ray
    /// is the converged picture's ray at four times its film coordinates), and the same mean
    /// luminance over the panel. The raw estimates (unbiased at any samples) differ by the
    /// tables alone, so their ratio may depart from 1 by what the tables' directional albedos
    /// do (their largest relative difference over incidences 0-60°, where the panel is seen
    /// and lit; each table's own half-vector quadrature), plus three standard errors of the
    /// ratio. The denoised preview departs from its raw estimate by the filter's bias where a
    /// sample is rare: within 6% (measured when a smooth coat's mirror was chosen with
    /// probability F ≈ 0.05: 4.8% for the red in the studio at 16 samples per pixel, 21% at 4,
    /// which is why the preview takes 16; since the mirror is split off at the first
    /// interaction the bound is looser than it needs to be).
    #[test]
    fn preview_is_the_converged_picture_coarser() {
        for name in ["silver_metallic", "red_solid"] {
            let p = live_table(
                &coating(name, Quality::Preview),
                Quality::Preview,
                &Cancel::new(),
            )
            .unwrap();
            let c = live_table(
                &coating(name, Quality::Converged),
                Quality::Converged,
                &Cancel::new(),
            )
            .unwrap();
            let (sp, sc) = (
                live::scene(&p, Lighting::Studio, Quality::Preview).unwrap(),
                live::scene(&c, Lighting::Studio, Quality::Converged).unwrap(),
            );
            for (x, y) in [(0.0, 0.0), (96.0, 64.0), (191.5, 127.5), (30.25, 100.0)] {
                let a = sp.camera.ray(DVec2::new(x, y));
                let b = sc.camera.ray(DVec2::new(4.0 * x, 4.0 * y));
                assert!((a.origin - b.origin).length() < 1e-12);
                assert!((a.dir - b.dir).length() < 1e-12, "{x} {y}");
            }
            let table_bound = [0.0, 15.0, 30.0, 45.0, 60.0]
                .iter()
                .map(|&t| (albedo_luminance(&p, t) / albedo_luminance(&c, t) - 1.0).abs())
                .fold(0.0, f64::max);
            for lighting in Lighting::ALL {
                let (lp, ep) = raw_panel(&p, lighting, Quality::Preview, 16);
                let (lc, ec) = raw_panel(&c, lighting, Quality::Converged, 4);
                let ratio = lp / lc;
                let se = ratio * ((ep / lp).powi(2) + (ec / lc).powi(2)).sqrt();
                let bound = table_bound + 3.0 * se;
                let shown = picture(&p, lighting, Quality::Preview, &Cancel::new()).unwrap();
                let mask = panel_pixels(&sp);
                let denoised = mean_luminance(&shown.image, &mask) / lp;
                eprintln!(
                    "{name} {lighting}: raw preview/converged {ratio:.4} (bound 1 ± {bound:.4}: \
                     tables {table_bound:.4}, 3 s.e. {:.4}); denoised/raw preview {denoised:.4}",
                    3.0 * se
                );
                assert!((ratio - 1.0).abs() <= bound, "{name} {lighting}: {ratio}");
                assert!(
                    (denoised - 1.0).abs() <= 0.06,
                    "{name} {lighting}: {denoised}"
                );
            }
        }
    }

    /// Each lighting lights the panel as its map says: the raw mean luminance of the red's
    /// panel (an exact table) within a factor 2 of `A(40°) E / π + F L̄`, the body's
    /// directional albedo at the camera's 40° under the irradiance `E` an upward-facing surface
    /// receives from the map (midpoint quadrature of the map, independent of the renderer)
    /// plus the coat's mirror (F 0.04, at normal incidence for n 1.5) of the mean radiance L̄
    /// of the map's upper half; the panel curves and tilts, so the factor 2. And no pixel of
    /// the picture is NaN, and fewer than a tenth of the panel's pixels clip to white.
    #[test]
    fn each_lighting_lights_the_panel_plausibly() {
        let q = Quality::Preview;
        let red = live_table(&coating("red_solid", q), q, &Cancel::new()).unwrap();
        for lighting in Lighting::ALL {
            let (n_t, n_p) = (180, 360);
            let (mut e, mut l_up, mut w_up) = (0.0, 0.0, 0.0);
            for i in 0..n_t / 2 {
                let t = (i as f64 + 0.5) * 180.0 / n_t as f64;
                let (s, c) = t.to_radians().sin_cos();
                for j in 0..n_p {
                    let l = lighting.radiance(t, (j as f64 + 0.5) * 360.0 / n_p as f64);
                    let d_omega = s * (PI / n_t as f64) * (2.0 * PI / n_p as f64);
                    e += l * c * d_omega;
                    l_up += l * d_omega;
                    w_up += d_omega;
                }
            }
            let expected = albedo_luminance(&red, 40.0) * e / PI + 0.04 * l_up / w_up;
            let (mean, _) = raw_panel(&red, lighting, q, 16);
            let shown = picture(&red, lighting, q, &Cancel::new()).unwrap();
            let scene = live::scene(&red, lighting, q).unwrap();
            let mask = panel_pixels(&scene);
            let srgb = shown.image.to_srgb8(shown.display);
            let clipped = mask
                .iter()
                .filter(|&&i| srgb[3 * i..3 * i + 3].iter().all(|&v| v == 255))
                .count();
            eprintln!(
                "{lighting}: panel {mean:.4}, expected {expected:.4} (E {e:.3}), ratio {:.3}; \
                 {clipped} of {} panel pixels clipped",
                mean / expected,
                mask.len()
            );
            assert!(shown.image.pixels.iter().flatten().all(|v| v.is_finite()));
            assert!((0.5..2.0).contains(&(mean / expected)), "{lighting}");
            assert!(clipped * 10 < mask.len(), "{lighting}");
            std::fs::write(
                std::env::temp_dir().join(format!("gonio-panel-{lighting}.png")),
                &shown.png,
            )
            .unwrap();
        }
    }
}
