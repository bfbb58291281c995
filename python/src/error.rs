//! The one exception of the package: `rbfsurf.RbfError`, a `ValueError`, with the message the
//! `rbf` command prints.

use pyo3::PyErr;

pyo3::create_exception!(
    rbfsurf,
    RbfError,
    pyo3::exceptions::PyValueError,
    "Bad input or a fit that failed, with the message the `rbf` command gives (the constraint, \
     vertex or file at fault). A subclass of ValueError."
);

/// An `RbfError` carrying `message`.
pub(crate) fn bad(message: impl std::fmt::Display) -> PyErr {
    RbfError::new_err(message.to_string())
}
