//! A booth picture on a display: absolute XYZ turned into sRGB or Display P3 through Little
//! CMS, written as an 8-bit PNG with the display's ICC profile embedded, and a mask of the
//! pixels the display cannot show.
//!
//! The display rule (the standard's, docs/standard.md "Files written"): the perfect diffuser in
//! the booth is shown as the display's white. A pixel's XYZ is divided by the perfect
//! diffuser's luminance Y_w (the exposure), adapted from the booth's white (the perfect
//! diffuser's chromaticity) to the ICC profile connection space's D50 by the linearised
//! Bradford transform (ICC.1:2010 Annex E), and taken to the display's linear RGB by the
//! inverse of the display profile's colorant matrix: the relative colorimetric intent
//! ([`super::RENDERING_INTENT`]) of a matrix/TRC profile, whose colorants Little CMS adapted
//! from D50 to the display's own D65 white by Bradford as well, so the booth's white comes out
//! as RGB (1, 1, 1) whatever the illuminant. Values outside [0, 1] in the display's linear RGB
//! are clipped channel by channel, and flagged; Little CMS then applies the display's transfer
//! curve and rounds to 8 bits (a transform from the display's linear twin to the display).
//! The flags:
//! - over range: the luminance is above the white's, Y > Y_w (a highlight brighter than the
//!   perfect diffuser);
//! - out of gamut: a linear channel below 0 (a chromaticity outside the display's triangle), or
//!   above 1 while Y ≤ Y_w (a colour too saturated for the display at that luminance).
//!
//! Both limits allow [`LINEAR_TOLERANCE`] before a pixel is flagged.

use super::XyzPicture;
use super::profile::{DisplaySpace, RENDERING_INTENT};
use crate::error::{RenderError, Result};
use glam::{DMat3, DVec3};
use gonio_color::Xyz;
use gonio_color::adaptation::bradford_matrix;
use image::ImageEncoder;
use lcms2::{PixelFormat, Profile, Tag, TagSignature, Transform};
use std::path::Path;

/// The ICC profile connection space's illuminant, D50 as ICC.1:2010 section 7.2.16 fixes it.
const PCS_D50: [f64; 3] = [0.9642, 1.0, 0.8249];

/// How far a linear display value (or Y/Y_w) may pass 0 or 1 before the pixel is flagged.
/// The ICC profile stores its colorant matrix in s15Fixed16 numbers (ICC.1:2010 section 4.6),
/// each entry within 2⁻¹⁷ ≈ 7.6e-6 of the exact one, so a linear channel, a sum of three
/// products with weights up to about 3 for the inverse matrix, can be off by about
/// 3 × 3 × 7.6e-6 ≈ 7e-5 for the booth's white itself; 1e-4 lets the white and the in-gamut
/// neutrals through, and is 20 times smaller than half an 8-bit step of the encoded value
/// at the top of the scale (0.5/255 ≈ 2e-3, about 2e-3 in linear there too), so no flag is
/// missed that would change a shown value visibly.
pub const LINEAR_TOLERANCE: f64 = 1e-4;

/// The mask's colour for a pixel out of the display's gamut only (magenta).
pub const MASK_OUT_OF_GAMUT: [u8; 3] = [255, 0, 255];
/// The mask's colour for a pixel over range only, brighter than the white (yellow).
pub const MASK_OVER_RANGE: [u8; 3] = [255, 255, 0];
/// The mask's colour for a pixel both out of gamut and over range (cyan).
pub const MASK_BOTH: [u8; 3] = [0, 255, 255];

/// A pixel's flags: out of the display's gamut.
const OUT_OF_GAMUT: u8 = 1;
/// A pixel's flags: brighter than the booth's white.
const OVER_RANGE: u8 = 2;

/// A picture rendered for a display: its 8-bit encoded RGB, which pixels were clipped and why,
/// and the display's ICC profile.
#[derive(Clone, Debug)]
pub struct DisplayPicture {
    space: DisplaySpace,
    width: usize,
    height: usize,
    rgb: Vec<[u8; 3]>,
    /// Each pixel's flags (bit 0 out of gamut, bit 1 over range), as in [`Self::flagged`].
    flags: Vec<u8>,
    out_of_gamut_fraction: f64,
    over_range_fraction: f64,
    icc: Vec<u8>,
}

