//! A lab server for the tests ([`gonio_lab::spawn`]): on an ephemeral port of 127.0.0.1, with
//! a small upload limit (1 MiB) so that the limit can be tested cheaply.

use gonio_lab::Limits;

/// The upload limit of the test server, bytes.
pub const UPLOAD_LIMIT: usize = 1 << 20;

/// The base URL (`http://127.0.0.1:PORT`) of a new server, running until the test process ends.
pub fn start() -> String {
    let limits = Limits {
        upload_bytes: UPLOAD_LIMIT,
        ..Limits::default()
    };
    let address = gonio_lab::spawn("127.0.0.1:0".parse().expect("an address"), limits);
    format!("http://{}", address.expect("a lab on a free port"))
}

/// An HTTP client that returns every status as a response (the tests check the statuses).
pub fn client() -> ureq::Agent {
    ureq::Agent::config_builder()
        .http_status_as_error(false)
        .build()
        .into()
}

/// A response's status and body (text).
pub fn text(response: Result<ureq::http::Response<ureq::Body>, ureq::Error>) -> (u16, String) {
    let mut r = response.expect("a response");
    let status = r.status().as_u16();
    (status, r.body_mut().read_to_string().expect("a text body"))
}

/// A response's status and body as JSON.
pub fn json(
    response: Result<ureq::http::Response<ureq::Body>, ureq::Error>,
) -> (u16, serde_json::Value) {
    let (status, body) = text(response);
    (
        status,
        serde_json::from_str(&body).unwrap_or_else(|e| panic!("{e}: {body}")),
    )
}

/// POST `body` (JSON) to `url`.
pub fn post(
    agent: &ureq::Agent,
    url: &str,
    body: &serde_json::Value,
) -> Result<ureq::http::Response<ureq::Body>, ureq::Error> {
    agent
        .post(url)
        .header("content-type", "application/json")
        .send(body.to_string())
}

/// The formulation of the example `name`, as the lab gives it.
pub fn example(agent: &ureq::Agent, base: &str, name: &str) -> serde_json::Value {
    let (status, v) = json(agent.get(format!("{base}/api/examples/{name}")).call());
    assert_eq!(status, 200, "{v}");
    v["formulation"].clone()
}

/// A file of the repository's test data (`crates/surface/tests/data`, `crates/brdf/tests/data`).
pub fn data(path: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}
