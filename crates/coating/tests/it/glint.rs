//! The flakes' glint ([`Glint`]): its BRDF against the layered walk's single scattering (which
//! SCATMECH checks, `scatmech_oracle`), the mean of the discrete flakes against that BRDF, and
//! the table that leaves it out.

use glam::{DVec2, DVec3};
use gonio_brdf::table::{Provenance, Resolution};
use gonio_coating::description::parse;
use gonio_coating::glint::Glint;
use gonio_coating::layered::Scratch;
use gonio_coating::system::Coating;
use gonio_io::Cancel;

const WL: [f64; 3] = [450.0, 550.0, 650.0];

/// A silver metallic under a smooth (or rough) top over a base of reflectance `rho`.
fn silver(top: &str, rho: f64, absorption: f64) -> Coating {
    parse(
        &format!(
            "{top}[coat]\nindex = 1.5\nthickness_um = 40\nabsorption_per_um = {absorption}\n\
             [flakes]\nkind = \"aluminium\"\ncoverage = 0.6\ntilt_deg = 12\n\
             [base]\nkind = \"diffuse\"\nreflectance = {rho}\n"
        ),
        &WL,
    )
    .unwrap()
}

fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

/// Under a smooth top over a black base, the walk's single scattering is the glint alone, and
/// each of its samples is exact: the two computations (the walk's refraction, Fresnel
/// transmissions and absorption, and the glint's closed form) agree to rounding.
#[test]
fn glint_is_the_walks_single_scattering_over_a_black_base() {
    let coating = silver("", 0.0, 0.002);
    let glint = Glint::new(&coating, &WL).unwrap().unwrap();
    let walks = coating.walks(&WL).unwrap();
    assert_eq!(walks.len(), 1, "one index for every band");
    let walk = &walks[0].1;
    let mut scratch = Scratch::default();
    let (mut single, mut g) = ([0.0; 3], [0.0; 3]);
    let mut peak = 0.0f64;
    let mut compared = 0;
    for ti in [0.0, 30.0, 60.0, 80.0] {
        for to in [5.0, 25.0, 45.0, 70.0, 85.0] {
            for po in [0.0, 60.0, 150.0, 180.0] {
                let (wi, wo) = (dir(ti, 180.0), dir(to, po));
                walk.eval_single(wo, wi, 1, 7, &mut scratch, &mut single);
                glint.eval(wo, wi, &mut g);
                for b in 0..3 {
                    peak = peak.max(g[b]);
                    assert!(
                        (single[b] - g[b]).abs() <= 1e-9 * single[b].max(1e-3),
                        "θi {ti} θo {to} φo {po} band {b}: walk {} glint {}",
                        single[b],
                        g[b]
                    );
                }
                compared += 1;
            }
        }
    }
    assert!(peak > 0.2 && compared == 80, "peak {peak}");
}

/// The discrete flakes average to the glint: flakes drawn as a point of the layer meets them
/// (a fraction c on a flake, its normal by `D(h) cos θh`), each sending its weight into the
/// direction it mirrors; what falls into a cone of half-angle 4° about `wi0` is, in the mean,
/// `∫_cone g(wo, wi) cos θi dωi` (the glint integrated over the cone by quadrature). At three
/// incidences; the tolerance is four standard errors of the mean over the draws (computed from
/// the draws), plus the quadrature's error (under 1e-4 relative at 48 × 48 nodes).
#[test]
fn discrete_flakes_average_to_the_glint() {
    let coating = silver("", 0.3, 0.001);
    let glint = Glint::new(&coating, &WL).unwrap().unwrap();
    let c = glint.coverage();
    let orientation = glint.orientation();
    let half = 4f64.to_radians();
    let draws = 400_000;
    for (to, ti) in [(15.0, 15.0), (45.0, 30.0), (75.0, 60.0)] {
        let wo = dir(to, 0.0);
        let wi0 = dir(ti, 180.0);
        // The glint integrated over the cone: polar coordinates about wi0.
        let (t, b) = frame(wi0);
        let mut expected = [0.0; 3];
        let mut g = [0.0; 3];
        let n = 48;
        for i in 0..n {
            let a = half * (i as f64 + 0.5) / n as f64;
            for j in 0..n {
                let phi = std::f64::consts::TAU * (j as f64 + 0.5) / n as f64;
                let w = a.cos() * wi0 + a.sin() * (phi.cos() * t + phi.sin() * b);
                glint.eval(wo, w, &mut g);
                let dw = a.sin() * (half / n as f64) * (std::f64::consts::TAU / n as f64);
                for k in 0..3 {
                    expected[k] += g[k] * w.z * dw;
                }
            }
        }
        // The discrete flakes, drawn with a fixed sequence (a Weyl sequence in two dimensions
        // and a third for the coverage).
        let (mut sum, mut sum2) = ([0.0; 3], [0.0; 3]);
        let mut out = [0.0; 3];
        let (mut hits, cos_half) = (0, half.cos());
        for k in 0..draws {
            let u = |a: f64| (0.5 + a * k as f64).fract();
            if u(0.618_033_988_749_894_9) >= c {
                continue;
            }
            let h = orientation.sample_d(DVec2::new(
                u(0.754_877_666_246_692_7),
                u(0.569_840_290_998_053_3),
            ));
            let Some(wi) = glint.flake(wo, h, &mut out) else {
                continue;
            };
            if wi.dot(wi0) < cos_half {
                continue;
            }
            hits += 1;
            for k in 0..3 {
                sum[k] += out[k];
                sum2[k] += out[k] * out[k];
            }
        }
        for k in 0..3 {
            let mean = sum[k] / draws as f64;
            let se = ((sum2[k] / draws as f64 - mean * mean) / draws as f64).sqrt();
            assert!(
                (mean - expected[k]).abs() <= 4.0 * se + 1e-4 * expected[k],
                "θo {to} θi {ti} band {k}: flakes {mean:.5} ± {se:.5}, glint {:.5} ({hits} hits)",
                expected[k]
            );
            assert!(se < 0.05 * expected[k], "too few hits to test: {hits}");
        }
    }
}

