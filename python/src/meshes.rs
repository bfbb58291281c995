//! Triangle meshes in and out: files, conversion to implicit surfaces, reconstruction from
//! scans, voxels and distances.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rbf_convert::{
    ConvertError, IterativeSettings, NormalSettings, ReconstructSettings, ScanSurface,
    convert_iterative, convert_normals, mesh_resolution, scan_surface, trimmed,
};
use rbf_core::NormalOffset;
use rbf_mesh::{TriMesh, VoxelMethod, VoxelSettings, signed_distance, voxelize};

use crate::arrays::{Floats, count, mesh_arrays, owned, triangles};
use crate::error::bad;
use crate::model::Model;

/// A `TriMesh` from an (n, 3) vertex array and an (m, 3) face array.
fn mesh(vertices: &Bound<'_, PyAny>, faces: &Bound<'_, PyAny>) -> PyResult<TriMesh> {
    let v = Floats::new(vertices, "vertices")?;
    let positions = v.points::<3>("vertices")?.into_owned();
    let tris = triangles(faces, positions.len())?;
    TriMesh::new(positions, tris).map_err(bad)
}

/// Reads a mesh file (OBJ, PLY, STL): ``(vertices, faces)`` as (n, 3) float64 and (m, 3) int64
/// arrays.
#[pyfunction]
pub(crate) fn read_mesh<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let mesh = py.detach(|| rbf_mesh::read_mesh(&path)).map_err(bad)?;
    mesh_arrays(py, &mesh)
}

/// Writes ``(vertices, faces)`` as a mesh file; the extension (.obj, .ply, .stl) decides the
/// format.
#[pyfunction]
pub(crate) fn write_mesh(
    py: Python<'_>,
    path: std::path::PathBuf,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let mesh = mesh(vertices, faces)?;
    py.detach(|| rbf_mesh::write_mesh(&path, &mesh))
        .map_err(bad)
}

/// The conversion of a closed mesh to an implicit surface (see ``rbfsurf.convert``).
#[pyfunction]
#[pyo3(signature = (vertices, faces, *, method="iterative", resolution=128, max_constraints=None, max_iterations=30, smoothing=0.0, offset=0.01))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _convert<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    method: &str,
    resolution: i64,
    max_constraints: Option<i64>,
    max_iterations: i64,
    smoothing: f64,
    offset: f64,
) -> PyResult<(Model, Bound<'py, PyDict>)> {
    let mesh = mesh(vertices, faces)?;
    let resolution = count(resolution, 8..=1024, "resolution")?;
    let max_iterations = count(max_iterations, 1..=1000, "max_iterations")?;
    let max_constraints = max_constraints
        .map(|m| count(m, 1..=usize::MAX, "max_constraints"))
        .transpose()?;
    let fail = |e: ConvertError| bad(e);
    let report = PyDict::new(py);
    report.set_item("method", method)?;
    let model = match method {
        "normals" => {
            if !(offset > 0.0 && offset.is_finite()) {
                return Err(bad(format!(
                    "offset must be a finite fraction > 0, not {offset}"
                )));
            }
            let settings = NormalSettings {
                offset: NormalOffset::Relative(offset),
                max_vertices: max_constraints.unwrap_or(usize::MAX),
                lambda: smoothing,
                tolerance: None,
            };
            let (model, r) = py
                .detach(|| convert_normals(&mesh, &settings, |_| {}))
                .map_err(fail)?;
            report.set_item("vertices", r.vertices)?;
            report.set_item("vertices_used", r.vertices_used)?;
            report.set_item("without_normal", r.without_normal)?;
            report.set_item("rows", r.fit.rows)?;
            report.set_item("residual", r.fit.residual)?;
            model
        }
        "iterative" => {
            let settings = IterativeSettings {
                resolution,
                max_iterations,
                max_constraints: max_constraints
                    .unwrap_or(IterativeSettings::default().max_constraints),
                lambda: smoothing,
                ..Default::default()
            };
            let (model, r) = py
                .detach(|| convert_iterative(&mesh, &settings, |_, _| {}))
                .map_err(fail)?;
            let best = &r.iterations[r.best.saturating_sub(1).min(r.iterations.len() - 1)];
            report.set_item("shape", r.shape.to_vec())?;
            report.set_item("voxel_size", r.voxel_size)?;
            report.set_item("watertight", r.watertight)?;
            report.set_item("iterations", r.iterations.len())?;
            report.set_item("best_iteration", r.best)?;
            report.set_item("max_error_voxels", best.max_error)?;
            report.set_item("rms_error_voxels", best.rms_error)?;
            report.set_item("constraints", model.constraints.len())?;
            if let Some(t) = r.topology {
                report.set_item("mesh_genus", t.goal_genus)?;
                report.set_item("mesh_components", t.goal_components)?;
                report.set_item("genus", t.genus)?;
                report.set_item("components", t.components)?;
                report.set_item("topology_kept", t.agrees())?;
            }
            // Where the loop fell short, its rival (normal constraints at the vertices) was
            // measured too; kept, its errors are the model's (the loop's stay in
            // `best_iteration`'s figures, `loop_*`).
            if let Some(rival) = r.rival {
                if rival.kept {
                    report.set_item("loop_max_error_voxels", best.max_error)?;
                    report.set_item("loop_rms_error_voxels", best.rms_error)?;
                    report.set_item("max_error_voxels", rival.max_error)?;
                    report.set_item("rms_error_voxels", rival.rms_error)?;
                }
                report.set_item("rival_kept", rival.kept)?;
                report.set_item("rival_vertices", rival.vertices)?;
                report.set_item("rival_max_error_voxels", rival.max_error)?;
                report.set_item("rival_rms_error_voxels", rival.rms_error)?;
            }
            model
        }
        other => {
            return Err(bad(format!(
                "method must be \"iterative\" or \"normals\", not {other:?}"
            )));
        }
    };
    if let Some(r) = &model.report {
        report.set_item("fit_residual", r.residual)?;
    }
    Ok((Model::new(model), report))
}

