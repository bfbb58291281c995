//! Integration tests of rbf-mesh, in one binary.

mod checks;
mod closest;
mod dipoles;
mod distance;
mod formats;
mod polygonize;
mod voxels;

use std::path::PathBuf;

/// A mesh shipped in the repository's `data/meshes`.
pub fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../data/meshes")
        .join(name)
}

/// An octahedron (closed, genus 0), faces counter-clockwise from outside.
pub fn octahedron() -> rbf_mesh::TriMesh {
    let p = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let t = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    rbf_mesh::TriMesh::new(p, t).unwrap()
}

/// Euclidean length.
pub fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}
