//! The lab's answers when a request cannot be served: the status a client can act on and the
//! library's own message, as JSON `{"error": "..."}`. A bad formulation or upload is the
//! client's (400, 404, 413), a computation stopped because a newer request replaced it is 409,
//! anything else is the server's (500, logged to stderr).

use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};

/// Why a request failed.
#[derive(Debug, thiserror::Error)]
pub enum ApiError {
    /// The request is wrong: bad JSON, an invalid formulation, an unreadable upload.
    #[error("{0}")]
    BadRequest(String),
    /// The request names something the lab does not have (an example, an upload).
    #[error("{0}")]
    NotFound(String),
    /// The body is larger than the lab accepts.
    #[error("{0}")]
    TooLarge(String),
    /// A newer request on the same channel (or the client leaving) stopped this one.
    #[error("cancelled: a newer request replaced this one")]
    Cancelled,
    /// The server failed (a bug): the message is logged and returned.
    #[error("internal error: {0}")]
    Internal(String),
}

impl ApiError {
    /// The HTTP status of this error.
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::BadRequest(_) => StatusCode::BAD_REQUEST,
            ApiError::NotFound(_) => StatusCode::NOT_FOUND,
            ApiError::TooLarge(_) => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::Cancelled => StatusCode::CONFLICT,
            ApiError::Internal(_) => StatusCode::INTERNAL_SERVER_ERROR,
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        if let ApiError::Internal(message) = &self {
            eprintln!("gonio lab: internal error: {message}");
        }
        let body = serde_json::json!({ "error": self.to_string() });
        (self.status(), axum::Json(body)).into_response()
    }
}

/// A library's error in a computation the client asked for, as the client's error: the
/// libraries refuse what the client sent (their messages name the field), so it is a 400, unless
/// `cancel` was raised, when the error is the computation stopping.
pub fn refused(cancel: &gonio_io::Cancel, error: impl std::fmt::Display) -> ApiError {
    if cancel.is_cancelled() {
        ApiError::Cancelled
    } else {
        ApiError::BadRequest(error.to_string())
    }
}
