//! Generalized winding numbers (Jacobson et al. 2013): the solid angle a mesh subtends at a
//! point over 4π. 1 inside a closed outward mesh, 0 outside, and a graceful inside/outside
//! answer for meshes with holes, overlaps or non-manifold parts. Evaluated fast with a bounding
//! hierarchy whose far clusters are replaced by their expansion to second order (after
//! Barill et al. 2018).

use rayon::prelude::*;

use super::clusters::{Clusters, Elements, Reach};
use crate::TriMesh;
use rbf_core::vec3::{cross, dot, norm, sub};

/// The solid angle of triangle (a, b, c) seen from p (Van Oosterom & Strackee 1983), signed
/// positive when the triangle faces away from p.
fn solid_angle(a: [f64; 3], b: [f64; 3], c: [f64; 3], p: [f64; 3]) -> f64 {
    let (a, b, c) = (sub(a, p), sub(b, p), sub(c, p));
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    let numerator = dot(a, cross(b, c));
    let denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    2.0 * numerator.atan2(denominator)
}

/// A cluster counts as far from 1.5 of its radii; the second-order term is added out to 2.5
/// times that (it falls off as (radius / distance)²).
const REACH: Reach = Reach {
    far: 1.5,
    second_order: 3.75,
};

/// A mesh prepared for fast winding-number queries.
pub struct WindingTree {
    corners: Vec<[[f64; 3]; 3]>,
    clusters: Clusters,
}

impl WindingTree {
    /// Builds the hierarchy (median splits of triangle centroids along the widest axis).
    pub fn new(mesh: &TriMesh) -> Self {
        let corners: Vec<[[f64; 3]; 3]> = (0..mesh.triangles().len())
            .map(|t| mesh.corners(t))
            .collect();
        let area = |t: usize| {
            let [a, b, c] = corners[t];
            cross(sub(b, a), sub(c, a)).map(|x| 0.5 * x)
        };
        let centroid = |t: usize| {
            let [a, b, c] = corners[t];
            core::array::from_fn(|d| (a[d] + b[d] + c[d]) / 3.0)
        };
        let reach = |t: usize, from: [f64; 3]| {
            corners[t]
                .iter()
                .map(|&p| norm(sub(p, from)))
                .fold(0.0, f64::max)
        };
        let elements = Elements {
            area: &area,
            centroid: &centroid,
            reach: &reach,
        };
        let clusters = Clusters::new(corners.len(), &elements);
        Self { corners, clusters }
    }

    /// The winding number at p: exact for near triangles, expansions for far clusters (1
    /// inside a closed mesh, 0 outside; the expansions can be off by 0.1 or so far from every
    /// triangle, so compare with ½).
    ///
    /// ```
    /// use rbf_mesh::{TriMesh, WindingTree};
    /// let tree = WindingTree::new(&TriMesh::icosphere(2));
    /// assert!(tree.winding_number([0.1, 0.2, 0.0]) > 0.5);
    /// assert!(tree.winding_number([0.0, 0.0, 0.99]) > 0.5);
    /// assert!(tree.winding_number([0.0, 0.0, 1.01]) < 0.5);
    /// assert!(tree.winding_number([3.0, 0.0, 0.0]) < 0.5);
    /// ```
    pub fn winding_number(&self, p: [f64; 3]) -> f64 {
        let sum = self.clusters.solid_angle(p, REACH, |t| {
            let [a, b, c] = self.corners[t];
            solid_angle(a, b, c, p)
        });
        sum / (4.0 * std::f64::consts::PI)
    }
}

impl WindingTree {
    pub(crate) fn root(&self) -> Option<usize> {
        self.clusters.root()
    }

    /// A node's bounding sphere.
    pub(crate) fn bounds(&self, n: usize) -> ([f64; 3], f64) {
        self.clusters.bounds(n)
    }

    pub(crate) fn children(&self, n: usize) -> Option<(usize, usize)> {
        self.clusters.children(n)
    }

    /// The corners of a leaf's triangles.
    pub(crate) fn leaf_triangles(&self, n: usize) -> impl Iterator<Item = [[f64; 3]; 3]> + '_ {
        self.clusters.elements(n).iter().map(|&t| self.corners[t])
    }
}

