//! Python bindings of the workspace (`import facesort`): thin conversions between numpy
//! arrays and the library's types, errors as Python exceptions, long work without the GIL.
//!
//! Nothing geometric is written here: every order, file and edge comes from `face-sort`,
//! `aspect-bake` and `sprite-compose`. The Python package around this module
//! (`python/facesort/`) adds the matplotlib projection and the vpype plugin.

mod camera;
mod exact;
mod files;
mod guard;
mod input;
mod mesh;

use pyo3::prelude::*;

/// The native module, `facesort._native`.
#[pymodule]
#[pyo3(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<mesh::Mesh>()?;
    m.add_class::<camera::Camera>()?;
    m.add_class::<mesh::Order>()?;
    m.add_class::<mesh::Presorted>()?;
    m.add_class::<files::Plot>()?;
    m.add_class::<files::YawBake>()?;
    m.add_class::<exact::ExactScene>()?;
    m.add_function(wrap_pyfunction!(files::svg, m)?)?;
    m.add_function(wrap_pyfunction!(files::pdf, m)?)?;
    m.add_function(wrap_pyfunction!(files::html, m)?)?;
    m.add_function(wrap_pyfunction!(files::plot_edges, m)?)?;
    m.add_function(wrap_pyfunction!(files::bake_yaw, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
