//! A multi-angle target: what a measured panel, a competitor's colour or a specification says a
//! coating should look like at each geometry, for comparing a formulation with it (`gonio
//! coating match`, the lab's target). It is read from a CSV of CIELAB per geometry, from a CSV
//! of reflectance factors per geometry (the layout `gonio multiangle --spectra` writes), or from
//! a measured BRDF read at a standard's geometries ([`Target::from_reading`] of
//! [`crate::multiangle::read_table`]). Colour is CIELAB under D65 for the 10° observer, the
//! standards' choice ([`Settings::default`]). A target read from reflectance factors (a spectral
//! CSV, a reading) keeps them ([`Target::spectra`]) for a spectral match.
//!
//! CSV layouts (a header line, then one line per geometry; `#` starts a comment line):
//! - `geometry,L,a,b` (or `L*`, `a*`, `b*`): CIELAB D65/10° at each geometry, named as
//!   `45as15` (illumination and aspecular angle, degrees);
//! - `geometry,R_400nm,R_410nm,...` (or bare wavelengths `400,410,...`): reflectance factors
//!   (1 = the perfect diffuser, not percent) at wavelengths spanning 400–700 nm at most 10 nm
//!   apart, turned into CIELAB here. Other columns (`illumination_deg`, `aspecular_deg`) are
//!   ignored.

use crate::error::{InstrumentError, Result};
use crate::multiangle::{Geometry, MultiangleReading, Settings};
use gonio_color::{Lab, SpectralToXyz, ciede2000, white};
use std::path::Path;

/// A target's colour at each of its geometries.
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    /// Where it came from (a file's name).
    pub source: String,
    /// CIELAB (D65/10°) at each geometry, in the file's order.
    pub colours: Vec<(Geometry, Lab)>,
    /// The reflectance factors behind the colours, when the target gives them (a spectral CSV,
    /// a reading); `None` for a CIELAB CSV.
    pub spectra: Option<Spectra>,
}

/// A target's reflectance factors: one spectrum per geometry, in the order of
/// [`Target::colours`], at `wavelengths_nm`.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectra {
    /// Increasing, nm.
    pub wavelengths_nm: Vec<f64>,
    /// Reflectance factors (1 = the perfect diffuser), one row per geometry.
    pub reflectance_factors: Vec<Vec<f64>>,
}

impl Target {
    /// The target a reading gives (a measured BRDF read at a standard's geometries).
    pub fn from_reading(source: impl Into<String>, reading: &MultiangleReading) -> Target {
        Target {
            source: source.into(),
            colours: reading
                .geometries
                .iter()
                .map(|g| (g.geometry, g.lab))
                .collect(),
            spectra: Some(Spectra {
                wavelengths_nm: reading.wavelengths_nm.clone(),
                reflectance_factors: reading
                    .geometries
                    .iter()
                    .map(|g| g.reflectance_factor.clone())
                    .collect(),
            }),
        }
    }

    /// The geometries of the target, in order.
    pub fn geometries(&self) -> Vec<Geometry> {
        self.colours.iter().map(|(g, _)| *g).collect()
    }

    /// Read a target CSV (the layouts of the module's documentation).
    pub fn read_csv(path: &Path) -> Result<Target> {
        let text = std::fs::read_to_string(path).map_err(|error| InstrumentError::Io {
            path: path.display().to_string(),
            error,
        })?;
        Target::parse_csv(&text, &path.display().to_string())
    }