/// Voxels of a closed mesh (see ``rbfsurf.voxelize``): the values, the centre of voxel
/// (0, 0, 0) and the voxel size.
#[pyfunction]
#[pyo3(signature = (vertices, faces, *, resolution=64, supersampling=4, method="auto", distance=false))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn _voxelize<'py>(
    py: Python<'py>,
    vertices: &Bound<'py, PyAny>,
    faces: &Bound<'py, PyAny>,
    resolution: i64,
    supersampling: i64,
    method: &str,
    distance: bool,
) -> PyResult<(Bound<'py, PyAny>, [f64; 3], f64)> {
    let mesh = mesh(vertices, faces)?;
    let resolution = count(resolution, 1..=4096, "resolution")?;
    let supersampling = count(
        supersampling,
        1..=rbf_mesh::MAX_SUPERSAMPLING,
        "supersampling",
    )?;
    let method = match method {
        "auto" => VoxelMethod::Auto,
        "rays" => VoxelMethod::Rays,
        "winding" => VoxelMethod::Winding,
        other => {
            return Err(bad(format!(
                "method must be \"auto\", \"rays\" or \"winding\", not {other:?}"
            )));
        }
    };
    let settings = VoxelSettings {
        resolution,
        supersampling,
        method,
        memory_limit: rbf_solve::memory_budget(),
        ..Default::default()
    };
    let volume = py
        .detach(|| {
            voxelize(&mesh, &settings).map(|v| if distance { signed_distance(&v) } else { v })
        })
        .map_err(bad)?;
    let origin = volume.origin;
    let size = volume.voxel_size;
    let shape = volume.shape;
    Ok((owned(py, volume.data, &shape)?, origin, size))
}

