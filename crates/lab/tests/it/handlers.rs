//! The JSON handlers take any body without failing: whatever a client sends (random JSON, random
//! formulations with fields of every type, random bytes), the answer is a 2xx or a 4xx with a
//! message, never a 500 (a panic in a handler or a computation is a 500).

use axum::body::Body;
use axum::http::Request;
use gonio_lab::{Lab, Limits};
use http_body_util::BodyExt;
use proptest::prelude::*;
use serde_json::{Value, json};
use std::sync::Arc;
use tower::ServiceExt;

/// Any JSON value, a few levels deep, with the field names a formulation uses among others.
fn any_json() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        (-1e3f64..1e3).prop_map(|x| json!(x)),
        prop_oneof![
            Just(-1.0f64),
            Just(0.0),
            Just(1e300),
            Just(0.5),
            Just(1.5),
            Just(40.0)
        ]
        .prop_map(|x| json!(x)),
        "[a-z_]{0,12}".prop_map(Value::String),
    ];
    let keys = prop_oneof![
        Just("top".to_string()),
        Just("roughness".to_string()),
        Just("alpha".to_string()),
        Just("coat".to_string()),
        Just("index".to_string()),
        Just("thickness_um".to_string()),
        Just("flakes".to_string()),
        Just("kind".to_string()),
        Just("coverage".to_string()),
        Just("tilt_deg".to_string()),
        Just("base".to_string()),
        Just("reflectance".to_string()),
        Just("nm".to_string()),
        Just("values".to_string()),
        Just("map".to_string()),
        "[a-z]{1,6}",
    ];
    leaf.prop_recursive(4, 48, 6, move |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..5).prop_map(Value::Array),
            prop::collection::btree_map(keys.clone(), inner, 0..6)
                .prop_map(|m| Value::Object(m.into_iter().collect())),
        ]
    })
}

/// A valid formulation with one field replaced by `value` at `path`.
fn mutated(path: usize, value: Value) -> Value {
    let mut f: Value = toml::from_str(gonio_lab::examples::EXAMPLES[0].1).unwrap();
    let pointers = [
        "/coat/index",
        "/coat/thickness_um",
        "/flakes/coverage",
        "/flakes/tilt_deg",
        "/flakes/kind",
        "/top/roughness/alpha",
        "/top/roughness",
        "/base/reflectance",
        "/base/kind",
        "/coat",
    ];
    *f.pointer_mut(pointers[path % pointers.len()]).unwrap() = value;
    f
}

fn status_of(router: &axum::Router, uri: &str, body: Vec<u8>) -> (u16, String) {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(async {
        let request = Request::post(uri)
            .header("content-type", "application/json")
            .body(Body::from(body))
            .unwrap();
        let response = router.clone().oneshot(request).await.unwrap();
        let status = response.status().as_u16();
        let bytes = response.into_body().collect().await.unwrap().to_bytes();
        (status, String::from_utf8_lossy(&bytes).into_owned())
    })
}

fn router() -> axum::Router {
    gonio_lab::api::router(Arc::new(Lab::new(Limits::default()).unwrap()))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Random JSON as a whole request, and random formulations, to the endpoints that only
    /// parse and check (the computing ones are reached with the same checks first).
    #[test]
    fn any_json_is_answered_without_a_server_error(body in any_json(), field in any_json(), path in 0usize..10) {
        let router = router();
        for uri in ["/api/formulation/to-toml", "/api/readings", "/api/picture", "/api/export/gbrdf",
                    "/api/constituents", "/api/match", "/api/sensitivity"] {
            let (status, text) = status_of(&router, uri, body.to_string().into_bytes());
            prop_assert!((400..500).contains(&status), "{uri} {body}: {status} {text}");
        }
        let request = json!({ "formulation": mutated(path, field.clone()) });
        let (status, text) = status_of(&router, "/api/formulation/to-toml", request.to_string().into_bytes());
        prop_assert!(status == 200 || (400..500).contains(&status), "{request}: {status} {text}");
        if status != 200 {
            prop_assert!(text.contains("\"error\""), "{text}");
        }
        // What a random formulation offers to vary, and a match or screening of it (refused
        // before it starts for want of a target, or of a valid constituent).
        let (status, text) = status_of(&router, "/api/constituents", request.to_string().into_bytes());
        prop_assert!(status == 200 || (400..500).contains(&status), "{request}: {status} {text}");
        let vary = json!([{ "name": "tilt" }, { "name": field }]);
        for uri in ["/api/match", "/api/sensitivity"] {
            let body = json!({ "formulation": mutated(path, field.clone()), "vary": vary, "target": "u1.csv" });
            let body = if uri == "/api/sensitivity" { json!({ "formulation": body["formulation"], "vary": vary, "outputs": [] }) } else { body };
            let (status, text) = status_of(&router, uri, body.to_string().into_bytes());
            prop_assert!((400..500).contains(&status), "{uri} {body}: {status} {text}");
        }
        // A selection of random pigments, counts and candidates.
        let select = json!({ "from": "select", "max": field, "candidates": [field], "finalists": field });
        for pigments in [select, json!({ "from": "select", "max": field })] {
            let body = json!({ "formulation": mutated(path, field.clone()), "vary": [],
                               "target": "u1.csv", "pigments": pigments });
            let (status, text) = status_of(&router, "/api/match", body.to_string().into_bytes());
            prop_assert!((400..500).contains(&status), "{body}: {status} {text}");
        }
    }

    /// Random bytes as a TOML description.
    #[test]
    fn any_bytes_as_a_description(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        let (status, text) = status_of(&router(), "/api/formulation/from-toml", bytes);
        prop_assert!(status == 200 || status == 400, "{status} {text}");
    }
}
