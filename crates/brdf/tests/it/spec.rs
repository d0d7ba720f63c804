//! Model descriptions: the documented example builds, JSON round trips keep every field, bad
//! parameters and unknown fields are named in the error. The descriptions are parsed by
//! `ModelSpec::from_json`, as the CLI and the Python package parse them; the same tagged tables
//! in TOML are read by scene files (gonio-render's scene and spectral tests).

use glam::DVec3;
use gonio_brdf::bxdf::{Brdf, Rgb};
use gonio_brdf::models::*;

#[test]
fn documented_example_builds_a_diffuse_plus_ggx_mix() {
    let spec = ModelSpec::from_json(
        r#"{"model": "ggx", "alpha": 0.2, "index": 1.5, "diffuse": [0.5, 0.1, 0.1]}"#,
    )
    .unwrap();
    let Model::Mix(mix) = spec.build().unwrap() else {
        panic!("expected a mix")
    };
    assert_eq!(mix.parts.len(), 2);
    assert_eq!(
        mix.parts[0],
        Model::Lambert(Lambert {
            albedo: Rgb::new(0.5, 0.1, 0.1)
        })
    );
    let wo = DVec3::new(0.3, 0.0, 0.9).normalize();
    let wi = DVec3::new(-0.3, 0.0, 0.9).normalize();
    let expect = mix.parts[0].eval(wo, wi) + mix.parts[1].eval(wo, wi);
    assert_eq!(Model::Mix(mix).eval(wo, wi), expect);
}

#[test]
fn json_round_trip_keeps_every_field() {
    let specs = [
        ModelSpec::Ward {
            specular: Reflectance::Rgb([0.1, 0.2, 0.3]),
            alpha: 0.1,
            alpha_y: Some(0.3),
            diffuse: None,
        },
        ModelSpec::Beckmann {
            m: 0.2,
            index: Index::Complex([0.27, 2.78]),
            tint: Some(Reflectance::Mono(0.9)),
            diffuse: Some(Reflectance::Mono(0.1)),
        },
        ModelSpec::Mix {
            parts: vec![
                ModelSpec::Lambert {
                    albedo: Reflectance::Mono(0.3),
                },
                ModelSpec::BlinnPhong {
                    specular: Reflectance::Mono(0.2),
                    exponent: 50.0,
                    diffuse: None,
                },
            ],
        },
    ];
    for spec in specs {
        let text = serde_json::to_string(&spec).unwrap();
        let back = ModelSpec::from_json(&text).unwrap();
        assert_eq!(back, spec, "{text}");
    }
}

#[test]
fn bad_parameters_are_named_in_the_error() {
    let cases = [
        (
            r#"{"model": "ggx", "alpha": -0.2, "index": 1.5}"#,
            "`alpha`",
        ),
        (
            r#"{"model": "lambert", "albedo": [0.5, -1, 0.2]}"#,
            "`albedo`",
        ),
        (
            r#"{"model": "beckmann", "m": 0.1, "index": [1.2, -3]}"#,
            "index[1]",
        ),
        (r#"{"model": "mix", "parts": []}"#, "`parts`"),
    ];
    for (json, field) in cases {
        let spec = ModelSpec::from_json(json).unwrap();
        let err = spec.build().unwrap_err().to_string();
        assert!(
            err.contains(field) && err.contains(spec.name()),
            "{json}: {err}"
        );
    }
    let unknown =
        ModelSpec::from_json(r#"{"model": "ward", "specular": 0.1, "alpha": 0.1, "roughness": 2}"#)
            .unwrap_err()
            .to_string();
    assert!(
        unknown.contains("roughness") && unknown.contains("docs/brdf-models.md"),
        "unknown fields are rejected: {unknown}"
    );
}
