//! Set-up shared by the renderer's integration tests: the white furnace scene, scene parsing
//! and render options.

use gonio_render::{ColourMode, RenderOptions, Scene};
use std::path::Path;

/// A unit sphere seen from 4 m in a uniform sky of radiance 1.
pub const FURNACE: &str = r#"
[camera]
position = [0.0, 0.0, 4.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 32
width = 40
height = 40

[materials.m]
brdf = { model = "lambert", albedo = 1.0 }

[[shapes]]
type = "sphere"
material = "m"

[[lights]]
type = "sky"
radiance = 1.0
"#;

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
