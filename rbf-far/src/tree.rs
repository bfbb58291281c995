//! A k-d tree of points: median splits along the box's longest side, leaves of bounded size.
//! The far field's clusters are its nodes; the iterative solver's subdomains are its leaves, and
//! its neighbour queries gather their overlaps.

/// A node covers `order[start..end]`; leaves have no children. Children have larger indices
/// than their parent.
#[derive(Clone, Debug)]
pub struct Node<const D: usize> {
    /// First position in [`Tree::order`].
    pub start: usize,
    /// One past the last position in [`Tree::order`].
    pub end: usize,
    /// The lower corner of the node's points' bounding box.
    pub lo: [f64; D],
    /// The upper corner.
    pub hi: [f64; D],
    /// The two children, or `None` for a leaf.
    pub children: Option<(usize, usize)>,
}

/// The tree; `order` lists point indices so that every node's points are contiguous.
///
/// ```
/// use rbf_far::Tree;
/// let points: Vec<[f64; 2]> = (0..100).map(|i| [i as f64, (i * 7 % 10) as f64]).collect();
/// let tree = Tree::new(&points, 8);
/// assert!(tree.leaves().iter().all(|&l| tree.points_of(l).len() <= 8));
/// assert_eq!(tree.points_of(0).len(), 100); // the root holds every point
/// ```
#[derive(Clone, Debug)]
pub struct Tree<const D: usize> {
    /// Nodes, the root first, every parent before its children.
    pub nodes: Vec<Node<D>>,
    /// Point indices, each node's contiguous.
    pub order: Vec<usize>,
}

impl<const D: usize> Tree<D> {
    /// Splits until no leaf holds more than `leaf_size` points (at least 1).
    pub fn new(points: &[[f64; D]], leaf_size: usize) -> Self {
        let leaf_size = leaf_size.max(1);
        let mut tree = Self {
            nodes: Vec::new(),
            order: (0..points.len()).collect(),
        };
        if !points.is_empty() {
            tree.build(points, 0, points.len(), leaf_size);
        }
        tree
    }

    fn build(&mut self, points: &[[f64; D]], start: usize, end: usize, leaf_size: usize) -> usize {
        let (lo, hi) = bounds(points, &self.order[start..end]);
        let id = self.nodes.len();
        self.nodes.push(Node {
            start,
            end,
            lo,
            hi,
            children: None,
        });
        if end - start > leaf_size {
            let axis = (0..D)
                .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
                .unwrap_or(0);
            let mid = start + (end - start) / 2;
            self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
                points[a][axis].total_cmp(&points[b][axis])
            });
            let left = self.build(points, start, mid, leaf_size);
            let right = self.build(points, mid, end, leaf_size);
            self.nodes[id].children = Some((left, right));
        }
        id
    }

    /// Indices of the leaves, left to right.
    pub fn leaves(&self) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| self.nodes[i].children.is_none())
            .collect()
    }

    /// The points of node `i`.
    pub fn points_of(&self, i: usize) -> &[usize] {
        &self.order[self.nodes[i].start..self.nodes[i].end]
    }

    /// Every point within distance `radius` of the box [lo, hi], with its squared distance
    /// to the box, appended to `out`.
    pub fn near_box(
        &self,
        points: &[[f64; D]],
        lo: &[f64; D],
        hi: &[f64; D],
        radius: f64,
        out: &mut Vec<(f64, usize)>,
    ) {
        let r2 = radius * radius;
        let mut stack = vec![0];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if box_gap2(&node.lo, &node.hi, lo, hi) > r2 {
                continue;
            }
            match node.children {
                Some((a, b)) => stack.extend([a, b]),
                None => {
                    for &i in self.points_of(n) {
                        let d2 = point_gap2(&points[i], lo, hi);
                        if d2 <= r2 {
                            out.push((d2, i));
                        }
                    }
                }
            }
        }
    }
}

/// The bounding box of `points[idx]`.
pub fn bounds<const D: usize>(points: &[[f64; D]], idx: &[usize]) -> ([f64; D], [f64; D]) {
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for &i in idx {
        for d in 0..D {
            lo[d] = lo[d].min(points[i][d]);
            hi[d] = hi[d].max(points[i][d]);
        }
    }
    (lo, hi)
}

/// Squared distance from a point to a box (0 inside).
pub fn point_gap2<const D: usize>(p: &[f64; D], lo: &[f64; D], hi: &[f64; D]) -> f64 {
    (0..D)
        .map(|d| {
            let g = (lo[d] - p[d]).max(p[d] - hi[d]).max(0.0);
            g * g
        })
        .sum()
}

/// Squared distance between two boxes (0 if they meet).
pub fn box_gap2<const D: usize>(
    alo: &[f64; D],
    ahi: &[f64; D],
    blo: &[f64; D],
    bhi: &[f64; D],
) -> f64 {
    (0..D)
        .map(|d| {
            let g = (blo[d] - ahi[d]).max(alo[d] - bhi[d]).max(0.0);
            g * g
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Vec<[f64; 3]> {
        (0..1000)
            .map(|i| [(i % 10) as f64, ((i / 10) % 10) as f64, (i / 100) as f64])
            .collect()
    }

    #[test]
    fn leaves_partition_the_points_and_respect_the_size() {
        let pts = grid();
        let tree = Tree::new(&pts, 30);
        let mut seen = vec![0; pts.len()];
        for leaf in tree.leaves() {
            let idx = tree.points_of(leaf);
            assert!(idx.len() <= 30 && !idx.is_empty());
            let (lo, hi) = (tree.nodes[leaf].lo, tree.nodes[leaf].hi);
            for &i in idx {
                seen[i] += 1;
                assert!((0..3).all(|d| lo[d] <= pts[i][d] && pts[i][d] <= hi[d]));
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
    }

    #[test]
    fn near_box_finds_exactly_the_points_within_the_radius() {
        let pts = grid();
        let tree = Tree::new(&pts, 7);
        let (lo, hi) = ([2.0, 2.0, 2.0], [3.0, 4.0, 2.5]);
        let mut found = Vec::new();
        tree.near_box(&pts, &lo, &hi, 1.5, &mut found);
        let mut got: Vec<usize> = found.iter().map(|&(_, i)| i).collect();
        got.sort_unstable();
        let want: Vec<usize> = (0..pts.len())
            .filter(|&i| point_gap2(&pts[i], &lo, &hi) <= 2.25)
            .collect();
        assert_eq!(got, want);
    }
}
