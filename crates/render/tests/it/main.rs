//! Integration tests of gonio-render: the renderer against conservation laws and independent renders, scene files, spectral rendering. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod common;
mod render;
mod scene;
mod spectral;
