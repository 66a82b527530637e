//! The boundary: no panic crosses into Python, and library errors become the documented
//! exceptions.

use std::fmt::Display;
use std::panic::{AssertUnwindSafe, catch_unwind};

use pyo3::PyResult;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// Runs `work` with the GIL released (other Python threads run meanwhile), turning a panic
/// into a `RuntimeError` that says it is a bug, never an abort or a `PanicException`.
pub fn detached<T: Send>(py: Python<'_>, work: impl FnOnce() -> PyResult<T> + Send) -> PyResult<T> {
    py.detach(|| caught(work))
}

/// [`detached`] without releasing the GIL (for work that touches Python objects).
pub fn caught<T>(work: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(work)) {
        Ok(result) => result,
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_owned());
            Err(PyRuntimeError::new_err(format!(
                "facesort internal error (a bug: please report it with the input): {message}"
            )))
        }
    }
}

/// A library error about the caller's input, as a `ValueError` that starts with what was
/// being done.
pub fn value_error(context: &str, error: impl Display) -> PyErr {
    PyValueError::new_err(format!("{context}: {error}"))
}
