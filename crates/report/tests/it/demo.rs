//! The demo through the library, as every front end calls it: `gonio_report::demo::run` on the
//! quick plan writes a report with every section filled, its tables rectangular, its summary
//! quoting the study's files, its steps reported in order, and, where Chromium is installed,
//! a page that renders in headless Chromium with every image loaded.

use gonio_io::Progress;
use gonio_report::demo::{DemoOutcome, DemoPlan, DemoProgress, run};
use std::path::Path;
use std::process::Command;
use std::sync::{Arc, Mutex};

/// Every table of the page has as many cells in each row as in its header row.
fn tables_are_rectangular(html: &str) {
    let tables: Vec<&str> = html
        .split("<table>")
        .skip(1)
        .map(|t| &t[..t.find("</table>").expect("a table is closed")])
        .collect();
    assert!(tables.len() >= 6, "only {} tables", tables.len());
    for table in tables {
        let rows: Vec<&str> = table.split("<tr>").skip(1).collect();
        let header = rows[0].matches("<th>").count();
        assert!(header > 0, "a table without a header row: {table}");
        for row in &rows[1..] {
            assert_eq!(
                row.matches("<td").count(),
                header,
                "a row whose cells do not match the {header} headers: {row}\nin {table}"
            );
        }
    }
}

/// The summary at the top states the study's 60° gloss readings as the study wrote them.
fn summary_quotes_the_results(html: &str, out: &Path) {
    let start = html.find("<h2>Summary</h2>").expect("a summary");
    let summary = &html[start..html.find("<h2>Contents</h2>").unwrap()];
    let gloss = std::fs::read_to_string(out.join("study/gloss.csv")).unwrap();
    let mut lines = gloss.lines();
    let column = lines
        .next()
        .and_then(|h| h.split(',').position(|c| c == "gu60"))
        .expect("gloss.csv has a gu60 column");
    let mut quoted = 0;
    for line in lines {
        let gu60: f64 = line.split(',').nth(column).unwrap().parse().unwrap();
        if summary.contains(&format!("{gu60:.1} GU")) || summary.contains(&format!("{gu60:.1} and"))
        {
            quoted += 1;
        }
    }
    assert!(
        quoted >= 2,
        "the summary quotes {quoted} of the 60° readings: {summary}"
    );
}

/// The standard of appearance: six booth pictures (two coatings, three views), each view's
/// files linked and written, a manifest per coating, and the closure table with a row per
/// coating and E2194 geometry whose ΔE00 is within 0.5 plus its noise bound (the quick run's
/// coarse tables do not matter to the closure: both sides read the same table), and the
/// conformance suite's summary with its own report linked.
fn standard_section_is_complete(html: &str, out: &Path) {
    let start = html
        .find("<h2>Standard of appearance")
        .expect("the standard section");
    let section = &html[start..start + html[start..].find("</section>").unwrap()];
    let pictures = section.matches("<img src=\"data:image/png;base64,").count();
    assert_eq!(pictures, 6, "{pictures} booth pictures");
    for coating in ["silver_metallic", "red_solid"] {
        for view in ["near-specular", "45", "flank"] {
            for file in [
                format!("{view}.exr"),
                format!("{view}-p3.png"),
                format!("{view}-srgb-mask.png"),
                format!("{view}-p3-mask.png"),
            ] {
                let rel = format!("standard/{coating}/{file}");
                assert!(
                    section.contains(&format!("href=\"{rel}\"")),
                    "{rel} not linked"
                );
                assert!(out.join(&rel).is_file(), "{rel} not written");
            }
        }
        let manifest = format!("standard/{coating}/manifest.json");
        assert!(section.contains(&format!("href=\"{manifest}\"")));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(&manifest)).unwrap()).unwrap();
        // Three views, each an OpenEXR, two renderings, their two masks and the specimen's mask.
        assert_eq!(json["outputs"].as_array().unwrap().len(), 18, "{manifest}");
        assert_eq!(
            json["inputs"][0]["path"],
            format!("{coating}.toml"),
            "{manifest}"
        );
    }
    let table = &section[section.find("<table>").expect("the closure table")..];
    let table = &table[..table.find("</table>").unwrap()];
    assert!(
        table.contains("<th>ΔE00</th><th>noise bound</th>"),
        "{table}"
    );
    let rows: Vec<Vec<&str>> = table
        .split("<tr>")
        .skip(2)
        .map(|r| {
            r.split("<td>")
                .skip(1)
                .map(|c| &c[..c.find("</td>").unwrap()])
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 10, "{table}");
    for row in &rows {
        assert!(
            ["silver metallic", "red solid"].contains(&row[0]),
            "{row:?}"
        );
        assert!(row[1].starts_with("45as"), "{row:?}");
        let de: f64 = row[8].parse().unwrap();
        let noise: f64 = row[9].parse().unwrap();
        assert!(de < 0.5 + noise, "{row:?}");
    }
    for scene in ["white_furnace", "coat", "mirror", "metamer_a"] {
        assert!(
            section.contains(&format!("<tr><td>{scene}</td>")),
            "conformance scene {scene} missing"
        );
    }
    assert!(section.contains("href=\"conformance/report.html\""));
    assert!(out.join("conformance/report.html").is_file());
}

