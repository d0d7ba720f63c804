//! End-to-end tests of `gonio compare` on the files other commands write: the curves CSV of
//! `gonio inplane` (here the quick demo's own) read back into `compare`.

use crate::common::{ok, quick_demo};

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    /// Every curves CSV the quick demo writes (the `gonio inplane` columns, with `inf`
    /// relative uncertainty where a detector caught nothing) compares against itself: zero RMS
    /// difference and equal peaks.
    #[test]
    fn demo_curves_round_trip_into_compare() {
        let dir = tempfile::tempdir().unwrap();
        let out = quick_demo().to_path_buf();
        let mut csvs = Vec::new();
        let mut stack = vec![out.clone()];
        while let Some(d) = stack.pop() {
            for entry in std::fs::read_dir(&d).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    stack.push(path);
                } else if path.extension().is_some_and(|e| e == "csv")
                    && std::fs::read_to_string(&path)
                        .unwrap()
                        .starts_with("method,wavelength_nm,incidence_deg,scatter_deg")
                {
                    csvs.push(path);
                }
            }
        }
        assert!(!csvs.is_empty(), "the demo wrote no curves CSV");
        let with_inf = csvs
            .iter()
            .filter(|p| std::fs::read_to_string(p).unwrap().contains(",inf"))
            .count();
        assert!(
            with_inf > 0,
            "no demo CSV has an infinite uncertainty: {csvs:?}"
        );
        for csv in &csvs {
            // The whole file reads, not only up to the first `inf` (where the reader once stopped).
            let name = csv.to_str().unwrap();
            ok(&["compare", name, name, "--method", "ray"]);
            // Its ray curves, rows unchanged, compared with themselves: nothing differs.
            let text = std::fs::read_to_string(csv).unwrap();
            let ray: Vec<&str> = text
                .lines()
                .enumerate()
                .filter(|(i, l)| *i == 0 || l.starts_with("ray,"))
                .map(|(_, l)| l)
                .collect();
            let ray_csv = dir.path().join("ray.csv");
            std::fs::write(&ray_csv, ray.join("\n") + "\n").unwrap();
            let ray_csv = ray_csv.to_str().unwrap();
            let out = ok(&["compare", ray_csv, ray_csv, "--json"]);
            let rows: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            let rows = rows.as_array().unwrap();
            assert!(!rows.is_empty(), "{name}");
            for row in rows {
                assert_eq!(row["rms_log10"].as_f64(), Some(0.0), "{name}: {row}");
                assert_eq!(row["peak_a"], row["peak_b"], "{name}");
            }
        }
    }
}
