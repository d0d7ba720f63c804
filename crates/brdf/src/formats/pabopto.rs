//! Export to the PAB-Opto goniophotometer data files that Radiance's `pabopto2bsdf` reads to
//! build its BSDF interpolant (G. Ward, Radiance `src/cv/pabopto2bsdf.c`): one text file per
//! incidence direction, with a header of `#` lines
//!
//! ```text
//! #sample_name "name"
//! #format: theta phi BSDF
//! #intheta 30
//! #inphi 0
//! ```
//!
//! then one `theta phi value` line per measured direction: angles in degrees (theta from the
//! normal, phi counter-clockwise from +x), the value a BSDF in 1/sr (photopic: the luminance
//! `0.2126 R + 0.7152 G + 0.0722 B` of the table's linear RGB). The incidence direction points
//! toward the light. Directions are a regular grid (2° in theta, 5° in phi) plus a dense polar
//! pattern within 6° of the specular direction, where glossy lobes live.

use crate::error::{BrdfError, Result};
use crate::gbrdf::write_atomic;
use crate::table::BrdfTable;
use crate::table::coords::dir;
use glam::DVec3;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Incidence angles exported by default (degrees).
pub const DEFAULT_THETA_I_DEG: [f64; 9] = [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0];

/// Write one file per incidence angle (phi_i = 0, and for anisotropic tables also 45°, 90°,
/// 135°) into the directory `out_dir` (created if needed), named `<name>_t<theta>_p<phi>.dat`.
/// Returns the paths written.
pub fn write(
    table: &BrdfTable,
    out_dir: &Path,
    name: &str,
    theta_i_deg: &[f64],
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(out_dir).map_err(|e| BrdfError::io(out_dir, e))?;
    let phis: &[f64] = if table.resolution().is_isotropic() {
        &[0.0]
    } else {
        &[0.0, 45.0, 90.0, 135.0]
    };
    let mut written = Vec::new();
    let mut buf = vec![0.0; table.channel_count()];
    for &pi in phis {
        for &ti in theta_i_deg {
            if !(0.0..90.0).contains(&ti) {
                return Err(BrdfError::Invalid(format!(
                    "incidence {ti}° outside [0, 90)°"
                )));
            }
            let path = out_dir.join(format!("{name}_t{ti}_p{pi}.dat"));
            let wi = dir(ti.to_radians(), pi.to_radians());
            write_atomic(&path, |w| {
                writeln!(w, "#sample_name \"{name}\"")?;
                writeln!(w, "#format: theta phi BSDF")?;
                writeln!(w, "#intheta {ti}")?;
                writeln!(w, "#inphi {pi}")?;
                for wo in directions(wi) {
                    table.eval_channels(wo, wi, &mut buf);
                    let rgb = table.to_rgb(&buf);
                    let y = 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
                    let theta = wo.z.clamp(-1.0, 1.0).acos().to_degrees();
                    let phi = wo.y.atan2(wo.x).to_degrees().rem_euclid(360.0);
                    writeln!(w, "{theta:.4} {phi:.4} {:.6e}", y.max(0.0))?;
                }
                Ok(())
            })?;
            written.push(path);
        }
    }
    Ok(written)
}

/// The outgoing directions of one file: a 2° × 5° grid and a polar pattern about the mirror
/// direction (rings at 0.25° to 6°, 24 azimuths each).
fn directions(wi: DVec3) -> Vec<DVec3> {
    let mut out = vec![DVec3::Z];
    for t in (1..45).map(|k| (2 * k) as f64) {
        for p in (0..72).map(|k| (5 * k) as f64) {
            out.push(dir(t.to_radians(), p.to_radians()));
        }
    }
    let mirror = DVec3::new(-wi.x, -wi.y, wi.z);
    let a = if mirror.z.abs() < 0.99 {
        DVec3::Z
    } else {
        DVec3::X
    };
    let e1 = a.cross(mirror).normalize();
    let e2 = mirror.cross(e1);
    out.push(mirror);
    for ring in [0.25f64, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0] {
        let (s, c) = ring.to_radians().sin_cos();
        for k in 0..24 {
            let p = k as f64 * std::f64::consts::TAU / 24.0;
            let d = mirror * c + (e1 * p.cos() + e2 * p.sin()) * s;
            if d.z > 0.0 {
                out.push(d);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::{Channels, Resolution, TableBuilder};

    #[test]
    fn files_have_the_header_pabopto2bsdf_reads_and_the_table_values() {
        let mut b = TableBuilder::new(Resolution::isotropic(16, 16, 16), Channels::Mono).unwrap();
        b.fill(|c, out| out[0] = 0.2 + c.wo.z);
        let t = b.build().unwrap();
        let dir_out = tempfile::tempdir().unwrap();
        let files = write(&t, dir_out.path(), "grey", &[0.0, 40.0]).unwrap();
        assert_eq!(files.len(), 2);
        let text = std::fs::read_to_string(&files[1]).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("#sample_name \"grey\""));
        assert_eq!(lines.next(), Some("#format: theta phi BSDF"));
        assert_eq!(lines.next(), Some("#intheta 40"));
        assert_eq!(lines.next(), Some("#inphi 0"));
        for line in lines.take(500) {
            let v: Vec<f64> = line.split(' ').map(|x| x.parse().unwrap()).collect();
            let want = 0.2 + v[0].to_radians().cos();
            assert!((v[2] - want).abs() < 0.01 * want, "{line}: want {want}");
        }
    }
}
