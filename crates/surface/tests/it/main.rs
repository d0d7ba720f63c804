//! Integration tests of gonio-surface: the instrument-file readers against the fixtures,
//! SurfaceTopography and corrupted input; atomic writes; height maps, their operations, profile
//! statistics and synthetic surfaces through the public API.
//!
//! Every test that the public API can express lives here; the library keeps as unit tests only
//! those that reach private items. A library's unit-test binary compiles again, optimised, every
//! function its tests reach, where these link the library's compiled copy. One test binary per
//! crate (one link instead of one per file); each module is one subject.

mod afm_formats;
mod atomic_write;
mod binary_formats;
mod corrupt;
mod extreme_spacings;
mod fixture_tools;
mod formats_x3p_sdf_gwyddion;
mod gaussian_filter;
mod heightmap;
mod ops;
mod profile_stats;
mod profiler_formats;
mod real_world_variants;
mod surfacetopography;
mod synth;
mod synth_psd;
mod turns;
mod waviness;
