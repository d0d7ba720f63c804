//! Integration tests of gonio-render: the renderer against conservation laws and independent
//! renders, scene files, spectral rendering, and its parts through the public API (camera,
//! shapes, images and their files, the denoiser, picture differences).
//!
//! Every test that the public API can express lives here; the library keeps as unit tests only
//! those that reach private items. A library's unit-test binary compiles again, optimised, every
//! function its tests reach, where these link the library's compiled copy. One test binary per
//! crate (one link instead of one per file); each module is one subject.

mod booth;
mod booth_doi;
mod camera;
mod common;
mod denoise;
mod difference;
mod flakes;
mod geometry;
mod image;
mod mesoscale;
mod oracle;
mod panel;
mod picture_display;
mod picture_exr;
mod picture_manifest;
mod render;
mod scene;
mod spectral;
mod texture;
mod texture_glint;