    /// Parse a target CSV's text; `source` names it in errors.
    pub fn parse_csv(text: &str, source: &str) -> Result<Target> {
        let bad = |line: usize, message: String| InstrumentError::Read {
            path: source.to_string(),
            message: format!("line {line}: {message}"),
        };
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (header_line, header) = lines.next().ok_or_else(|| {
            bad(
                1,
                "empty: give a header line and one line per geometry".into(),
            )
        })?;
        let names: Vec<String> = header.split(',').map(|s| s.trim().to_string()).collect();
        let find = |want: &[&str]| names.iter().position(|n| want.contains(&n.as_str()));
        let geometry = find(&["geometry"]).ok_or_else(|| {
            bad(
                header_line,
                "no 'geometry' column (write e.g. geometry,L,a,b)".into(),
            )
        })?;
        let lab = (find(&["L", "L*"]), find(&["a", "a*"]), find(&["b", "b*"]));
        let bands: Vec<(usize, f64)> = names
            .iter()
            .enumerate()
            .filter_map(|(i, n)| {
                let nm = n.strip_prefix("R_").unwrap_or(n);
                let nm = nm.strip_suffix("nm").unwrap_or(nm);
                nm.parse::<f64>().ok().map(|w| (i, w))
            })
            .collect();
        let spectral = match lab {
            (Some(l), Some(a), Some(b)) => Err([l, a, b]),
            _ => {
                let wl: Vec<f64> = bands.iter().map(|b| b.1).collect();
                let spans = wl.first().is_some_and(|&w| w <= 400.0)
                    && wl.last().is_some_and(|&w| w >= 700.0)
                    && wl
                        .windows(2)
                        .all(|p| p[1] > p[0] && p[1] - p[0] <= 10.0 + 1e-9);
                if !spans {
                    return Err(bad(
                        header_line,
                        "give columns L, a, b (CIELAB D65/10°) or reflectance factors \
                         R_400nm, R_410nm, ... R_700nm (increasing, at most 10 nm apart)"
                            .into(),
                    ));
                }
                let settings = Settings::default();
                let to_xyz = SpectralToXyz::new(&wl, settings.illuminant, settings.observer)
                    .map_err(|e| bad(header_line, e.to_string()))?;
                Ok((to_xyz, white(settings.illuminant, settings.observer)))
            }
        };
        let mut colours = Vec::new();
        let mut factors = Vec::new();
        for (n, line) in lines {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if cells.len() != names.len() {
                return Err(bad(
                    n,
                    format!("{} cells, the header has {}", cells.len(), names.len()),
                ));
            }
            let number = |i: usize| {
                cells[i]
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| bad(n, format!("{}: '{}' is not a number", names[i], cells[i])))
            };
            let g = Geometry::parse(cells[geometry]).map_err(|e| bad(n, e.to_string()))?;
            let colour = match &spectral {
                Err([l, a, b]) => Lab {
                    l: number(*l)?,
                    a: number(*a)?,
                    b: number(*b)?,
                },
                Ok((to_xyz, white)) => {
                    let r = bands
                        .iter()
                        .map(|&(i, _)| number(i))
                        .collect::<Result<Vec<f64>>>()?;
                    let lab = to_xyz
                        .xyz(&r)
                        .map_err(|e| bad(n, e.to_string()))?
                        .to_lab(*white);
                    factors.push(r);
                    lab
                }
            };
            if colours.iter().any(|(h, _)| *h == g) {
                return Err(bad(n, format!("geometry {g} appears twice")));
            }
            colours.push((g, colour));
        }
        if colours.is_empty() {
            return Err(bad(header_line, "no geometries after the header".into()));
        }
        let spectra = spectral.is_ok().then(|| Spectra {
            wavelengths_nm: bands.iter().map(|b| b.1).collect(),
            reflectance_factors: factors,
        });
        Ok(Target {
            source: source.to_string(),
            colours,
            spectra,
        })
    }

    /// CIEDE2000 of `reading` from the target at each of the target's geometries, in order. The
    /// reading must hold every geometry of the target (read it at [`Target::geometries`]).
    pub fn de00(&self, reading: &MultiangleReading) -> Result<Vec<f64>> {
        self.colours
            .iter()
            .map(|&(g, lab)| {
                let r = reading.at(g).ok_or_else(|| {
                    InstrumentError::Invalid(format!(
                        "the reading has no geometry {g} of the target {}",
                        self.source
                    ))
                })?;
                Ok(ciede2000(r.lab, lab))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiangle::{E2194, read_lambertian};

    /// A grey Lambertian surface of reflectance 0.3 read at E2194 ([`read_lambertian`]), written as reflectance
    /// factors and as CIELAB, gives the same target both ways (the spectral CSV's colour is
    /// computed as the reading's), and its own reading is ΔE00 0 from it. L* of a 0.3
    /// reflectance factor is 116·0.3^(1/3) − 16 = 61.65 (CIE 15:2004, Y/Yn above 0.008856).
    #[test]
    fn lab_and_spectral_csv_give_the_same_target() {
        let wl: Vec<f64> = (0..31).map(|i| 400.0 + 10.0 * i as f64).collect();
        let grey = vec![0.3; wl.len()];
        let reading = read_lambertian(&grey, &wl, &E2194, &Settings::default()).unwrap();
        let mut spectral = String::from("# a grey tile\ngeometry,illumination_deg");
        for w in &wl {
            spectral.push_str(&format!(",R_{w}nm"));
        }
        let mut lab = String::from("geometry,L*,a*,b*\n");
        spectral.push('\n');
        for g in &reading.geometries {
            spectral.push_str(&format!("{},45", g.geometry));
            for r in &g.reflectance_factor {
                spectral.push_str(&format!(",{r}"));
            }
            spectral.push('\n');
            lab.push_str(&format!(
                "{},{},{},{}\n",
                g.geometry, g.lab.l, g.lab.a, g.lab.b
            ));
        }
        let a = Target::parse_csv(&spectral, "grey.csv").unwrap();
        let b = Target::parse_csv(&lab, "grey.csv").unwrap();
        assert_eq!(a.geometries(), E2194.to_vec());
        assert_eq!(b.spectra, None);
        let kept = a.spectra.as_ref().unwrap();
        assert_eq!(kept.wavelengths_nm, wl);
        assert_eq!(
            kept.reflectance_factors,
            Target::from_reading("grey", &reading)
                .spectra
                .unwrap()
                .reflectance_factors
        );
        let expected_l = 116.0 * 0.3f64.cbrt() - 16.0;
        for ((_, x), (_, y)) in a.colours.iter().zip(&b.colours) {
            assert!(
                (x.l - y.l).abs() < 1e-9 && (x.l - expected_l).abs() < 1e-6,
                "{x:?}"
            );
        }
        assert!(a.de00(&reading).unwrap().iter().all(|d| d.abs() < 1e-9));
        let fewer = read_lambertian(&grey, &wl, &E2194[..2], &Settings::default()).unwrap();
        assert!(read_lambertian(&grey[1..], &wl, &E2194, &Settings::default()).is_err());
        assert!(a.de00(&fewer).unwrap_err().to_string().contains("45as45"));
    }

    /// Bad CSVs are errors naming the file, the line and what to write.
    #[test]
    fn bad_target_csvs_say_what_is_wrong() {
        let err = |text: &str| Target::parse_csv(text, "t.csv").unwrap_err().to_string();
        assert!(err("").contains("t.csv: line 1: empty"));
        assert!(err("L,a,b\n1,2,3\n").contains("no 'geometry' column"));
        assert!(err("geometry,L\n45as15,50\n").contains("give columns L, a, b"));
        assert!(err("geometry,R_400nm,R_700nm\n45as15,0.1,0.2\n").contains("at most 10 nm"));
        let e = err("geometry,L,a,b\n45as15,50,1\n");
        assert!(e.contains("line 2: 3 cells, the header has 4"), "{e}");
        let e = err("geometry,L,a,b\n45as15,50,x,1\n");
        assert!(e.contains("line 2: a: 'x' is not a number"), "{e}");
        assert!(err("geometry,L,a,b\n45xx15,50,1,1\n").contains("line 2"));
        assert!(err("geometry,L,a,b\n45as15,50,1,1\n45as15,50,1,1\n").contains("twice"));
        assert!(err("geometry,L,a,b\n").contains("no geometries"));
    }
}
