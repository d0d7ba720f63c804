//! Thin-film reflectance against `tmm` (PyPI; S. J. Byrnes, "Multilayer optical calculations",
//! arXiv:1603.02720), which computes it by transfer matrices, not by gonio's Airy recursion:
//! interference flakes (TiO2 | mica | TiO2 in a binder) of several coating thicknesses, an
//! absorbing metal film on glass and a film over a metal substrate, at 0 to 80° and 400 to
//! 700 nm, s and p. Both are exact solutions of the same boundary-value problem, so they agree
//! to rounding; the bound is the issue's 1e-6.

use gonio_coating::thin_film::{Film, Polarisation, Stack, interference_flake};
use num_complex::Complex64;

const SCRIPT: &str = r#"
import json, sys, math
import tmm
cases = json.load(sys.stdin)
out = []
for c in cases:
    n = [complex(re, im) for re, im in c["n"]]
    d = [math.inf] + c["d"] + [math.inf]
    th = math.radians(c["theta_deg"])
    out.append([tmm.coh_tmm(p, n, d, th, c["lambda_nm"])["R"] for p in ("s", "p")])
json.dump(out, sys.stdout)
"#;

struct Case {
    stack: Stack,
    indices: Vec<Complex64>,
    thicknesses: Vec<f64>,
    theta_deg: f64,
    lambda_nm: f64,
}

#[test]
fn stacks_agree_with_tmm() {
    let mut cases = Vec::new();
    let mut add =
        |ambient: f64, films: Vec<Film>, substrate: Complex64, theta_deg: f64, lambda_nm: f64| {
            let mut indices = vec![Complex64::new(ambient, 0.0)];
            indices.extend(films.iter().map(|f| f.index));
            indices.push(substrate);
            let thicknesses = films.iter().map(|f| f.thickness_nm).collect();
            cases.push(Case {
                stack: Stack::new(ambient, films, substrate).unwrap(),
                indices,
                thicknesses,
                theta_deg,
                lambda_nm,
            });
        };
    for theta in [0.0, 25.0, 45.0, 65.0, 80.0] {
        for lambda in [400.0, 470.0, 550.0, 630.0, 700.0] {
            for tio2 in [60.0, 120.0, 180.0] {
                // The flake helper's own stack, so the dispersion is the one gonio uses.
                let flake = interference_flake(tio2, 400.0, 1.58, 1.5, lambda).unwrap();
                let n_tio2 = gonio_coating::thin_film::rutile_ordinary(lambda);
                let films = vec![
                    Film {
                        index: Complex64::new(n_tio2, 0.0),
                        thickness_nm: tio2,
                    },
                    Film {
                        index: Complex64::new(1.58, 0.0),
                        thickness_nm: 400.0,
                    },
                    Film {
                        index: Complex64::new(n_tio2, 0.0),
                        thickness_nm: tio2,
                    },
                ];
                assert_eq!(
                    flake,
                    Stack::new(1.5, films.clone(), Complex64::new(1.5, 0.0)).unwrap()
                );
                add(1.5, films, Complex64::new(1.5, 0.0), theta, lambda);
            }
            // 12 nm of aluminium (n + iκ ≈ 0.96 + 6.69i at 550 nm) on glass, from air.
            add(
                1.0,
                vec![Film {
                    index: Complex64::new(0.96, 6.69),
                    thickness_nm: 12.0,
                }],
                Complex64::new(1.52, 0.0),
                theta,
                lambda,
            );
            // A lossy dielectric film over gold-like metal, from a binder.
            add(
                1.5,
                vec![
                    Film {
                        index: Complex64::new(2.0, 0.05),
                        thickness_nm: 85.0,
                    },
                    Film {
                        index: Complex64::new(1.38, 0.0),
                        thickness_nm: 140.0,
                    },
                ],
                Complex64::new(0.47, 2.4),
                theta,
                lambda,
            );
        }
    }
    let json: Vec<serde_json::Value> = cases
        .iter()
        .map(|c| {
            serde_json::json!({
                "n": c.indices.iter().map(|n| [n.re, n.im]).collect::<Vec<_>>(),
                "d": c.thicknesses,
                "theta_deg": c.theta_deg,
                "lambda_nm": c.lambda_nm,
            })
        })
        .collect();
    let Some(reference) =
        crate::oracle::run::<Vec<[f64; 2]>>(SCRIPT, "tmm", "tmm", &serde_json::Value::Array(json))
    else {
        return;
    };
    assert_eq!(reference.len(), cases.len());
    let mut worst = 0.0f64;
    for (c, [rs, rp]) in cases.iter().zip(reference) {
        let theta = c.theta_deg.to_radians();
        let s = c.stack.reflectance(Polarisation::S, theta, c.lambda_nm);
        let p = c.stack.reflectance(Polarisation::P, theta, c.lambda_nm);
        worst = worst.max((s - rs).abs()).max((p - rp).abs());
        assert!(
            (s - rs).abs() < 1e-6 && (p - rp).abs() < 1e-6,
            "{:?} at {}° {} nm: s {s} vs {rs}, p {p} vs {rp}",
            c.indices,
            c.theta_deg,
            c.lambda_nm
        );
    }
    println!(
        "{} cases, largest difference from tmm {worst:.1e}",
        cases.len()
    );
}
