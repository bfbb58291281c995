//! The nearest point of a mesh to a query point, through the bounding hierarchy of
//! [`WindingTree`].

use super::winding::WindingTree;
use rbf_core::vec3::{dot, norm, sub};

/// The point of triangle (a, b, c) nearest to p, by the Voronoi regions of its corners, edges
/// and face (Ericson, Real-Time Collision Detection, §5.1.5).
///
/// ```
/// let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
/// let q = rbf_mesh::closest_on_triangle([0.2, 0.3, 5.0], a, b, c);
/// assert!((q[0] - 0.2).abs() < 1e-15 && (q[1] - 0.3).abs() < 1e-15 && q[2] == 0.0);
/// assert_eq!(rbf_mesh::closest_on_triangle([2.0, -1.0, 0.0], a, b, c), b);
/// ```
pub fn closest_on_triangle(p: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let along = |o: [f64; 3], e: [f64; 3], t: f64| -> [f64; 3] {
        core::array::from_fn(|d| o[d] + t * e[d])
    };
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return along(a, ab, d1 / (d1 - d3));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return along(a, ac, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let total = va + vb + vc;
    if !(total > 0.0) {
        // A degenerate triangle whose regions did not catch p: its nearest corner.
        return [a, b, c]
            .into_iter()
            .min_by(|x, y| norm(sub(*x, p)).total_cmp(&norm(sub(*y, p))))
            .unwrap_or(a);
    }
    let (v, w) = (vb / total, vc / total);
    core::array::from_fn(|d| a[d] + v * ab[d] + w * ac[d])
}

impl WindingTree {
    /// The point of the mesh nearest to `p` and its distance, searching no farther than
    /// `max_distance`; `None` when no triangle comes that near.
    ///
    /// ```
    /// use rbf_mesh::{TriMesh, WindingTree};
    /// let tree = WindingTree::new(&TriMesh::icosphere(3));
    /// let (q, d) = tree.closest_point([0.0, 0.0, 2.0], f64::INFINITY).unwrap();
    /// assert!((d - 1.0).abs() < 0.01 && (q[2] - 1.0).abs() < 0.01);
    /// assert!(tree.closest_point([0.0, 0.0, 2.0], 0.5).is_none());
    /// ```
    pub fn closest_point(&self, p: [f64; 3], max_distance: f64) -> Option<([f64; 3], f64)> {
        let mut best: Option<([f64; 3], f64)> = None;
        let mut reach = max_distance;
        let mut stack = vec![self.root()?];
        while let Some(n) = stack.pop() {
            let (centre, radius) = self.bounds(n);
            if norm(sub(centre, p)) - radius > reach {
                continue;
            }
            match self.children(n) {
                Some((l, r)) => {
                    // Visit the nearer child first (pushed last).
                    let dl = norm(sub(self.bounds(l).0, p));
                    let dr = norm(sub(self.bounds(r).0, p));
                    let (near, far) = if dl <= dr { (l, r) } else { (r, l) };
                    stack.push(far);
                    stack.push(near);
                }
                None => {
                    for [a, b, c] in self.leaf_triangles(n) {
                        let q = closest_on_triangle(p, a, b, c);
                        let d = norm(sub(q, p));
                        if d <= reach {
                            reach = d;
                            best = Some((q, d));
                        }
                    }
                }
            }
        }
        best
    }
}
