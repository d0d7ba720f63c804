//! Integration tests of gonio-instrument: the virtual instruments on whole maps (the isotropy
//! check, the ray method against Kirchhoff), on a measured paint (the multi-angle
//! spectrophotometer) and through the public API (gloss, haze and DOI, multi-angle readings,
//! specimens, the coating study, curves, comparison and the methods' validity).
//!
//! Every test that the public API can express lives here; the library keeps as unit tests only
//! those that reach private items. A library's unit-test binary compiles again, optimised, every
//! function its tests reach, where these link the library's compiled copy. One test binary per
//! crate (one link instead of one per file); each module is one subject.

mod coating_readings;
mod coating_study;
mod coating_tables;
mod compare;
mod curves;
mod gloss;
mod isotropy;
mod multiangle;
mod multiangle_readings;
mod ray_vs_kirchhoff;
mod specimens;
mod validity;
