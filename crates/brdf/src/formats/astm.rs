//! The ASTM-style text of the Cornell gonioreflectometer measurements (Cornell University Program
//! of Computer Graphics reflectance data): `KEY value` header lines, a
//! `VARS theta_i,phi_i,theta_s,phi_s,400nm,...` line naming the columns, then one
//! comma-separated line per geometry with angles in radians and the BRDF in 1/sr per band.
//!
//! Directions: the light is at (theta_i, phi_i) and the detector at (theta_s, phi_s), both
//! measured from the normal; the mirror direction of the light is at phi_i + 180° (the files'
//! peaks sit at phi_s = 180° for phi_i = 0).

use super::scattered::{FitResidual, Sample, import_samples};
use crate::error::{BrdfError, Result};
use crate::table::coords::dir;
use crate::table::{BrdfTable, Channels, Provenance, Resolution};
use std::collections::BTreeMap;
use std::path::Path;

/// A parsed ASTM file.
#[derive(Debug, Clone)]
pub struct AstmFile {
    /// Header keys and values (`SAMPLE_NAME`, `LAB_COMMENTS`, ...).
    pub header: BTreeMap<String, String>,
    /// Band wavelengths in nm.
    pub wavelengths_nm: Vec<f64>,
    /// The measured geometries.
    pub samples: Vec<Sample>,
}

/// Read and check an ASTM file.
pub fn read(path: &Path) -> Result<AstmFile> {
    let text = std::fs::read_to_string(path).map_err(|e| BrdfError::io(path, e))?;
    parse(&text, path)
}

/// Parse the text of an ASTM file (`path` only names it in errors).
pub fn parse(text: &str, path: &Path) -> Result<AstmFile> {
    let bad = |line: usize, p: String| BrdfError::format(path, format!("line {line}: {p}"));
    let mut header = BTreeMap::new();
    let mut wavelengths_nm = None;
    let mut samples = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        let n = i + 1;
        if line.is_empty() {
            continue;
        }
        let starts_numeric = line.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '.');
        if !starts_numeric {
            let (key, value) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
            if key == "VARS" {
                wavelengths_nm = Some(parse_vars(value).map_err(|p| bad(n, p))?);
            }
            header.insert(key.to_string(), value.trim().to_string());
            continue;
        }
        let Some(wl) = &wavelengths_nm else {
            return Err(bad(n, "data before the VARS line".into()));
        };
        let nums: Vec<f64> = line
            .split(',')
            .map(|s| s.trim().parse::<f64>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|e| bad(n, format!("not a number: {e}")))?;
        if nums.len() != 4 + wl.len() {
            return Err(bad(
                n,
                format!("{} values, VARS names {}", nums.len(), 4 + wl.len()),
            ));
        }
        if nums[..4]
            .iter()
            .any(|a| a.abs() > 2.0 * std::f64::consts::PI)
        {
            return Err(bad(
                n,
                "angle beyond 2π: the angles must be in radians".into(),
            ));
        }
        samples.push(Sample {
            wi: dir(nums[0], nums[1]),
            wo: dir(nums[2], nums[3]),
            values: nums[4..].to_vec(),
        });
    }
    let wavelengths_nm = wavelengths_nm
        .ok_or_else(|| BrdfError::format(path, "no VARS line: not a Cornell ASTM file"))?;
    if let Some(count) = header
        .get("NUM_POINTS")
        .and_then(|v| v.parse::<usize>().ok())
        && count != samples.len()
    {
        return Err(BrdfError::format(
            path,
            format!(
                "NUM_POINTS says {count} but {} data lines follow (truncated?)",
                samples.len()
            ),
        ));
    }
    Ok(AstmFile {
        header,
        wavelengths_nm,
        samples,
    })
}

/// The wavelengths of a VARS list `theta_i,phi_i,theta_s,phi_s,400nm,...`.
fn parse_vars(vars: &str) -> std::result::Result<Vec<f64>, String> {
    let names: Vec<&str> = vars.split(',').map(str::trim).collect();
    if names.len() < 5 || names[..4] != ["theta_i", "phi_i", "theta_s", "phi_s"] {
        return Err(format!(
            "VARS must start theta_i,phi_i,theta_s,phi_s and name bands: '{vars}'"
        ));
    }
    names[4..]
        .iter()
        .map(|n| {
            n.strip_suffix("nm")
                .and_then(|w| w.parse::<f64>().ok())
                .ok_or_else(|| format!("band '{n}' is not of the form 550nm"))
        })
        .collect()
}

/// Import: the smoothing fit of the file's samples resampled on an isotropic spectral table;
/// returns the table and the fit residual at the measured points (also stored in the
/// table's provenance as `fit_median_relative_residual` and `fit_rms_relative_residual`).
pub fn import(path: &Path, res: Resolution) -> Result<(BrdfTable, FitResidual)> {
    let file = read(path)?;
    let mut prov = Provenance::new(path.display().to_string(), "import:astm");
    prov.description = file.header.get("SAMPLE_NAME").cloned();
    let channels = Channels::Spectral {
        wavelengths_nm: file.wavelengths_nm,
    };
    import_samples(path, &file.samples, channels, res, prov)
}

/// Resolution of imported tables, 90 × 90 × 48. The measurements are about 10° apart, but a
/// high-gloss paint's specular peak is far narrower: 90 theta_h nodes (square-root spacing,
/// nodes at 0.011°, 0.044°, 0.10°, 0.18°) and theta_d every 1° keep the peak round where the
/// 45 × 45 grid bent it (Cayman, a ring 0.2° from specular at 60°: 11% variation from the grid
/// alone at 45 × 45, 0.3% at 90 × 90; docs/brdf-tables.md). phi_d every 7.5° resolves the
/// measured azimuths (48 and 96 nodes give the same ring to 0.1%).
pub fn default_resolution() -> Resolution {
    Resolution::isotropic(90, 90, 48)
}
