//! gonio's readers against an independent one: SurfaceTopography (PyPI), run on every fixture
//! in `tests/data` by `tests/surfacetopography.py`. For each file both read, the grid, the
//! lateral size, the valid fraction and Sq after removing the least-squares plane must agree;
//! where they do not, [`KNOWN_DIFFERENCES`] names the file and a test elsewhere shows from the
//! file's bytes which reader is right.
//!
//! Without Python or SurfaceTopography the test says so and passes, unless
//! `GONIO_REQUIRE_ORACLES=1` (set by `.ci/run`), when a missing oracle fails it.

use crate::fixture_tools::{rel, sq_plane};
use gonio_surface::io;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Sq agrees within 0.5%: both readers level by the least-squares plane over the valid points
/// and take the rms, so only the heights themselves can differ; 0.5% allows for float32 data
/// converted in a different order, never for a misread scale (which changes Sq by factors).
const SQ_TOLERANCE: f64 = 0.005;
/// Lateral sizes agree to float32 precision (several formats store the pixel as f32).
const SIZE_TOLERANCE: f64 = 1e-6;
/// Valid fractions agree to one point in 10⁴ (the smallest fixture has 12 points: exact there).
const VALID_TOLERANCE: f64 = 1e-4;

/// Where gonio and SurfaceTopography disagree: file, quantity, and the test that shows from the
/// file's bytes that gonio is right. The file's other quantities are still compared.
const KNOWN_DIFFERENCES: &[(&str, &str, &str)] = &[
    (
        "frt-1.frt",
        "valid fraction",
        "profiler_formats::frt_zero_line_is_outside_the_valid_range: the last line holds 0, \
         outside the file's own valid range 5..65529; SurfaceTopography keeps it as 0 m",
    ),
    (
        "frt-1.frt",
        "Sq",
        "the same zero line, 78 µm below the surface, raises SurfaceTopography's Sq to 4.396 µm",
    ),
    (
        "nms-1.nms",
        "size",
        "profiler_formats::nms_lateral_size_is_160_um_not_160_m: the step 312.5 is in nm \
         (512 × 312.5 nm = 160 µm); SurfaceTopography reads it as mm",
    ),
];

/// Fixtures SurfaceTopography 1.27 cannot read at all, with its reason: gonio reads them, and
/// its own tests check them against the values the files state.
const ORACLE_REFUSES: &[(&str, &str)] = &[
    (
        "ISO5436-sample1.x3p",
        "its X3P reader needs <DataLink>; this openGPS sample stores the points in <DataList>",
    ),
    ("gsf-1.gsf", "it has no Gwyddion Simple Field reader"),
];

/// Skip with a reason, or fail when `GONIO_REQUIRE_ORACLES=1` demands the oracle.
fn oracle_missing(why: &str) {
    assert!(
        std::env::var("GONIO_REQUIRE_ORACLES").as_deref() != Ok("1"),
        "GONIO_REQUIRE_ORACLES=1 but {why}"
    );
    eprintln!("skipping the SurfaceTopography comparison: {why}");
}

fn fixtures() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file() && p.extension().is_none_or(|e| e != "md"))
        .collect();
    files.sort();
    files
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn every_fixture_reads_as_surfacetopography_reads_it() {
        let files = fixtures();
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/surfacetopography.py");
        let python = std::env::var("GONIO_PYTHON").unwrap_or_else(|_| "python3".into());
        let out = match Command::new(&python).arg(&script).args(&files).output() {
            Ok(out) => out,
            Err(e) => return oracle_missing(&format!("cannot run {python}: {e}")),
        };
        if out.status.code() == Some(77) {
            return oracle_missing(
                "SurfaceTopography is not installed (`pip install SurfaceTopography`)",
            );
        }
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let report: Value = serde_json::from_slice(&out.stdout).expect("JSON from the script");
        let mut compared = 0;
        let mut failures = Vec::new();
        for file in &files {
            let name = file.file_name().unwrap().to_str().unwrap();
            let theirs = &report[file.to_str().unwrap()];
            let refused = ORACLE_REFUSES.iter().find(|(n, _)| *n == name);
            if let Some(error) = theirs.get("error") {
                assert!(
                    refused.is_some(),
                    "SurfaceTopography cannot read {name}, which is not listed: {error}"
                );
                continue;
            }
            assert!(
                refused.is_none(),
                "{name} is listed as refused but SurfaceTopography reads it now: compare it"
            );
            let mut disagree = |quantity: &str, message: String| {
                let known = KNOWN_DIFFERENCES
                    .iter()
                    .any(|(n, q, _)| *n == name && *q == quantity);
                if known {
                    eprintln!("{name}: {message} (known: gonio is right)");
                } else {
                    failures.push(format!("{name}: {message}"));
                }
            };
            let map = io::read(file).unwrap_or_else(|e| panic!("{name}: {e}"));
            let grid: Vec<u64> = theirs["grid"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_u64().unwrap())
                .collect();
            // A line profile is one-dimensional in SurfaceTopography, one row here.
            let (ours_grid, ours_size) = if map.is_profile() {
                (vec![map.nx() as u64], vec![map.nx() as f64 * map.dx()])
            } else {
                (
                    vec![map.nx() as u64, map.ny() as u64],
                    vec![map.nx() as f64 * map.dx(), map.ny() as f64 * map.dy()],
                )
            };
            if grid != ours_grid {
                disagree(
                    "grid",
                    format!("grid {ours_grid:?}, SurfaceTopography {grid:?}"),
                );
                continue;
            }
            let size: Vec<f64> = theirs["size_m"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            for (axis, (a, b)) in ours_size.iter().zip(&size).enumerate() {
                if rel(*a, *b) > SIZE_TOLERANCE {
                    disagree(
                        "size",
                        format!("size along axis {axis} {a} m, SurfaceTopography {b} m"),
                    );
                }
            }
            let valid = theirs["valid_fraction"].as_f64().unwrap();
            if (map.valid_fraction() - valid).abs() > VALID_TOLERANCE {
                disagree(
                    "valid fraction",
                    format!(
                        "valid fraction {}, SurfaceTopography {valid}",
                        map.valid_fraction()
                    ),
                );
            }
            let sq = theirs["sq_m"].as_f64().unwrap();
            let ours = sq_plane(&map);
            if rel(ours, sq) > SQ_TOLERANCE {
                disagree("Sq", format!("Sq {ours} m, SurfaceTopography {sq} m"));
            }
            eprintln!(
                "{name}: {} × {}, Sq {ours:.6e} m vs {sq:.6e} m ({:+.3}%)",
                map.nx(),
                map.ny(),
                100.0 * (ours / sq - 1.0)
            );
            compared += 1;
        }
        assert!(
            failures.is_empty(),
            "disagreements:\n{}",
            failures.join("\n")
        );
        assert!(compared >= 10, "only {compared} fixtures compared");
    }
}
