//! Orange peel measured and pictured agree in kind: on a series of mesoscale maps whose
//! long-wave slopes grow, the virtual DOI meter (ASTM E430, `gonio_instrument`, reading the ray
//! method's geometric-optics BRDF of the map, which is what the mirror-like coat under it shows a
//! meter) falls, and the reflected edge in a picture of the same map (`gonio_render`) wanders more.
//! Here, above both crates, since neither depends on the other.

/// A DOI reading and a render per map: seconds each.
mod slow {
    use gonio_instrument::meter::{MapMethod, read_height_map};
    use gonio_render::{ColourMode, RenderOptions, Scene, render};
    use gonio_surface::synth::GaussianSurface;

    /// The render's geometry (as in the render crate's mesoscale tests): a mirror-like panel at
    /// y = 0 seen straight down from 1 m, the edge of an emitter 3 m above it along z. The
    /// reflected edge wanders by W = 2 D h_x at the light.
    const HC: f64 = 1.0;
    const D: f64 = 3.0;

    /// The rms about its mean, over the image rows, of the reflected edge's wander W (m): each
    /// row's edge at the sum of its pixels' coverage (value over the mean of the ten leftmost,
    /// lit, pixels), turned into W = (HC + D) tx through the camera ray there.
    fn rms_wander(dir: &std::path::Path) -> f64 {
        let text = format!(
            "[camera]\nposition = [0.0, {HC}, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\n\
             fov_deg = 6.0\nwidth = 160\nheight = 200\n\n\
             [materials.mirror]\nbrdf = {{ model = \"ggx\", alpha = 5e-5, index = [0.2, 3.0] }}\n\
             mesoscale = {{ file = \"map.gsf\" }}\n\n\
             [[shapes]]\ntype = \"rectangle\"\nsize = [0.4, 0.4]\nrotate_deg = [-90.0, 0.0, 0.0]\n\
             material = \"mirror\"\n\n\
             [[lights]]\ntype = \"rectangle\"\nsize = [8.0, 8.0]\nrotate_deg = [90.0, 0.0, 0.0]\n\
             translate = [-4.0, {D}, 0.0]\nradiance = 1.0\n"
        );
        let scene = Scene::from_toml(&text, &dir.join("edge.toml")).unwrap();
        let opts = RenderOptions {
            spp: Some(64),
            seed: Some(1),
            colour: ColourMode::Tristimulus,
            ..RenderOptions::default()
        };
        let (image, _) = render(&scene, &opts).unwrap();
        let (w, h) = (scene.camera.width, scene.camera.height);
        let grey = |x: usize, y: usize| image.pixels[y * w + x].iter().sum::<f32>() as f64 / 3.0;
        let wander: Vec<f64> = (0..h)
            .map(|y| {
                let lit = (0..10).map(|x| grey(x, y)).sum::<f64>() / 10.0;
                let edge = (0..w).map(|x| grey(x, y) / lit).sum::<f64>();
                assert!(
                    edge > 12.0 && edge < w as f64 - 4.0,
                    "row {y}: edge at {edge}"
                );
                let d = scene.camera.ray(glam::DVec2::new(edge, y as f64 + 0.5)).dir;
                (HC + D) * d.x / -d.y
            })
            .collect();
        let mean = wander.iter().sum::<f64>() / h as f64;
        (wander.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / h as f64).sqrt()
    }

    /// Gaussian maps of correlation length T = 16 mm (512 × 512 points at 0.5 mm, periodic, 16
    /// correlation lengths per period so that the periodic autocorrelation is the Gaussian one)
    /// with Sq 5.5, 11, 22 and 33 µm, one seed: rms slope along x √2 Sq / T = 0.49 to 2.9 mrad,
    /// which spreads the mirror's reflection by twice that, across the 0.3° (5.2 mrad) offset of
    /// the DOI meter's side slits. DOI falls at every step and the rms wander grows; since the
    /// maps are one map scaled, the wander grows in proportion to Sq, within 10%: the
    /// edge-finding noise is about 0.1 pixel, 0.2 mm of W, against W = 2 D √2 Sq / T = 2.9 mm
    /// at 5.5 µm, and the reflected edge meets each row once as long as the mirror point's
    /// shift HC tx does not turn 2 D h_x faster than (HC + D) tx grows, 2 D HC h_xx < HC + D,
    /// h_xx < 0.67 /m, against the rms curvature √12 Sq / T² = 0.45 /m of the largest.
    #[test]
    fn doi_falls_and_the_reflection_wanders_more_as_long_wave_slopes_grow() {
        let sq_um = [5.5, 11.0, 22.0, 33.0];
        let mut rows = Vec::new();
        for &sq in &sq_um {
            let dir = tempfile::tempdir().unwrap();
            let map = GaussianSurface::square(sq * 1e-6, 16e-3, 512, 0.5e-3, 7)
                .generate()
                .unwrap();
            gonio_surface::io::write(&map, &dir.path().join("map.gsf")).unwrap();
            let doi = read_height_map(&map, MapMethod::Ray, 1.5)
                .unwrap()
                .report
                .doi;
            let wander = rms_wander(dir.path());
            eprintln!(
                "Sq {sq} µm: DOI {doi:.1}, rms wander {:.2} mm",
                wander * 1e3
            );
            rows.push((doi, wander));
        }
        for (k, pair) in rows.windows(2).enumerate() {
            let ((doi_a, w_a), (doi_b, w_b)) = (pair[0], pair[1]);
            assert!(
                doi_b < doi_a,
                "DOI rose from Sq {} to {} µm",
                sq_um[k],
                sq_um[k + 1]
            );
            let (ratio, want) = (w_b / w_a, sq_um[k + 1] / sq_um[k]);
            assert!(
                (ratio / want - 1.0).abs() < 0.1,
                "wander grew {ratio:.2}-fold from Sq {} to {} µm, not {want:.2}-fold",
                sq_um[k],
                sq_um[k + 1]
            );
        }
    }
}
