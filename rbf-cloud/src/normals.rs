//! Normals from local planes: the direction of least spread of each point's neighbourhood
//! (the eigenvector of the smallest eigenvalue of its covariance; Hoppe et al. 1992). Their
//! sign is arbitrary here; `orient_normals` makes them consistent.

use nalgebra::Matrix3;
use rayon::prelude::*;

use crate::{Neighbours, PointTree};

/// A unit normal at every point, from the point and its neighbours (unoriented). A
/// neighbourhood with no spread at all (every neighbour coincident) gets [0, 0, 0].
///
/// ```
/// use rbf_cloud::{Neighbours, estimate_normals};
/// let points: Vec<[f64; 3]> = (0..50).map(|i| [(i % 7) as f64, (i / 7) as f64, 2.0]).collect();
/// let normals = estimate_normals(&points, &Neighbours::new(&points, 8));
/// assert!(normals.iter().all(|n| n[2].abs() > 0.999));
/// ```
pub fn estimate_normals(points: &[[f64; 3]], neighbours: &Neighbours) -> Vec<[f64; 3]> {
    (0..points.len())
        .into_par_iter()
        .map(|i| normal_of(points, i, neighbours.of(i)))
        .collect()
}

/// The unit normal at point `i` from it and its neighbours `near` (indices into `points`),
/// as [`estimate_normals`] finds it; [0, 0, 0] where they do not spread.
///
/// ```
/// use rbf_cloud::normal_of;
/// let points = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0], [1.0, 1.0, 1.0]];
/// assert!(normal_of(&points, 0, &[1, 2, 3])[2].abs() > 0.999);
/// ```
pub fn normal_of(points: &[[f64; 3]], i: usize, near: &[u32]) -> [f64; 3] {
    let Some(covariance) = covariance_of(points, i, near) else {
        return [0.0; 3];
    };
    let eigen = covariance.symmetric_eigen();
    let smallest = (0..3)
        .min_by(|&a, &b| eigen.eigenvalues[a].total_cmp(&eigen.eigenvalues[b]))
        .unwrap_or(0);
    let v = eigen.eigenvectors.column(smallest);
    let length = v.norm();
    if length > 0.0 {
        [v[0] / length, v[1] / length, v[2] / length]
    } else {
        [0.0; 3]
    }
}

/// [`estimate_normals`] for a cloud scanned in lines: where a point's neighbourhood in `near`
/// still lies along a line (where the lines run farther apart than elsewhere, on a face nearly
/// parallel to the planes that cut them), or along one curved contour, its normal is taken from
/// twice as many of its nearest points (through `tree`, over `points`), and again, up to
/// `most`.
///
/// ```
/// use rbf_cloud::{Neighbours, PointTree, estimate_normals_spanning_lines};
/// // Lines 0.05 apart of points 0.002 apart in the plane z = 1: 16 neighbours cannot tell it.
/// let points: Vec<[f64; 3]> =
///     (0..10_000).map(|i| [(i % 500) as f64 * 0.002, (i / 500) as f64 * 0.05, 1.0]).collect();
/// let tree = PointTree::new(&points);
/// let normals = estimate_normals_spanning_lines(&points, &tree, &Neighbours::with_tree(&tree, &points, 16), 256);
/// assert!(normals.iter().all(|n| n[2].abs() > 0.999));
/// ```
pub fn estimate_normals_spanning_lines(
    points: &[[f64; 3]],
    tree: &PointTree,
    near: &Neighbours,
    most: usize,
) -> Vec<[f64; 3]> {
    (0..points.len())
        .into_par_iter()
        .map(|i| {
            let mut k = near.k();
            let mut wider: Vec<u32> = near.of(i).to_vec();
            let mut reach: Vec<f64> = near.distances_of(i).to_vec();
            while k < most && (along_line(points, i, &wider) || on_one_curve(&reach)) {
                k = (2 * k).min(most);
                (wider, reach) = tree
                    .k_nearest(&points[i], k + 1)
                    .into_iter()
                    .filter(|&(j, _)| j != i)
                    .map(|(j, d)| (j as u32, d))
                    .unzip();
            }
            normal_of(points, i, &wider)
        })
        .collect()
}

/// Whether neighbours at the sorted distances `reach` lie along one curve, straight or not
/// (a contour that curls within its slice is planar, and its plane is the slice's): the k-th
/// lies about k/4 times as far as the fourth along a curve, √(k/4) times over a surface; the
/// test is their geometric mean, (k/4)^¾.
fn on_one_curve(reach: &[f64]) -> bool {
    let k = reach.len();
    if k < 8 {
        return false;
    }
    let ratio = reach[k - 1] / reach[3].max(f64::MIN_POSITIVE);
    ratio > (k as f64 / 4.0).powf(0.75)
}

