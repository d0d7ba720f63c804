//! Integration tests of gonio-scatter: the scattering methods against analytic models and each
//! other, the BRDF tables they make and their cache, and the goniometer geometry.
//!
//! Every test that the public API can express lives here; the library keeps as unit tests only
//! those that reach private items. A library's unit-test binary compiles again, optimised, every
//! function its tests reach, where these link the library's compiled copy. One test binary per
//! crate (one link instead of one per file); each module is one subject.

mod alloc;
mod analytic;
mod cache;
mod geometry;
mod kirchhoff_rough;
mod kirchhoff_shadowing;
mod kirchhoff_vs_models;
mod ray_model;
mod ray_transmission;
mod table;
