//! The error type of the `instrument` crate: unreadable curve files (naming the file and line)
//! and failures of the scattering and surface crates it drives.

/// Everything that can go wrong in a virtual instrument or study.
#[derive(Debug, thiserror::Error)]
pub enum InstrumentError {
    /// A curve file could not be parsed; the message names the line and column.
    #[error("{path}: {message}")]
    Read { path: String, message: String },
    /// A file could not be read or written.
    #[error("{path}: {error}")]
    Io {
        path: String,
        /// What went wrong; printed in the message, so not also returned as `source()`.
        error: std::io::Error,
    },
    /// An input or option is out of range.
    #[error("{0}")]
    Invalid(String),
    /// A scattering computation failed.
    #[error(transparent)]
    Scatter(#[from] gonio_scatter::ScatterError),
    /// A surface operation failed.
    #[error(transparent)]
    Surface(#[from] gonio_surface::SurfaceError),
    /// A plot could not be drawn or written.
    #[error(transparent)]
    Plot(#[from] gonio_plot::PlotError),
    /// A coating could not be computed.
    #[error(transparent)]
    Coating(#[from] gonio_coating::CoatingError),
    /// The caller raised its [`gonio_io::Cancel`] flag before the computation finished: no
    /// result, not a partial one.
    #[error("cancelled")]
    Cancelled,
}

/// Result with [`InstrumentError`].
pub type Result<T, E = InstrumentError> = std::result::Result<T, E>;
