//! The error type of the `report` crate, and the [`Context`] that prefixes an error with what
//! was being done.

/// Everything that can go wrong while composing a report: the computations' own errors, and
/// the files read and written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// An input or a result is not what the report needs; the message says which.
    #[error("{0}")]
    Invalid(String),
    /// A file could not be read, written, copied or created.
    #[error("{path}: {error}")]
    Io {
        path: String,
        /// What went wrong; printed in the message, so not also returned as `source()`.
        error: std::io::Error,
    },
    /// An error and what was being done when it happened.
    #[error("{context}: {error}")]
    Context {
        context: String,
        /// Printed in the message, so not also returned as `source()`.
        error: Box<ReportError>,
    },
    #[error(transparent)]
    Surface(#[from] gonio_surface::SurfaceError),
    #[error(transparent)]
    Scatter(#[from] gonio_scatter::ScatterError),
    #[error(transparent)]
    Brdf(#[from] gonio_brdf::BrdfError),
    #[error(transparent)]
    Coating(#[from] gonio_coating::CoatingError),
    #[error(transparent)]
    Instrument(#[from] gonio_instrument::InstrumentError),
    #[error(transparent)]
    Formulation(#[from] gonio_formulation::FormulationError),
    #[error(transparent)]
    Render(#[from] gonio_render::RenderError),
    #[error(transparent)]
    Conformance(#[from] gonio_conformance::Error),
    #[error(transparent)]
    Plot(#[from] gonio_plot::PlotError),
    /// Formatting the page failed (writing into a `String` does not; kept for `write!`).
    #[error("formatting the report: {0}")]
    Format(#[from] std::fmt::Error),
}

/// Result with [`ReportError`].
pub type Result<T, E = ReportError> = std::result::Result<T, E>;

/// What was being done, put before an error (`"sq50nm: synthesising the surface: ..."`), or
/// the message of a missing value.
pub trait Context<T> {
    /// The error prefixed with `context`.
    fn context(self, context: impl Into<String>) -> Result<T>;
    /// The error prefixed with `context()`, made only on an error.
    fn with_context(self, context: impl FnOnce() -> String) -> Result<T>;
}

impl<T, E: Into<ReportError>> Context<T> for std::result::Result<T, E> {
    fn context(self, context: impl Into<String>) -> Result<T> {
        self.map_err(|e| ReportError::Context {
            context: context.into(),
            error: Box::new(e.into()),
        })
    }

    fn with_context(self, context: impl FnOnce() -> String) -> Result<T> {
        self.map_err(|e| ReportError::Context {
            context: context(),
            error: Box::new(e.into()),
        })
    }
}

/// A missing value is an [`ReportError::Invalid`] with the context as its message.
impl<T> Context<T> for Option<T> {
    fn context(self, context: impl Into<String>) -> Result<T> {
        self.ok_or_else(|| ReportError::Invalid(context.into()))
    }

    fn with_context(self, context: impl FnOnce() -> String) -> Result<T> {
        self.ok_or_else(|| ReportError::Invalid(context()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_context_comes_first_and_a_missing_value_says_what() {
        let err: Result<()> =
            Err(ReportError::Invalid("no rows".into())).context("the gloss table");
        assert_eq!(err.unwrap_err().to_string(), "the gloss table: no rows");
        let none: Option<u8> = None;
        assert_eq!(
            none.context("a scene file has a name")
                .unwrap_err()
                .to_string(),
            "a scene file has a name"
        );
    }
}
