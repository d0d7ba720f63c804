//! gonio-formulation: from a coating's appearance back to its formulation. Which constituents
//! matter for which reading ([`sensitivity`]: Sobol indices and Morris screening, generic, no
//! physics; [`coating_sensitivity`]: the same applied to a coating's gloss, haze, DOI and
//! multi-angle colour ([`appearance`]), read by `instrument::coating_study`) and, later, which
//! values reproduce a target (matching). `docs/formulation.md` gives the estimators, their checks
//! and their cost.

pub mod appearance;
pub mod coating_sensitivity;
pub mod error;
pub mod sensitivity;
pub mod sensitivity_report;

pub use error::{FormulationError, Result};