/// A scan to a closed surface (see ``rbfsurf.reconstruct``): the mesh, the model and a dict
/// of what was done.
#[pyfunction]
#[pyo3(signature = (points, normals=None, *, tolerance=None, smoothing=None, max_centres=None, keep_outliers=false, resolution=None, trim=None))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
pub(crate) fn _reconstruct<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    normals: Option<&Bound<'py, PyAny>>,
    tolerance: Option<f64>,
    smoothing: Option<f64>,
    max_centres: Option<i64>,
    keep_outliers: bool,
    resolution: Option<i64>,
    trim: Option<f64>,
) -> PyResult<(
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Model,
    Bound<'py, PyDict>,
)> {
    let p = Floats::new(points, "points")?;
    let positions = p.points::<3>("points")?.into_owned();
    let normals = match normals {
        Some(n) => {
            let n = Floats::new(n, "normals")?;
            let n = n.points::<3>("normals")?.into_owned();
            if n.len() != positions.len() {
                return Err(bad(format!(
                    "normals has {} rows for {} points",
                    n.len(),
                    positions.len()
                )));
            }
            Some(n)
        }
        None => None,
    };
    if let Some(t) = tolerance
        && !(t > 0.0 && t.is_finite())
    {
        return Err(bad(format!(
            "tolerance must be a finite number > 0, not {t}"
        )));
    }
    if let Some(smoothing) = smoothing
        && !(smoothing > 0.0 && smoothing.is_finite())
    {
        return Err(bad(format!(
            "smoothing must be a finite number > 0, not {smoothing} (tolerance=T fits greedily instead)"
        )));
    }
    if let Some(d) = trim
        && !(d > 0.0 && d.is_finite())
    {
        return Err(bad(format!("trim must be a finite number > 0, not {d}")));
    }
    let mut settings = ReconstructSettings {
        tolerance,
        smoothing,
        outlier_ratio: (!keep_outliers).then_some(2.5),
        ..Default::default()
    };
    if let Some(n) = max_centres {
        settings = settings.with_max_centres(count(n, 10..=1_000_000, "max_centres")?);
    }
    let resolution = resolution
        .map(|r| count(r, 2..=2048, "resolution"))
        .transpose()?;
    let (model, report, mesh, resolution, bubbles) = py
        .detach(|| {
            let resolution = resolution.unwrap_or_else(|| mesh_resolution(&positions));
            let ScanSurface {
                model,
                report,
                mesh,
                dropped: bubbles,
            } = scan_surface(&positions, normals.as_deref(), &settings, Some(resolution))?;
            let mesh = match trim {
                Some(d) => trimmed(&mesh, &positions, d)?,
                None => mesh,
            };
            Ok::<_, ConvertError>((model, report, mesh, resolution, bubbles))
        })
        .map_err(bad)?;
    let d = PyDict::new(py);
    d.set_item("points", report.points)?;
    d.set_item("duplicates", report.duplicates)?;
    d.set_item("outliers", report.outliers)?;
    d.set_item("working", report.working)?;
    d.set_item("normals_estimated", report.normals_estimated)?;
    d.set_item("normals_filled", report.normals_filled)?;
    d.set_item("flipped", report.flipped)?;
    d.set_item("refuted", report.refuted)?;
    d.set_item("reversed_by_winding", report.reversed_by_winding)?;
    d.set_item("reversed_by_sight", report.reversed_by_sight)?;
    d.set_item("looked_again", report.looked_again)?;
    d.set_item("disagreeing", report.disagreeing)?;
    d.set_item("contradicted", report.contradicted)?;
    d.set_item("pieces", report.pieces)?;
    d.set_item("neighbours", report.neighbours)?;
    d.set_item("noise", report.noise)?;
    d.set_item("smoothed", report.smoothed)?;
    d.set_item("tolerance", report.tolerance)?;
    d.set_item("centres", report.centres)?;
    d.set_item("added_where_sheets_close", report.added_where_sheets_close)?;
    d.set_item("lambda", report.lambda)?;
    d.set_item("beyond_tolerance", report.beyond_tolerance)?;
    d.set_item("largest_miss", report.largest_miss)?;
    d.set_item("within_tolerance", report.within_tolerance)?;
    d.set_item("resolution", resolution)?;
    d.set_item("outside_added", report.outside_added)?;
    d.set_item("bubbles_dropped", bubbles)?;
    let check = mesh.check();
    d.set_item("watertight", check.is_watertight())?;
    d.set_item("genus", check.genus)?;
    d.set_item("components", check.components)?;
    let (v, f) = mesh_arrays(py, &mesh)?;
    Ok((v, f, Model::new(model), d))
}
