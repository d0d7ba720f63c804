//! The MERL BRDF database's `.binary` files (Matusik, Pfister, Brand & McMillan, "A data-driven
//! reflectance model", SIGGRAPH 2003; layout as read by the database's public `BRDFRead.cpp`):
//!
//! - three little-endian i32: the node counts along theta_h, theta_d and phi_d (90, 90, 180);
//! - then 3 × the product of those f64 values, all red, then all green, then all blue, each
//!   index `phi_d + n_phi_d (theta_d + n_theta_d theta_h)`;
//! - stored values times the channel scales 1/1500, 1.15/1500, 1.66/1500 are the BRDF in 1/sr;
//!   negative values mark cells without a measurement.
//!
//! MERL readers take a negative value for a missing measurement, so colours outside the sRGB
//! gamut (a saturated paint's linear sRGB has a negative component) cannot be written as they
//! are: [`write()`] maps each such colour into the gamut at constant luminance, moving it toward
//! the grey of its own luminance `Y = 0.2126 R + 0.7152 G + 0.0722 B` (IEC 61966-2-1) just far
//! enough that its smallest component is 0: `rgb' = Y + t (rgb − Y)`, `t = Y / (Y − min)`. Hue
//! (the direction of `rgb − Y` in the chromaticity plane) and luminance are kept, chroma is
//! reduced as little as the gamut demands; a colour of non-positive luminance (noise in a dark
//! cell) becomes black. The export reports how many cells it mapped.
//!
//! theta_h node j lies at `90° (j/n)²`, theta_d node j at `90° j/n`, phi_d node j at `180° j/n`:
//! phi_d covers half a turn because MERL assumes reciprocity (phi_d and phi_d + 180° are the
//! same pair with wi and wo swapped). These are the nodes of gonio's own grid, so an isotropic
//! table of `n_theta_h × n_theta_d × 2 n_phi_d` cells maps onto a MERL file cell for cell.

use crate::error::{BrdfError, Result};
use crate::gbrdf::write_atomic;
use crate::table::{BrdfTable, Cell, Channels, HalfDiff, Provenance, Resolution, TableBuilder};
use std::io::Write;
use std::path::Path;

/// The channel scales of the MERL files (stored value × scale = f in 1/sr).
pub const SCALES: [f64; 3] = [1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0];

/// Node counts of the MERL database files.
pub const DIMS: [usize; 3] = [90, 90, 180];

/// Read a MERL `.binary` file into an isotropic RGB table of `n_theta_h × n_theta_d ×
/// 2 n_phi_d` cells; negative (unmeasured) values become "no data".
pub fn read(path: &Path) -> Result<BrdfTable> {
    let bytes = std::fs::read(path).map_err(|e| BrdfError::io(path, e))?;
    let bad = |p: String| BrdfError::format(path, p);
    if bytes.len() < 12 {
        return Err(bad(
            "too short for a MERL .binary file (12-byte header)".into()
        ));
    }
    let dim = |k: usize| i32::from_le_bytes(bytes[4 * k..4 * k + 4].try_into().expect("4 bytes"));
    let dims = [dim(0), dim(1), dim(2)];
    if dims.iter().any(|&d| !(1..=10_000).contains(&d)) {
        return Err(bad(format!(
            "implausible dimensions {dims:?} in the header (not a MERL file?)"
        )));
    }
    let [nh, nd, np] = dims.map(|d| d as usize);
    let n = nh * nd * np;
    if bytes.len() != 12 + 3 * 8 * n {
        return Err(bad(format!(
            "header says {nh} × {nd} × {np} cells ({} bytes) but the file has {} bytes",
            12 + 24 * n,
            bytes.len()
        )));
    }
    let value = |c: usize, i: usize| {
        let o = 12 + 8 * (c * n + i);
        f64::from_le_bytes(bytes[o..o + 8].try_into().expect("8 bytes"))
    };
    let res = Resolution::isotropic(nh, nd, 2 * np);
    let mut b = TableBuilder::new(res, Channels::Rgb)
        .map_err(|e| bad(e.to_string()))?
        .with_provenance(Provenance::new(path.display().to_string(), "import:merl"));
    let stored: Vec<usize> = b.cells().map(|c| c.index).collect();
    for cell in stored {
        let [_, th, td, pd] = res.cell_indices(cell);
        let i = (th * nd + td) * np + pd % np;
        for (c, scale) in SCALES.iter().enumerate() {
            let v = value(c, i);
            let v = if v < 0.0 { f64::NAN } else { v * scale };
            b.set(cell, c, v)?;
        }
    }
    b.build()
}

/// What [`write()`] did to fit the table into the format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct MerlExport {
    /// Cells written (above the horizon).
    pub cells: usize,
    /// Of these, cells whose colour was outside the sRGB gamut and was mapped into it.
    pub out_of_gamut: usize,
}

/// `rgb` mapped into the sRGB gamut at constant luminance (module docs); unchanged when no
/// component is negative.
pub fn into_gamut(rgb: glam::DVec3) -> glam::DVec3 {
    let min = rgb.min_element();
    if min >= 0.0 {
        return rgb;
    }
    let y = rgb.dot(glam::DVec3::new(0.2126, 0.7152, 0.0722));
    if y <= 0.0 {
        return glam::DVec3::ZERO;
    }
    let grey = glam::DVec3::splat(y);
    // The smallest component of grey + t (rgb - grey) is y + t (min - y) = 0.
    let t = y / (y - min);
    (grey + t * (rgb - grey)).max(glam::DVec3::ZERO)
}

/// Write `table` as a MERL `.binary` file of the standard 90 × 90 × 180 cells: each cell holds
/// the mean of the table at its pair of directions and at the swapped pair (MERL stores one
/// value for both), in linear sRGB mapped into its gamut ([`into_gamut`]); cells below the
/// horizon hold -1.
pub fn write(table: &BrdfTable, path: &Path) -> Result<MerlExport> {
    let [nh, nd, np] = DIMS;
    let res = Resolution::isotropic(nh, nd, 2 * np);
    let nc = table.channel_count();
    let n = nh * nd * np;
    let mut out = vec![-1.0f64; 3 * n];
    let mut buf = vec![0.0; nc];
    let mut report = MerlExport {
        cells: 0,
        out_of_gamut: 0,
    };
    for th in 0..nh {
        for td in 0..nd {
            for pd in 0..np {
                let cell = res.cell_index(0, th, td, pd);
                let a = res.cell_angles(cell);
                let (wi, wo) = a.to_dirs();
                if !(Cell {
                    index: cell,
                    wi,
                    wo,
                    angles: a,
                })
                .is_above_horizon()
                {
                    continue;
                }
                let mut rgb = glam::DVec3::ZERO;
                for phi_d in [a.phi_d, a.phi_d + std::f64::consts::PI] {
                    table.eval_angles(&HalfDiff { phi_d, ..a }, &mut buf);
                    rgb += table.to_rgb(&buf) * 0.5;
                }
                report.cells += 1;
                if rgb.min_element() < 0.0 {
                    report.out_of_gamut += 1;
                    rgb = into_gamut(rgb);
                }
                let i = (th * nd + td) * np + pd;
                for c in 0..3 {
                    out[c * n + i] = rgb[c] / SCALES[c];
                }
            }
        }
    }
    write_atomic(path, |w| {
        for d in DIMS {
            w.write_all(&(d as i32).to_le_bytes())?;
        }
        let mut bytes = Vec::with_capacity(8 * out.len());
        out.iter()
            .for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
        w.write_all(&bytes)
    })?;
    Ok(report)
}
