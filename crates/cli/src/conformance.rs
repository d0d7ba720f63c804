//! `gonio conformance`: the appearance conformance suite (`gonio_conformance`,
//! docs/conformance.md) on gonio's renderer and, through gonio's exports, on Mitsuba 3 and
//! Radiance; a summary table, the report in `-o DIR` (composed by `gonio_report::conformance`),
//! exit status 1 when a renderer fails a scene it can represent.

use anyhow::{Context, Result, bail};
use clap::Args;
use gonio_conformance::{Options, Renderer};
use gonio_report::conformance::verdict_name;
use std::path::PathBuf;

#[derive(Args)]
pub struct ConformanceArgs {
    /// Folder of the report (report.html, results.json, the pictures as PNG) and of the scenes'
    /// files for each renderer (files/).
    #[arg(short, long, value_name = "DIR", default_value = "conformance")]
    output: PathBuf,
    /// The renderers, comma-separated: gonio, mitsuba (Python module mitsuba), radiance
    /// (Python module pyradiance). A missing peer is reported unavailable, or is an error under
    /// GONIO_REQUIRE_ORACLES=1.
    #[arg(long, value_delimiter = ',', default_value = "gonio,mitsuba,radiance")]
    renderers: Vec<String>,
    /// Samples per pixel of gonio and Mitsuba (the pictures are 64 × 64 pixels); 1 to 65536.
    #[arg(long, default_value_t = 64)]
    spp: u32,
    /// Print the results as JSON instead of the table.
    #[arg(long)]
    json: bool,
}

pub fn run(a: ConformanceArgs) -> Result<()> {
    if !(1..=65536).contains(&a.spp) {
        bail!("--spp: {} is not between 1 and 65536", a.spp);
    }
    let renderers = a
        .renderers
        .iter()
        .map(|n| {
            Renderer::from_name(n.trim()).with_context(|| {
                format!("--renderers: unknown renderer `{n}` (gonio, mitsuba or radiance)")
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let (results, report) = gonio_report::conformance::run(&Options {
        renderers,
        spp: a.spp,
        dir: a.output.clone(),
    })?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&results)?);
    } else {
        println!(
            "{:<14} {:<16} {:<12} {:>10} {:>10} {:>9} {:>7} {:>6}",
            "scene", "renderer", "verdict", "value", "reference", "tolerance", "ΔE00", "FLIP"
        );
        for s in &results.scenes {
            for r in &s.runs {
                let verdict = verdict_name(r.verdict);
                // The failing check, or the last (a metameric scene's pair).
                let worst = r.checks.iter().find(|c| !c.pass).or(r.checks.last());
                let de = r.regions.iter().map(|g| g.delta_e00).fold(0.0, f64::max);
                match worst {
                    Some(c) => println!(
                        "{:<14} {:<16} {:<12} {:>10.5} {:>10.5} {:>9.5} {:>7.3} {:>6.3}",
                        s.scene.id.name(),
                        r.label(),
                        verdict,
                        c.value,
                        c.reference,
                        c.tolerance,
                        de,
                        r.flip_mean
                    ),
                    None => println!(
                        "{:<14} {:<16} {:<12}",
                        s.scene.id.name(),
                        r.label(),
                        verdict
                    ),
                }
            }
        }
        println!("report: {}", report.display());
    }
    if !results.passed() {
        eprintln!("conformance: a renderer failed a scene it can represent");
        std::process::exit(1);
    }
    Ok(())
}
