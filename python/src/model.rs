//! `rbfsurf.Model`: a fitted implicit function f, positive inside, zero on the surface.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rbf_core::{AnyModel, FitReport, Kernel, Model as CoreModel};
use rbf_far::Evaluator;
use rbf_mesh::{PolygonizeSettings, Resolution, polygonize_continuation, polygonize_grid};
use rbf_render::{Camera, Csg, Object, RenderSettings, render_framed};

use crate::arrays::{Floats, count, mesh_arrays, owned};
use crate::error::bad;

/// A fitted model: f(x) = Σ wⱼ φ(|x − cⱼ|) + a + b·x, positive inside, zero on the surface,
/// negative outside (for RBFInterpolator's models: the interpolated data).
///
/// Call it on an (n, dim) array for values; ``gradient`` for ∇f. 3D models polygonize and
/// render. Models are saved as the JSON that the ``rbf`` command reads (``rbf info``,
/// ``rbf mesh``), and pickle.
///
/// >>> import numpy as np, rbfsurf
/// >>> m = rbfsurf.fit(interior=[[0, 0, 0]], boundary=np.eye(3).tolist() + [[-1, -1, -1]])
/// >>> round(float(m([[0, 0, 0]])[0]), 9)
/// 1.0
#[pyclass(module = "rbfsurf", frozen)]
pub(crate) struct Model {
    pub(crate) inner: AnyModel,
}

/// A model of a known dimension, as one of either.
pub(crate) trait IntoAnyModel {
    fn into_any(self) -> AnyModel;
}

impl IntoAnyModel for CoreModel<2> {
    fn into_any(self) -> AnyModel {
        AnyModel::Two(self)
    }
}

impl IntoAnyModel for CoreModel<3> {
    fn into_any(self) -> AnyModel {
        AnyModel::Three(self)
    }
}

impl Model {
    pub(crate) fn new(model: impl IntoAnyModel) -> Self {
        Self {
            inner: model.into_any(),
        }
    }

    fn three(&self, what: &str) -> PyResult<&CoreModel<3>> {
        match &self.inner {
            AnyModel::Three(m) => Ok(m),
            AnyModel::Two(_) => Err(bad(format!(
                "this is a 2D model: {what} works on surfaces in 3D"
            ))),
        }
    }
}

/// Values of a D-dimensional model at the rows of `x` (or, with `gradient`, its gradients
/// row by row), on every core without the GIL; and the number of rows.
fn evaluate<const D: usize>(
    py: Python<'_>,
    m: &CoreModel<D>,
    x: &Floats<'_>,
    gradient: bool,
) -> PyResult<(Vec<f64>, usize)> {
    let points = x.points::<D>("x")?;
    let view = m.interpolant.view();
    let out = py.detach(|| {
        // Large models through the far field, within 1e-6 of the centres' diagonal.
        let f = Evaluator::with_default_accuracy(view, &points);
        let mut values = vec![0.0; points.len()];
        if !gradient {
            let _ = f.values(&points, &mut values);
            return values;
        }
        let mut grads = vec![[0.0; D]; points.len()];
        let _ = f.values_and_gradients(&points, &mut values, &mut grads);
        grads.into_flattened()
    });
    Ok((out, points.len()))
}

fn report_dict<'py>(py: Python<'py>, r: &FitReport) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("rows", r.rows)?;
    d.set_item("residual", r.residual)?;
    d.set_item("condition", r.condition)?;
    // The model file's name of the method (`projected-cholesky`, `iterative`, …).
    let method = serde_json::to_value(r.method)
        .ok()
        .and_then(|v| v.as_str().map(str::to_owned))
        .unwrap_or_default();
    d.set_item("method", method)?;
    d.set_item("refinements", r.refinements)?;
    d.set_item("iterations", r.iterations)?;
    Ok(d)
}

