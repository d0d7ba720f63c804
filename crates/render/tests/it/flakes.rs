//! Discrete flakes ([`gonio_render::flakes`]): a rendered patch of many flakes averages to the
//! coating's glint; one flake larger than the picture is a tilted mirror under the coat; the
//! flakes' size follows the description; the picture does not depend on the thread count.

use crate::common::{opts, scene};
use glam::DVec3;
use gonio_brdf::fresnel::dielectric;
use gonio_coating::description::parse;
use gonio_coating::glint::Glint;
use gonio_render::flakes::FlakeField;
use gonio_render::{ColourMode, RenderOptions, render};
use std::collections::HashSet;

const BANDS: [f64; 3] = [450.0, 550.0, 650.0];

/// The glint of a silver metallic with a smooth top, flakes `diameter_um` across.
pub fn glint(diameter_um: f64) -> Glint {
    let coating = parse(
        &format!(
            "[coat]\nindex = 1.5\nthickness_um = 40\n\
             [flakes]\nkind = \"aluminium\"\ncoverage = 0.6\ntilt_deg = 12\n\
             diameter_um = {diameter_um}\n[base]\nkind = \"diffuse\"\nreflectance = 0.25\n"
        ),
        &BANDS,
    )
    .unwrap();
    Glint::new(&coating, &BANDS).unwrap().unwrap()
}

pub fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// A square patch (normal +z, shading tangent +x) of a black material seen from `wo` at 10 m
/// over `field` metres, `px` pixels a side, under a lamp of radiance 1 and angular radius
/// `lamp_deg` in direction `wi` 100 m away, nothing else lit; the material is then given `flakes`.
pub fn patch(wo: DVec3, wi: DVec3, field: f64, px: usize, lamp_deg: f64) -> gonio_render::Scene {
    let cam = wo * 10.0;
    let lamp = wi * 100.0;
    let fov = 2.0 * (field / 2.0 / 10.0).atan().to_degrees();
    let up = if wo.z > 0.999 {
        "[0.0, 1.0, 0.0]"
    } else {
        "[0.0, 0.0, 1.0]"
    };
    scene(&format!(
        "[camera]\nposition = [{}, {}, {}]\nlook_at = [0.0, 0.0, 0.0]\nup = {up}\n\
         fov_deg = {fov}\nwidth = {px}\nheight = {px}\n\
         [materials.black]\nbrdf = {{ model = \"lambert\", albedo = 0.0 }}\n\
         [[shapes]]\ntype = \"rectangle\"\nsize = [1.0, 1.0]\nmaterial = \"black\"\n\
         [[lights]]\ntype = \"sphere\"\ncenter = [{}, {}, {}]\nradius = {}\nradiance = 1.0\n",
        cam.x,
        cam.y,
        cam.z,
        lamp.x,
        lamp.y,
        lamp.z,
        100.0 * lamp_deg.to_radians().sin(),
    ))
}

pub fn with_flakes(mut s: gonio_render::Scene, field: FlakeField) -> gonio_render::Scene {
    let m = s.materials[0].clone();
    s.materials[0] = m.with_flakes(field);
    s
}

/// Averaged over a patch of some 10⁶ flakes, the rendered radiance under a lamp of 3° radius is
/// the glint integrated over the lamp, `∫ g(wo, wi) cos θi dωi` (quadrature, 48 × 48 nodes), at
/// three geometries (the sparkle camera's 0°/15°, off-specular 30°/45°, specular 60°/60°).
/// Pixels of 67 µm hold some ten flakes of 20 µm, so pixels are nearly independent: the
/// tolerance is four standard errors of the image's mean, from the pixels' spread.
#[test]
fn a_patch_of_flakes_averages_to_the_glint() {
    let g = glint(20.0);
    let lamp = 3.0f64.to_radians();
    for (to, ti) in [(0.0, 15.0), (30.0, 45.0), (60.0, 60.0)] {
        let (wo, wi0) = (dir(to, 0.0), dir(ti, 180.0));
        let px = 300;
        let field = FlakeField::new(g.clone(), 7).unwrap();
        let s = with_flakes(patch(wo, wi0, 0.02, px, 3.0), field.clone());
        let (image, _) = render(&s, &opts(8, 1, ColourMode::Tristimulus)).unwrap();
        // Expected: the glint over the lamp's cone.
        let t = wi0.cross(DVec3::Y).normalize();
        let b = wi0.cross(t);
        let n = 48;
        let mut bands = [0.0; 3];
        let mut v = [0.0; 3];
        for i in 0..n {
            let a = lamp * (i as f64 + 0.5) / n as f64;
            for j in 0..n {
                let phi = std::f64::consts::TAU * (j as f64 + 0.5) / n as f64;
                let w = a.cos() * wi0 + a.sin() * (phi.cos() * t + phi.sin() * b);
                g.eval(wo, w, &mut v);
                let dw = a.sin() * (lamp / n as f64) * (std::f64::consts::TAU / n as f64);
                for k in 0..3 {
                    bands[k] += v[k] * w.z * dw;
                }
            }
        }
        let expected = field.to_rgb(&bands);
        for c in 0..3 {
            let values: Vec<f64> = (0..px * px)
                .map(|k| f64::from(image.get(k % px, k / px)[c]))
                .collect();
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            let var =
                values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (values.len() - 1) as f64;
            let se = (var / values.len() as f64).sqrt();
            assert!(
                (mean - expected[c]).abs() <= 4.0 * se + 1e-3 * expected[c],
                "θo {to} θi {ti} channel {c}: picture {mean:.5} ± {se:.5}, glint {:.5}",
                expected[c]
            );
            assert!(
                se < 0.05 * expected[c],
                "too noisy to test: {se} of {}",
                expected[c]
            );
        }
    }
}

