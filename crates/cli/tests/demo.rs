//! The demo end to end: `gonio demo --quick` writes a report with every section filled, and,
//! where Chromium is installed, the page renders in headless Chromium with every image loaded.

use std::path::Path;
use std::process::Command;

fn gonio() -> Command {
    Command::new(env!("CARGO_BIN_EXE_gonio"))
}

#[test]
fn quick_demo_writes_a_complete_report() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let status = gonio()
        .args(["demo", "--quick", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for title in [
        "Surfaces: the epoxy roughness series",
        "A real instrument file: x3p-2.x3p",
        "Isotropy of x3p-2.x3p",
        "The roughness study",
    ] {
        assert!(html.contains(title), "section '{title}' missing");
    }
    let images = html.matches("<img src=\"data:image/png;base64,").count();
    assert!(images >= 8, "only {images} images");
    assert!(!text_of(&html).contains("NaN"), "a NaN reached the report");
    if let Some(chromium) = find_chromium() {
        check_in_browser(&chromium, &out.join("report.html"), images);
    } else {
        eprintln!("chromium not installed: browser check skipped");
    }
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
