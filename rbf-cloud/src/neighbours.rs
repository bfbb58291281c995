//! Each point's k nearest other points, found once through one k-d tree ([`PointTree`]) on
//! every core.

use rayon::prelude::*;

use crate::PointTree;

/// The k nearest other points of every point, nearest first.
#[derive(Clone, Debug)]
pub struct Neighbours {
    k: usize,
    /// Row i: the indices of point i's neighbours (k per row).
    indices: Vec<u32>,
    /// Row i: their distances.
    distances: Vec<f64>,
}

impl Neighbours {
    /// The `k` nearest other points of each of `points` (fewer when there are not that many
    /// other points: then every other point). Coincident points are neighbours at distance 0.
    ///
    /// ```
    /// use rbf_cloud::Neighbours;
    /// let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
    /// let near = Neighbours::new(&points, 1);
    /// assert_eq!(near.of(2), &[1]);
    /// assert_eq!(near.distances_of(2), &[2.0]);
    /// ```
    pub fn new(points: &[[f64; 3]], k: usize) -> Self {
        Self::with_tree(&PointTree::new(points), points, k)
    }

    /// [`Neighbours::new`] through a tree already built over `points` (the same points, in
    /// order).
    ///
    /// ```
    /// use rbf_cloud::{Neighbours, PointTree};
    /// let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
    /// let tree = PointTree::new(&points);
    /// assert_eq!(Neighbours::with_tree(&tree, &points, 2).of(0), &[1, 2]);
    /// ```
    pub fn with_tree(tree: &PointTree, points: &[[f64; 3]], k: usize) -> Self {
        let k = k.min(points.len().saturating_sub(1));
        if k == 0 {
            return Self::from_rows(0, Vec::new());
        }
        let reach = typical_reach(tree, points, k);
        let rows: Vec<(Vec<u32>, Vec<f64>)> = points
            .par_iter()
            .enumerate()
            .map(|(i, p)| row_within(tree, p, i, k, reach))
            .collect();
        Self::from_rows(k, rows)
    }

    /// The `k` nearest other points of some of `points` only (all of which `tree` holds, in
    /// order): row r of the result holds those of point `which[r]`, as [`Neighbours::with_tree`]
    /// would find them.
    ///
    /// # Panics
    /// If an index in `which` is not below `points.len()`.
    ///
    /// ```
    /// use rbf_cloud::{Neighbours, PointTree};
    /// let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
    /// let tree = PointTree::new(&points);
    /// let near = Neighbours::of_some(&tree, &points, &[2], 1);
    /// assert_eq!((near.len(), near.of(0)), (1, &[1][..]));
    /// ```
    pub fn of_some(tree: &PointTree, points: &[[f64; 3]], which: &[usize], k: usize) -> Self {
        let k = k.min(points.len().saturating_sub(1));
        if k == 0 {
            return Self::from_rows(0, Vec::new());
        }
        let reach = typical_reach(tree, points, k);
        let rows: Vec<(Vec<u32>, Vec<f64>)> = which
            .par_iter()
            .map(|&i| row_within(tree, &points[i], i, k, reach))
            .collect();
        Self::from_rows(k, rows)
    }

    fn from_rows(k: usize, rows: Vec<(Vec<u32>, Vec<f64>)>) -> Self {
        if k == 0 {
            return Self {
                k: 0,
                indices: Vec::new(),
                distances: Vec::new(),
            };
        }
        let mut indices = Vec::with_capacity(rows.len() * k);
        let mut distances = Vec::with_capacity(rows.len() * k);
        for (i, d) in rows {
            // A row short of k (the point itself was not returned among equals, or points that
            // are not finite were not found) is padded with
            // its last neighbour, so that every row has k entries.
            let last = (*i.last().unwrap_or(&0), *d.last().unwrap_or(&0.0));
            indices.extend(i.iter().copied().chain(std::iter::repeat(last.0)).take(k));
            distances.extend(d.iter().copied().chain(std::iter::repeat(last.1)).take(k));
        }
        Self {
            k,
            indices,
            distances,
        }
    }

    /// Neighbours per point.
    pub fn k(&self) -> usize {
        self.k
    }

    /// The neighbours of point i, nearest first.
    pub fn of(&self, i: usize) -> &[u32] {
        &self.indices[i * self.k..(i + 1) * self.k]
    }

    /// Their distances.
    pub fn distances_of(&self, i: usize) -> &[f64] {
        &self.distances[i * self.k..(i + 1) * self.k]
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.indices.len().checked_div(self.k).unwrap_or(0)
    }

