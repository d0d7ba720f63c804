//! The conformance suite's report (`gonio conformance`, `gonio.report.conformance`, the lab's
//! `POST /api/report/conformance`): [`gonio_conformance::run`] computes the pictures, the
//! regions' statistics and the verdicts; this composes them into one [`Report`] page: a
//! summary of the verdicts, a table of every scene by every renderer, and for each scene its
//! reference and, per renderer and route (its own, gonio's export, the peer's native
//! version), the pictures (reference, picture, difference, FLIP map), the
//! regions, the checks and what its export loses.

use crate::Result;
use crate::html::{Block, Report, Section};
use gonio_conformance::suite::{Run, SceneResult};
use gonio_conformance::{Options, Results, Verdict};
use std::path::{Path, PathBuf};

/// A verdict in words.
pub fn verdict_name(v: Verdict) -> &'static str {
    match v {
        Verdict::Pass => "pass",
        Verdict::KnownLoss => "known loss",
        Verdict::Fail => "FAIL",
        Verdict::Unavailable => "unavailable",
    }
}

/// Run the suite into `options.dir` and write its report there (`report.html`); the results
/// and the report's path.
pub fn run(options: &Options) -> Result<(Results, PathBuf)> {
    let results = gonio_conformance::run(options)?;
    let path = write(&results, &options.dir)?;
    Ok((results, path))
}

/// Write the report of `results`, whose pictures are in `dir`, as `dir/report.html`.
pub fn write(results: &Results, dir: &Path) -> Result<PathBuf> {
    let path = dir.join("report.html");
    report(results, dir).write(&path)?;
    Ok(path)
}

/// The check a run's row shows: the failing one, or the last (a metameric scene's pair).
fn shown_check(r: &Run) -> Option<&gonio_conformance::suite::Check> {
    r.checks.iter().find(|c| !c.pass).or(r.checks.last())
}

/// The largest ΔE00 of a run's regions from their references.
fn worst_delta_e(r: &Run) -> f64 {
    r.regions.iter().map(|g| g.delta_e00).fold(0.0, f64::max)
}

/// The summary's paragraphs: the counts of verdicts, then each known loss and failure with its
/// measured shortfall.
fn summary(results: &Results) -> Vec<String> {
    let runs: Vec<(&SceneResult, &Run)> = results
        .scenes
        .iter()
        .flat_map(|s| s.runs.iter().map(move |r| (s, r)))
        .collect();
    let count = |v: Verdict| runs.iter().filter(|(_, r)| r.verdict == v).count();
    let mut out = vec![format!(
        "{} scenes, {} runs: {} pass, {} known losses of an export, {} fail, {} unavailable. \
         The suite {}.",
        results.scenes.len(),
        runs.len(),
        count(Verdict::Pass),
        count(Verdict::KnownLoss),
        count(Verdict::Fail),
        count(Verdict::Unavailable),
        if results.passed() {
            "passes: every available renderer passes every scene it can represent"
        } else {
            "fails: a renderer fails a scene it can represent"
        }
    )];
    for (s, r) in runs
        .iter()
        .filter(|(_, r)| matches!(r.verdict, Verdict::KnownLoss | Verdict::Fail))
    {
        if let Some(c) = shown_check(r) {
            let rel = if c.reference != 0.0 {
                format!(" ({:+.1}%)", 100.0 * (c.value - c.reference) / c.reference)
            } else {
                String::new()
            };
            out.push(format!(
                "{} by {}: {} — {}: {:.5} against {:.5}{rel}, tolerance {:.5}.",
                s.scene.id.name(),
                r.label(),
                verdict_name(r.verdict),
                c.what,
                c.value,
                c.reference,
                c.tolerance
            ));
        }
    }
    out
}

/// The table of every scene by every renderer.
fn table(results: &Results) -> Block {
    let headers = [
        "scene",
        "renderer (route)",
        "verdict",
        "value",
        "reference",
        "tolerance",
        "ΔE00",
        "FLIP",
        "time (s)",
    ];
    let mut rows = vec![];
    for s in &results.scenes {
        for r in &s.runs {
            let mut row = vec![
                s.scene.id.name().to_string(),
                r.label(),
                verdict_name(r.verdict).to_string(),
            ];
            match shown_check(r) {
                Some(c) => row.extend([
                    format!("{:.5}", c.value),
                    format!("{:.5}", c.reference),
                    format!("{:.5}", c.tolerance),
                    format!("{:.3}", worst_delta_e(r)),
                    format!("{:.3}", r.flip_mean),
                ]),
                None => row.extend(std::iter::repeat_n(String::from("—"), 5)),
            }
            row.push(format!("{:.1}", r.seconds));
            rows.push(row);
        }
    }
    Block::Table {
        headers: headers.map(String::from).to_vec(),
        rows,
    }
}

