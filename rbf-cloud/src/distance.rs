//! How far points are from a cloud.

use crate::PointTree;

/// The distance from each of `queries` to the nearest point of `cloud` (infinite if the cloud
/// is empty), through one k-d tree, on every core ([`PointTree::distances`] asks a tree already
/// built).
///
/// ```
/// use rbf_cloud::distances_to_cloud;
/// let cloud = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
/// assert_eq!(distances_to_cloud(&cloud, &[[1.0, 2.0, 0.0], [0.5, 0.0, 0.0]]), vec![2.0, 0.5]);
/// ```
pub fn distances_to_cloud(cloud: &[[f64; 3]], queries: &[[f64; 3]]) -> Vec<f64> {
    PointTree::new(cloud).distances(queries)
}
