//! One view's files in one call: the absolute XYZ OpenEXR and, for each display, the rendering
//! and its mask, named after the view, with what each display could not show.

use super::{DisplayPicture, DisplaySpace, XyzPicture, write_xyz_exr};
use crate::error::Result;
use std::path::{Path, PathBuf};

/// A display rendering's files and what was clipped.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayFiles {
    pub space: DisplaySpace,
    /// The PNG with the display's ICC profile.
    pub png: PathBuf,
    /// The mask of out-of-gamut and over-range pixels.
    pub mask: PathBuf,
    pub out_of_gamut_fraction: f64,
    pub over_range_fraction: f64,
}

/// The files of one view.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewFiles {
    /// The absolute XYZ picture (OpenEXR).
    pub exr: PathBuf,
    /// One per display of [`DisplaySpace::ALL`].
    pub displays: Vec<DisplayFiles>,
}

impl ViewFiles {
    /// Every file written, the OpenEXR first (the outputs of a manifest).
    pub fn paths(&self) -> Vec<&Path> {
        let mut paths = vec![self.exr.as_path()];
        for d in &self.displays {
            paths.push(&d.png);
            paths.push(&d.mask);
        }
        paths
    }
}

/// Write the view `name`'s files into the folder `dir`: `NAME.exr` (absolute XYZ), and for
/// each display `NAME-srgb.png`, `NAME-srgb-mask.png`, `NAME-p3.png`, `NAME-p3-mask.png`;
/// `white` is the perfect diffuser's XYZ in cd/m² in the booth, shown as the display's white.
pub fn write_view(
    dir: &Path,
    name: &str,
    picture: &XyzPicture,
    white: [f64; 3],
) -> Result<ViewFiles> {
    let exr = dir.join(format!("{name}.exr"));
    write_xyz_exr(&exr, picture)?;
    let displays = DisplaySpace::ALL
        .into_iter()
        .map(|space| {
            let shown = DisplayPicture::new(picture, white, space)?;
            let png = dir.join(format!("{name}-{}.png", space.file_stem()));
            let mask = dir.join(format!("{name}-{}-mask.png", space.file_stem()));
            shown.write_png(&png)?;
            shown.write_mask(&mask)?;
            Ok(DisplayFiles {
                space,
                png,
                mask,
                out_of_gamut_fraction: shown.out_of_gamut_fraction(),
                over_range_fraction: shown.over_range_fraction(),
            })
        })
        .collect::<Result<_>>()?;
    Ok(ViewFiles { exr, displays })
}
