//! # rbfsurf (Python)
//!
//! The native module `rbfsurf._native` of the Python package in this folder: NumPy arrays in,
//! the workspace's fits, evaluation, polygonizing, rendering, conversion, voxels and sculpting
//! with the GIL released, NumPy arrays out. The Python layer (`rbfsurf/`) adds scipy's
//! `RBFInterpolator` and the keyword-friendly `fit`. Built by maturin (`pip install ./python`);
//! tested by pytest on the installed wheel (`python/tests`).

use pyo3::prelude::*;

mod arrays;
mod error;
mod fitting;
mod meshes;
mod model;
mod session;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("RbfError", m.py().get_type::<error::RbfError>())?;
    m.add_class::<model::Model>()?;
    m.add_class::<session::Session>()?;
    m.add_function(wrap_pyfunction!(fitting::_fit, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::_convert, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::_voxelize, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::_reconstruct, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::write_mesh, m)?)?;
    Ok(())
}
