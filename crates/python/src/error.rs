//! gonio's errors as Python exceptions: a file the operating system cannot open or write becomes
//! `OSError` (`FileNotFoundError`, `PermissionError` where the cause says so), everything else
//! (a malformed file, a value out of range) `ValueError`; the message is gonio's own, naming the
//! file and what to fix.

use pyo3::PyErr;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyPermissionError, PyValueError};
use std::io::ErrorKind;

/// An error on its way to Python.
pub struct Error(PyErr);

/// Result of the module's Rust functions.
pub type Result<T> = std::result::Result<T, Error>;

impl From<Error> for PyErr {
    fn from(e: Error) -> PyErr {
        e.0
    }
}

impl From<PyErr> for Error {
    fn from(e: PyErr) -> Error {
        Error(e)
    }
}

/// A `ValueError` with `message`.
pub fn invalid(message: impl Into<String>) -> Error {
    Error(PyValueError::new_err(message.into()))
}

/// The exception of an operating-system error, with gonio's message.
fn os(kind: ErrorKind, message: String) -> Error {
    Error(match kind {
        ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        ErrorKind::PermissionDenied => PyPermissionError::new_err(message),
        _ => PyOSError::new_err(message),
    })
}

impl From<gonio_surface::SurfaceError> for Error {
    fn from(e: gonio_surface::SurfaceError) -> Error {
        match &e {
            gonio_surface::SurfaceError::Io { error, .. } => os(error.kind(), e.to_string()),
            _ => invalid(e.to_string()),
        }
    }
}

impl From<gonio_brdf::BrdfError> for Error {
    fn from(e: gonio_brdf::BrdfError) -> Error {
        match &e {
            gonio_brdf::BrdfError::Io { cause, .. } => os(cause.kind(), e.to_string()),
            _ => invalid(e.to_string()),
        }
    }
}

impl From<gonio_scatter::ScatterError> for Error {
    fn from(e: gonio_scatter::ScatterError) -> Error {
        match e {
            gonio_scatter::ScatterError::Surface(s) => s.into(),
            other => invalid(other.to_string()),
        }
    }
}

impl From<gonio_instrument::InstrumentError> for Error {
    fn from(e: gonio_instrument::InstrumentError) -> Error {
        use gonio_instrument::InstrumentError as E;
        match e {
            E::Surface(s) => s.into(),
            E::Scatter(s) => s.into(),
            E::Io { ref error, .. } => os(error.kind(), e.to_string()),
            other => invalid(other.to_string()),
        }
    }
}

impl From<gonio_render::RenderError> for Error {
    fn from(e: gonio_render::RenderError) -> Error {
        use gonio_render::RenderError as E;
        match e {
            E::Brdf(b) => b.into(),
            E::Io { ref error, .. } => os(error.kind(), e.to_string()),
            other => invalid(other.to_string()),
        }
    }
}

impl From<gonio_formulation::FormulationError> for Error {
    fn from(e: gonio_formulation::FormulationError) -> Error {
        use gonio_formulation::FormulationError as E;
        match e {
            E::Instrument(i) => i.into(),
            E::Io { ref error, .. } => os(error.kind(), e.to_string()),
            other => invalid(other.to_string()),
        }
    }
}

impl From<gonio_report::ReportError> for Error {
    fn from(e: gonio_report::ReportError) -> Error {
        use gonio_report::ReportError as E;
        match e {
            E::Io { ref error, .. } => os(error.kind(), e.to_string()),
            E::Surface(s) => s.into(),
            E::Scatter(s) => s.into(),
            E::Brdf(b) => b.into(),
            E::Instrument(i) => i.into(),
            E::Formulation(f) => f.into(),
            E::Render(r) => r.into(),
            E::Conformance(gonio_conformance::Error::Io { ref source, .. }) => {
                os(source.kind(), e.to_string())
            }
            other => invalid(other.to_string()),
        }
    }
}

impl From<gonio_coating::CoatingError> for Error {
    fn from(e: gonio_coating::CoatingError) -> Error {
        invalid(e.to_string())
    }
}

impl From<gonio_color::ColorError> for Error {
    fn from(e: gonio_color::ColorError) -> Error {
        invalid(e.to_string())
    }
}