/// Two unit vectors perpendicular to `w` and to each other.
fn frame(w: DVec3) -> (DVec3, DVec3) {
    let t = w.cross(DVec3::Y).normalize();
    (t, w.cross(t))
}

/// The table without the glint: its walks drop the single visits' flake lobe, so each cell is
/// at most the full table's (the same walks, fewer contributions). Under a smooth top each
/// walk's single visit is exact, so the difference is the glint to rounding; under a rough
/// top (α 0.03) it is the glint seen through the rough top, estimated by 64 walks a cell:
/// within 15% of the mean-plane glint where the glint is over half its peak (the walks'
/// noise there, about 4% at 64 walks, and the top's blur of the lobe, under 1%).
#[test]
fn table_without_glint_leaves_out_the_glint() {
    let resolution = Resolution::isotropic(8, 8, 4);
    for top in [
        "",
        "[top]\nroughness = { distribution = \"ggx\", alpha = 0.03 }\n",
    ] {
        let coating = silver(top, 0.25, 0.0);
        let glint = Glint::new(&coating, &WL).unwrap().unwrap();
        let full = coating
            .table(resolution, &WL, 64, Provenance::default())
            .unwrap();
        let rest = coating
            .table_without_glint(
                resolution,
                &WL,
                64,
                Provenance::default(),
                &Cancel::default(),
            )
            .unwrap();
        assert!(rest.provenance().extra.contains_key("glint"));
        let mut g = [0.0; 3];
        let mut peak = 0.0f64;
        for cell in 0..resolution.cell_count() {
            let (wi, wo) = resolution.cell_angles(cell).to_dirs();
            glint.eval(wo, wi, &mut g);
            peak = peak.max(g[1]);
        }
        let (mut checked, mut worst) = (0, 0.0f64);
        for cell in 0..resolution.cell_count() {
            let (wi, wo) = resolution.cell_angles(cell).to_dirs();
            let (a, b) = (full.cell_values(cell), rest.cell_values(cell));
            if a[0].is_nan() {
                continue;
            }
            glint.eval(wo, wi, &mut g);
            for k in 0..3 {
                let (a, b) = (f64::from(a[k]), f64::from(b[k]));
                assert!(
                    b >= 0.0 && b <= a * (1.0 + 1e-6),
                    "{top}: rest {b} over full {a}"
                );
                if top.is_empty() {
                    assert!(
                        (a - b - g[k]).abs() <= 1e-5 * a.max(1.0),
                        "smooth top: {a} - {b} against the glint {}",
                        g[k]
                    );
                } else if g[k] > 0.5 * peak {
                    worst = worst.max(((a - b) / g[k] - 1.0).abs());
                    checked += 1;
                }
            }
        }
        if !top.is_empty() {
            assert!(
                checked > 3 && worst < 0.15,
                "{checked} cells, worst {worst}"
            );
        }
    }
}
