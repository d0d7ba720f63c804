//! A simple CSV of BRDF samples, one geometry per row:
//! `theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,<channel columns>`, angles in degrees from the
//! normal and from +x (`i`: toward the light, `o`: toward the detector), values in 1/sr. The
//! channel columns are `f_per_sr` (monochrome), `r_per_sr,g_per_sr,b_per_sr` (RGB) or
//! `f_<wavelength>nm_per_sr` (spectral). Lines starting with `#` are comments.
//!
//! Export writes the table on a regular angular grid; import treats the rows as scattered
//! samples and builds a table with the smoothing interpolation of [`super::scattered`].

use super::scattered::{FitResidual, Sample, import_samples};
use crate::error::{BrdfError, Result};
use crate::gbrdf::write_atomic;
use crate::table::coords::dir;
use crate::table::{BrdfTable, Channels, Provenance, Resolution};
use std::io::Write;
use std::path::Path;

/// The angle columns, in order.
pub const ANGLE_COLUMNS: [&str; 4] = ["theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg"];

/// Write `table` at every combination of theta_i in [0, 85]°, theta_o in [0, 85]° and phi_o
/// in [0, 360)° on steps of `step_deg`, with phi_i = 0.
pub fn write(table: &BrdfTable, path: &Path, step_deg: f64) -> Result<()> {
    if !(0.1..=45.0).contains(&step_deg) {
        return Err(BrdfError::Invalid(format!(
            "CSV step {step_deg}° outside 0.1–45°"
        )));
    }
    let steps = |max: f64| {
        (0..)
            .map(move |k| k as f64 * step_deg)
            .take_while(move |a| *a <= max + 1e-9)
    };
    let names = table.channels().column_names();
    let mut buf = vec![0.0; table.channel_count()];
    write_atomic(path, |w| {
        writeln!(w, "{},{}", ANGLE_COLUMNS.join(","), names.join(","))?;
        for ti in steps(85.0) {
            for to in steps(85.0) {
                for po in steps(360.0 - step_deg) {
                    let wi = dir(ti.to_radians(), 0.0);
                    let wo = dir(to.to_radians(), po.to_radians());
                    table.eval_channels(wo, wi, &mut buf);
                    write!(w, "{ti},0,{to},{po}")?;
                    for v in &buf {
                        write!(w, ",{v:.6e}")?;
                    }
                    writeln!(w)?;
                }
            }
        }
        Ok(())
    })
}

/// The channels named by the value columns of a header.
fn channels_of(names: &[&str]) -> std::result::Result<Channels, String> {
    let bare: Vec<&str> = names
        .iter()
        .map(|n| n.strip_suffix("_per_sr").unwrap_or(n))
        .collect();
    match bare.as_slice() {
        [_] => Ok(Channels::Mono),
        ["r", "g", "b"] => Ok(Channels::Rgb),
        _ => bare
            .iter()
            .map(|n| {
                n.strip_prefix("f_")
                    .unwrap_or(n)
                    .strip_suffix("nm")
                    .and_then(|w| w.parse::<f64>().ok())
                    .ok_or_else(|| {
                        format!("column '{n}' is neither r/g/b nor f_<wavelength>nm_per_sr")
                    })
            })
            .collect::<std::result::Result<Vec<f64>, String>>()
            .map(|wavelengths_nm| Channels::Spectral { wavelengths_nm }),
    }
}

/// Read the samples of a CSV file and their channels.
pub fn read_samples(path: &Path) -> Result<(Channels, Vec<Sample>)> {
    let text = std::fs::read_to_string(path).map_err(|e| BrdfError::io(path, e))?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
    let (_, header) = lines
        .next()
        .ok_or_else(|| BrdfError::format(path, "empty file"))?;
    let cols: Vec<&str> = header.split(',').map(str::trim).collect();
    if cols.len() < 5 || cols[..4] != ANGLE_COLUMNS {
        return Err(BrdfError::format(
            path,
            format!(
                "the header must start {} and name value columns",
                ANGLE_COLUMNS.join(",")
            ),
        ));
    }
    let channels = channels_of(&cols[4..]).map_err(|p| BrdfError::format(path, p))?;
    let mut samples = Vec::new();
    for (i, line) in lines {
        let nums: Vec<f64> = line
            .split(',')
            .map(|s| s.trim().parse::<f64>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|e| BrdfError::format(path, format!("line {}: {e}", i + 1)))?;
        if nums.len() != cols.len() {
            return Err(BrdfError::format(
                path,
                format!(
                    "line {}: {} values for {} columns",
                    i + 1,
                    nums.len(),
                    cols.len()
                ),
            ));
        }
        let r = |d: f64| d.to_radians();
        samples.push(Sample {
            wi: dir(r(nums[0]), r(nums[1])),
            wo: dir(r(nums[2]), r(nums[3])),
            values: nums[4..].to_vec(),
        });
    }
    Ok((channels, samples))
}

/// Import: the rows as scattered samples, smoothed and resampled on an isotropic table.
pub fn import(path: &Path, res: Resolution) -> Result<(BrdfTable, FitResidual)> {
    let (channels, samples) = read_samples(path)?;
    let prov = Provenance::new(path.display().to_string(), "import:csv");
    import_samples(path, &samples, channels, res, prov)
}
