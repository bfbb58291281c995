//! Generalized winding numbers (Jacobson et al. 2013): the solid angle a mesh subtends at a
//! point over 4π. 1 inside a closed outward mesh, 0 outside, and a graceful inside/outside
//! answer for meshes with holes, overlaps or non-manifold parts.

use rayon::prelude::*;

use crate::TriMesh;
use crate::mesh::{cross, dot, norm, sub};

/// The solid angle of triangle (a, b, c) seen from p (Van Oosterom & Strackee 1983), signed
/// positive when the triangle faces away from p.
fn solid_angle(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> f64 {
    let (a, b, c) = (sub(a, p), sub(b, p), sub(c, p));
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    let numerator = dot(a, cross(b, c));
    let denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    2.0 * numerator.atan2(denominator)
}

/// The winding number of the mesh at each point, by summing every triangle's solid angle
/// (exact; O(points × triangles), in parallel over points).
///
/// ```
/// # use rbf_mesh::{TriMesh, winding_numbers};
/// let tet = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )
/// .unwrap();
/// let w = winding_numbers(&tet, &[[0.1, 0.1, 0.1], [2.0, 2.0, 2.0]]);
/// assert!((w[0] - 1.0).abs() < 1e-12 && w[1].abs() < 1e-12);
/// ```
pub fn winding_numbers(mesh: &TriMesh, points: &[[f64; 3]]) -> Vec<f64> {
    let corners: Vec<[[f64; 3]; 3]> = (0..mesh.triangles().len())
        .map(|t| mesh.corners(t))
        .collect();
    points
        .par_iter()
        .map(|&p| {
            corners
                .iter()
                .map(|&[a, b, c]| solid_angle(a, b, c, p))
                .sum::<f64>()
                / (4.0 * std::f64::consts::PI)
        })
        .collect()
}