    /// Whether there are no rows (fewer than two points).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Points whose k + 1 nearest a search within a radius looks for at once: a fifth of the rows
/// reach beyond it and are searched again by [`PointTree::k_nearest`]. A region denser than
/// most gathers more points than it needs (a cluster ten times as dense, ten times as many).
const WITHIN_SHARE: f64 = 0.8;

/// A radius within which about [`WITHIN_SHARE`] of the points have their k + 1 nearest (their
/// own and k others), from a sample of a thousand of them.
fn typical_reach(tree: &PointTree, points: &[[f64; 3]], k: usize) -> f64 {
    let step = (points.len() / 1000).max(1);
    let mut reach: Vec<f64> = (0..points.len())
        .step_by(step)
        .filter_map(|i| tree.k_nearest(&points[i], k + 1).last().map(|n| n.1))
        .collect();
    if reach.is_empty() {
        return 0.0;
    }
    let at = ((reach.len() as f64 * WITHIN_SHARE) as usize).min(reach.len() - 1);
    let reach = *reach.select_nth_unstable_by(at, f64::total_cmp).1;
    // Points not finite (found by nothing) leave every row to the k-nearest search.
    if reach.is_finite() { reach } else { 0.0 }
}

/// Point `i`'s row as [`row`] finds it, through the points within `reach` when there are k + 1
/// of them or more: collecting those and sorting the nearest is cheaper than the k-nearest
/// search's heap (0.50 s against 0.82 s for 128 neighbours of 10⁵ scan points, 0.11 against
/// 0.14 for 16).
fn row_within(
    tree: &PointTree,
    p: &[f64; 3],
    i: usize,
    k: usize,
    reach: f64,
) -> (Vec<u32>, Vec<f64>) {
    let mut found = tree.within(p, reach);
    if found.len() <= k {
        return row(tree, p, i, k);
    }
    found.select_nth_unstable_by(k, |a, b| a.1.total_cmp(&b.1));
    found.truncate(k + 1);
    found.sort_unstable_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    let mut row: Vec<(u32, f64)> = (found.into_iter())
        .filter(|n| n.0 != i)
        .map(|(j, d)| (j as u32, d))
        .collect();
    row.truncate(k);
    row.into_iter().unzip()
}

/// The `k` nearest points to point `i` at `p`, other than itself, nearest first.
fn row(tree: &PointTree, p: &[f64; 3], i: usize, k: usize) -> (Vec<u32>, Vec<f64>) {
    // The point itself is among them (at distance 0, maybe behind a duplicate).
    let mut row: Vec<(u32, f64)> = (tree.k_nearest(p, k + 1).into_iter())
        .filter(|n| n.0 != i)
        .map(|(j, d)| (j as u32, d))
        .collect();
    row.truncate(k);
    row.into_iter().unzip()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Every row holds the k smallest distances to other points, nearest first, whether it
        /// was found within the typical reach or beyond it (a dense cluster beside sparse
        /// points makes both kinds).
        #[test]
        fn rows_are_the_nearest_others_as_a_search_of_every_point_finds_them(
            sparse in prop::collection::vec(prop::array::uniform3(-10.0..10.0f64), 5..120),
            dense in prop::collection::vec(prop::array::uniform3(-0.5..0.5f64), 0..200),
            k in 1usize..20,
        ) {
            let points: Vec<[f64; 3]> = sparse.into_iter().chain(dense).collect();
            let near = Neighbours::new(&points, k);
            let k = k.min(points.len() - 1);
            prop_assert_eq!(near.k(), k);
            for (i, p) in points.iter().enumerate() {
                let mut all: Vec<f64> = (points.iter().enumerate())
                    .filter(|&(j, _)| j != i)
                    .map(|(_, q)| (0..3).map(|d| (p[d] - q[d]).powi(2)).sum::<f64>().sqrt())
                    .collect();
                all.sort_by(f64::total_cmp);
                for (r, (&j, &d)) in near.of(i).iter().zip(near.distances_of(i)).enumerate() {
                    prop_assert!(j as usize != i);
                    let q = points[j as usize];
                    let actual = (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f64>().sqrt();
                    prop_assert!((actual - d).abs() <= 1e-12);
                    prop_assert!((d - all[r]).abs() <= 1e-12, "row {} rank {}: {} against {}", i, r, d, all[r]);
                }
            }
        }
    }
}