impl DisplayPicture {
    /// Render `picture` for `space`; `white` is the perfect diffuser's XYZ in cd/m² in the
    /// booth (the same observer as the picture), shown as the display's white.
    pub fn new(picture: &XyzPicture, white: [f64; 3], space: DisplaySpace) -> Result<Self> {
        if !(white.iter().all(|v| v.is_finite() && *v > 0.0)) {
            return Err(RenderError::Invalid(format!(
                "the booth's white must be a positive, finite XYZ in cd/m², not {white:?}"
            )));
        }
        let lcms = |what: &str, e: lcms2::Error| {
            RenderError::Invalid(format!("Little CMS: the {space:?} {what}: {e}"))
        };
        // The profiles as embedded (parsed back from their ICC bytes), so that the conversion
        // uses the colorants a reader of the PNG finds, rounded to s15Fixed16.
        let icc = space.icc()?;
        let display = Profile::new_icc(&icc).map_err(|e| lcms("profile", e))?;
        let linear_icc = space
            .linear_profile()?
            .icc()
            .map_err(|e| lcms("linear profile's bytes", e))?;
        let linear_profile =
            Profile::new_icc(&linear_icc).map_err(|e| lcms("linear profile", e))?;
        // Bradford from the white in cd/m² to D50 with Y = 1 maps the one onto the other
        // exactly, so it divides by Y_w (the exposure) as it adapts.
        let to_linear = pcs_to_linear(&display, space)?
            * DMat3::from_cols_array_2d(&bradford_matrix(
                Xyz::from_array(white),
                Xyz::from_array(PCS_D50),
            ))
            .transpose();
        let lin: Vec<[f64; 3]> = picture
            .xyz()
            .iter()
            .map(|p| (to_linear * DVec3::from_array(p.map(f64::from))).to_array())
            .collect();
        let clipped: Vec<[f64; 3]> = lin.iter().map(|l| l.map(|c| c.clamp(0.0, 1.0))).collect();
        let encode: Transform<[f64; 3], [u8; 3]> = Transform::new(
            &linear_profile,
            PixelFormat::RGB_DBL,
            &display,
            PixelFormat::RGB_8,
            RENDERING_INTENT,
        )
        .map_err(|e| lcms("transform", e))?;
        let mut rgb = vec![[0u8; 3]; clipped.len()];
        encode.transform_pixels(&clipped, &mut rgb);
        let flags: Vec<u8> = picture
            .xyz()
            .iter()
            .zip(&lin)
            .map(|(p, l)| {
                let over = f64::from(p[1]) / white[1] > 1.0 + LINEAR_TOLERANCE;
                let below = l.iter().any(|&c| c < -LINEAR_TOLERANCE);
                let above = l.iter().any(|&c| c > 1.0 + LINEAR_TOLERANCE);
                let mut f = 0;
                if below || (above && !over) {
                    f |= OUT_OF_GAMUT;
                }
                if over {
                    f |= OVER_RANGE;
                }
                f
            })
            .collect();
        let n = flags.len() as f64;
        let count = |bit: u8| flags.iter().filter(|&&f| f & bit != 0).count() as f64 / n;
        Ok(DisplayPicture {
            space,
            width: picture.width(),
            height: picture.height(),
            rgb,
            out_of_gamut_fraction: count(OUT_OF_GAMUT),
            over_range_fraction: count(OVER_RANGE),
            flags,
            icc,
        })
    }

    /// The display.
    pub fn space(&self) -> DisplaySpace {
        self.space
    }

    /// The size in pixels, (width, height).
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Encoded display RGB, 0–255, row-major, top row first.
    pub fn rgb(&self) -> &[[u8; 3]] {
        &self.rgb
    }

    /// The fraction of the pixels out of the display's gamut (with or without over range).
    pub fn out_of_gamut_fraction(&self) -> f64 {
        self.out_of_gamut_fraction
    }

    /// The fraction of the pixels brighter than the booth's white.
    pub fn over_range_fraction(&self) -> f64 {
        self.over_range_fraction
    }

    /// The display's ICC profile, as embedded in the PNG.
    pub fn icc(&self) -> &[u8] {
        &self.icc
    }

    /// Pixel `i`'s flags: (out of gamut, over range), `i` counted row-major from the top left.
    /// Panics if `i` is outside the picture.
    pub fn flagged(&self, i: usize) -> (bool, bool) {
        let f = self.flags[i];
        (f & OUT_OF_GAMUT != 0, f & OVER_RANGE != 0)
    }

