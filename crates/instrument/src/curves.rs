//! In-plane curves as CSV: the columns `gonio inplane` writes
//! (`method,wavelength_nm,incidence_deg,scatter_deg,brdf_per_sr,reflectance`, optionally followed
//! by `rel_uncertainty`, `inf` for a detector that caught nothing) and the simple measured form
//! `incidence_deg,scatter_deg,reflectance`. What `write_csv` writes, `read_csv` reads back.

use crate::error::InstrumentError;
use gonio_scatter::{CurvePoint, InplaneCurve};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

/// The columns of the in-plane CSV, in order (the Python package's DataFrames take the same).
pub const COLUMNS: [&str; 7] = [
    "method",
    "wavelength_nm",
    "incidence_deg",
    "scatter_deg",
    "brdf_per_sr",
    "reflectance",
    "rel_uncertainty",
];

/// Write curves as CSV to `path` atomically ([`gonio_io::write_atomic`]).
pub fn write_csv(path: &Path, curves: &[InplaneCurve]) -> Result<(), InstrumentError> {
    let io_err = |error| InstrumentError::Io {
        path: path.display().to_string(),
        error,
    };
    gonio_io::write_atomic(path, |w| write_csv_to(w, curves).map_err(io_err), io_err)
}

/// Write curves as CSV to any writer.
pub fn write_csv_to(w: &mut impl Write, curves: &[InplaneCurve]) -> std::io::Result<()> {
    writeln!(w, "{}", COLUMNS.join(","))?;
    for c in curves {
        let wl = c.wavelength_nm.map(|v| format!("{v}")).unwrap_or_default();
        for p in &c.points {
            let unc = p
                .rel_uncertainty
                .map(|v| format!("{v:.6e}"))
                .unwrap_or_default();
            writeln!(
                w,
                "{},{},{},{},{:.8e},{:.8e},{}",
                c.method, wl, c.incidence_deg, p.scatter_deg, p.brdf_per_sr, p.reflectance, unc
            )?;
        }
    }
    Ok(())
}

/// Read curves from a CSV file in either of the two layouts. Rows are grouped into curves by
/// (method, wavelength, incidence), in the order they first appear; points are sorted by angle.
/// The simple layout gives the method "measured" and no BRDF column (it is derived from the
/// reflectance only when `aperture_sr` is given: `f = rho / (Omega cos ts)`).
pub fn read_csv(
    path: &Path,
    aperture_sr: Option<f64>,
) -> Result<Vec<InplaneCurve>, InstrumentError> {
    let err = |message: String| InstrumentError::Read {
        path: path.display().to_string(),
        message,
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_path(path)
        .map_err(|e| err(e.to_string()))?;
    let headers = reader.headers().map_err(|e| err(e.to_string()))?.clone();
    let col = |name: &str| headers.iter().position(|h| h == name);
    let (Some(ci), Some(cs), Some(cr)) =
        (col("incidence_deg"), col("scatter_deg"), col("reflectance"))
    else {
        return Err(err(format!(
            "needs the columns incidence_deg, scatter_deg and reflectance (found: {})",
            headers.iter().collect::<Vec<_>>().join(",")
        )));
    };
    let (cm, cw, cb, cu) = (
        col("method"),
        col("wavelength_nm"),
        col("brdf_per_sr"),
        col("rel_uncertainty"),
    );
    let mut order: Vec<(String, Option<u64>, u64)> = Vec::new();
    let mut groups: BTreeMap<(String, Option<u64>, u64), InplaneCurve> = BTreeMap::new();
    for record in reader.records() {
        // The csv crate's errors name the record and its line themselves.
        let record = record.map_err(|e| err(e.to_string()))?;
        // The line in the file, comment lines counted (the reader skips them).
        let line = record.position().map_or(0, |p| p.line());
        let number = |c: usize, name: &str| -> Result<f64, InstrumentError> {
            let text = record.get(c).unwrap_or("");
            let v: f64 = text
                .parse()
                .map_err(|_| err(format!("line {line}: {name} '{text}' is not a number")))?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(err(format!("line {line}: {name} is not finite")))
            }
        };
        let optional = |c: Option<usize>, name: &str| -> Result<Option<f64>, InstrumentError> {
            match c.and_then(|c| record.get(c)).filter(|t| !t.is_empty()) {
                None => Ok(None),
                Some(_) => number(c.unwrap(), name).map(Some),
            }
        };
        // A relative uncertainty is `inf` where a detector caught nothing (the ray method's
        // 1/√count with no rays): `write_csv` writes it so, and it reads back as written.
        let uncertainty = |c: Option<usize>| -> Result<Option<f64>, InstrumentError> {
            match c.and_then(|c| record.get(c)).filter(|t| !t.is_empty()) {
                None => Ok(None),
                Some(text) => match text.parse::<f64>() {
                    Ok(v) if v >= 0.0 => Ok(Some(v)),
                    _ => Err(err(format!(
                        "line {line}: rel_uncertainty '{text}' is not a number >= 0 (or inf)"
                    ))),
                },
            }
        };
        let method = cm
            .and_then(|c| record.get(c))
            .unwrap_or("measured")
            .to_string();
        let wavelength = optional(cw, "wavelength_nm")?;
        let incidence = number(ci, "incidence_deg")?;
        let scatter = number(cs, "scatter_deg")?;
        let reflectance = number(cr, "reflectance")?;
        let brdf = match optional(cb, "brdf_per_sr")? {
            Some(b) => b,
            None => aperture_sr
                .map(|omega| reflectance / (omega * scatter.to_radians().cos()))
                .unwrap_or(f64::NAN),
        };
        let key = (
            method.clone(),
            wavelength.map(f64::to_bits),
            incidence.to_bits(),
        );
        let curve = groups.entry(key.clone()).or_insert_with(|| {
            order.push(key);
            InplaneCurve {
                method,
                wavelength_nm: wavelength,
                incidence_deg: incidence,
                points: Vec::new(),
            }
        });
        curve.points.push(CurvePoint {
            scatter_deg: scatter,
            brdf_per_sr: brdf,
            reflectance,
            rel_uncertainty: uncertainty(cu)?,
        });
    }
    if order.is_empty() {
        return Err(err("no data rows".into()));
    }
    Ok(order
        .into_iter()
        .map(|k| {
            let mut c = groups.remove(&k).expect("every key was inserted");
            c.points
                .sort_by(|a, b| a.scatter_deg.total_cmp(&b.scatter_deg));
            c
        })
        .collect())
}
