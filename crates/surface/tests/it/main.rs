//! Integration tests of gonio-surface: the instrument-file readers against the fixtures, SurfaceTopography and corrupted input; atomic writes. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod afm_formats;
mod atomic_write;
mod binary_formats;
mod corrupt;
mod fixture_tools;
mod formats_x3p_sdf_gwyddion;
mod profiler_formats;
mod real_world_variants;
mod surfacetopography;