    /// The mask's pixels: [`MASK_OUT_OF_GAMUT`], [`MASK_OVER_RANGE`] or [`MASK_BOTH`] where
    /// flagged, elsewhere the picture in dark grey (a quarter of its mean encoded value, at
    /// most 63) so that the flags can be placed.
    pub fn mask(&self) -> Vec<[u8; 3]> {
        (0..self.rgb.len())
            .map(|i| match self.flagged(i) {
                (true, false) => MASK_OUT_OF_GAMUT,
                (false, true) => MASK_OVER_RANGE,
                (true, true) => MASK_BOTH,
                (false, false) => {
                    let [r, g, b] = self.rgb[i].map(u32::from);
                    [((r + g + b) / 12) as u8; 3]
                }
            })
            .collect()
    }

    /// Write the rendering as an 8-bit RGB PNG with the display's ICC profile in its iCCP
    /// chunk (atomically).
    pub fn write_png(&self, path: &Path) -> Result<()> {
        write_rgb_png(path, self.width, self.height, &self.rgb, Some(&self.icc))
    }

    /// Write the mask ([`Self::mask`]) as an 8-bit RGB PNG (atomically). It carries no
    /// profile: its colours are labels, not measurements.
    pub fn write_mask(&self, path: &Path) -> Result<()> {
        write_rgb_png(path, self.width, self.height, &self.mask(), None)
    }
}

/// The matrix from ICC PCS XYZ (D50, the white's Y = 1) to the display's linear RGB: the
/// inverse of the profile's colorant matrix, whose columns are its red, green and blue
/// colorant tags (ICC.1:2010 section F.3, the matrix/TRC model: PCS XYZ = [r g b] · linear RGB,
/// for the relative colorimetric intent). Little CMS computed the colorants from the primaries
/// and the white, adapted to D50 by Bradford. Little CMS's own XYZ transforms are not used for
/// this step: its XYZ input encoding ends at 1.99997 (ICC.1:2010 section 6.3.4.3) and its
/// output clips negative values, while a booth picture's highlights reach hundreds of times the
/// white and the flags need the linear values before clipping.
fn pcs_to_linear(profile: &Profile, space: DisplaySpace) -> Result<DMat3> {
    let colorant = |tag| match profile.read_tag(tag) {
        Tag::CIEXYZ(c) => Ok(DVec3::new(c.X, c.Y, c.Z)),
        _ => Err(RenderError::Invalid(format!(
            "Little CMS: the {space:?} profile has no {tag:?}"
        ))),
    };
    let m = DMat3::from_cols(
        colorant(TagSignature::RedColorantTag)?,
        colorant(TagSignature::GreenColorantTag)?,
        colorant(TagSignature::BlueColorantTag)?,
    );
    Ok(m.inverse())
}

/// An 8-bit RGB PNG, with `icc` in its iCCP chunk when given, written atomically.
fn write_rgb_png(
    path: &Path,
    width: usize,
    height: usize,
    rgb: &[[u8; 3]],
    icc: Option<&[u8]>,
) -> Result<()> {
    write_png(
        path,
        (width, height),
        rgb.as_flattened(),
        image::ExtendedColorType::Rgb8,
        icc,
    )
}

/// An 8-bit PNG of `bytes` (`colour`: grey `L8` or `Rgb8`), with `icc` in its iCCP chunk when
/// given, written atomically.
pub(crate) fn write_png(
    path: &Path,
    (width, height): (usize, usize),
    bytes: &[u8],
    colour: image::ExtendedColorType,
    icc: Option<&[u8]>,
) -> Result<()> {
    let too_large = || RenderError::image(path, format!("{width} × {height} is too large for PNG"));
    let (w, h) = (
        u32::try_from(width).map_err(|_| too_large())?,
        u32::try_from(height).map_err(|_| too_large())?,
    );
    gonio_io::write_atomic(
        path,
        |out| {
            let mut encoder = image::codecs::png::PngEncoder::new(out);
            if let Some(icc) = icc {
                encoder.set_icc_profile(icc.to_vec()).map_err(|e| {
                    RenderError::image(path, format!("cannot embed the ICC profile: {e}"))
                })?;
            }
            encoder
                .write_image(bytes, w, h, colour)
                .map_err(|e| RenderError::image(path, format!("cannot encode the PNG: {e}")))
        },
        |e| RenderError::Io {
            path: path.to_path_buf(),
            error: e,
        },
    )
}
