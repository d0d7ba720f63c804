//! The booth's absolute picture as OpenEXR: CIE XYZ in cd/m², one f32 channel each for X, Y
//! and Z, written with the `exr` crate.
//!
//! The header follows OpenEXR's standard attributes ("Standard Optional Attributes",
//! <https://openexr.com/en/latest/StandardOptionalAttributes.html>): `chromaticities` gives the
//! CIE (x, y) of the pixel values (1, 0, 0), (0, 1, 0), (0, 0, 1) and (1, 1, 1), and
//! `whiteLuminance` the luminance in cd/m² of the value (1, 1, 1). For XYZ data the
//! "primaries" are the XYZ primaries themselves, red (1, 0), green (0, 1), blue (0, 0), white
//! (1/3, 1/3) (the chromaticities OpenEXR's `ImfChromaticities` maps to the identity RGB → XYZ
//! matrix), and with `whiteLuminance` = 1 the matrix carries no scale: a pixel's Y is its
//! luminance in cd/m². A custom string attribute ([`UNITS_ATTRIBUTE`]) says so in words and
//! names the observer. The pixels are ZIP-compressed (lossless), so the file holds the
//! renderer's values bit for bit.

use super::XyzPicture;
use crate::error::{RenderError, Result};
use exr::meta::attribute::Chromaticities;
use exr::prelude::*;
use std::path::Path;

/// The name of the header's custom string attribute saying the unit and the observer.
pub const UNITS_ATTRIBUTE: &str = "gonioUnits";

/// Write `picture` to `path` (atomically, through gonio-io) as an OpenEXR file of absolute
/// CIE XYZ in cd/m².
pub fn write_xyz_exr(path: &Path, picture: &XyzPicture) -> Result<()> {
    let width = picture.width();
    let xyz = picture.xyz();
    let channels = SpecificChannels::build()
        .with_channel("X")
        .with_channel("Y")
        .with_channel("Z")
        .with_pixel_fn(|p: Vec2<usize>| {
            let [x, y, z] = xyz[p.y() * width + p.x()];
            (x, y, z)
        });
    let mut attributes = LayerAttributes {
        white_luminance: Some(1.0),
        ..LayerAttributes::default()
    };
    attributes.other.insert(
        Text::from(UNITS_ATTRIBUTE),
        AttributeValue::Text(Text::from(units_text(picture).as_str())),
    );
    let encoding = Encoding {
        compression: Compression::ZIP16,
        ..Encoding::default()
    };
    let layer = Layer::new((width, picture.height()), attributes, encoding, channels);
    let mut image = Image::from_layer(layer);
    image.attributes.chromaticities = Some(Chromaticities {
        red: Vec2(1.0, 0.0),
        green: Vec2(0.0, 1.0),
        blue: Vec2(0.0, 0.0),
        white: Vec2(1.0 / 3.0, 1.0 / 3.0),
    });
    gonio_io::write_atomic(
        path,
        |out| {
            image.write().to_buffered(out).map_err(|e| {
                RenderError::image(path, format!("cannot encode the OpenEXR file: {e}"))
            })
        },
        |e| RenderError::Io {
            path: path.to_path_buf(),
            error: e,
        },
    )
}

/// The [`UNITS_ATTRIBUTE`] text (ASCII, as OpenEXR's text attributes are bytes).
fn units_text(picture: &XyzPicture) -> String {
    format!(
        "absolute CIE XYZ tristimulus values in cd/m^2 (Y is the luminance); {}",
        picture.observer_name()
    )
}
