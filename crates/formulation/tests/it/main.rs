//! Integration tests of gonio-formulation: the sensitivity estimators against analytic indices
//! (Ishigami's function, linear models), against SALib on the same points and outputs (oracle),
//! the coating's sensitivity against what its physics says, and matches of targets the model
//! synthesises (CIELAB and spectral). One test binary per crate; each
//! module is one subject.

mod coating_sensitivity;
mod cornell_paints;
mod embedded_screen;
mod lab_target;
mod matching;
mod measured_samples;
mod oracle;
mod salib;
mod search;
mod selection;
mod sensitivity;
mod spectral_matching;
mod watch;
