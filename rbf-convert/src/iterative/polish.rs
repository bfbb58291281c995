//! The returned surface checked against the mesh itself (not in Yngve & Turk, whose error is
//! between boundary voxels): a surface within a voxel by that measure can still stray 1.5
//! voxels from the mesh where constraints are sparse, or carry a false handle across a gap
//! wider than the probes reach. The surface's own polygonization (made to measure its topology)
//! is compared with the mesh both ways: where a point of the surface lies farther than
//! [`FAR`] voxels from the mesh, it becomes an exterior or interior constraint with its signed
//! distance (outside or inside the mesh by its winding number), and where a vertex of the mesh
//! lies that far from the surface, a boundary constraint; then the model is fitted again.

use rayon::prelude::*;
use rbf_core::Constraint;
use rbf_mesh::{TriMesh, WindingTree};

/// Distance, in voxels, beyond which a point counts as astray.
pub(crate) const FAR: f64 = 1.0;

/// Constraints that pull the surface back where it strays from the mesh (checked at its
/// `vertices`, indices into it: every one, or a finely cut mesh's sample), no two within a
/// voxel of each other or of an existing constraint.
pub(crate) fn corrections(
    mesh: &TriMesh,
    vertices: &[usize],
    tree: &WindingTree,
    surface: &TriMesh,
    constraints: &[Constraint<3>],
    voxel: f64,
) -> Vec<Constraint<3>> {
    let far = FAR * voxel;
    let reach = 4.0 * voxel;
    // Surface points far from the mesh: push them to their side of it.
    let astray: Vec<(f64, Constraint<3>)> = surface
        .positions()
        .par_iter()
        .filter_map(|&p| {
            let d = tree.closest_point(p, reach).map_or(reach, |(_, d)| d);
            (d > far).then(|| {
                let c = if tree.winding_number(p) > 0.5 {
                    Constraint::interior(p, d)
                } else {
                    Constraint::exterior(p, -d)
                };
                (d, c)
            })
        })
        .collect();
    // Mesh vertices far from the surface: put the surface through them.
    let surface_tree = WindingTree::new(surface);
    let missed: Vec<(f64, Constraint<3>)> = vertices
        .par_iter()
        .map(|&v| mesh.positions()[v])
        .filter_map(|p| {
            let d = surface_tree
                .closest_point(p, reach)
                .map_or(reach, |(_, d)| d);
            (d > far).then_some((d, Constraint::boundary(p)))
        })
        .collect();
    let mut all: Vec<(f64, Constraint<3>)> = astray.into_iter().chain(missed).collect();
    all.sort_by(|a, b| b.0.total_cmp(&a.0));
    let key = |p: [f64; 3]| p.map(|c| (c / voxel).floor() as i64);
    let mut taken: std::collections::HashSet<[i64; 3]> =
        constraints.iter().map(|c| key(c.position)).collect();
    all.into_iter()
        .filter(|(_, c)| taken.insert(key(c.position)))
        .map(|(_, c)| c)
        .collect()
}
