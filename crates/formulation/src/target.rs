//! What a match aims at: a multi-angle colour read from a file at a standard's geometries
//! ([`read_target`]: a CSV of CIELAB or of reflectance factors, a measured BRDF in Cornell's
//! ASTM text or a spectral `.gbrdf` table) and, optionally, gloss-meter readings
//! ([`GlossTarget`], `20=85,60=92`).

use crate::error::{FormulationError, Result};
use gonio_brdf::formats::astm;
use gonio_brdf::table::BrdfTable;
use gonio_instrument::multiangle::{self, Geometry, Settings};
use gonio_instrument::multiangle_target::{Spectra, Target};
use std::path::Path;

/// The target `all` at `geometries` only, in their order, with its spectra when it has them;
/// every one of them must be in it (others are left out). The error names the target and the
/// geometries it holds.
pub fn at_geometries(all: Target, geometries: &[Geometry]) -> Result<Target> {
    let indices = geometries
        .iter()
        .map(|&g| {
            all.colours
                .iter()
                .position(|(h, _)| *h == g)
                .ok_or_else(|| {
                    FormulationError::Invalid(format!(
                        "{}: the target has no geometry {g} (it holds {}; give every geometry \
                     of the standard)",
                        all.source,
                        all.geometries()
                            .iter()
                            .map(Geometry::to_string)
                            .collect::<Vec<_>>()
                            .join(", ")
                    ))
                })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Target {
        source: all.source.clone(),
        colours: indices.iter().map(|&i| all.colours[i]).collect(),
        spectra: all.spectra.map(|s| Spectra {
            reflectance_factors: indices
                .iter()
                .map(|&i| s.reflectance_factors[i].clone())
                .collect(),
            wavelengths_nm: s.wavelengths_nm,
        }),
    })
}

/// Read the target `path` at `geometries`, by its extension:
/// - `.csv`: [`Target::read_csv`] (CIELAB or reflectance factors per geometry); it must hold
///   every one of `geometries` (others it holds are left out of the match);
/// - `.astm`: a measured BRDF (Cornell's ASTM text), imported as `gonio brdf import` imports it
///   (fitted and resampled onto [`astm::default_resolution`]) and read at `geometries` with
///   [`multiangle::read_table`] (D65/10°, point apertures);
/// - `.gbrdf`: a spectral BRDF table, read the same way.
pub fn read_target(path: &Path, geometries: &[Geometry]) -> Result<Target> {
    let name = path.display().to_string();
    let invalid = |e: &dyn std::fmt::Display| FormulationError::Invalid(format!("{name}: {e}"));
    if geometries.is_empty() {
        return Err(invalid(&"a target needs at least one geometry"));
    }
    if gonio_io::extension(path) == "csv" {
        return at_geometries(Target::read_csv(path)?, geometries);
    }
    let table = measured_table(path)?;
    let reading = multiangle::read_table(&table, geometries, &Settings::default())
        .map_err(|e| invalid(&e))?;
    Ok(Target::from_reading(name, &reading))
}

/// The measured BRDF `path` as a table: `.astm` (Cornell's ASTM text) imported as `gonio brdf
/// import` imports it (fitted and resampled onto [`astm::default_resolution`]), `.gbrdf` read;
/// any other extension refused, naming the target's formats.
pub(crate) fn measured_table(path: &Path) -> Result<BrdfTable> {
    let name = path.display().to_string();
    let invalid = |e: &dyn std::fmt::Display| FormulationError::Invalid(format!("{name}: {e}"));
    match gonio_io::extension(path).as_str() {
        "astm" => Ok(astm::import(path, astm::default_resolution())
            .map_err(|e| invalid(&e))?
            .0),
        "gbrdf" => gonio_brdf::gbrdf::read(path).map_err(|e| invalid(&e)),
        _ => Err(invalid(
            &"a target is a .csv (CIELAB or reflectance factors per geometry), a measured \
              BRDF (.astm) or a spectral table (.gbrdf)",
        )),
    }
}

/// A gloss-meter reading the match should reproduce (ISO 2813).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlossTarget {
    /// 20, 60 or 85°.
    pub angle: u32,
    /// Gloss units.
    pub gu: f64,
}

impl GlossTarget {
    /// Read `20=85,60=92`: gloss units at 20, 60 or 85°, each angle at most once.
    pub fn parse_list(s: &str) -> Result<Vec<GlossTarget>> {
        let mut all: Vec<GlossTarget> = Vec::new();
        for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let invalid = |why: &str| {
                FormulationError::Invalid(format!(
                    "gloss '{part}': {why} (write ANGLE=GU, e.g. 20=85,60=92)"
                ))
            };
            let (angle, gu) = part.split_once('=').ok_or_else(|| invalid("no '='"))?;
            let angle: u32 = angle
                .trim()
                .parse()
                .ok()
                .filter(|a| [20, 60, 85].contains(a))
                .ok_or_else(|| invalid("the angle is 20, 60 or 85"))?;
            let gu: f64 = gu
                .trim()
                .parse()
                .ok()
                .filter(|g: &f64| g.is_finite() && *g >= 0.0)
                .ok_or_else(|| invalid("the gloss is a non-negative number of GU"))?;
            if all.iter().any(|t| t.angle == angle) {
                return Err(invalid("this angle is given twice"));
            }
            all.push(GlossTarget { angle, gu });
        }
        Ok(all)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gloss_targets_are_read_and_bad_ones_refused() {
        assert_eq!(
            GlossTarget::parse_list("20=85, 60=92.5").unwrap(),
            vec![
                GlossTarget {
                    angle: 20,
                    gu: 85.0
                },
                GlossTarget {
                    angle: 60,
                    gu: 92.5
                }
            ]
        );
        for bad in ["45=80", "20", "20=x", "20=-1", "20=1,20=2"] {
            let e = GlossTarget::parse_list(bad).unwrap_err().to_string();
            assert!(e.contains("ANGLE=GU"), "{bad}: {e}");
        }
    }

    /// A CSV target is cut to the standard's geometries, and one that lacks a geometry of the
    /// standard is refused, naming the file and the geometry.
    #[test]
    fn csv_targets_must_hold_the_standards_geometries() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.csv");
        std::fs::write(
            &path,
            "geometry,L,a,b\n45as15,90,1,2\n45as45,50,1,2\n45as110,20,1,2\n",
        )
        .unwrap();
        let two = [Geometry::new(45.0, 110.0), Geometry::new(45.0, 15.0)];
        let t = read_target(&path, &two).unwrap();
        assert_eq!(t.geometries(), two.to_vec());
        assert_eq!(t.colours[1].1.l, 90.0);
        assert_eq!(t.spectra, None);
        let e = read_target(&path, &multiangle::E2194)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("t.csv") && e.contains("no geometry 45as25"),
            "{e}"
        );
        let e = read_target(&dir.path().join("t.txt"), &two)
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.txt") && e.contains(".astm"), "{e}");
    }
}
