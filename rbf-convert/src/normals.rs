//! Conversion by normal constraints (Turk & O'Brien 2002, §4.3).

use rbf_core::{Constraint, FitSettings, Model, NormalOffset};
use rbf_mesh::TriMesh;

use crate::{ConvertError, poisson_subset};

/// Settings of the normal-constraint conversion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalSettings {
    /// Offset of each normal constraint; 0.01 of the bounding box's longest side by default
    /// (the papers' 0.01 for a model in a unit cube).
    pub offset: NormalOffset,
    /// At most this many vertices are used (each gives two rows); more are thinned to an evenly
    /// spread subset. Every vertex by default (`usize::MAX`): above 2500 vertices the fit is
    /// iterative, in memory and time that grow with the vertices (a 48 000-vertex mesh whole).
    /// With a `tolerance`, the greedy fit's budget (5000 when unset).
    pub max_vertices: usize,
    /// Regularization λ of the fit.
    pub lambda: f64,
    /// Instead of an even spread, choose vertices greedily (`rbf_solve::fit_greedy`) until
    /// the surface meets every vertex, and the offset point of its normal constraint, within
    /// this fraction of the bounding box's longest side, using at most `max_vertices`. None
    /// (an even spread) by default.
    pub tolerance: Option<f64>,
}

impl Default for NormalSettings {
    fn default() -> Self {
        Self {
            offset: NormalOffset::Relative(0.01),
            max_vertices: usize::MAX,
            lambda: 0.0,
            tolerance: None,
        }
    }
}

/// How many vertices became constraints, whether they were thinned, and the fit's figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalReport {
    /// Vertices of the mesh used by its triangles.
    pub vertices: usize,
    /// Vertices that became constraints.
    pub vertices_used: usize,
    /// Vertices skipped because their normal has zero length (e.g. on a fold).
    pub without_normal: usize,
    /// Whether the vertices were thinned (to an even spread of `max_vertices`, or greedily).
    pub thinned: bool,
    /// With a tolerance: the largest miss over every vertex's constraint, as a fraction of the
    /// box's longest side, and whether it is within the tolerance.
    pub greedy: Option<(f64, bool)>,
    /// The fit's residual and condition estimate.
    pub fit: rbf_core::FitReport,
}

/// Which vertices of `mesh` its triangles use.
fn used_vertices(mesh: &TriMesh) -> Vec<bool> {
    let mut used = vec![false; mesh.positions().len()];
    for t in mesh.triangles() {
        for &v in t {
            used[v as usize] = true;
        }
    }
    used
}

/// The vertices its triangles use whose `normals` are finite and not zero.
pub(crate) fn vertices_with_normals(mesh: &TriMesh, normals: &[[f64; 3]]) -> Vec<usize> {
    let used = used_vertices(mesh);
    (0..used.len())
        .filter(|&v| used[v] && normals[v].iter().all(|c| c.is_finite()))
        .filter(|&v| normals[v].iter().any(|&c| c != 0.0))
        .collect()
}

/// Converts a mesh to an interpolating implicit surface through its vertices, with normal
/// constraints against the vertex normals, fitted with rbf-solve (`progress` hears the fit's
/// reports; the greedy choice reports nothing).
pub fn convert_normals(
    mesh: &TriMesh,
    settings: &NormalSettings,
    progress: impl FnMut(rbf_solve::FitProgress),
) -> Result<(Model<3>, NormalReport), ConvertError> {
    let normals = mesh.vertex_normals();
    let candidates = vertices_with_normals(mesh, &normals);
    let vertices = used_vertices(mesh).iter().filter(|&&u| u).count();
    if candidates.is_empty() {
        return Err(ConvertError::NoNormals);
    }
    let fit_settings = FitSettings {
        lambda: settings.lambda,
        normal_offset: settings.offset,
        ..Default::default()
    };
    let normal = |v: usize| Constraint::normal(mesh.positions()[v], normals[v]);
    let (fit, constraints, greedy) = match settings.tolerance {
        None => {
            let points: Vec<[f64; 3]> = candidates.iter().map(|&v| mesh.positions()[v]).collect();
            let chosen = poisson_subset(&points, settings.max_vertices);
            let constraints: Vec<Constraint<3>> =
                chosen.iter().map(|&i| normal(candidates[i])).collect();
            (
                rbf_solve::fit_with(
                    &constraints,
                    &fit_settings,
                    &rbf_solve::FitOptions::default(),
                    progress,
                )?,
                constraints,
                None,
            )
        }
        Some(tolerance) => {
            let all: Vec<Constraint<3>> = candidates.iter().map(|&v| normal(v)).collect();
            let greedy = rbf_solve::GreedySettings {
                tolerance,
                max_constraints: if settings.max_vertices == usize::MAX {
                    rbf_solve::GreedySettings::default().max_constraints
                } else {
                    settings.max_vertices
                },
                ..Default::default()
            };
            let (fit, r) = rbf_solve::fit_greedy(&all, &fit_settings, &greedy, |_| {})?;
            let worst = r
                .rounds
                .last()
                .map_or(f64::INFINITY, |round| round.max_error);
            (fit, r.constraints, Some((worst, r.converged)))
        }
    };
    let report = NormalReport {
        vertices,
        vertices_used: constraints.len(),
        without_normal: vertices - candidates.len(),
        thinned: constraints.len() < candidates.len(),
        greedy,
        fit: fit.report,
    };
    let model = Model {
        constraints,
        settings: fit_settings,
        interpolant: fit.interpolant,
        report: Some(fit.report),
    };
    Ok((model, report))
}
