//! The reports for Python: the demo written up as `report.html` by [`gonio_report::demo`], the
//! same call as `gonio demo`.

use crate::error::Result;
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