/// One flake wider than the picture is a tilted mirror under the coat: seen along the normal,
/// it shows a lamp placed where its mirror sends the camera's ray (refracted into the coat by
/// Snell's law, reflected about the flake's normal, refracted out), with the radiance
/// `T(θo) T(θi) R(ι)` of the lamp (Fresnel's transmittances of the coat, written here, and the
/// aluminium flake's reflectance at the local angle ι; the flakes' projected-area weight is 1
/// seen along the normal, within the tilt table's 1e-3), every pixel alike; and the lamp moved
/// 4° off that direction is not seen.
#[test]
fn one_large_flake_is_a_tilted_mirror() {
    let g = glint(1e6); // 1 m across: the 1 cm picture lies on one flake
    let eta = g.eta();
    let wo = DVec3::Z;
    // A seed whose flake under the picture's centre mirrors the camera out of the coat.
    let (field, flake) = (1..50)
        .find_map(|seed| {
            let field = FlakeField::new(g.clone(), seed).unwrap();
            let at = |x: f64, y: f64| field.flake_at(DVec3::new(x, y, -40e-6));
            let centre = at(0.0, 0.0)?;
            let corners = [
                (-0.006, -0.006),
                (0.006, 0.006),
                (-0.006, 0.006),
                (0.006, -0.006),
            ];
            let one = corners.iter().all(|&(x, y)| at(x, y) == Some(centre));
            let h = centre.normal;
            let up = 2.0 * h.z * h - DVec3::Z;
            let exits = up.truncate().length() * eta < 0.9;
            (one && exits && h.z < 0.99).then_some((field, centre))
        })
        .expect("a seed with one tilted flake under the picture");
    let h = flake.normal;
    // The mirror, by hand: inside the coat the camera's ray is the normal itself.
    let up = 2.0 * h.z * h - DVec3::Z;
    let s = up.truncate() * eta;
    let out = DVec3::new(s.x, s.y, (1.0 - s.length_squared()).sqrt());
    let mut r = [0.0; 3];
    let coating_flakes = parse(
        "[coat]\nindex = 1.5\nthickness_um = 40\n[flakes]\nkind = \"aluminium\"\n\
         coverage = 0.6\ntilt_deg = 12\n[base]\nkind = \"diffuse\"\nreflectance = 0.25\n",
        &BANDS,
    )
    .unwrap()
    .flakes
    .unwrap();
    for (k, &w) in BANDS.iter().enumerate() {
        let t = (1.0 - dielectric(1.0, eta)) * (1.0 - dielectric(out.z, eta));
        r[k] = t * coating_flakes.optics(eta, w).unwrap().reflectance(h.z);
    }
    let expected = field.to_rgb(&r);
    let px = 32;
    let lit = with_flakes(patch(wo, out, 0.01, px, 1.0), field.clone());
    let (image, _) = render(&lit, &opts(4, 1, ColourMode::Tristimulus)).unwrap();
    for k in 0..px * px {
        let p = image.get(k % px, k / px);
        for c in 0..3 {
            let got = f64::from(p[c]);
            assert!(
                (got - expected[c]).abs() <= 2e-3 * expected[c],
                "pixel {k} channel {c}: {got} against the mirror's {}",
                expected[c]
            );
        }
    }
    // The lamp 4° away from the mirror direction (its radius is 1°).
    let axis = out.cross(DVec3::X).normalize();
    let away = glam::DQuat::from_axis_angle(axis, 4f64.to_radians()) * out;
    let dark = with_flakes(patch(wo, away, 0.01, px, 1.0), field);
    let (image, _) = render(&dark, &opts(4, 1, ColourMode::Tristimulus)).unwrap();
    assert!((0..px * px).all(|k| image.get(k % px, k / px) == [0.0; 3]));
}

