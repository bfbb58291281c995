//! How far points are from a cloud.

use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rayon::prelude::*;

/// The distance from each of `queries` to the nearest point of `cloud` (infinite if the cloud
/// is empty), through one k-d tree, on every core.
///
/// ```
/// use rbf_cloud::distances_to_cloud;
/// let cloud = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
/// assert_eq!(distances_to_cloud(&cloud, &[[1.0, 2.0, 0.0], [0.5, 0.0, 0.0]]), vec![2.0, 0.5]);
/// ```
pub fn distances_to_cloud(cloud: &[[f64; 3]], queries: &[[f64; 3]]) -> Vec<f64> {
    if cloud.is_empty() {
        return vec![f64::INFINITY; queries.len()];
    }
    let tree: ImmutableKdTree<f64, 3> = ImmutableKdTree::new_from_slice(cloud);
    queries
        .par_iter()
        .map(|q| tree.nearest_one::<SquaredEuclidean>(q).distance.sqrt())
        .collect()
}
