//! The conformance suite's report through the library, as every front end calls it:
//! `gonio_report::conformance::run` on gonio alone writes `report.html` with a row per scene in
//! its table, each scene's section with its strip of pictures embedded, and a summary whose
//! counts are the results'.

use gonio_conformance::{Options, Renderer, Verdict};

#[test]
fn the_report_holds_every_scene_and_its_pictures() {
    let dir = tempfile::tempdir().unwrap();
    let (results, path) = gonio_report::conformance::run(&Options {
        renderers: vec![Renderer::Gonio],
        spp: 16,
        dir: dir.path().to_path_buf(),
    })
    .unwrap();
    assert_eq!(path, dir.path().join("report.html"));
    let html = std::fs::read_to_string(&path).unwrap();
    let passes = results
        .scenes
        .iter()
        .flat_map(|s| &s.runs)
        .filter(|r| r.verdict == Verdict::Pass)
        .count();
    let runs = results.scenes.iter().map(|s| s.runs.len()).sum::<usize>();
    assert!(
        html.contains(&format!(
            "{} scenes, {runs} runs: {passes} pass",
            results.scenes.len()
        )),
        "the summary's counts"
    );
    for s in &results.scenes {
        let name = s.scene.id.name();
        assert!(
            html.contains(&format!("<tr><td>{name}</td><td>gonio</td>")),
            "{name}'s row"
        );
        assert!(
            html.contains(&format!("<h2>{name}</h2>")),
            "{name}'s section"
        );
    }
    // The reference and one strip per scene, embedded.
    assert_eq!(
        html.matches("data:image/png;base64,").count(),
        2 * results.scenes.len()
    );
}
