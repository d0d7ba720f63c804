//! `gonio._gonio`, the compiled half of the Python package `gonio` (built by maturin from
//! `crates/python`; the pure-Python half in `python/gonio` turns its columns into pandas
//! DataFrames and runs studies on Dask). Every function is a thin call into gonio's crates:
//! the physics is theirs, so Python and the command line give the same numbers. Long
//! computations release the GIL (`Python::detach`) and run on rayon's threads, so that Python
//! threads and Dask workers compute in parallel.

mod coating;
mod color;
mod error;
mod instruments;
mod matching;
mod render;
mod report;
mod surface;
mod table;

use pyo3::prelude::*;

#[pymodule]
fn _gonio(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("COLUMNS", gonio_instrument::curves::COLUMNS.to_vec())?;
    let names = |set: &[gonio_instrument::multiangle::Geometry]| -> Vec<String> {
        set.iter().map(|g| g.to_string()).collect()
    };
    m.add("E2194", names(&gonio_instrument::multiangle::E2194))?;
    m.add("E2539", names(&gonio_instrument::multiangle::E2539))?;
    m.add_class::<surface::Surface>()?;
    m.add_function(wrap_pyfunction!(surface::read_surface, m)?)?;
    m.add_function(wrap_pyfunction!(surface::synthesize, m)?)?;
    m.add_function(wrap_pyfunction!(instruments::inplane_columns, m)?)?;
    m.add_function(wrap_pyfunction!(instruments::gloss_json, m)?)?;
    m.add_function(wrap_pyfunction!(instruments::multiangle_columns, m)?)?;
    m.add_class::<table::Table>()?;
    m.add_function(wrap_pyfunction!(table::import_table, m)?)?;
    m.add_function(wrap_pyfunction!(table::tabulate, m)?)?;
    m.add_function(wrap_pyfunction!(table::compute_table, m)?)?;
    m.add_function(wrap_pyfunction!(render::render_scene, m)?)?;
    m.add_function(wrap_pyfunction!(report::report_demo, m)?)?;
    m.add_function(wrap_pyfunction!(render::booth_json, m)?)?;
    m.add_function(wrap_pyfunction!(report::report_conformance, m)?)?;
    m.add_function(wrap_pyfunction!(color::xyz, m)?)?;
    m.add_function(wrap_pyfunction!(color::from_lab, m)?)?;
    m.add_class::<coating::Coating>()?;
    m.add("TABLE_WALKS", gonio_coating::system::TABLE_WALKS)?;
    m.add("TARGET_DL", gonio_coating::system::TARGET_DL)?;
    m.add_function(wrap_pyfunction!(coating::read_coating, m)?)?;
    m.add_class::<coating::SensitivityPlan>()?;
    m.add_function(wrap_pyfunction!(coating::sensitivity_plan, m)?)?;
    m.add_function(wrap_pyfunction!(matching::match_coating, m)?)?;
    m.add_class::<matching::SelectionPlan>()?;
    m.add_function(wrap_pyfunction!(matching::selection_plan, m)?)?;
    m.add_function(wrap_pyfunction!(matching::selection_search, m)?)?;
    Ok(())
}
