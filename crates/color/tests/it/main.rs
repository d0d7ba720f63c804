//! Integration tests of gonio-color: colorimetry against colour-science, and spectra, tristimulus
//! values, chromatic adaptation, CIEDE2000 and hero-wavelength sampling through the public API.
//!
//! Every test that the public API can express lives here; the library keeps as unit tests only
//! those that reach private items. A library's unit-test binary compiles again, optimised, every
//! function its tests reach, where these link the library's compiled copy. One test binary per
//! crate (one link instead of one per file); each module is one subject.

mod adaptation;
mod ciede2000;
mod colorchecker;
mod hero;
mod spectrum;
mod tristimulus;
