//! Virtual instruments for gonio: gloss meters (ISO 2813 / ASTM D523), reflection haze and
//! distinctness of image (ASTM E430), and the comparison of measured and computed in-plane curves.

pub mod compare;
pub mod curves;
pub mod error;
pub mod gloss;
mod quadrature;
pub mod specimens;
pub mod study;

pub use error::{InstrumentError, Result};
pub use gloss::{GlossReport, Specimen, measure};
