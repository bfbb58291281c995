//! Statistical outlier removal: a point whose mean distance to its neighbours is far above the
//! cloud's typical one lies off the scanned surface.

use crate::Neighbours;

/// Flags the points whose mean distance to their neighbours exceeds the mean over all points
/// by more than `ratio` standard deviations (Rusu et al. 2008; Open3D and PCL use the same rule,
/// commonly with 20 neighbours and a ratio of 2).
///
/// ```
/// use rbf_cloud::{Neighbours, statistical_outliers};
/// let mut points: Vec<[f64; 3]> = (0..100).map(|i| [(i % 10) as f64, (i / 10) as f64, 0.0]).collect();
/// points.push([5.0, 5.0, 40.0]);
/// let flags = statistical_outliers(&Neighbours::new(&points, 8), 2.0);
/// assert!(flags[100] && flags.iter().filter(|&&f| f).count() == 1);
/// ```
pub fn statistical_outliers(neighbours: &Neighbours, ratio: f64) -> Vec<bool> {
    let n = neighbours.len();
    if n == 0 || neighbours.k() == 0 {
        return vec![false; n];
    }
    let means: Vec<f64> = (0..n)
        .map(|i| {
            let d = neighbours.distances_of(i);
            d.iter().sum::<f64>() / d.len() as f64
        })
        .collect();
    let mean = means.iter().sum::<f64>() / n as f64;
    let deviation = (means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
    let limit = mean + ratio * deviation;
    means.iter().map(|&m| m > limit).collect()
}
