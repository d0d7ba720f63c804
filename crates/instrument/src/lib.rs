//! Virtual instruments for gonio: in-plane curves by several methods at once (`inplane`), gloss
//! meters (ISO 2813 / ASTM D523), reflection haze (ASTM E430, ASTM D4039) and distinctness of
//! image (ASTM E430) on a height map or a table (`gloss`, `meter`), the comparison of measured and computed
//! in-plane curves, the isotropy check (the curves of a map and of the map turned about its
//! normal), the multi-angle spectrophotometer of effect coatings (ASTM E2194, E2539:
//! `multiangle`), the validity warnings of a virtual reading (`validity`), and every reading the
//! lab shows of a formulation or a measured BRDF in one cancellable call (`coating_readings`,
//! `brdf_readings`).

pub mod brdf_readings;
pub mod coating_readings;
pub mod coating_study;
pub mod coating_study_output;
pub mod coating_summary;
pub mod compare;
pub mod curves;
pub mod error;
pub mod gloss;
pub mod inplane;
pub mod isotropy;
pub mod meter;
pub mod multiangle;
pub mod multiangle_target;
pub mod specimens;
pub mod study;
pub mod validity;

pub use error::{InstrumentError, Result};
pub use gloss::{GlossReport, Specimen, measure};
