//! The files of the isotropy check ([`gonio_instrument::isotropy`]) that `gonio isotropy` and
//! the demo write: each turn's curves against the original's as a plot, and every curve as CSV.

use crate::Result;
use crate::output::write_atomic;
use crate::plots::plot_pairs;
use gonio_instrument::isotropy::RotationCheck;
use gonio_scatter::InplaneCurve;
use std::io::Write;
use std::path::Path;

/// Both orientations' reflectance curves on a log axis: original as lines, turned as dots, one
/// colour per incidence.
pub fn plot_check(path: &Path, c: &RotationCheck) -> Result<()> {
    let pairs: Vec<(&InplaneCurve, &InplaneCurve)> =
        c.rotated.curves.iter().zip(&c.original.curves).collect();
    let title = format!(
        "In-plane reflectance: original (lines) and turned by {}° (dots)",
        c.angle_deg
    );
    plot_pairs(path, &title, &pairs, |curve, turned| {
        if turned {
            format!("turned {}°, {}°", c.angle_deg, curve.incidence_deg)
        } else {
            format!("original, {}°", curve.incidence_deg)
        }
    })
}

/// The curves of every check, original and turned, as CSV (the `--csv` output).
pub fn write_csv(path: &Path, checks: &[RotationCheck]) -> Result<()> {
    write_atomic(path, |w| {
        writeln!(
            w,
            "rotation_deg,orientation,method,wavelength_nm,incidence_deg,scatter_deg,\
             brdf_per_sr,reflectance,rel_uncertainty"
        )?;
        for c in checks {
            for (name, o) in [("original", &c.original), ("rotated", &c.rotated)] {
                for curve in &o.curves {
                    let wl = curve.wavelength_nm.map_or(String::new(), |v| v.to_string());
                    for p in &curve.points {
                        let unc = p
                            .rel_uncertainty
                            .filter(|u| u.is_finite())
                            .map_or(String::new(), |u| format!("{u:.6e}"));
                        writeln!(
                            w,
                            "{},{name},{},{wl},{},{},{:.8e},{:.8e},{unc}",
                            c.angle_deg,
                            curve.method,
                            curve.incidence_deg,
                            p.scatter_deg,
                            p.brdf_per_sr,
                            p.reflectance
                        )?;
                    }
                }
            }
        }
        Ok(())
    })
}