/// The flakes on a plane have the size the description gives: the number of distinct flakes
/// met on a 2 × 2 mm square of a plane, over the coverage, is the square's area over the mean
/// flake area π d²/4 (the constant κ of `gonio_render::flakes`; statistical error of ~5000 cells
/// about 1.5%, tolerance 5%), on planes of three orientations; and the coverage is the fraction
/// of points on a flake (within 2%).
#[test]
fn flakes_have_the_size_and_coverage_of_the_description() {
    let d = 20e-6;
    let field = FlakeField::new(glint(20.0), 3).unwrap();
    for normal in [DVec3::Z, dir(40.0, 30.0), dir(75.0, 200.0)] {
        let t = normal.cross(DVec3::new(0.3, 0.5, 0.8)).normalize();
        let b = normal.cross(t);
        let (side, n) = (2e-3, 800);
        let (mut sites, mut on) = (HashSet::new(), 0usize);
        for i in 0..n {
            for j in 0..n {
                let p =
                    (i as f64 / n as f64 - 0.5) * side * t + (j as f64 / n as f64 - 0.5) * side * b;
                if let Some(f) = field.flake_at(p) {
                    on += 1;
                    sites.insert(f.site);
                }
            }
        }
        let coverage = on as f64 / (n * n) as f64;
        assert!((coverage - 0.6).abs() < 0.02 * 0.6, "coverage {coverage}");
        let expected = 0.6 * side * side / (std::f64::consts::PI * d * d / 4.0);
        let count = sites.len() as f64;
        assert!(
            (count - expected).abs() < 0.05 * expected,
            "plane {normal}: {count} flakes, {expected:.0} expected"
        );
    }
}

/// The same picture, bit for bit, on one thread and on four.
#[test]
fn flakes_do_not_depend_on_the_thread_count() {
    let field = FlakeField::new(glint(20.0), 5).unwrap();
    let s = with_flakes(
        patch(dir(0.0, 0.0), dir(15.0, 180.0), 0.005, 64, 3.0),
        field,
    );
    let run = |threads| {
        let options = RenderOptions {
            threads: Some(threads),
            ..opts(4, 2, ColourMode::Spectral)
        };
        render(&s, &options).unwrap().0
    };
    let (a, b) = (run(1), run(4));
    assert!((0..64 * 64).all(|k| a.get(k % 64, k / 64) == b.get(k % 64, k / 64)));
    assert!(
        (0..64 * 64).any(|k| a.get(k % 64, k / 64)[1] > 0.0),
        "some flake glints"
    );
}

/// The whole coating: its flakes drawn one by one over the table without their glint, each
/// point letting through what it shows of the light from inside (the base between the flakes,
/// nothing through a metal flake), average to the coating's table with the flakes smooth.
mod slow {
    use super::*;
    use gonio_coating::system::default_bands;
    use gonio_render::coating_material::{FlakeMode, from_coating};
    use gonio_render::material::Material;

    /// The mean radiance of the patch under a 3° lamp, with discrete flakes against smooth
    /// ones, at the three geometries of the glint's test: within four standard errors (from
    /// the pixels' spread, both pictures' errors combined; pixels of 67 µm hold about ten
    /// flakes and gaps, so they are nearly independent).
    #[test]
    fn discrete_flakes_average_to_the_coatings_table() {
        let coating = parse(
            "[top]\nroughness = { distribution = \"ggx\", alpha = 0.05 }\n\
             [coat]\nindex = 1.5\nthickness_um = 40\n[flakes]\nkind = \"aluminium\"\n\
             coverage = 0.6\ntilt_deg = 12\n[base]\nkind = \"diffuse\"\nreflectance = 0.25\n",
            &default_bands(),
        )
        .unwrap();
        let discrete = from_coating("d", &coating, "test", FlakeMode::Discrete, 3).unwrap();
        let smooth = from_coating("s", &coating, "test", FlakeMode::Smooth, 3).unwrap();
        let px = 300;
        let stats = |material: &Material, wo: DVec3, wi: DVec3| {
            let mut s = patch(wo, wi, 0.02, px, 3.0);
            s.materials[0] = material.clone();
            let (image, _) = render(&s, &opts(8, 1, ColourMode::Tristimulus)).unwrap();
            let y: Vec<f64> = image
                .pixels
                .iter()
                .map(|&p| gonio_render::texture_metrics::luminance(p))
                .collect();
            let n = y.len() as f64;
            let mean = y.iter().sum::<f64>() / n;
            let var = y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, (var / n).sqrt())
        };
        for (to, ti) in [(0.0, 15.0), (30.0, 45.0), (60.0, 60.0)] {
            let (wo, wi) = (dir(to, 0.0), dir(ti, 180.0));
            let (a, sa) = stats(&discrete, wo, wi);
            let (b, sb) = stats(&smooth, wo, wi);
            let se = (sa * sa + sb * sb).sqrt();
            assert!(
                (a - b).abs() <= 4.0 * se,
                "θo {to} θi {ti}: discrete {a:.6} ± {sa:.6}, smooth {b:.6} ± {sb:.6}"
            );
            assert!(se < 0.05 * b, "too noisy to test: {se} of {b}");
        }
    }
}