/// The page without its embedded image data.
fn text_of(html: &str) -> String {
    let mut text = String::new();
    let mut rest = html;
    while let Some(i) = rest.find("base64,") {
        text.push_str(&rest[..i]);
        rest = &rest[i..];
        rest = &rest[rest.find('"').unwrap_or(rest.len())..];
    }
    text.push_str(rest);
    text
}

fn find_chromium() -> Option<String> {
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|c| {
            Command::new(c)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
        .map(String::from)
}

/// Load the page in headless Chromium with a script that counts images that failed to decode,
/// and read the verdict back from the dumped DOM.
fn check_in_browser(chromium: &str, report: &Path, expected: usize) {
    let html = std::fs::read_to_string(report).unwrap();
    let probe = "<script>window.addEventListener('load',()=>{const imgs=[...document.images];\
        const bad=imgs.filter(i=>!(i.complete&&i.naturalWidth>0)).length;\
        document.body.setAttribute('data-probe','images='+imgs.length+';bad='+bad);});</script></body>";
    let page = report.with_file_name("probe.html");
    std::fs::write(&page, html.replace("</body>", probe)).unwrap();
    let profile = tempfile::tempdir().unwrap();
    let out = Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--virtual-time-budget=10000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    let dom = String::from_utf8_lossy(&out.stdout);
    let verdict = format!("data-probe=\"images={expected};bad=0\"");
    assert!(
        dom.contains(&verdict),
        "Chromium did not load every image: expected {verdict}; stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A plan whose output folder cannot be made (a file stands in its way) is an error naming it,
/// before any work.
#[test]
fn an_output_folder_that_cannot_be_made_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("taken");
    std::fs::write(&file, "a file").unwrap();
    let plan = DemoPlan {
        output: file.join("out"),
        quick: true,
    };
    let err = run(&plan, &DemoProgress::default()).unwrap_err();
    assert!(err.to_string().contains("taken"), "{err}");
}

/// Tests that take seconds each: `cargo test -- --skip slow::` leaves them out of a quick run.
mod slow {
    use super::*;

    #[test]
    fn quick_demo_writes_a_complete_report() {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("report-quick-demo");
        if out.exists() {
            std::fs::remove_dir_all(&out).unwrap();
        }
        let steps = Arc::new(Mutex::new(Vec::new()));
        let heard = steps.clone();
        let progress = DemoProgress {
            steps: Progress::new(move |r| {
                heard
                    .lock()
                    .unwrap()
                    .push((r.stage.to_string(), r.done, r.total))
            }),
            work: Progress::silent(),
        };
        let plan = DemoPlan {
            output: out.clone(),
            quick: true,
        };
        let DemoOutcome {
            report,
            sections,
            seconds,
        } = run(&plan, &progress).unwrap();
        assert_eq!(report, out.join("report.html"));
        let titles = [
            "Surfaces: the epoxy roughness series",
            "A real instrument file: x3p-2.x3p",
            "Isotropy of x3p-2.x3p",
            "The roughness study",
            "Coatings and multi-angle colour",
            "Formulation: a measured paint matched from the pigment library",
            "Texture: sparkle, graininess and orange peel",
            "Standard of appearance: the viewing booth",
        ];
        let names: Vec<&str> = sections.iter().map(|(t, _)| t.as_str()).collect();
        assert_eq!(names, titles);
        let spent: f64 = sections.iter().map(|(_, s)| s).sum();
        assert!(spent > 0.0 && spent <= seconds, "{spent} s of {seconds} s");
        let steps = steps.lock().unwrap();
        assert_eq!(steps.len(), 8, "{steps:?}");
        for (k, (stage, done, total)) in steps.iter().enumerate() {
            assert_eq!((*done, *total), (k as u64, 8), "{stage}");
        }
        let html = std::fs::read_to_string(&report).unwrap();
        for title in titles {
            assert!(html.contains(title), "section '{title}' missing");
        }
        let images = html.matches("<img src=\"data:image/png;base64,").count();
        assert!(images >= 8, "only {images} images");
        assert!(!text_of(&html).contains("NaN"), "a NaN reached the report");
        tables_are_rectangular(&html);
        summary_quotes_the_results(&html, &out);
        standard_section_is_complete(&html, &out);
        if let Some(chromium) = find_chromium() {
            check_in_browser(&chromium, &report, images);
        } else {
            // `.ci/run` installs Chromium and sets GONIO_REQUIRE_ORACLES=1: there the check must run.
            assert!(
                std::env::var("GONIO_REQUIRE_ORACLES").as_deref() != Ok("1"),
                "GONIO_REQUIRE_ORACLES=1 but chromium is not installed: the browser check cannot run"
            );
            eprintln!("chromium not installed: browser check skipped");
        }
    }
}
