//! The page in a real browser: `tests/browser/lab_page.py` drives Debian's Chromium through
//! Playwright against a lab on an ephemeral port, and this test checks what it saw. Without
//! Playwright or Chromium the test skips, saying why, unless `GONIO_REQUIRE_ORACLES=1` (set by
//! `.ci/run`, which installs them) demands them. Screenshots: `target/lab-browser/`.

mod slow {
    use crate::server::{data, start};

    #[test]
    fn the_page_in_chromium() {
        let base = start();
        let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/lab-browser");
        let script =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/lab_page.py");
        let run = std::process::Command::new("python3")
            .arg(&script)
            .arg(format!("{base}/"))
            .arg(&out)
            .arg(data("crates/surface/tests/data/matrix-3.txt"))
            .arg(data("crates/brdf/tests/data/cayman.astm"))
            .output();
        let run = match run {
            Ok(r)
                if r.status.code() == Some(3)
                    || !r.status.success()
                        && r.stdout.is_empty()
                        && String::from_utf8_lossy(&r.stderr).contains("No module named") =>
            {
                let why = String::from_utf8_lossy(&r.stderr).trim().to_string();
                assert!(
                    std::env::var("GONIO_REQUIRE_ORACLES").as_deref() != Ok("1"),
                    "GONIO_REQUIRE_ORACLES=1 but {why}"
                );
                eprintln!("skipping the browser test: {why}");
                return;
            }
            Ok(r) => r,
            Err(e) => {
                assert!(
                    std::env::var("GONIO_REQUIRE_ORACLES").as_deref() != Ok("1"),
                    "GONIO_REQUIRE_ORACLES=1 but python3: {e}"
                );
                eprintln!("skipping the browser test: python3: {e}");
                return;
            }
        };
        assert!(
            run.status.success(),
            "the browser script failed:\n{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let seen: serde_json::Value =
            serde_json::from_slice(&run.stdout).expect("the script's JSON");
        eprintln!("{seen:#}");
        assert_eq!(seen["errors"], serde_json::json!([]), "errors in the page");
        let f = |k: &str| seen[k].as_f64().unwrap_or_else(|| panic!("{k}: {seen}"));
        assert!(f("alpha_after") > 0.15, "the slider did not move α: {seen}");
        assert!(
            f("gloss60_after") < f("gloss60_before") - 1.0,
            "60° gloss did not fall: {seen}"
        );
        assert_ne!(
            seen["swatch_after"], seen["swatch_before"],
            "the 45as15 swatch did not change"
        );
        assert_eq!(seen["invalid_row"], "flakes.coverage", "{seen}");
        assert!(
            seen["invalid_message"]
                .as_str()
                .unwrap()
                .contains("coverage 1.5"),
            "{seen}"
        );
        let stats = seen["topography_stats"].as_str().unwrap();
        assert!(
            stats.contains("matrix-3.txt")
                && stats.contains("256 × 256")
                && stats.contains("Sq 0.0352"),
            "{stats}"
        );
        let rows: Vec<&str> = seen["de00_rows"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r.as_str().unwrap())
            .collect();
        assert!(
            rows.iter().any(|r| r.starts_with("45as15"))
                && rows.iter().any(|r| r.starts_with("mean ΔE00")),
            "{rows:?}"
        );
        assert!(
            seen["pinned_columns"].as_str().unwrap().contains('A'),
            "{seen}"
        );
        // The way back: a match's progress, its cancellation, its result in the form and its
        // ΔE00 table; a Morris screening's chart, one bar per constituent and reading.
        assert_eq!(
            seen["match_vary"],
            serde_json::json!(["tilt", "coverage", "concentration:cyan"]),
            "{seen}"
        );
        for (k, says) in [
            ("match_progress_line", "best mean ΔE00 so far"),
            ("match_cancelled_line", "cancelled after"),
            ("match_done_line", "the form holds the fitted formulation"),
        ] {
            assert!(seen[k].as_str().unwrap().contains(says), "{k}: {seen}");
        }
        let rows = |k: &str| -> Vec<String> {
            seen[k]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| r.as_str().unwrap().to_string())
                .collect()
        };
        let de = rows("match_de00_rows");
        assert_eq!(de.len(), 7, "a head, five geometries and the mean: {de:?}");
        assert!(
            de[1].starts_with("45as15") && de[6].starts_with("mean"),
            "{de:?}"
        );
        let values = rows("match_values_rows");
        // A head and the three constituents, with a σ column (a dash where Gauss–Newton cannot
        // give one: here the coverage ends at its bound after 3 iterations).
        assert_eq!(values.len(), 4, "{values:?}");
        assert!(values[0].contains("σ (1 sd)"), "{values:?}");
        assert_ne!(
            seen["coverage_before"], seen["coverage_after"],
            "the form was not filled"
        );
        assert!(
            rows("form_de00_rows")
                .iter()
                .any(|r| r.starts_with("mean ΔE00")),
            "{seen}"
        );
        // "Let gonio select" up to 2 of 3: the choice named, a head and 2 finalists (the chosen
        // one marked), the chosen pigments in the form as library pigments.
        let chosen = seen["select_chosen"].as_str().unwrap();
        assert!(chosen.starts_with("gonio chose "), "{seen}");
        assert!(
            chosen.contains("of 2 finalists, from 6 combinations of 3 candidates"),
            "{chosen}"
        );
        let finalists = rows("select_finalists_rows");
        assert_eq!(finalists.len(), 3, "{finalists:?}");
        assert_eq!(
            finalists.iter().filter(|r| r.starts_with('✓')).count(),
            1,
            "{finalists:?}"
        );
        let form: Vec<&str> = seen["select_form_pigments"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|p| p.as_str())
            .collect();
        let named = chosen
            .trim_start_matches("gonio chose ")
            .split(':')
            .next()
            .unwrap();
        for p in named.split(" + ") {
            assert!(
                form.contains(&p.replace(' ', "_").as_str()),
                "{p} not in the form's {form:?}"
            );
        }
        assert!(
            seen["select_done_line"]
                .as_str()
                .unwrap()
                .contains("6 combinations screened, 2 finalists"),
            "{seen}"
        );
        assert!(f("narrow_select_overflow_px") <= 0.0, "{seen}");
        let mut bars: Vec<String> = rows("sens_bars");
        bars.sort();
        assert_eq!(
            bars,
            [
                "L@45as15 roughness",
                "L@45as15 tilt",
                "gu60 roughness",
                "gu60 tilt"
            ],
            "{seen}"
        );
        assert!(
            seen["sens_summary"].as_str().unwrap().contains("60° gloss"),
            "{seen}"
        );
        assert!(f("narrow_running_overflow_px") <= 0.0, "{seen}");
        assert!(
            f("narrow_overflow_px") <= 0.0,
            "the narrow page scrolls sideways: {seen}"
        );
        // The downloaded TOML is a description `gonio coating info` reads (the same library call).
        let toml = seen["toml"].as_str().unwrap();
        let bands = gonio_coating::system::default_bands();
        let coating = gonio_coating::description::read(toml.as_ref(), &bands)
            .expect("the downloaded TOML reads");
        gonio_instrument::coating_summary::summarise(&coating, &bands, 16)
            .expect("and is summarised");
        assert!(
            coating
                .flakes
                .as_ref()
                .is_some_and(|fl| (fl.tilt_deg - 25.0).abs() < 1e-9),
            "the TOML is not the formulation shown"
        );
    }
}
