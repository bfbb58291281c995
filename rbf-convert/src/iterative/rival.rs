//! The loop's rival (not in Yngve & Turk): normal constraints at an even spread of the mesh's
//! vertices (Turk & O'Brien 2002, §4.3), each inside point only as deep as it stays nearest
//! its own vertex among all of the mesh's (Carr et al. 2001's check), so that a wall thinner
//! than the offset is not crossed; where the wall under a vertex is thinner than two offsets
//! and at least a voxel thick, a slab holds both its sides ([`slab`]); then refined at its
//! largest voxel errors as the loop refines its own models ([`refine_rival`]).
//!
//! The loop places its constraints by voxel errors, which cannot see a wall a couple of voxels
//! thick: on a spherical shell with a wall of 2 voxels and three openings (a skull's bony
//! shell, genus 2) it stalled with 576 constraints, 9.3 voxels off, genus 15 and six pieces.
//! Normal constraints at 2000 of its vertices hold both sides of the wall: genus 2, one
//! piece, within 0.23 voxel RMS of the mesh but 2.96 voxels off at worst; with slabs at 1000
//! and the refinement, genus 2 within 0.08 voxel RMS and 1.29 at worst. Where the loop's model
//! falls short of its goals, the rival is fitted, measured the same way and kept if it ranks
//! better ([`RivalReport`]).

use rayon::prelude::*;
use rbf_cloud::{PointTree, clear_offsets};
use rbf_core::{Constraint, FitSettings, Model, NormalOffset};
use rbf_mesh::{TriMesh, WindingTree};

