//! Pictures that are measurements: the files the virtual viewing booth writes for each view
//! (issue 44, point 1), from a picture of absolute CIE XYZ in cd/m².
//!
//! - [`write_xyz_exr`]: the absolute XYZ as OpenEXR (channels X, Y, Z in f32, cd/m², the
//!   chromaticities of the XYZ primaries and `whiteLuminance` = 1 in its header);
//! - [`DisplayPicture`]: the picture on an sRGB or Display P3 display through Little CMS, the
//!   booth's white shown as the display's white, written as PNG with its ICC profile embedded,
//!   beside a mask of the out-of-gamut and over-range pixels;
//! - [`write_view`]: the three above for one view (the OpenEXR, and a rendering and a mask per
//!   display), named after it;
//! - [`write_manifest`]: the SHA-256 of every input and output file, gonio's version, the seed
//!   and the settings, so that a picture can be reproduced and checked.
//!
//! The colour management lives here rather than in gonio-color: gonio-color is the pure-Rust
//! colour science at the bottom of the workspace (no file formats, no C), and these are a
//! picture's output files (OpenEXR, PNG with iCCP, JSON), written like the renderer's other
//! images; the ICC profiles and the Little CMS transforms serve only them.

mod display;
mod manifest;
mod profile;
mod view;
mod xyz_exr;

pub(crate) use display::write_png;
pub use display::{DisplayPicture, MASK_BOTH, MASK_OUT_OF_GAMUT, MASK_OVER_RANGE};
pub use manifest::{MANIFEST_FORMAT, sha256_file, write_manifest};
pub use profile::{DisplaySpace, ICC_CREATED, RENDERING_INTENT};
pub use view::{DisplayFiles, ViewFiles, write_view};
pub use xyz_exr::{UNITS_ATTRIBUTE, write_xyz_exr};

use crate::error::{RenderError, Result};
use gonio_color::Observer;

/// A picture of absolute CIE XYZ tristimulus values in cd/m² (Y is the luminance), row-major,
/// top row first, seen by `observer`; checked when made ([`XyzPicture::new`]).
#[derive(Clone, Copy, Debug)]
pub struct XyzPicture<'a> {
    width: usize,
    height: usize,
    xyz: &'a [[f32; 3]],
    observer: Observer,
}

impl<'a> XyzPicture<'a> {
    /// The picture, checked: a positive size, `width × height` pixels, every value finite.
    pub fn new(
        width: usize,
        height: usize,
        xyz: &'a [[f32; 3]],
        observer: Observer,
    ) -> Result<Self> {
        if width == 0 || height == 0 {
            return Err(RenderError::Invalid(format!(
                "an XYZ picture of {width} × {height} pixels is empty"
            )));
        }
        if width.checked_mul(height) != Some(xyz.len()) {
            return Err(RenderError::Invalid(format!(
                "an XYZ picture of {width} × {height} pixels needs {} values, not {}",
                width as u128 * height as u128,
                xyz.len()
            )));
        }
        if let Some(i) = xyz.iter().position(|p| p.iter().any(|v| !v.is_finite())) {
            return Err(RenderError::Invalid(format!(
                "the XYZ picture's pixel ({}, {}) (column, row) is not finite: {:?}",
                i % width,
                i / width,
                xyz[i]
            )));
        }
        Ok(XyzPicture {
            width,
            height,
            xyz,
            observer,
        })
    }

    /// The width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// The height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The pixels' XYZ in cd/m², row-major, top row first.
    pub fn xyz(&self) -> &'a [[f32; 3]] {
        self.xyz
    }

    /// The observer.
    pub fn observer(&self) -> Observer {
        self.observer
    }

    /// The observer in words (ASCII), as the files' headers name it.
    pub fn observer_name(&self) -> &'static str {
        match self.observer {
            Observer::Cie1931TwoDegree => "CIE 1931 2 degree standard colorimetric observer",
            Observer::Cie1964TenDegree => {
                "CIE 1964 10 degree supplementary standard colorimetric observer"
            }
        }
    }
}
