//! Errors of the coating optics: a constituent's description that cannot describe a material.

/// What is wrong with a coating's description.
#[derive(Debug, thiserror::Error)]
pub enum CoatingError {
    /// A value out of its physical range, with what it must be.
    #[error("{0}")]
    Invalid(String),
    /// The caller raised its [`gonio_io::Cancel`] flag before the computation finished: no
    /// partial result is returned.
    #[error("cancelled")]
    Cancelled,
}

pub type Result<T> = std::result::Result<T, CoatingError>;