/// Whether point `i` and its neighbours `near` lie along a line (see [`LINE_SPREAD`]).
fn along_line(points: &[[f64; 3]], i: usize, near: &[u32]) -> bool {
    covariance_of(points, i, near).is_some_and(|c| {
        let mut e: Vec<f64> = c.symmetric_eigenvalues().iter().copied().collect();
        e.sort_by(f64::total_cmp);
        e[1] < LINE_SPREAD * e[2]
    })
}

/// The covariance of point `i` and its neighbours `near` about their centre; `None` where it
/// is zero or not finite.
fn covariance_of(points: &[[f64; 3]], i: usize, near: &[u32]) -> Option<Matrix3<f64>> {
    let count = (near.len() + 1) as f64;
    let members = || std::iter::once(&points[i]).chain(near.iter().map(|&j| &points[j as usize]));
    let mut centre = [0.0; 3];
    for p in members() {
        (0..3).for_each(|d| centre[d] += p[d] / count);
    }
    let mut covariance = Matrix3::<f64>::zeros();
    for p in members() {
        let q = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
        for r in 0..3 {
            for c in 0..3 {
                covariance[(r, c)] += q[r] * q[c];
            }
        }
    }
    let usable = covariance.iter().any(|v| *v != 0.0) && covariance.iter().all(|v| v.is_finite());
    usable.then_some(covariance)
}

/// A neighbourhood whose middle spread is below this share of its largest (eigenvalues of its
/// covariance) lies along a line: it cannot tell a plane.
const LINE_SPREAD: f64 = 0.05;

/// The share of `rows` (rows of `near`, each that of the point `which[r]`) whose neighbourhood
/// lies along a line, as points scanned in lines do (slices, a line scanner's profiles, lidar
/// rings) where the lines lie farther apart than `near` reaches: their planes, and so their
/// normals, are undetermined.
///
/// ```
/// use rbf_cloud::{Neighbours, PointTree, line_share};
/// // A square of lines 0.05 apart, of points 0.002 apart: 16 neighbours stay on their own
/// // line, 256 reach across several.
/// let points: Vec<[f64; 3]> =
///     (0..10_000).map(|i| [(i % 500) as f64 * 0.002, (i / 500) as f64 * 0.05, 0.0]).collect();
/// let tree = PointTree::new(&points);
/// let which: Vec<usize> = (0..points.len()).step_by(10).collect();
/// assert!(line_share(&points, &which, &Neighbours::of_some(&tree, &points, &which, 16)) > 0.9);
/// assert!(line_share(&points, &which, &Neighbours::of_some(&tree, &points, &which, 256)) < 0.1);
/// ```
pub fn line_share(points: &[[f64; 3]], which: &[usize], near: &Neighbours) -> f64 {
    if which.is_empty() {
        return 0.0;
    }
    let along_lines = which
        .par_iter()
        .enumerate()
        .filter(|&(r, &i)| along_line(points, i, near.of(r)))
        .count();
    along_lines as f64 / which.len() as f64
}

#[cfg(test)]
mod tests {
    use super::on_one_curve;

    /// The distances from a point to its `k` nearest among `others`, sorted.
    fn reach(p: [f64; 3], others: &[[f64; 3]], k: usize) -> Vec<f64> {
        let mut d: Vec<f64> = others
            .iter()
            .filter(|q| **q != p)
            .map(|q| ((0..3).map(|i| (q[i] - p[i]).powi(2)).sum::<f64>()).sqrt())
            .collect();
        d.sort_by(f64::total_cmp);
        d.truncate(k);
        d
    }

    /// A contour curled into a circle (in its slice's plane) is one curve, as a straight line
    /// is; a lattice over a surface is not, at 16 and at 64 neighbours.
    #[test]
    fn a_curled_contour_is_one_curve_and_a_surface_is_not() {
        let circle: Vec<[f64; 3]> = (0..200)
            .map(|j| {
                let t = std::f64::consts::TAU * j as f64 / 200.0;
                [0.1 * t.cos(), 0.1 * t.sin(), 0.0]
            })
            .collect();
        let line: Vec<[f64; 3]> = (0..200).map(|j| [0.003 * j as f64, 0.0, 0.0]).collect();
        let lattice: Vec<[f64; 3]> = (0..900)
            .map(|j| [0.01 * (j % 30) as f64, 0.01 * (j / 30) as f64, 0.0])
            .collect();
        for k in [16, 64] {
            assert!(on_one_curve(&reach(circle[0], &circle, k)), "circle, {k}");
            assert!(on_one_curve(&reach(line[100], &line, k)), "line, {k}");
            assert!(
                !on_one_curve(&reach(lattice[465], &lattice, k)),
                "lattice, {k}"
            );
        }
    }
}
