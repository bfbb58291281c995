//! The loop's rival (not in Yngve & Turk): normal constraints at an even spread of the mesh's
//! vertices (Turk & O'Brien 2002, §4.3), each inside point only as deep as it stays nearest
//! its own vertex among all of the mesh's (Carr et al. 2001's check), so that a wall thinner
//! than the offset is not crossed.
//!
//! The loop places its constraints by voxel errors, which cannot see a wall a couple of voxels
//! thick: on a spherical shell with a wall of 2 voxels and three openings (a skull's bony
//! shell, genus 2) it stalled with 576 constraints, 9.3 voxels off, genus 15 and six pieces.
//! Normal constraints at 2000 of its vertices hold both sides of the wall: genus 2, one
//! piece, within 0.2 voxel RMS of the mesh. Where the loop's model falls short of its goals,
//! the rival is fitted, measured the same way and kept if it ranks better ([`RivalReport`]).

use rbf_cloud::clear_offsets;
use rbf_core::{Constraint, FitSettings, Model, NormalOffset};
use rbf_mesh::TriMesh;

use crate::{ConvertError, poisson_subset};

/// The offset of the rival's normal constraints, as a fraction of the box's longest side:
/// Turk & O'Brien's 0.01 (`--method normals`'s default).
const OFFSET: f64 = 0.01;

/// What became of the rival of a loop that fell short of its goals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RivalReport {
    /// Vertices that carry its normal constraints (two rows each).
    pub vertices: usize,
    /// Its largest voxel error, measured as the loop's models are.
    pub max_error: f64,
    /// RMS of the same errors, in voxels.
    pub rms_error: f64,
    /// Its genus (`None`: its surface was not closed) and components, if measured: only a
    /// rival whose errors could win with the mesh's topology is.
    pub topology: Option<(Option<i64>, usize)>,
    /// Whether it was kept instead of the loop's model.
    pub kept: bool,
}

/// The fewest vertices a rival is fitted on.
const FEWEST_VERTICES: usize = 4;

/// The rival model of `mesh`: normal constraints at an even spread of at most `vertices` of
/// its vertices, fitted with the regularization `lambda`; an error for fewer than
/// [`FEWEST_VERTICES`].
pub(crate) fn rival_model(
    mesh: &TriMesh,
    vertices: usize,
    lambda: f64,
) -> Result<Model<3>, ConvertError> {
    if vertices < FEWEST_VERTICES {
        return Err(ConvertError::TooFewPoints {
            points: vertices,
            needed: FEWEST_VERTICES,
        });
    }
    let normals = mesh.vertex_normals();
    let candidates = crate::normals::vertices_with_normals(mesh, &normals);
    if candidates.is_empty() {
        return Err(ConvertError::NoNormals);
    }
    let points: Vec<[f64; 3]> = candidates.iter().map(|&v| mesh.positions()[v]).collect();
    let units: Vec<[f64; 3]> = candidates
        .iter()
        .map(|&v| rbf_core::vec3::normalize(normals[v]))
        .collect();
    let (lo, hi) = crate::poisson::bounds(&points);
    let longest = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let distance = OFFSET * longest;
    let chosen = poisson_subset(&points, vertices);
    // Cleared against every vertex, not only the chosen: the other side of a thin wall is
    // sampled as finely as the mesh is.
    let clear = clear_offsets(&points, &units, distance);
    let constraints: Vec<Constraint<3>> = chosen
        .iter()
        .map(|&i| {
            let inside = clear[i][0].max(distance / 32.0);
            Constraint::normal(points[i], units[i])
                .with_offset(inside)
                .with_value(inside / distance)
        })
        .collect();
    let settings = FitSettings {
        normal_offset: NormalOffset::Absolute(distance),
        lambda,
        ..Default::default()
    };
    let fit = rbf_solve::fit(&constraints, &settings)?;
    Ok(Model {
        constraints,
        settings,
        interpolant: fit.interpolant,
        report: Some(fit.report),
    })
}
