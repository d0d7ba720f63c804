//! The error type of the `formulation` crate.

/// Everything that can go wrong in a sensitivity analysis or a formulation study.
#[derive(Debug, thiserror::Error)]
pub enum FormulationError {
    /// An input, an option or a matrix is out of range or inconsistent; the message says which.
    #[error("{0}")]
    Invalid(String),
    /// A file could not be written.
    #[error("{path}: {error}")]
    Io {
        path: String,
        /// What went wrong; printed in the message, so not also returned as `source()`.
        error: std::io::Error,
    },
    /// A virtual instrument could not read a coating.
    #[error(transparent)]
    Instrument(#[from] gonio_instrument::InstrumentError),
    /// The caller raised its [`gonio_io::Cancel`] flag before the computation finished: no
    /// partial result is returned.
    #[error("cancelled")]
    Cancelled,
    /// A coating could not be built.
    #[error(transparent)]
    Coating(#[from] gonio_coating::CoatingError),
}

/// Result with [`FormulationError`].
pub type Result<T, E = FormulationError> = std::result::Result<T, E>;