/// One scene's section.
fn scene_section(s: &SceneResult, dir: &Path) -> Section {
    let name = s.scene.id.name();
    let mut blocks = vec![
        Block::Text(s.scene.title.clone()),
        Block::Image {
            path: dir.join(format!("{name}_reference.png")),
            caption: "the analytic reference".into(),
        },
    ];
    for r in &s.runs {
        let rn = r.label();
        let mut head = format!("{rn}: {}.", verdict_name(r.verdict));
        if let Some(l) = &r.loss {
            head += &format!(" What its version of the scene loses: {}.", l.text);
        }
        blocks.push(Block::Text(head));
        if r.verdict == Verdict::Unavailable {
            continue;
        }
        blocks.push(Block::Image {
            path: dir.join(format!("{name}_{rn}_strip.png")),
            caption: format!(
                "{rn}: reference, picture, difference (red brighter, blue darker than the \
                 reference, full at 10% of the scene's white), FLIP map (mean {:.4}); {:.1} s",
                r.flip_mean, r.seconds
            ),
        });
        blocks.push(Block::Table {
            headers: [
                "region",
                "pixels",
                "value",
                "reference",
                "SE",
                "L*a*b*",
                "reference L*a*b*",
                "ΔE00",
            ]
            .map(String::from)
            .to_vec(),
            rows: r
                .regions
                .iter()
                .map(|g| {
                    vec![
                        g.name.clone(),
                        g.pixels.to_string(),
                        format!("{:.5}", g.value),
                        format!("{:.5}", g.reference),
                        format!("{:.1e}", g.standard_error),
                        format!("{:.2} {:.2} {:.2}", g.lab[0], g.lab[1], g.lab[2]),
                        format!(
                            "{:.2} {:.2} {:.2}",
                            g.reference_lab[0], g.reference_lab[1], g.reference_lab[2]
                        ),
                        format!("{:.3}", g.delta_e00),
                    ]
                })
                .collect(),
        });
        blocks.push(Block::Table {
            headers: ["check", "value", "reference", "tolerance", "holds"]
                .map(String::from)
                .to_vec(),
            rows: r
                .checks
                .iter()
                .map(|c| {
                    vec![
                        c.what.clone(),
                        format!("{:.5}", c.value),
                        format!("{:.5}", c.reference),
                        format!("{:.5}", c.tolerance),
                        if c.pass { "yes" } else { "no" }.to_string(),
                    ]
                })
                .collect(),
        });
    }
    Section {
        title: name.to_string(),
        blocks,
        seconds: s.runs.iter().map(|r| r.seconds).sum(),
    }
}

/// The report of `results`, whose pictures are in `dir`.
pub fn report(results: &Results, dir: &Path) -> Report {
    let mut sections = vec![Section {
        title: "Every scene by every renderer".into(),
        blocks: vec![
            Block::Text(
                "Value: the failing check's, or the last one's (the region's mean luminance; in \
                 the metameric scenes the pair's ΔE00). ΔE00: the largest of the regions' from \
                 their references. FLIP: the picture's mean, reported, not judged."
                    .into(),
            ),
            table(results),
        ],
        seconds: 0.0,
    }];
    sections.extend(results.scenes.iter().map(|s| scene_section(s, dir)));
    Report {
        title: "gonio conformance".into(),
        intro: format!(
            "Appearance test scenes with analytic references, rendered by gonio and, through \
             gonio's exports (its tables as Mitsuba's tensor .bsdf and Radiance's XML BSDF), by \
             Mitsuba 3 and Radiance, whose native versions are shown beside them so that the \
             difference says what each export loses: {0} × {0} pixels, {1} samples per \
             pixel (gonio, Mitsuba; four times that in the metameric scenes). Values are mean \
             luminances (linear sRGB) over each region; the tolerance is 4 standard errors of \
             the Monte Carlo mean plus the bounded loss of the renderer's tables (docs/conformance.md).",
            results.size, results.spp
        ),
        summary: summary(results),
        sections,
    }
}
