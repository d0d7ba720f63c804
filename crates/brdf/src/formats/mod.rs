//! Exchange formats of tabulated BRDFs: import of the Cornell ASTM measurements, MERL `.binary`
//! and CSV samples; export to MERL, the Mitsuba 3 / pbrt-v4 tensor `.bsdf`, Radiance's XML BSDF
//! (tensor tree), Radiance PAB-Opto data files and CSV. Scattered samples become tables through [`scattered`].

pub mod astm;
pub mod csv;
pub mod lobe_model;
pub mod merl;
pub mod mitsuba;
pub mod pabopto;
pub mod radiance_xml;
pub mod scattered;
pub mod tensor;

/// The material's name in a Radiance export (the XML BSDF's and the PAB-Opto files'): the stem
/// of `path`, "brdf" where it has none.
pub fn radiance_name(path: &std::path::Path) -> &str {
    path.file_stem().and_then(|s| s.to_str()).unwrap_or("brdf")
}
