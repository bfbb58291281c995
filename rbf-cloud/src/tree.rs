//! One k-d tree over a point set (kiddo's `ImmutableKdTree`), built once and asked many
//! questions: the nearest point, the k nearest, all within a radius.

use std::num::NonZero;

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;

/// A k-d tree over points in `D` dimensions (3 unless said), answering by the points' indices.
///
/// ```
/// use rbf_cloud::PointTree;
/// let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
/// let tree = PointTree::new(&points);
/// assert_eq!(tree.nearest(&[2.5, 0.0, 0.0]), Some((2, 0.5)));
/// assert_eq!(tree.k_nearest(&[0.2, 0.0, 0.0], 2), vec![(0, 0.2), (1, 0.8)]);
/// let mut near: Vec<usize> = tree.within(&[0.5, 0.0, 0.0], 1.0).into_iter().map(|n| n.0).collect();
/// near.sort();
/// assert_eq!(near, vec![0, 1]);
/// ```
#[derive(Debug)]
pub struct PointTree<const D: usize = 3> {
    tree: ImmutableKdTree<f64, D>,
    len: usize,
}

impl<const D: usize> PointTree<D> {
    /// The tree over `points`; point i answers as index i.
    pub fn new(points: &[[f64; D]]) -> Self {
        Self {
            tree: ImmutableKdTree::new_from_slice(points),
            len: points.len(),
        }
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the tree holds no point.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The nearest point to `q` and its distance; `None` for an empty tree or a query that is
    /// not finite. Points that are not finite are never found.
    pub fn nearest(&self, q: &[f64; D]) -> Option<(usize, f64)> {
        if self.is_empty() || !q.iter().all(|x| x.is_finite()) {
            return None;
        }
        let n = self.tree.nearest_one::<SquaredEuclidean>(q);
        (n.distance < f64::MAX).then(|| (n.item as usize, n.distance.sqrt()))
    }

    /// The `k` nearest points to `q` (all of them if there are fewer; fewer still when some are
    /// not finite), nearest first, with their distances.
    pub fn k_nearest(&self, q: &[f64; D], k: usize) -> Vec<(usize, f64)> {
        let Some(wanted) = NonZero::new(k.min(self.len)) else {
            return Vec::new();
        };
        (self
            .tree
            .nearest_n::<SquaredEuclidean>(q, wanted)
            .into_iter())
        .map(|n| (n.item as usize, n.distance.sqrt()))
        .collect()
    }

    /// Every point within distance `r` of `q` (at most r), in no particular order, with its
    /// distance.
    pub fn within(&self, q: &[f64; D], r: f64) -> Vec<(usize, f64)> {
        if self.is_empty() || !(r >= 0.0) {
            return Vec::new();
        }
        (self
            .tree
            .within_unsorted::<SquaredEuclidean>(q, r * r)
            .into_iter())
        .map(|n| (n.item as usize, n.distance.sqrt()))
        .collect()
    }

    /// The distance from each of `queries` to its nearest point (infinite for an empty tree or
    /// a query that is not finite), on every core.
    pub fn distances(&self, queries: &[[f64; D]]) -> Vec<f64> {
        queries
            .par_iter()
            .map(|q| self.nearest(q).map_or(f64::INFINITY, |n| n.1))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn brute<const D: usize>(points: &[[f64; D]], q: &[f64; D]) -> Vec<(usize, f64)> {
        let mut all: Vec<(usize, f64)> = (points.iter().enumerate())
            .map(|(i, p)| (i, (0..D).map(|d| (p[d] - q[d]).powi(2)).sum::<f64>().sqrt()))
            .collect();
        all.sort_by(|a, b| a.1.total_cmp(&b.1));
        all
    }

    proptest! {
        #[test]
        fn answers_as_a_search_of_every_point_does(
            points in prop::collection::vec(prop::array::uniform3(-10.0..10.0f64), 1..300),
            q in prop::array::uniform3(-12.0..12.0f64),
            k in 1usize..12,
            r in 0.0..6.0f64,
        ) {
            let tree = PointTree::new(&points);
            let all = brute(&points, &q);
            let (_, d) = tree.nearest(&q).unwrap();
            prop_assert!((d - all[0].1).abs() <= 1e-12);
            let found = tree.k_nearest(&q, k);
            prop_assert_eq!(found.len(), k.min(points.len()));
            for (f, b) in found.iter().zip(&all) {
                prop_assert!((f.1 - b.1).abs() <= 1e-12);
            }
            let mut inside: Vec<usize> = tree.within(&q, r).into_iter().map(|n| n.0).collect();
            inside.sort_unstable();
            let mut expected: Vec<usize> = all.iter().filter(|b| b.1 <= r).map(|b| b.0).collect();
            expected.sort_unstable();
            prop_assert_eq!(inside, expected);
        }

        #[test]
        fn works_in_two_dimensions(
            points in prop::collection::vec(prop::array::uniform2(-10.0..10.0f64), 1..200),
            q in prop::array::uniform2(-12.0..12.0f64),
        ) {
            let tree = PointTree::new(&points);
            let all = brute(&points, &q);
            prop_assert!((tree.nearest(&q).unwrap().1 - all[0].1).abs() <= 1e-12);
        }
    }

    #[test]
    fn an_empty_tree_finds_nothing() {
        let tree = PointTree::<3>::new(&[]);
        assert!(tree.is_empty());
        assert_eq!(tree.nearest(&[0.0; 3]), None);
        assert!(tree.k_nearest(&[0.0; 3], 3).is_empty());
        assert!(tree.within(&[0.0; 3], 1.0).is_empty());
        assert_eq!(tree.distances(&[[0.0; 3]]), vec![f64::INFINITY]);
    }

    #[test]
    fn what_is_not_finite_is_never_found() {
        let tree = PointTree::new(&[[f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0]]);
        assert_eq!(tree.nearest(&[f64::NAN, 0.0, 0.0]), None);
        assert_eq!(tree.nearest(&[0.0, 0.0, 0.0]), Some((1, 1.0)));
        assert_eq!(tree.k_nearest(&[0.0; 3], 2), vec![(1, 1.0)]);
        assert_eq!(
            tree.distances(&[[f64::INFINITY, 0.0, 0.0]]),
            vec![f64::INFINITY]
        );
    }
}
