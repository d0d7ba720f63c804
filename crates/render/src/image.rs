//! The rendered picture: linear RGB radiance per pixel, written as OpenEXR (linear, 32-bit
//! float), Radiance `.hdr` (linear RGBE) or PNG (exposure, a tone curve and the sRGB transfer
//! function), chosen by the file's extension. Files are written to a temporary file in the
//! target directory and renamed, so a failed write never leaves half an image.

use crate::error::{RenderError, Result};
use serde::Deserialize;
use std::path::Path;

/// A linear RGB image, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Radiance in W m⁻² sr⁻¹ per channel (linear sRGB primaries), row-major.
    pub pixels: Vec<[f32; 3]>,
}

/// The curve that maps exposed linear values to display values in [0, 1] for PNG output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ToneCurve {
    /// Clip at 1.
    Clamp,
    /// `x / (1 + x)` (Reinhard et al., "Photographic tone reproduction", SIGGRAPH 2002, eq. 3).
    Reinhard,
    /// The ACES filmic fit of K. Narkowicz ("ACES Filmic Tone Mapping Curve", 2015):
    /// `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)`.
    #[default]
    Filmic,
}

impl ToneCurve {
    /// The display value of the exposed linear value `x >= 0`.
    pub fn apply(self, x: f64) -> f64 {
        let x = x.max(0.0);
        let y = match self {
            ToneCurve::Clamp => x,
            ToneCurve::Reinhard => x / (1.0 + x),
            ToneCurve::Filmic => x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14),
        };
        y.clamp(0.0, 1.0)
    }
}

/// How linear values become PNG pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Display {
    /// Exposure in stops: values are multiplied by `2^exposure` before the tone curve.
    pub exposure: f64,
    /// The tone curve.
    pub tone: ToneCurve,
}

impl Default for Display {
    fn default() -> Self {
        Display {
            exposure: 0.0,
            tone: ToneCurve::Filmic,
        }
    }
}

impl Image {
    /// A black image.
    pub fn new(width: usize, height: usize) -> Image {
        Image {
            width,
            height,
            pixels: vec![[0.0; 3]; width * height],
        }
    }

    /// The pixel at column `x`, row `y` (row 0 at the top).
    pub fn get(&self, x: usize, y: usize) -> [f32; 3] {
        self.pixels[y * self.width + x]
    }

    /// Mean of the three channels of every pixel.
    pub fn luminance_mean(&self) -> f64 {
        let sum: f64 = self
            .pixels
            .iter()
            .map(|p| p.iter().map(|&c| f64::from(c)).sum::<f64>() / 3.0)
            .sum();
        sum / self.pixels.len().max(1) as f64
    }

    /// 8-bit sRGB of every pixel after exposure and the tone curve.
    pub fn to_srgb8(&self, display: Display) -> Vec<u8> {
        let scale = display.exposure.exp2();
        self.pixels
            .iter()
            .flat_map(|p| {
                p.map(|c| {
                    let v = display.tone.apply(f64::from(c) * scale);
                    (gonio_color::srgb::encode(v) * 255.0).round() as u8
                })
            })
            .collect()
    }

    /// The image binned `k × k`: each pixel of the result is the mean of a `k × k` block (the
    /// blocks that do not fit at the right and bottom edges are dropped). Binning the mean of
    /// `n` samples per pixel gives the mean of `k² n` samples per block, so that a comparison
    /// of two renders can trade resolution for noise without rendering again.
    pub fn binned(&self, k: usize) -> Image {
        let k = k.max(1);
        let (w, h) = (self.width / k, self.height / k);
        let mut out = Image::new(w, h);
        let norm = 1.0 / (k * k) as f32;
        for (i, p) in out.pixels.iter_mut().enumerate() {
            let (x0, y0) = ((i % w) * k, (i / w) * k);
            for y in y0..y0 + k {
                for q in &self.pixels[y * self.width + x0..y * self.width + x0 + k] {
                    for (a, b) in p.iter_mut().zip(q) {
                        *a += b * norm;
                    }
                }
            }
        }
        out
    }

    /// The PNG file of the image after exposure and the tone curve of `display`, in memory.
    pub fn png(&self, display: Display) -> Result<Vec<u8>> {
        let mut bytes = std::io::Cursor::new(Vec::new());
        self.srgb_image(display)
            .write_to(&mut bytes, image::ImageFormat::Png)
            .map_err(|e| RenderError::Invalid(format!("cannot encode the PNG: {e}")))?;
        Ok(bytes.into_inner())
    }

    /// The 8-bit sRGB image of [`Image::to_srgb8`].
    fn srgb_image(&self, display: Display) -> image::DynamicImage {
        let (w, h) = (self.width as u32, self.height as u32);
        image::DynamicImage::ImageRgb8(
            image::RgbImage::from_raw(w, h, self.to_srgb8(display)).expect("size matches"),
        )
    }

    /// Write the image; the format follows the extension: `.exr` (linear float), `.hdr`
    /// (linear RGBE) or `.png` (with `display`). The write is atomic.
    pub fn write(&self, path: &Path, display: Display) -> Result<()> {
        let ext = gonio_io::extension(path);
        let (w, h) = (self.width as u32, self.height as u32);
        let floats: Vec<f32> = self.pixels.iter().flatten().copied().collect();
        let (img, format) = match ext.as_str() {
            "exr" => (
                image::DynamicImage::ImageRgb32F(
                    image::Rgb32FImage::from_raw(w, h, floats).expect("size matches"),
                ),
                image::ImageFormat::OpenExr,
            ),
            "hdr" => (
                image::DynamicImage::ImageRgb32F(
                    image::Rgb32FImage::from_raw(w, h, floats).expect("size matches"),
                ),
                image::ImageFormat::Hdr,
            ),
            "png" => (self.srgb_image(display), image::ImageFormat::Png),
            _ => {
                return Err(RenderError::image(
                    path,
                    "unknown image extension: use .exr (linear float), .hdr (Radiance) or .png",
                ));
            }
        };
        let io = |e: std::io::Error| RenderError::Io {
            path: path.to_path_buf(),
            error: e,
        };
        gonio_io::write_atomic(
            path,
            |out| {
                img.write_to(out, format)
                    .map_err(|e| RenderError::image(path, format!("cannot encode: {e}")))
            },
            io,
        )
    }

    /// Read a linear image (`.exr`, `.hdr`; PNG and other 8-bit formats are decoded from sRGB).
    pub fn read(path: &Path) -> Result<Image> {
        let img = image::ImageReader::open(path)
            .map_err(|e| RenderError::Io {
                path: path.to_path_buf(),
                error: e,
            })?
            .with_guessed_format()
            .map_err(|e| RenderError::Io {
                path: path.to_path_buf(),
                error: e,
            })?
            .decode()
            .map_err(|e| RenderError::image(path, format!("cannot decode: {e}")))?;
        let linear = matches!(
            img,
            image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
        );
        let rgb = img.to_rgb32f();
        let (w, h) = rgb.dimensions();
        let pixels = rgb
            .pixels()
            .map(|p| {
                if linear {
                    p.0
                } else {
                    p.0.map(|c| gonio_color::srgb::decode(f64::from(c)) as f32)
                }
            })
            .collect();
        Ok(Image {
            width: w as usize,
            height: h as usize,
            pixels,
        })
    }
}
