//! Set-up shared by the renderer's integration tests: the white furnace scene, scene parsing
//! and render options.

use gonio_render::{ColourMode, RenderOptions, Scene};
use std::path::Path;

/// The white furnace of `examples/furnace.toml` (shared with the command line's tests): a unit
/// sphere of albedo 1 seen from 4 m in a uniform sky of radiance 1, every pixel 1.
pub const FURNACE: &str = include_str!("../../../../../examples/furnace.toml");

/// A scene from TOML text (relative paths resolve against the working directory).
pub fn scene(text: &str) -> Scene {
    Scene::from_toml(text, Path::new("test.toml")).unwrap()
}

/// `spp` samples per pixel, seed `seed`, colour mode `colour`, the rest default.
pub fn opts(spp: u32, seed: u32, colour: ColourMode) -> RenderOptions {
    RenderOptions {
        spp: Some(spp),
        seed: Some(seed),
        colour,
        ..RenderOptions::default()
    }
}
