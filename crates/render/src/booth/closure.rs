//! The picture's side of the booth's closure against the multi-angle instrument
//! (`docs/standard.md`, closure (b)): a flat panel of a material under the collimated light
//! alone at a geometry's illumination, seen by the distant (orthographic) camera at its
//! aspecular angle, its pixels averaged and turned into CIELAB against the perfect diffuser
//! under the same light and observer, with the noise bound of that mean.
//!
//! The instrument's side (`gonio_instrument::multiangle`) sits beside this crate, not below it,
//! so the comparison of the two is composed above both (`gonio_report::closure`); the tests of
//! this crate compare the two themselves.
//!
//! The noise bound: with a distant light and camera and a flat panel, every pixel the specimen
//! covers estimates the same XYZ, so the standard error of the mean of X, Y and Z follows from
//! their spread over the pixels (the sample variance over the pixels' number). The bound is the
//! largest CIEDE2000 difference (CIE 142:2001) between the mean and the mean moved by three
//! standard errors in one of X, Y, Z, either sign.

use super::{BoothSpec, BoothView, Run, render};
use crate::error::Result;
use crate::material::Material;
use gonio_color::{Lab, Xyz, ciede2000};

/// The closure picture's size and samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosurePicture {
    /// Width and height, pixels (the square picture holds the panel with a fifth to spare).
    pub size: usize,
    /// Samples per pixel.
    pub spp: u32,
    /// The illuminance on the specimen, lx (it cancels in CIELAB against the white).
    pub illuminance_lux: f64,
}

impl Default for ClosurePicture {
    /// 24 × 24 pixels at 32 samples: the closure tests' picture (noise bound about 0.1 ΔE00 for
    /// a solid, 0.3 for a metallic near the specular).
    fn default() -> Self {
        ClosurePicture {
            size: 24,
            spp: 32,
            illuminance_lux: 2000.0,
        }
    }
}

/// The mean of a specimen's pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpecimenMean {
    /// The mean X, Y, Z, cd/m² (NaN when no pixel is covered).
    pub xyz: [f64; 3],
    /// The standard error of each mean, from the pixels' spread, cd/m² (NaN when fewer than
    /// two pixels are covered).
    pub standard_error: [f64; 3],
    /// The pixels the specimen covers whole.
    pub pixels: usize,
}

/// What the picture reads at one geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PictureReading {
    /// CIELAB of the mean against the perfect diffuser under the same light and observer.
    pub lab: Lab,
    /// The largest ΔE00 from moving the mean by three standard errors in X, Y or Z.
    pub noise_bound: f64,
    /// The mean itself.
    pub mean: SpecimenMean,
}

/// The mean of X, Y, Z over the pixels `view`'s specimen covers whole, and the standard error
/// of each mean from the pixels' spread (the sample variance over the pixels' number). The
/// one computation of a specimen's mean: the closure reads it, and so does the booth's summary
/// ([`super::write_booth`]). Where a view covers too few pixels, the undefined values are NaN
/// (see [`SpecimenMean`]); [`read_flat_panel`] refuses fewer than two.
pub fn specimen_mean(view: &BoothView) -> SpecimenMean {
    let pixels: Vec<[f64; 3]> = view
        .image
        .xyz
        .iter()
        .zip(&view.specimen)
        .filter(|(_, on)| **on)
        .map(|(p, _)| p.map(f64::from))
        .collect();
    let n = pixels.len() as f64;
    let xyz: [f64; 3] = std::array::from_fn(|c| {
        if pixels.is_empty() {
            f64::NAN
        } else {
            pixels.iter().map(|p| p[c]).sum::<f64>() / n
        }
    });
    let standard_error = std::array::from_fn(|c| {
        if pixels.len() < 2 {
            return f64::NAN;
        }
        let var = pixels.iter().map(|p| (p[c] - xyz[c]).powi(2)).sum::<f64>() / (n - 1.0);
        (var / n).sqrt()
    });
    SpecimenMean {
        xyz,
        standard_error,
        pixels: pixels.len(),
    }
}

/// The booth of the closure at one geometry: D65, the collimated light alone at
/// `illumination_deg` from the normal, a flat panel seen by the orthographic camera at the
/// aspecular angle `aspecular_deg`, the 10° observer.
pub fn flat_panel_spec(
    illumination_deg: f64,
    aspecular_deg: f64,
    picture: &ClosurePicture,
) -> BoothSpec {
    let mut spec = BoothSpec::default();
    spec.light.illuminance_lux = picture.illuminance_lux;
    spec.light.directional_fraction = 1.0;
    spec.light.directional_deg = illumination_deg;
    spec.camera.projection = "orthographic".into();
    spec.camera.views = vec![format!("as{aspecular_deg}")];
    spec.render.width = picture.size;
    spec.render.height = picture.size;
    spec.render.spp = picture.spp;
    spec
}

/// What the picture of a flat panel of `material` reads at the geometry (`illumination_deg`,
/// `aspecular_deg`): its pixels' mean as CIELAB against the booth's white, with the noise bound.
pub fn read_flat_panel(
    material: &Material,
    illumination_deg: f64,
    aspecular_deg: f64,
    picture: &ClosurePicture,
    run: &Run,
) -> Result<PictureReading> {
    let spec = flat_panel_spec(illumination_deg, aspecular_deg, picture);
    let pictures = render(&spec, material, run)?;
    let white = Xyz::from_array(pictures.white);
    let view = &pictures.views[0];
    let mean = specimen_mean(view);
    if mean.pixels < 2 {
        return Err(crate::RenderError::Invalid(format!(
            "the view {} covers {} pixels of the specimen whole: too few for a mean and its spread",
            view.name, mean.pixels
        )));
    }
    let lab = |xyz: [f64; 3]| -> Lab { Xyz::from_array(xyz).to_lab(white) };
    let at_mean = lab(mean.xyz);
    let noise_bound = (0..3)
        .flat_map(|c| [-3.0, 3.0].map(move |k| (c, k)))
        .map(|(c, k)| {
            let mut moved = mean.xyz;
            moved[c] += k * mean.standard_error[c];
            ciede2000(lab(moved), at_mean)
        })
        .fold(0.0, f64::max);
    Ok(PictureReading {
        lab: at_mean,
        noise_bound,
        mean,
    })
}