use super::IterativeSettings;
use super::goal::{Goal, summary};
use super::topology::first_change;
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
/// [`FEWEST_VERTICES`]. With the mesh's winding `tree`, a wall thinner than two offsets but not
/// than `thinnest` (a voxel) gets slabs ([`slab`]), and then the rows stay within
/// `2 · with_slabs`. A wall under a voxel gets none: held at its own thickness, a bowl's wall
/// of 0.85 voxel (`benches/thin_meshes.py`) came out within 0.2 voxel RMS but pinched into
/// holes near its rim, and cubes of half a voxel, which measure the topology, saw thousands of
/// handles in it. (Two offsets are 2.56 voxels at 128: the window holds walls of 1–2.56
/// voxels there, none below 50.)
pub(crate) fn rival_model(
    mesh: &TriMesh,
    tree: Option<&WindingTree>,
    thinnest: f64,
    vertices: usize,
    with_slabs: usize,
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
    // Cleared against every vertex, not only the chosen: the other side of a thin wall is
    // sampled as finely as the mesh is.
    let clear = clear_offsets(&points, &units, distance);
    // Normal constraints at `count` vertices, and the mirrors of those on thin walls.
    let place = |count: usize| {
        let chosen = poisson_subset(&points, count);
        let walls: Vec<Option<f64>> = match tree {
            Some(tree) => chosen
                .par_iter()
                .map(|&i| slab(tree, points[i], units[i], distance).filter(|&w| w >= thinnest))
                .collect(),
            None => vec![None; chosen.len()],
        };
        let chosen_points: Vec<[f64; 3]> = chosen.iter().map(|&i| points[i]).collect();
        let chosen_tree = PointTree::new(&chosen_points);
        let mut normal_constraints = Vec::with_capacity(chosen.len());
        let mut mirrors = Vec::new();
        for (&i, wall) in chosen.iter().zip(&walls) {
            let (p, n) = (points[i], units[i]);
            let inside = match wall {
                Some(w) => {
                    let far: [f64; 3] = core::array::from_fn(|d| p[d] - w * n[d]);
                    let held = chosen_tree
                        .nearest(&far)
                        .is_some_and(|(_, r)| r < MIRROR_CLEARANCE * distance);
                    if !held {
                        mirrors.push(Constraint::boundary(far));
                    }
                    0.5 * w
                }
                None => clear[i][0].max(distance / 32.0),
            };
            normal_constraints.push(
                Constraint::normal(p, n)
                    .with_offset(inside)
                    .with_value(inside / distance),
            );
        }
        (normal_constraints, mirrors)
    };
    let (mut constraints, mut mirrors) = place(vertices);
    // With slabs, fewer vertices: the rest of the rows for the refinement that finishes the
    // walls' rims.
    let rows = if mirrors.is_empty() {
        2 * vertices
    } else {
        2 * with_slabs.min(vertices)
    };
    let used = 2 * constraints.len() + mirrors.len();
    if used > rows {
        // Fewer vertices, in proportion, so that their mirrors fit too.
        (constraints, mirrors) = place((vertices * rows / used).max(FEWEST_VERTICES));
    }
    let room = rows.saturating_sub(2 * constraints.len());
    constraints.extend(mirrors.into_iter().take(room));
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

/// A wall's far side that lies this many offsets or nearer to a chosen vertex is not
/// constrained again: that vertex holds it.
const MIRROR_CLEARANCE: f64 = 0.5;

/// Steps per offset of [`slab`]'s march through a wall.
const SLAB_STEPS: f64 = 8.0;

/// The thickness of the mesh's wall under the surface point `p` with outward unit normal `n`,
/// if it is thinner than two offsets `distance`: where the mesh's inside (winding numbers
/// above ½) ends on the ray inward, marched in eighths of the offset and then bisected.
///
/// Normal constraints hold one side of a wall; where the wall is thinner than the spacing of
/// the vertices they sit on, its other side is free between them, and the fitted wall swells
/// or breaks. A slab holds both: the vertex, a boundary constraint on the far side (its
/// mirror), and the normal constraint's inside point halfway between, as deep as the wall is
/// thick.
fn slab(tree: &WindingTree, p: [f64; 3], n: [f64; 3], distance: f64) -> Option<f64> {
    let step = distance / SLAB_STEPS;
    let inside = |t: f64| tree.winding_number(core::array::from_fn(|d| p[d] - t * n[d])) > 0.5;
    if !inside(0.25 * step) {
        return None; // a normal that does not enter the solid cleanly (a sharp crease)
    }
    let (lo, hi) = first_change(inside, true, 2.0 * SLAB_STEPS * step, step, 10)?;
    Some(0.5 * (lo + hi))
}

/// Rounds of [`refine_rival`] at most.
const REFINE_ROUNDS: usize = 4;

/// The rival refined as the loop refines its models (Yngve & Turk's §5.3, [`Goal::refine`]):
/// constraints at its largest voxel errors, their values in the rival's scale (offsets), up to
/// `rows` rows in all, for at most [`REFINE_ROUNDS`] rounds; the round with the smallest
/// maximum error (then RMS) is kept. Where a thin wall ends (the rim of an opening), the
/// spread's slabs leave its middle free and the fitted wall runs on across the opening: on the
/// skull-like shell, a film four voxels into its lower opening, which the first rounds'
/// exterior constraints took away. A round may be worse before a later one is better (the
/// plate of `benches/thin_meshes.py`: 2.83 → 3.00 → 2.00 → 1.41 voxels).
pub(crate) fn refine_rival(
    goal: &Goal,
    mut rival: Model<3>,
    settings: &IterativeSettings,
    rows: usize,
) -> Model<3> {
    let scale = match rival.settings.normal_offset {
        NormalOffset::Absolute(d) if d > 0.0 => 1.0 / d,
        _ => 1.0,
    };
    let rows_of = |m: &Model<3>| -> usize { m.constraints.iter().map(Constraint::rows).sum() };
    if rows_of(&rival) >= rows {
        return rival; // no room: a rival without slabs, whose spread took the whole share
    }
    let mut errors = goal.errors(&goal.evaluate(&rival.interpolant.view(), settings));
    let mut best = (summary(&errors), rival.clone());
    for _ in 0..REFINE_ROUNDS {
        let room = rows.saturating_sub(rows_of(&rival));
        if room == 0 {
            break;
        }
        let mut constraints = rival.constraints.clone();
        let before = constraints.len();
        let budget = IterativeSettings {
            max_constraints: before + room,
            ..*settings
        };
        if goal.refine(&errors, &mut constraints, &budget, true) == 0 {
            break;
        }
        for c in &mut constraints[before..] {
            c.value *= scale;
        }
        let Ok(fit) = rbf_solve::fit(&constraints, &rival.settings) else {
            break;
        };
        errors = goal.errors(&goal.evaluate(&fit.interpolant.view(), settings));
        rival = Model {
            constraints,
            interpolant: fit.interpolant,
            report: Some(fit.report),
            ..rival
        };
        if summary(&errors) < best.0 {
            best = (summary(&errors), rival.clone());
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::slab;
    use rbf_mesh::{TriMesh, WindingTree};

    /// A closed box over [−1, 1] × [−1, 1] × [0, `thick`], outward facing.
    fn plate(thick: f64) -> TriMesh {
        let positions: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                let bit = |b: usize| (i >> b) & 1 == 1;
                let x = if bit(0) { 1.0 } else { -1.0 };
                let y = if bit(1) { 1.0 } else { -1.0 };
                [x, y, if bit(2) { thick } else { 0.0 }]
            })
            .collect();
        let quads = [
            [0, 2, 3, 1], // z = 0
            [4, 5, 7, 6], // z = thick
            [0, 1, 5, 4], // y = −1
            [2, 6, 7, 3], // y = 1
            [0, 4, 6, 2], // x = −1
            [1, 3, 7, 5], // x = 1
        ];
        let triangles = quads
            .iter()
            .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
            .collect();
        let mesh = TriMesh::new(positions, triangles).unwrap();
        assert!(mesh.volume() > 0.0);
        mesh
    }

    #[test]
    fn a_slab_measures_a_wall_thinner_than_two_offsets_and_no_other() {
        let tree = WindingTree::new(&plate(0.1));
        // Down through the plate from its top face: 0.1 thick.
        let w = slab(&tree, [0.2, 0.3, 0.1], [0.0, 0.0, 1.0], 0.08).unwrap();
        assert!((w - 0.1).abs() < 1e-3, "{w}");
        // The same wall is not thinner than two offsets of 0.04.
        assert!(slab(&tree, [0.2, 0.3, 0.1], [0.0, 0.0, 1.0], 0.04).is_none());
        // Across the plate from its side: 2 wide.
        assert!(slab(&tree, [1.0, 0.3, 0.05], [1.0, 0.0, 0.0], 0.08).is_none());
        // A normal that points into the solid does not enter it cleanly.
        assert!(slab(&tree, [0.2, 0.3, 0.1], [0.0, 0.0, -1.0], 0.08).is_none());
    }
}
