//! How far off a scanned surface each point may place its inside and outside constraints.

use rayon::prelude::*;

use crate::PointTree;

/// Halvings of the wanted distance tried before a side is given up.
const HALVINGS: u32 = 5;

/// For each point, the distances [inward, outward] along its (outward) normal, each `wanted`
/// or that halved up to five times, at which the moved point is still nearest to its own point
/// (or to a neighbour within that distance whose normal agrees): Carr et al.'s check of
/// off-surface points (SIGGRAPH 2001, §3.1), so that constraints off one sheet of a thin part
/// do not land inside the other sheet. 0 where even the smallest distance fails.
///
/// ```
/// use rbf_cloud::clear_offsets;
/// // Two parallel sheets 0.2 apart, facing away from each other.
/// let mut points = Vec::new();
/// let mut normals = Vec::new();
/// for i in 0..10 {
///     for j in 0..10 {
///         let (x, y) = (i as f64 * 0.1, j as f64 * 0.1);
///         points.push([x, y, 0.1]);
///         normals.push([0.0, 0.0, 1.0]);
///         points.push([x, y, -0.1]);
///         normals.push([0.0, 0.0, -1.0]);
///     }
/// }
/// let offsets = clear_offsets(&points, &normals, 0.4);
/// // Outward: free; inward: only up to the middle between the sheets.
/// assert_eq!(offsets[0][1], 0.4);
/// assert!(offsets[0][0] > 0.0 && offsets[0][0] <= 0.1);
/// ```
pub fn clear_offsets(points: &[[f64; 3]], normals: &[[f64; 3]], wanted: f64) -> Vec<[f64; 2]> {
    clear_offsets_with_tree(&PointTree::new(points), points, normals, wanted)
}

/// [`clear_offsets`] through a tree already built over `points` (the same points, in order).
///
/// ```
/// use rbf_cloud::{PointTree, clear_offsets_with_tree};
/// let points = [[0.0, 0.0, 0.1], [0.0, 0.0, -0.1]];
/// let normals = [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
/// let offsets = clear_offsets_with_tree(&PointTree::new(&points), &points, &normals, 0.4);
/// assert_eq!(offsets[0][1], 0.4);
/// assert!(offsets[0][0] <= 0.1);
/// ```
pub fn clear_offsets_with_tree(
    tree: &PointTree,
    points: &[[f64; 3]],
    normals: &[[f64; 3]],
    wanted: f64,
) -> Vec<[f64; 2]> {
    if points.is_empty() || normals.len() != points.len() || !(wanted > 0.0) {
        return vec![[0.0; 2]; normals.len().min(points.len())];
    }
    points
        .par_iter()
        .zip(normals)
        .enumerate()
        .map(|(i, (p, n))| {
            let side = |sign: f64| {
                let mut d = wanted;
                for _ in 0..=HALVINGS {
                    let q: [f64; 3] = core::array::from_fn(|k| p[k] + sign * d * n[k]);
                    let j = tree.nearest(&q).map_or(i, |n| n.0);
                    let agrees = j == i
                        || (j < points.len()
                            && distance(&points[j], p) <= d
                            && dot(&normals[j], n) > 0.5 * norm(&normals[j]) * norm(n));
                    if agrees {
                        return d;
                    }
                    d *= 0.5;
                }
                0.0
            };
            [side(-1.0), side(1.0)]
        })
        .collect()
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: &[f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d: [f64; 3] = core::array::from_fn(|k| a[k] - b[k]);
    norm(&d)
}
