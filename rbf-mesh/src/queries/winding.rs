//! Generalized winding numbers (Jacobson et al. 2013): the solid angle a mesh subtends at a
//! point over 4π. 1 inside a closed outward mesh, 0 outside, and a graceful inside/outside
//! answer for meshes with holes, overlaps or non-manifold parts. Evaluated fast with a bounding
//! hierarchy whose far clusters are replaced by their expansion to second order (after
//! Barill et al. 2018).

use rayon::prelude::*;

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

/// A node of the hierarchy: its triangles are `order[start..end]`.
struct Node {
    start: usize,
    end: usize,
    /// Children, or none for a leaf.
    children: Option<(usize, usize)>,
    /// Σ area vectors (½ (b − a) × (c − a)).
    area: [f64; 3],
    /// Area-weighted centroid.
    centre: [f64; 3],
    /// Σ area vector ⊗ (triangle centroid − centre), for the second-order term.
    moment: [[f64; 3]; 3],
    /// Largest distance from `centre` to a corner of the node's triangles.
    radius: f64,
}

/// Triangles per leaf.
const LEAF: usize = 8;
/// A cluster counts as far when the query is this many radii from its centre.
const FAR: f64 = 1.5;
/// Clusters within this many times the far distance also get the second-order term.
const SECOND_ORDER: f64 = 2.5;

/// A mesh prepared for fast winding-number queries.
pub struct WindingTree {
    corners: Vec<[[f64; 3]; 3]>,
    order: Vec<usize>,
    nodes: Vec<Node>,
}

impl WindingTree {
    /// Builds the hierarchy (median splits of triangle centroids along the widest axis).
    pub fn new(mesh: &TriMesh) -> Self {
        let corners: Vec<[[f64; 3]; 3]> = (0..mesh.triangles().len())
            .map(|t| mesh.corners(t))
            .collect();
        let mut tree = Self {
            order: (0..corners.len()).collect(),
            corners,
            nodes: Vec::new(),
        };
        if !tree.corners.is_empty() {
            tree.build(0, tree.corners.len());
        }
        tree
    }

    fn build(&mut self, start: usize, end: usize) -> usize {
        let mut area = [0.0; 3];
        let mut weighted = [0.0; 3];
        let mut total = 0.0;
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &t in &self.order[start..end] {
            let [a, b, c] = self.corners[t];
            let av = cross(sub(b, a), sub(c, a)).map(|x| 0.5 * x);
            let w = norm(av);
            for d in 0..3 {
                area[d] += av[d];
                let centroid = (a[d] + b[d] + c[d]) / 3.0;
                weighted[d] += w * centroid;
                lo[d] = lo[d].min(centroid);
                hi[d] = hi[d].max(centroid);
            }
            total += w;
        }
        let centre = if total > 0.0 {
            weighted.map(|x| x / total)
        } else {
            core::array::from_fn(|d| 0.5 * (lo[d] + hi[d]))
        };
        let mut moment = [[0.0; 3]; 3];
        for &t in &self.order[start..end] {
            let [a, b, c] = self.corners[t];
            let av = cross(sub(b, a), sub(c, a)).map(|x| 0.5 * x);
            let offset: [f64; 3] = core::array::from_fn(|d| (a[d] + b[d] + c[d]) / 3.0 - centre[d]);
            for i in 0..3 {
                for j in 0..3 {
                    moment[i][j] += av[i] * offset[j];
                }
            }
        }
        let radius = self.order[start..end]
            .iter()
            .flat_map(|&t| self.corners[t])
            .map(|p| norm(sub(p, centre)))
            .fold(0.0, f64::max);
        let id = self.nodes.len();
        self.nodes.push(Node {
            start,
            end,
            children: None,
            area,
            centre,
            moment,
            radius,
        });
        if end - start > LEAF {
            let axis = (0..3)
                .max_by(|&x, &y| (hi[x] - lo[x]).total_cmp(&(hi[y] - lo[y])))
                .unwrap_or(0);
            let mid = (start + end) / 2;
            let corners = &self.corners;
            let key = |t: &usize| {
                let [a, b, c] = corners[*t];
                a[axis] + b[axis] + c[axis]
            };
            self.order[start..end]
                .select_nth_unstable_by(mid - start, |x, y| key(x).total_cmp(&key(y)));
            let left = self.build(start, mid);
            let right = self.build(mid, end);
            self.nodes[id].children = Some((left, right));
        }
        id
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
        if self.nodes.is_empty() {
            return 0.0;
        }
        let mut sum = 0.0;
        // The tree is balanced, so its depth is about log2(triangles / LEAF): 64 is plenty.
        let mut stack = [0usize; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let n = stack[top];
            let node = &self.nodes[n];
            let r = sub(node.centre, p);
            let d = norm(r);
            if d > FAR * node.radius {
                let d3 = d * d * d;
                sum += dot(node.area, r) / d3;
                // Each triangle's solid angle ≈ A·g(c) with g(x) = (x − p)/|x − p|³, expanded
                // about the cluster's centre: N·g + Σ J:M with J = ∇g. The second-order term
                // falls off as (radius / distance)², so far clusters skip it.
                if d < SECOND_ORDER * FAR * node.radius {
                    let d5 = d3 * d * d;
                    let m = &node.moment;
                    let trace = m[0][0] + m[1][1] + m[2][2];
                    let mut rmr = 0.0;
                    for i in 0..3 {
                        rmr += r[i] * (m[i][0] * r[0] + m[i][1] * r[1] + m[i][2] * r[2]);
                    }
                    sum += trace / d3 - 3.0 * rmr / d5;
                }
                continue;
            }
            match node.children {
                Some((a, b)) if top + 2 <= stack.len() => {
                    stack[top] = a;
                    stack[top + 1] = b;
                    top += 2;
                }
                Some(_) => {
                    // Deeper than the stack: count the cluster by its expansion.
                    sum += dot(node.area, r) / (d * d * d);
                }
                None => {
                    for &t in &self.order[node.start..node.end] {
                        let [a, b, c] = self.corners[t];
                        sum += solid_angle(a, b, c, p);
                    }
                }
            }
        }
        sum / (4.0 * std::f64::consts::PI)
    }
}

impl WindingTree {
    pub(crate) fn root(&self) -> Option<usize> {
        (!self.nodes.is_empty()).then_some(0)
    }

    /// A node's bounding sphere.
    pub(crate) fn bounds(&self, n: usize) -> ([f64; 3], f64) {
        (self.nodes[n].centre, self.nodes[n].radius)
    }

    pub(crate) fn children(&self, n: usize) -> Option<(usize, usize)> {
        self.nodes[n].children
    }

    /// The corners of a leaf's triangles.
    pub(crate) fn leaf_triangles(&self, n: usize) -> impl Iterator<Item = [[f64; 3]; 3]> + '_ {
        let node = &self.nodes[n];
        self.order[node.start..node.end]
            .iter()
            .map(|&t| self.corners[t])
    }
}

impl WindingTree {
    /// True when some triangle comes within `radius` of `centre` (tested on bounding spheres of
    /// the hierarchy and boxes of the triangles).
    pub(crate) fn any_triangle_near(&self, centre: [f64; 3], radius: f64) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if norm(sub(node.centre, centre)) > node.radius + radius {
                continue;
            }
            match node.children {
                Some((a, b)) => {
                    stack.push(a);
                    stack.push(b);
                }
                None => {
                    for &t in &self.order[node.start..node.end] {
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