impl WindingTree {
    /// True when some triangle comes within `radius` of `centre` (tested on bounding spheres of
    /// the hierarchy and boxes of the triangles).
    pub(crate) fn any_triangle_near(&self, centre: [f64; 3], radius: f64) -> bool {
        let Some(root) = self.root() else {
            return false;
        };
        let mut stack = vec![root];
        while let Some(n) = stack.pop() {
            let (at, reach) = self.bounds(n);
            if norm(sub(at, centre)) > reach + radius {
                continue;
            }
            match self.children(n) {
                Some((a, b)) => {
                    stack.push(a);
                    stack.push(b);
                }
                None => {
                    for &t in self.clusters.elements(n) {
                        let near = (0..3).all(|d| {
                            let lo = self.corners[t]
                                .iter()
                                .map(|p| p[d])
                                .fold(f64::INFINITY, f64::min);
                            let hi = self.corners[t]
                                .iter()
                                .map(|p| p[d])
                                .fold(f64::NEG_INFINITY, f64::max);
                            lo <= centre[d] + radius && hi >= centre[d] - radius
                        });
                        if near {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }

    /// The class of every point within `radius` of `centre`, when no triangle comes that near
    /// and the winding number at the centre is clearly 0 or 1 (off ½ by more than ¼): away
    /// from the mesh the winding number is harmonic and varies slowly.
    fn clear_class(&self, centre: [f64; 3], radius: f64) -> Option<bool> {
        if self.any_triangle_near(centre, radius) {
            return None;
        }
        let w = self.winding_number(centre);
        ((w - 0.5).abs() > 0.25).then_some(w > 0.5)
    }

    /// Inside (winding number > ½) at every voxel centre of a grid (`origin` is the centre of
    /// voxel (0, 0, 0), C order). Blocks of 4³ voxels, then of 2³, that no triangle comes near
    /// and where the winding number at the block's centre is clearly 0 or 1 take that class
    /// whole; the rest are evaluated voxel by voxel.
    pub(crate) fn classify_grid(&self, origin: [f64; 3], h: f64, shape: [usize; 3]) -> Vec<bool> {
        crate::classify_blocks(shape, 4, |_, lo, hi| {
            let centre: [f64; 3] =
                core::array::from_fn(|d| origin[d] + h * 0.5 * ((lo[d] + hi[d] - 1) as f64));
            let radius = 0.5
                * h
                * (((hi[0] - lo[0]).pow(2) + (hi[1] - lo[1]).pow(2) + (hi[2] - lo[2]).pow(2))
                    as f64)
                    .sqrt();
            let count = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
            if let Some(inside) = self.clear_class(centre, radius) {
                return vec![inside; count];
            }
            // Near the mesh: the same test on sub-blocks of 2³, then voxel by voxel.
            let mut out = vec![false; count];
            let (sy, sz) = (hi[1] - lo[1], hi[2] - lo[2]);
            for i0 in (lo[0]..hi[0]).step_by(2) {
                for j0 in (lo[1]..hi[1]).step_by(2) {
                    for k0 in (lo[2]..hi[2]).step_by(2) {
                        let (i1, j1, k1) = (
                            (i0 + 2).min(hi[0]),
                            (j0 + 2).min(hi[1]),
                            (k0 + 2).min(hi[2]),
                        );
                        let c = [
                            origin[0] + h * 0.5 * ((i0 + i1 - 1) as f64),
                            origin[1] + h * 0.5 * ((j0 + j1 - 1) as f64),
                            origin[2] + h * 0.5 * ((k0 + k1 - 1) as f64),
                        ];
                        let r = 0.5
                            * h
                            * (((i1 - i0).pow(2) + (j1 - j0).pow(2) + (k1 - k0).pow(2)) as f64)
                                .sqrt();
                        let whole = self.clear_class(c, r);
                        for i in i0..i1 {
                            for j in j0..j1 {
                                for k in k0..k1 {
                                    let at = ((i - lo[0]) * sy + (j - lo[1])) * sz + (k - lo[2]);
                                    out[at] = whole.unwrap_or_else(|| {
                                        let p = [
                                            origin[0] + h * i as f64,
                                            origin[1] + h * j as f64,
                                            origin[2] + h * k as f64,
                                        ];
                                        self.winding_number(p) > 0.5
                                    });
                                }
                            }
                        }
                    }
                }
            }
            out
        })
    }
}

/// The winding number of the mesh at each point (fast: hierarchical, in parallel).
///
/// ```
/// # use rbf_mesh::{TriMesh, winding_numbers};
/// let tet = TriMesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// )
/// .unwrap();
/// let w = winding_numbers(&tet, &[[0.1, 0.1, 0.1], [2.0, 2.0, 2.0]]);
/// assert!((w[0] - 1.0).abs() < 1e-9 && w[1].abs() < 1e-3);
/// ```
pub fn winding_numbers(mesh: &TriMesh, points: &[[f64; 3]]) -> Vec<f64> {
    let tree = WindingTree::new(mesh);
    points.par_iter().map(|&p| tree.winding_number(p)).collect()
}

/// The winding number at each point by summing every triangle's solid angle: exact, and
/// O(points × triangles). For tests and small meshes.
#[doc(hidden)]
pub fn winding_numbers_exact(mesh: &TriMesh, points: &[[f64; 3]]) -> Vec<f64> {
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
