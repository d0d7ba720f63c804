//! gonio-formulation: from a coating's appearance back to its formulation. Which constituents
//! matter for which reading ([`sensitivity`]: Sobol indices and Morris screening, generic, no
//! physics; [`coating_sensitivity`]: the same applied to a coating's gloss, haze, DOI and
//! multi-angle colour ([`appearance`]), read by `instrument::coating_study`) and which values
//! reproduce a target ([`matching`]; with the pigments chosen from gonio's library by
//! [`selection`], screened by [`screen`]; against a [`target`], by [`match_objective`], written back as a description by
//! [`fitted_description`]), and what the lab shows of an uploaded target
//! ([`lab_target`]). `docs/formulation.md` gives the methods, their checks and their
//! cost.

pub mod appearance;
pub mod bounds;
pub mod coating_sensitivity;
pub mod embedded_screen;
pub mod error;
pub mod fitted_description;
pub mod lab_target;
pub mod match_objective;
mod match_reader;
pub mod match_report;
pub mod matching;
pub mod measured_samples;
pub mod prediction;
pub mod screen;
pub mod search;
pub mod selection;
pub mod sensitivity;
pub mod sensitivity_report;
pub mod target;
pub mod watch;

pub use error::{FormulationError, Result};
