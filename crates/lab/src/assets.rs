//! The page: HTML, CSS and JavaScript written in this repository (`crates/lab/assets/`) and
//! embedded in the program, so the lab works offline and a user needs no build step.

use axum::http::header;
use axum::response::{IntoResponse, Response};

pub fn page() -> Response {
    (
        [(header::CONTENT_TYPE, "text/html; charset=utf-8")],
        include_str!("../assets/lab.html"),
    )
        .into_response()
}

pub fn script() -> Response {
    (
        [(header::CONTENT_TYPE, "text/javascript; charset=utf-8")],
        include_str!("../assets/lab.js"),
    )
        .into_response()
}

pub fn style() -> Response {
    (
        [(header::CONTENT_TYPE, "text/css; charset=utf-8")],
        include_str!("../assets/lab.css"),
    )
        .into_response()
}
