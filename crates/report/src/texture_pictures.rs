//! The pictures of the virtual texture camera ([`gonio_render::texture`]) as `gonio texture -o`
//! and the demo write them: each exposed so that its median shows mid-grey.

use crate::Result;
use crate::output::create_dir;
use gonio_render::texture::TextureReading;
use gonio_render::texture_metrics::luminance;
use gonio_render::{Display, Image, ToneCurve};
use std::path::Path;

/// The display of a texture picture: exposed so that its median luminance shows as mid-grey
/// (the surround between the sparkles, which outshine it a thousandfold, or the diffuse
/// picture's mean tone), filmic.
pub fn median_grey(image: &Image) -> Display {
    let mut y: Vec<f64> = image.pixels.iter().map(|&p| luminance(p)).collect();
    y.sort_by(f64::total_cmp);
    let median = y.get(y.len() / 2).copied().unwrap_or(0.0).max(1e-12);
    Display {
        exposure: (0.18 / median).log2(),
        tone: ToneCurve::Filmic,
    }
}

/// The pictures as PNG (sparkle_15.png, sparkle_45.png, sparkle_75.png, diffuse.png), each
/// exposed by [`median_grey`].
pub fn write_pictures(r: &TextureReading, dir: &Path) -> Result<()> {
    create_dir(dir)?;
    let png = |image: &Image, name: &str| -> Result<()> {
        image.write(&dir.join(name), median_grey(image))?;
        Ok(())
    };
    for s in &r.sparkle {
        png(&s.image, &format!("sparkle_{}.png", s.angle_deg))?;
    }
    png(&r.diffuse, "diffuse.png")
}