/// The scipy name of a kernel.
pub(crate) fn kernel_name(k: Kernel) -> &'static str {
    match k {
        Kernel::Linear => "linear",
        Kernel::ThinPlate => "thin_plate_spline",
        _ => "cubic",
    }
}

#[pymethods]
impl Model {
    /// f at the rows of ``x``, an (n, dim) array-like (float64 arrays are read in place):
    /// an (n,) float64 array. A row with a NaN or an infinity raises ``RbfError`` naming it
    /// (scipy would return NaN; a silent NaN travels far before anyone sees it).
    fn __call__<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let x = Floats::new(x, "x")?;
        let (v, n) = match &self.inner {
            AnyModel::Two(m) => evaluate(py, m, &x, false)?,
            AnyModel::Three(m) => evaluate(py, m, &x, false)?,
        };
        owned(py, v, &[n])
    }

    /// ∇f at the rows of ``x``: an (n, dim) float64 array.
    fn gradient<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let x = Floats::new(x, "x")?;
        let dim = self.dim();
        let (g, n) = match &self.inner {
            AnyModel::Two(m) => evaluate(py, m, &x, true)?,
            AnyModel::Three(m) => evaluate(py, m, &x, true)?,
        };
        owned(py, g, &[n, dim])
    }

    /// 2 or 3.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dimension()
    }

    /// The kernel, by scipy's name: ``"cubic"`` (r³), ``"linear"`` (r) or
    /// ``"thin_plate_spline"`` (r² log r).
    #[getter]
    fn kernel(&self) -> &'static str {
        match &self.inner {
            AnyModel::Two(m) => kernel_name(m.interpolant.kernel()),
            AnyModel::Three(m) => kernel_name(m.interpolant.kernel()),
        }
    }

    /// The centres cⱼ: an (n, dim) array.
    #[getter]
    fn centres<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match &self.inner {
            AnyModel::Two(m) => owned(
                py,
                m.interpolant.centres().as_flattened().to_vec(),
                &[m.interpolant.centres().len(), 2],
            ),
            AnyModel::Three(m) => owned(
                py,
                m.interpolant.centres().as_flattened().to_vec(),
                &[m.interpolant.centres().len(), 3],
            ),
        }
    }

    /// The weights wⱼ: an (n,) array.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let w = match &self.inner {
            AnyModel::Two(m) => m.interpolant.weights().to_vec(),
            AnyModel::Three(m) => m.interpolant.weights().to_vec(),
        };
        let n = w.len();
        owned(py, w, &[n])
    }

    /// The fit's figures — ``rows``, ``residual`` (max|f(cᵢ) − hᵢ| / max|hᵢ|), ``condition``
    /// (NaN when not estimated), ``method``, ``iterations`` — or None.
    #[getter]
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let r = match &self.inner {
            AnyModel::Two(m) => m.report.as_ref(),
            AnyModel::Three(m) => m.report.as_ref(),
        };
        r.map(|r| report_dict(py, r)).transpose()
    }

    /// The model as the JSON of ``rbf fit``'s model files.
    fn to_json(&self) -> String {
        match &self.inner {
            AnyModel::Two(m) => m.to_json(),
            AnyModel::Three(m) => m.to_json(),
        }
    }

    /// Reads a model from the JSON of a model file.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        AnyModel::from_json(text)
            .map(|inner| Self { inner })
            .map_err(bad)
    }

    /// Writes the model file (JSON) that ``rbfsurf.load`` and the ``rbf`` command read.
    fn save(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        py.detach(|| {
            // Through a temporary file and a rename: an interrupted save leaves the old file.
            let name = path
                .file_name()
                .map_or("model".into(), |n| n.to_string_lossy().into_owned());
            let tmp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
            let written =
                std::fs::write(&tmp, self.to_json()).and_then(|_| std::fs::rename(&tmp, &path));
            if written.is_err() {
                let _ = std::fs::remove_file(&tmp);
            }
            written
        })
        .map_err(|e| pyo3::exceptions::PyOSError::new_err(format!("{}: {e}", path.display())))
    }

    /// The surface f = 0 as a triangle mesh: ``(vertices, faces)``, an (n, 3) float64 array and
    /// an (m, 3) int64 array, outward-facing. ``resolution`` cubes across the longest side of
    /// the surface's box; ``method="continuation"`` crawls from the model's boundary
    /// constraints, ``"grid"`` samples the whole box (finds pieces without constraints).
    /// A closed surface gives a watertight mesh.
    #[pyo3(signature = (resolution=128, *, method="continuation"))]
    fn polygonize<'py>(
        &self,
        py: Python<'py>,
        resolution: i64,
        method: &str,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let model = self.three("polygonize")?;
        let resolution = count(resolution, 2..=2048, "resolution")?;
        let grid = match method {
            "continuation" => false,
            "grid" => true,
            other => {
                return Err(bad(format!(
                    "method must be \"continuation\" or \"grid\", not {other:?}"
                )));
            }
        };
        let settings = PolygonizeSettings {
            resolution: Resolution::Cells(resolution),
            ..Default::default()
        };
        let view = model.interpolant.view();
        let result = py.detach(|| {
            let f = Evaluator::with_default_accuracy(view, view.centres());
            if grid {
                polygonize_grid(&f, &settings)
            } else {
                polygonize_continuation(&f, &rbf_mesh::surface_seeds(model), &settings)
            }
        });
        let (mesh, _) = result.map_err(bad)?;
        mesh_arrays(py, &mesh)
    }

    /// A ray-traced picture: an (height, width, 3) uint8 sRGB array. The camera orbits the
    /// surface's box (``azimuth``, ``elevation`` in degrees); ``samples`` rays per pixel side
    /// (antialiasing), ``shadows`` on the ground.
    #[pyo3(signature = (width=640, height=480, *, azimuth=30.0, elevation=20.0, samples=2, shadows=false, ground=true))]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        width: i64,
        height: i64,
        azimuth: f64,
        elevation: f64,
        samples: i64,
        shadows: bool,
        ground: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let model = self.three("render")?;
        let side = 1..=rbf_render::MAX_SIDE as usize;
        let width = count(width, side.clone(), "width")? as u32;
        let height = count(height, side, "height")? as u32;
        let samples = count(samples, 1..=16, "samples")? as u32;
        if !(azimuth.is_finite() && elevation.is_finite()) {
            return Err(bad(
                "azimuth and elevation must be finite numbers of degrees",
            ));
        }
        let settings = RenderSettings {
            samples,
            shadows,
            ground,
            ..Default::default()
        };
        let view = model.interpolant.view();
        let objects = [Object::new(Csg::Model(0), 0)];
        let image = py
            .detach(|| {
                let views = [Evaluator::with_coarse(
                    view,
                    view.centres(),
                    rbf_far::default_accuracy(view.centres()),
                )];
                render_framed(&views, &objects, &settings, (width, height), |lo, hi| {
                    Camera::orbit(lo, hi, azimuth, elevation, width, height)
                })
                .map(|(image, _, _)| image)
            })
            .map_err(bad)?;
        let (h, w) = (image.height() as usize, image.width() as usize);
        owned(py, image.to_srgb8(), &[h, w, 3])
    }

    /// Pickles as the model's JSON.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let from_json = py.get_type::<Model>().getattr("from_json")?;
        Ok((from_json, (self.to_json(),)))
    }

    fn __repr__(&self) -> String {
        let (centres, report) = match &self.inner {
            AnyModel::Two(m) => (m.interpolant.centres().len(), m.report.as_ref()),
            AnyModel::Three(m) => (m.interpolant.centres().len(), m.report.as_ref()),
        };
        let residual = report.map_or(String::new(), |r| format!(", residual {:.1e}", r.residual));
        format!(
            "<rbfsurf.Model: {}D, {} kernel, {centres} centres{residual}>",
            self.dim(),
            self.kernel()
        )
    }
}
