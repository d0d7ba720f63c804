//! What a formulation study writes, for every front end alike: its rows as CSV (one line per
//! value of the varied constituent: gloss, haze, DOI, flop index, and L*, a*, b* at each
//! multi-angle geometry), as JSON, and its two plots (gloss and DOI, and L* at each geometry,
//! against the constituent).

use crate::coating_study::StudyRow;
use crate::error::{InstrumentError, Result};
use crate::multiangle::Geometry;
use gonio_plot::{self as plot, LinePlot, Series};
use std::io::Write;
use std::path::Path;

/// The study of the description `file` varying `vary` (as given, e.g. `roughness`), whose
/// constituent reads `label`, as JSON: `{file, vary, label, rows: [{value, gu20, gu60, gu85,
/// haze, haze_20_log, doi, flop_index, multiangle: [{name, L, a, b, C, h_deg}]}]}`.
pub fn json(file: &str, vary: &str, label: &str, rows: &[StudyRow]) -> serde_json::Value {
    serde_json::json!({
        "file": file,
        "vary": vary,
        "label": label,
        "rows": rows.iter().map(|r| serde_json::json!({
            "value": r.value,
            "gu20": r.gloss.gu20, "gu60": r.gloss.gu60, "gu85": r.gloss.gu85,
            "haze": r.gloss.haze, "haze_20_log": r.gloss.haze_20_log, "doi": r.gloss.doi,
            "flop_index": r.multiangle.flop_index(),
            "multiangle": r.multiangle.geometries.iter().map(|g| serde_json::json!({
                "name": g.geometry.to_string(), "L": g.lab.l, "a": g.lab.a, "b": g.lab.b,
                "C": g.lab.chroma(), "h_deg": g.lab.hue_deg(),
            })).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
    })
}

/// The rows as CSV: `value,gu20,gu60,gu85,haze,haze_20_log,doi,flop_index` then `L_G,a_G,b_G`
/// for each of `geometries` (named as `45as15`); an empty flop index where the geometries do
/// not give one.
pub fn csv(rows: &[StudyRow], geometries: &[Geometry]) -> String {
    let mut csv = String::from("value,gu20,gu60,gu85,haze,haze_20_log,doi,flop_index");
    for g in geometries {
        csv.push_str(&format!(",L_{g},a_{g},b_{g}"));
    }
    csv.push('\n');
    for r in rows {
        csv.push_str(&format!(
            "{},{},{},{},{},{},{},{}",
            r.value,
            r.gloss.gu20,
            r.gloss.gu60,
            r.gloss.gu85,
            r.gloss.haze,
            r.gloss.haze_20_log,
            r.gloss.doi,
            r.multiangle
                .flop_index()
                .map_or(String::new(), |f| f.to_string())
        ));
        for g in &r.multiangle.geometries {
            csv.push_str(&format!(",{},{},{}", g.lab.l, g.lab.a, g.lab.b));
        }
        csv.push('\n');
    }
    csv
}

/// Write `study.csv`, `study.json`, `gloss.png` and `lightness.png` into `dir` (created if
/// missing), each atomically.
pub fn write(
    dir: &Path,
    json: &serde_json::Value,
    rows: &[StudyRow],
    label: &str,
    geometries: &[Geometry],
) -> Result<()> {
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |error| InstrumentError::Io { path, error }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    for (name, text) in [
        ("study.csv", csv(rows, geometries)),
        (
            "study.json",
            serde_json::to_string_pretty(json).expect("a JSON value serialises"),
        ),
    ] {
        let path = dir.join(name);
        gonio_io::write_atomic(
            &path,
            |w| w.write_all(text.as_bytes()),
            std::convert::identity,
        )
        .map_err(io(&path))?;
    }
    plot(dir, label, rows)
}

/// The study's plots: gloss (20/60/85°) and DOI against the varied constituent, and L* at each
/// multi-angle geometry against it.
pub fn plot(dir: &Path, label: &str, rows: &[StudyRow]) -> Result<()> {
    let gloss: Vec<Series> = [("20°", 0), ("60°", 1), ("85°", 2), ("DOI", 3)]
        .into_iter()
        .map(|(name, i)| Series {
            label: if i == 3 {
                "DOI".into()
            } else {
                format!("gloss {name}")
            },
            points: rows
                .iter()
                .map(|r| {
                    (
                        r.value,
                        [r.gloss.gu20, r.gloss.gu60, r.gloss.gu85, r.gloss.doi][i],
                    )
                })
                .collect(),
            colour: plot::palette(i),
            markers: false,
        })
        .collect();
    plot::line_plot_png(
        &dir.join("gloss.png"),
        (900, 600),
        &LinePlot {
            title: &format!("Gloss (ISO 2813, GU) and DOI (ASTM E430) against {label}"),
            x_label: label,
            y_label: "GU / DOI",
            log_y: false,
        },
        &gloss,
    )?;
    let lightness: Vec<Series> = rows[0]
        .multiangle
        .geometries
        .iter()
        .enumerate()
        .map(|(k, g)| Series {
            label: g.geometry.to_string(),
            points: rows
                .iter()
                .map(|r| (r.value, r.multiangle.geometries[k].lab.l))
                .collect(),
            colour: plot::palette(k),
            markers: false,
        })
        .collect();
    Ok(plot::line_plot_png(
        &dir.join("lightness.png"),
        (900, 600),
        &LinePlot {
            title: &format!("Multi-angle lightness L* (D65/10°) against {label}"),
            x_label: label,
            y_label: "L*",
            log_y: false,
        },
        &lightness,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coating_study::{Constituent, run};
    use crate::multiangle::E2194;

    /// A two-value study of the coat's thickness over a grey base writes a CSV with a header and
    /// one line per value whose columns match the rows, JSON with the same rows, and two plots
    /// (PNG files that decode to the requested size).
    #[test]
    fn study_files_hold_the_rows() {
        let wl = gonio_coating::system::default_bands();
        let coating = gonio_coating::description::parse(
            "[coat]\nindex = 1.5\nthickness_um = 40\n[base]\nkind = \"diffuse\"\nreflectance = 0.3\n",
            &wl,
        )
        .unwrap();
        let rows = run(
            &coating,
            &Constituent::CoatThickness,
            &[20.0, 60.0],
            &E2194,
            &wl,
            16,
            1,
        )
        .unwrap();
        let text = csv(&rows, &E2194);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        let header: Vec<&str> = lines[0].split(',').collect();
        assert_eq!(header.len(), 8 + 3 * E2194.len());
        assert_eq!(header[8], format!("L_{}", E2194[0]));
        for (line, row) in lines[1..].iter().zip(&rows) {
            let cells: Vec<&str> = line.split(',').collect();
            assert_eq!(cells.len(), header.len());
            assert_eq!(cells[0].parse::<f64>().unwrap(), row.value);
            let l: f64 = cells[8].parse().unwrap();
            assert_eq!(l, row.multiangle.geometries[0].lab.l);
        }
        let json = json("grey.toml", "thickness", "coat thickness, µm", &rows);
        assert_eq!(json["rows"][1]["value"], 60.0);
        assert_eq!(
            json["rows"][0]["multiangle"].as_array().unwrap().len(),
            E2194.len()
        );
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("study");
        write(&out, &json, &rows, "coat thickness, µm", &E2194).unwrap();
        for name in ["gloss.png", "lightness.png"] {
            let image = image::open(out.join(name)).unwrap();
            assert_eq!((image.width(), image.height()), (900, 600), "{name}");
        }
        let read: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("study.json")).unwrap())
                .unwrap();
        // serde_json parses floats to within an ulp, not exactly (no float_roundtrip feature).
        assert_eq!(read["rows"].as_array().unwrap().len(), 2);
        let gu60 = read["rows"][1]["gu60"].as_f64().unwrap();
        assert!((gu60 - rows[1].gloss.gu60).abs() < 1e-12 * gu60, "{gu60}");
        assert_eq!(
            std::fs::read_to_string(out.join("study.csv")).unwrap(),
            text
        );
    }
}
