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
        let rows: Vec<(Vec<u32>, Vec<f64>)> = points
            .par_iter()
            .enumerate()
            .map(|(i, p)| row(tree, p, i, k))
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
        let rows: Vec<(Vec<u32>, Vec<f64>)> = which
            .par_iter()
            .map(|&i| row(tree, &points[i], i, k))
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
