//! gonio-conformance's integration tests: the references against independent computations, and
//! the suite on each renderer (in `slow`).

mod common;
mod flip;
mod metamer;
mod optics;
mod scenes;
mod suite;
