//! Integration tests of gonio-render: the renderer against conservation laws and independent renders, scene files, spectral rendering. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod camera;
mod common;
mod denoise;
mod difference;
mod geometry;
mod image;
mod render;
mod scene;
mod spectral;
