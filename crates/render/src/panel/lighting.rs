//! The lights a coating is judged under, each an equirectangular environment map drawn by the
//! program (grey, so that the colour is the coating's own: in the spectral mode a grey light is
//! D65, [`crate::spectral`]) and the albedo of the floor the panel stands on.
//!
//! - **studio**: a dark studio with two softboxes, one behind the panel that it mirrors toward
//!   the camera, one behind the camera lighting it from the viewer's side. Dark, so that a
//!   metallic's flop shows (what it sends away from the specular direction).
//! - **booth**: a colour-matching booth (ASTM D1729, "Visual appraisal of colors and color
//!   differences of diffusely-illuminated opaque materials": a diffuse overhead source, a
//!   neutral grey interior of Munsell N5 to N7). The whole upper sky is lit, so the panel shows
//!   its colour at every angle and its gloss as the bright edge of the ceiling.
//!
//! The maps are in W m⁻² sr⁻¹ on the scale of the panel scene's exposure (one stop up, filmic).

use crate::image::Image;
use std::sync::{Arc, OnceLock};

/// A light setting of the panel pictures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Lighting {
    /// A dark studio with two softboxes.
    Studio,
    /// A colour-matching booth: a diffuse ceiling over a grey interior.
    Booth,
}

/// The map's size: 256 × 128 pixels (1.4° each), finer than any edge of the lights drawn.
const MAP: (usize, usize) = (256, 128);

impl Lighting {
    /// Every setting, in the order a user is offered them.
    pub const ALL: [Lighting; 2] = [Lighting::Studio, Lighting::Booth];

    /// Its name in the API (`"studio"`, `"booth"`).
    pub fn name(self) -> &'static str {
        match self {
            Lighting::Studio => "studio",
            Lighting::Booth => "booth",
        }
    }

    /// One line saying what it is and what it shows.
    pub fn description(self) -> &'static str {
        match self {
            Lighting::Studio => {
                "dark studio with two softboxes: the gloss as a mirrored softbox, a metallic's \
                 flop against the dark"
            }
            Lighting::Booth => {
                "colour-matching booth (ASTM D1729): a diffuse ceiling over grey walls, the \
                 colour seen at every angle"
            }
        }
    }

    /// The setting called `name` (as [`Lighting::name`] gives it).
    pub fn from_name(name: &str) -> Option<Lighting> {
        Lighting::ALL.into_iter().find(|l| l.name() == name)
    }

    /// The file name of its map beside a scene.
    pub fn map_file(self) -> &'static str {
        match self {
            Lighting::Studio => "dark_studio.hdr",
            Lighting::Booth => "light_booth.hdr",
        }
    }

    /// The albedo of the floor (Lambertian, grey): the studio's black floor, the booth's N6.
    pub fn floor_albedo(self) -> f64 {
        match self {
            Lighting::Studio => 0.12,
            // Munsell N6: luminous reflectance 0.30 (ASTM D1535's table of the Munsell value).
            Lighting::Booth => 0.30,
        }
    }

    /// The radiance (grey) toward polar angle `theta_deg` from the zenith (+y) and azimuth
    /// `phi_deg` from +x toward +z (the renderer's equirectangular mapping; the camera of the
    /// panel scene looks along −z, so φ = 270° is ahead of it and 90° behind it).
    pub fn radiance(self, theta_deg: f64, phi_deg: f64) -> f64 {
        match self {
            Lighting::Studio => studio(theta_deg, phi_deg),
            Lighting::Booth => booth(theta_deg, Lighting::Booth.floor_albedo()),
        }
    }

    /// The map (256 × 128, linear), drawn once per setting.
    pub fn map(self) -> Arc<Image> {
        static MAPS: [OnceLock<Arc<Image>>; 2] = [OnceLock::new(), OnceLock::new()];
        let slot = Lighting::ALL
            .iter()
            .position(|&l| l == self)
            .expect("in ALL");
        MAPS[slot].get_or_init(|| Arc::new(self.draw())).clone()
    }

    /// Draw the map, each pixel the radiance at its centre.
    fn draw(self) -> Image {
        draw(|theta, phi| self.radiance(theta, phi))
    }
}

/// The booth's map (as [`Lighting::Booth`]'s) with an interior of luminous reflectance
/// `interior` (the viewing booth's Munsell grey, [`crate::booth`]).
pub(crate) fn booth_map(interior: f64) -> Image {
    draw(|theta, _| booth(theta, interior))
}

/// Draw a map (256 × 128), each pixel `radiance(θ, φ)` (degrees) at its centre.
fn draw(radiance: impl Fn(f64, f64) -> f64) -> Image {
    let (w, h) = MAP;
    let mut image = Image::new(w, h);
    for j in 0..h {
        let theta = 180.0 * (j as f64 + 0.5) / h as f64;
        for i in 0..w {
            let phi = 360.0 * (i as f64 + 0.5) / w as f64;
            image.pixels[j * w + i] = [radiance(theta, phi) as f32; 3];
        }
    }
    image
}

impl std::fmt::Display for Lighting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The dark studio.
fn studio(theta_deg: f64, phi_deg: f64) -> f64 {
    let within = |t: (f64, f64), p: (f64, f64)| {
        (t.0..=t.1).contains(&theta_deg) && (p.0..=p.1).contains(&phi_deg)
    };
    if within((35.0, 65.0), (235.0, 305.0)) {
        4.0 // behind the panels, mirrored by them toward the camera
    } else if within((25.0, 55.0), (65.0, 115.0)) {
        3.0 // behind the camera
    } else if theta_deg < 90.0 {
        0.03 + 0.03 * (theta_deg.to_radians()).cos()
    } else {
        0.01
    }
}

/// The booth: a ceiling diffuser of radiance 1 within 35° of the zenith; grey walls of
/// luminous reflectance ρ below it, lit by the ceiling: a Lambertian wall facing the horizon
/// under the ceiling's cap sees about `E = π sin²35° · 0.5` (half the cap above its horizon), so
/// its radiance is `ρ E / π = 0.5 ρ sin²35°` = 0.05 for N6 (ρ 0.30); the floor below the
/// horizon, under the whole cap (`E = π sin²35°`), `ρ sin²35°` = 0.10.
fn booth(theta_deg: f64, rho: f64) -> f64 {
    let cap = 35f64.to_radians().sin().powi(2);
    if theta_deg <= 35.0 {
        1.0
    } else if theta_deg < 90.0 {
        0.5 * rho * cap
    } else {
        rho * cap
    }
}
