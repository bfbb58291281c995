//! NumPy in and out: any array-like of numbers becomes float64 without a copy when it already
//! is one; results are NumPy arrays that own the vectors they were computed in.

use std::borrow::Cow;

use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::error::bad;

/// `numpy.asarray(obj, dtype)`: a view of an array that already has the type, a converted copy
/// otherwise (lists, other float widths, integers).
fn as_array<'py>(obj: &Bound<'py, PyAny>, dtype: &str, name: &str) -> PyResult<Bound<'py, PyAny>> {
    let py = obj.py();
    let numpy = py.import("numpy")?;
    if numpy.call_method1("iscomplexobj", (obj,))?.is_truthy()? {
        return Err(bad(format!("{name}: complex numbers are not taken")));
    }
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", dtype)?;
    numpy
        .call_method("asarray", (obj,), Some(&kwargs))
        .map_err(|e| {
            bad(format!(
                "{name}: cannot be read as an array of {dtype}: {e}"
            ))
        })
}

/// A float64 array of any shape, borrowed when possible.
pub(crate) struct Floats<'py> {
    array: PyReadonlyArrayDyn<'py, f64>,
}

impl<'py> Floats<'py> {
    /// Reads `obj` (an array-like of numbers); `name` is the argument's name in errors.
    pub(crate) fn new(obj: &Bound<'py, PyAny>, name: &str) -> PyResult<Self> {
        let array = as_array(obj, "float64", name)?
            .cast_into::<PyArrayDyn<f64>>()
            .map_err(|_| bad(format!("{name}: not an array of numbers")))?
            .try_readonly()
            .map_err(|e| bad(format!("{name}: {e}")))?;
        Ok(Self { array })
    }

    /// The shape.
    pub(crate) fn shape(&self) -> Vec<usize> {
        self.array.shape().to_vec()
    }

    /// The numbers in C order: the array's own memory when it is C-contiguous, a copy otherwise
    /// (Fortran order, strided views).
    pub(crate) fn values(&self) -> PyResult<Cow<'_, [f64]>> {
        if self.array.is_c_contiguous()
            && let Ok(s) = self.array.as_slice()
        {
            return Ok(Cow::Borrowed(s));
        }
        Ok(Cow::Owned(self.array.as_array().iter().copied().collect()))
    }

    /// The rows of an `(n, D)` array as points; an error naming `name` for another shape, and
    /// `name` and the row for the first row with a NaN or an infinity (every entry point that
    /// takes coordinates, queries included, refuses them: see [`finite_rows`]).
    pub(crate) fn points<const D: usize>(&self, name: &str) -> PyResult<Cow<'_, [[f64; D]]>> {
        let shape = self.shape();
        if shape.len() != 2 || shape[1] != D {
            return Err(bad(format!(
                "{name} must have shape (n, {D}), not {}",
                shape_text(&shape)
            )));
        }
        let points = match self.values()? {
            Cow::Borrowed(s) => Cow::Borrowed(s.as_chunks::<D>().0),
            Cow::Owned(v) => Cow::Owned(v.as_chunks::<D>().0.to_vec()),
        };
        finite_rows(&points, name)?;
        Ok(points)
    }

    /// A one-dimensional array of `n` numbers, or a scalar repeated `n` times.
    pub(crate) fn per_row(&self, n: usize, name: &str) -> PyResult<Vec<f64>> {
        let shape = self.shape();
        let values = self.values()?;
        match shape[..] {
            [] => Ok(vec![values[0]; n]),
            [m] if m == n => Ok(values.into_owned()),
            _ => Err(bad(format!(
                "{name} must be a number or have shape ({n},), not {}",
                shape_text(&shape)
            ))),
        }
    }
}

/// Refuses the first row of `points` with a coordinate that is NaN or infinite, naming
/// `name[row]` as rbfsurf's Python layer does (`rbfsurf._checks.points`).
pub(crate) fn finite_rows<const D: usize>(points: &[[f64; D]], name: &str) -> PyResult<()> {
    match points.iter().position(|p| !p.iter().all(|v| v.is_finite())) {
        None => Ok(()),
        Some(i) => {
            // Written as Python writes floats: nan, inf, -inf, 0.5.
            let coordinates: Vec<String> = points[i]
                .iter()
                .map(|v| {
                    if v.is_nan() {
                        "nan".into()
                    } else {
                        format!("{v:?}")
                    }
                })
                .collect();
            Err(bad(format!(
                "{name}[{i}] = [{}]: every coordinate must be a finite number",
                coordinates.join(", ")
            )))
        }
    }
}

/// The second dimension of an `(n, 2)` or `(n, 3)` array, which decides the model's dimension.
pub(crate) fn point_dimension(points: &Floats<'_>, name: &str) -> PyResult<usize> {
    match points.shape()[..] {
        [_, d @ (2 | 3)] => Ok(d),
        ref s => Err(bad(format!(
            "{name} must have shape (n, 2) or (n, 3): rbf fits curves in 2D and surfaces in 3D, not {}",
            shape_text(s)
        ))),
    }
}

/// Triangles as vertex indices: an `(m, 3)` array of whole numbers, checked against `vertices`.
pub(crate) fn triangles(obj: &Bound<'_, PyAny>, vertices: usize) -> PyResult<Vec<[u32; 3]>> {
    let faces = Floats::new(obj, "faces")?;
    let shape = faces.shape();
    if shape.len() != 2 || shape[1] != 3 {
        return Err(bad(format!(
            "faces must have shape (m, 3), not {}",
            shape_text(&shape)
        )));
    }
    let flat = faces.values()?;
    if let Some(k) = flat
        .iter()
        .position(|&i| !(i >= 0.0 && i < vertices as f64 && i.fract() == 0.0))
    {
        return Err(bad(format!(
            "faces: triangle {} uses vertex {}, but the vertices are numbered 0 to {}",
            k / 3,
            flat[k],
            vertices as i64 - 1
        )));
    }
    Ok(flat
        .chunks_exact(3)
        .map(|t| [t[0] as u32, t[1] as u32, t[2] as u32])
        .collect())
}

/// A count given from Python, checked to lie in `range` (a negative one is a `ValueError` too,
/// not an `OverflowError`).
pub(crate) fn count(
    value: i64,
    range: std::ops::RangeInclusive<usize>,
    name: &str,
) -> PyResult<usize> {
    match usize::try_from(value) {
        Ok(v) if range.contains(&v) => Ok(v),
        _ => Err(bad(format!(
            "{name} must be {} to {}, not {value}",
            range.start(),
            range.end()
        ))),
    }
}

/// `(n, …)` as Python prints a shape.
pub(crate) fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A mesh as NumPy arrays: `(vertices, faces)`, (n, 3) float64 and (m, 3) int64.
pub(crate) fn mesh_arrays<'py>(
    py: Python<'py>,
    mesh: &rbf_mesh::TriMesh,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (n, m) = (mesh.positions().len(), mesh.triangles().len());
    let faces: Vec<i64> = mesh
        .triangles()
        .as_flattened()
        .iter()
        .map(|&i| i64::from(i))
        .collect();
    Ok((
        owned(py, mesh.positions().as_flattened().to_vec(), &[n, 3])?,
        owned(py, faces, &[m, 3])?,
    ))
}

/// A NumPy array of `shape` owning `data` (C order).
pub(crate) fn owned<'py, T: numpy::Element>(
    py: Python<'py>,
    data: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let flat = PyArray1::from_vec(py, data);
    if shape.len() == 1 {
        return Ok(flat.into_any());
    }
    Ok(flat.reshape(shape)?.into_any())
}
