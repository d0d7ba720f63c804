//! The reports for Python: the demo written up as `report.html` by [`gonio_report::demo`], the
//! same call as `gonio demo`, and the conformance suite's by [`gonio_report::conformance`], the
//! same call as `gonio conformance`.

use crate::error::{Result, invalid};
use gonio_conformance::{Options, Renderer};
use gonio_report::demo::{DemoPlan, DemoProgress};
use pyo3::prelude::*;
use std::path::PathBuf;

/// Run the demo into the folder `output_dir` (`quick`: the small run the tests use) and return
/// the report's path. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (output_dir, quick))]
pub fn report_demo(py: Python<'_>, output_dir: PathBuf, quick: bool) -> Result<PathBuf> {
    let plan = DemoPlan {
        output: output_dir,
        quick,
    };
    let outcome = py.detach(move || gonio_report::demo::run(&plan, &DemoProgress::default()))?;
    Ok(outcome.report)
}

/// Run the conformance suite on `renderers` (names; `None`: every renderer) at `spp` samples
/// per pixel (`None`: 64) into the folder `output_dir`, write its report there, and return the
/// results as JSON text (`results.json`'s) and the report's path. The GIL is released while it
/// runs.
#[pyfunction]
#[pyo3(signature = (output_dir, renderers, spp))]
pub fn report_conformance(
    py: Python<'_>,
    output_dir: PathBuf,
    renderers: Option<Vec<String>>,
    spp: Option<u32>,
) -> Result<(String, PathBuf)> {
    let renderers = match renderers {
        None => Renderer::ALL.to_vec(),
        Some(names) => names
            .iter()
            .map(|n| {
                Renderer::from_name(n).ok_or_else(|| {
                    invalid(format!(
                        "renderers: unknown renderer '{n}' (gonio, mitsuba or radiance)"
                    ))
                })
            })
            .collect::<Result<Vec<_>>>()?,
    };
    let options = Options {
        renderers,
        spp: spp.unwrap_or(64),
        dir: output_dir,
    };
    let (results, path) = py.detach(move || gonio_report::conformance::run(&options))?;
    let json = serde_json::to_string(&results)
        .map_err(|e| invalid(format!("the conformance results: {e}")))?;
    Ok((json, path))
}
