//! The display colour spaces of the booth's display renderings, as ICC profiles built with
//! Little CMS (the `lcms2` crate), and the rendering intent their transforms use.
//!
//! Both displays share sRGB's white and transfer curve and differ in their primaries:
//! - sRGB, IEC 61966-2-1:1999: primaries (0.64, 0.33), (0.30, 0.60), (0.15, 0.06), white D65
//!   (0.3127, 0.3290) — the same data as Little CMS's built-in `cmsCreate_sRGBProfile`;
//! - Display P3 (Apple; the DCI-P3 primaries of SMPTE EG 432-1:2010 with a D65 white and the
//!   sRGB curve): primaries (0.680, 0.320), (0.265, 0.690), (0.150, 0.060), white D65.
//!
//! The curve is IEC 61966-2-1's: V = 12.92 L for L ≤ 0.0031308, else 1.055 L^(1/2.4) − 0.055,
//! stored as the ICC parametric curve of type 4 (ICC.1:2010 table 65) with g = 2.4,
//! a = 1/1.055, b = 0.055/1.055, c = 1/12.92, d = 0.04045. Each space also has a linear twin
//! (the same primaries and white, the identity curve): the source of the Little CMS transform
//! that encodes the clipped linear display values.

use crate::error::{RenderError, Result};
use lcms2::{CIExyY, CIExyYTRIPLE, Intent, Locale, MLU, Profile, Tag, TagSignature, ToneCurve};

/// The rendering intent of every display rendering: ICC relative colorimetric. The booth's
/// white (after the exposure and the chromatic adaptation of [`super::DisplayPicture`]) lands
/// on the display's white, colours inside the display's gamut are reproduced exactly, and
/// those outside are clipped channel by channel in the display's linear RGB (and flagged in the
/// mask). Perceptual would compress in-gamut colours too, which a picture that is a
/// measurement must not do; and these matrix/TRC profiles carry no perceptual table, so Little
/// CMS would fall back to the colorimetric transform anyway (ICC.1:2010 section 8.3).
pub const RENDERING_INTENT: Intent = Intent::RelativeColorimetric;

/// The creation date and time written in the embedded profiles' header (ICC.1:2010 section
/// 7.2.8, bytes 24 to 35: year, month, day, hours, minutes, seconds, each a big-endian u16, UTC):
/// the day these profiles' definition was last changed, fixed so that a PNG does not depend on
/// when it was written.
pub const ICC_CREATED: [u16; 6] = [2026, 12, 6, 0, 0, 0];

/// The display a rendering is made for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DisplaySpace {
    /// sRGB (IEC 61966-2-1).
    Srgb,
    /// Display P3 (P3 primaries, D65 white, sRGB curve).
    DisplayP3,
}

/// CIE D65 as the displays' white, (x, y) = (0.3127, 0.3290) (IEC 61966-2-1).
const D65: CIExyY = CIExyY {
    x: 0.3127,
    y: 0.3290,
    Y: 1.0,
};

impl DisplaySpace {
    /// Both displays, in the order the booth writes them.
    pub const ALL: [DisplaySpace; 2] = [DisplaySpace::Srgb, DisplaySpace::DisplayP3];

    /// A short name for file names ("srgb", "p3").
    pub fn file_stem(self) -> &'static str {
        match self {
            DisplaySpace::Srgb => "srgb",
            DisplaySpace::DisplayP3 => "p3",
        }
    }

    /// The profile's description, as written in its `desc` tag.
    pub fn description(self) -> &'static str {
        match self {
            DisplaySpace::Srgb => "sRGB IEC 61966-2-1 (gonio, Little CMS)",
            DisplaySpace::DisplayP3 => {
                "Display P3: P3 primaries, D65, sRGB curve (gonio, Little CMS)"
            }
        }
    }

    /// The CIE (x, y) of the red, green and blue primaries.
    pub fn primaries(self) -> [[f64; 2]; 3] {
        match self {
            DisplaySpace::Srgb => [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],
            DisplaySpace::DisplayP3 => [[0.680, 0.320], [0.265, 0.690], [0.150, 0.060]],
        }
    }

    /// The display's ICC profile (version 4, matrix/TRC, the sRGB curve).
    pub fn profile(self) -> Result<Profile> {
        let curve =
            ToneCurve::new_parametric(4, &[2.4, 1.0 / 1.055, 0.055 / 1.055, 1.0 / 12.92, 0.04045])
                .map_err(|e| RenderError::Invalid(format!("Little CMS: the sRGB curve: {e}")))?;
        self.build(&curve, self.description())
    }

    /// The display's ICC profile as a PNG embeds it: [`DisplaySpace::profile`]'s bytes with the
    /// creation date and time [`ICC_CREATED`] in the header instead of the clock's, which Little CMS
    /// stamps (and has no setter for). So the same picture is the same bytes from run to run, as
    /// the manifest's SHA-256 of each PNG expects. Little CMS leaves the header's profile ID
    /// (its MD5, which would cover the date) zero, so no checksum needs recomputing.
    pub fn icc(self) -> Result<Vec<u8>> {
        let mut bytes = self.profile()?.icc().map_err(|e| {
            RenderError::Invalid(format!("Little CMS: the {self:?} profile's bytes: {e}"))
        })?;
        if bytes.len() < 128 || bytes[84..100].iter().any(|&b| b != 0) {
            return Err(RenderError::Invalid(format!(
                "Little CMS: the {self:?} profile's header is not the 128 bytes with a zero \
                 profile ID that its creation date can be set in"
            )));
        }
        for (k, v) in ICC_CREATED.iter().enumerate() {
            bytes[24 + 2 * k..26 + 2 * k].copy_from_slice(&v.to_be_bytes());
        }
        Ok(bytes)
    }

    /// The display's linear twin: its primaries and white with the identity curve, whose RGB
    /// is the display's linear RGB (relative to its white).
    pub fn linear_profile(self) -> Result<Profile> {
        self.build(&ToneCurve::new(1.0), "linear")
    }

    fn build(self, curve: &ToneCurve, description: &str) -> Result<Profile> {
        let [r, g, b] = self.primaries();
        let xy = |[x, y]: [f64; 2]| CIExyY { x, y, Y: 1.0 };
        let primaries = CIExyYTRIPLE {
            Red: xy(r),
            Green: xy(g),
            Blue: xy(b),
        };
        let mut profile = Profile::new_rgb(&D65, &primaries, &[curve, curve, curve])
            .map_err(|e| RenderError::Invalid(format!("Little CMS: the {self:?} profile: {e}")))?;
        let mut text = MLU::new(1);
        text.set_text_ascii(description, Locale::none());
        if !profile.write_tag(TagSignature::ProfileDescriptionTag, Tag::MLU(&text)) {
            return Err(RenderError::Invalid(format!(
                "Little CMS: cannot describe the {self:?} profile"
            )));
        }
        Ok(profile)
    }
}
